// The viewer's settings documents (samples/viewer/settings_document.h): JSON save/load round trips for
// every method of the metadata (enums by name, derived settings left to the SDK, the falloff tables), the load
// errors, documents of version 1, and copy-as-C. No GL.
#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "json_reader.h"
#include "method_spec_parser.h"
#include "obscura/obscura.h"
#include "settings_document.h"

namespace {

using obscura::viewer::SettingsDocumentError;
using obscura::viewer::settings_from_json;
using obscura::viewer::settings_to_c;
using obscura::viewer::settings_to_json;

std::vector<obscura_method> all_methods() {
    std::vector<obscura_method> methods;
    for (int m = OBSCURA_METHOD_DEFAULT + 1; m < int(OBSCURA_METHOD_COUNT_); ++m) {
        if (obscura_method_name(obscura_method(m))) methods.push_back(obscura_method(m));
    }
    return methods;
}

std::vector<obscura_setting_info> infos_of(obscura_method method) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    EXPECT_EQ(obscura_get_setting_infos(method, &infos, &count), OBSCURA_OK);
    std::vector<obscura_setting_info> rows(infos, infos + count);
    // Then the rows every method shares (temporal accumulation), which the document holds too.
    EXPECT_EQ(obscura_get_shared_setting_infos(&infos, &count), OBSCURA_OK);
    rows.insert(rows.end(), infos, infos + count);
    return rows;
}

obscura_settings defaults_of(obscura_method method) {
    obscura_settings settings;
    EXPECT_EQ(obscura_default_settings(method, &settings), OBSCURA_OK);
    return settings;
}

double get(const obscura_settings& settings, const char* name) {
    double value = -12345.0;
    EXPECT_EQ(obscura_get_setting(&settings, name, &value), OBSCURA_OK) << name;
    return value;
}

// An array setting's values (the falloff tables), read through its offset.
std::vector<float> table_of(const obscura_settings& settings, const obscura_setting_info& info) {
    const float* values = obscura::samples::array_values(settings, info);
    return std::vector<float>(values, values + info.value_count);
}

// An in-range value other than the default: ints and enums take min or max (whichever differs), floats the
// middle between the default and the max (or the min when the default is the max), toggles flip.
double non_default_value(const obscura_setting_info& info, double default_value) {
    switch (info.type) {
        case OBSCURA_SETTING_INT:
        case OBSCURA_SETTING_ENUM: return default_value != info.min_value ? info.min_value : info.max_value;
        case OBSCURA_SETTING_TOGGLE: return default_value != 0.0 ? 0.0 : 1.0;
        case OBSCURA_SETTING_FLOAT:
        default:
            return default_value < info.max_value ? default_value + (info.max_value - default_value) * 0.5
                                                  : info.min_value + (default_value - info.min_value) * 0.5;
    }
}

// A falloff table that is no falloff's: 1, 15/16 ... 1/16 (every value in [0, 1], not all 0).
void fill_table(obscura_settings& settings, const obscura_setting_info& info) {
    float* values = obscura::samples::array_values(settings, info);
    for (uint32_t i = 0; i < info.value_count; ++i) values[i] = 1.0f - float(i) / float(info.value_count);
}

// Every setting of `method` moved off its default (derived ones set to a value; arrays filled).
obscura_settings changed_settings(obscura_method method) {
    obscura_settings settings = defaults_of(method);
    for (const obscura_setting_info& info : infos_of(method)) {
        if (obscura::samples::is_array(info)) {
            fill_table(settings, info);
            continue;
        }
        const double default_value = get(settings, info.name);
        const double value = non_default_value(info, default_value);
        EXPECT_EQ(obscura_set_setting(&settings, info.name, value), OBSCURA_OK) << info.name << " = " << value;
        EXPECT_NE(get(settings, info.name), default_value) << info.name;
    }
    return settings;
}

// The settings a document can hold (settings_from_json refuses settings that do not resolve): changed_settings, less
// the keys it returns to their defaults, `kept`. Moved one by one, FFAO's settings conflict: SAAO (on) needs K a
// multiple of 18 and no frame split, and K moved to 4 leaves a split of 4 no orientation to evaluate (K/2 = 2). So
// SAAO stays off and K is 8 (still not its default, 16).
obscura_settings resolving_changed_settings(obscura_method method, std::vector<std::string>* kept) {
    obscura_settings settings = changed_settings(method);
    if (method == OBSCURA_METHOD_FFAO) {
        EXPECT_EQ(obscura_set_setting(&settings, "saao", 0.0), OBSCURA_OK);
        EXPECT_EQ(obscura_set_setting(&settings, "sectors", 8.0), OBSCURA_OK);
        kept->push_back("saao");
    }
    obscura_settings resolved = settings;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &settings, &resolved), OBSCURA_OK)
        << obscura_method_name(method) << ": " << obscura_get_last_error(nullptr);
    return settings;
}

// The same effective values, the same derived fields left to the SDK, the same arrays.
void expect_same_settings(obscura_method method, const obscura_settings& expected, const obscura_settings& actual) {
    EXPECT_EQ(actual.method, method);
    for (const obscura_setting_info& info : infos_of(method)) {
        if (obscura::samples::is_array(info)) {
            EXPECT_EQ(table_of(actual, info), table_of(expected, info))
                << obscura_method_name(method) << "." << info.name;
            continue;
        }
        EXPECT_EQ(get(actual, info.name), get(expected, info.name)) << obscura_method_name(method) << "." << info.name;
        EXPECT_EQ(obscura::samples::derives(actual, info), obscura::samples::derives(expected, info))
            << obscura_method_name(method) << "." << info.name;
    }
}

const obscura_setting_info& info_of(obscura_method method, const char* name) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    EXPECT_EQ(obscura_get_setting_infos(method, &infos, &count), OBSCURA_OK);
    for (uint32_t i = 0; i < count; ++i) {
        if (std::strcmp(infos[i].name, name) == 0) return infos[i];
    }
    EXPECT_EQ(obscura_get_shared_setting_infos(&infos, &count), OBSCURA_OK);
    for (uint32_t i = 0; i < count; ++i) {
        if (std::strcmp(infos[i].name, name) == 0) return infos[i];
    }
    ADD_FAILURE() << obscura_method_name(method) << " has no setting " << name;
    return infos[0];
}

