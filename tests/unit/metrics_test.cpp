// Image error metrics and the JSON writer of samples/common (obscura_samples_metrics): no GL.
// Every expected value is worked out by hand in the comment next to it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "json_writer.h"
#include "metrics.h"

namespace {

using obscura::samples::compare_images;
using obscura::samples::contact_sheet;
using obscura::samples::error_heat_map;
using obscura::samples::ErrorMetrics;
using obscura::samples::flicker;
using obscura::samples::FloatImage;
using obscura::samples::JsonWriter;
using obscura::samples::thickness_classes;
using obscura::samples::ThicknessClass;
using obscura::samples::WindowMinimum;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

FloatImage make_image(int width, int height, std::vector<float> pixels, int channels = 1) {
    FloatImage image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.pixels = std::move(pixels);
    return image;
}

FloatImage constant_image(int width, int height, float value, int channels = 1) {
    return make_image(width, height, std::vector<float>(size_t(width) * size_t(height) * size_t(channels), value),
                      channels);
}

// RGB of pixel (x, y), y counted from the bottom row.
std::vector<float> rgb_at(const FloatImage& image, int x, int y) {
    return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

// ---- compare_images ----------------------------------------------------------------------------------

TEST(CompareImages, IdenticalImagesHaveNoErrorAndInfinitePsnr) {
    const FloatImage image = make_image(2, 2, {0.1f, 0.2f, 0.9f, 1.0f});
    const ErrorMetrics m = compare_images(image, image);
    EXPECT_EQ(m.pixels, 4u);
    EXPECT_EQ(m.mean_abs, 0.0);
    EXPECT_EQ(m.max_abs, 0.0);
    EXPECT_EQ(m.within_5pct, 1.0);
    EXPECT_EQ(m.over_threshold, 0.0);
    EXPECT_TRUE(std::isinf(m.psnr) && m.psnr > 0.0);
}

TEST(CompareImages, ConstantOffset) {
    // Every pixel off by 0.125 (exact in float): e_A = max = 0.125, MSE = 1/64, PSNR = 10 log10(64).
    const FloatImage reference = make_image(2, 2, {0.25f, 0.5f, 0.75f, 0.125f});
    const FloatImage image = make_image(2, 2, {0.375f, 0.625f, 0.875f, 0.25f});
    const ErrorMetrics m = compare_images(image, reference);
    EXPECT_EQ(m.mean_abs, 0.125);
    EXPECT_EQ(m.max_abs, 0.125);
    EXPECT_NEAR(m.psnr, 18.061799739838872, 1e-12);
    EXPECT_EQ(m.within_5pct, 0.0);
    EXPECT_EQ(m.over_threshold, 1.0);
    // Symmetric.
    const ErrorMetrics swapped = compare_images(reference, image);
    EXPECT_EQ(swapped.mean_abs, m.mean_abs);
    EXPECT_EQ(swapped.psnr, m.psnr);
}

// mean_signed leaves non-finite pixels out, and says over how many it is taken: a pooled mean (obscura compare's
// per-class figures over frames) weighs it by that count, not by all pixels (one NaN pixel doubled a class's +0.1).
TEST(CompareImages, SignedMeanCountsItsFinitePixels) {
    const FloatImage reference = make_image(2, 1, {0.5f, 0.5f});
    const FloatImage image = make_image(2, 1, {0.6f, std::numeric_limits<float>::quiet_NaN()});
    const ErrorMetrics m = compare_images(image, reference);
    EXPECT_EQ(m.pixels, 2u);
    EXPECT_EQ(m.signed_pixels, 1u);
    EXPECT_NEAR(m.mean_signed, 0.1, 1e-6);
}

TEST(CompareImages, FivePercentBoundaryIsInclusive) {
    // Errors 0.05, 0.05 (within), 0.0501, 0.0501 (outside): e_<5% = 1/2.
    const FloatImage reference = constant_image(4, 1, 0.5f);
    const FloatImage image = make_image(4, 1, {0.55f, 0.45f, 0.5501f, 0.4499f});
    const ErrorMetrics m = compare_images(image, reference);
    EXPECT_DOUBLE_EQ(m.within_5pct, 0.5);
    EXPECT_NEAR(m.mean_abs, (0.05 + 0.05 + 0.0501 + 0.0501) / 4.0, 1e-7);
}

TEST(CompareImages, ThresholdCountsPixelsOffByMore) {
    // 8-bit levels: 4 steps off is not "more than 4/255", 5 steps is. One of four pixels is over.
    const FloatImage reference = make_image(4, 1, {100 / 255.0f, 100 / 255.0f, 100 / 255.0f, 100 / 255.0f});
    const FloatImage image = make_image(4, 1, {104 / 255.0f, 96 / 255.0f, 105 / 255.0f, 100 / 255.0f});
    EXPECT_DOUBLE_EQ(compare_images(image, reference).over_threshold, 0.25);
    EXPECT_DOUBLE_EQ(compare_images(image, reference, nullptr, 0.0).over_threshold, 0.75);
}

TEST(CompareImages, MaskSelectsPixels) {
    // Only pixels 0 and 2 compared: errors 0.1 and 0.3, e_A = 0.2; the 0.9 error of pixel 1 is ignored.
    const FloatImage reference = constant_image(3, 1, 0.0f);
    const FloatImage image = make_image(3, 1, {0.1f, 0.9f, 0.3f});
    const std::vector<uint8_t> mask = {1, 0, 255};
    const ErrorMetrics m = compare_images(image, reference, &mask);
    EXPECT_EQ(m.pixels, 2u);
    EXPECT_NEAR(m.mean_abs, 0.2, 1e-7);
    EXPECT_NEAR(m.max_abs, 0.3, 1e-7);
}

TEST(CompareImages, EmptyMaskComparesNothing) {
    const FloatImage reference = constant_image(2, 1, 0.0f);
    const FloatImage image = constant_image(2, 1, 1.0f);
    const std::vector<uint8_t> mask = {0, 0};
    const ErrorMetrics m = compare_images(image, reference, &mask);
    EXPECT_EQ(m.pixels, 0u);
    EXPECT_EQ(m.mean_abs, 0.0);
    EXPECT_EQ(m.within_5pct, 1.0);
    EXPECT_TRUE(std::isinf(m.psnr));
}

TEST(CompareImages, MaskOfWrongSizeThrows) {
    const FloatImage image = constant_image(2, 2, 0.5f);
    const std::vector<uint8_t> mask = {1, 1, 1};
    EXPECT_THROW(compare_images(image, image, &mask), std::invalid_argument);
}

TEST(CompareImages, NonFinitePixelsCountAsErrorOne) {
    // One NaN pixel in the image, one infinite in the reference, two equal: e_A = 2/4, max 1, MSE 1/2.
    const FloatImage reference = make_image(4, 1, {0.5f, kInf, 0.5f, 0.5f});
    const FloatImage image = make_image(4, 1, {kNaN, 0.5f, 0.5f, 0.5f});
    const ErrorMetrics m = compare_images(image, reference);
    EXPECT_DOUBLE_EQ(m.mean_abs, 0.5);
    EXPECT_EQ(m.max_abs, 1.0);
    EXPECT_DOUBLE_EQ(m.within_5pct, 0.5);
    EXPECT_NEAR(m.psnr, 10.0 * std::log10(2.0), 1e-12);
    // Even NaN against NaN is an error: a broken pixel is never "equal".
    const FloatImage nan = constant_image(1, 1, kNaN);
    EXPECT_EQ(compare_images(nan, nan).mean_abs, 1.0);
}

TEST(CompareImages, SizeMismatchThrows) {
    EXPECT_THROW(compare_images(constant_image(2, 2, 0.0f), constant_image(2, 3, 0.0f)), std::invalid_argument);
    EXPECT_THROW(compare_images(constant_image(2, 2, 0.0f), constant_image(2, 2, 0.0f, 3)), std::invalid_argument);
    FloatImage short_of_pixels = constant_image(2, 2, 0.0f);
    short_of_pixels.pixels.pop_back();
    EXPECT_THROW(compare_images(short_of_pixels, short_of_pixels), std::invalid_argument);
}

TEST(CompareImages, SeveralChannelsUseTheLargestChannelError) {
    // Channel errors 0.1, 0.3, 0.2 -> pixel error 0.3.
    const FloatImage reference = constant_image(1, 1, 0.5f, 3);
    const FloatImage image = make_image(1, 1, {0.6f, 0.2f, 0.7f}, 3);
    EXPECT_NEAR(compare_images(image, reference).mean_abs, 0.3, 1e-7);
}

// ---- luminance, quantize_8bit ----------------------------------------------------------------------

TEST(Luminance, MeanOfRgbAlphaIgnored) {
    const FloatImage rgba = make_image(2, 1, {0.3f, 0.6f, 0.9f, 0.0f, 1.0f, 1.0f, 1.0f, 0.5f}, 4);
    const FloatImage gray = obscura::samples::luminance(rgba);
    ASSERT_EQ(gray.channels, 1);
    ASSERT_EQ(gray.pixels.size(), 2u);
    EXPECT_NEAR(gray.pixels[0], 0.6f, 1e-6f);
    EXPECT_EQ(gray.pixels[1], 1.0f);
    const FloatImage one = constant_image(2, 2, 0.25f);
    EXPECT_EQ(obscura::samples::luminance(one).pixels, one.pixels);
    EXPECT_THROW(obscura::samples::luminance(constant_image(1, 1, 0.0f, 2)), std::invalid_argument);
}

TEST(Quantize8Bit, RoundsClampsAndKeepsNaN) {
    const FloatImage q = obscura::samples::quantize_8bit(make_image(4, 1, {0.5f, -1.0f, 2.0f, kNaN}));
    EXPECT_EQ(q.pixels[0], 128 / 255.0f);  // 127.5 rounds half away from zero
    EXPECT_EQ(q.pixels[1], 0.0f);
    EXPECT_EQ(q.pixels[2], 1.0f);
    EXPECT_TRUE(std::isnan(q.pixels[3]));
}

// ---- error_heat_map ----------------------------------------------------------------------------------

TEST(ErrorHeatMap, ColoursFromWhiteToBlack) {
    // Errors 0, 0.2/3, 0.4/3, 0.2 (full scale), 0.5 (beyond), NaN with the default full scale 0.2.
    const FloatImage reference = constant_image(6, 1, 0.0f);
    const FloatImage image = make_image(6, 1, {0.0f, 0.2f / 3.0f, 0.4f / 3.0f, 0.2f, 0.5f, kNaN});
    const FloatImage heat = error_heat_map(image, reference);
    ASSERT_EQ(heat.channels, 3);
    ASSERT_EQ(heat.width, 6);
    ASSERT_EQ(heat.height, 1);
    const auto near = [](const std::vector<float>& actual, const std::vector<float>& expected) {
        for (size_t i = 0; i < 3; ++i) {
            if (std::fabs(actual[i] - expected[i]) > 1e-5f) return false;
        }
        return true;
    };
    EXPECT_TRUE(near(rgb_at(heat, 0, 0), {1, 1, 1}));  // white: no error
    EXPECT_TRUE(near(rgb_at(heat, 1, 0), {1, 1, 0}));  // yellow at a third
    EXPECT_TRUE(near(rgb_at(heat, 2, 0), {1, 0, 0}));  // red at two thirds
    EXPECT_TRUE(near(rgb_at(heat, 3, 0), {0, 0, 0}));  // black at full scale
    EXPECT_TRUE(near(rgb_at(heat, 4, 0), {0, 0, 0}));  // and beyond
    EXPECT_TRUE(near(rgb_at(heat, 5, 0), {0, 0, 0}));  // NaN: error 1
}

TEST(ErrorHeatMap, FullScaleIsAParameter) {
    // Error 0.05 at full scale 0.1 is half way: between yellow (1/3) and red (2/3), green 0.5.
    const FloatImage heat = error_heat_map(constant_image(1, 1, 0.55f), constant_image(1, 1, 0.5f), 0.1);
    EXPECT_EQ(heat.at(0, 0, 0), 1.0f);
    EXPECT_NEAR(heat.at(0, 0, 1), 0.5f, 1e-5f);
    EXPECT_EQ(heat.at(0, 0, 2), 0.0f);
    EXPECT_THROW(error_heat_map(constant_image(1, 1, 0.0f), constant_image(1, 1, 0.0f), 0.0), std::invalid_argument);
}

// ---- flicker --------------------------------------------------------------------------------------

TEST(Flicker, IdenticalMotionIsZeroWhateverTheOffset) {
    // The method is the reference plus a constant 0.1: every frame-to-frame change matches.
    std::vector<FloatImage> reference, method;
    for (int f = 0; f < 4; ++f) {
        reference.push_back(make_image(2, 1, {0.1f * float(f), 0.5f}));
        method.push_back(make_image(2, 1, {0.1f * float(f) + 0.125f, 0.625f}));
    }
    EXPECT_NEAR(flicker(method, reference), 0.0, 1e-7);
}

TEST(Flicker, MeasuresChangeTheReferenceDoesNotHave) {
    // Reference still; the method's first pixel alternates 0.5, 0.75, 0.5: |0.25| per pair on one of
    // two pixels -> mean 0.125.
    const std::vector<FloatImage> reference(3, constant_image(2, 1, 0.5f));
    const std::vector<FloatImage> method = {make_image(2, 1, {0.5f, 0.5f}), make_image(2, 1, {0.75f, 0.5f}),
                                            make_image(2, 1, {0.5f, 0.5f})};
    EXPECT_DOUBLE_EQ(flicker(method, reference), 0.125);
}

// With masks only the pixels seen in both frames of a pair count: the sky (still in both) no longer waters
// the flicker down.
TEST(Flicker, MasksLeaveOutPixelsNotSeenInBothFrames) {
    const std::vector<FloatImage> reference(3, constant_image(2, 1, 0.5f));
    const std::vector<FloatImage> method = {make_image(2, 1, {0.5f, 1.0f}), make_image(2, 1, {0.75f, 1.0f}),
                                            make_image(2, 1, {0.5f, 1.0f})};
    const std::vector<std::vector<uint8_t>> geometry_then_sky(3, std::vector<uint8_t>{1, 0});
    EXPECT_DOUBLE_EQ(flicker(method, reference, &geometry_then_sky), 0.25);  // 0.125 over both pixels
    // The first pixel is sky in the middle frame: no pair sees it in both frames, nothing is counted.
    const std::vector<std::vector<uint8_t>> gone = {{1, 0}, {0, 0}, {1, 0}};
    EXPECT_DOUBLE_EQ(flicker(method, reference, &gone), 0.0);
    const std::vector<std::vector<uint8_t>> too_few(2, std::vector<uint8_t>{1, 1});
    EXPECT_THROW(flicker(method, reference, &too_few), std::invalid_argument);
    const std::vector<std::vector<uint8_t>> wrong_size(3, std::vector<uint8_t>{1});
    EXPECT_THROW(flicker(method, reference, &wrong_size), std::invalid_argument);
}

TEST(Flicker, NeedsMatchingFrameLists) {
    const std::vector<FloatImage> two(2, constant_image(2, 1, 0.5f));
    const std::vector<FloatImage> three(3, constant_image(2, 1, 0.5f));
    EXPECT_THROW(flicker(two, three), std::invalid_argument);
    EXPECT_THROW(flicker({two[0]}, {two[0]}), std::invalid_argument);
    EXPECT_THROW(flicker(two, {two[0], constant_image(1, 1, 0.5f)}), std::invalid_argument);
}

// ---- frames_since_event, error_by_age ----------------------------------------------------------------

TEST(Ghosting, FramesSinceEventCountUpWhileAliveAndRestartAtEachEvent) {
    using obscura::samples::frames_since_event;
    // Pixel 0: event in frame 1, then alive: 0 1 2 (and -1 before). Pixel 1: event in 0, dies in 2, alive again in 3
    // without an event: -1 from the death on. Pixel 2: events in 0 and 2: 0 1 0 1.
    const std::vector<std::vector<uint8_t>> event = {{0, 1, 1}, {1, 0, 0}, {0, 0, 1}, {0, 0, 0}};
    const std::vector<std::vector<uint8_t>> alive = {{1, 1, 1}, {1, 1, 1}, {1, 0, 1}, {1, 1, 1}};
    const std::vector<std::vector<int>> ages = frames_since_event(event, alive);
    ASSERT_EQ(ages.size(), 4u);
    EXPECT_EQ(ages[0], (std::vector<int>{-1, 0, 0}));
    EXPECT_EQ(ages[1], (std::vector<int>{0, 1, 1}));
    EXPECT_EQ(ages[2], (std::vector<int>{1, -1, 0}));
    EXPECT_EQ(ages[3], (std::vector<int>{2, -1, 1}));
    // An event where the pixel is not alive does not count.
    EXPECT_EQ(frames_since_event({{1}}, {{0}})[0], std::vector<int>{-1});
    EXPECT_THROW(frames_since_event({{1}}, {{1}, {1}}), std::invalid_argument);
    EXPECT_THROW(frames_since_event({{1, 0}}, {{1}}), std::invalid_argument);
}

TEST(Ghosting, ErrorByAgePoolsTheOldestAgesAndComparesWithTheConvergedImages) {
    using obscura::samples::error_by_age;
    // Two frames of 3 pixels. Ages: frame 0 {0, -1, 5}, frame 1 {1, 2, 6}; max_age 2 -> buckets 0, 1, >=2.
    const std::vector<FloatImage> truth(2, constant_image(3, 1, 0.5f));
    const std::vector<FloatImage> frames = {make_image(3, 1, {0.7f, 0.0f, 0.5f}), make_image(3, 1, {0.6f, 0.25f, 0.75f})};
    const std::vector<FloatImage> converged = {make_image(3, 1, {0.5f, 0.0f, 0.5f}), make_image(3, 1, {0.55f, 0.5f, 0.5f})};
    const std::vector<std::vector<int>> ages = {{0, -1, 5}, {1, 2, 6}};
    const std::vector<obscura::samples::AgeErrors> buckets = error_by_age(frames, converged, truth, ages, 2);
    ASSERT_EQ(buckets.size(), 3u);
    EXPECT_EQ(buckets[0].pixels, 1u);  // |0.7 - 0.5|, converged 0
    EXPECT_NEAR(buckets[0].mean_abs, 0.2, 1e-6);
    EXPECT_NEAR(buckets[0].converged_mean_abs, 0.0, 1e-6);
    EXPECT_EQ(buckets[1].pixels, 1u);  // |0.6 - 0.5|, converged |0.55 - 0.5|
    EXPECT_NEAR(buckets[1].mean_abs, 0.1, 1e-6);
    EXPECT_NEAR(buckets[1].converged_mean_abs, 0.05, 1e-6);
    EXPECT_EQ(buckets[2].pixels, 3u);  // ages 5, 2 and 6: (0 + 0.25 + 0.25) / 3, converged (0 + 0 + 0) / 3
    EXPECT_NEAR(buckets[2].mean_abs, 0.5 / 3.0, 1e-6);
    EXPECT_NEAR(buckets[2].converged_mean_abs, 0.0, 1e-6);
    // An empty bucket stays 0; mismatched inputs are refused.
    EXPECT_EQ(error_by_age(frames, converged, truth, {{-1, -1, -1}, {-1, -1, -1}}, 2)[0].pixels, 0u);
    EXPECT_THROW(error_by_age(frames, converged, truth, {{0, 0, 0}}, 2), std::invalid_argument);
    EXPECT_THROW(error_by_age(frames, converged, truth, {{0, 0}, {0, 0}}, 2), std::invalid_argument);
    EXPECT_THROW(error_by_age(frames, converged, truth, ages, -1), std::invalid_argument);
}

// ---- surface_flicker -------------------------------------------------------------------------------

// A wall 4 m in front of a camera looking down -z (a plain perspective, 90 degrees, no guard band) seen in 8x8 pixels:
// one pixel is 1 m wide there.
obscura::samples::FrameGeometry wall_frame(double camera_x) {
    obscura::samples::FrameGeometry frame;
    frame.view_depth = constant_image(8, 8, 4.0f);
    frame.view = glm::dmat4(1.0);
    frame.view[3][0] = -camera_x;  // world -> view: the camera at (camera_x, 0, 0)
    const double n = 0.1, f = 100.0;
    frame.projection = glm::dmat4(0.0);
    frame.projection[0][0] = 1.0;
    frame.projection[1][1] = 1.0;
    frame.projection[2][2] = -(f + n) / (f - n);
    frame.projection[2][3] = -1.0;
    frame.projection[3][2] = -2.0 * f * n / (f - n);
    frame.depth_width = 8;
    frame.depth_height = 8;
    return frame;
}

TEST(SurfaceFlicker, FollowsTheSurfaceAcrossACameraMove) {
    using obscura::samples::surface_flicker;
    // AO painted on the wall (a ramp in world x): the camera moves one metre (one pixel) to the right, so the image
    // moves one pixel to the left and every surface point keeps its value: 0, while the per-pixel change is 0.1.
    std::vector<float> ramp(64), shifted(64);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
            ramp[size_t(y * 8 + x)] = 0.1f * float(x);
            shifted[size_t(y * 8 + x)] = 0.1f * float(x + 1);
        }
    }
    const std::vector<FloatImage> frames = {make_image(8, 8, ramp), make_image(8, 8, shifted)};
    EXPECT_NEAR(surface_flicker(frames, {wall_frame(0.0), wall_frame(1.0)}).value_or(-1.0), 0.0, 1e-6);
    // A still camera: the plain mean change, 0.1 per pixel.
    EXPECT_NEAR(surface_flicker(frames, {wall_frame(0.0), wall_frame(0.0)}).value_or(-1.0), 0.1, 1e-6);
    // Where the previous frame saw another surface (its depth 10 % off) nothing counts: nothing was measured.
    obscura::samples::FrameGeometry farther = wall_frame(0.0);
    farther.view_depth = constant_image(8, 8, 4.4f);
    EXPECT_FALSE(surface_flicker(frames, {farther, wall_frame(0.0)}).has_value());
    // Sky does not count either.
    obscura::samples::FrameGeometry sky = wall_frame(0.0);
    sky.view_depth = constant_image(8, 8, 0.0f);
    EXPECT_FALSE(surface_flicker(frames, {wall_frame(0.0), sky}).has_value());
    EXPECT_THROW(surface_flicker({frames[0]}, {wall_frame(0.0)}), std::invalid_argument);
    EXPECT_THROW(surface_flicker(frames, {wall_frame(0.0)}), std::invalid_argument);
}

