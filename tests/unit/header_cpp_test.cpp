// The public header from C++: every struct value-initialised, enums usable, C linkage of the API.
#include <cstddef>
#include <cstring>
#include <type_traits>

#include <gtest/gtest.h>

#include "obscura/obscura.h"

namespace {

// The API has C linkage: a pointer to it has a plain C function type (no C++ overload resolution).
static_assert(std::is_same<decltype(&obscura_version), uint32_t (*)()>::value, "obscura_version signature");
static_assert(std::is_same<decltype(&obscura_render),
                           obscura_status (*)(obscura_context*, const obscura_input*, const obscura_settings*,
                                              const obscura_output*)>::value,
              "obscura_render signature");
// Every public struct is trivially copyable and standard-layout (C compatible).
static_assert(std::is_standard_layout<obscura_input>::value && std::is_trivially_copyable<obscura_input>::value, "");
static_assert(std::is_standard_layout<obscura_output>::value, "");
static_assert(std::is_standard_layout<obscura_settings>::value, "");
static_assert(std::is_standard_layout<obscura_context_desc>::value, "");
static_assert(std::is_standard_layout<obscura_setting_info>::value, "");
static_assert(std::is_standard_layout<obscura_timing>::value, "");
static_assert(std::is_standard_layout<obscura_rect>::value, "");
static_assert(std::is_standard_layout<obscura_allocator>::value, "");

TEST(HeaderCpp, EveryStructValueInitialises) {
    obscura_allocator allocator{};
    obscura_context_desc desc{};
    obscura_hbao_settings hbao{};
    obscura_settings settings{};
    obscura_setting_info info{};
    obscura_rect rect{};
    obscura_input input{};
    obscura_output output{};
    obscura_timing timing{};
    EXPECT_EQ(allocator.alloc, nullptr);
    EXPECT_EQ(desc.get_proc_address, nullptr);
    EXPECT_EQ(hbao.radius, 0.0f);
    EXPECT_EQ(settings.method, OBSCURA_METHOD_DEFAULT);
    EXPECT_EQ(info.name, nullptr);
    EXPECT_EQ(rect.width, 0);
    EXPECT_EQ(input.depth_kind, OBSCURA_DEPTH_HARDWARE);
    EXPECT_EQ(input.projection_layout, OBSCURA_MATRIX_COLUMN_MAJOR);
    EXPECT_EQ(input.clip_depth, OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_EQ(output.blend, OBSCURA_BLEND_OVERWRITE);
    EXPECT_EQ(output.debug_view, OBSCURA_DEBUG_NONE);
    EXPECT_EQ(timing.label, nullptr);
}

TEST(HeaderCpp, ZeroIsEveryEnumDefault) {
    // The "zero-initialised struct is valid" contract relies on these values.
    EXPECT_EQ(int(OBSCURA_METHOD_DEFAULT), 0);
    EXPECT_EQ(int(OBSCURA_TOGGLE_DEFAULT), 0);
    EXPECT_EQ(int(OBSCURA_DEPTH_HARDWARE), 0);
    EXPECT_EQ(int(OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE), 0);
    EXPECT_EQ(int(OBSCURA_MATRIX_COLUMN_MAJOR), 0);
    EXPECT_EQ(int(OBSCURA_BLEND_OVERWRITE), 0);
    EXPECT_EQ(int(OBSCURA_DEBUG_NONE), 0);
}

TEST(HeaderCpp, CallsWithoutGl) {
    obscura_settings settings{};
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_HBAO, &settings), OBSCURA_OK);
    EXPECT_EQ(settings.struct_size, sizeof settings);
    EXPECT_EQ(std::strncmp(obscura_status_string(OBSCURA_OK), "OBSCURA_STATUS_OK", 17), 0);
}

}  // namespace
