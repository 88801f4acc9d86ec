// Settings: defaulting of zero fields, validation, the set/get API and the metadata table.
// No GL: everything here goes through the public C API (libobscura.a), which needs no context.
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "obscura/obscura.h"
#include "passes/sao.h"
#include "settings.h"

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Stores any int into an enum field, as a C host may (no out-of-range C++ enum value is formed).
template <class Enum>
void store_raw(Enum* field, int32_t value) {
    static_assert(sizeof(Enum) == sizeof(int32_t), "int-sized C enum");
    std::memcpy(field, &value, sizeof value);
}

obscura_settings zero_settings() {
    obscura_settings s;
    std::memset(&s, 0, sizeof s);
    s.struct_size = sizeof s;
    return s;
}

obscura_settings resolved(const obscura_settings& in) {
    obscura_settings out;
    std::memset(&out, 0xCD, sizeof out);
    EXPECT_EQ(obscura_resolve_settings(nullptr, &in, &out), OBSCURA_OK);
    return out;
}

obscura_status resolve_status(const obscura_settings& in) {
    obscura_settings out;
    return obscura_resolve_settings(nullptr, &in, &out);
}

const obscura_setting_info* find_info(const char* name) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    if (obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &infos, &count) != OBSCURA_OK) return nullptr;
    for (uint32_t i = 0; i < count; ++i)
        if (std::strcmp(infos[i].name, name) == 0) return &infos[i];
    return nullptr;
}

// ---- Defaulting ----------------------------------------------------------------------------------

TEST(SettingsDefaults, ZeroFieldsResolveToTableDefaults) {
    obscura_settings r = resolved(zero_settings());
    EXPECT_EQ(r.method, OBSCURA_METHOD_HBAO);  // DEFAULT resolves to HBAO
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &infos, &count), OBSCURA_OK);
    ASSERT_GT(count, 0u);
    for (uint32_t i = 0; i < count; ++i) {
        const obscura_setting_info& info = infos[i];
        const unsigned char* field = reinterpret_cast<const unsigned char*>(&r) + info.offset;
        double value = 0;
        if (info.type == OBSCURA_SETTING_FLOAT) {
            float f;
            std::memcpy(&f, field, sizeof f);
            value = f;
        } else {
            int32_t v;
            std::memcpy(&v, field, sizeof v);
            value = info.type == OBSCURA_SETTING_TOGGLE ? (v == OBSCURA_TOGGLE_ON ? 1.0 : v == OBSCURA_TOGGLE_OFF ? 0.0 : -1.0)
                                                        : double(v);
        }
        if (std::strcmp(info.name, "decay_rate") == 0) continue;  // derived, checked below
        EXPECT_EQ(value, double(float(info.default_value))) << info.name;
    }
}

TEST(SettingsDefaults, HeaderDocumentedDefaults) {
    obscura_settings r = resolved(zero_settings());
    EXPECT_FLOAT_EQ(r.hbao.radius, 1.0f);
    EXPECT_FLOAT_EQ(r.hbao.falloff_c, 0.3f);
    EXPECT_EQ(r.hbao.directions, 8);
    EXPECT_EQ(r.hbao.steps, 7);
    EXPECT_EQ(r.hbao.estimator, 2);
    EXPECT_FLOAT_EQ(r.hbao.bias, 0.0f);
    EXPECT_FLOAT_EQ(r.hbao.intensity, 2.0f);
    EXPECT_FLOAT_EQ(r.hbao.power, 0.5f);
    EXPECT_FLOAT_EQ(r.hbao.max_radius_pixels, 256.0f);
    EXPECT_EQ(r.hbao.blur, OBSCURA_TOGGLE_ON);
    EXPECT_EQ(r.hbao.blur_radius, 1);
    EXPECT_FLOAT_EQ(r.hbao.blur_sharpness, 89.3f);
}

TEST(SettingsDefaults, DecayRateDerivedFromDefaults) {
    obscura_settings r = resolved(zero_settings());
    EXPECT_FLOAT_EQ(r.hbao.decay_rate, 0.3f * 1.0f * 1.0f);
}

TEST(SettingsDefaults, DecayRateDerivedAsCTimesRadiusSquared) {
    obscura_settings s = zero_settings();
    s.hbao.radius = 2.5f;
    s.hbao.falloff_c = 0.5f;
    EXPECT_FLOAT_EQ(resolved(s).hbao.decay_rate, 0.5f * 2.5f * 2.5f);
}

TEST(SettingsDefaults, ExplicitDecayRateIsKept) {
    obscura_settings s = zero_settings();
    s.hbao.radius = 2.0f;
    s.hbao.decay_rate = 7.0f;
    EXPECT_FLOAT_EQ(resolved(s).hbao.decay_rate, 7.0f);
}

TEST(SettingsDefaults, NonZeroFieldsAreKept) {
    obscura_settings s = zero_settings();
    s.hbao.radius = 0.25f;
    s.hbao.directions = 3;
    s.hbao.steps = 100;
    s.hbao.blur = OBSCURA_TOGGLE_OFF;
    obscura_settings r = resolved(s);
    EXPECT_FLOAT_EQ(r.hbao.radius, 0.25f);
    EXPECT_EQ(r.hbao.directions, 3);
    EXPECT_EQ(r.hbao.steps, 100);
    EXPECT_EQ(r.hbao.blur, OBSCURA_TOGGLE_OFF);
}

// The editable form: obscura_default_settings resolves to exactly what a zero struct resolves to, but leaves
// the derived fields 0 ("derive"), so that editing what they derive from moves them.
TEST(SettingsDefaults, DefaultSettingsAreTheEditableForm) {
    obscura_settings d;
    std::memset(&d, 0, sizeof d);
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_HBAO, &d), OBSCURA_OK);
    EXPECT_EQ(d.struct_size, sizeof(obscura_settings));
    EXPECT_EQ(d.flags, uint32_t(OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE));
    // Derived fields are left to derive ...
    EXPECT_EQ(d.hbao.decay_rate, 0.0f);
    EXPECT_EQ(d.reference.decay_rate, 0.0f);
    EXPECT_EQ(d.sao.turns, 0);
    EXPECT_EQ(d.lsao.preset, 0);
    EXPECT_EQ(d.lsao.directions, 0);
    EXPECT_EQ(d.lsao.step_length, 0.0f);
    EXPECT_EQ(d.lsao.line_spacing, 0.0f);
    EXPECT_EQ(d.ffao.sectors, 0);
    // ... the others hold their defaults explicitly.
    EXPECT_EQ(d.hbao.radius, 1.0f);
    EXPECT_EQ(d.hbao.directions, 8);
    EXPECT_EQ(d.hbao.blur, OBSCURA_TOGGLE_ON);
    EXPECT_EQ(d.lsao.tangent, -0.85f);
    EXPECT_EQ(d.ffao.falloff, OBSCURA_FALLOFF_EXPONENTIAL);
    // The same effective settings as a zero struct (the flag aside).
    obscura_settings from_defaults = resolved(d);
    obscura_settings from_zero = resolved(zero_settings());
    from_zero.flags = from_defaults.flags;
    EXPECT_EQ(std::memcmp(&from_defaults, &from_zero, sizeof from_zero), 0);
}