// A still camera lands every point on its own texel, with bilinear weight 0 on the texels beside it: those may lie on
// another surface (here every other column is 10 % deeper, like a slanted floor's rows at low resolution) and do not
// decide whether the point was seen. Until 2026-12-06 all four texels had to match, so such a view measured nothing
// and reported 0, "no flicker" (found by a review: the room at 16x9).
TEST(SurfaceFlicker, TexelsWithoutWeightDoNotDecide) {
    using obscura::samples::surface_flicker;
    std::vector<float> depth(64), before(64, 0.5f), after(64, 0.6f);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) depth[size_t(y * 8 + x)] = x % 2 == 0 ? 4.0f : 4.4f;
    }
    obscura::samples::FrameGeometry frame = wall_frame(0.0);
    frame.view_depth = make_image(8, 8, depth);
    const std::vector<FloatImage> frames = {make_image(8, 8, before), make_image(8, 8, after)};
    const std::optional<double> flicker = surface_flicker(frames, {frame, frame});
    ASSERT_TRUE(flicker.has_value()) << "a still camera follows every geometry pixel";
    EXPECT_NEAR(*flicker, 0.1, 1e-6);
}

TEST(SurfaceFlicker, FollowsAMovingPartToWhereItWas) {
    using obscura::samples::surface_flicker;
    // A still camera; the wall's left half (x < 4) is a part that slides one metre (one pixel) to the right between
    // the frames, carrying its AO with it (a ramp in its own x): at frame 1 its pixels x = 1..4 show what pixels
    // 0..3 showed. Followed back, its points keep their values; the right half is still and unchanged.
    std::vector<float> before(64), after(64);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
            before[size_t(y * 8 + x)] = x < 4 ? 0.1f * float(x) : 0.9f;
            after[size_t(y * 8 + x)] = x >= 1 && x <= 4 ? 0.1f * float(x - 1) : x == 0 ? 0.0f : 0.9f;
        }
    }
    const std::vector<FloatImage> frames = {make_image(8, 8, before), make_image(8, 8, after)};
    obscura::samples::FrameGeometry moved = wall_frame(0.0);
    moved.moving.assign(64, 0);
    for (int y = 0; y < 8; ++y) {
        for (int x = 1; x <= 4; ++x) moved.moving[size_t(y * 8 + x)] = 1;
    }
    moved.motion = glm::dvec3(1.0, 0.0, 0.0);
    // Pixel 4 of the moving part came from pixel 3 (0.3), where the still wall (0.9) is now; pixel 0, uncovered,
    // is given the value the part had there (the same depth: the test cannot tell it was hidden).
    EXPECT_NEAR(surface_flicker(frames, {wall_frame(0.0), moved}).value_or(-1.0), 0.0, 1e-6);
    // Without the motion the moving pixels are compared with what was at their place: 0.1 each (and 0.6 at x = 4).
    EXPECT_GT(surface_flicker(frames, {wall_frame(0.0), wall_frame(0.0)}).value_or(-1.0), 0.05);
    moved.moving.resize(10);
    EXPECT_THROW(surface_flicker(frames, {wall_frame(0.0), moved}), std::invalid_argument);
}

