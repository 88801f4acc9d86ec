#include "method_spec_parser.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

namespace obscura::samples {
namespace {

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// The shortest decimal that reads back to the same float: "0.3", "1", "1e-08".
std::string shortest_float(float value) {
    char digits[32];
    const std::to_chars_result result = std::to_chars(digits, digits + sizeof digits, value);
    return std::string(digits, size_t(result.ptr - digits));
}

// "[1, 32]", "[0.001, 10000] m": a row's range for messages.
std::string range_text(const obscura_setting_info& info) {
    return "[" + format_number(info.min_value) + ", " + format_number(info.max_value) + "]" +
           (info.unit && *info.unit ? std::string(" ") + info.unit : std::string());
}

// Whether `text` is, as a whole, a finite decimal number (optional '-', digits, '.', exponent), and if so its value in
// `value`. std::from_chars, not strtod: no leading spaces, no '+', no hexadecimal floats ("0x10").
bool read_decimal(const std::string& text, double& value) {
    const char* const end = text.data() + text.size();
    const std::from_chars_result parsed = std::from_chars(text.data(), end, value);
    return !text.empty() && parsed.ec == std::errc() && parsed.ptr == end && std::isfinite(value);
}

// A finite number, the whole of `text`; MethodSpecError naming `what` otherwise.
double parse_number(const std::string& text, const std::string& what) {
    double value = 0.0;
    if (!read_decimal(text, value)) throw MethodSpecError(what + ": '" + text + "' is not a number");
    return value;
}

template <class T>
T* field_at(obscura_settings& settings, size_t offset) {
    return reinterpret_cast<T*>(reinterpret_cast<unsigned char*>(&settings) + offset);
}
template <class T>
const T* field_at(const obscura_settings& settings, size_t offset) {
    return reinterpret_cast<const T*>(reinterpret_cast<const unsigned char*>(&settings) + offset);
}

// The array's values as the SDK checks them with falloff = table: the row's count, each in its range.
void check_array(const obscura_setting_info& info, const std::vector<float>& values, const std::string& what) {
    if (values.size() != info.value_count) {
        throw MethodSpecError(what + ": " + std::to_string(values.size()) + " values, expected " +
                              std::to_string(info.value_count) + " (" + info.name + "=V0/V1/.../V" +
                              std::to_string(info.value_count - 1) + " or " + info.name + "=@FILE)");
    }
    for (size_t i = 0; i < values.size(); ++i) {
        // Compared as the float the field holds, so the documented edges themselves pass.
        if (!(values[i] >= float(info.min_value) && values[i] <= float(info.max_value))) {
            throw MethodSpecError(what + "[" + std::to_string(i) + "] = " + format_number(values[i]) + " is outside " +
                                  range_text(info));
        }
    }
}

obscura_method method_of(const obscura_settings& settings) {
    return settings.method == OBSCURA_METHOD_DEFAULT ? OBSCURA_METHOD_HBAO : settings.method;
}

// The settings of a spec: the method's editable defaults, then each assignment (already checked) in order.
using Applied = std::vector<std::pair<const obscura_setting_info*, SettingAssignment>>;
obscura_settings build_settings(obscura_method method, const Applied& applied) {
    obscura_settings settings;
    const obscura_status status = obscura_default_settings(method, &settings);
    if (status != OBSCURA_OK) {
        throw SettingsLibraryError(std::string("obscura_default_settings failed: ") + obscura_status_string(status));
    }
    for (const auto& [info, assignment] : applied) {
        apply_setting(settings, *info, assignment.value, std::string(obscura_method_name(method)) + " " + info->name);
    }
    return settings;
}

// Settings whose every value is in range and that the SDK still refuses: constraints between settings. The
// SDK says why (obscura_get_last_error(NULL) after a call without a context); the falloff table's case also
// gets the spec syntax that fixes it.
void check_resolves(const std::string& text, obscura_method method, const obscura_settings& settings) {
    obscura_settings resolved;
    const obscura_status status = obscura_resolve_settings(nullptr, &settings, &resolved);
    if (status == OBSCURA_OK) return;
    const std::string reason = obscura_get_last_error(nullptr);
    if (status != OBSCURA_STATUS_INVALID_SETTING) {
        throw SettingsLibraryError("obscura_resolve_settings(" + text + ") failed: " + obscura_status_string(status) +
                                   (reason.empty() ? "" : " (" + reason + ")"));
    }
    if (uses_falloff_table(settings)) {
        const obscura_setting_info* table = falloff_table_info(method);
        const float* values = array_values(settings, *table);
        bool any = false;
        for (uint32_t i = 0; i < table->value_count; ++i) any = any || values[i] != 0.0f;
        if (!any) {
            const std::string last = std::to_string(table->value_count - 1);
            throw MethodSpecError("method spec '" + text + "': falloff=table needs " + table->name +
                                  ", which is all zero: give it as " + table->name + "=V0/V1/.../V" + last + " (" +
                                  std::to_string(table->value_count) + " values in " + range_text(*table) +
                                  ", rho at d = i/" + last + " * radius, not all 0) or " + table->name + "=@FILE");
        }
    }
    throw MethodSpecError("method spec '" + text + "' is refused: " + reason);
}

}  // namespace

std::vector<obscura_method> all_methods() {
    std::vector<obscura_method> methods;
    for (int value = OBSCURA_METHOD_HBAO; value < OBSCURA_METHOD_COUNT_; ++value) {
        if (obscura_method_name(obscura_method(value))) methods.push_back(obscura_method(value));
    }
    return methods;
}

std::string method_names() {
    std::string names;
    for (obscura_method method : all_methods()) {
        names += (names.empty() ? "" : ", ") + std::string(obscura_method_name(method));
    }
    return names;
}

obscura_method find_method(std::string_view name) {
    for (obscura_method method : all_methods()) {
        if (name == obscura_method_name(method)) return method;
    }
    throw MethodSpecError("unknown method '" + std::string(name) + "' (valid: " + method_names() + ")");
}

std::vector<obscura_setting_info> setting_infos(obscura_method method) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    const obscura_status status = obscura_get_setting_infos(method, &infos, &count);
    if (status != OBSCURA_OK) {
        throw SettingsLibraryError(std::string("obscura_get_setting_infos failed: ") + obscura_status_string(status));
    }
    std::vector<obscura_setting_info> rows(infos, infos + count);
    // The rows every method shares (temporal accumulation, resolution) follow the method's own.
    const obscura_setting_info* shared = nullptr;
    uint32_t shared_count = 0;
    if (obscura_get_shared_setting_infos(&shared, &shared_count) != OBSCURA_OK) {
        throw SettingsLibraryError("obscura_get_shared_setting_infos failed");
    }
    rows.insert(rows.end(), shared, shared + shared_count);
    return rows;
}