TEST(SettingsDefaults, EditingMovesWhatIsDerived) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_LSAO, &s), OBSCURA_OK);
    s.hbao.radius = 1.5f;  // the README's example
    s.lsao.preset = 4;     // K = 32, D_S = 4.69, D_L = 1.70
    s.lsao.radius = 2.0f;
    s.sao.samples = 16;
    s.ffao.saao = OBSCURA_TOGGLE_ON;
    const obscura_settings r = resolved(s);
    EXPECT_FLOAT_EQ(r.hbao.decay_rate, 0.3f * 1.5f * 1.5f);
    EXPECT_EQ(r.lsao.directions, 32);
    EXPECT_NEAR(r.lsao.step_length, 4.69f, 1e-6f);
    EXPECT_NEAR(r.lsao.line_spacing, 1.70f, 1e-6f);
    EXPECT_FLOAT_EQ(r.lsao.decay_rate, 0.3f * 2.0f * 2.0f);
    EXPECT_EQ(r.sao.turns, obscura::default_spiral_turns(16));
    EXPECT_EQ(r.ffao.sectors, 18);  // SAAO's K
    // A value written into a derived field fixes it.
    s.lsao.directions = 8;
    EXPECT_EQ(resolved(s).lsao.directions, 8);
}

// GTAO's power derives from the thickness mode: 1.75 with horizons, 1.5 with the bitmask (whose slabs already make up
// for part of the occluders its 3 steps miss, docs/quality.md); a power that is set is kept in either mode.
TEST(SettingsDefaults, GtaoPowerDerivesFromTheThicknessMode) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_GTAO, &s), OBSCURA_OK);
    EXPECT_EQ(s.gtao.power, 0.0f);  // the editable form leaves a derived field 0
    EXPECT_FLOAT_EQ(resolved(s).gtao.power, 1.75f);
    s.gtao.thickness_mode = 2;  // bitmask
    EXPECT_FLOAT_EQ(resolved(s).gtao.power, 1.5f);
    s.gtao.power = 1.2f;
    EXPECT_FLOAT_EQ(resolved(s).gtao.power, 1.2f);
    s.gtao.thickness_mode = 1;
    EXPECT_FLOAT_EQ(resolved(s).gtao.power, 1.2f);
}

// LSAO's preset derives to k8 (the shortest step) at every size, at half and quarter size too, where every step
// spans 2 or 4 host texels; a preset that is set is kept at any resolution.
TEST(SettingsDefaults, LsaoPresetDerivesToK8AtEveryResolution) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_LSAO, &s), OBSCURA_OK);
    EXPECT_EQ(resolved(s).lsao.preset, 1);
    EXPECT_EQ(resolved(s).lsao.directions, 8);
    for (obscura_resolution scale : {OBSCURA_RESOLUTION_HALF, OBSCURA_RESOLUTION_QUARTER}) {
        s.resolution.scale = scale;
        const obscura_settings r = resolved(s);
        EXPECT_EQ(r.lsao.preset, 1) << int(scale);
        EXPECT_EQ(r.lsao.directions, 8) << int(scale);
        EXPECT_NEAR(r.lsao.line_spacing, 1.41f, 1e-6f) << int(scale);
    }
    s.lsao.preset = 2;
    EXPECT_EQ(resolved(s).lsao.preset, 2);
    EXPECT_EQ(resolved(s).lsao.directions, 16);
    obscura_settings zero = zero_settings();
    zero.resolution.scale = OBSCURA_RESOLUTION_HALF;
    EXPECT_EQ(resolved(zero).lsao.preset, 1);
}

// Zero is a value where the range includes it: in the editable form 0 means 0; in a zero struct it still
// means the default; obscura_set_setting moves a zero struct to the editable form without changing the others.
TEST(SettingsDefaults, ZeroCanBeSetWhereTheRangeIncludesIt) {
    obscura_settings editable;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_LSAO, &editable), OBSCURA_OK);
    editable.lsao.tangent = 0.0f;
    editable.lsao.normal_threshold = 0.0f;
    EXPECT_EQ(resolved(editable).lsao.tangent, 0.0f);
    EXPECT_EQ(resolved(editable).lsao.normal_threshold, 0.0f);

    obscura_settings zero = zero_settings();
    zero.method = OBSCURA_METHOD_LSAO;
    EXPECT_FLOAT_EQ(resolved(zero).lsao.tangent, -0.85f);
    EXPECT_FLOAT_EQ(resolved(zero).lsao.normal_threshold, 0.8f);
    ASSERT_EQ(obscura_set_setting(&zero, "tangent", 0.0), OBSCURA_OK);
    EXPECT_TRUE(zero.flags & OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE);
    const obscura_settings r = resolved(zero);
    EXPECT_EQ(r.lsao.tangent, 0.0f);
    EXPECT_FLOAT_EQ(r.lsao.normal_threshold, 0.8f);  // still its default, now written out
    double value = 1.0;
    ASSERT_EQ(obscura_get_setting(&zero, "tangent", &value), OBSCURA_OK);
    EXPECT_EQ(value, 0.0);
    // Derived fields still derive from 0, in either form.
    ASSERT_EQ(obscura_set_setting(&zero, "directions", 0.0), OBSCURA_OK);
    EXPECT_EQ(resolved(zero).lsao.directions, 8);
}

// Every released header's obscura_settings is accepted, its missing fields reading as their defaults; a size
// no header had is refused; nothing is written past the caller's size.
TEST(SettingsDefaults, EveryReleasedStructSizeIsAccepted) {
    const uint32_t sizes[] = {uint32_t(offsetof(obscura_settings, reference)),  // 0.1: HBAO
                              uint32_t(offsetof(obscura_settings, sao)),        // 0.2: + REFERENCE
                              uint32_t(offsetof(obscura_settings, flags)),      // 0.3: + SAO, LSAO, FFAO
                              uint32_t(offsetof(obscura_settings, gtao)),       // 0.4: + flags
                              uint32_t(sizeof(obscura_settings))};
    for (uint32_t size : sizes) {
        SCOPED_TRACE(size);
        unsigned char bytes[sizeof(obscura_settings) + 16];
        std::memset(bytes, 0xAB, sizeof bytes);
        obscura_settings* s = reinterpret_cast<obscura_settings*>(bytes);
        ASSERT_EQ(obscura_default_settings_sized(OBSCURA_METHOD_HBAO, s, size), OBSCURA_OK);
        EXPECT_EQ(s->struct_size, size);
        for (size_t i = size; i < sizeof bytes; ++i) ASSERT_EQ(bytes[i], 0xAB) << "written past the struct at " << i;
        s->hbao.radius = 2.0f;
        ASSERT_EQ(obscura_resolve_settings(nullptr, s, s), OBSCURA_OK);
        EXPECT_EQ(s->struct_size, size);
        EXPECT_FLOAT_EQ(s->hbao.decay_rate, 0.3f * 4.0f);
        for (size_t i = size; i < sizeof bytes; ++i) ASSERT_EQ(bytes[i], 0xAB) << "written past the struct at " << i;
        double value = 0.0;
        EXPECT_EQ(obscura_get_setting(s, "radius", &value), OBSCURA_OK);
        EXPECT_EQ(value, 2.0);
    }
    obscura_settings s = zero_settings();
    for (uint32_t bad : {0u, 4u, sizes[0] - 4, sizes[1] + 4, uint32_t(sizeof(obscura_settings)) + 4}) {
        s.struct_size = bad;
        EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &s), OBSCURA_STATUS_INVALID_STRUCT_SIZE) << bad;
        obscura_settings d;
        EXPECT_EQ(obscura_default_settings_sized(OBSCURA_METHOD_HBAO, &d, bad), OBSCURA_STATUS_INVALID_STRUCT_SIZE);
    }
    // A 0.1 struct has no SAO block: its settings are not there to set.
    unsigned char v01[sizeof(obscura_settings)];
    obscura_settings* old = reinterpret_cast<obscura_settings*>(v01);
    ASSERT_EQ(obscura_default_settings_sized(OBSCURA_METHOD_SAO, old, sizes[0]), OBSCURA_OK);
    EXPECT_EQ(obscura_set_setting(old, "samples", 12.0), OBSCURA_STATUS_UNKNOWN_SETTING);
}

