#include "method_spec.h"

#include <cstring>

#include "cli_args.h"
#include "cli_errors.h"
#include "obscura_session.h"

namespace obscura::cli {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    size_t start = 0;
    while (true) {
        const size_t end = text.find(separator, start);
        parts.push_back(text.substr(start, end - start));
        if (end == std::string::npos) return parts;
        start = end + 1;
    }
}

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

// Toggles also take on/off/true/false/yes/no; everything else is a number.
double parse_setting_value(const obscura_setting_info* info, const std::string& key, const std::string& text) {
    if (info && info->type == OBSCURA_SETTING_TOGGLE) {
        for (const char* on : {"on", "true", "yes"}) {
            if (text == on) return 1.0;
        }
        for (const char* off : {"off", "false", "no"}) {
            if (text == off) return 0.0;
        }
    }
    return parse_double(key, text);
}

}  // namespace

std::vector<obscura_method> all_methods() {
    std::vector<obscura_method> methods;
    for (int value = OBSCURA_METHOD_HBAO; value < OBSCURA_METHOD_COUNT_; ++value) {
        methods.push_back(static_cast<obscura_method>(value));
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

MethodSpec parse_method_spec(const std::string& text) {
    MethodSpec spec;
    spec.text = text;
    const size_t colon = text.find(':');
    const obscura_method method = find_method(text.substr(0, colon));
    const obscura_status defaults = obscura_default_settings(method, &spec.settings);
    if (defaults != OBSCURA_OK) throw ApiError(api_error_message(defaults, "obscura_default_settings", nullptr));
    if (colon == std::string::npos) return spec;

    const std::vector<obscura_setting_info> infos = setting_infos(method);
    const char* method_name = obscura_method_name(method);
    for (const std::string& assignment : split(text.substr(colon + 1), ',')) {
        if (assignment.empty()) continue;
        const size_t equals = assignment.find('=');
        if (equals == std::string::npos) {
            throw UsageError("'" + assignment + "' in --method " + text + " is not key=value");
        }
        const std::string key = assignment.substr(0, equals);
        const obscura_setting_info* info = find_info(infos, key);
        if (!info) {
            throw UsageError("unknown setting '" + key + "' for " + method_name + " (valid: " + valid_keys(method) + ")");
        }
        const double value = parse_setting_value(info, key, assignment.substr(equals + 1));
        const obscura_status status = obscura_set_setting(&spec.settings, key.c_str(), value);
        if (status == OBSCURA_STATUS_UNKNOWN_SETTING) {
            throw UsageError("unknown setting '" + key + "' for " + method_name + " (valid: " + valid_keys(method) + ")");
        }
        if (status == OBSCURA_STATUS_INVALID_SETTING) {
            throw UsageError(key + "=" + assignment.substr(equals + 1) + " is out of range for " + method_name +
                             ": [" + format_number(info->min_value) + ", " + format_number(info->max_value) + "] " +
                             info->unit);
        }
        if (status != OBSCURA_OK) throw ApiError(api_error_message(status, "obscura_set_setting(" + key + ")", nullptr));
    }
    return spec;
}

std::string format_setting_value(const obscura_setting_info& info, double value) {
    if (info.type == OBSCURA_SETTING_TOGGLE) return value != 0.0 ? "on" : "off";
    std::string text = format_number(value);
    if (info.unit && *info.unit) text += std::string(" ") + info.unit;
    return text;
}

void print_effective_settings(std::FILE* out, const ObscuraSession& session, const obscura_settings& settings) {
    obscura_settings resolved{};
    session.check(obscura_resolve_settings(session.get(), &settings, &resolved), "obscura_resolve_settings");
    std::fprintf(out, "effective settings (%s):\n", obscura_method_name(resolved.method));
    const std::vector<obscura_setting_info> infos = setting_infos(resolved.method);
    if (infos.empty()) std::fprintf(out, "  (no settings)\n");
    for (const obscura_setting_info& info : infos) {
        double value = 0.0;
        session.check(obscura_get_setting(&resolved, info.name, &value), std::string("obscura_get_setting(") + info.name + ")");
        std::fprintf(out, "  %-18s %s\n", info.name, format_setting_value(info, value).c_str());
    }
}

}  // namespace obscura::cli
