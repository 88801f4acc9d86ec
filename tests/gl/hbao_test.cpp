// HBAO behaviour on analytic scenes (CPU ray cast, uploaded as D32F depth, 320x180):
//   - flat surfaces get no occlusion,
//   - concave corners and contacts get occlusion, open surfaces away from occluders get none,
//   - results are deterministic,
//   - the guard band supplies occluders to the output rectangle's edge,
//   - debug views, blur and the shaping settings do what they say.
// Visibility thresholds are stated with each test; "no occlusion" allows 0.005 below 1 on planes (as
// specified; measured on llvmpipe: >= 0.9985, the SDK stores visibility as R16F whose step below 1 is
// 2^-11) and 0.01 on open regions of multi-object scenes (measured >= 0.9985), which the bilateral
// blur may mix with neighbours. Occluded regions are asserted with wide margins (measured values in
// the comments) so that HBAO tuning does not break them while a loss of occlusion does.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "ao_test_scene.h"

namespace obscura_test {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

class Hbao : public GLTest {};

// ---- Flat surfaces ------------------------------------------------------------------------------------

class HbaoFlatPlane : public GLTest, public ::testing::WithParamInterface<Projection> {};

TEST_P(HbaoFlatPlane, FacingCameraIsUnoccluded) {
    AoScene scene = make_ao_scene(GetParam(), glm::dmat4(1.0),
                                  {plane(1, glm::dvec3(0.0, 0.0, -5.0), glm::dvec3(0.0, 0.0, 1.0))});
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_FALSE(v.empty());
    Stats s = stats(v, std::vector<bool>(v.size(), true));
    EXPECT_GT(s.min, 0.995) << describe(s);
}

TEST_P(HbaoFlatPlane, TiltedIsUnoccluded) {
    AoScene scene = tilted_plane_scene(GetParam());
    Stats s = geometry_stats(scene, render_visibility(ctx(), scene.input, make_settings(1.0f)));
    ASSERT_EQ(s.count, kWidth * kHeight);
    EXPECT_GT(s.min, 0.995) << describe(s);
}

TEST_P(HbaoFlatPlane, SteepFloorIsUnoccluded) {
    AoScene scene = steep_floor_scene(GetParam());
    Stats s = geometry_stats(scene, render_visibility(ctx(), scene.input, make_settings(1.0f)));
    ASSERT_GT(s.count, kWidth * kHeight / 2);
    EXPECT_GT(s.min, 0.995) << describe(s);
}

INSTANTIATE_TEST_SUITE_P(Variants, HbaoFlatPlane, all_projections(), projection_test_name);

// ---- A concave corner: floor (y = 0) and a wall (z = 0, facing +z) --------------------------------------

// corner_scene() and crease_distance() come from ao_test_scene.h.

TEST_F(Hbao, CornerOccludedNearCrease) {
    AoScene scene = corner_scene();
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_FALSE(v.empty());
    // Within 5 cm of the crease about half of every hemisphere is wall or floor: strong occlusion
    // (measured: mean 0.60, max 0.64).
    Stats near = stats(v, select(scene.hits, kWidth, kHeight, 8, [](const Hit& h) { return crease_distance(h) < 0.05; }));
    ASSERT_GT(near.count, 100);
    EXPECT_LT(near.mean, 0.8) << describe(near);
    EXPECT_LT(near.max, 0.9) << describe(near);
}

TEST_F(Hbao, CornerUnoccludedFarFromCrease) {
    AoScene scene = corner_scene();
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_FALSE(v.empty());
    // Beyond the radius (1 m) plus the blur footprint nothing occludes (measured min 0.9985).
    Stats far = stats(v, select(scene.hits, kWidth, kHeight, 8, [](const Hit& h) { return crease_distance(h) > 1.4; }));
    ASSERT_GT(far.count, 1000);
    EXPECT_GT(far.min, 0.99) << describe(far);
}

TEST_F(Hbao, CornerOcclusionDecreasesWithDistance) {
    AoScene scene = corner_scene();
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_FALSE(v.empty());
    double previous = 0.0;
    for (double d : {0.05, 0.2, 0.4, 0.7}) {
        Stats band = stats(v, select(scene.hits, kWidth, kHeight, 8, [d](const Hit& h) {
            double c = crease_distance(h);
            return c >= d && c < d + 0.1;
        }));
        ASSERT_GT(band.count, 50) << "band at " << d;
        EXPECT_GT(band.mean, previous) << "band at " << d << ": " << describe(band);
        previous = band.mean;
    }
}

// ---- A box on a floor ---------------------------------------------------------------------------------

TEST_F(Hbao, BoxContactOccluded) {
    AoScene scene = box_scene();
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_FALSE(v.empty());
    Stats contact = stats(v, select(scene.hits, kWidth, kHeight, 8, [](const Hit& h) {
        return h.id == 1 && footprint_distance(h) < 0.05;
    }));
    ASSERT_GT(contact.count, 50);
    EXPECT_LT(contact.mean, 0.85) << describe(contact);  // measured 0.67
}

TEST_F(Hbao, BoxOpenFloorUnoccluded) {
    AoScene scene = box_scene();
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_FALSE(v.empty());
    // Floor more than radius + blur footprint from the box, closer than 15 m: beyond that the floor is
    // seen within ~8 degrees of grazing, where HBAO's horizon test loses up to 0.018 (reported to the
    // hbao.comp owner; it is independent of depth precision: reversed-Z gives the same values).
    Stats open = stats(v, select(scene.hits, kWidth, kHeight, 8, [](const Hit& h) {
        return h.id == 1 && footprint_distance(h) > 1.4 && h.view_depth() < 15.0;
    }));
    ASSERT_GT(open.count, 1000);
    EXPECT_GT(open.min, 0.99) << describe(open);
}

TEST_F(Hbao, BoxTopCentreUnoccluded) {
    AoScene scene = box_scene();
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_FALSE(v.empty());
    Stats top = stats(v, select(scene.hits, kWidth, kHeight, 8, [](const Hit& h) {
        return h.id == 2 && h.world.y > kBoxHeight - 1e-6 && std::fabs(h.world.x) < 0.25 && std::fabs(h.world.z) < 0.25;
    }));
    ASSERT_GT(top.count, 100);
    EXPECT_GT(top.min, 0.99) << describe(top);  // measured 0.9985
}

// ---- Determinism ------------------------------------------------------------------------------------------

TEST_F(Hbao, TwoRendersAreBitIdentical) {
    AoScene scene = box_scene();
    std::vector<float> a = render_visibility(ctx(), scene.input, make_settings(1.0f));
    std::vector<float> b = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

TEST_F(Hbao, FreshContextIsBitIdentical) {
    AoScene scene = box_scene();
    std::vector<float> a = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ContextPtr other = create_context();
    ASSERT_NE(other, nullptr);
    std::vector<float> b = render_visibility(other.get(), scene.input, make_settings(1.0f));
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

// ---- Guard band ---------------------------------------------------------------------------------------------

// Floor plus a pillar placed so that it lies entirely in the left guard band, next to the output rect.
struct GuardBandSetup {
    obscura_rect rect{32, 18, 256, 144};
    glm::dmat4 view = look_at(glm::dvec3(0.0, 2.5, 3.5), glm::dvec3(0.0, 0.0, 0.0));
    Primitive pillar;
    bool found = false;
};

GuardBandSetup guard_band_setup() {
    GuardBandSetup setup;
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), setup.view);
    // Slide the pillar left until its rightmost projected corner is 3 texels left of the rect.
    for (double x = -1.0; x > -6.0; x -= 0.01) {
        glm::dvec3 lo(x - 0.15, 0.0, -0.15), hi(x + 0.15, 1.2, 0.15);
        double max_px = -1e9;
        for (int c = 0; c < 8; ++c) {
            glm::dvec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
            max_px = std::max(max_px, camera.project(corner).x);
        }
        if (max_px < setup.rect.x - 3) {
            setup.pillar = box(2, lo, hi);
            setup.found = true;
            break;
        }
    }
    return setup;
}

TEST_F(Hbao, GuardBandOccluderDarkensRectEdge) {
    GuardBandSetup setup = guard_band_setup();
    ASSERT_TRUE(setup.found);
    Primitive floor = plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
    AoScene with = make_ao_scene(Projection::Perspective, setup.view, {floor, setup.pillar});
    AoScene without = make_ao_scene(Projection::Perspective, setup.view, {floor});
    // Preconditions: the pillar is visible in the guard band and nowhere inside the rect.
    int inside = 0, in_guard = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            if (with.hits[size_t(y) * kWidth + x].id != 2) continue;
            bool in_rect = x >= setup.rect.x && x < setup.rect.x + setup.rect.width && y >= setup.rect.y &&
                           y < setup.rect.y + setup.rect.height;
            (in_rect ? inside : in_guard)++;
        }
    ASSERT_EQ(inside, 0);
    ASSERT_GT(in_guard, 20);
    with.input.output_rect = setup.rect;
    without.input.output_rect = setup.rect;
    std::vector<float> a = render_visibility(ctx(), with.input, make_settings(1.0f));
    std::vector<float> b = render_visibility(ctx(), without.input, make_settings(1.0f));
    ASSERT_FALSE(a.empty());
    ASSERT_FALSE(b.empty());
    // Left 4 columns of the rect, rows whose floor point is within 0.6 m of the pillar.
    double darkest_drop = 0.0, sum_drop = 0.0;
    int count = 0;
    for (int ry = 0; ry < setup.rect.height; ++ry) {
        for (int rx = 0; rx < 4; ++rx) {
            const Hit& h = with.hits[size_t(ry + setup.rect.y) * kWidth + (rx + setup.rect.x)];
            glm::dvec3 c = 0.5 * (setup.pillar.bounds_min + setup.pillar.bounds_max);
            if (std::hypot(h.world.x - c.x, h.world.z - c.z) > 0.6) continue;
            size_t i = size_t(ry) * setup.rect.width + rx;
            double drop = double(b[i]) - double(a[i]);
            darkest_drop = std::max(darkest_drop, drop);
            sum_drop += drop;
            ++count;
        }
    }
    ASSERT_GT(count, 8);
    EXPECT_GT(sum_drop / count, 0.05) << "mean visibility drop at the edge";  // measured 0.115
    EXPECT_GT(darkest_drop, 0.1);                                             // measured 0.198
    // Far from the pillar (right half) the two renders agree.
    double max_diff_right = 0.0;
    for (int ry = 0; ry < setup.rect.height; ++ry)
        for (int rx = setup.rect.width / 2; rx < setup.rect.width; ++rx) {
            size_t i = size_t(ry) * setup.rect.width + rx;
            max_diff_right = std::max(max_diff_right, double(std::fabs(a[i] - b[i])));
        }
    EXPECT_LT(max_diff_right, 1e-3);
}