// settings_from_json(text) throws a SettingsDocumentError whose message contains every one of `parts`.
void expect_load_error(const std::string& text, std::initializer_list<const char*> parts) {
    try {
        settings_from_json(text);
        ADD_FAILURE() << "no error for: " << text;
    } catch (const SettingsDocumentError& error) {
        const std::string message = error.what();
        for (const char* part : parts) {
            EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
        }
    }
}

std::string document_of(const char* method, const std::string& settings_members, int version = 2) {
    return R"({"format": "obscura-settings", "version": )" + std::to_string(version) + R"(, "method": ")" + method +
           R"(", "settings": {)" + settings_members + "}}";
}
std::string hbao_document(const std::string& settings_members) { return document_of("hbao", settings_members); }

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) lines.push_back(line);
    return lines;
}

// ---- JSON ----------------------------------------------------------------------------------------

TEST(SettingsDocument, MetadataCoversEveryMethod) {
    EXPECT_EQ(all_methods().size(), size_t(OBSCURA_METHOD_COUNT_) - 1);
    for (obscura_method method : all_methods()) EXPECT_FALSE(infos_of(method).empty()) << obscura_method_name(method);
}

TEST(SettingsDocument, JsonHasEverySettingInMetadataOrder) {
    for (obscura_method method : all_methods()) {
        const obscura_settings defaults = defaults_of(method);
        const std::string text = settings_to_json(defaults);
        const obscura::samples::JsonValue document = obscura::samples::parse_json(text);
        EXPECT_EQ(document.find("format")->as_string(), "obscura-settings");
        EXPECT_EQ(document.find("version")->as_number(), 2.0);
        EXPECT_EQ(document.find("method")->as_string(), obscura_method_name(method));
        const obscura::samples::JsonValue::Object& members = document.find("settings")->members();
        const std::vector<obscura_setting_info> infos = infos_of(method);
        ASSERT_EQ(members.size(), infos.size()) << text;
        for (size_t i = 0; i < infos.size(); ++i) {
            const obscura_setting_info& info = infos[i];
            const obscura::samples::JsonValue& member = members[i].second;
            EXPECT_EQ(members[i].first, info.name);
            if (obscura::samples::is_array(info)) {
                ASSERT_TRUE(member.is_array()) << info.name;
                EXPECT_EQ(member.items().size(), size_t(info.value_count)) << info.name;
                continue;
            }
            const double value = get(defaults, info.name);
            if (info.type == OBSCURA_SETTING_TOGGLE) {
                EXPECT_EQ(member.as_string(), value != 0.0 ? "on" : "off") << info.name;
            } else if (obscura::samples::is_derived(info)) {  // derived enums (LSAO's preset) too
                EXPECT_EQ(member.as_number(), 0.0) << info.name << ": the defaults derive it";
            } else if (info.type == OBSCURA_SETTING_ENUM) {
                EXPECT_EQ(member.as_string(), obscura::samples::value_name(info, value)) << info.name;
            } else {
                EXPECT_EQ(float(member.as_number()), float(value)) << info.name;
            }
        }
    }
    // Floats in their shortest form, ints as integers, toggles as words, derived settings 0 ("derive").
    obscura_settings hbao = defaults_of(OBSCURA_METHOD_HBAO);
    ASSERT_EQ(obscura_set_setting(&hbao, "radius", 1.5), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "falloff_c", 0.3), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "blur", 0), OBSCURA_OK);
    const std::string text = settings_to_json(hbao);
    EXPECT_NE(text.find("\"method\": \"hbao\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"radius\": 1.5,"), std::string::npos) << text;
    EXPECT_NE(text.find("\"falloff_c\": 0.3,"), std::string::npos) << text;
    EXPECT_NE(text.find("\"decay_rate\": 0,"), std::string::npos) << text;
    EXPECT_NE(text.find("\"directions\": 8,"), std::string::npos) << text;
    EXPECT_NE(text.find("\"estimator\": \"largest_occluder\","), std::string::npos) << text;
    EXPECT_NE(text.find("\"blur\": \"off\","), std::string::npos) << text;
}

TEST(SettingsDocument, DefaultsRoundTripForEveryMethod) {
    for (obscura_method method : all_methods()) {
        const obscura_settings defaults = defaults_of(method);
        expect_same_settings(method, defaults, settings_from_json(settings_to_json(defaults)));
    }
}

TEST(SettingsDocument, ChangedSettingsRoundTripForEveryMethod) {
    for (obscura_method method : all_methods()) {
        SCOPED_TRACE(obscura_method_name(method));
        std::vector<std::string> kept;
        const obscura_settings changed = resolving_changed_settings(method, &kept);
        const std::string text = settings_to_json(changed);
        const obscura_settings loaded = settings_from_json(text);
        expect_same_settings(method, changed, loaded);
        // And no key still equals its default (the round trip did not fall back to defaults).
        const obscura_settings defaults = defaults_of(method);
        for (const obscura_setting_info& info : infos_of(method)) {
            if (std::find(kept.begin(), kept.end(), info.name) != kept.end()) continue;
            if (obscura::samples::is_array(info)) {
                EXPECT_NE(table_of(loaded, info), table_of(defaults, info)) << info.name;
            } else {
                EXPECT_NE(get(loaded, info.name), get(defaults, info.name)) << info.name;
            }
        }
        EXPECT_EQ(settings_to_json(loaded), text);
    }
    // FFAO's SAAO, which resolving_changed_settings keeps off, round-trips on with a K of its own.
    obscura_settings saao = defaults_of(OBSCURA_METHOD_FFAO);
    ASSERT_EQ(obscura_set_setting(&saao, "saao", 1.0), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&saao, "sectors", 36.0), OBSCURA_OK);
    expect_same_settings(OBSCURA_METHOD_FFAO, saao, settings_from_json(settings_to_json(saao)));
}

TEST(SettingsDocument, FloatsThatAreNotDecimalRoundTrip) {
    // Float values whose shortest decimal differs from the double's: 0.999f is above 0.999 as a double, yet the
    // document holds 0.999 and the range check [1e-3, 0.999] passes.
    obscura_settings hbao = defaults_of(OBSCURA_METHOD_HBAO);
    ASSERT_EQ(obscura_set_setting(&hbao, "falloff_c", 0.999), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "radius", 0.1), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "decay_rate", 1e-8), OBSCURA_OK);
    const obscura_settings loaded = settings_from_json(settings_to_json(hbao));
    expect_same_settings(OBSCURA_METHOD_HBAO, hbao, loaded);
    EXPECT_EQ(get(loaded, "falloff_c"), double(0.999f));
}

