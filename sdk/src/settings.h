// Settings: the metadata table (declared once, read by the API, the CLI, the viewer and the docs),
// defaulting of zero fields, and validation.
#ifndef OBSCURA_SETTINGS_H
#define OBSCURA_SETTINGS_H

#include "error.h"

namespace obscura {

// The table for `method` (OBSCURA_METHOD_DEFAULT maps to HBAO); count 0 for methods with none yet.
const obscura_setting_info* setting_infos(obscura_method method, uint32_t* count);

// Resolved method (DEFAULT -> HBAO); OBSCURA_METHOD_COUNT_ for unknown values.
obscura_method resolve_method(obscura_method method);

// SAO's default spiral turns for s samples: the integer nearest 7s/9 sharing no factor with s (7 for 9).
int default_spiral_turns(int samples);

// Sizes of every released version of obscura_settings that the library accepts.
bool is_known_settings_size(uint32_t struct_size);

// Defaults every zero field, validates every field, and derives dependent values (HBAO decay rate).
Error resolve_settings(const obscura_settings& in, obscura_settings* out);

// REFERENCE settings with the falloff of `method_settings`'s method (obscura_reference_settings_for).
Error reference_settings_for(const obscura_settings& method_settings, obscura_settings* out);

// Reads / writes one field through the table (the value a UI shows: defaults for zero fields).
Error get_setting(const obscura_settings& settings, const char* name, double* value);
Error set_setting(obscura_settings* settings, const char* name, double value);

}  // namespace obscura

#endif  // OBSCURA_SETTINGS_H