TEST_F(Hbao, NarrowRectWritesOnlyItsSize) {
    AoScene scene = corner_scene();
    scene.input.output_rect = obscura_rect{40, 30, 100, 60};
    const int tw = 200, th = 120;
    HostTexture target = make_texture(GL_R32F, tw, th);
    fill_texture(target.get(), tw, th, -1.0f, 0, 0, 1);
    obscura_output output = make_output(target.get());
    output.x = 70;
    output.y = 20;
    obscura_settings settings = make_settings(1.0f);
    ASSERT_EQ(obscura_render(ctx(), &scene.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<float> v = read_texture(target.get(), tw, th, 1);
    int outside_written = 0, inside_unwritten = 0;
    for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x) {
            bool inside = x >= output.x && x < output.x + 100 && y >= output.y && y < output.y + 60;
            float value = v[size_t(y) * tw + x];
            if (inside && !(value >= 0.0f && value <= 1.0f)) ++inside_unwritten;
            if (!inside && value != -1.0f) ++outside_written;
        }
    EXPECT_EQ(outside_written, 0);
    EXPECT_EQ(inside_unwritten, 0);
    // The written block equals the same rect rendered into its own texture.
    std::vector<float> own = render_visibility(ctx(), scene.input, settings);
    ASSERT_EQ(own.size(), size_t(100 * 60));
    int mismatched = 0;
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 100; ++x)
            mismatched += own[size_t(y) * 100 + x] != v[size_t(y + output.y) * tw + (x + output.x)];
    EXPECT_EQ(mismatched, 0);
}