// A crease within the depth tolerance: the wall's left half (world x < 0) faces +z, its right half +x (a fold seen
// head-on, every pixel at the same depth), and each face has its own constant AO, 0.2 and 0.8: a view-independent
// image. The camera moves a quarter metre: frame 1's pixel 3 (world x = -0.25) lies between frame 0's texels 3 and 4,
// one on each face, so reading across the fold measured 0.15 there. With normals the fold's other face does not count
// as the point's surface, and what remains is the truth's 0; without them the old figure, 0.15 / 7 per row.
TEST(SurfaceFlicker, ACreaseIsNotOneSurface) {
    using obscura::samples::surface_flicker;
    std::vector<float> values(64);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) values[size_t(y * 8 + x)] = x < 4 ? 0.2f : 0.8f;
    }
    const std::vector<FloatImage> frames = {make_image(8, 8, values), make_image(8, 8, values)};
    obscura::samples::FrameGeometry before = wall_frame(0.0), after = wall_frame(0.25);
    EXPECT_NEAR(surface_flicker(frames, {before, after}).value_or(-1.0), 0.15 / 7.0, 1e-6);
    for (obscura::samples::FrameGeometry* frame : {&before, &after}) {
        frame->normal.resize(64);
        for (int y = 0; y < 8; ++y) {
            for (int x = 0; x < 8; ++x) frame->normal[size_t(y * 8 + x)] = x < 4 ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
        }
    }
    EXPECT_NEAR(surface_flicker(frames, {before, after}).value_or(-1.0), 0.0, 1e-9);
    // Facets of one curved surface (here 30 degrees apart) and a face seen from behind stay one surface.
    for (int y = 0; y < 8; ++y) {
        for (int x = 4; x < 8; ++x) {
            before.normal[size_t(y * 8 + x)] = glm::vec3(0.5f, 0.0f, -0.8660254f);
            after.normal[size_t(y * 8 + x)] = glm::vec3(0.5f, 0.0f, -0.8660254f);
        }
    }
    EXPECT_NEAR(surface_flicker(frames, {before, after}).value_or(-1.0), 0.15 / 7.0, 1e-6);
    before.normal.resize(10);
    EXPECT_THROW(surface_flicker(frames, {before, after}), std::invalid_argument);
}