const obscura_setting_info* find_setting(const std::vector<obscura_setting_info>& infos, std::string_view name) {
    for (const obscura_setting_info& info : infos) {
        if (name == info.name) return &info;
    }
    return nullptr;
}

bool is_derived(const obscura_setting_info& info) { return (info.flags & OBSCURA_SETTING_FLAG_DERIVED) != 0; }

bool is_array(const obscura_setting_info& info) { return info.type == OBSCURA_SETTING_FLOAT_ARRAY; }

std::string c_field_path(obscura_method method, const obscura_setting_info& info) {
    if (std::strchr(info.name, '.') != nullptr) return info.name;  // a shared row names its block
    // The blocks of fields added to a released method after its own block's layout (obscura.h).
    struct AddedBlock {
        size_t offset, size;
        const char* member;
    };
    constexpr AddedBlock kAddedBlocks[] = {
        {offsetof(obscura_settings, ffao_added), sizeof(obscura_ffao_added_settings), "ffao_added"},
    };
    for (const AddedBlock& block : kAddedBlocks) {
        if (info.offset >= block.offset && info.offset < block.offset + block.size) {
            return std::string(block.member) + "." + info.name;
        }
    }
    return std::string(obscura_method_name(method)) + "." + info.name;
}

std::string value_name(const obscura_setting_info& info, double value) {
    if ((info.type != OBSCURA_SETTING_ENUM && info.type != OBSCURA_SETTING_TOGGLE) || !info.value_names) return "";
    const double index = value - info.min_value;
    if (!(index >= 0.0 && index < double(info.value_count)) || index != std::floor(index)) return "";
    const char* name = info.value_names[size_t(index)];
    return name ? name : "";
}

std::string value_name_list(const obscura_setting_info& info) {
    std::string names;
    if ((info.type != OBSCURA_SETTING_ENUM && info.type != OBSCURA_SETTING_TOGGLE) || !info.value_names) return names;
    for (uint32_t i = 0; i < info.value_count; ++i) {
        if (info.value_names[i]) names += (names.empty() ? "" : ", ") + std::string(info.value_names[i]);
    }
    return names;
}

double stored_value(const obscura_settings& settings, const obscura_setting_info& info) {
    switch (info.type) {
        case OBSCURA_SETTING_FLOAT: return *field_at<float>(settings, info.offset);
        case OBSCURA_SETTING_INT:
        case OBSCURA_SETTING_ENUM:
        case OBSCURA_SETTING_TOGGLE: return *field_at<int32_t>(settings, info.offset);
        case OBSCURA_SETTING_FLOAT_ARRAY: return 0.0;
    }
    return 0.0;
}