// Binaries built against 0.3 call the plain symbols: a 0.3-sized struct, the 0.3 table layout.
TEST(SettingsDefaults, TheZeroThreeSymbolsKeepTheZeroThreeLayout) {
    unsigned char bytes[sizeof(obscura_settings)];
    std::memset(bytes, 0xAB, sizeof bytes);
    obscura_settings* s = reinterpret_cast<obscura_settings*>(bytes);
    ASSERT_EQ((obscura_default_settings)(OBSCURA_METHOD_HBAO, s), OBSCURA_OK);
    EXPECT_EQ(s->struct_size, uint32_t(offsetof(obscura_settings, flags)));
    for (size_t i = offsetof(obscura_settings, flags); i < sizeof bytes; ++i) ASSERT_EQ(bytes[i], 0xAB);

    const obscura_setting_info* table = nullptr;
    uint32_t count = 0;
    ASSERT_EQ((obscura_get_setting_infos)(OBSCURA_METHOD_FFAO, &table, &count), OBSCURA_OK);
    const obscura::SettingInfo03* rows = reinterpret_cast<const obscura::SettingInfo03*>(table);
    const obscura_setting_info* infos = nullptr;
    uint32_t current = 0;
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_FFAO, &infos, &current), OBSCURA_OK);
    EXPECT_EQ(count, current - 2);  // falloff_table is new in 0.4, frame_split (the last row) in 0.5
    for (uint32_t i = 0; i < count; ++i) {
        EXPECT_STREQ(rows[i].name, infos[i].name);
        EXPECT_EQ(rows[i].offset, infos[i].offset);
        EXPECT_EQ(rows[i].type, infos[i].type == OBSCURA_SETTING_ENUM ? OBSCURA_SETTING_INT : infos[i].type);
    }
    EXPECT_EQ(obscura_get_setting_infos_sized(OBSCURA_METHOD_FFAO, &infos, &current, 12), OBSCURA_STATUS_INVALID_STRUCT_SIZE);
}

// A caller built against 0.4 passes its (smaller) obscura_setting_info size and gets the 0.4 layout without the rows
// added in 0.5, whose fields its obscura_settings does not have (a host writing rows by offset would overrun it).
TEST(SettingsDefaults, TheZeroFourInfoSizeKeepsTheZeroFourRows) {
    const uint32_t size_04 = uint32_t(offsetof(obscura_setting_info, added_in));
    const uint32_t settings_04 = uint32_t(offsetof(obscura_settings, gtao));
    for (obscura_method method : {OBSCURA_METHOD_HBAO, OBSCURA_METHOD_FFAO, OBSCURA_METHOD_LSAO}) {
        const obscura_setting_info* table = nullptr;
        uint32_t count = 0;
        ASSERT_EQ(obscura_get_setting_infos_sized(method, &table, &count, size_04), OBSCURA_OK);
        const obscura_setting_info* infos = nullptr;
        uint32_t current = 0;
        ASSERT_EQ(obscura_get_setting_infos(method, &infos, &current), OBSCURA_OK);
        uint32_t k = 0;
        for (uint32_t i = 0; i < current; ++i) {
            if (infos[i].added_in > 400) {
                EXPECT_GE(infos[i].offset, settings_04) << infos[i].name << ": a 0.5 row inside the 0.4 struct";
                continue;
            }
            ASSERT_LT(k, count);
            obscura_setting_info row = {};
            std::memcpy(&row, reinterpret_cast<const unsigned char*>(table) + size_t(k) * size_04, size_04);
            ++k;
            EXPECT_STREQ(row.name, infos[i].name);
            EXPECT_EQ(row.offset, infos[i].offset);
            EXPECT_EQ(row.flags, infos[i].flags);
            EXPECT_EQ(row.value_count, infos[i].value_count);
            EXPECT_LE(row.offset, settings_04 - 4) << row.name << " lies beyond a 0.4 struct";
        }
        EXPECT_EQ(k, count);
        EXPECT_EQ(count, method == OBSCURA_METHOD_FFAO ? current - 1 : current);  // frame_split is 0.5's
    }
}

TEST(SettingsDefaults, DefaultSettingsForDefaultMethodIsHbao) {
    obscura_settings d;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_DEFAULT, &d), OBSCURA_OK);
    EXPECT_EQ(d.method, OBSCURA_METHOD_HBAO);
}

TEST(SettingsDefaults, DefaultSettingsRejectsBadArguments) {
    obscura_settings d;
    EXPECT_EQ(obscura_default_settings(OBSCURA_METHOD_HBAO, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_default_settings(obscura_method(99), &d), OBSCURA_STATUS_INVALID_ENUM);
    EXPECT_EQ(obscura_default_settings(obscura_method(-1), &d), OBSCURA_STATUS_INVALID_ENUM);
}

TEST(SettingsDefaults, ResolveMayAliasInput) {
    obscura_settings s = zero_settings();
    s.hbao.radius = 2.0f;
    ASSERT_EQ(obscura_resolve_settings(nullptr, &s, &s), OBSCURA_OK);
    EXPECT_FLOAT_EQ(s.hbao.radius, 2.0f);
    EXPECT_EQ(s.hbao.directions, 8);
    EXPECT_FLOAT_EQ(s.hbao.decay_rate, 0.3f * 4.0f);
}

// ---- Validation ----------------------------------------------------------------------------------

struct BadRadius {
    float value;
    const char* what;
};

class SettingsInvalidRadius : public ::testing::TestWithParam<BadRadius> {};

TEST_P(SettingsInvalidRadius, IsInvalidSetting) {
    obscura_settings s = zero_settings();
    s.hbao.radius = GetParam().value;
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING) << GetParam().what;
}

INSTANTIATE_TEST_SUITE_P(Values, SettingsInvalidRadius,
                         ::testing::Values(BadRadius{kNaN, "NaN"}, BadRadius{kInf, "PlusInf"}, BadRadius{-kInf, "MinusInf"},
                                           BadRadius{-1.0f, "Negative"}, BadRadius{1e-4f, "BelowMin"},
                                           BadRadius{1.5e4f, "AboveMax"}),
                         [](const ::testing::TestParamInfo<BadRadius>& param_info) {
                             std::string name = param_info.param.what;
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

TEST(SettingsValidation, RadiusRangeLimitsAreInclusive) {
    obscura_settings s = zero_settings();
    s.hbao.radius = 1e4f;
    EXPECT_EQ(resolve_status(s), OBSCURA_OK);
    s.hbao.radius = 1e-3f;
    EXPECT_EQ(resolve_status(s), OBSCURA_OK);
}

TEST(SettingsValidation, DirectionsOutOfRange) {
    obscura_settings s = zero_settings();
    for (int32_t k : {-1, 33, 1000}) {
        s.hbao.directions = k;
        EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING) << "K = " << k;
    }
    for (int32_t k : {1, 32}) {
        s.hbao.directions = k;
        EXPECT_EQ(resolve_status(s), OBSCURA_OK) << "K = " << k;
    }
}

TEST(SettingsValidation, StepsOutOfRange) {
    obscura_settings s = zero_settings();
    for (int32_t n : {-5, 129}) {
        s.hbao.steps = n;
        EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING) << "N = " << n;
    }
    for (int32_t n : {1, 128}) {
        s.hbao.steps = n;
        EXPECT_EQ(resolve_status(s), OBSCURA_OK) << "N = " << n;
    }
}