// ---- frames_since_disocclusion ---------------------------------------------------------------------------

TEST(FramesSinceDisocclusion, CountsFromWhereAPointCameIntoView) {
    using obscura::samples::frames_since_disocclusion;
    // The camera moves one metre (one pixel) to the right per frame: a new column of the wall enters on the right
    // each frame (age 0), and the one that entered a frame before is one frame old; what frame 0 saw has no event.
    const std::vector<std::vector<int>> ages =
        frames_since_disocclusion({wall_frame(0.0), wall_frame(1.0), wall_frame(2.0)});
    ASSERT_EQ(ages.size(), 3u);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
            const size_t i = size_t(y * 8 + x);
            EXPECT_EQ(ages[0][i], -1);
            EXPECT_EQ(ages[1][i], x == 7 ? 0 : -1) << x << ", " << y;
            EXPECT_EQ(ages[2][i], x == 7 ? 0 : x == 6 ? 1 : -1) << x << ", " << y;
        }
    }
    // A point the previous frame saw at another depth (something in front of it there) came into view: 0; sky
    // has no age.
    obscura::samples::FrameGeometry nearer = wall_frame(0.0);
    nearer.view_depth = constant_image(8, 8, 3.0f);
    obscura::samples::FrameGeometry sky = wall_frame(0.0);
    sky.view_depth = constant_image(8, 8, 0.0f);
    const std::vector<std::vector<int>> uncovered = frames_since_disocclusion({nearer, wall_frame(0.0), sky});
    for (size_t i = 0; i < 64; ++i) {
        EXPECT_EQ(uncovered[1][i], 0);
        EXPECT_EQ(uncovered[2][i], -1);
    }
    EXPECT_TRUE(frames_since_disocclusion({}).empty());
}