TEST(SettingsDocument, EnumsAreWrittenAsNamesAndReadAsNamesOrNumbers) {
    obscura_settings ffao = defaults_of(OBSCURA_METHOD_FFAO);
    ASSERT_EQ(obscura_set_setting(&ffao, "falloff", OBSCURA_FALLOFF_INVERSE_QUADRATIC), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&ffao, "geometry", 2), OBSCURA_OK);
    const std::string text = settings_to_json(ffao);
    EXPECT_NE(text.find("\"falloff\": \"inverse_quadratic\","), std::string::npos) << text;
    EXPECT_NE(text.find("\"geometry\": \"mipmap\","), std::string::npos) << text;
    expect_same_settings(OBSCURA_METHOD_FFAO, ffao, settings_from_json(text));
    // Names and numbers read alike.
    const obscura_settings by_name = settings_from_json(document_of("lsao", R"("preset": "k24", "pattern": "free")"));
    const obscura_settings by_number = settings_from_json(document_of("lsao", R"("preset": 3, "pattern": 2)"));
    EXPECT_EQ(get(by_name, "preset"), 3.0);
    EXPECT_EQ(get(by_name, "pattern"), 2.0);
    expect_same_settings(OBSCURA_METHOD_LSAO, by_name, by_number);
}

TEST(SettingsDocument, DerivedSettingsAreWrittenAsZeroUnlessSet) {
    // The preset's K is derived: written 0, loaded as "derive", so the loaded document is K = 32 ...
    obscura_settings lsao = defaults_of(OBSCURA_METHOD_LSAO);
    ASSERT_EQ(obscura_set_setting(&lsao, "preset", 4), OBSCURA_OK);
    std::string text = settings_to_json(lsao);
    EXPECT_NE(text.find("\"preset\": \"k32\","), std::string::npos) << text;
    EXPECT_NE(text.find("\"directions\": 0,"), std::string::npos) << text;
    obscura_settings loaded = settings_from_json(text);
    EXPECT_EQ(get(loaded, "directions"), 32.0);
    // ... and another preset chosen after loading moves K with it.
    ASSERT_EQ(obscura_set_setting(&loaded, "preset", 1), OBSCURA_OK);
    EXPECT_EQ(get(loaded, "directions"), 8.0);
    // A K that was set stays set.
    ASSERT_EQ(obscura_set_setting(&lsao, "directions", 24), OBSCURA_OK);
    text = settings_to_json(lsao);
    EXPECT_NE(text.find("\"directions\": 24,"), std::string::npos) << text;
    loaded = settings_from_json(text);
    ASSERT_EQ(obscura_set_setting(&loaded, "preset", 1), OBSCURA_OK);
    EXPECT_EQ(get(loaded, "directions"), 24.0);
    // HBAO's decay rate follows the radius of a loaded document.
    loaded = settings_from_json(settings_to_json(defaults_of(OBSCURA_METHOD_HBAO)));
    ASSERT_EQ(obscura_set_setting(&loaded, "radius", 2.0), OBSCURA_OK);
    EXPECT_EQ(get(loaded, "decay_rate"), double(0.3f * 2.0f * 2.0f));
}