TEST_F(Hbao, RectResultMatchesFullRender) {
    // The AO inside a rect is the AO of the full frame at the same texels (occluders come from the
    // whole depth texture, the blur apron is computed).
    AoScene scene = box_scene();
    std::vector<float> full = render_visibility(ctx(), scene.input, make_settings(1.0f));
    obscura_rect rect{50, 40, 160, 90};
    scene.input.output_rect = rect;
    std::vector<float> part = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_EQ(part.size(), size_t(rect.width * rect.height));
    double worst = 0.0;
    for (int y = 0; y < rect.height; ++y)
        for (int x = 0; x < rect.width; ++x)
            worst = std::max(worst, double(std::fabs(part[size_t(y) * rect.width + x] -
                                                      full[size_t(y + rect.y) * kWidth + (x + rect.x)])));
    EXPECT_EQ(worst, 0.0);
}

// ---- Debug views, blur and shaping ------------------------------------------------------------------------

TEST_F(Hbao, BeforeBlurDiffersFromBlurred) {
    AoScene scene = box_scene();
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> blurred = render_visibility(ctx(), scene.input, settings);
    std::vector<float> raw = render_visibility(ctx(), scene.input, settings, OBSCURA_DEBUG_AO_BEFORE_BLUR);
    ASSERT_EQ(raw.size(), blurred.size());
    ASSERT_FALSE(raw.empty());
    double max_diff = 0.0;
    for (size_t i = 0; i < raw.size(); ++i) max_diff = std::max(max_diff, double(std::fabs(raw[i] - blurred[i])));
    EXPECT_GT(max_diff, 0.05);  // measured 0.33
    // Blurring keeps the average occlusion (a weighted mean of neighbours): within 0.01 overall.
    double mean_raw = 0.0, mean_blurred = 0.0;
    for (size_t i = 0; i < raw.size(); ++i) {
        mean_raw += raw[i];
        mean_blurred += blurred[i];
    }
    EXPECT_NEAR(mean_raw / raw.size(), mean_blurred / raw.size(), 0.01);
}

