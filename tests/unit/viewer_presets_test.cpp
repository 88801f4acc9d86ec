// The viewer's presets (samples/viewer/viewer_presets.h): every spec parses with the samples' method-spec parser
// into settings of the method whose combo lists it, and those settings resolve; every method has exactly one
// preset of its plain defaults, no two presets of a method share a label, and FFAO's presets of its paper are
// infinitely thick. A misspelled key or value in a preset would otherwise surface only when a technical artist
// picks it. No GL.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "method_spec_parser.h"
#include "obscura/obscura.h"
#include "viewer_presets.h"

namespace {

using obscura::viewer::kViewerPresets;
using obscura::viewer::ViewerPreset;

TEST(ViewerPresets, EverySpecParsesIntoItsMethodAndResolves) {
    for (const ViewerPreset& preset : kViewerPresets) {
        SCOPED_TRACE(std::string(preset.label) + ": " + preset.spec);
        obscura_settings settings{};
        try {
            settings = obscura::samples::parse_method_spec(preset.spec);
        } catch (const obscura::samples::MethodSpecError& error) {
            ADD_FAILURE() << error.what();
            continue;
        }
        EXPECT_EQ(settings.method, preset.method);
        obscura_settings resolved{};
        resolved.struct_size = sizeof resolved;
        EXPECT_EQ(obscura_resolve_settings(nullptr, &settings, &resolved), OBSCURA_OK);
    }
}

// FFAO's paper renders an infinitely thick depth field; the defaults are 0.4 m thick since 0.5 (docs/parameters.md,
// "FFAO's thickness"), so a preset that names the paper and starts from them must set thickness 0 itself.
TEST(ViewerPresets, FfaoPaperPresetsAreInfinitelyThick) {
    int paper_presets = 0;
    for (const ViewerPreset& preset : kViewerPresets) {
        if (preset.method != OBSCURA_METHOD_FFAO || std::string(preset.label).find("paper") == std::string::npos) {
            continue;
        }
        SCOPED_TRACE(std::string(preset.label) + ": " + preset.spec);
        ++paper_presets;
        const obscura_settings settings = obscura::samples::parse_method_spec(preset.spec);
        obscura_settings resolved{};
        resolved.struct_size = sizeof resolved;
        ASSERT_EQ(obscura_resolve_settings(nullptr, &settings, &resolved), OBSCURA_OK);
        EXPECT_EQ(resolved.ffao.thickness, 0.0f);
    }
    EXPECT_GE(paper_presets, 4);
}

TEST(ViewerPresets, EachMethodHasOneDefaultsPresetAndDistinctLabels) {
    for (int m = OBSCURA_METHOD_HBAO; m < OBSCURA_METHOD_COUNT_; ++m) {
        const auto method = static_cast<obscura_method>(m);
        SCOPED_TRACE(obscura_method_name(method));
        int defaults = 0;
        std::set<std::string> labels;
        for (const ViewerPreset& preset : kViewerPresets) {
            if (preset.method != method) continue;
            EXPECT_TRUE(labels.insert(preset.label).second) << "label used twice: " << preset.label;
            if (std::string(preset.spec) == obscura_method_name(method)) {
                ++defaults;
                EXPECT_NE(std::string(preset.label).find("defaults"), std::string::npos) << preset.label;
            }
        }
        EXPECT_EQ(defaults, 1);
    }
}

}  // namespace