TEST(SettingsValidation, NonFiniteFloatFieldsAreInvalid) {
    for (float obscura_hbao_settings::*field :
         {&obscura_hbao_settings::falloff_c, &obscura_hbao_settings::decay_rate, &obscura_hbao_settings::bias,
          &obscura_hbao_settings::intensity, &obscura_hbao_settings::power, &obscura_hbao_settings::max_radius_pixels,
          &obscura_hbao_settings::blur_sharpness}) {
        obscura_settings s = zero_settings();
        s.hbao.*field = kNaN;
        EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);
        s.hbao.*field = kInf;
        EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);
    }
}

TEST(SettingsValidation, OtherRangesAreChecked) {
    obscura_settings s = zero_settings();
    s.hbao.falloff_c = 1.0f;  // (0, 1)
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);
    s = zero_settings();
    s.hbao.bias = 0.6f;
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);
    s = zero_settings();
    s.hbao.bias = -0.1f;
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);
    s = zero_settings();
    s.hbao.estimator = 3;
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);
    s = zero_settings();
    s.hbao.blur_radius = 17;
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);
    s = zero_settings();
    s.hbao.max_radius_pixels = 0.5f;
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);
}

TEST(SettingsValidation, BadMethodIsInvalidEnum) {
    obscura_settings s = zero_settings();
    store_raw(&s.method, OBSCURA_METHOD_COUNT_);
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_ENUM);
    store_raw(&s.method, -3);
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_ENUM);
}

TEST(SettingsValidation, BadToggleIsInvalidEnum) {
    obscura_settings s = zero_settings();
    store_raw(&s.hbao.blur, 3);
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_ENUM);
    store_raw(&s.hbao.blur, -1);
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_ENUM);
}

// A 0.4 struct carries OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE but ends before GTAO's block: the fields it lacks hold their
// defaults, not a literal 0 (gtao.mip_offset, whose range includes 0, read 0 instead of 3.3).
TEST(SettingsDefaults, FieldsAnOlderStructLacksHoldTheirDefaultsUnderZeroIsValue) {
    const uint32_t size_04 = uint32_t(offsetof(obscura_settings, gtao));
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings_sized(OBSCURA_METHOD_HBAO, &s, size_04), OBSCURA_OK);
    ASSERT_NE(s.flags & OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE, 0u);
    store_raw(&s.method, int32_t(OBSCURA_METHOD_GTAO));  // a host that passes GTAO's value by number
    double v = 0.0;
    ASSERT_EQ(obscura_get_setting(&s, "mip_offset", &v), OBSCURA_OK) << obscura_get_last_error(nullptr);
    obscura_settings current;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_GTAO, &current), OBSCURA_OK);
    EXPECT_FLOAT_EQ(float(v), current.gtao.mip_offset);
    EXPECT_GT(v, 0.0);
}

TEST(SettingsValidation, ResolutionScaleOutsideTheEnumIsInvalidEnum) {
    // resolution.scale is the C enum obscura_resolution: an unknown value is INVALID_ENUM, as for every C enum field.
    obscura_settings s = zero_settings();
    store_raw(&s.resolution.scale, 7);
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_ENUM);
    store_raw(&s.resolution.scale, -1);
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_ENUM);
    store_raw(&s.resolution.scale, int32_t(OBSCURA_RESOLUTION_QUARTER));
    EXPECT_EQ(resolve_status(s), OBSCURA_OK);
}

TEST(SettingsValidation, WrongStructSize) {
    obscura_settings s = zero_settings();
    // Sizes no released header had (EveryReleasedStructSizeIsAccepted covers the ones they had).
    for (uint32_t size : {0u, uint32_t(sizeof(obscura_settings) - 8), uint32_t(sizeof(obscura_settings) + 4)}) {
        s.struct_size = size;
        EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_STRUCT_SIZE) << size;
    }
}

TEST(SettingsValidation, NullArguments) {
    obscura_settings s = zero_settings();
    EXPECT_EQ(obscura_resolve_settings(nullptr, nullptr, &s), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
}

TEST(SettingsValidation, FailedResolveLeavesOutputUntouched) {
    obscura_settings s = zero_settings();
    s.hbao.radius = kNaN;
    obscura_settings out;
    std::memset(&out, 0x5A, sizeof out);
    obscura_settings before = out;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &out), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(std::memcmp(&out, &before, sizeof out), 0);
}

// ---- set / get -----------------------------------------------------------------------------------

TEST(SettingsSetGet, RoundTripEveryTableEntry) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &infos, &count), OBSCURA_OK);
    for (uint32_t i = 0; i < count; ++i) {
        const obscura_setting_info& info = infos[i];
        double value;
        if (info.type == OBSCURA_SETTING_TOGGLE) {
            value = 0.0;  // off: the non-default state
        } else if (info.type == OBSCURA_SETTING_INT || info.type == OBSCURA_SETTING_ENUM) {
            value = std::floor((info.min_value + info.max_value) / 2);
        } else if (info.type == OBSCURA_SETTING_FLOAT_ARRAY) {
            continue;  // written through the offset (SettingsSetGet.ArraysAreRefusedByName)
        } else {
            value = double(float(info.min_value + (info.max_value - info.min_value) * 0.375));
        }
        obscura_settings s = zero_settings();
        ASSERT_EQ(obscura_set_setting(&s, info.name, value), OBSCURA_OK) << info.name;
        double read = -12345.0;
        ASSERT_EQ(obscura_get_setting(&s, info.name, &read), OBSCURA_OK) << info.name;
        EXPECT_EQ(read, value) << info.name;
        // The value set is also what resolving uses.
        EXPECT_EQ(resolve_status(s), OBSCURA_OK) << info.name;
    }
}

// Arrays (the falloff tables) have a metadata row but no scalar value: they are written through the offset.
TEST(SettingsSetGet, ArraysAreRefusedByName) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_FFAO, &s), OBSCURA_OK);
    double value = 0.0;
    EXPECT_EQ(obscura_set_setting(&s, "falloff_table", 0.5), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_get_setting(&s, "falloff_table", &value), OBSCURA_STATUS_INVALID_SETTING);
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_FFAO, &infos, &count), OBSCURA_OK);
    const obscura_setting_info* table = nullptr;
    for (uint32_t i = 0; i < count; ++i) {
        if (std::strcmp(infos[i].name, "falloff_table") == 0) table = &infos[i];
    }
    ASSERT_NE(table, nullptr);
    EXPECT_EQ(table->offset, offsetof(obscura_settings, ffao) + offsetof(obscura_ffao_settings, falloff_table));
    ASSERT_EQ(obscura_set_setting(&s, "falloff", OBSCURA_FALLOFF_TABLE), OBSCURA_OK);
    EXPECT_EQ(resolve_status(s), OBSCURA_STATUS_INVALID_SETTING);  // all zero
    float* values = reinterpret_cast<float*>(reinterpret_cast<unsigned char*>(&s) + table->offset);
    for (uint32_t i = 0; i < table->value_count; ++i) values[i] = 1.0f - float(i) / 15.0f;
    EXPECT_EQ(resolve_status(s), OBSCURA_OK);
}

// A refusal names the C field: the shared rows' block is obscura_settings itself, FFAO's added rows live in ffao_added
// (set_setting once said "hbao.temporal.max_frames", a field no header has; resolve already named them right).
TEST(SettingsSetGet, RefusalsNameTheCField) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_HBAO, &s), OBSCURA_OK);
    EXPECT_EQ(obscura_set_setting(&s, "temporal.max_frames", 100), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_NE(std::string(obscura_get_last_error(nullptr)).find("obscura_settings.temporal.max_frames = 100"),
              std::string::npos)
        << obscura_get_last_error(nullptr);
    EXPECT_EQ(obscura_set_setting(&s, "steps", 1000), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_NE(std::string(obscura_get_last_error(nullptr)).find("hbao.steps = 1000"), std::string::npos)
        << obscura_get_last_error(nullptr);
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_FFAO, &s), OBSCURA_OK);
    EXPECT_EQ(obscura_set_setting(&s, "frame_split", 7), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_NE(std::string(obscura_get_last_error(nullptr)).find("ffao_added.frame_split = 7"), std::string::npos)
        << obscura_get_last_error(nullptr);
}