// ---- contact_sheet -----------------------------------------------------------------------------------

TEST(ContactSheet, GridSize) {
    // Three 10x8 images in 2 columns: 2 rows; gaps of 4 around and between cells.
    const std::vector<FloatImage> images(3, constant_image(10, 8, 1.0f));
    const FloatImage sheet = contact_sheet(images, {}, 2);
    EXPECT_EQ(sheet.channels, 3);
    EXPECT_EQ(sheet.width, 2 * 10 + 3 * 4);
    EXPECT_EQ(sheet.height, 2 * 8 + 3 * 4);
    EXPECT_EQ(sheet.pixels.size(), size_t(sheet.width) * size_t(sheet.height) * 3);
    // columns <= 0: a single row.
    EXPECT_EQ(contact_sheet(images, {}, 0).width, 3 * 10 + 4 * 4);
}

TEST(ContactSheet, LabelsAddAStripUnderEachRow) {
    // Cells narrower than 256: 1 pixel per font pixel, strip of 7 + 4.
    const std::vector<FloatImage> images(3, constant_image(10, 8, 0.0f));
    const FloatImage sheet = contact_sheet(images, {"a", "b", "c"}, 2);
    EXPECT_EQ(sheet.height, 2 * (8 + 11) + 3 * 4);
    // Ink (white) appears only in the label strips: the images are black, the background grey.
    int ink = 0;
    for (size_t i = 0; i < sheet.pixels.size(); i += 3) ink += sheet.pixels[i] == 1.0f;
    EXPECT_GT(ink, 3 * 10);
    // Cells of 256 pixels and more get double-size labels: strip of 14 + 4.
    const FloatImage wide = contact_sheet({constant_image(256, 2, 0.0f)}, {"x"}, 1);
    EXPECT_EQ(wide.height, 2 + 18 + 2 * 4);
}

TEST(ContactSheet, FirstImageAtTopLeftUpright) {
    // A 2x2 gray image whose top row is white: the sheet's top-left cell shows it the same way up.
    const FloatImage image = make_image(2, 2, {0.0f, 0.0f, 1.0f, 1.0f});  // rows bottom-up
    const FloatImage sheet = contact_sheet({image, constant_image(2, 2, 0.5f, 3)}, {}, 1);
    ASSERT_EQ(sheet.height, 2 * 2 + 3 * 4);
    const int top = sheet.height - 1 - 4;  // first cell's top row, counted from the bottom
    EXPECT_EQ(rgb_at(sheet, 4, top), (std::vector<float>{1, 1, 1}));
    EXPECT_EQ(rgb_at(sheet, 4, top - 1), (std::vector<float>{0, 0, 0}));
    EXPECT_EQ(rgb_at(sheet, 4, 4), (std::vector<float>{0.5f, 0.5f, 0.5f}));  // second cell, bottom row
    EXPECT_EQ(rgb_at(sheet, 0, 0), (std::vector<float>{0.2f, 0.2f, 0.2f}));   // background
}

TEST(ContactSheet, RejectsBadInput) {
    const FloatImage image = constant_image(2, 2, 0.0f);
    EXPECT_THROW(contact_sheet({}, {}, 1), std::invalid_argument);
    EXPECT_THROW(contact_sheet({image, image}, {"one"}, 1), std::invalid_argument);
    EXPECT_THROW(contact_sheet({constant_image(2, 2, 0.0f, 2)}, {}, 1), std::invalid_argument);
}

// ---- JsonWriter ------------------------------------------------------------------------------------

TEST(JsonWriter, NestedDocument) {
    JsonWriter json;
    json.begin_object().field("a", 1).key("b").begin_array().value(0.5).value("x\"y").null().end_array();
    json.key("c").begin_object().end_object().field("d", true).field("n", size_t(7)).end_object();
    EXPECT_EQ(json.str(),
              "{\n"
              "  \"a\": 1,\n"
              "  \"b\": [\n"
              "    0.5,\n"
              "    \"x\\\"y\",\n"
              "    null\n"
              "  ],\n"
              "  \"c\": {},\n"
              "  \"d\": true,\n"
              "  \"n\": 7\n"
              "}");
}