TEST_F(Hbao, BlurReducesNoise) {
    // The per-pixel jitter makes neighbouring raw values differ; the blur smooths them. Measured as the
    // mean absolute difference of horizontal neighbours on the floor near the box.
    AoScene scene = box_scene();
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> blurred = render_visibility(ctx(), scene.input, settings);
    std::vector<float> raw = render_visibility(ctx(), scene.input, settings, OBSCURA_DEBUG_AO_BEFORE_BLUR);
    ASSERT_FALSE(raw.empty());
    double tv_raw = 0.0, tv_blurred = 0.0;
    int n = 0;
    for (int y = 8; y < kHeight - 8; ++y)
        for (int x = 8; x < kWidth - 9; ++x) {
            const Hit& h = scene.hits[size_t(y) * kWidth + x];
            const Hit& r = scene.hits[size_t(y) * kWidth + x + 1];
            if (h.id != 1 || r.id != 1 || footprint_distance(h) > 0.5) continue;
            size_t i = size_t(y) * kWidth + x;
            tv_raw += std::fabs(raw[i + 1] - raw[i]);
            tv_blurred += std::fabs(blurred[i + 1] - blurred[i]);
            ++n;
        }
    ASSERT_GT(n, 200);
    EXPECT_LT(tv_blurred, 0.6 * tv_raw);  // measured ratio 0.43
}

TEST_F(Hbao, BlurOffEqualsBeforeBlur) {
    AoScene scene = box_scene();
    obscura_settings settings = make_settings(1.0f);
    settings.hbao.blur = OBSCURA_TOGGLE_OFF;
    std::vector<float> none = render_visibility(ctx(), scene.input, settings);
    std::vector<float> raw = render_visibility(ctx(), scene.input, settings, OBSCURA_DEBUG_AO_BEFORE_BLUR);
    ASSERT_EQ(none.size(), raw.size());
    ASSERT_FALSE(none.empty());
    EXPECT_EQ(std::memcmp(none.data(), raw.data(), none.size() * sizeof(float)), 0);
}

TEST_F(Hbao, PowerTwoSquaresVisibility) {
    AoScene scene = box_scene();
    obscura_settings settings = make_settings(1.0f);
    settings.hbao.blur = OBSCURA_TOGGLE_OFF;
    settings.hbao.power = 1.0f;  // the plain visibility (the default is 0.5)
    std::vector<float> one = render_visibility(ctx(), scene.input, settings);
    settings.hbao.power = 2.0f;
    std::vector<float> two = render_visibility(ctx(), scene.input, settings);
    ASSERT_EQ(one.size(), two.size());
    ASSERT_FALSE(one.empty());
    // R16F keeps 11 bits: v^2 computed from a rounded v differs by at most ~2 * 2^-11.
    double worst = 0.0;
    for (size_t i = 0; i < one.size(); ++i) worst = std::max(worst, std::fabs(double(two[i]) - double(one[i]) * one[i]));
    EXPECT_LT(worst, 2e-3);
}