TEST(SettingsSetGet, SetWritesTheStructField) {
    obscura_settings s = zero_settings();
    ASSERT_EQ(obscura_set_setting(&s, "radius", 2.5), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&s, "directions", 6), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&s, "blur", 1), OBSCURA_OK);
    EXPECT_FLOAT_EQ(s.hbao.radius, 2.5f);
    EXPECT_EQ(s.hbao.directions, 6);
    EXPECT_EQ(s.hbao.blur, OBSCURA_TOGGLE_ON);
    ASSERT_EQ(obscura_set_setting(&s, "blur", 0), OBSCURA_OK);
    EXPECT_EQ(s.hbao.blur, OBSCURA_TOGGLE_OFF);
}

TEST(SettingsSetGet, GetOfZeroFieldReportsDefault) {
    obscura_settings s = zero_settings();
    double v = 0;
    ASSERT_EQ(obscura_get_setting(&s, "radius", &v), OBSCURA_OK);
    EXPECT_EQ(v, 1.0);
    ASSERT_EQ(obscura_get_setting(&s, "steps", &v), OBSCURA_OK);
    EXPECT_EQ(v, 7.0);
    ASSERT_EQ(obscura_get_setting(&s, "blur", &v), OBSCURA_OK);
    EXPECT_EQ(v, 1.0);
}

TEST(SettingsSetGet, GetOfDerivedDecayRate) {
    obscura_settings s = zero_settings();
    s.hbao.radius = 2.0f;
    double v = 0;
    ASSERT_EQ(obscura_get_setting(&s, "decay_rate", &v), OBSCURA_OK);
    EXPECT_NEAR(v, 0.3 * 4.0, 1e-6);
}

TEST(SettingsSetGet, DerivedFieldsOfSettingsThatDoNotResolveReadDerive) {
    // LSAO at K = 12 with the aligned pattern (which needs 8n): decay_rate has no derived value and reads 0, "derive"
    // (an editor keeps reading every row while the user is half way through a change); resolve says why.
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_LSAO, &s), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&s, "directions", 12.0), OBSCURA_OK);
    double v = -1.0;
    ASSERT_EQ(obscura_get_setting(&s, "decay_rate", &v), OBSCURA_OK);
    EXPECT_EQ(v, 0.0);
    obscura_settings resolved;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &resolved), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_NE(std::string(obscura_get_last_error(nullptr)).find("directions"), std::string::npos)
        << obscura_get_last_error(nullptr);
    // A derived field the host fixed reads its value.
    s.lsao.decay_rate = 0.5f;
    ASSERT_EQ(obscura_get_setting(&s, "decay_rate", &v), OBSCURA_OK);
    EXPECT_EQ(v, 0.5);
}

TEST(SettingsSetGet, GetReportsTheValueResolveUses) {
    // LSAO's segments hold a multiple of 8 steps (the aligned patterns): 9 is used as 16 and reads so;
    // the struct keeps what the host stored.
    obscura_settings s = zero_settings();
    s.method = OBSCURA_METHOD_LSAO;
    ASSERT_EQ(obscura_set_setting(&s, "segment_steps", 9.0), OBSCURA_OK);
    EXPECT_EQ(s.lsao.segment_steps, 9);
    double v = 0;
    ASSERT_EQ(obscura_get_setting(&s, "segment_steps", &v), OBSCURA_OK);
    EXPECT_EQ(v, 16.0);
    obscura_settings resolved{};
    ASSERT_EQ(obscura_resolve_settings(nullptr, &s, &resolved), OBSCURA_OK);
    EXPECT_EQ(resolved.lsao.segment_steps, 16);
    // A value resolve leaves alone reads as stored.
    ASSERT_EQ(obscura_set_setting(&s, "segment_steps", 24.0), OBSCURA_OK);
    ASSERT_EQ(obscura_get_setting(&s, "segment_steps", &v), OBSCURA_OK);
    EXPECT_EQ(v, 24.0);
}

TEST(SettingsSetGet, SettingZeroMeansDefault) {
    obscura_settings s = zero_settings();
    ASSERT_EQ(obscura_set_setting(&s, "radius", 3.0), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&s, "radius", 0.0), OBSCURA_OK);
    double v = 0;
    ASSERT_EQ(obscura_get_setting(&s, "radius", &v), OBSCURA_OK);
    EXPECT_EQ(v, 1.0);
}

TEST(SettingsSetGet, OutOfRangeIsRejectedAndFieldUnchanged) {
    obscura_settings s = zero_settings();
    s.hbao.radius = 2.0f;
    EXPECT_EQ(obscura_set_setting(&s, "radius", 2e4), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_set_setting(&s, "radius", -1.0), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_set_setting(&s, "radius", std::nan("")), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_set_setting(&s, "radius", HUGE_VAL), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_FLOAT_EQ(s.hbao.radius, 2.0f);
    EXPECT_EQ(obscura_set_setting(&s, "directions", 33), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_set_setting(&s, "steps", 129), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(s.hbao.directions, 0);
    EXPECT_EQ(s.hbao.steps, 0);
}

TEST(SettingsSetGet, IntegerSettingsRejectFractions) {
    obscura_settings s = zero_settings();
    EXPECT_EQ(obscura_set_setting(&s, "directions", 2.5), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(s.hbao.directions, 0);
}

TEST(SettingsSetGet, ToggleAcceptsOnlyZeroOrOne) {
    obscura_settings s = zero_settings();
    EXPECT_EQ(obscura_set_setting(&s, "blur", 2.0), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_set_setting(&s, "blur", 0.5), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(s.hbao.blur, OBSCURA_TOGGLE_DEFAULT);
}

TEST(SettingsSetGet, UnknownNames) {
    obscura_settings s = zero_settings();
    double v = 0;
    for (const char* name : {"", "Radius", "radius ", "hbao.radius", "no_such_setting"}) {
        EXPECT_EQ(obscura_set_setting(&s, name, 1.0), OBSCURA_STATUS_UNKNOWN_SETTING) << "'" << name << "'";
        EXPECT_EQ(obscura_get_setting(&s, name, &v), OBSCURA_STATUS_UNKNOWN_SETTING) << "'" << name << "'";
    }
}

TEST(SettingsSetGet, FfaoSectorsMustBeEven) {
    obscura_settings s = zero_settings();
    s.method = OBSCURA_METHOD_FFAO;
    ASSERT_EQ(obscura_set_setting(&s, "sectors", 18.0), OBSCURA_OK);
    obscura_settings resolved;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &resolved), OBSCURA_OK);
    ASSERT_EQ(obscura_set_setting(&s, "sectors", 17.0), OBSCURA_OK);
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &resolved), OBSCURA_STATUS_INVALID_SETTING);
    s.ffao.sectors = 0;
    s.ffao.falloff = OBSCURA_FALLOFF_TABLE;  // an all-zero table describes no falloff
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &resolved), OBSCURA_STATUS_INVALID_SETTING);
}

