#include "method_spec.h"

#include <cmath>

#include "cli_args.h"
#include "cli_errors.h"
#include "obscura_session.h"

namespace obscura::cli {
namespace {

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string valid_keys(obscura_method method) {
    std::string keys;
    for (const obscura_setting_info& info : setting_infos(method)) {
        keys += std::string(keys.empty() ? "" : ", ") + info.name;
    }
    return keys.empty() ? "none" : keys;
}

const obscura_setting_info* find_info(const std::vector<obscura_setting_info>& infos, const std::string& key) {
    for (const obscura_setting_info& info : infos) {
        if (key == info.name) return &info;
    }
    return nullptr;
}

// KEY=VALUE, from a spec or from --set.
struct Assignment {
    std::string key;
    std::string value;
    std::string text;  // as given
};

Assignment parse_assignment(const std::string& text, const std::string& where) {
    const size_t equals = text.find('=');
    if (text.empty()) throw UsageError("empty setting in " + where + " (expected KEY=VALUE)");
    if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
        throw UsageError("'" + text + "' in " + where + " is not KEY=VALUE");
    }
    return Assignment{text.substr(0, equals), text.substr(equals + 1), text};
}

// Toggles take on/off (also true/false, yes/no, 1/0); everything else is a number.
double parse_setting_value(const obscura_setting_info& info, const Assignment& assignment, const char* method_name) {
    const std::string& text = assignment.value;
    if (info.type == OBSCURA_SETTING_TOGGLE) {
        for (const char* on : {"on", "true", "yes", "1"}) {
            if (text == on) return 1.0;
        }
        for (const char* off : {"off", "false", "no", "0"}) {
            if (text == off) return 0.0;
        }
        throw UsageError(std::string(method_name) + " " + assignment.key + ": '" + text + "' is not on or off");
    }
    return parse_double(std::string(method_name) + " " + assignment.key, text);
}

// Applies one assignment whose key the method has (the caller checked).
void apply(obscura_settings& settings, const obscura_setting_info& info, const Assignment& assignment) {
    const char* method_name = obscura_method_name(settings.method);
    const double value = parse_setting_value(info, assignment, method_name);
    const obscura_status status = obscura_set_setting(&settings, info.name, value);
    if (status == OBSCURA_STATUS_INVALID_SETTING) {
        const bool whole = info.type == OBSCURA_SETTING_FLOAT || value == std::floor(value);
        const std::string range = "[" + format_number(info.min_value) + ", " + format_number(info.max_value) + "]" +
                                  (info.unit && *info.unit ? std::string(" ") + info.unit : std::string());
        throw UsageError(std::string(method_name) + " " + assignment.text +
                         (whole ? " is outside " + range : " must be a whole number in " + range));
    }
    if (status != OBSCURA_OK) {
        throw ApiError(api_error_message(status, std::string("obscura_set_setting(") + info.name + ")", nullptr));
    }
}

}  // namespace

std::vector<obscura_method> all_methods() {
    std::vector<obscura_method> methods;
    for (int value = OBSCURA_METHOD_HBAO; value < OBSCURA_METHOD_COUNT_; ++value) {
        methods.push_back(static_cast<obscura_method>(value));
    }
    return methods;
}

std::vector<obscura_method> comparable_methods() {
    std::vector<obscura_method> methods;
    for (obscura_method method : all_methods()) {
        if (method != OBSCURA_METHOD_REFERENCE && obscura_method_available(method)) methods.push_back(method);
    }
    return methods;
}

obscura_method find_method(const std::string& name) {
    std::string names;
    for (obscura_method method : all_methods()) {
        const char* method_name = obscura_method_name(method);
        if (method_name && name == method_name) return method;
        names += std::string(names.empty() ? "" : ", ") + (method_name ? method_name : "?");
    }
    throw UsageError("unknown method '" + name + "' (valid: " + names + ")");
}

std::vector<obscura_setting_info> setting_infos(obscura_method method) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    const obscura_status status = obscura_get_setting_infos(method, &infos, &count);
    if (status != OBSCURA_OK) throw ApiError(api_error_message(status, "obscura_get_setting_infos", nullptr));
    return std::vector<obscura_setting_info>(infos, infos + count);
}