TEST(SettingsDocument, FalloffTablesRoundTrip) {
    for (obscura_method method : {OBSCURA_METHOD_FFAO, OBSCURA_METHOD_REFERENCE}) {
        SCOPED_TRACE(obscura_method_name(method));
        obscura_settings settings = defaults_of(method);
        ASSERT_EQ(obscura_set_setting(&settings, "falloff", OBSCURA_FALLOFF_TABLE), OBSCURA_OK);
        const obscura_setting_info& table = info_of(method, "falloff_table");
        fill_table(settings, table);
        obscura::samples::array_values(settings, table)[3] = 0.3f;  // a float that is not a short decimal
        const std::string text = settings_to_json(settings);
        EXPECT_NE(text.find("\"falloff\": \"table\""), std::string::npos) << text;
        const obscura_settings loaded = settings_from_json(text);
        expect_same_settings(method, settings, loaded);
        EXPECT_EQ(table_of(loaded, table)[3], 0.3f);
        obscura_settings resolved;
        EXPECT_EQ(obscura_resolve_settings(nullptr, &loaded, &resolved), OBSCURA_OK);
    }
    // Written by hand.
    const obscura_settings loaded = settings_from_json(document_of("ffao", R"("falloff": "table",
        "falloff_table": [1, 1, 0.9, 0.8, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1, 0, 0, 0, 0, 0])"));
    EXPECT_EQ(get(loaded, "falloff"), double(OBSCURA_FALLOFF_TABLE));
    EXPECT_EQ(table_of(loaded, info_of(OBSCURA_METHOD_FFAO, "falloff_table"))[2], 0.9f);
}

// Version 1 (the viewer before the editable form): effective values everywhere, derived ones written out,
// enums as numbers, no tables. Such documents load; the derived values that are what the document's other
// settings derive load as "derive", other ones as set.
TEST(SettingsDocument, Version1DocumentsLoad) {
    const obscura_settings hbao = settings_from_json(document_of("hbao", R"("radius": 1, "falloff_c": 0.3,
        "decay_rate": 0.3, "directions": 8, "steps": 12, "estimator": 1, "bias": 0, "intensity": 1, "power": 1,
        "max_radius_pixels": 256, "blur": "on", "blur_radius": 4, "blur_sharpness": 16)", 1));
    // Version 1 wrote every value: the defaults before 0.5 (12 steps, horizon split, ...) load as given.
    obscura_settings written = defaults_of(OBSCURA_METHOD_HBAO);
    for (const auto& [name, value] : {std::pair<const char*, double>{"steps", 12}, {"estimator", 1}, {"intensity", 1},
                                      {"power", 1}, {"blur_radius", 4}, {"blur_sharpness", 16}}) {
        ASSERT_EQ(obscura_set_setting(&written, name, value), OBSCURA_OK) << name;
    }
    expect_same_settings(OBSCURA_METHOD_HBAO, written, hbao);
    obscura_settings moved = hbao;
    ASSERT_EQ(obscura_set_setting(&moved, "radius", 2.0), OBSCURA_OK);
    EXPECT_EQ(get(moved, "decay_rate"), double(0.3f * 2.0f * 2.0f));
    // A decay rate of its own stays.
    const obscura_settings own = settings_from_json(document_of("hbao", R"("radius": 1, "decay_rate": 0.5)", 1));
    EXPECT_EQ(get(own, "decay_rate"), double(0.5f));
    EXPECT_FALSE(obscura::samples::derives(own, info_of(OBSCURA_METHOD_HBAO, "decay_rate")));
    // LSAO's K, D_S and D_L as the preset derives them load as "derive"; a K the preset does not give stays
    // (version 1 wrote K = 16 with preset 4, and rendered K = 16).
    const obscura_settings lsao = settings_from_json(document_of("lsao", R"("falloff": 2, "preset": 3,
        "directions": 24, "step_length": 3.56, "line_spacing": 1.69)", 1));
    EXPECT_TRUE(obscura::samples::derives(lsao, info_of(OBSCURA_METHOD_LSAO, "directions")));
    EXPECT_TRUE(obscura::samples::derives(lsao, info_of(OBSCURA_METHOD_LSAO, "step_length")));
    EXPECT_TRUE(obscura::samples::derives(lsao, info_of(OBSCURA_METHOD_LSAO, "line_spacing")));
    EXPECT_EQ(get(lsao, "directions"), 24.0);
    const obscura_settings pinned = settings_from_json(document_of("lsao", R"("preset": 4, "directions": 16)", 1));
    EXPECT_EQ(get(pinned, "directions"), 16.0);
    // A document without a version reads as this version: its values as given.
    const obscura_settings unversioned = settings_from_json(R"({"method": "hbao", "settings": {"decay_rate": 0.3}})");
    EXPECT_FALSE(obscura::samples::derives(unversioned, info_of(OBSCURA_METHOD_HBAO, "decay_rate")));
}

TEST(SettingsDocument, MissingKeysKeepTheirDefaultsAndTogglesTakeBooleans) {
    const obscura_settings loaded = settings_from_json(R"({"method": "sao", "settings": {"samples": 16, "mip": false,
        "blur": true, "quad_filter": "off"}})");
    const obscura_settings defaults = defaults_of(OBSCURA_METHOD_SAO);
    EXPECT_EQ(loaded.method, OBSCURA_METHOD_SAO);
    for (const obscura_setting_info& info : infos_of(OBSCURA_METHOD_SAO)) {
        const std::string name = info.name;
        double expected = get(defaults, info.name);
        if (name == "samples") expected = 16.0;
        // Derived, the spiral's turns follow the taps: 7 * 16 / 9 = 12.4, and 12 shares a factor with 16.
        if (name == "turns") expected = 13.0;
        if (name == "mip" || name == "quad_filter") expected = 0.0;
        if (name == "blur") expected = 1.0;
        EXPECT_EQ(get(loaded, info.name), expected) << name;
    }
    // A document with a method only is the method's defaults.
    expect_same_settings(OBSCURA_METHOD_LSAO, defaults_of(OBSCURA_METHOD_LSAO),
                         settings_from_json(R"({"method": "lsao"})"));
    // 0 is "default" where the range excludes it (hbao decay_rate derives C * radius^2).
    const obscura_settings derived = settings_from_json(hbao_document(R"("radius": 2, "decay_rate": 0)"));
    EXPECT_EQ(get(derived, "decay_rate"), double(0.3f * 2.0f * 2.0f));
}

TEST(SettingsDocument, LoadErrorsNameTheProblem) {
    // Malformed JSON: the reader's message, with its position.
    expect_load_error("{\"method\": \"hbao\",}", {"malformed", "1:"});
    expect_load_error("[1, 2]", {"object"});
    // Method.
    expect_load_error(R"({"settings": {}})", {"\"method\"", "hbao", "sao", "lsao", "ffao", "reference"});
    expect_load_error(R"({"method": "ssao"})", {"method", "ssao", "hbao, sao, lsao, ffao, reference"});
    expect_load_error(R"({"method": 1})", {"method", "hbao"});
    // Unknown key: named, with the method's keys listed.
    expect_load_error(hbao_document(R"("radiuss": 1)"), {"\"radiuss\"", "hbao", "radius, falloff_c", "blur_sharpness"});
    expect_load_error(R"({"method": "hbao", "colour": 1})", {"\"colour\""});
    // Wrong JSON type.
    expect_load_error(hbao_document(R"("radius": "big")"), {"\"radius\"", "number", "\"big\""});
    expect_load_error(hbao_document(R"("directions": [8])"), {"\"directions\"", "number"});
    expect_load_error(hbao_document(R"("directions": 2.5)"), {"\"directions\"", "whole", "2.5"});
    expect_load_error(R"({"method": "hbao", "settings": [1]})", {"\"settings\"", "object"});
    // Out of range: key, value and the metadata's range.
    expect_load_error(hbao_document(R"("radius": 20000)"), {"\"radius\"", "20000", "[0.001, 10000] m"});
    expect_load_error(hbao_document(R"("directions": 33)"), {"\"directions\"", "33", "[1, 32]"});
    expect_load_error(hbao_document(R"("bias": -0.1)"), {"\"bias\"", "-0.1", "[0, 0.5]"});
    expect_load_error(R"({"method": "lsao", "settings": {"segment_steps": -2}})",
                      {"\"segment_steps\"", "-2", "[-1, 4096]"});
    // Toggles.
    expect_load_error(hbao_document(R"("blur": "yes")"), {"\"blur\"", "toggle", "\"yes\""});
    expect_load_error(hbao_document(R"("blur": 1)"), {"\"blur\"", "toggle"});
    expect_load_error(hbao_document(R"("blur": null)"), {"\"blur\"", "toggle"});
    // Enums: a name or a number of theirs.
    expect_load_error(document_of("ffao", R"("falloff": "expo")"),
                      {"\"falloff\"", "\"expo\"", "rho0, inverse_quadratic, exponential, table"});
    expect_load_error(document_of("ffao", R"("falloff": 5)"), {"\"falloff\"", "5", "[1, 4]", "rho0"});
    expect_load_error(document_of("ffao", R"("falloff": 2.5)"), {"\"falloff\"", "whole", "2.5"});
    expect_load_error(document_of("lsao", R"("preset": true)"), {"\"preset\"", "value name or a number"});
    // Arrays: 16 numbers in [0, 1].
    expect_load_error(document_of("ffao", R"("falloff_table": 1)"), {"\"falloff_table\"", "array of 16 numbers"});
    expect_load_error(document_of("ffao", R"("falloff_table": [1, 0.5])"), {"\"falloff_table\"", "2 values", "16"});
    expect_load_error(document_of("reference", R"("falloff_table": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2])"),
                      {"\"falloff_table\"", "[15]", "2", "[0, 1]"});
    expect_load_error(document_of("ffao", R"("falloff_table": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, "x"])"),
                      {"\"falloff_table\"", "[15]", "number", "\"x\""});
    // Derived settings: 0 derives, other values keep their range.
    expect_load_error(document_of("lsao", R"("directions": 65)"), {"\"directions\"", "65", "[1, 64]"});
    // Format and version.
    expect_load_error(R"({"format": "other", "method": "hbao"})", {"\"format\"", "\"other\"", "obscura-settings"});
    expect_load_error(R"({"version": 3, "method": "hbao"})", {"\"version\"", "3", "newer"});
    expect_load_error(R"({"version": "1", "method": "hbao"})", {"\"version\""});
    expect_load_error(R"({"version": 0, "method": "hbao"})", {"\"version\""});
    // And the error is a std::runtime_error.
    EXPECT_THROW(settings_from_json("{"), std::runtime_error);
}

// Every value in range, but settings the SDK refuses as a whole: refused when loaded, with the SDK's reason, as the
// same settings given as a --method spec are (they used to load, and every render then failed).
TEST(SettingsDocument, SettingsThatDoNotResolveAreRefused) {
    expect_load_error(document_of("ffao", R"("falloff": "table")"), {"ffao", "refused", "falloff_table", "all zero"});
    expect_load_error(document_of("reference", R"("falloff": "table",
        "falloff_table": [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0])"), {"refused", "all zero"});
    expect_load_error(document_of("ffao", R"("saao": "on", "sectors": 16)"), {"ffao", "refused", "sectors"});
    // The same settings through the spec parser are refused too.
    EXPECT_THROW(obscura::samples::parse_method_spec("ffao:saao=on:sectors=16"), obscura::samples::MethodSpecError);
    // Version 1 documents are checked the same way.
    expect_load_error(document_of("ffao", R"("saao": "on", "sectors": 16)", 1), {"refused", "sectors"});
    // What resolves still loads.
    EXPECT_NO_THROW(settings_from_json(document_of("ffao", R"("saao": "on")")));
}

// 0 in a field whose range excludes it (radius, intensity, the tap count, an enum numbered from 1) is not a value of
// it: the SDK would read it as the default, so a document saying 0 loaded as something else. Out of range now,
// except in derived fields (0 derives) and in version 1 documents, which were read with 0 as the default.
TEST(SettingsDocument, ZeroOutsideTheRangeIsRefused) {
    expect_load_error(hbao_document(R"("radius": 0)"), {"\"radius\"", "= 0", "[0.001, 10000] m", "default"});
    expect_load_error(hbao_document(R"("intensity": 0)"), {"\"intensity\"", "= 0", "[0.001, 16]"});
    expect_load_error(document_of("sao", R"("samples": 0)"), {"\"samples\"", "= 0", "[1, 64]"});
    expect_load_error(document_of("ffao", R"("falloff": 0)"), {"\"falloff\"", "= 0", "[1, 4]", "rho0"});
    // 0 is a value where the range includes it (HBAO's bias, FFAO's thickness), and derives a derived field.
    EXPECT_EQ(get(settings_from_json(hbao_document(R"("bias": 0)")), "bias"), 0.0);
    EXPECT_EQ(get(settings_from_json(document_of("ffao", R"("thickness": 0)")), "thickness"), 0.0);
    EXPECT_TRUE(obscura::samples::derives(settings_from_json(hbao_document(R"("decay_rate": 0)")),
                                          info_of(OBSCURA_METHOD_HBAO, "decay_rate")));
    // Version 1: 0 reads as the default, as it did.
    const obscura_settings version1 = settings_from_json(document_of("hbao", R"("radius": 0, "intensity": 0)", 1));
    EXPECT_EQ(get(version1, "radius"), 1.0);
    EXPECT_EQ(get(version1, "intensity"), 2.0);
}

// The panel's "derive" box (no context here: the context-free values; viewer_scene_test checks a renderer's):
// unticked, a derived field holds the value it derived, so the picture stays and the box stays unticked.
TEST(SettingsDocument, UntickingDeriveSetsTheDerivedValue) {
    using obscura::viewer::effective_setting_value;
    using obscura::viewer::set_derive;
    obscura_settings hbao = defaults_of(OBSCURA_METHOD_HBAO);
    ASSERT_EQ(obscura_set_setting(&hbao, "radius", 2.0), OBSCURA_OK);
    const obscura_setting_info decay = info_of(OBSCURA_METHOD_HBAO, "decay_rate");
    EXPECT_EQ(effective_setting_value(nullptr, hbao, decay), double(0.3f * 2.0f * 2.0f));
    ASSERT_TRUE(set_derive(nullptr, hbao, decay, false));
    EXPECT_FALSE(obscura::samples::derives(hbao, decay));
    EXPECT_EQ(get(hbao, "decay_rate"), double(0.3f * 2.0f * 2.0f));
    ASSERT_TRUE(set_derive(nullptr, hbao, decay, true));
    EXPECT_TRUE(obscura::samples::derives(hbao, decay));
    // Without a context LSAO's segment_steps has no value (it depends on the renderer): nothing to set.
    obscura_settings lsao = defaults_of(OBSCURA_METHOD_LSAO);
    const obscura_setting_info steps = info_of(OBSCURA_METHOD_LSAO, "segment_steps");
    EXPECT_EQ(effective_setting_value(nullptr, lsao, steps), 0.0);
    EXPECT_FALSE(set_derive(nullptr, lsao, steps, false));
    EXPECT_TRUE(obscura::samples::derives(lsao, steps));
}

// ---- C -------------------------------------------------------------------------------------------

TEST(SettingsDocument, CForDefaultsHasNoAssignments) {
    for (obscura_method method : all_methods()) {
        std::string upper = obscura_method_name(method);
        for (char& c : upper) c = char(c - 'a' + 'A');
        EXPECT_EQ(settings_to_c(defaults_of(method)),
                  "obscura_settings settings;\nobscura_default_settings(OBSCURA_METHOD_" + upper + ", &settings);\n");
    }
    // DEFAULT is HBAO.
    obscura_settings zero;
    std::memset(&zero, 0, sizeof zero);
    zero.struct_size = sizeof zero;
    EXPECT_EQ(settings_to_c(zero),
              "obscura_settings settings;\nobscura_default_settings(OBSCURA_METHOD_HBAO, &settings);\n");
}

TEST(SettingsDocument, CListsExactlyTheChangedSettings) {
    obscura_settings hbao = defaults_of(OBSCURA_METHOD_HBAO);
    ASSERT_EQ(obscura_set_setting(&hbao, "radius", 1.5), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "intensity", 3.0), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "falloff_c", 0.1), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "decay_rate", 1e-8), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "steps", 16), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&hbao, "blur", 0), OBSCURA_OK);
    EXPECT_EQ(settings_to_c(hbao),
              "obscura_settings settings;\n"
              "obscura_default_settings(OBSCURA_METHOD_HBAO, &settings);\n"
              "settings.hbao.radius = 1.5f;\n"
              "settings.hbao.falloff_c = 0.1f;\n"
              "settings.hbao.decay_rate = 1e-08f;\n"
              "settings.hbao.steps = 16;\n"
              "settings.hbao.intensity = 3.0f;\n"
              "settings.hbao.blur = OBSCURA_TOGGLE_OFF;\n");

    obscura_settings lsao = defaults_of(OBSCURA_METHOD_LSAO);
    ASSERT_EQ(obscura_set_setting(&lsao, "tangent", -1.0), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&lsao, "segment_steps", -1), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&lsao, "normal_test", 1), OBSCURA_OK);
    EXPECT_EQ(settings_to_c(lsao),
              "obscura_settings settings;\n"
              "obscura_default_settings(OBSCURA_METHOD_LSAO, &settings);\n"
              "settings.lsao.tangent = -1.0f;\n"
              "settings.lsao.segment_steps = -1;\n"
              "settings.lsao.normal_test = OBSCURA_TOGGLE_ON;\n");

    // A field added to FFAO after its block's release lives in its own block (obscura_ffao_added_settings).
    obscura_settings ffao = defaults_of(OBSCURA_METHOD_FFAO);
    ASSERT_EQ(obscura_set_setting(&ffao, "frame_split", 4), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&ffao, "segments", 1), OBSCURA_OK);
    EXPECT_EQ(settings_to_c(ffao),
              "obscura_settings settings;\n"
              "obscura_default_settings(OBSCURA_METHOD_FFAO, &settings);\n"
              "settings.ffao.segments = 1;\n"
              "settings.ffao_added.frame_split = 4;\n");

    // resolution.scale is a C enum (obscura_resolution), which C++ does not assign from an int: its constant.
    obscura_settings half = defaults_of(OBSCURA_METHOD_GTAO);
    ASSERT_EQ(obscura_set_setting(&half, "resolution.scale", double(OBSCURA_RESOLUTION_HALF)), OBSCURA_OK);
    EXPECT_EQ(settings_to_c(half),
              "obscura_settings settings;\n"
              "obscura_default_settings(OBSCURA_METHOD_GTAO, &settings);\n"
              "settings.resolution.scale = OBSCURA_RESOLUTION_HALF; /* half */\n");
}