TEST(SettingsSetGet, BadMethodAndNullArguments) {
    obscura_settings s = zero_settings();
    double v = 0;
    EXPECT_EQ(obscura_set_setting(nullptr, "radius", 1.0), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_set_setting(&s, nullptr, 1.0), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_get_setting(nullptr, "radius", &v), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_get_setting(&s, nullptr, &v), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_get_setting(&s, "radius", nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    store_raw(&s.method, 42);
    EXPECT_EQ(obscura_set_setting(&s, "radius", 1.0), OBSCURA_STATUS_INVALID_ENUM);
    EXPECT_EQ(obscura_get_setting(&s, "radius", &v), OBSCURA_STATUS_INVALID_ENUM);
}

// ---- Metadata table -------------------------------------------------------------------------------

TEST(SettingsTable, DefaultsWithinRange) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &infos, &count), OBSCURA_OK);
    for (uint32_t i = 0; i < count; ++i) {
        const obscura_setting_info& info = infos[i];
        EXPECT_LE(info.min_value, info.max_value) << info.name;
        double default_value = info.default_value;
        if (std::strcmp(info.name, "decay_rate") == 0) {
            // The table stores 0 = "derived (C * radius^2)"; the value actually used must be in range.
            EXPECT_EQ(info.default_value, 0.0);
            obscura_settings s = zero_settings();
            ASSERT_EQ(obscura_get_setting(&s, "decay_rate", &default_value), OBSCURA_OK);
        }
        EXPECT_GE(default_value, info.min_value) << info.name;
        EXPECT_LE(default_value, info.max_value) << info.name;
        if (info.type != OBSCURA_SETTING_FLOAT) {
            EXPECT_EQ(default_value, std::floor(default_value)) << info.name;
        }
        if (info.type == OBSCURA_SETTING_TOGGLE) {
            EXPECT_EQ(info.min_value, 0.0) << info.name;
            EXPECT_EQ(info.max_value, 1.0) << info.name;
        }
    }
}

TEST(SettingsTable, NamesAndOffsetsUniqueAndInside) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &infos, &count), OBSCURA_OK);
    std::set<std::string> names;
    std::set<size_t> offsets;
    for (uint32_t i = 0; i < count; ++i) {
        const obscura_setting_info& info = infos[i];
        ASSERT_NE(info.name, nullptr);
        EXPECT_GT(std::strlen(info.name), 0u);
        ASSERT_NE(info.unit, nullptr) << info.name;
        ASSERT_NE(info.description, nullptr) << info.name;
        EXPECT_GT(std::strlen(info.description), 0u) << info.name;
        EXPECT_TRUE(names.insert(info.name).second) << "duplicate name " << info.name;
        EXPECT_TRUE(offsets.insert(info.offset).second) << "duplicate offset of " << info.name;
        // Every field is 4 bytes (float, int32_t or an enum) and lies inside the hbao member.
        EXPECT_GE(info.offset, offsetof(obscura_settings, hbao)) << info.name;
        EXPECT_LE(info.offset + 4, offsetof(obscura_settings, hbao) + sizeof(obscura_hbao_settings)) << info.name;
        EXPECT_EQ(info.offset % 4, 0u) << info.name;
    }
}

TEST(SettingsTable, EveryHbaoFieldAppearsWithItsType) {
    struct Field {
        size_t offset;
        obscura_setting_type type;
        const char* name;
    };
#define HBAO_FIELD(f, t) Field{offsetof(obscura_settings, hbao) + offsetof(obscura_hbao_settings, f), t, #f}
    const std::vector<Field> fields = {
        HBAO_FIELD(radius, OBSCURA_SETTING_FLOAT),        HBAO_FIELD(falloff_c, OBSCURA_SETTING_FLOAT),
        HBAO_FIELD(decay_rate, OBSCURA_SETTING_FLOAT),    HBAO_FIELD(directions, OBSCURA_SETTING_INT),
        HBAO_FIELD(steps, OBSCURA_SETTING_INT),           HBAO_FIELD(estimator, OBSCURA_SETTING_ENUM),
        HBAO_FIELD(bias, OBSCURA_SETTING_FLOAT),          HBAO_FIELD(intensity, OBSCURA_SETTING_FLOAT),
        HBAO_FIELD(power, OBSCURA_SETTING_FLOAT),         HBAO_FIELD(max_radius_pixels, OBSCURA_SETTING_FLOAT),
        HBAO_FIELD(blur, OBSCURA_SETTING_TOGGLE),         HBAO_FIELD(blur_radius, OBSCURA_SETTING_INT),
        HBAO_FIELD(blur_sharpness, OBSCURA_SETTING_FLOAT),
    };
#undef HBAO_FIELD
    // A field added to obscura_hbao_settings without a table entry (or this list) changes the size.
    ASSERT_EQ(sizeof(obscura_hbao_settings), fields.size() * 4);
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &infos, &count), OBSCURA_OK);
    EXPECT_EQ(count, fields.size());
    for (const Field& field : fields) {
        const obscura_setting_info* info = find_info(field.name);
        ASSERT_NE(info, nullptr) << field.name << " has no table entry with its field name";
        EXPECT_EQ(info->offset, field.offset) << field.name;
        EXPECT_EQ(info->type, field.type) << field.name;
    }
}

TEST(SettingsTable, DefaultMethodSharesHbaoTable) {
    const obscura_setting_info* a = nullptr;
    const obscura_setting_info* b = nullptr;
    uint32_t na = 0, nb = 0;
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &a, &na), OBSCURA_OK);
    ASSERT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_DEFAULT, &b, &nb), OBSCURA_OK);
    EXPECT_EQ(a, b);
    EXPECT_EQ(na, nb);
}

TEST(SettingsTable, EveryMethodHasATable) {
    for (int m = OBSCURA_METHOD_HBAO; m < OBSCURA_METHOD_COUNT_; ++m) {
        const obscura_setting_info* infos = nullptr;
        uint32_t count = 0;
        ASSERT_EQ(obscura_get_setting_infos(obscura_method(m), &infos, &count), OBSCURA_OK);
        EXPECT_GT(count, 0u) << obscura_method_name(obscura_method(m));
    }
}

TEST(SettingsTable, BadArguments) {
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    EXPECT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_HBAO, nullptr, &count), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &infos, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_get_setting_infos(obscura_method(77), &infos, &count), OBSCURA_STATUS_INVALID_ENUM);
}

}  // namespace

namespace {

obscura_settings settings_of(obscura_method method) {
    obscura_settings s;
    std::memset(&s, 0, sizeof s);
    s.struct_size = sizeof s;
    s.method = method;
    return s;
}

}  // namespace

// ---- REFERENCE ---------------------------------------------------------------------------------------

TEST(ReferenceSettings, DefaultsMatchTheDefaultHbaoFalloff) {
    obscura_settings reference;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_REFERENCE, &reference), OBSCURA_OK);
    obscura_settings hbao;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_HBAO, &hbao), OBSCURA_OK);
    EXPECT_EQ(reference.reference.falloff, OBSCURA_FALLOFF_RHO0);
    EXPECT_EQ(reference.reference.radius, hbao.hbao.radius);
    EXPECT_EQ(reference.reference.falloff_c, hbao.hbao.falloff_c);
    EXPECT_EQ(reference.reference.decay_rate, hbao.hbao.decay_rate);
    EXPECT_EQ(reference.reference.thickness, 0.0f);  // infinitely thick
    EXPECT_EQ(reference.reference.rays, 256);
    EXPECT_EQ(reference.reference.rays_per_dispatch, 16);
    EXPECT_EQ(reference.reference.first_ray, 0);
}