TEST(JsonWriter, EscapesStrings) {
    EXPECT_EQ(JsonWriter::quote("a\\b\n\t\x01 \xc3\xa9"), "\"a\\\\b\\n\\t\\u0001 \xc3\xa9\"");
}

TEST(JsonWriter, NumbersShortestAndNonFiniteAsNull) {
    JsonWriter json;
    json.begin_array().value(0.1).value(-2.5e-7).value(std::numeric_limits<double>::infinity());
    json.value(std::nan("")).value(-3).end_array();
    EXPECT_EQ(json.str(), "[\n  0.1,\n  -2.5e-07,\n  null,\n  null,\n  -3\n]");
}

TEST(JsonWriter, MisuseThrows) {
    EXPECT_THROW(JsonWriter().key("k"), std::logic_error);
    EXPECT_THROW(JsonWriter().begin_object().value(1), std::logic_error);
    EXPECT_THROW(JsonWriter().begin_array().key("k"), std::logic_error);
    EXPECT_THROW(JsonWriter().begin_array().end_object(), std::logic_error);
    EXPECT_THROW(JsonWriter().begin_object().key("k").end_object(), std::logic_error);
    EXPECT_THROW(JsonWriter().value(1).value(2), std::logic_error);
    EXPECT_THROW(JsonWriter().begin_object().str(), std::logic_error);
}

}  // namespace

// ---- signed_error_map --------------------------------------------------------------------------------

TEST(SignedErrorMap, RedTooDarkBlueTooBright) {
    FloatImage reference;
    reference.width = 4;
    reference.height = 1;
    reference.pixels = {0.5f, 0.5f, 0.5f, 0.5f};
    FloatImage image = reference;
    image.pixels = {0.5f, 0.4f, 0.9f, std::nanf("")};  // equal, darker by half the scale, brighter past it, NaN
    const FloatImage map = obscura::samples::signed_error_map(image, reference, 0.2);
    ASSERT_EQ(map.channels, 3);
    const std::vector<float> expected = {1.0f, 1.0f, 1.0f,   1.0f, 0.5f, 0.5f,   0.0f, 0.0f, 1.0f,   0.0f, 0.0f, 0.0f};
    ASSERT_EQ(map.pixels.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(map.pixels[i], expected[i], 1e-6f) << "sample " << i;
    EXPECT_THROW(obscura::samples::signed_error_map(image, reference, 0.0), std::invalid_argument);
}

namespace {

obscura::samples::FloatImage directions(std::vector<float> xyz, int channels) {
    obscura::samples::FloatImage image;
    image.width = int(xyz.size()) / channels;
    image.height = 1;
    image.channels = channels;
    image.pixels = std::move(xyz);
    return image;
}


TEST(MeanAngle, DegreesBetweenDirectionsOverTheMask) {
    // Pixel 0: the same direction (lengths differ); pixel 1: 90 degrees; pixel 2: 60 degrees, masked out.
    const auto method = directions({0, 0, 2, 0, 0, 1, 0, 0, 1}, 3);
    const auto truth = directions({0, 0, 1, 1, 0, 0, 0, 1, 1.7320508f}, 3);
    EXPECT_NEAR(obscura::samples::mean_angle_degrees(method, truth), (0.0 + 90.0 + 30.0) / 3.0, 1e-4);
    const std::vector<uint8_t> mask = {1, 1, 0};
    EXPECT_NEAR(obscura::samples::mean_angle_degrees(method, truth, &mask), 45.0, 1e-4);
}

TEST(MeanAngle, FourChannelsUseRgbAndBadVectorsCountHalfACircle) {
    // RGBA (the SDK's bent-normal texture: alpha is the visibility) against RGB; a zero vector counts 180.
    const auto method = directions({0, 1, 0, 0.5f, 0, 0, 0, 1}, 4);
    const auto truth = directions({0, 1, 0, 0, 0, 1}, 3);
    EXPECT_NEAR(obscura::samples::mean_angle_degrees(method, truth), 90.0, 1e-4);
    EXPECT_THROW(obscura::samples::mean_angle_degrees(directions({0, 1}, 2), truth), std::invalid_argument);
}

// ---- thickness_classes and WindowMinimum ------------------------------------------------------------------

// A far plane at `far` metres with a near square of `side` pixels at `near` metres whose bottom-left pixel is
// (left, bottom); every pixel is geometry unless a row is made sky afterwards.
struct DepthScene {
    FloatImage depth;
    std::vector<uint8_t> mask;
    DepthScene(int width, int height, float far, float near, int left, int bottom, int side)
        : depth(constant_image(width, height, far)), mask(size_t(width) * size_t(height), 1) {
        for (int y = bottom; y < bottom + side; ++y) {
            for (int x = left; x < left + side; ++x) depth.pixels[size_t(y) * size_t(width) + size_t(x)] = near;
        }
    }
    void make_sky_row(int y) {
        for (int x = 0; x < depth.width; ++x) {
            mask[size_t(y) * size_t(depth.width) + size_t(x)] = 0;
            depth.pixels[size_t(y) * size_t(depth.width) + size_t(x)] = 0.0f;
        }
    }
};

ThicknessClass class_at(const std::vector<uint8_t>& classes, int width, int x, int y) {
    return ThicknessClass(classes[size_t(y) * size_t(width) + size_t(x)]);
}

size_t count_class(const std::vector<uint8_t>& classes, ThicknessClass value) {
    return size_t(std::count(classes.begin(), classes.end(), uint8_t(value)));
}

TEST(ThicknessClasses, NearSquareInFrontOfAFarPlane) {
    // A 64x64 image: far plane at 10 m, an 8x8 square at 5 m over x, y in [28, 35], the top row (y = 63) sky.
    // 40 pixels per metre at 1 m and a 1 m radius: the radius covers floor(40 / 10) = 4 pixels on the far plane.
    DepthScene scene(64, 64, 10.0f, 5.0f, 28, 28, 8);
    scene.make_sky_row(63);
    const std::vector<uint8_t> classes = thickness_classes(scene.depth, scene.mask, 1.0, 0.3, 40.0, 256.0);
    ASSERT_EQ(classes.size(), 64u * 64u);
    // The square's border: a far neighbour 5 m behind (> max(0.1, 0.05 * 5)).
    EXPECT_EQ(class_at(classes, 64, 28, 30), ThicknessClass::Silhouette);
    EXPECT_EQ(class_at(classes, 64, 35, 35), ThicknessClass::Silhouette);
    EXPECT_EQ(class_at(classes, 64, 31, 28), ThicknessClass::Silhouette);
    // The square's 28 border pixels and the 64 of the row under the sky (below).
    EXPECT_EQ(count_class(classes, ThicknessClass::Silhouette), 28u + 64u);
    // Its inside: nothing nearer, no far neighbour.
    EXPECT_EQ(class_at(classes, 64, 29, 29), ThicknessClass::Rest);
    EXPECT_EQ(class_at(classes, 64, 34, 31), ThicknessClass::Rest);
    // The far plane within 4 pixels (Chebyshev distance) of the square: halo; from 5 pixels on: rest.
    EXPECT_EQ(class_at(classes, 64, 27, 30), ThicknessClass::Halo);
    EXPECT_EQ(class_at(classes, 64, 24, 30), ThicknessClass::Halo);
    EXPECT_EQ(class_at(classes, 64, 23, 30), ThicknessClass::Rest);
    EXPECT_EQ(class_at(classes, 64, 39, 39), ThicknessClass::Halo);
    EXPECT_EQ(class_at(classes, 64, 40, 39), ThicknessClass::Rest);
    EXPECT_EQ(class_at(classes, 64, 24, 24), ThicknessClass::Halo);
    EXPECT_EQ(class_at(classes, 64, 23, 24), ThicknessClass::Rest);
    EXPECT_EQ(count_class(classes, ThicknessClass::Halo), 16u * 16u - 8u * 8u);  // the 16x16 footprint less the square
    // Sky is its own class; the far plane's row under it is a silhouette (sky counts as far), the rest of the
    // far plane's border is not (no neighbour outside the image counts).
    EXPECT_EQ(class_at(classes, 64, 10, 63), ThicknessClass::Sky);
    EXPECT_EQ(count_class(classes, ThicknessClass::Sky), 64u);
    EXPECT_EQ(class_at(classes, 64, 10, 62), ThicknessClass::Silhouette);
    EXPECT_EQ(class_at(classes, 64, 0, 0), ThicknessClass::Rest);
    EXPECT_EQ(class_at(classes, 64, 63, 30), ThicknessClass::Rest);
}

TEST(ThicknessClasses, ThicknessThresholdIsRespected) {
    // The square 0.6 m in front of the plane: a silhouette (0.6 > max(0.1, 0.05 * 9.4)), but not thicker than
    // T = 0.7, so no halo; with T = 0.3 its 4-pixel footprint is a halo.
    const DepthScene scene(64, 64, 10.0f, 9.4f, 28, 28, 8);
    const std::vector<uint8_t> thick = thickness_classes(scene.depth, scene.mask, 1.0, 0.7, 40.0, 256.0);
    EXPECT_EQ(count_class(thick, ThicknessClass::Halo), 0u);
    EXPECT_EQ(count_class(thick, ThicknessClass::Silhouette), 28u);
    const std::vector<uint8_t> thin = thickness_classes(scene.depth, scene.mask, 1.0, 0.3, 40.0, 256.0);
    EXPECT_EQ(count_class(thin, ThicknessClass::Halo), 16u * 16u - 8u * 8u);
}

TEST(ThicknessClasses, ARecedingFloorIsNoHaloOfItself) {
    // Depth growing smoothly with y (a floor seen from above it): nearer pixels everywhere in the window, but no
    // depth step, so no silhouette and no halo.
    FloatImage depth = constant_image(48, 48, 0.0f);
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 48; ++x) depth.pixels[size_t(y) * 48u + size_t(x)] = 2.0f + 0.05f * float(y);
    }
    const std::vector<uint8_t> mask(48u * 48u, 1);
    const std::vector<uint8_t> classes = thickness_classes(depth, mask, 1.0, 0.3, 40.0, 256.0);
    EXPECT_EQ(count_class(classes, ThicknessClass::Rest), 48u * 48u);
}

