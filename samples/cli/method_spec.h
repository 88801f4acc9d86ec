// Method specs on the command line: "hbao" or "hbao:radius=1.5,blur=off,steps=8". Every key is
// applied through obscura_set_setting, so whatever the SDK's settings metadata declares works here.
#ifndef OBSCURA_CLI_METHOD_SPEC_H
#define OBSCURA_CLI_METHOD_SPEC_H

#include <cstdio>
#include <string>
#include <vector>

#include "obscura/obscura.h"

namespace obscura::cli {

class ObscuraSession;

struct MethodSpec {
    std::string text;            // as given, for tables and CSV
    obscura_settings settings{}; // the method's defaults with the spec's keys applied
    obscura_method method() const { return settings.method; }
    const char* name() const { return obscura_method_name(settings.method); }
};

// Every method of the API, OBSCURA_METHOD_DEFAULT excluded.
std::vector<obscura_method> all_methods();
// "hbao" -> OBSCURA_METHOD_HBAO; UsageError listing the method names otherwise.
obscura_method find_method(const std::string& name);
// The settings metadata of `method` (an empty list when it has none).
std::vector<obscura_setting_info> setting_infos(obscura_method method);
// UsageError on unknown methods or keys (listing the valid ones) and on values out of range.
MethodSpec parse_method_spec(const std::string& text);
// Prints the values obscura_resolve_settings says will be used, one per line.
void print_effective_settings(std::FILE* out, const ObscuraSession& session, const obscura_settings& settings);
// "1.5 m", "on", "12".
std::string format_setting_value(const obscura_setting_info& info, double value);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_METHOD_SPEC_H
