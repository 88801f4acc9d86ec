// The samples' method-spec parser (samples/common/method_spec_parser.h), which the CLI, the viewer and the golden
// tests share: specs start from the editable defaults (derived settings follow the keys given), value names,
// the falloff table inline and from a file, and the errors, each naming the problem. No GL.
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "method_spec_parser.h"
#include "obscura/obscura.h"

namespace {

using obscura::samples::MethodSpecError;
using obscura::samples::parse_method_spec;

double get(const obscura_settings& settings, const char* name) {
    double value = -12345.0;
    EXPECT_EQ(obscura_get_setting(&settings, name, &value), OBSCURA_OK) << name;
    return value;
}

std::vector<float> table_of(const obscura_settings& settings) {
    const obscura_setting_info* info = obscura::samples::falloff_table_info(settings.method);
    EXPECT_NE(info, nullptr);
    if (!info) return {};
    const float* values = obscura::samples::array_values(settings, *info);
    return std::vector<float>(values, values + info->value_count);
}

// parse_method_spec(spec) throws a MethodSpecError whose message contains every one of `parts`.
void expect_spec_error(const std::string& spec, std::initializer_list<const char*> parts) {
    try {
        parse_method_spec(spec);
        ADD_FAILURE() << "no error for " << spec;
    } catch (const MethodSpecError& error) {
        const std::string message = error.what();
        for (const char* part : parts) {
            EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
        }
    }
}

bool resolves(const obscura_settings& settings) {
    obscura_settings resolved;
    return obscura_resolve_settings(nullptr, &settings, &resolved) == OBSCURA_OK;
}

const char* const kTable = "1/0.95/0.9/0.8/0.7/0.6/0.5/0.4/0.3/0.2/0.15/0.1/0.05/0.02/0.01/0";

class TempFile {
public:
    TempFile(const char* name, const std::string& contents) : path_(::testing::TempDir() + name) {
        std::FILE* file = std::fopen(path_.c_str(), "wb");
        EXPECT_NE(file, nullptr) << path_;
        if (file) {
            std::fwrite(contents.data(), 1, contents.size(), file);
            std::fclose(file);
        }
    }
    ~TempFile() { std::remove(path_.c_str()); }
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

// ---- Defaults and derived settings -------------------------------------------------------------------

TEST(MethodSpecParser, StartsFromTheEditableDefaults) {
    for (obscura_method method : obscura::samples::all_methods()) {
        obscura_settings expected;
        ASSERT_EQ(obscura_default_settings(method, &expected), OBSCURA_OK);
        const obscura_settings parsed = parse_method_spec(obscura_method_name(method));
        EXPECT_EQ(std::memcmp(&parsed, &expected, sizeof parsed), 0) << obscura_method_name(method);
    }
}

TEST(MethodSpecParser, LsaoPresetMovesKDsAndDl) {
    // The paper's Table 2: k32 is K = 32, D_S = 4.69, D_L = 1.70 (the golden case lsao_clutter_k32).
    for (const char* spec : {"lsao:preset=4", "lsao:preset=k32"}) {
        const obscura_settings lsao = parse_method_spec(spec);
        EXPECT_EQ(get(lsao, "preset"), 4.0) << spec;
        EXPECT_EQ(get(lsao, "directions"), 32.0) << spec;
        EXPECT_EQ(get(lsao, "step_length"), double(4.69f)) << spec;
        EXPECT_EQ(get(lsao, "line_spacing"), double(1.70f)) << spec;
    }
    EXPECT_EQ(get(parse_method_spec("lsao:preset=k8"), "directions"), 8.0);
    EXPECT_EQ(get(parse_method_spec("lsao:preset=k24"), "directions"), 24.0);
    // A K given in the spec wins over the preset's.
    EXPECT_EQ(get(parse_method_spec("lsao:preset=4:directions=16"), "directions"), 16.0);
}

TEST(MethodSpecParser, RadiusMovesTheDerivedDecayRate) {
    const obscura_settings hbao = parse_method_spec("hbao:radius=1.5");
    EXPECT_EQ(get(hbao, "decay_rate"), double(0.3f * 1.5f * 1.5f));
    // Given, it stays; 0 derives it again.
    EXPECT_EQ(get(parse_method_spec("hbao:radius=1.5:decay_rate=0.2"), "decay_rate"), double(0.2f));
    EXPECT_EQ(get(parse_method_spec("hbao:decay_rate=0.2:radius=2:decay_rate=0"), "decay_rate"),
              double(0.3f * 2.0f * 2.0f));
    // SAAO derives FFAO's K = 18.
    EXPECT_EQ(get(parse_method_spec("ffao:saao=on"), "sectors"), 18.0);
}

TEST(MethodSpecParser, SetOptionsApplyWhereTheMethodHasTheKeyAndTheSpecWins) {
    const obscura_settings hbao = parse_method_spec("hbao:radius=2", {"radius=3", "rays=8", "intensity=1.5"});
    EXPECT_EQ(get(hbao, "radius"), 2.0);
    EXPECT_EQ(get(hbao, "intensity"), 1.5);
    EXPECT_EQ(get(parse_method_spec("reference", {"rays=8"}), "rays"), 8.0);
}

// ---- Value names -------------------------------------------------------------------------------------

TEST(MethodSpecParser, EnumsTakeTheirNamesOrNumbers) {
    EXPECT_EQ(get(parse_method_spec("ffao:falloff=exponential"), "falloff"), double(OBSCURA_FALLOFF_EXPONENTIAL));
    EXPECT_EQ(get(parse_method_spec("ffao:falloff=rho0"), "falloff"), double(OBSCURA_FALLOFF_RHO0));
    EXPECT_EQ(get(parse_method_spec("ffao:falloff=2"), "falloff"), double(OBSCURA_FALLOFF_INVERSE_QUADRATIC));
    EXPECT_EQ(get(parse_method_spec("lsao:pattern=free"), "pattern"), 2.0);
    EXPECT_EQ(get(parse_method_spec("lsao:tangent_strategy=fixed"), "tangent_strategy"), 3.0);  // not the default
    EXPECT_EQ(get(parse_method_spec("ffao:geometry=mipmap"), "geometry"), 2.0);
    EXPECT_EQ(get(parse_method_spec("sao:mip_filter=max"), "mip_filter"), 5.0);
    EXPECT_EQ(get(parse_method_spec("hbao:estimator=largest_occluder"), "estimator"), 2.0);
}

TEST(MethodSpecParser, TogglesTakeTheirWords) {
    for (const char* on : {"on", "true", "yes", "1"}) {
        EXPECT_EQ(get(parse_method_spec(std::string("hbao:blur=") + on), "blur"), 1.0) << on;
    }
    for (const char* off : {"off", "false", "no", "0"}) {
        EXPECT_EQ(get(parse_method_spec(std::string("hbao:blur=") + off), "blur"), 0.0) << off;
    }
}

TEST(MethodSpecParser, UnknownNamesAreRefusedWithTheValidOnes) {
    expect_spec_error("ffao:falloff=expo", {"ffao falloff", "'expo'", "rho0, inverse_quadratic, exponential, table"});
    expect_spec_error("lsao:preset=k64", {"lsao preset", "'k64'", "k8, k16, k24, k32, k8_figure1, k16_figure13"});
    expect_spec_error("lsao:pattern=aligned8", {"aligned, free"});
    expect_spec_error("ffao:falloff=7", {"ffao falloff=7", "[1, 4]", "rho0, inverse_quadratic, exponential, table"});
    expect_spec_error("hbao:blur=maybe", {"hbao blur", "'maybe'", "on or off"});
}

// ---- The falloff table -------------------------------------------------------------------------------

TEST(MethodSpecParser, FalloffTableInline) {
    for (const char* method : {"ffao", "reference"}) {
        const obscura_settings settings =
            parse_method_spec(std::string(method) + ":falloff=table:falloff_table=" + kTable);
        EXPECT_EQ(get(settings, "falloff"), double(OBSCURA_FALLOFF_TABLE)) << method;
        const std::vector<float> table = table_of(settings);
        ASSERT_EQ(table.size(), 16u);
        EXPECT_EQ(table[0], 1.0f);
        EXPECT_EQ(table[1], 0.95f);
        EXPECT_EQ(table[14], 0.01f);
        EXPECT_EQ(table[15], 0.0f);
        EXPECT_TRUE(resolves(settings)) << method;
        EXPECT_TRUE(obscura::samples::uses_falloff_table(settings));
    }
    // Without falloff=table the table is kept, and not used.
    const obscura_settings unused = parse_method_spec(std::string("ffao:falloff_table=") + kTable);
    EXPECT_EQ(table_of(unused)[1], 0.95f);
    EXPECT_FALSE(obscura::samples::uses_falloff_table(unused));
}

TEST(MethodSpecParser, FalloffTableFromAFile) {
    // Whitespace, commas and newlines between the numbers.
    const TempFile file("obscura_method_spec_table.txt",
                        "1, 0.95, 0.9\n0.8 0.7\t0.6,0.5\r\n0.4 0.3 0.2 0.15 0.1 0.05 0.02 0.01 0\n\n");
    const obscura_settings settings = parse_method_spec("ffao:falloff=table:falloff_table=@" + file.path());
    const obscura_settings inline_table = parse_method_spec(std::string("ffao:falloff=table:falloff_table=") + kTable);
    EXPECT_EQ(table_of(settings), table_of(inline_table));
    EXPECT_TRUE(resolves(settings));

    const TempFile short_file("obscura_method_spec_short.txt", "1 0.5 0\n");
    expect_spec_error("ffao:falloff_table=@" + short_file.path(), {"falloff_table", "3 values, expected 16"});
    const TempFile bad_file("obscura_method_spec_bad.txt", "1 0.5 zero\n");
    expect_spec_error("ffao:falloff_table=@" + bad_file.path(), {"falloff_table", "'zero' is not a number"});
    expect_spec_error("ffao:falloff_table=@/nonexistent-dir/table.txt", {"cannot open", "/nonexistent-dir/table.txt"});
}

TEST(MethodSpecParser, FalloffTableErrorsSaySo) {
    expect_spec_error("ffao:falloff_table=1/0.5/0",
                      {"ffao falloff_table", "3 values, expected 16", "V0/V1/.../V15", "@FILE"});
    expect_spec_error("ffao:falloff_table=1/1/1/1/1/1/1/1/1/1/1/1/1/1/1/1/1", {"17 values, expected 16"});
    expect_spec_error("ffao:falloff_table=1/1/1/1/1/1/1/1/1/1/1/1/1/1/1/1.5", {"falloff_table[15] = 1.5", "[0, 1]"});
    expect_spec_error("reference:falloff_table=-0.1/1/1/1/1/1/1/1/1/1/1/1/1/1/1/1",
                      {"falloff_table[0] = -0.1", "[0, 1]"});
    expect_spec_error("ffao:falloff_table=1//1", {"falloff_table", "'' is not a number"});
}

TEST(MethodSpecParser, TableFalloffWithoutATableIsAUsageErrorSayingSo) {
    for (const char* spec : {"ffao:falloff=table", "ffao:falloff=4", "reference:falloff=table",
                             "ffao:falloff=table:falloff_table=0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0"}) {
        expect_spec_error(spec, {spec, "falloff=table needs falloff_table", "all zero", "V0/V1/.../V15", "@FILE"});
    }
}

// ---- Other errors ------------------------------------------------------------------------------------

TEST(MethodSpecParser, SettingsThatDoNotGoTogetherNameTheKey) {
    // Every value is in its range; the SDK refuses the combination.
    expect_spec_error("ffao:sectors=9", {"'ffao:sectors=9'", "refused", "ffao.sectors = 9", "even"});
    expect_spec_error("lsao:directions=12", {"'lsao:directions=12'", "lsao.directions = 12", "K = 8n", "free"});
    expect_spec_error("ffao:saao=on:sectors=8", {"ffao.sectors = 8 with saao", "multiple of 18"});
    expect_spec_error("ffao:saao=on:frame_split=2", {"ffao_added.frame_split = 2 with saao", "one or the other"});
    expect_spec_error("ffao:sectors=4:frame_split=4", {"ffao_added.frame_split = 4 with K = 4", "at most K/2 = 2"});
    EXPECT_EQ(get(parse_method_spec("ffao:sectors=8:frame_split=4"), "frame_split"), 4.0);
    EXPECT_EQ(get(parse_method_spec("ffao"), "frame_split"), 1.0);
    // With the free pattern K = 12 is fine.
    EXPECT_EQ(get(parse_method_spec("lsao:pattern=free:directions=12"), "directions"), 12.0);
}

TEST(MethodSpecParser, ErrorsNameTheProblem) {
    expect_spec_error("ssao", {"unknown method 'ssao'", "hbao, sao, lsao, ffao, reference"});
    expect_spec_error(":radius=1", {"no method name"});
    expect_spec_error("hbao:radiuss=1", {"unknown setting 'radiuss'", "hbao has: radius, falloff_c"});
    expect_spec_error("hbao:radius", {"'radius'", "not KEY=VALUE"});
    expect_spec_error("hbao::radius=1", {"empty setting"});
    expect_spec_error("hbao:radius=big", {"hbao radius", "'big' is not a number"});
    expect_spec_error("hbao:radius=20000", {"hbao radius=20000 is outside [0.001, 10000] m"});
    expect_spec_error("hbao:steps=2.5", {"hbao steps=2.5 must be a whole number in [1, 128]"});
    expect_spec_error("hbao:decay_rate=-1", {"decay_rate=-1 is outside", "0 to derive it"});
    expect_spec_error("hbao:falloff_table=1", {"unknown setting 'falloff_table'"});
    // And a MethodSpecError is a std::runtime_error.
    EXPECT_THROW(parse_method_spec("nosuch"), std::runtime_error);
}

TEST(MethodSpecParser, FormatsValuesAsSpecsWriteThem) {
    const std::vector<obscura_setting_info> ffao = obscura::samples::setting_infos(OBSCURA_METHOD_FFAO);
    const obscura_setting_info* falloff = obscura::samples::find_setting(ffao, "falloff");
    ASSERT_NE(falloff, nullptr);
    EXPECT_EQ(obscura::samples::format_setting_value(*falloff, 3.0), "exponential");
    EXPECT_EQ(obscura::samples::value_name_list(*falloff), "rho0, inverse_quadratic, exponential, table");
    EXPECT_EQ(obscura::samples::format_setting_value(*obscura::samples::find_setting(ffao, "radius"), 1.5), "1.5 m");
    EXPECT_EQ(obscura::samples::format_setting_value(*obscura::samples::find_setting(ffao, "saao"), 1.0), "on");
    const float table[] = {1.0f, 0.5f, 0.25f, 0.0f};
    EXPECT_EQ(obscura::samples::format_array_value(table, 4), "1/0.5/0.25/0");
}

}  // namespace
