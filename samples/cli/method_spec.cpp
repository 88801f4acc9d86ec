#include "method_spec.h"

#include <algorithm>
#include <utility>

#include "cli_args.h"
#include "cli_errors.h"
#include "method_spec_parser.h"
#include "obscura_session.h"

namespace obscura::cli {
namespace {

// Runs `call` with the common parser's errors turned into the CLI's: a wrong spec is a usage error (exit 2),
// what the library cannot do an API error (exit 1).
template <class Call>
auto with_cli_errors(Call&& call) -> decltype(call()) {
    try {
        return call();
    } catch (const samples::MethodSpecError& error) {
        throw UsageError(error.what());
    } catch (const samples::SettingsLibraryError& error) {
        throw ApiError(error.what());
    }
}

}  // namespace

std::vector<obscura_method> all_methods() { return samples::all_methods(); }

std::vector<obscura_method> comparable_methods() {
    std::vector<obscura_method> methods;
    for (obscura_method method : all_methods()) {
        if (method != OBSCURA_METHOD_REFERENCE && obscura_method_available(method)) methods.push_back(method);
    }
    return methods;
}

obscura_method find_method(const std::string& name) {
    return with_cli_errors([&] { return samples::find_method(name); });
}

std::vector<obscura_setting_info> setting_infos(obscura_method method) {
    return with_cli_errors([&] { return samples::setting_infos(method); });
}

MethodSpec parse_method_spec(const std::string& text, const std::vector<std::string>& set_options) {
    MethodSpec spec;
    spec.text = text;
    spec.settings = with_cli_errors([&] { return samples::parse_method_spec(text, set_options); });
    return spec;
}

std::vector<MethodSpec> parse_method_specs(const std::string& option, const std::string& list,
                                           const std::vector<std::string>& set_options) {
    std::vector<MethodSpec> specs;
    for (const std::string& text : split_list(option, list)) specs.push_back(parse_method_spec(text, set_options));
    std::vector<std::string> set_keys;
    for (const std::string& set : set_options) {
        const samples::SettingAssignment assignment =
            with_cli_errors([&] { return samples::parse_assignment(set, "--set"); });
        // Two values for one key: the last would win silently.
        if (std::find(set_keys.begin(), set_keys.end(), assignment.key) != set_keys.end()) {
            throw UsageError("--set " + assignment.key + " given more than once");
        }
        set_keys.push_back(assignment.key);
        bool used = false;
        std::string methods;
        for (const MethodSpec& spec : specs) {
            used = used || samples::find_setting(setting_infos(spec.method()), assignment.key) != nullptr;
            methods += std::string(methods.empty() ? "" : ", ") + spec.name();
        }
        if (!used) throw UsageError("--set " + set + ": no method of this command has a setting '" + assignment.key +
                                    "' (methods: " + methods + "; see --list-settings)");
    }
    return specs;
}

std::vector<EffectiveSetting> effective_settings(const obscura_settings& settings, obscura_context* context) {
    obscura_settings resolved{};
    const obscura_status status = obscura_resolve_settings(context, &settings, &resolved);
    if (status != OBSCURA_OK) throw ApiError(api_error_message(status, "obscura_resolve_settings", context));
    std::vector<EffectiveSetting> values;
    for (const obscura_setting_info& info : setting_infos(resolved.method)) {
        EffectiveSetting value;
        value.info = info;
        value.derived = samples::derives(settings, info);
        if (samples::is_array(info)) {
            const float* stored = with_cli_errors([&] { return samples::array_values(resolved, info); });
            value.values.assign(stored, stored + info.value_count);
        } else {
            const obscura_status read = obscura_get_setting(&resolved, info.name, &value.value);
            if (read != OBSCURA_OK) {
                throw ApiError(api_error_message(read, std::string("obscura_get_setting(") + info.name + ")", nullptr));
            }
        }
        values.push_back(std::move(value));
    }
    return values;
}

std::string format_setting_value(const obscura_setting_info& info, double value) {
    return samples::format_setting_value(info, value);
}

void print_effective_settings(std::FILE* out, const obscura_settings& settings, obscura_context* context) {
    const std::vector<EffectiveSetting> values = effective_settings(settings, context);
    const bool table = with_cli_errors([&] { return samples::uses_falloff_table(settings); });
    std::fprintf(out, "effective settings (%s):\n", obscura_method_name(settings.method));
    if (values.empty()) std::fprintf(out, "  (no settings)\n");
    for (const EffectiveSetting& value : values) {
        std::string text;
        if (samples::is_array(value.info)) {
            // Only the table falloff reads the table; otherwise its values mean nothing.
            text = table ? samples::format_array_value(value.values.data(), value.info.value_count)
                         : "(unused: falloff is not table)";
        } else {
            text = format_setting_value(value.info, value.value);
            if (value.derived) text += " (derived)";
        }
        std::fprintf(out, "  %-18s %s\n", value.info.name, text.c_str());
    }
}

}  // namespace obscura::cli