bool derives(const obscura_settings& settings, const obscura_setting_info& info) {
    return is_derived(info) && stored_value(settings, info) == 0.0;
}

const float* array_values(const obscura_settings& settings, const obscura_setting_info& info) {
    if (!is_array(info) || info.offset + size_t(info.value_count) * sizeof(float) > sizeof(obscura_settings)) {
        throw SettingsLibraryError(std::string("setting '") + info.name + "' is not an array of obscura_settings");
    }
    return field_at<float>(settings, info.offset);
}

float* array_values(obscura_settings& settings, const obscura_setting_info& info) {
    return const_cast<float*>(array_values(static_cast<const obscura_settings&>(settings), info));
}

const obscura_setting_info* falloff_table_info(obscura_method method) {
    // The metadata's rows are static: the pointer stays valid after the vector is gone.
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    if (obscura_get_setting_infos(method, &infos, &count) != OBSCURA_OK) return nullptr;
    for (uint32_t i = 0; i < count; ++i) {
        if (is_array(infos[i]) && std::strcmp(infos[i].name, "falloff_table") == 0) return &infos[i];
    }
    return nullptr;
}

bool uses_falloff_table(const obscura_settings& settings) {
    const obscura_method method = method_of(settings);
    if (!falloff_table_info(method)) return false;
    const std::vector<obscura_setting_info> infos = setting_infos(method);
    const obscura_setting_info* falloff = find_setting(infos, "falloff");
    double value = 0.0;
    if (!falloff || obscura_get_setting(&settings, falloff->name, &value) != OBSCURA_OK) return false;
    return value_name(*falloff, value) == "table";
}

double parse_setting_value(const obscura_setting_info& info, const std::string& text, const std::string& what) {
    if (info.type == OBSCURA_SETTING_TOGGLE) {
        for (const char* on : {"on", "true", "yes", "1"}) {
            if (text == on) return 1.0;
        }
        for (const char* off : {"off", "false", "no", "0"}) {
            if (text == off) return 0.0;
        }
        throw MethodSpecError(what + ": '" + text + "' is not on or off");
    }
    if (info.type == OBSCURA_SETTING_ENUM) {
        for (uint32_t i = 0; info.value_names && i < info.value_count; ++i) {
            if (info.value_names[i] && text == info.value_names[i]) return info.min_value + i;
        }
        double value = 0.0;
        if (!read_decimal(text, value)) {
            throw MethodSpecError(what + ": '" + text + "' is not one of its values (valid: " + value_name_list(info) +
                                  ", or their numbers " + format_number(info.min_value) + " to " +
                                  format_number(info.max_value) + ")");
        }
        return value;
    }
    if (is_array(info)) {
        throw MethodSpecError(what + " is an array of " + std::to_string(info.value_count) +
                              " values: V0/V1/... or @FILE");
    }
    return parse_number(text, what);
}

std::vector<float> parse_array_value(const obscura_setting_info& info, const std::string& text,
                                     const std::string& what) {
    if (!text.empty() && text[0] == '@') return read_array_file(info, text.substr(1), what);
    std::vector<float> values;
    for (size_t start = 0;;) {
        const size_t end = text.find('/', start);
        const std::string item = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
        values.push_back(float(parse_number(item, what + " value " + std::to_string(values.size()))));
        if (end == std::string::npos) break;
        start = end + 1;
    }
    check_array(info, values, what);
    return values;
}

std::vector<float> read_array_file(const obscura_setting_info& info, const std::string& path, const std::string& what) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw MethodSpecError(what + ": cannot open '" + path + "': " + std::strerror(errno));
    // A table is a few hundred bytes: read at most 64 KiB, so that @/dev/zero or a wrong path to a large file cannot
    // take the memory (and a longer file is refused, not cut).
    constexpr size_t kMaxBytes = 64 * 1024;
    std::string contents(kMaxBytes + 1, '\0');
    file.read(&contents[0], std::streamsize(contents.size()));
    if (file.bad()) throw MethodSpecError(what + ": cannot read '" + path + "'");
    contents.resize(size_t(file.gcount()));
    if (contents.size() > kMaxBytes) {
        throw MethodSpecError(what + ": '" + path + "' is longer than 64 KiB; a falloff table holds 16 numbers");
    }
    std::vector<float> values;
    const char* const separators = " \t\r\n,";
    for (size_t start = contents.find_first_not_of(separators); start != std::string::npos;) {
        const size_t end = contents.find_first_of(separators, start);
        const std::string item = contents.substr(start, end == std::string::npos ? std::string::npos : end - start);
        values.push_back(float(parse_number(item, what + " ('" + path + "')")));
        start = end == std::string::npos ? end : contents.find_first_not_of(separators, end);
    }
    check_array(info, values, what + " ('" + path + "')");
    return values;
}

