// Settings: the generic machinery over every method's metadata rows (each method declares its rows and its
// derived values beside its technique, sdk/src/methods/): defaulting of zero fields, range checks, the
// derived values through the registry, get/set by name, and the falloff a method is compared with. No GL.
#ifndef OBSCURA_SETTINGS_H
#define OBSCURA_SETTINGS_H

#include <cstddef>

#include "error.h"

namespace obscura {

// A metadata row's offset: `field` of the `block` member (obscura_<block>_settings) of obscura_settings.
#define OBSCURA_SETTING_OFFSET(block, field) \
    (offsetof(obscura_settings, block) + offsetof(obscura_##block##_settings, field))

// The table for `method` (OBSCURA_METHOD_DEFAULT maps to HBAO); null and count 0 for a value that is no method.
const obscura_setting_info* setting_infos(obscura_method method, uint32_t* count);

// Resolved method (DEFAULT -> HBAO); OBSCURA_METHOD_COUNT_ for unknown values.
obscura_method resolve_method(obscura_method method);

// Sizes of every released version of obscura_settings that the library accepts.
bool is_known_settings_size(uint32_t struct_size);

// Defaults every zero field, validates every field, and derives dependent values (each method's `derive`).
Error resolve_settings(const obscura_settings& in, obscura_settings* out);

// REFERENCE settings with the falloff of `method_settings`'s method (obscura_reference_settings_for).
Error reference_settings_for(const obscura_settings& method_settings, obscura_settings* out);

// Reads / writes one field through the table (the value a UI shows: defaults for zero fields).
Error get_setting(const obscura_settings& settings, const char* name, double* value);
Error set_setting(obscura_settings* settings, const char* name, double value);

// For the methods' `derive`: a falloff table is read only with OBSCURA_FALLOFF_TABLE, where it must describe
// a falloff (values in [0, 1], not all 0). `method` names it in the message.
Error check_falloff_table(const char* method, int32_t falloff, const float (&table)[OBSCURA_FALLOFF_TABLE_SIZE]);

}  // namespace obscura

#endif  // OBSCURA_SETTINGS_H
