// Method specs, the one parser of the CLI, the viewer and the golden tests: NAME[:KEY=VALUE[:KEY=VALUE...]],
// e.g. "hbao:directions=16:steps=48", "lsao:preset=k32", "ffao:falloff=table:falloff_table=@rho.txt".
//
//     obscura_settings settings = parse_method_spec("hbao:radius=1.5");  // MethodSpecError: the spec is wrong
//
// A spec starts from obscura_default_settings(method), the editable form: the derived fields (decay rates,
// LSAO's K, D_S and D_L, SAO's spiral turns, FFAO's K) stay 0, "derive", unless the spec gives them, so
// `lsao:preset=4` renders K = 32 and `hbao:radius=1.5` moves the falloff's end. Every key goes through the
// SDK's settings metadata (obscura_get_setting_infos): whatever it declares works here, with its ranges and
// value names. Values:
//   - numbers: every setting but the arrays (ENUM settings take their values, toggles 1 and 0); 0 in a derived
//     field derives it;
//   - the value names of ENUM settings (ffao:falloff=exponential, lsao:pattern=free, lsao:preset=k32);
//   - toggles: on/off, true/false, yes/no, 1/0;
//   - FLOAT_ARRAY settings (the falloff_table of REFERENCE and FFAO): V0/V1/.../V15 inline, or @FILE, a text
//     file of the values separated by whitespace, commas or newlines. Each in the metadata's range.
// After the keys the settings are resolved (obscura_resolve_settings): settings that the SDK refuses as a
// whole (falloff=table with the table all zero, FFAO's K odd, ...) are a MethodSpecError with the SDK's reason
// (obscura_get_last_error(NULL)), and for the falloff table the spec syntax that gives one.
#ifndef OBSCURA_SAMPLES_METHOD_SPEC_PARSER_H
#define OBSCURA_SAMPLES_METHOD_SPEC_PARSER_H

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "obscura/obscura.h"

namespace obscura::samples {

// The spec (or a value in it) is wrong: the user's to fix (the CLI's exit code 2). what() names the spec or
// the key and says what is expected.
class MethodSpecError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The library cannot do what a valid spec asks: a method it does not implement, a metadata call that fails
// (the CLI's exit code 1).
class SettingsLibraryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// ---- Methods and their metadata ----------------------------------------------------------------------
// Every method of the API, OBSCURA_METHOD_DEFAULT excluded.
std::vector<obscura_method> all_methods();
// "hbao, sao, lsao, ffao, reference": the names of every method, for messages.
std::string method_names();
// "hbao" -> OBSCURA_METHOD_HBAO; MethodSpecError listing the method names otherwise.
obscura_method find_method(std::string_view name);
// The settings metadata of `method` (an empty list when it has none), then the rows every method shares (temporal
// accumulation); SettingsLibraryError when a call fails.
std::vector<obscura_setting_info> setting_infos(obscura_method method);
// The row named `name`, or nullptr.
const obscura_setting_info* find_setting(const std::vector<obscura_setting_info>& infos, std::string_view name);

// ---- Rows --------------------------------------------------------------------------------------------
bool is_derived(const obscura_setting_info& info);  // OBSCURA_SETTING_FLAG_DERIVED
bool is_array(const obscura_setting_info& info);    // OBSCURA_SETTING_FLOAT_ARRAY
// The row's field as C names it inside obscura_settings: "<method>.<key>" ("ffao.sectors"), a shared row's key
// ("temporal.enabled"), or for a field added to a released method later its own block's ("ffao_added.frame_split").
std::string c_field_path(obscura_method method, const obscura_setting_info& info);
// The name of `value` of an ENUM or TOGGLE row ("exponential", "on"); "" when the value has none.
std::string value_name(const obscura_setting_info& info, double value);
// Every value name of the row, ", "-separated ("rho0, inverse_quadratic, exponential, table"); "" for none.
std::string value_name_list(const obscura_setting_info& info);
// The field as stored in `settings` (not resolved): 0 in a derived field means "derive".
double stored_value(const obscura_settings& settings, const obscura_setting_info& info);
// A derived field that holds 0: the SDK derives it.
bool derives(const obscura_settings& settings, const obscura_setting_info& info);
// The floats of a FLOAT_ARRAY row inside `settings` (info.value_count of them); SettingsLibraryError when
// the row is not an array or does not fit the struct.
float* array_values(obscura_settings& settings, const obscura_setting_info& info);
const float* array_values(const obscura_settings& settings, const obscura_setting_info& info);

// The falloff table row of `method` (REFERENCE, FFAO), or nullptr for a method without one.
const obscura_setting_info* falloff_table_info(obscura_method method);
// Whether `settings` weigh occluders with their falloff table (the method's falloff reads "table"); only then
// does the SDK read the table.
bool uses_falloff_table(const obscura_settings& settings);

// ---- Values ------------------------------------------------------------------------------------------
// The number obscura_set_setting takes for `text` (a number, a value name, a toggle word). `what` names the
// setting in messages ("ffao falloff"). MethodSpecError for anything else, listing the value names.
double parse_setting_value(const obscura_setting_info& info, const std::string& text, const std::string& what);
// An array's values from `text`: V0/V1/... inline or @FILE. MethodSpecError for a wrong count, a value that is
// not a number or outside the row's range, a file that cannot be read.
std::vector<float> parse_array_value(const obscura_setting_info& info, const std::string& text,
                                     const std::string& what);
// The values of a file as @FILE reads it (whitespace, commas or newlines between them), checked the same way.
std::vector<float> read_array_file(const obscura_setting_info& info, const std::string& path, const std::string& what);
// Sets the row's field from `text` (what a spec's KEY=VALUE holds): through obscura_set_setting, arrays through
// their offset. MethodSpecError for a value the parsers or the SDK refuse (its range in the message).
void apply_setting(obscura_settings& settings, const obscura_setting_info& info, const std::string& text,
                   const std::string& what);

// "1.5 m", "on", "exponential", "12": an effective value (obscura_get_setting) as the user writes it.
std::string format_setting_value(const obscura_setting_info& info, double value);
// "1/0.8/0.5/0": array values as a spec takes them inline.
std::string format_array_value(const float* values, uint32_t count);

// ---- Specs -------------------------------------------------------------------------------------------
// KEY=VALUE, from a spec or from the CLI's --set.
struct SettingAssignment {
    std::string key;
    std::string value;
    std::string text;  // as given
};
// MethodSpecError naming `where` when `text` is empty or not KEY=VALUE.
SettingAssignment parse_assignment(const std::string& text, const std::string& where);

// One spec, parsed and resolved (see the top of this file). `set_options` (KEY=VALUE) are applied first, each
// only where the method has its key; the spec's own keys are checked first (an unknown one is reported as
// such) and applied last (they win). MethodSpecError: no or an unknown method, an unknown key, a value that
// is not one of the setting's, settings the SDK refuses as a whole. SettingsLibraryError: a method this
// library does not implement.
obscura_settings parse_method_spec(const std::string& text, const std::vector<std::string>& set_options = {});

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_METHOD_SPEC_PARSER_H
