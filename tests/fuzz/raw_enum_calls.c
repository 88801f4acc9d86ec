/* The API's enum parameters called with arbitrary ints, as a C host may: C enums take any int value, so
   nothing here is undefined (in C++ forming such a value would be). */
#include <stdint.h>

#include "obscura/obscura.h"

const char* fuzz_status_string(int32_t status) { return obscura_status_string((obscura_status)status); }

const char* fuzz_method_name(int32_t method) { return obscura_method_name((obscura_method)method); }

int fuzz_method_available(int32_t method) { return obscura_method_available((obscura_method)method); }

/* The macros of this header: the sized entry points with this header's struct sizes. */
int32_t fuzz_default_settings(int32_t method, obscura_settings* out) {
    return (int32_t)obscura_default_settings((obscura_method)method, out);
}

int32_t fuzz_get_setting_infos(int32_t method, const obscura_setting_info** out_infos, uint32_t* out_count) {
    return (int32_t)obscura_get_setting_infos((obscura_method)method, out_infos, out_count);
}

/* The sized entry points with any size. */
int32_t fuzz_default_settings_sized(int32_t method, obscura_settings* out, uint32_t out_size) {
    return (int32_t)obscura_default_settings_sized((obscura_method)method, out, out_size);
}

int32_t fuzz_get_setting_infos_sized(int32_t method, const obscura_setting_info** out_infos, uint32_t* out_count,
                                     uint32_t info_size) {
    return (int32_t)obscura_get_setting_infos_sized((obscura_method)method, out_infos, out_count, info_size);
}

/* The 0.3 ABI: the plain symbols a binary built against the 0.3 header calls (the parentheses keep the macros
   of the same names from expanding). */
int32_t fuzz_default_settings_03(int32_t method, obscura_settings* out) {
    return (int32_t)(obscura_default_settings)((obscura_method)method, out);
}

int32_t fuzz_get_setting_infos_03(int32_t method, const obscura_setting_info** out_infos, uint32_t* out_count) {
    return (int32_t)(obscura_get_setting_infos)((obscura_method)method, out_infos, out_count);
}
