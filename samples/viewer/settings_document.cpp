#include "settings_document.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

#include "json_reader.h"
#include "json_writer.h"
#include "method_spec_parser.h"

namespace obscura::viewer {
namespace {

using samples::JsonValue;

// The method's metadata rows, then the rows every method shares (temporal accumulation, resolution):
// samples::setting_infos.
struct SettingTable {
    std::vector<obscura_setting_info> rows;

    const obscura_setting_info* begin() const { return rows.data(); }
    const obscura_setting_info* end() const { return rows.data() + rows.size(); }
    const obscura_setting_info* find(std::string_view name) const {
        for (const obscura_setting_info& info : *this) {
            if (name == info.name) return &info;
        }
        return nullptr;
    }
};

SettingTable setting_table(obscura_method method) {
    try {
        return SettingTable{samples::setting_infos(method)};
    } catch (const std::exception& e) {
        throw SettingsDocumentError(e.what());
    }
}

// settings.method as the SDK reads it (DEFAULT is HBAO). The field is read as the int a C host may have
// stored, so a value outside the enumerators is reported, not loaded through the enum type.
obscura_method method_of(const obscura_settings& settings) {
    static_assert(sizeof(obscura_method) == sizeof(int32_t), "the API's C enums are int-sized");
    int32_t value;
    std::memcpy(&value, &settings.method, sizeof value);
    if (value == OBSCURA_METHOD_DEFAULT) return OBSCURA_METHOD_HBAO;
    if (value < 0 || value >= int32_t(OBSCURA_METHOD_COUNT_) || !obscura_method_name(obscura_method(value))) {
        throw SettingsDocumentError("settings.method = " + std::to_string(value) + " is not an obscura_method");
    }
    return obscura_method(value);
}

double effective_value(const obscura_settings& settings, const char* name) {
    double value = 0.0;
    const obscura_status status = obscura_get_setting(&settings, name, &value);
    if (status != OBSCURA_OK) {
        throw SettingsDocumentError(std::string("obscura_get_setting(\"") + name +
                                    "\") failed: " + obscura_status_string(status));
    }
    return value;
}

// A float setting's value, finite (NaN and infinities cannot be written as JSON or C).
float finite_float(obscura_method method, const obscura_setting_info& info, double value) {
    const float f = float(value);
    if (!std::isfinite(f)) {
        throw SettingsDocumentError(std::string(obscura_method_name(method)) + "." + info.name +
                                    " is not a finite number");
    }
    return f;
}

// The shortest decimal form that reads back to the same float, e.g. "0.3" for 0.3f, "1" for 1.0f.
std::string shortest_float(float value) {
    char digits[32];
    const std::to_chars_result result = std::to_chars(digits, digits + sizeof digits, value);
    return std::string(digits, size_t(result.ptr - digits));
}

// The shortest double form of a number (messages): "0.001", "10000", "1e+08".
std::string shortest_double(double value) {
    char digits[32];
    const std::to_chars_result result = std::to_chars(digits, digits + sizeof digits, value);
    return std::string(digits, size_t(result.ptr - digits));
}

// The double whose JSON form (JsonWriter: shortest double) is the float's shortest form: 0.3f is written
// "0.3", not "0.30000001192092896", and still loads as exactly 0.3f. Falls back to the float's exact value
// should the decimal not round back to it through double.
double float_as_json_number(float value) {
    const std::string text = shortest_float(value);
    double parsed = 0.0;
    const std::from_chars_result result = std::from_chars(text.data(), text.data() + text.size(), parsed);
    if (result.ec != std::errc() || float(parsed) != value) return double(value);
    return parsed;
}

// A C float literal that reads back to `value`: "1.5f", "1.0f", "1e-08f", "-0.85f".
std::string c_float_literal(float value) {
    std::string text = shortest_float(value);
    if (text.find_first_of(".e") == std::string::npos) text += ".0";
    return text + "f";
}

// How a JSON value reads in a message: `the string "big"`, `the number 2.5`, `an array` ...
std::string describe(const JsonValue& value) {
    switch (value.type()) {
        case JsonValue::Type::string: return "the string " + samples::JsonWriter::quote(value.as_string());
        case JsonValue::Type::number: return "the number " + shortest_double(value.as_number());
        case JsonValue::Type::boolean: return value.as_bool() ? "true" : "false";
        default: return JsonValue::type_name(value.type());
    }
}

std::string quoted(std::string_view text) { return samples::JsonWriter::quote(text); }

std::string key_names(const SettingTable& table) {
    std::string names;
    for (const obscura_setting_info& info : table) {
        if (!names.empty()) names += ", ";
        names += info.name;
    }
    return names;
}

std::string range_text(const obscura_setting_info& info) {
    std::string range = "[" + shortest_double(info.min_value) + ", " + shortest_double(info.max_value) + "]";
    if (info.unit && info.unit[0]) range += std::string(" ") + info.unit;
    return range;
}

// The value of one entry of "settings", as obscura_set_setting takes it (toggles: 0 off, 1 on; enums their
// number, from a name or a number), in a document of `version`. Arrays: array_value.
double setting_value(obscura_method method, const obscura_setting_info& info, const JsonValue& value, int version) {
    const std::string what = std::string("setting ") + quoted(info.name) + " of " + obscura_method_name(method);
    if (info.type == OBSCURA_SETTING_TOGGLE) {
        if (value.is_bool()) return value.as_bool() ? 1.0 : 0.0;
        if (value.is_string() && value.as_string() == "on") return 1.0;
        if (value.is_string() && value.as_string() == "off") return 0.0;
        throw SettingsDocumentError(what + " is a toggle: expected \"on\", \"off\", true or false, not " +
                                    describe(value));
    }
    if (info.type == OBSCURA_SETTING_ENUM && value.is_string()) {
        for (uint32_t i = 0; info.value_names && i < info.value_count; ++i) {
            if (value.as_string() == info.value_names[i]) return info.min_value + i;
        }
        throw SettingsDocumentError(what + " = " + describe(value) + " is not one of its values: " +
                                    samples::value_name_list(info));
    }
    if (!value.is_number()) {
        const char* const expected =
            info.type == OBSCURA_SETTING_ENUM ? " must be a value name or a number, not " : " must be a number, not ";
        throw SettingsDocumentError(what + expected + describe(value));
    }
    const double number = value.as_number();
    if (info.type != OBSCURA_SETTING_FLOAT && number != std::floor(number)) {
        throw SettingsDocumentError(what + " must be a whole number, not " + shortest_double(number));
    }
    // 0 in a derived field means "derive" (what version 2 writes for it). Where the range excludes 0 (radius,
    // intensity, samples, falloff) the SDK would read it as the default, which is not what a document saying 0 means:
    // it is out of range. Version 1 documents were read with 0 as the default there, and still are.
    const bool zero_derives = number == 0.0 && samples::is_derived(info);
    const bool version1_default = number == 0.0 && version < 2 && info.min_value > 0.0;
    if (!zero_derives && !version1_default && (number < info.min_value || number > info.max_value)) {
        std::string range = range_text(info);
        if (info.type == OBSCURA_SETTING_ENUM) range += " (" + samples::value_name_list(info) + ")";
        const char* const default_hint = number == 0.0 ? " (leave the key out for its default)" : "";
        throw SettingsDocumentError(what + " = " + shortest_double(number) + " is outside its range " + range +
                                    default_hint);
    }
    return number;
}

// An array setting's entry: value_count numbers, each in the row's range.
std::vector<float> array_value(obscura_method method, const obscura_setting_info& info, const JsonValue& value) {
    const std::string what = std::string("setting ") + quoted(info.name) + " of " + obscura_method_name(method);
    if (!value.is_array()) {
        throw SettingsDocumentError(what + " must be an array of " + std::to_string(info.value_count) +
                                    " numbers, not " + describe(value));
    }
    if (value.items().size() != info.value_count) {
        throw SettingsDocumentError(what + " has " + std::to_string(value.items().size()) + " values, expected " +
                                    std::to_string(info.value_count));
    }
    std::vector<float> values;
    for (const JsonValue& item : value.items()) {
        const std::string element = what + "[" + std::to_string(values.size()) + "]";
        if (!item.is_number()) throw SettingsDocumentError(element + " must be a number, not " + describe(item));
        const float number = float(item.as_number());
        if (!(number >= float(info.min_value) && number <= float(info.max_value))) {
            throw SettingsDocumentError(element + " = " + shortest_double(item.as_number()) + " is outside its range " +
                                        range_text(info));
        }
        values.push_back(number);
    }
    return values;
}

// Version 1 documents wrote every effective value, derived ones too (decay_rate 0.3 for the default radius).
// Loaded as given, they would pin those values: moving the radius would then leave the falloff's end where it
// was. A derived value that is what the document's other settings derive is loaded as "derive"; one that
// differs was set by its author and stays.
void derive_where_derived(obscura_settings& settings) {
    for (const obscura_setting_info& info : setting_table(method_of(settings))) {
        if (!samples::is_derived(info) || samples::derives(settings, info)) continue;
        obscura_settings derived = settings;
        if (obscura_set_setting(&derived, info.name, 0.0) != OBSCURA_OK) continue;
        if (effective_value(derived, info.name) == effective_value(settings, info.name)) settings = derived;
    }
}

// Every value is in its range, but settings the SDK refuses as a whole (the table falloff with an all-zero table,
// FFAO's SAAO with K = 16) would load and then fail every render: they are refused here, with the SDK's reason, as
// the method-spec parser refuses the same settings given on the command line.
void check_resolves(const obscura_settings& settings) {
    obscura_settings resolved = settings;
    const obscura_status status = obscura_resolve_settings(nullptr, &settings, &resolved);
    if (status == OBSCURA_OK) return;
    const std::string reason = obscura_get_last_error(nullptr);
    throw SettingsDocumentError(std::string("the settings of ") + obscura_method_name(method_of(settings)) +
                                " are refused: " + (reason.empty() ? obscura_status_string(status) : reason));
}

}  // namespace

double effective_setting_value(obscura_context* context, const obscura_settings& settings,
                               const obscura_setting_info& info) {
    obscura_settings resolved = settings;
    // Resolved, a derived field holds what the SDK derives, a renderer-dependent one (LSAO's segment_steps) too when
    // a context is given; unresolved settings have no derived values, and read as they are stored.
    const obscura_settings& source =
        obscura_resolve_settings(context, &settings, &resolved) == OBSCURA_OK ? resolved : settings;
    return effective_value(source, info.name);
}

bool set_derive(obscura_context* context, obscura_settings& settings, const obscura_setting_info& info, bool derive) {
    if (!samples::is_derived(info)) return false;
    // Ticked: 0, "derive". Unticked: the value the renders use now, so that the picture does not change and the
    // field is set (0 there would be "derive" again).
    const double value = derive ? 0.0 : effective_setting_value(context, settings, info);
    if (!derive && value == 0.0) return false;
    return obscura_set_setting(&settings, info.name, value) == OBSCURA_OK;
}

bool method_from_name(std::string_view name, obscura_method* method) {
    for (int m = OBSCURA_METHOD_DEFAULT + 1; m < int(OBSCURA_METHOD_COUNT_); ++m) {
        const char* candidate = obscura_method_name(obscura_method(m));
        if (candidate && name == candidate) {
            if (method) *method = obscura_method(m);
            return true;
        }
    }
    return false;
}

std::string method_names() {
    std::string names;
    for (int m = OBSCURA_METHOD_DEFAULT + 1; m < int(OBSCURA_METHOD_COUNT_); ++m) {
        const char* name = obscura_method_name(obscura_method(m));
        if (!name) continue;
        if (!names.empty()) names += ", ";
        names += name;
    }
    return names;
}

std::string settings_to_json(const obscura_settings& settings) {
    const obscura_method method = method_of(settings);
    const SettingTable table = setting_table(method);
    samples::JsonWriter json;
    json.begin_object()
        .field("format", kSettingsFormat)
        .field("version", kSettingsVersion)
        .field("method", obscura_method_name(method));
    json.key("settings").begin_object();
    for (const obscura_setting_info& info : table) {
        if (samples::is_array(info)) {
            json.key(info.name).begin_array();
            const float* values = samples::array_values(settings, info);
            for (uint32_t i = 0; i < info.value_count; ++i) {
                json.value(float_as_json_number(finite_float(method, info, values[i])));
            }
            json.end_array();
            continue;
        }
        // A derived field left to the SDK is written as 0, "derive": the loaded document derives it again.
        const double value = samples::derives(settings, info) ? 0.0 : effective_value(settings, info.name);
        switch (info.type) {
            case OBSCURA_SETTING_FLOAT:
                json.field(info.name, float_as_json_number(finite_float(method, info, value)));
                break;
            case OBSCURA_SETTING_INT: json.field(info.name, static_cast<long long>(std::llround(value))); break;
            case OBSCURA_SETTING_TOGGLE: json.field(info.name, value != 0.0 ? "on" : "off"); break;
            case OBSCURA_SETTING_ENUM: {
                const std::string name = samples::value_name(info, value);
                if (name.empty()) {
                    json.field(info.name, static_cast<long long>(std::llround(value)));
                } else {
                    json.field(info.name, name);
                }
                break;
            }
            case OBSCURA_SETTING_FLOAT_ARRAY: break;
        }
    }
    json.end_object().end_object();
    return json.str() + "\n";
}

obscura_settings settings_from_json(std::string_view text) {
    JsonValue document;
    try {
        document = samples::parse_json(text);
    } catch (const samples::JsonParseError& error) {
        throw SettingsDocumentError(std::string("malformed settings document: ") + error.what());
    }
    if (!document.is_object()) {
        throw SettingsDocumentError(std::string("a settings document is a JSON object, not ") + describe(document));
    }
    for (const JsonValue::Member& member : document.members()) {
        const std::string& key = member.first;
        if (key != "format" && key != "version" && key != "method" && key != "settings") {
            throw SettingsDocumentError("unknown key " + quoted(key) +
                                        " in the settings document; expected format, version, method, settings");
        }
    }

    if (const JsonValue* format = document.find("format")) {
        if (!format->is_string() || format->as_string() != kSettingsFormat) {
            throw SettingsDocumentError(std::string("\"format\" is ") + describe(*format) + "; expected \"" +
                                        kSettingsFormat + "\"");
        }
    }
    int version_number = kSettingsVersion;
    if (const JsonValue* version = document.find("version")) {
        if (!version->is_number() || version->as_number() < 1.0 ||
            version->as_number() != std::floor(version->as_number())) {
            throw SettingsDocumentError("\"version\" must be a positive whole number, not " + describe(*version));
        }
        if (version->as_number() > kSettingsVersion) {
            throw SettingsDocumentError("\"version\" " + shortest_double(version->as_number()) +
                                        " is newer than this viewer reads (" + std::to_string(kSettingsVersion) +
                                        ")");
        }
        version_number = int(version->as_number());
    }

    const JsonValue* method_value = document.find("method");
    if (!method_value) {
        throw SettingsDocumentError("the settings document has no \"method\"; expected one of: " + method_names());
    }
    obscura_method method = OBSCURA_METHOD_DEFAULT;
    if (!method_value->is_string()) {
        throw SettingsDocumentError("\"method\" must be a method name, not " + describe(*method_value) +
                                    "; expected one of: " + method_names());
    }
    if (!method_from_name(method_value->as_string(), &method)) {
        throw SettingsDocumentError("unknown method " + quoted(method_value->as_string()) +
                                    "; expected one of: " + method_names());
    }

    obscura_settings settings;
    const obscura_status status = obscura_default_settings(method, &settings);
    if (status != OBSCURA_OK) {
        throw SettingsDocumentError(std::string("obscura_default_settings failed: ") + obscura_status_string(status));
    }
    const JsonValue* values = document.find("settings");
    if (!values) return settings;  // every setting keeps its default (and the defaults resolve)
    if (!values->is_object()) {
        throw SettingsDocumentError("\"settings\" must be an object of setting names and values, not " +
                                    describe(*values));
    }
    const SettingTable table = setting_table(method);
    for (const JsonValue::Member& member : values->members()) {
        const obscura_setting_info* info = table.find(member.first);
        if (!info) {
            throw SettingsDocumentError("unknown setting " + quoted(member.first) + " for " +
                                        obscura_method_name(method) + "; its settings are: " + key_names(table));
        }
        if (samples::is_array(*info)) {
            const std::vector<float> elements = array_value(method, *info, member.second);
            std::copy(elements.begin(), elements.end(), samples::array_values(settings, *info));
            continue;
        }
        const double value = setting_value(method, *info, member.second, version_number);
        const obscura_status set_status = obscura_set_setting(&settings, info->name, value);
        if (set_status != OBSCURA_OK) {
            throw SettingsDocumentError(std::string("setting ") + quoted(info->name) + " of " +
                                        obscura_method_name(method) + " = " + shortest_double(value) +
                                        " was rejected: " + obscura_status_string(set_status));
        }
    }
    if (version_number < 2) derive_where_derived(settings);
    check_resolves(settings);
    return settings;
}

std::string settings_to_c(const obscura_settings& settings) {
    const obscura_method method = method_of(settings);
    const std::string name = obscura_method_name(method);
    // The enum constant and the member of obscura_settings are both named after the method:
    // OBSCURA_METHOD_HBAO / settings.hbao ... OBSCURA_METHOD_REFERENCE / settings.reference.
    std::string constant = "OBSCURA_METHOD_";
    for (const char c : name) constant += (c >= 'a' && c <= 'z') ? char(c - 'a' + 'A') : c;

    obscura_settings defaults;
    const obscura_status status = obscura_default_settings(method, &defaults);
    if (status != OBSCURA_OK) {
        throw SettingsDocumentError(std::string("obscura_default_settings failed: ") + obscura_status_string(status));
    }

    std::string code = "obscura_settings settings;\nobscura_default_settings(" + constant + ", &settings);\n";
    // Every metadata key is the name of its C field (each method's file declares each entry with the field its
    // offset is taken from, under the same name; settings_document_test checks all of them against offsetof), so
    // the assignment is settings.<method>.<key>, settings.<key> for a shared row ("temporal.enabled"), or the added
    // block's for a field added later (samples::c_field_path).
    for (const obscura_setting_info& info : setting_table(method)) {
        const std::string field = "settings." + samples::c_field_path(method, info);
        if (samples::is_array(info)) {
            // Every element, where any differs: the table reads as one.
            const float* values = samples::array_values(settings, info);
            const float* default_values = samples::array_values(defaults, info);
            if (std::equal(values, values + info.value_count, default_values)) continue;
            for (uint32_t i = 0; i < info.value_count; ++i) {
                const std::string literal = c_float_literal(finite_float(method, info, values[i]));
                code += field + "[" + std::to_string(i) + "] = " + literal + ";\n";
            }
            continue;
        }
        // A derived field is written only where it is set: obscura_default_settings leaves it 0, "derive".
        if (samples::derives(settings, info)) continue;
        const double value = effective_value(settings, info.name);
        if (!samples::is_derived(info) && value == effective_value(defaults, info.name)) continue;
        std::string literal, comment;
        switch (info.type) {
            case OBSCURA_SETTING_FLOAT: literal = c_float_literal(finite_float(method, info, value)); break;
            case OBSCURA_SETTING_INT: literal = std::to_string(std::llround(value)); break;
            case OBSCURA_SETTING_TOGGLE: literal = value != 0.0 ? "OBSCURA_TOGGLE_ON" : "OBSCURA_TOGGLE_OFF"; break;
            case OBSCURA_SETTING_ENUM: {
                // By number: the SDK's enumerated fields are plain int32_t (only the falloff has C constants), except
                // resolution.scale, a C enum (obscura_resolution), which C++ does not assign from an int: its constant.
                const std::string value_name = samples::value_name(info, value);
                if (std::strcmp(info.name, "resolution.scale") == 0 && !value_name.empty()) {
                    literal = "OBSCURA_RESOLUTION_";
                    for (char ch : value_name) literal += char(std::toupper(static_cast<unsigned char>(ch)));
                } else {
                    literal = std::to_string(std::llround(value));
                }
                if (!value_name.empty()) comment = " /* " + value_name + " */";
                break;
            }
            case OBSCURA_SETTING_FLOAT_ARRAY: break;
        }
        code += field + " = " + literal + ";" + comment + "\n";
    }
    return code;
}

bool write_text_file(const std::string& path, std::string_view text, std::string* error) {
    // Written beside the target and renamed over it, so a failed save leaves the old file whole.
    const std::string temporary = path + ".tmp";
    {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        if (!file) {
            if (error) *error = "cannot open '" + temporary + "' for writing: " + std::strerror(errno);
            return false;
        }
        file.write(text.data(), std::streamsize(text.size()));
        file.flush();
        if (!file) {
            if (error) *error = "cannot write '" + temporary + "': " + std::strerror(errno);
            file.close();
            std::remove(temporary.c_str());
            return false;
        }
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        if (error) *error = "cannot replace '" + path + "': " + std::strerror(errno);
        std::remove(temporary.c_str());
        return false;
    }
    return true;
}

bool read_text_file(const std::string& path, std::string* text, std::string* error) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        if (error) *error = "cannot open '" + path + "': " + std::strerror(errno);
        return false;
    }
    std::string contents((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (file.bad()) {
        if (error) *error = "cannot read '" + path + "'";
        return false;
    }
    if (text) *text = std::move(contents);
    return true;
}

}  // namespace obscura::viewer
