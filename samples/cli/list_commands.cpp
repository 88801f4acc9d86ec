// obscura --list-scenes, --list-methods, --list-settings [METHOD]: what the scene library and the
// SDK's metadata declare, without GL.
#include <cstdio>
#include <exception>
#include <string>

#include "cli_errors.h"
#include "commands.h"
#include "method_spec.h"
#include "scene_library.h"

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

// A value of a setting as its type reads: whole numbers for ints (%g would print 16777216 as 1.67772e+07).
std::string format_value(const obscura_setting_info& info, double value) {
    char text[32];
    std::snprintf(text, sizeof text, info.type == OBSCURA_SETTING_FLOAT ? "%g" : "%.0f", value);
    return text;
}

std::string format_default(const obscura_setting_info& info) {
    if (info.type == OBSCURA_SETTING_TOGGLE) return info.default_value != 0.0 ? "on" : "off";
    return format_value(info, info.default_value);
}

void print_method_settings(obscura_method method) {
    std::printf("%s%s\n", obscura_method_name(method), obscura_method_available(method) ? "" : " (not available)");
    const std::vector<obscura_setting_info> infos = setting_infos(method);
    if (infos.empty()) {
        std::printf("  (no settings)\n\n");
        return;
    }
    std::printf("  %-18s %-7s %-9s %-9s %-9s %-5s %s\n", "name", "type", "default", "min", "max", "unit",
                "description");
    for (const obscura_setting_info& info : infos) {
        std::printf("  %-18s %-7s %-9s %-9s %-9s %-5s %s\n", info.name, type_name(info.type),
                    format_default(info).c_str(), format_value(info, info.min_value).c_str(),
                    format_value(info, info.max_value).c_str(), info.unit ? info.unit : "",
                    info.description ? info.description : "");
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

int run_list_methods(ArgumentList& arguments) {
    arguments.require_all_taken();
    for (obscura_method method : all_methods()) {
        std::printf("%-10s %s\n", obscura_method_name(method),
                    obscura_method_available(method) ? "available" : "not available");
    }
    return 0;
}

int run_list_scenes(ArgumentList& arguments) {
    arguments.require_all_taken();
    for (const samples::SceneInfo& info : samples::list_scenes()) {
        std::string viewpoints;
        if (info.available) {
            try {
                for (const samples::NamedCamera& camera : samples::load_scene(info.name).viewpoints) {
                    viewpoints += (viewpoints.empty() ? "" : ", ") + camera.name;
                }
            } catch (const std::exception& error) {
                viewpoints = std::string("(cannot load: ") + error.what() + ")";
            }
        } else if (info.name == "bunny") {
            viewpoints = std::string("(needs ") + samples::bunny_obj_path() + ")";
        }
        std::printf("%-9s %-13s %s\n", info.name.c_str(), info.available ? "available" : "not available",
                    info.description.c_str());
        if (!viewpoints.empty()) std::printf("%-9s %-13s viewpoints: %s\n", "", "", viewpoints.c_str());
    }
    std::printf("or a path to a Wavefront .obj file (viewpoints: default, left, right, top)\n");
    return 0;
}

}  // namespace obscura::cli