void apply_setting(obscura_settings& settings, const obscura_setting_info& info, const std::string& text,
                   const std::string& what) {
    if (is_array(info)) {
        const std::vector<float> values = parse_array_value(info, text, what);
        std::memcpy(array_values(settings, info), values.data(), values.size() * sizeof(float));
        return;
    }
    const double value = parse_setting_value(info, text, what);
    const obscura_status status = obscura_set_setting(&settings, info.name, value);
    if (status == OBSCURA_STATUS_INVALID_SETTING) {
        const bool whole = info.type == OBSCURA_SETTING_FLOAT || value == std::floor(value);
        std::string message =
            what + "=" + text + (whole ? " is outside " : " must be a whole number in ") + range_text(info);
        if (info.type == OBSCURA_SETTING_ENUM) message += " (" + value_name_list(info) + ")";
        if (is_derived(info)) message += " (or 0 to derive it)";
        throw MethodSpecError(message);
    }
    if (status != OBSCURA_OK) {
        throw SettingsLibraryError(std::string("obscura_set_setting(") + info.name + ") failed: " +
                                   obscura_status_string(status));
    }
}

std::string format_setting_value(const obscura_setting_info& info, double value) {
    if (info.type == OBSCURA_SETTING_TOGGLE) return value != 0.0 ? "on" : "off";
    if (info.type == OBSCURA_SETTING_ENUM) {
        const std::string name = value_name(info, value);
        if (!name.empty()) return name;
    }
    char text[32];
    std::snprintf(text, sizeof text, info.type == OBSCURA_SETTING_FLOAT ? "%g" : "%.0f", value);
    return info.unit && *info.unit ? std::string(text) + " " + info.unit : std::string(text);
}

std::string format_array_value(const float* values, uint32_t count) {
    std::string text;
    for (uint32_t i = 0; i < count; ++i) text += (i == 0 ? "" : "/") + shortest_float(values[i]);
    return text;
}

SettingAssignment parse_assignment(const std::string& text, const std::string& where) {
    const size_t equals = text.find('=');
    if (text.empty()) throw MethodSpecError("empty setting in " + where + " (expected KEY=VALUE)");
    if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
        throw MethodSpecError("'" + text + "' in " + where + " is not KEY=VALUE");
    }
    return SettingAssignment{text.substr(0, equals), text.substr(equals + 1), text};
}

obscura_settings parse_method_spec(const std::string& text, const std::vector<std::string>& set_options) {
    const size_t colon = text.find(':');
    const std::string name = text.substr(0, colon);
    if (name.empty()) throw MethodSpecError("method spec '" + text + "' has no method name");
    const obscura_method method = find_method(name);
    if (!obscura_method_available(method)) {
        throw SettingsLibraryError("method '" + name + "' is not available in this build of libobscura " +
                                   "(obscura_method_available returned 0; see --list-methods)");
    }
    const std::vector<obscura_setting_info> infos = setting_infos(method);
    std::string keys;
    for (const obscura_setting_info& info : infos) keys += (keys.empty() ? "" : ", ") + std::string(info.name);

    // The spec's keys are checked first (so that a typo is reported as such), applied last (so that they win).
    Applied own;
    for (size_t start = colon; start != std::string::npos;) {
        const size_t end = text.find(':', start + 1);
        const std::string item = text.substr(start + 1, end == std::string::npos ? std::string::npos : end - start - 1);
        const SettingAssignment assignment = parse_assignment(item, "method spec '" + text + "'");
        const obscura_setting_info* info = find_setting(infos, assignment.key);
        if (!info) {
            throw MethodSpecError("unknown setting '" + assignment.key + "' in '" + text + "' (" + name +
                                  " has: " + (keys.empty() ? "none" : keys) + ")");
        }
        own.emplace_back(info, assignment);
        start = end;
    }
    Applied applied;
    for (const std::string& option : set_options) {
        const SettingAssignment assignment = parse_assignment(option, "--set");
        if (const obscura_setting_info* info = find_setting(infos, assignment.key)) {
            applied.emplace_back(info, assignment);
        }
    }
    applied.insert(applied.end(), own.begin(), own.end());
    const obscura_settings settings = build_settings(method, applied);
    check_resolves(text, method, settings);
    return settings;
}

}  // namespace obscura::samples
