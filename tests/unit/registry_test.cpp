// The method registry (sdk/src/method_registry.h): one row per obscura_method, in enum order, each complete,
// and everything the API says about a method comes from its row.
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "method_registry.h"
#include "settings.h"

namespace {

TEST(MethodRegistry, OneCompleteRowPerMethodInEnumOrder) {
    uint32_t count = 0;
    const obscura::MethodDescriptor* const* rows = obscura::method_descriptors(&count);
    ASSERT_EQ(count, uint32_t(OBSCURA_METHOD_COUNT_) - 1);
    std::set<std::string> names;
    for (uint32_t i = 0; i < count; ++i) {
        const obscura::MethodDescriptor& row = *rows[i];
        SCOPED_TRACE(row.name ? row.name : "(null)");
        EXPECT_EQ(int(row.method), int(i) + 1);
        ASSERT_NE(row.name, nullptr);
        EXPECT_TRUE(names.insert(row.name).second) << "duplicate name";
        EXPECT_STREQ(obscura_method_name(row.method), row.name);
        EXPECT_EQ(obscura_method_available(row.method), 1);
        EXPECT_EQ(obscura::find_method(row.method), &row);
        // The settings block lies inside obscura_settings, clear of struct_size, method and flags, and every
        // metadata row inside the block.
        EXPECT_GE(row.settings_offset, offsetof(obscura_settings, hbao));
        EXPECT_LE(row.settings_offset + row.settings_size, sizeof(obscura_settings));
        const size_t flags_begin = offsetof(obscura_settings, flags), flags_end = flags_begin + sizeof(uint32_t);
        EXPECT_TRUE(row.settings_offset + row.settings_size <= flags_begin || row.settings_offset >= flags_end);
        ASSERT_NE(row.settings, nullptr);
        ASSERT_GT(row.setting_count, 0u);
        // A block of added fields (if any) lies after the 0.4 layout, clear of every other block.
        if (row.added_size != 0) {
            EXPECT_GE(row.added_offset, offsetof(obscura_settings, gtao) + sizeof(obscura_gtao_settings));
        }
        EXPECT_LE(row.added_offset + row.added_size, sizeof(obscura_settings));
        for (uint32_t s = 0; s < row.setting_count; ++s) {
            const size_t offset = row.settings[s].offset;
            const bool in_block = offset >= row.settings_offset && offset < row.settings_offset + row.settings_size;
            const bool in_added = offset >= row.added_offset && offset < row.added_offset + row.added_size;
            EXPECT_TRUE(in_block || in_added) << row.settings[s].name;
        }
        EXPECT_NE(row.derive, nullptr);
        ASSERT_NE(row.passes, nullptr);
        EXPECT_GT(row.pass_count, 0u);
        EXPECT_NE(row.create_technique, nullptr);
        // Only the screen-space reference has no falloff of its own to map.
        EXPECT_EQ(row.reference_falloff == nullptr, row.method == OBSCURA_METHOD_REFERENCE);
    }
}

TEST(MethodRegistry, DefaultIsHbaoAndUnknownValuesHaveNoRow) {
    EXPECT_EQ(obscura::find_method(OBSCURA_METHOD_DEFAULT), obscura::find_method(OBSCURA_METHOD_HBAO));
    EXPECT_EQ(obscura::find_method_value(int32_t(OBSCURA_METHOD_COUNT_)), nullptr);
    EXPECT_EQ(obscura::find_method_value(-1), nullptr);
    EXPECT_EQ(obscura::find_method_value(1 << 30), nullptr);
    EXPECT_EQ(obscura_method_name(OBSCURA_METHOD_COUNT_), nullptr);
    EXPECT_EQ(obscura_method_available(OBSCURA_METHOD_COUNT_), 0);
}

// Every timing label a method reports is the public label of one of its row's passes; the header's list of
// labels (obscura_timing.label) is this union plus "total", "depth_prepare" and "composite".
TEST(MethodRegistry, PassLabelsAreDistinctAndNamed) {
    std::set<std::string> labels;
    for (int p = 0; p < int(obscura::PassId::Count); ++p) {
        const std::string label = obscura::pass_label(obscura::PassId(p));
        EXPECT_NE(label, "?");
        EXPECT_TRUE(labels.insert(label).second) << label;
    }
    EXPECT_STREQ(obscura::pass_label(obscura::PassId::Count), "?");
}

TEST(MethodRegistry, EnumeratedSettingsNameEveryValue) {
    uint32_t count = 0;
    const obscura::MethodDescriptor* const* rows = obscura::method_descriptors(&count);
    for (uint32_t i = 0; i < count; ++i) {
        for (uint32_t s = 0; s < rows[i]->setting_count; ++s) {
            const obscura_setting_info& info = rows[i]->settings[s];
            SCOPED_TRACE(std::string(rows[i]->name) + "." + info.name);
            if (info.type == OBSCURA_SETTING_ENUM || info.type == OBSCURA_SETTING_TOGGLE) {
                ASSERT_NE(info.value_names, nullptr);
                EXPECT_EQ(double(info.value_count), info.max_value - info.min_value + 1.0);
                std::set<std::string> names;
                for (uint32_t v = 0; v < info.value_count; ++v) {
                    ASSERT_NE(info.value_names[v], nullptr);
                    EXPECT_GT(std::strlen(info.value_names[v]), 0u);
                    EXPECT_TRUE(names.insert(info.value_names[v]).second) << info.value_names[v];
                }
            } else if (info.type == OBSCURA_SETTING_FLOAT_ARRAY) {
                EXPECT_EQ(info.value_count, uint32_t(OBSCURA_FALLOFF_TABLE_SIZE));
                EXPECT_EQ(info.value_names, nullptr);
            } else {
                EXPECT_EQ(info.value_count, 0u);
                EXPECT_EQ(info.value_names, nullptr);
            }
            if (info.flags & OBSCURA_SETTING_FLAG_DERIVED) {
                EXPECT_EQ(info.default_value, 0.0);
            }
        }
    }
}

}  // namespace