MethodSpec parse_method_spec(const std::string& text, const std::vector<std::string>& set_options) {
    MethodSpec spec;
    spec.text = text;
    const size_t colon = text.find(':');
    const std::string name = text.substr(0, colon);
    if (name.empty()) throw UsageError("method spec '" + text + "' has no method name");
    const obscura_method method = find_method(name);
    if (!obscura_method_available(method)) {
        throw ApiError("method '" + name + "' is not available in this build of libobscura " +
                       "(obscura_method_available returned 0; see --list-methods)");
    }
    // Zero means default (resolved at render time): derived defaults such as HBAO's decay rate
    // (C * radius^2) then follow the keys given, which obscura_default_settings' explicit values would not.
    spec.settings = obscura_settings{};
    spec.settings.struct_size = sizeof spec.settings;
    spec.settings.method = method;

    // The spec's keys are checked first (so a typo is reported as such), applied last (so they win).
    const std::vector<obscura_setting_info> infos = setting_infos(method);
    std::vector<std::pair<const obscura_setting_info*, Assignment>> own;
    for (size_t start = colon; start != std::string::npos;) {
        const size_t end = text.find(':', start + 1);
        const std::string item = text.substr(start + 1, end == std::string::npos ? std::string::npos : end - start - 1);
        const Assignment assignment = parse_assignment(item, "method spec '" + text + "'");
        const obscura_setting_info* info = find_info(infos, assignment.key);
        if (!info) {
            throw UsageError("unknown setting '" + assignment.key + "' in '" + text + "' (" + name +
                             " has: " + valid_keys(method) + ")");
        }
        own.emplace_back(info, assignment);
        start = end;
    }
    for (const std::string& option : set_options) {
        const Assignment assignment = parse_assignment(option, "--set");
        if (const obscura_setting_info* info = find_info(infos, assignment.key)) apply(spec.settings, *info, assignment);
    }
    for (const auto& [info, assignment] : own) apply(spec.settings, *info, assignment);
    return spec;
}

std::vector<MethodSpec> parse_method_specs(const std::string& option, const std::string& list,
                                           const std::vector<std::string>& set_options) {
    std::vector<MethodSpec> specs;
    for (const std::string& text : split_list(option, list)) specs.push_back(parse_method_spec(text, set_options));
    for (const std::string& set : set_options) {
        const Assignment assignment = parse_assignment(set, "--set");
        bool used = false;
        std::string methods;
        for (const MethodSpec& spec : specs) {
            used = used || find_info(setting_infos(spec.method()), assignment.key) != nullptr;
            methods += std::string(methods.empty() ? "" : ", ") + spec.name();
        }
        if (!used) throw UsageError("--set " + set + ": no method of this command has a setting '" + assignment.key +
                                    "' (methods: " + methods + "; see --list-settings)");
    }
    return specs;
}

std::vector<EffectiveSetting> effective_settings(const obscura_settings& settings) {
    obscura_settings resolved{};
    const obscura_status status = obscura_resolve_settings(nullptr, &settings, &resolved);
    if (status != OBSCURA_OK) throw ApiError(api_error_message(status, "obscura_resolve_settings", nullptr));
    std::vector<EffectiveSetting> values;
    for (const obscura_setting_info& info : setting_infos(resolved.method)) {
        EffectiveSetting value;
        value.info = info;
        const obscura_status read = obscura_get_setting(&resolved, info.name, &value.value);
        if (read != OBSCURA_OK) {
            throw ApiError(api_error_message(read, std::string("obscura_get_setting(") + info.name + ")", nullptr));
        }
        values.push_back(value);
    }
    return values;
}

std::string format_setting_value(const obscura_setting_info& info, double value) {
    if (info.type == OBSCURA_SETTING_TOGGLE) return value != 0.0 ? "on" : "off";
    std::string text = format_number(value);
    if (info.unit && *info.unit) text += std::string(" ") + info.unit;
    return text;
}

void print_effective_settings(std::FILE* out, const obscura_settings& settings) {
    const std::vector<EffectiveSetting> values = effective_settings(settings);
    std::fprintf(out, "effective settings (%s):\n", obscura_method_name(settings.method));
    if (values.empty()) std::fprintf(out, "  (no settings)\n");
    for (const EffectiveSetting& value : values) {
        std::fprintf(out, "  %-18s %s\n", value.info.name, format_setting_value(value.info, value.value).c_str());
    }
}

}  // namespace obscura::cli