TEST(ThicknessClasses, SilhouetteStepIsTenCentimetresOrFivePercent) {
    // At 1 m the step must exceed 0.1 m; at 10 m, 0.5 m.
    const auto silhouettes = [](float far, float near) {
        const DepthScene scene(16, 16, far, near, 6, 6, 4);
        return count_class(thickness_classes(scene.depth, scene.mask, 1.0, 0.3, 10.0, 256.0), ThicknessClass::Silhouette);
    };
    EXPECT_EQ(silhouettes(1.0f, 0.85f), 12u);  // the square's 12 border pixels
    EXPECT_EQ(silhouettes(1.0f, 0.95f), 0u);
    EXPECT_EQ(silhouettes(10.0f, 9.4f), 12u);
    EXPECT_EQ(silhouettes(10.0f, 9.6f), 0u);
}

TEST(ThicknessClasses, RadiusCapAndPixelsPerMetre) {
    // The radius in pixels shrinks with depth and is capped by max_radius_px.
    const DepthScene scene(64, 64, 10.0f, 5.0f, 28, 28, 8);
    // 20 pixels per metre at 1 m: 2 pixels on the far plane, a 12x12 footprint.
    EXPECT_EQ(count_class(thickness_classes(scene.depth, scene.mask, 1.0, 0.3, 20.0, 256.0), ThicknessClass::Halo),
              12u * 12u - 8u * 8u);
    // A 0.5 m radius at 40 pixels per metre is the same 2 pixels.
    EXPECT_EQ(count_class(thickness_classes(scene.depth, scene.mask, 0.5, 0.3, 40.0, 256.0), ThicknessClass::Halo),
              12u * 12u - 8u * 8u);
    // 4 pixels, capped at 1.
    EXPECT_EQ(count_class(thickness_classes(scene.depth, scene.mask, 1.0, 0.3, 40.0, 1.0), ThicknessClass::Halo),
              10u * 10u - 8u * 8u);
    // Under a pixel: no window, no halo.
    EXPECT_EQ(count_class(thickness_classes(scene.depth, scene.mask, 1.0, 0.3, 9.0, 256.0), ThicknessClass::Halo), 0u);
}