TEST(ReferenceSettings, ForHbaoCopiesItsFalloff) {
    obscura_settings hbao = settings_of(OBSCURA_METHOD_HBAO);
    hbao.hbao.radius = 2.0f;
    hbao.hbao.falloff_c = 0.2f;
    hbao.hbao.directions = 16;  // not a falloff property: must not matter
    obscura_settings reference;
    ASSERT_EQ(obscura_reference_settings_for(&hbao, &reference), OBSCURA_OK);
    EXPECT_EQ(reference.method, OBSCURA_METHOD_REFERENCE);
    EXPECT_EQ(reference.reference.falloff, OBSCURA_FALLOFF_RHO0);
    EXPECT_FLOAT_EQ(reference.reference.radius, 2.0f);
    EXPECT_FLOAT_EQ(reference.reference.falloff_c, 0.2f);
    EXPECT_FLOAT_EQ(reference.reference.decay_rate, 0.2f * 2.0f * 2.0f);  // HBAO's derived r
    EXPECT_EQ(reference.reference.rays, 256);

    hbao.hbao.decay_rate = 0.5f;  // an explicit r is carried over as is
    ASSERT_EQ(obscura_reference_settings_for(&hbao, &reference), OBSCURA_OK);
    EXPECT_FLOAT_EQ(reference.reference.decay_rate, 0.5f);
}

TEST(ReferenceSettings, ForReferenceIsTheResolvedInput) {
    obscura_settings in = settings_of(OBSCURA_METHOD_REFERENCE);
    in.reference.rays = 1024;
    in.reference.falloff = OBSCURA_FALLOFF_EXPONENTIAL;
    obscura_settings out;
    ASSERT_EQ(obscura_reference_settings_for(&in, &out), OBSCURA_OK);
    EXPECT_EQ(out.reference.rays, 1024);
    EXPECT_EQ(out.reference.falloff, OBSCURA_FALLOFF_EXPONENTIAL);
    EXPECT_EQ(out.reference.radius, 1.0f);
    // The reference of one frame at the full size: a REFERENCE accumulated or at half size is measured against it
    // (the viewer's error map once compared a half-size REFERENCE with a half-size reference and showed no error).
    in.temporal.enabled = OBSCURA_TOGGLE_ON;
    in.resolution.scale = OBSCURA_RESOLUTION_HALF;
    ASSERT_EQ(obscura_reference_settings_for(&in, &out), OBSCURA_OK);
    EXPECT_EQ(out.temporal.enabled, OBSCURA_TOGGLE_OFF);
    EXPECT_EQ(out.resolution.scale, OBSCURA_RESOLUTION_FULL);
    EXPECT_EQ(out.reference.rays, 1024);
}

TEST(ReferenceSettings, ForRejectsBadInput) {
    obscura_settings out;
    EXPECT_EQ(obscura_reference_settings_for(nullptr, &out), OBSCURA_STATUS_NULL_ARGUMENT);
    obscura_settings in = settings_of(OBSCURA_METHOD_HBAO);
    EXPECT_EQ(obscura_reference_settings_for(&in, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    in.hbao.radius = -1.0f;
    EXPECT_EQ(obscura_reference_settings_for(&in, &out), OBSCURA_STATUS_INVALID_SETTING);
    in = settings_of(OBSCURA_METHOD_HBAO);
    in.struct_size = 4;
    EXPECT_EQ(obscura_reference_settings_for(&in, &out), OBSCURA_STATUS_INVALID_STRUCT_SIZE);
}

TEST(ReferenceSettings, TableFalloffNeedsATable) {
    obscura_settings s = settings_of(OBSCURA_METHOD_REFERENCE);
    s.reference.falloff = OBSCURA_FALLOFF_TABLE;
    obscura_settings out;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &out), OBSCURA_STATUS_INVALID_SETTING);  // all zero
    for (int i = 0; i < OBSCURA_FALLOFF_TABLE_SIZE; ++i) s.reference.falloff_table[i] = 1.0f - float(i) / 15.0f;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &out), OBSCURA_OK);
    s.reference.falloff_table[3] = 1.5f;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &out), OBSCURA_STATUS_INVALID_SETTING);
    s.reference.falloff_table[3] = std::nanf("");
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &out), OBSCURA_STATUS_INVALID_SETTING);
    // Other falloffs ignore the table, whatever it holds.
    s.reference.falloff = OBSCURA_FALLOFF_RHO0;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &out), OBSCURA_OK);
}

TEST(ReferenceSettings, RangesAreChecked) {
    obscura_settings s = settings_of(OBSCURA_METHOD_REFERENCE);
    EXPECT_EQ(obscura_set_setting(&s, "falloff", 5), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_set_setting(&s, "rays", 65537), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_set_setting(&s, "thickness", -1), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(obscura_set_setting(&s, "thickness", 0.05), OBSCURA_OK);
    EXPECT_EQ(obscura_set_setting(&s, "falloff", 2), OBSCURA_OK);
    double value = 0;
    EXPECT_EQ(obscura_get_setting(&s, "falloff", &value), OBSCURA_OK);
    EXPECT_EQ(value, 2.0);
    EXPECT_EQ(obscura_get_setting(&s, "decay_rate", &value), OBSCURA_OK);
    EXPECT_NEAR(value, 0.3, 1e-7);  // derived: C * radius^2
}

// Found by the settings fuzzer: range checks compared the double argument while the field stores a float, so
// float(1e-8) < 1e-8 and float(0.999) > 0.999 were accepted by obscura_set_setting and refused by resolving:
// 14 documented limits could not be used. Every float setting's minimum and maximum must now set and resolve,
// and the next float beyond the maximum must be refused.
TEST(SettingsRanges, EveryFloatSettingsLimitsSetAndResolve) {
    const obscura_method methods[] = {OBSCURA_METHOD_HBAO, OBSCURA_METHOD_SAO, OBSCURA_METHOD_LSAO, OBSCURA_METHOD_FFAO,
                                      OBSCURA_METHOD_REFERENCE};
    int checked = 0;
    for (obscura_method method : methods) {
        const obscura_setting_info* infos = nullptr;
        uint32_t count = 0;
        ASSERT_EQ(obscura_get_setting_infos(method, &infos, &count), OBSCURA_OK);
        for (uint32_t i = 0; i < count; ++i) {
            if (infos[i].type != OBSCURA_SETTING_FLOAT) continue;
            for (double limit : {infos[i].min_value, infos[i].max_value}) {
                obscura_settings s;
                ASSERT_EQ(obscura_default_settings(method, &s), OBSCURA_OK);
                ASSERT_EQ(obscura_set_setting(&s, infos[i].name, limit), OBSCURA_OK)
                    << obscura_method_name(method) << "." << infos[i].name << " = " << limit;
                obscura_settings resolved;
                EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &resolved), OBSCURA_OK)
                    << obscura_method_name(method) << "." << infos[i].name << " = " << limit;
                ++checked;
            }
            obscura_settings s;
            ASSERT_EQ(obscura_default_settings(method, &s), OBSCURA_OK);
            const double beyond = double(std::nextafter(float(infos[i].max_value), std::numeric_limits<float>::max()));
            EXPECT_EQ(obscura_set_setting(&s, infos[i].name, beyond), OBSCURA_STATUS_INVALID_SETTING)
                << obscura_method_name(method) << "." << infos[i].name << " = " << beyond;
        }
    }
    EXPECT_GT(checked, 60);
}

// Found by the settings fuzzer: with radius and C at their minimums (1e-3) the derived decay rate is 1e-9; the
// resolved settings must resolve again and give a reference (decay_rate's minimum was 1e-8).
TEST(SettingsRanges, SmallestDerivedDecayRateResolvesAgain) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_HBAO, &s), OBSCURA_OK);
    s.hbao.radius = 1e-3f;
    s.hbao.falloff_c = 1e-3f;
    s.hbao.decay_rate = 0.0f;
    obscura_settings resolved, again, reference;
    ASSERT_EQ(obscura_resolve_settings(nullptr, &s, &resolved), OBSCURA_OK);
    EXPECT_EQ(obscura_resolve_settings(nullptr, &resolved, &again), OBSCURA_OK);
    EXPECT_EQ(obscura_reference_settings_for(&s, &reference), OBSCURA_OK);
}

