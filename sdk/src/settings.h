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

// One metadata row (the methods' tables, sdk/src/methods/). Toggles get their value names here.
constexpr const char* const kToggleNames[] = {"off", "on"};
constexpr obscura_setting_info setting_row(const char* name, obscura_setting_type type, double default_value,
                                           double min_value, double max_value, const char* unit,
                                           const char* description, size_t offset, uint32_t flags = 0) {
    return obscura_setting_info{name, type, default_value, min_value, max_value, unit, description, offset, flags,
                                type == OBSCURA_SETTING_TOGGLE ? 2u : 0u,
                                type == OBSCURA_SETTING_TOGGLE ? kToggleNames : nullptr, 0u};
}
// A row added to a released method's table in header version `version` (OBSCURA_VERSION's packing): older callers'
// tables leave it out (setting_infos_04, setting_infos_03).
constexpr obscura_setting_info added_row(obscura_setting_info row, uint32_t version) {
    row.added_in = version;
    return row;
}
// An ENUM row: `names` name the values min_value, min_value + 1, ... (N of them). A derived one (`flags`
// OBSCURA_SETTING_FLAG_DERIVED) has default 0: the method's derive step picks its value.
template <size_t N>
constexpr obscura_setting_info enum_row(const char* name, double default_value, double min_value, const char* description,
                                        size_t offset, const char* const (&names)[N], uint32_t count = N,
                                        uint32_t flags = 0) {
    return obscura_setting_info{name,        OBSCURA_SETTING_ENUM, default_value, min_value, min_value + count - 1,
                                "",          description,          offset,        flags,     count,
                                names,       0u};
}
// A FLOAT_ARRAY row of N floats in [min, max]. Arrays have no default: 0 everywhere.
constexpr obscura_setting_info array_row(const char* name, uint32_t length, double min_value, double max_value,
                                         const char* description, size_t offset) {
    return obscura_setting_info{name, OBSCURA_SETTING_FLOAT_ARRAY, 0.0, min_value, max_value, "", description,
                                offset, 0, length, nullptr, 0u};
}

// The names of obscura_falloff's values from OBSCURA_FALLOFF_RHO0 on.
constexpr const char* const kFalloffNames[] = {"rho0", "inverse_quadratic", "exponential", "table"};

// The table for `method` (OBSCURA_METHOD_DEFAULT maps to HBAO); null and count 0 for a value that is no method.
const obscura_setting_info* setting_infos(const obscura_method& method, uint32_t* count);

// obscura_setting_info as the 0.3 header declared it (the binaries built against 0.3 read this layout).
struct SettingInfo03 {
    const char* name;
    obscura_setting_type type;
    double default_value, min_value, max_value;
    const char* unit;
    const char* description;
    size_t offset;
};
static_assert(sizeof(SettingInfo03) == offsetof(obscura_setting_info, flags), "0.4 appended to the 0.3 layout");
// The method's table in the 0.3 layout: ENUM rows read as INT, array rows (new in 0.4) and rows added since left out.
const SettingInfo03* setting_infos_03(const obscura_method& method, uint32_t* count);

// obscura_setting_info as the 0.4 header declared it: 0.4 appended three fields to the 0.3 layout, 0.5 added_in.
struct SettingInfo04 {
    SettingInfo03 first;  // the 0.3 fields
    uint32_t flags;
    uint32_t value_count;
    const char* const* value_names;
};
static_assert(offsetof(SettingInfo04, flags) == offsetof(obscura_setting_info, flags), "the 0.3 fields first");
static_assert(sizeof(SettingInfo04) == offsetof(obscura_setting_info, added_in), "0.5 appended to the 0.4 layout");
static_assert(sizeof(SettingInfo04) != sizeof(obscura_setting_info), "the sizes tell the layouts apart");
// The method's table in the 0.4 layout: the rows added in 0.5 (added_in > 400) left out.
const SettingInfo04* setting_infos_04(const obscura_method& method, uint32_t* count);

// Resolved method (DEFAULT -> HBAO); OBSCURA_METHOD_COUNT_ for unknown values.
obscura_method resolve_method(const obscura_method& method);

// Sizes of every released version of obscura_settings that the library accepts (0.1 ... this header).
bool is_known_settings_size(uint32_t struct_size);
uint32_t settings_size_03();  // the 0.3 header's sizeof(obscura_settings)

// The caller's struct (any released size) as a whole obscura_settings: its bytes, then zeros (the defaults
// of the fields its header did not have). INVALID_STRUCT_SIZE for a size no header had; `what` names the call.
Error read_host_settings(const obscura_settings* host, obscura_settings* out, const char* what);
// Writes whole settings back into a caller's struct of `size` bytes (a known size), struct_size = size.
void write_host_settings(const obscura_settings& settings, obscura_settings* host, uint32_t size);

// The editable form of `method`'s defaults (obscura_default_settings): every field its default, derived fields
// 0, OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE set. INVALID_ENUM for a value that is no method.
Error default_settings(const obscura_method& method, obscura_settings* out);

// Defaults every zero field, validates every field, and derives dependent values (each method's `derive`).
// `in` is whole (read_host_settings).
Error resolve_settings(const obscura_settings& in, obscura_settings* out);
// What resolved settings leave to the context because it depends on the GL renderer (LSAO's segment_steps 0), as a
// context on such a renderer settles it (MethodDescriptor::derive_for_renderer).
void derive_for_renderer(bool cpu_renderer, obscura_settings* resolved);

// REFERENCE settings with the falloff of `method_settings`'s method (obscura_reference_settings_for).
Error reference_settings_for(const obscura_settings& method_settings, obscura_settings* out);

// Reads / writes one field of whole settings through the table (the value a UI shows: what resolve will use).
// get_setting reads every row, those beyond an older caller's struct as what resolve uses for them (their
// defaults: read_host_settings filled them); set_setting cannot store there: `host_size`, the caller's struct size,
// makes fields beyond it UNKNOWN_SETTING.
Error get_setting(const obscura_settings& settings, const char* name, double* value);
Error set_setting(obscura_settings* settings, const char* name, double value,
                  uint32_t host_size = sizeof(obscura_settings));

// For the methods' `derive`: a falloff table is read only with OBSCURA_FALLOFF_TABLE, where it must describe
// a falloff (values in [0, 1], not all 0). `method` names it in the message.
Error check_falloff_table(const char* method, int32_t falloff, const float (&table)[OBSCURA_FALLOFF_TABLE_SIZE]);

}  // namespace obscura

#endif  // OBSCURA_SETTINGS_H