// Reads the C back as a compiler would (literal by literal; enums' comments and arrays' elements too) and
// checks it rebuilds every method's changed settings exactly.
TEST(SettingsDocument, CRebuildsTheSettingsOfEveryMethod) {
    for (obscura_method method : all_methods()) {
        SCOPED_TRACE(obscura_method_name(method));
        const obscura_settings changed = changed_settings(method);
        const std::vector<std::string> lines = lines_of(settings_to_c(changed));
        const std::vector<obscura_setting_info> infos = infos_of(method);
        std::vector<std::string> expected_keys;  // metadata order, each array element on a line of its own
        for (const obscura_setting_info& info : infos) {
            if (!obscura::samples::is_array(info)) expected_keys.push_back(info.name);
            for (uint32_t e = 0; obscura::samples::is_array(info) && e < info.value_count; ++e) {
                expected_keys.push_back(std::string(info.name) + "[" + std::to_string(e) + "]");
            }
        }
        ASSERT_EQ(lines.size(), 2 + expected_keys.size());
        obscura_settings rebuilt = defaults_of(method);
        const std::string prefix = std::string("settings.") + obscura_method_name(method) + ".";
        for (size_t i = 2; i < lines.size(); ++i) {
            std::string line = lines[i];
            // An enum's value name follows as a comment: /* exponential */.
            const size_t comment = line.find(" /* ");
            if (comment != std::string::npos) {
                ASSERT_EQ(line.compare(line.size() - 3, 3, " */"), 0) << line;
                line.erase(comment);
            }
            // A shared row (temporal accumulation, resolution) is settings.<block>.<field>, its key "<block>.<field>";
            // a field added to a released method later is settings.<method>_added.<key> (obscura_ffao_added_settings).
            const bool shared = line.compare(0, 18, "settings.temporal.") == 0 ||
                                line.compare(0, 20, "settings.resolution.") == 0;
            const std::string added_prefix = std::string("settings.") + obscura_method_name(method) + "_added.";
            const bool added = line.compare(0, added_prefix.size(), added_prefix) == 0;
            if (!shared && !added) {
                ASSERT_EQ(line.compare(0, prefix.size(), prefix), 0) << line;
            }
            const size_t equals = line.find(" = ");
            ASSERT_NE(equals, std::string::npos) << line;
            ASSERT_EQ(line.back(), ';') << line;
            const size_t key_start =
                shared ? std::string("settings.").size() : added ? added_prefix.size() : prefix.size();
            const std::string key = line.substr(key_start, equals - key_start);
            EXPECT_EQ(key, expected_keys[i - 2]);
            const std::string literal = line.substr(equals + 3, line.size() - equals - 4);
            double value = 0.0;
            if (literal == "OBSCURA_TOGGLE_ON") value = 1.0;
            else if (literal == "OBSCURA_TOGGLE_OFF") value = 0.0;
            else if (literal == "OBSCURA_RESOLUTION_FULL") value = double(OBSCURA_RESOLUTION_FULL);
            else if (literal == "OBSCURA_RESOLUTION_HALF") value = double(OBSCURA_RESOLUTION_HALF);
            else if (literal == "OBSCURA_RESOLUTION_QUARTER") value = double(OBSCURA_RESOLUTION_QUARTER);
            else if (literal.back() == 'f') {
                ASSERT_NE(literal.find_first_of(".e"), std::string::npos) << "not a C float literal: " << literal;
                value = std::strtof(literal.c_str(), nullptr);
            } else {
                char* end = nullptr;
                value = double(std::strtol(literal.c_str(), &end, 10));
                EXPECT_EQ(*end, '\0') << literal;
            }
            const size_t bracket = key.find('[');
            if (bracket != std::string::npos) {
                const obscura_setting_info& info = info_of(method, key.substr(0, bracket).c_str());
                obscura::samples::array_values(rebuilt, info)[std::stoul(key.substr(bracket + 1))] = float(value);
                continue;
            }
            const obscura_setting_info& info = info_of(method, key.c_str());
            if (info.type == OBSCURA_SETTING_ENUM) {
                EXPECT_NE(comment, std::string::npos) << "no value name after " << line;
                EXPECT_EQ(lines[i].substr(comment + 4, lines[i].size() - comment - 7),
                          obscura::samples::value_name(info, value));
            }
            ASSERT_EQ(obscura_set_setting(&rebuilt, key.c_str(), value), OBSCURA_OK) << line;
        }
        expect_same_settings(method, changed, rebuilt);
    }
}

