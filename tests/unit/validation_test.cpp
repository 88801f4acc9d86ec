// The first stage of obscura_render's validation needs no GL (sdk/src/frame_input.h, output_writer.h): the
// input's and the output's fields are checked here without a context, and what they decode to is what the
// passes get.
#include <gtest/gtest.h>

#include <cstring>

#include "frame_input.h"
#include "output_writer.h"

namespace {

constexpr GLint kMaxTextureSize = 16384;

// A standard perspective matrix (column-major): fovy 60 degrees, aspect 16:9, near 0.1, far 100.
obscura_input valid_input() {
    obscura_input input;
    std::memset(&input, 0, sizeof input);
    input.struct_size = sizeof input;
    input.depth_texture = 7;  // never looked at by stage 1
    input.depth_width = 352;
    input.depth_height = 198;
    const float f = 1.7320508f, aspect = 16.0f / 9.0f, n = 0.1f, far_plane = 100.0f;
    input.projection[0] = f / aspect;
    input.projection[5] = f;
    input.projection[10] = (far_plane + n) / (n - far_plane);
    input.projection[11] = -1.0f;
    input.projection[14] = 2.0f * far_plane * n / (n - far_plane);
    return input;
}

template <class Enum>
void store_raw(Enum* field, int32_t value) {
    std::memcpy(field, &value, sizeof value);
}

TEST(ValidationFields, ValidInputDecodesWithoutGl) {
    obscura::FrameInput frame;
    const obscura_input input = valid_input();
    ASSERT_FALSE(obscura::check_input_fields(input, kMaxTextureSize, &frame));
    EXPECT_EQ(frame.width, 352);
    EXPECT_EQ(frame.height, 198);
    // A zero rectangle means the whole texture; meters_to_view_units 0 means 1.
    EXPECT_EQ(frame.output_rect.width, 352);
    EXPECT_EQ(frame.output_rect.height, 198);
    EXPECT_EQ(frame.meters_to_view_units, 1.0f);
    EXPECT_FALSE(frame.depth_linear);
    EXPECT_EQ(frame.depth_texture, 7u);
}

TEST(ValidationFields, EachBadFieldHasItsStatus) {
    obscura::FrameInput frame;
    obscura_input input = valid_input();
    input.depth_width = 0;
    EXPECT_EQ(obscura::check_input_fields(input, kMaxTextureSize, &frame).status(), OBSCURA_STATUS_INVALID_SIZE);
    input = valid_input();
    input.depth_width = kMaxTextureSize + 1;
    EXPECT_EQ(obscura::check_input_fields(input, kMaxTextureSize, &frame).status(), OBSCURA_STATUS_INVALID_SIZE);
    input = valid_input();
    input.output_rect = {300, 0, 100, 10};  // past the right edge
    EXPECT_EQ(obscura::check_input_fields(input, kMaxTextureSize, &frame).status(), OBSCURA_STATUS_INVALID_RECT);
    input = valid_input();
    store_raw(&input.depth_kind, 9);
    EXPECT_EQ(obscura::check_input_fields(input, kMaxTextureSize, &frame).status(), OBSCURA_STATUS_INVALID_ENUM);
    input = valid_input();
    input.meters_to_view_units = -1.0f;
    EXPECT_EQ(obscura::check_input_fields(input, kMaxTextureSize, &frame).status(), OBSCURA_STATUS_INVALID_SETTING);
    input = valid_input();
    std::memset(input.projection, 0, sizeof input.projection);
    EXPECT_EQ(obscura::check_input_fields(input, kMaxTextureSize, &frame).status(), OBSCURA_STATUS_INVALID_PROJECTION);
    input = valid_input();
    std::swap(input.projection[11], input.projection[14]);  // row-major given as column-major
    EXPECT_EQ(obscura::check_input_fields(input, kMaxTextureSize, &frame).status(),
              OBSCURA_STATUS_PROJECTION_TRANSPOSED);
}

TEST(ValidationFields, OutputFields) {
    obscura_output output;
    std::memset(&output, 0, sizeof output);
    output.struct_size = sizeof output;
    output.x = 3;
    output.y = 4;
    obscura::OutputTarget target;
    ASSERT_FALSE(obscura::check_output_fields(output, &target));
    EXPECT_EQ(target.x, 3);
    EXPECT_EQ(target.y, 4);
    store_raw(&output.blend, 5);
    EXPECT_EQ(obscura::check_output_fields(output, &target).status(), OBSCURA_STATUS_INVALID_ENUM);
    store_raw(&output.blend, 0);
    store_raw(&output.debug_view, OBSCURA_DEBUG_TAP_COUNT + 1);
    EXPECT_EQ(obscura::check_output_fields(output, &target).status(), OBSCURA_STATUS_INVALID_ENUM);
    store_raw(&output.debug_view, 0);
    output.x = -1;
    EXPECT_EQ(obscura::check_output_fields(output, &target).status(), OBSCURA_STATUS_INVALID_RECT);
}

}  // namespace
