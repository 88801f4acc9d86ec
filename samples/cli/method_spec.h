// Method specs on the command line: NAME[:KEY=VALUE[:KEY=VALUE...]], e.g. "hbao:directions=16:steps=48",
// "lsao:preset=k32" or "ffao:falloff=table:falloff_table=@rho.txt"; lists of them separated by ','
// ("--methods hbao,hbao:blur=off"). The parsing is samples/common/method_spec_parser.h's, which the viewer
// and the golden tests share: this wraps it in the CLI's errors, UsageError (exit 2) for a wrong spec,
// ApiError (exit 1) for what the library cannot do. `--set KEY=VALUE` applies a key to every method of the
// command that has it.
#ifndef OBSCURA_CLI_METHOD_SPEC_H
#define OBSCURA_CLI_METHOD_SPEC_H

#include <cstdio>
#include <string>
#include <vector>

#include "obscura/obscura.h"

namespace obscura::cli {

struct MethodSpec {
    std::string text;             // as given, for tables, JSON and CSV
    obscura_settings settings{};  // the editable defaults, then the --set keys it has, then the spec's keys
    obscura_method method() const { return settings.method; }
    const char* name() const { return obscura_method_name(settings.method); }
};

// Every method of the API, OBSCURA_METHOD_DEFAULT excluded.
std::vector<obscura_method> all_methods();
// The methods `compare` and `demo` measure by default: every available one except the REFERENCE.
std::vector<obscura_method> comparable_methods();
// "hbao" -> OBSCURA_METHOD_HBAO; UsageError listing the method names otherwise.
obscura_method find_method(const std::string& name);
// The settings metadata of `method` (an empty list when it has none).
std::vector<obscura_setting_info> setting_infos(obscura_method method);

// One spec. UsageError for an unknown method or key, a value that is not one of the setting's (a number, a
// value name, on/off, a table of the right length), out of its range, or settings the SDK refuses as a whole
// (falloff=table without falloff_table, say); ApiError (exit code 1) for a method this library does not
// implement. `set_options` are the values of --set (KEY=VALUE), applied where the method has the key.
MethodSpec parse_method_spec(const std::string& text, const std::vector<std::string>& set_options = {});
// A ','-separated list of specs (an empty entry is a UsageError), and --set applied to each. A --set key
// that none of the methods has is a UsageError.
std::vector<MethodSpec> parse_method_specs(const std::string& option, const std::string& list,
                                           const std::vector<std::string>& set_options);

// The settings that obscura_resolve_settings says will be used, by metadata name, in table order.
struct EffectiveSetting {
    obscura_setting_info info;
    double value = 0.0;         // toggles: 0 off, 1 on; enums: their value; arrays: 0
    std::vector<float> values;  // arrays: their values
    bool derived = false;       // a derived field the settings leave to the SDK (0, "derive")
};
// With a context, resolved through it: the values its renderer derives (lsao.segment_steps: whole lines on a CPU
// rasteriser, segments on a GPU or with OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS), what a frame there uses; without one, such
// fields read 0.
std::vector<EffectiveSetting> effective_settings(const obscura_settings& settings, obscura_context* context = nullptr);
// Prints effective_settings(), one per line: enums by name, derived values marked, the falloff table inline.
void print_effective_settings(std::FILE* out, const obscura_settings& settings, obscura_context* context = nullptr);
// "1.5 m", "on", "exponential", "12".
std::string format_setting_value(const obscura_setting_info& info, double value);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_METHOD_SPEC_H