TEST(SettingsDocument, CNamesEnumsAndWritesTablesAndOnlySetDerivedFields) {
    obscura_settings ffao = defaults_of(OBSCURA_METHOD_FFAO);
    ASSERT_EQ(obscura_set_setting(&ffao, "falloff", OBSCURA_FALLOFF_TABLE), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&ffao, "radius", 2.0), OBSCURA_OK);  // moves the derived decay rate: not written
    const obscura_setting_info& table = info_of(OBSCURA_METHOD_FFAO, "falloff_table");
    fill_table(ffao, table);
    std::string expected = "obscura_settings settings;\n"
                           "obscura_default_settings(OBSCURA_METHOD_FFAO, &settings);\n"
                           "settings.ffao.radius = 2.0f;\n"
                           "settings.ffao.falloff = 4; /* table */\n";
    const char* const elements[] = {"1.0f",    "0.9375f", "0.875f", "0.8125f", "0.75f",  "0.6875f",
                                    "0.625f",  "0.5625f", "0.5f",   "0.4375f", "0.375f", "0.3125f",
                                    "0.25f",   "0.1875f", "0.125f", "0.0625f"};
    for (int i = 0; i < 16; ++i) {
        expected += "settings.ffao.falloff_table[" + std::to_string(i) + "] = " + elements[i] + ";\n";
    }
    EXPECT_EQ(settings_to_c(ffao), expected);

    // A derived field set to a value is written, even the value it would derive.
    obscura_settings lsao = defaults_of(OBSCURA_METHOD_LSAO);
    ASSERT_EQ(obscura_set_setting(&lsao, "preset", 4), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&lsao, "line_spacing", 1.7), OBSCURA_OK);
    EXPECT_EQ(settings_to_c(lsao),
              "obscura_settings settings;\n"
              "obscura_default_settings(OBSCURA_METHOD_LSAO, &settings);\n"
              "settings.lsao.preset = 4; /* k32 */\n"
              "settings.lsao.line_spacing = 1.7f;\n");
}