TEST_F(Hbao, IntensityIncreasesOcclusion) {
    AoScene scene = corner_scene();
    obscura_settings settings = make_settings(1.0f);
    settings.hbao.intensity = 1.0f;  // the plain obscurance (the default is 2)
    std::vector<float> normal = render_visibility(ctx(), scene.input, settings);
    settings.hbao.intensity = 2.0f;
    std::vector<float> strong = render_visibility(ctx(), scene.input, settings);
    ASSERT_FALSE(normal.empty());
    std::vector<bool> near = select(scene.hits, kWidth, kHeight, 8, [](const Hit& h) { return crease_distance(h) < 0.3; });
    Stats a = stats(normal, near), b = stats(strong, near);
    EXPECT_LT(b.mean, a.mean - 0.05) << describe(a) << " vs " << describe(b);
}

TEST_F(Hbao, LargerRadiusReachesFurther) {
    AoScene scene = corner_scene();
    std::vector<bool> band =
        select(scene.hits, kWidth, kHeight, 8, [](const Hit& h) { return crease_distance(h) > 1.2 && crease_distance(h) < 1.6; });
    std::vector<float> small = render_visibility(ctx(), scene.input, make_settings(1.0f));
    std::vector<float> large = render_visibility(ctx(), scene.input, make_settings(3.0f));
    ASSERT_FALSE(small.empty());
    Stats a = stats(small, band), b = stats(large, band);
    ASSERT_GT(a.count, 100);
    EXPECT_GT(a.min, 0.99) << describe(a);                        // measured 0.9985
    EXPECT_LT(b.mean, a.mean - 0.03) << describe(a) << " vs " << describe(b);  // measured 0.999 -> 0.946
}

TEST_F(Hbao, SubPixelRadiusGivesNoOcclusion) {
    // 1 mm covers a tenth of a texel here: nothing is marched, visibility is exactly 1 before and after
    // the blur (a weighted mean of ones).
    AoScene scene = corner_scene();
    std::vector<float> raw =
        render_visibility(ctx(), scene.input, make_settings(0.001f), OBSCURA_DEBUG_AO_BEFORE_BLUR);
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(0.001f));
    ASSERT_FALSE(v.empty());
    ASSERT_FALSE(raw.empty());
    std::vector<bool> all(v.size(), true);
    Stats before = stats(raw, all), after = stats(v, all);
    int below_raw = 0, below = 0;
    for (size_t i = 0; i < v.size(); ++i) {
        below_raw += raw[i] != 1.0f;
        below += v[i] != 1.0f;
    }
    EXPECT_EQ(below_raw, 0) << "before blur: " << describe(before);
    EXPECT_EQ(below, 0) << "after blur: " << describe(after);
}

TEST_F(Hbao, SkyIsUnoccluded) {
    // A sphere floating in the sky: every sky texel is exactly 1, the sphere itself is convex.
    AoScene scene = make_ao_scene(Projection::Perspective, glm::dmat4(1.0),
                                  {sphere(1, glm::dvec3(0.0, 0.0, -4.0), 1.0)});
    std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
    ASSERT_FALSE(v.empty());
    int sky = 0;
    for (size_t i = 0; i < v.size(); ++i) {
        if (scene.hits[i].hit) continue;
        ++sky;
        ASSERT_EQ(v[i], 1.0f) << "sky texel " << i;
    }
    EXPECT_GT(sky, 1000);
}

TEST_F(Hbao, ProjectionsAgreeOnTheCorner) {
    // The same scene through every perspective variant gives the same AO (up to depth precision and
    // R16F storage): the decoded view positions are the same.
    std::vector<float> reference = render_visibility(ctx(), corner_scene(Projection::Perspective).input,
                                                     make_settings(1.0f));
    ASSERT_FALSE(reference.empty());
    for (Projection p : {Projection::ReversedZ, Projection::Infinite, Projection::ReversedInfinite,
                         Projection::LinearView}) {
        AoScene scene = corner_scene(p);
        std::vector<float> v = render_visibility(ctx(), scene.input, make_settings(1.0f));
        ASSERT_EQ(v.size(), reference.size());
        double mean_diff = 0.0, max_diff = 0.0;
        for (size_t i = 0; i < v.size(); ++i) {
            double d = std::fabs(double(v[i]) - reference[i]);
            mean_diff += d;
            max_diff = std::max(max_diff, d);
        }
        mean_diff /= v.size();
        EXPECT_LT(mean_diff, 1e-3) << projection_name(p);  // measured <= 7e-5
        EXPECT_LT(max_diff, 0.01) << projection_name(p);   // measured <= 0.001 (two R16F steps)
    }
}

}  // namespace
}  // namespace obscura_test