// ---- obscura_evaluate_falloff: the SDK's falloff, as the geometry truth weighs its hits ------------------

namespace {

float falloff_at(const obscura_settings& settings, float distance) {
    float rho = -1.0f;
    EXPECT_EQ(obscura_evaluate_falloff(&settings, &distance, &rho, 1), OBSCURA_OK);
    return rho;
}

obscura_settings reference_with_falloff(obscura_falloff falloff) {
    obscura_settings settings{};
    settings.struct_size = sizeof settings;
    settings.method = OBSCURA_METHOD_REFERENCE;
    settings.reference.falloff = falloff;
    return settings;
}

}  // namespace

// Values worked out by hand from the header's formulas (radius 1 m, C = 0.3, r = C radius^2 = 0.3 m^2).
TEST(EvaluateFalloff, EachKindAtKnownDistances) {
    const obscura_settings rho0 = reference_with_falloff(OBSCURA_FALLOFF_RHO0);
    EXPECT_NEAR(falloff_at(rho0, 0.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(falloff_at(rho0, 0.5f), 0.39f / 0.55f - 0.3f, 1e-6f);  // r(1+C)/(r+d^2) - C
    EXPECT_NEAR(falloff_at(rho0, 1.0f), 0.0f, 1e-6f);                  // reaches 0 at the radius
    EXPECT_EQ(falloff_at(rho0, 3.0f), 0.0f);                           // and stays there
    const obscura_settings inverse = reference_with_falloff(OBSCURA_FALLOFF_INVERSE_QUADRATIC);
    EXPECT_NEAR(falloff_at(inverse, std::sqrt(0.3f)), 0.5f, 1e-6f);    // r/(r+d^2) at d^2 = r
    const obscura_settings exponential = reference_with_falloff(OBSCURA_FALLOFF_EXPONENTIAL);
    EXPECT_NEAR(falloff_at(exponential, std::sqrt(0.3f)), std::exp(-1.0f), 1e-6f);
    obscura_settings table = reference_with_falloff(OBSCURA_FALLOFF_TABLE);
    for (int i = 0; i < OBSCURA_FALLOFF_TABLE_SIZE; ++i) table.reference.falloff_table[i] = i % 2 ? 0.0f : 1.0f;
    EXPECT_NEAR(falloff_at(table, 0.5f / 15.0f), 0.5f, 1e-6f);         // halfway between samples 0 and 1
    EXPECT_NEAR(falloff_at(table, 2.0f / 15.0f), 1.0f, 1e-6f);
    EXPECT_EQ(falloff_at(table, 1.0f), 0.0f);                          // 0 from the radius on
    // Outside the domain: negative is on the surface, NaN and infinity a miss (and the table is not read
    // out of its bounds).
    EXPECT_EQ(falloff_at(table, -0.1f), falloff_at(table, 0.0f));
    EXPECT_EQ(falloff_at(rho0, -5.0f), falloff_at(rho0, 0.0f));
    const std::initializer_list<const obscura_settings*> kinds = {&rho0, &inverse, &exponential, &table};
    for (const obscura_settings* settings : kinds) {
        EXPECT_EQ(falloff_at(*settings, std::numeric_limits<float>::quiet_NaN()), 0.0f);
        EXPECT_EQ(falloff_at(*settings, std::numeric_limits<float>::infinity()), 0.0f);
    }
}

// Another method's falloff is the one obscura_reference_settings_for maps it to.
TEST(EvaluateFalloff, MethodsWeighWithTheirReferenceFalloff) {
    obscura_settings hbao{};
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_HBAO, &hbao), OBSCURA_OK);
    hbao.hbao.radius = 2.0f;
    hbao.hbao.decay_rate = 0.0f;  // derived: C * 4 m^2, so rho0 ends at 2 m
    EXPECT_GT(falloff_at(hbao, 1.9f), 0.0f);
    EXPECT_EQ(falloff_at(hbao, 2.01f), 0.0f);
    obscura_settings sao{};
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_SAO, &sao), OBSCURA_OK);
    EXPECT_EQ(falloff_at(sao, 0.99f * sao.sao.radius), 1.0f);  // AlchemyAO: a step at the radius
    EXPECT_EQ(falloff_at(sao, 1.01f * sao.sao.radius), 0.0f);
    obscura_settings lsao{};
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_LSAO, &lsao), OBSCURA_OK);
    obscura_settings mapped{};
    ASSERT_EQ(obscura_reference_settings_for(&lsao, &mapped), OBSCURA_OK);
    const float distances[3] = {0.1f, 1.0f, 30.0f};
    float from_method[3], from_reference[3];
    ASSERT_EQ(obscura_evaluate_falloff(&lsao, distances, from_method, 3), OBSCURA_OK);
    ASSERT_EQ(obscura_evaluate_falloff(&mapped, distances, from_reference, 3), OBSCURA_OK);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(from_method[i], from_reference[i]);
    EXPECT_GT(from_method[2], 0.0f);  // r/(r+d^2) never reaches 0
}

TEST(EvaluateFalloff, RefusesBadArgumentsAndSettings) {
    obscura_settings settings = reference_with_falloff(OBSCURA_FALLOFF_RHO0);
    float distance = 0.5f, rho = -1.0f;
    EXPECT_EQ(obscura_evaluate_falloff(nullptr, &distance, &rho, 1), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_evaluate_falloff(&settings, nullptr, &rho, 1), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_evaluate_falloff(&settings, &distance, nullptr, 1), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_evaluate_falloff(&settings, nullptr, nullptr, 0), OBSCURA_OK);  // validates only
    settings.reference.falloff = 9;
    EXPECT_EQ(obscura_evaluate_falloff(&settings, &distance, &rho, 1), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(rho, -1.0f);  // nothing written on failure
    settings = reference_with_falloff(OBSCURA_FALLOFF_TABLE);  // a table of zeros is refused
    EXPECT_EQ(obscura_evaluate_falloff(&settings, &distance, &rho, 1), OBSCURA_STATUS_INVALID_SETTING);
    settings.struct_size = 4;
    EXPECT_EQ(obscura_evaluate_falloff(&settings, &distance, &rho, 1), OBSCURA_STATUS_INVALID_STRUCT_SIZE);
}

// Calls without a context leave their reason where obscura_get_last_error(NULL) reads it, on this thread.
TEST(SettingsMessages, CallsWithoutAContextSayWhy) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_FFAO, &s), OBSCURA_OK);
    EXPECT_STREQ(obscura_get_last_error(nullptr), "");
    s.ffao.sectors = 9;
    obscura_settings r;
    ASSERT_EQ(obscura_resolve_settings(nullptr, &s, &r), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_NE(std::string(obscura_get_last_error(nullptr)).find("ffao.sectors = 9"), std::string::npos)
        << obscura_get_last_error(nullptr);
    EXPECT_EQ(obscura_set_setting(&s, "no_such_setting", 1.0), OBSCURA_STATUS_UNKNOWN_SETTING);
    EXPECT_NE(std::string(obscura_get_last_error(nullptr)).find("no_such_setting"), std::string::npos);
    s.ffao.sectors = 0;
    ASSERT_EQ(obscura_resolve_settings(nullptr, &s, &r), OBSCURA_OK);
    EXPECT_STREQ(obscura_get_last_error(nullptr), "");
}