// settings_to_c writes settings.<method>.<key>: every metadata key must be its C field's name, and every
// method name the member of obscura_settings. The table names each field in C; a setting added to the SDK
// must be added here too.
TEST(SettingsDocument, MetadataKeysAreTheCFieldNames) {
    struct Field {
        const char* method;
        const char* name;
        size_t offset;
        const char* c_path;  // as the generated C writes it (samples::c_field_path)
    };
#define OBSCURA_TEST_FIELD(method, field) {#method, #field, offsetof(obscura_settings, method.field), #method "." #field}
    const Field fields[] = {
        OBSCURA_TEST_FIELD(hbao, radius), OBSCURA_TEST_FIELD(hbao, falloff_c), OBSCURA_TEST_FIELD(hbao, decay_rate),
        OBSCURA_TEST_FIELD(hbao, directions), OBSCURA_TEST_FIELD(hbao, steps), OBSCURA_TEST_FIELD(hbao, estimator),
        OBSCURA_TEST_FIELD(hbao, bias), OBSCURA_TEST_FIELD(hbao, intensity), OBSCURA_TEST_FIELD(hbao, power),
        OBSCURA_TEST_FIELD(hbao, max_radius_pixels), OBSCURA_TEST_FIELD(hbao, blur),
        OBSCURA_TEST_FIELD(hbao, blur_radius), OBSCURA_TEST_FIELD(hbao, blur_sharpness),
        OBSCURA_TEST_FIELD(reference, radius), OBSCURA_TEST_FIELD(reference, falloff),
        OBSCURA_TEST_FIELD(reference, falloff_c), OBSCURA_TEST_FIELD(reference, decay_rate),
        OBSCURA_TEST_FIELD(reference, thickness), OBSCURA_TEST_FIELD(reference, rays),
        OBSCURA_TEST_FIELD(reference, rays_per_dispatch), OBSCURA_TEST_FIELD(reference, first_ray),
        OBSCURA_TEST_FIELD(reference, falloff_table),
        OBSCURA_TEST_FIELD(sao, radius), OBSCURA_TEST_FIELD(sao, samples), OBSCURA_TEST_FIELD(sao, turns),
        OBSCURA_TEST_FIELD(sao, mip), OBSCURA_TEST_FIELD(sao, mip_filter), OBSCURA_TEST_FIELD(sao, log_q),
        OBSCURA_TEST_FIELD(sao, intensity), OBSCURA_TEST_FIELD(sao, bias), OBSCURA_TEST_FIELD(sao, contrast),
        OBSCURA_TEST_FIELD(sao, epsilon), OBSCURA_TEST_FIELD(sao, max_radius_pixels),
        OBSCURA_TEST_FIELD(sao, quad_filter), OBSCURA_TEST_FIELD(sao, blur), OBSCURA_TEST_FIELD(sao, blur_radius),
        OBSCURA_TEST_FIELD(sao, blur_stride), OBSCURA_TEST_FIELD(sao, blur_sharpness),
        OBSCURA_TEST_FIELD(sao, blur_depth_range),
        OBSCURA_TEST_FIELD(lsao, radius), OBSCURA_TEST_FIELD(lsao, falloff), OBSCURA_TEST_FIELD(lsao, falloff_c),
        OBSCURA_TEST_FIELD(lsao, decay_rate), OBSCURA_TEST_FIELD(lsao, preset), OBSCURA_TEST_FIELD(lsao, pattern),
        OBSCURA_TEST_FIELD(lsao, directions), OBSCURA_TEST_FIELD(lsao, step_length),
        OBSCURA_TEST_FIELD(lsao, line_spacing), OBSCURA_TEST_FIELD(lsao, tangent),
        OBSCURA_TEST_FIELD(lsao, tangent_strategy), OBSCURA_TEST_FIELD(lsao, hull_capacity),
        OBSCURA_TEST_FIELD(lsao, exact), OBSCURA_TEST_FIELD(lsao, segment_steps),
        OBSCURA_TEST_FIELD(lsao, warmup_tolerance), OBSCURA_TEST_FIELD(lsao, warmup_stride),
        OBSCURA_TEST_FIELD(lsao, depth_threshold), OBSCURA_TEST_FIELD(lsao, normal_test),
        OBSCURA_TEST_FIELD(lsao, normal_threshold), OBSCURA_TEST_FIELD(lsao, intensity),
        OBSCURA_TEST_FIELD(lsao, power),
        OBSCURA_TEST_FIELD(ffao, radius), OBSCURA_TEST_FIELD(ffao, falloff), OBSCURA_TEST_FIELD(ffao, falloff_c),
        OBSCURA_TEST_FIELD(ffao, decay_rate), OBSCURA_TEST_FIELD(ffao, sectors), OBSCURA_TEST_FIELD(ffao, segments),
        OBSCURA_TEST_FIELD(ffao, base_interval), OBSCURA_TEST_FIELD(ffao, geometry),
        OBSCURA_TEST_FIELD(ffao, thickness), OBSCURA_TEST_FIELD(ffao, jitter), OBSCURA_TEST_FIELD(ffao, saao),
        OBSCURA_TEST_FIELD(ffao, saao_blur), OBSCURA_TEST_FIELD(ffao, intensity), OBSCURA_TEST_FIELD(ffao, power),
        OBSCURA_TEST_FIELD(ffao, falloff_table),
        // FFAO's 0.5 fields, in their own block after the 0.4 layout (the C path below checks the block's name).
        {"ffao", "frame_split", offsetof(obscura_settings, ffao_added.frame_split), "ffao_added.frame_split"},
        OBSCURA_TEST_FIELD(gtao, radius), OBSCURA_TEST_FIELD(gtao, preset), OBSCURA_TEST_FIELD(gtao, slices),
        OBSCURA_TEST_FIELD(gtao, steps), OBSCURA_TEST_FIELD(gtao, thickness_mode),
        OBSCURA_TEST_FIELD(gtao, thickness), OBSCURA_TEST_FIELD(gtao, thickness_blend),
        OBSCURA_TEST_FIELD(gtao, sectors), OBSCURA_TEST_FIELD(gtao, falloff_range),
        OBSCURA_TEST_FIELD(gtao, step_power), OBSCURA_TEST_FIELD(gtao, mip), OBSCURA_TEST_FIELD(gtao, mip_offset),
        OBSCURA_TEST_FIELD(gtao, intensity), OBSCURA_TEST_FIELD(gtao, power), OBSCURA_TEST_FIELD(gtao, albedo),
        OBSCURA_TEST_FIELD(gtao, max_radius_pixels), OBSCURA_TEST_FIELD(gtao, denoise),
        OBSCURA_TEST_FIELD(gtao, denoise_sharpness), OBSCURA_TEST_FIELD(gtao, frame_index),
    };
#undef OBSCURA_TEST_FIELD
    // The rows every method shares name their block: "temporal.enabled" is settings.temporal.enabled.
#define OBSCURA_TEST_SHARED_FIELD(block, field) {#block "." #field, offsetof(obscura_settings, block.field)}
    const struct {
        const char* name;
        size_t offset;
    } shared_fields[] = {
        OBSCURA_TEST_SHARED_FIELD(temporal, enabled), OBSCURA_TEST_SHARED_FIELD(temporal, max_frames),
        OBSCURA_TEST_SHARED_FIELD(temporal, clamp), OBSCURA_TEST_SHARED_FIELD(temporal, plane_tolerance),
        OBSCURA_TEST_SHARED_FIELD(resolution, scale), OBSCURA_TEST_SHARED_FIELD(resolution, upsample_tolerance),
    };
#undef OBSCURA_TEST_SHARED_FIELD
    const obscura_setting_info* shared = nullptr;
    uint32_t shared_count = 0;
    ASSERT_EQ(obscura_get_shared_setting_infos(&shared, &shared_count), OBSCURA_OK);
    ASSERT_EQ(shared_count, sizeof shared_fields / sizeof shared_fields[0]);
    for (uint32_t i = 0; i < shared_count; ++i) {
        EXPECT_STREQ(shared[i].name, shared_fields[i].name);
        EXPECT_EQ(shared[i].offset, shared_fields[i].offset) << shared[i].name;
    }
    for (obscura_method method : all_methods()) {
        for (const obscura_setting_info& info : infos_of(method)) {
            if (std::strchr(info.name, '.')) continue;  // a shared row: checked above
            const Field* match = nullptr;
            for (const Field& field : fields) {
                if (std::strcmp(field.method, obscura_method_name(method)) == 0 &&
                    std::strcmp(field.name, info.name) == 0) {
                    match = &field;
                }
            }
            ASSERT_NE(match, nullptr) << obscura_method_name(method) << "." << info.name
                                      << ": not a field of this table; check its C name and add it";
            EXPECT_EQ(info.offset, match->offset) << obscura_method_name(method) << "." << info.name;
            EXPECT_EQ(obscura::samples::c_field_path(method, info), match->c_path);
        }
    }
}

// ---- Files ---------------------------------------------------------------------------------------

TEST(SettingsDocument, TextFilesRoundTrip) {
    const std::string path = ::testing::TempDir() + "obscura_settings_document_test.json";
    const std::string text = settings_to_json(changed_settings(OBSCURA_METHOD_FFAO));
    std::string error;
    ASSERT_TRUE(obscura::viewer::write_text_file(path, text, &error)) << error;
    std::string read;
    ASSERT_TRUE(obscura::viewer::read_text_file(path, &read, &error)) << error;
    EXPECT_EQ(read, text);
    std::remove(path.c_str());
    EXPECT_FALSE(obscura::viewer::read_text_file(path, &read, &error));
    EXPECT_NE(error.find(path), std::string::npos) << error;
    EXPECT_FALSE(obscura::viewer::write_text_file("/nonexistent-dir/x.json", text, &error));
    EXPECT_NE(error.find("/nonexistent-dir/x.json"), std::string::npos) << error;
}

}  // namespace
