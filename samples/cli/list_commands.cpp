// obscura --list-scenes, --list-methods, --list-settings [METHOD]: what the scene library and the
// SDK's metadata declare, without GL. --list-settings: one row per setting (name, type, default, range, unit,
// description); enums name their values, derived settings say "derived", arrays are float[N].
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli_errors.h"
#include "commands.h"
#include "method_spec.h"
#include "method_spec_parser.h"
#include "scene_library.h"

namespace obscura::cli {
namespace {

// "float", "int", "toggle", "enum", "float[16]".
std::string type_name(const obscura_setting_info& info) {
    switch (info.type) {
    case OBSCURA_SETTING_FLOAT: return "float";
    case OBSCURA_SETTING_INT: return "int";
    case OBSCURA_SETTING_TOGGLE: return "toggle";
    case OBSCURA_SETTING_ENUM: return "enum";
    case OBSCURA_SETTING_FLOAT_ARRAY: return "float[" + std::to_string(info.value_count) + "]";
    }
    return "?";
}

// A value of a setting as its type reads: whole numbers for ints and enums (%g would print 16777216 as
// 1.67772e+07).
std::string format_value(const obscura_setting_info& info, double value) {
    char text[32];
    std::snprintf(text, sizeof text, info.type == OBSCURA_SETTING_FLOAT || samples::is_array(info) ? "%g" : "%.0f",
                  value);
    return text;
}

// Derived fields have no default of their own ("derived": the description says from what); arrays none at all.
std::string format_default(const obscura_setting_info& info) {
    if (samples::is_derived(info)) return "derived";
    if (samples::is_array(info)) return "none";
    if (info.type == OBSCURA_SETTING_TOGGLE || info.type == OBSCURA_SETTING_ENUM) {
        const std::string name = samples::value_name(info, info.default_value);
        if (!name.empty()) return name;
    }
    return format_value(info, info.default_value);
}

// Enums list their value names (a spec takes the names or the numbers min..max), arrays how a spec gives them.
std::string format_description(const obscura_setting_info& info) {
    const std::string description = info.description ? info.description : "";
    if (info.type == OBSCURA_SETTING_ENUM) return "{" + samples::value_name_list(info) + "} " + description;
    if (samples::is_array(info)) {
        return std::to_string(info.value_count) + " values, V0/V1/.../V" + std::to_string(info.value_count - 1) +
               " or @FILE: " + description;
    }
    return description;
}

void print_method_settings(obscura_method method) {
    std::printf("%s%s\n", obscura_method_name(method), obscura_method_available(method) ? "" : " (not available)");
    const std::vector<obscura_setting_info> infos = setting_infos(method);
    if (infos.empty()) {
        std::printf("  (no settings)\n\n");
        return;
    }
    // Columns as wide as their widest cell (at least the old fixed widths), so that names such as
    // "inverse_quadratic" keep the table aligned; scripts read the widths from the header line.
    std::vector<std::vector<std::string>> rows = {{"name", "type", "default", "min", "max", "unit", "description"}};
    for (const obscura_setting_info& info : infos) {
        rows.push_back({info.name, type_name(info), format_default(info), format_value(info, info.min_value),
                        format_value(info, info.max_value), info.unit ? info.unit : "", format_description(info)});
    }
    std::vector<size_t> widths = {18, 7, 9, 9, 9, 5};
    for (const std::vector<std::string>& row : rows) {
        for (size_t column = 0; column < widths.size(); ++column) {
            widths[column] = std::max(widths[column], row[column].size());
        }
    }
    for (const std::vector<std::string>& row : rows) {
        std::string line = " ";
        for (size_t column = 0; column < widths.size(); ++column) {
            line += " " + row[column] + std::string(widths[column] - row[column].size(), ' ');
        }
        std::printf("%s %s\n", line.c_str(), row.back().c_str());
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
