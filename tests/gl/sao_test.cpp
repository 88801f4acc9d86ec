// SAO behaviour through the public API on analytic scenes (CPU ray cast, uploaded as depth, 320x180):
//   - flat surfaces get no occlusion (with and without the z hierarchy, every projection),
//   - a concave corner gets occlusion near its crease and none beyond the radius,
//   - the number of depth taps per pixel does not depend on the radius (tap-count debug view),
//   - the hierarchy changes the picture little (PSNR against level-0-only sampling),
//   - settings reach the shader (samples, intensity, blur) and render without GL errors.
// The z pyramid itself is checked texel by texel in z_pyramid_test.cpp.
#include <algorithm>
#include <cmath>

#include "ao_test_scene.h"

namespace obscura_test {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

obscura_settings sao_settings(float radius = 1.0f) {
    obscura_settings s;
    obscura_default_settings(OBSCURA_METHOD_SAO, &s);
    s.sao.radius = radius;
    return s;
}

class Sao : public GLTest {};

// ---- Flat surfaces ------------------------------------------------------------------------------------

class SaoFlatPlane : public GLTest, public ::testing::WithParamInterface<Projection> {};

// A plane seen at 35 degrees from grazing covers the image: every tap lies on the receiver's tangent plane,
// so v.n = 0 and the estimator adds nothing, whichever MIP level a tap reads.
TEST_P(SaoFlatPlane, SteepFloorIsUnoccluded) {
    AoScene scene = steep_floor_scene(GetParam());
    for (obscura_toggle mip : {OBSCURA_TOGGLE_ON, OBSCURA_TOGGLE_OFF}) {
        obscura_settings settings = sao_settings(1.0f);
        settings.sao.mip = mip;
        Stats s = geometry_stats(scene, render_visibility(ctx(), scene.input, settings));
        ASSERT_GT(s.count, kWidth * kHeight / 2);
        EXPECT_GT(s.min, 0.995) << "mip " << (mip == OBSCURA_TOGGLE_ON ? "on" : "off") << ": " << describe(s);
    }
}

TEST_P(SaoFlatPlane, TiltedIsUnoccluded) {
    AoScene scene = tilted_plane_scene(GetParam());
    Stats s = geometry_stats(scene, render_visibility(ctx(), scene.input, sao_settings(2.0f)));
    ASSERT_EQ(s.count, kWidth * kHeight);
    EXPECT_GT(s.min, 0.995) << describe(s);
}

INSTANTIATE_TEST_SUITE_P(Variants, SaoFlatPlane, all_projections(), projection_test_name);

// ---- A concave corner: floor (y = 0) and a wall (z = 0, facing +z) --------------------------------------

// corner_scene() and crease_distance() come from ao_test_scene.h.

TEST_F(Sao, CornerOccludedNearCreaseOnly) {
    AoScene scene = corner_scene();
    std::vector<float> v = render_visibility(ctx(), scene.input, sao_settings(1.0f));
    ASSERT_FALSE(v.empty());
    // Near the crease the other plane fills a quarter of the ball (measured: mean 0.24, max 0.63).
    Stats near = stats(v, select(scene.hits, kWidth, kHeight, 12, [](const Hit& h) { return crease_distance(h) < 0.1; }));
    ASSERT_GT(near.count, 100);
    EXPECT_LT(near.mean, 0.8) << describe(near);
    // Beyond the radius (1 m) plus the blur's reach the ball holds only the receiver's own plane (measured:
    // exactly 1 everywhere).
    Stats far = stats(v, select(scene.hits, kWidth, kHeight, 12, [](const Hit& h) { return crease_distance(h) > 1.4; }));
    ASSERT_GT(far.count, 1000);
    EXPECT_GT(far.min, 0.99) << describe(far);
}

TEST_F(Sao, IntensityDarkensAndContrastShapes) {
    AoScene scene = corner_scene();
    auto near_mean = [&](const obscura_settings& settings) {
        std::vector<float> v = render_visibility(ctx(), scene.input, settings);
        return stats(v, select(scene.hits, kWidth, kHeight, 12, [](const Hit& h) { return crease_distance(h) < 0.2; }))
            .mean;
    };
    obscura_settings base = sao_settings(1.0f);
    obscura_settings strong = base;
    strong.sao.intensity = 2.0f;
    obscura_settings contrast = base;
    contrast.sao.contrast = 2.0f;
    const double v_base = near_mean(base), v_strong = near_mean(strong), v_contrast = near_mean(contrast);
    // Measured: 0.29, 0.08 with sigma = 2, 0.15 with k = 2.
    EXPECT_LT(v_strong, v_base - 0.05);
    // k = 2 squares each pixel's visibility before the blur: the mean drops, but not below the square of the
    // mean (the mean of squares is at least that).
    EXPECT_LT(v_contrast, v_base - 0.05);
    EXPECT_GE(v_contrast, v_base * v_base - 0.01);
}

// ---- Constant cost -----------------------------------------------------------------------------------

// The tap-count debug view reports the depth texels each pixel's AO read (/ 256). Away from the texture's
// border every one of the s taps is read, at any radius: the cost of SAO does not grow with the radius.
TEST_F(Sao, RadiusDoesNotChangeTheNumberOfTaps) {
    AoScene scene = corner_scene();
    const int border = 40;  // beyond the capped screen radius below
    std::vector<bool> inner = select(scene.hits, kWidth, kHeight, border, [](const Hit&) { return true; });
    for (int samples : {9, 16}) {
        for (float radius : {0.1f, 0.5f, 3.0f}) {
            obscura_settings settings = sao_settings(radius);
            settings.sao.samples = samples;
            settings.sao.max_radius_pixels = 32.0f;
            std::vector<float> v = render_visibility(ctx(), scene.input, settings, OBSCURA_DEBUG_TAP_COUNT);
            ASSERT_FALSE(v.empty());
            Stats s = stats(v, inner);
            ASSERT_GT(s.count, 1000);
            EXPECT_EQ(std::lround(s.min * 256.0), samples) << "radius " << radius << ": " << describe(s);
            EXPECT_EQ(std::lround(s.max * 256.0), samples) << "radius " << radius << ": " << describe(s);
        }
    }
}

TEST_F(Sao, TapCountOfSkyIsZero) {
    AoScene scene = make_ao_scene(Projection::Perspective, glm::dmat4(1.0),
                                  {sphere(1, glm::dvec3(0.0, 0.0, -6.0), 1.0)});
    std::vector<float> v = render_visibility(ctx(), scene.input, sao_settings(1.0f), OBSCURA_DEBUG_TAP_COUNT);
    ASSERT_FALSE(v.empty());
    std::vector<bool> sky(v.size());
    for (size_t i = 0; i < sky.size(); ++i) sky[i] = !scene.hits[i].hit;
    Stats s = stats(v, sky);
    ASSERT_GT(s.count, 1000);
    EXPECT_EQ(s.max, 0.0) << describe(s);
}

// ---- The hierarchy's effect on the picture ------------------------------------------------------------------

double psnr(const std::vector<float>& a, const std::vector<float>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    const double mse = sum / double(a.size());
    return mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : 200.0;
}

// The paper's claim for rotated-grid subsampling: quality comparable to sampling level 0 only. Boxes and
// spheres on a floor, 1.5 m radius: about 60 px on screen, so the outer taps read level 2 (measured: 47 dB).
TEST_F(Sao, HierarchyKeepsThePicture) {
    AoScene scene = make_ao_scene(Projection::Perspective, look_at(glm::dvec3(0.0, 2.0, 4.0), glm::dvec3(0.0, 0.3, 0.0)),
                                  {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                                   box(2, glm::dvec3(-1.5, 0.0, -0.5), glm::dvec3(-0.5, 1.0, 0.5)),
                                   sphere(3, glm::dvec3(0.8, 0.6, 0.0), 0.6)});
    obscura_settings with_mip = sao_settings(1.5f);
    obscura_settings without = with_mip;
    without.sao.mip = OBSCURA_TOGGLE_OFF;
    std::vector<float> a = render_visibility(ctx(), scene.input, with_mip);
    std::vector<float> b = render_visibility(ctx(), scene.input, without);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    EXPECT_GT(psnr(a, b), 30.0);
    // ... while the two differ: the hierarchy is in use.
    EXPECT_NE(a, b);
}

// ---- Settings ---------------------------------------------------------------------------------------------

TEST_F(Sao, EveryMipFilterAndSampleCountRendersCleanly) {
    AoScene scene = corner_scene();
    for (int filter = 1; filter <= 5; ++filter) {
        obscura_settings settings = sao_settings(2.0f);
        settings.sao.mip_filter = filter;
        std::vector<float> v = render_visibility(ctx(), scene.input, settings);
        ASSERT_FALSE(v.empty()) << "filter " << filter;
        Stats near = stats(v, select(scene.hits, kWidth, kHeight, 12, [](const Hit& h) { return crease_distance(h) < 0.1; }));
        EXPECT_LT(near.mean, 0.85) << "filter " << filter << ": " << describe(near);
    }
    for (int samples : {1, 2, 64}) {
        obscura_settings settings = sao_settings(1.0f);
        settings.sao.samples = samples;
        EXPECT_FALSE(render_visibility(ctx(), scene.input, settings).empty()) << samples << " samples";
    }
}

TEST_F(Sao, BlurSmoothsTheSpiralNoise) {
    AoScene scene = corner_scene();
    obscura_settings blurred = sao_settings(1.0f);
    obscura_settings raw = blurred;
    raw.sao.blur = OBSCURA_TOGGLE_OFF;
    raw.sao.quad_filter = OBSCURA_TOGGLE_OFF;
    std::vector<float> a = render_visibility(ctx(), scene.input, blurred);
    std::vector<float> b = render_visibility(ctx(), scene.input, raw);
    ASSERT_EQ(a.size(), b.size());
    // Noise: mean absolute difference between horizontal neighbours on the floor near the crease.
    auto roughness = [&](const std::vector<float>& v) {
        double sum = 0.0;
        int count = 0;
        for (int y = 12; y < kHeight - 12; ++y)
            for (int x = 12; x < kWidth - 13; ++x) {
                const Hit& h = scene.hits[size_t(y) * kWidth + x];
                const Hit& n = scene.hits[size_t(y) * kWidth + x + 1];
                if (!h.hit || !n.hit || h.id != 1 || n.id != 1 || crease_distance(h) > 0.6) continue;
                sum += std::fabs(double(v[size_t(y) * kWidth + x]) - v[size_t(y) * kWidth + x + 1]);
                ++count;
            }
        return count > 0 ? sum / count : 0.0;
    };
    // Measured: 0.013 blurred, 0.098 raw.
    EXPECT_LT(roughness(a), 0.5 * roughness(b)) << "blurred " << roughness(a) << ", raw " << roughness(b);
}

// The quad filter pairs the pixels of absolute 2x2 quads: a pixel's AO does not depend on where the output rectangle
// ends. Without the blur (no apron) a rectangle ending on an odd coordinate once left its last column and row
// unpaired; they differed from a rectangle one texel larger.
TEST_F(Sao, QuadFilterDoesNotDependOnWhereTheRectangleEnds) {
    AoScene scene = corner_scene();
    obscura_settings settings = sao_settings(1.0f);
    settings.sao.blur = OBSCURA_TOGGLE_OFF;
    ASSERT_EQ(settings.sao.quad_filter == OBSCURA_TOGGLE_OFF, false);
    obscura_input odd_end = scene.input, even_end = scene.input;
    odd_end.output_rect = obscura_rect{8, 8, 47, 47};
    even_end.output_rect = obscura_rect{8, 8, 48, 48};
    const std::vector<float> a = render_visibility(ctx(), odd_end, settings);
    const std::vector<float> b = render_visibility(ctx(), even_end, settings);
    ASSERT_EQ(a.size(), size_t(47 * 47));
    ASSERT_EQ(b.size(), size_t(48 * 48));
    int differing = 0;
    for (int y = 0; y < 47; ++y)
        for (int x = 0; x < 47; ++x) differing += a[size_t(y) * 47 + x] != b[size_t(y) * 48 + x] ? 1 : 0;
    EXPECT_EQ(differing, 0);
}

TEST_F(Sao, MemoryIncludesThePyramidAndPackedTextures) {
    AoScene scene = corner_scene();
    ASSERT_FALSE(render_visibility(ctx(), scene.input, make_settings(1.0f)).empty());
    uint64_t hbao_bytes = 0, sao_bytes = 0;
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &hbao_bytes), OBSCURA_OK);
    ASSERT_FALSE(render_visibility(ctx(), scene.input, sao_settings(1.0f)).empty());
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &sao_bytes), OBSCURA_OK);
    const uint64_t texels = uint64_t(scene.input.depth_width) * uint64_t(scene.input.depth_height);
    // SAO: two RGBA8 textures (8 B per texel) and the MIP levels of the R32F depth (about 4/3 B per texel); HBAO's
    // default: the AO pass's R16F result and its blur's R16F intermediate (4 B per texel), which SAO does not use.
    EXPECT_GE(sao_bytes - hbao_bytes, texels * 8 + texels - texels * 4);
    EXPECT_LE(sao_bytes - hbao_bytes, texels * 8 + texels * 2 - texels * 4);
}

}  // namespace
}  // namespace obscura_test
