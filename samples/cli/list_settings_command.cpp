// obscura --list-settings [method]: the settings tables exactly as the SDK's metadata declares them.
#include <cstdio>
#include <string>

#include "cli_errors.h"
#include "commands.h"
#include "method_spec.h"

namespace obscura::cli {
namespace {

const char* type_name(obscura_setting_type type) {
    switch (type) {
    case OBSCURA_SETTING_FLOAT: return "float";
    case OBSCURA_SETTING_INT: return "int";
    case OBSCURA_SETTING_TOGGLE: return "toggle";
    }
    return "?";
}

std::string format_default(const obscura_setting_info& info) {
    if (info.type == OBSCURA_SETTING_TOGGLE) return info.default_value != 0.0 ? "on" : "off";
    char text[32];
    std::snprintf(text, sizeof text, "%g", info.default_value);
    return text;
}

void print_method_settings(obscura_method method) {
    std::printf("%s%s\n", obscura_method_name(method), obscura_method_available(method) ? "" : " (not available yet)");
    const std::vector<obscura_setting_info> infos = setting_infos(method);
    if (infos.empty()) {
        std::printf("  (no settings)\n\n");
        return;
    }
    std::printf("  %-18s %-7s %-9s %-9s %-9s %-5s %s\n", "name", "type", "default", "min", "max", "unit",
                "description");
    for (const obscura_setting_info& info : infos) {
        std::printf("  %-18s %-7s %-9s %-9g %-9g %-5s %s\n", info.name, type_name(info.type),
                    format_default(info).c_str(),
                    info.min_value, info.max_value, info.unit ? info.unit : "", info.description ? info.description : "");
    }
    std::printf("\n");
}

}  // namespace

int run_list_settings(ArgumentList& arguments) {
    const std::vector<std::string> names = arguments.take_positionals();
    arguments.require_all_taken();
    if (names.size() > 1) throw UsageError("--list-settings takes at most one method");
    if (names.empty()) {
        for (obscura_method method : all_methods()) print_method_settings(method);
    } else {
        print_method_settings(find_method(names.front()));
    }
    return 0;
}

}  // namespace obscura::cli