TEST(ThicknessClasses, MatchesABruteForceClassification) {
    // Random depths in [1, 12] m with some sky, classified by the definition pixel by pixel.
    const int width = 37;
    const int height = 23;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> depths(1.0f, 12.0f);
    std::uniform_int_distribution<int> percent(0, 99);
    FloatImage depth = constant_image(width, height, 0.0f);
    std::vector<uint8_t> mask(size_t(width) * size_t(height));
    for (size_t i = 0; i < mask.size(); ++i) {
        mask[i] = percent(random) >= 10;
        depth.pixels[i] = mask[i] ? depths(random) : 0.0f;
    }
    const double radius = 0.7, thickness = 0.3, scale = 30.0, cap = 9.0;
    const std::vector<uint8_t> classes = thickness_classes(depth, mask, radius, thickness, scale, cap);
    const auto far_at = [&](int x, int y) {
        return mask[size_t(y) * size_t(width) + size_t(x)] ? double(depth.at(x, y)) : std::numeric_limits<double>::infinity();
    };
    // First the silhouettes (a 4-neighbour farther by more than the step), then the halos behind them.
    std::vector<bool> silhouette(mask.size(), false);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (!mask[size_t(y) * size_t(width) + size_t(x)]) continue;
            const double here = depth.at(x, y);
            const double step = std::max(0.1, 0.05 * here);
            const int neighbours[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
            for (const auto& offset : neighbours) {
                const int nx = x + offset[0], ny = y + offset[1];
                if (nx >= 0 && ny >= 0 && nx < width && ny < height && far_at(nx, ny) > here + step) {
                    silhouette[size_t(y) * size_t(width) + size_t(x)] = true;
                }
            }
        }
    }
    size_t halos = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            ThicknessClass expected = ThicknessClass::Sky;
            if (mask[size_t(y) * size_t(width) + size_t(x)]) {
                const double here = depth.at(x, y);
                const int half = int(std::floor(std::min(cap, radius * scale / here)));
                double nearest = std::numeric_limits<double>::infinity();  // the nearest silhouette in the window
                for (int wy = std::max(0, y - half); wy <= std::min(height - 1, y + half); ++wy) {
                    for (int wx = std::max(0, x - half); wx <= std::min(width - 1, x + half); ++wx) {
                        if (silhouette[size_t(wy) * size_t(width) + size_t(wx)]) nearest = std::min(nearest, far_at(wx, wy));
                    }
                }
                expected = silhouette[size_t(y) * size_t(width) + size_t(x)] ? ThicknessClass::Silhouette
                           : nearest < here - thickness                      ? ThicknessClass::Halo
                                                                             : ThicknessClass::Rest;
            }
            halos += expected == ThicknessClass::Halo;
            ASSERT_EQ(class_at(classes, width, x, y), expected) << "pixel " << x << ", " << y;
        }
    }
    EXPECT_GT(halos, 0u);
}

TEST(WindowMinimum, MatchesABruteForceScan) {
    // Every pixel and half size of a random 19x13 image with some +infinity, against a plain scan of the window
    // clipped to the image (half sizes up to 12: windows wider than the image both ways).
    const int width = 19;
    const int height = 13;
    std::mt19937 random(3);
    std::uniform_real_distribution<float> values(-5.0f, 5.0f);
    FloatImage image = constant_image(width, height, 0.0f);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = i % 7 == 3 ? std::numeric_limits<float>::infinity() : values(random);
    }
    const int max_half_size = 12;
    const WindowMinimum window(image, max_half_size);
    for (int half = 0; half <= max_half_size; ++half) {
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                float expected = std::numeric_limits<float>::infinity();
                for (int wy = std::max(0, y - half); wy <= std::min(height - 1, y + half); ++wy) {
                    for (int wx = std::max(0, x - half); wx <= std::min(width - 1, x + half); ++wx) {
                        expected = std::min(expected, image.at(wx, wy));
                    }
                }
                ASSERT_EQ(window.query(x, y, half), expected) << "pixel " << x << ", " << y << ", half size " << half;
            }
        }
    }
    EXPECT_THROW(window.query(width, 0, 1), std::out_of_range);
    EXPECT_THROW(window.query(0, 0, max_half_size + 1), std::out_of_range);
    EXPECT_THROW(WindowMinimum(image, -1), std::invalid_argument);
    EXPECT_THROW(WindowMinimum(constant_image(2, 2, 0.0f, 3), 1), std::invalid_argument);
    EXPECT_THROW(WindowMinimum(make_image(2, 1, {0.0f, kNaN}), 1), std::invalid_argument);
}

TEST(ThicknessClasses, RejectsBadInput) {
    const DepthScene scene(8, 8, 10.0f, 5.0f, 2, 2, 2);
    // Mask and depth of different sizes; a depth image whose pixel count does not match; several channels.
    EXPECT_THROW(thickness_classes(scene.depth, std::vector<uint8_t>(63, 1), 1.0, 0.3, 40.0, 256.0), std::invalid_argument);
    FloatImage short_depth = scene.depth;
    short_depth.pixels.pop_back();
    EXPECT_THROW(thickness_classes(short_depth, scene.mask, 1.0, 0.3, 40.0, 256.0), std::invalid_argument);
    EXPECT_THROW(thickness_classes(constant_image(8, 8, 1.0f, 3), scene.mask, 1.0, 0.3, 40.0, 256.0), std::invalid_argument);
    // Parameters out of range.
    EXPECT_THROW(thickness_classes(scene.depth, scene.mask, 0.0, 0.3, 40.0, 256.0), std::invalid_argument);
    EXPECT_THROW(thickness_classes(scene.depth, scene.mask, 1.0, -0.1, 40.0, 256.0), std::invalid_argument);
    EXPECT_THROW(thickness_classes(scene.depth, scene.mask, 1.0, 0.3, kInf, 256.0), std::invalid_argument);
    EXPECT_THROW(thickness_classes(scene.depth, scene.mask, 1.0, 0.3, 40.0, kNaN), std::invalid_argument);
    // A geometry pixel without a depth.
    FloatImage holed = scene.depth;
    holed.pixels[5] = 0.0f;
    EXPECT_THROW(thickness_classes(holed, scene.mask, 1.0, 0.3, 40.0, 256.0), std::invalid_argument);
    // Sky is allowed any depth, a geometry-less image is all sky.
    FloatImage sky = scene.depth;
    sky.pixels.assign(sky.pixels.size(), kNaN);
    const std::vector<uint8_t> none(64, 0);
    EXPECT_EQ(count_class(thickness_classes(sky, none, 1.0, 0.3, 40.0, 256.0), ThicknessClass::Sky), 64u);
}

TEST(ThicknessClassImage, ColoursPerClass) {
    const FloatImage image = obscura::samples::thickness_class_image({0, 1, 2, 3}, 2, 2);
    ASSERT_EQ(image.channels, 3);
    EXPECT_EQ(rgb_at(image, 0, 0), (std::vector<float>{0.0f, 0.0f, 0.0f}));  // sky black
    EXPECT_EQ(rgb_at(image, 1, 0), (std::vector<float>{1.0f, 1.0f, 1.0f}));  // rest white
    EXPECT_GT(rgb_at(image, 0, 1)[2], rgb_at(image, 0, 1)[0]);             // halo blue
    EXPECT_GT(rgb_at(image, 1, 1)[0], rgb_at(image, 1, 1)[2]);             // silhouette red
    EXPECT_THROW(obscura::samples::thickness_class_image({0, 1, 2}, 2, 2), std::invalid_argument);
    EXPECT_THROW(obscura::samples::thickness_class_image({0, 1, 2, 4}, 2, 2), std::invalid_argument);
    EXPECT_STREQ(obscura::samples::thickness_class_name(ThicknessClass::Halo), "halo");
}

}  // namespace
