// SAO's sample pattern (sdk/src/passes/sao.*) and settings: the spiral of eq. 6-7 with the default turns,
// the per-pixel rotation of eq. 8, how the taps cover the disc, the z-pyramid depth the taps can reach,
// and the SAO settings table (defaults of the paper, spec keys, the matching reference).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "obscura/obscura.h"
#include "passes/sao.h"
#include "settings.h"

namespace {

constexpr double kTwoPi = 6.283185307179586;

TEST(SaoSpiral, DefaultTurnsArePapersAndCoprime) {
    EXPECT_EQ(obscura::default_spiral_turns(9), 7);  // the paper's tau for s = 9
    for (int s = 1; s <= OBSCURA_SAO_MAX_SAMPLES; ++s) {
        int t = obscura::default_spiral_turns(s);
        EXPECT_GE(t, 1);
        EXPECT_EQ(std::gcd(s, t), 1) << "s " << s << " tau " << t;
        if (s > 2) {
            EXPECT_LE(std::fabs(t - 7.0 * s / 9.0), s / 4.0) << "s " << s;
        }
    }
}

// With tau coprime with s the s angles 2 pi tau alpha_i are a permutation of s evenly spaced angles (one per
// sector of 2 pi / s), and the radii alpha_i = (i + 0.5) / s are evenly spaced: the pattern covers the disc.
TEST(SaoSpiral, AnglesAndRadiiAreEvenlySpaced) {
    for (int s : {4, 7, 9, 12, 16, 24, 32, 64}) {
        const int tau = obscura::default_spiral_turns(s);
        std::vector<double> angles;
        for (int i = 0; i < s; ++i) {
            obscura::SpiralTap tap = obscura::spiral_tap(i, s, tau);
            EXPECT_NEAR(tap.alpha, (i + 0.5) / s, 1e-6);
            EXPECT_GE(tap.angle, 0.0f);
            EXPECT_LT(tap.angle, float(kTwoPi));
            angles.push_back(tap.angle);
        }
        std::sort(angles.begin(), angles.end());
        for (int i = 1; i < s; ++i) EXPECT_NEAR(angles[i] - angles[i - 1], kTwoPi / s, 1e-5) << "s " << s;
    }
}

TEST(SaoSpiral, RotationIsEquation8) {
    // phi = 30 x ^ y + 10 x y, reduced to [0, 2 pi), at 4K coordinates too (10 x y up to 8e7, where a float
    // reduction is off by radians).
    for (int y = 0; y < 2200; y += 37)
        for (int x = 0; x < 3900; x += 53) {
            const long double phi = std::fmod((long double)((30 * x) ^ y) + 10.0L * x * y, 2.0L * 3.14159265358979323846L);
            EXPECT_NEAR(obscura::spiral_rotation(x, y), double(phi), 1e-5) << x << ", " << y;
        }
}

// Over a block of pixels the rotated taps fill the disc evenly: in a histogram of 8 sectors x 3 rings
// (rings of equal radial width, as the taps' radii are) every cell holds its share within 20 %.
TEST(SaoSpiral, RotatedTapsCoverTheDiscEvenly) {
    const int s = 9, tau = obscura::default_spiral_turns(s);
    const int sectors = 8, rings = 3;
    std::vector<int> histogram(size_t(sectors * rings), 0);
    int total = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const double phi = obscura::spiral_rotation(x, y);
            for (int i = 0; i < s; ++i) {
                obscura::SpiralTap tap = obscura::spiral_tap(i, s, tau);
                double angle = std::fmod(tap.angle + phi, kTwoPi);
                int sector = std::min(int(angle / kTwoPi * sectors), sectors - 1);
                int ring = std::min(int(tap.alpha * rings), rings - 1);
                ++histogram[size_t(ring * sectors + sector)];
                ++total;
            }
        }
    const double expected = double(total) / double(sectors * rings);
    for (int cell = 0; cell < sectors * rings; ++cell) {
        EXPECT_NEAR(histogram[size_t(cell)], expected, 0.2 * expected) << "ring " << cell / sectors << " sector "
                                                                       << cell % sectors;
    }
}

TEST(SaoLevels, DeepestLevelFollowsEquation9) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_SAO, &s), OBSCURA_OK);
    // Outermost tap at 17/18 of 256 px = 241 px: findMSB = 7, minus log q' = 3: level 4, so 5 levels.
    EXPECT_EQ(obscura::SaoPass::wanted_levels(s.sao), 5);
    s.sao.log_q = 5;
    EXPECT_EQ(obscura::SaoPass::wanted_levels(s.sao), 3);
    s.sao.max_radius_pixels = 4.0f;
    EXPECT_EQ(obscura::SaoPass::wanted_levels(s.sao), 1);
    s.sao.max_radius_pixels = 256.0f;
    s.sao.mip = OBSCURA_TOGGLE_OFF;
    EXPECT_EQ(obscura::SaoPass::wanted_levels(s.sao), 1);
}

TEST(SaoSettings, PaperDefaultsAndSpecKeys) {
    obscura_settings s;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_SAO, &s), OBSCURA_OK);
    EXPECT_EQ(s.sao.samples, 9);
    EXPECT_EQ(s.sao.turns, 0);  // derived from the samples: 7 for the paper's 9
    double turns = 0.0;
    ASSERT_EQ(obscura_get_setting(&s, "turns", &turns), OBSCURA_OK);
    EXPECT_EQ(turns, 7.0);
    EXPECT_EQ(s.sao.mip, OBSCURA_TOGGLE_ON);
    EXPECT_EQ(s.sao.mip_filter, 1);
    EXPECT_EQ(s.sao.log_q, 3);
    EXPECT_EQ(s.sao.blur_radius, 3);
    EXPECT_EQ(s.sao.blur_stride, 3);
    EXPECT_EQ(s.sao.blur_sharpness, 2048.0f);
    for (const char* key : {"radius", "samples", "turns", "mip", "mip_filter", "log_q", "intensity", "bias",
                            "contrast", "epsilon", "blur", "blur_radius", "blur_stride", "blur_sharpness"}) {
        double value = -1.0;
        EXPECT_EQ(obscura_get_setting(&s, key, &value), OBSCURA_OK) << key;
    }
    // mip=0|1 is a toggle.
    ASSERT_EQ(obscura_set_setting(&s, "mip", 0.0), OBSCURA_OK);
    EXPECT_EQ(s.sao.mip, OBSCURA_TOGGLE_OFF);
    // Zero turns derive from the samples.
    s.sao.turns = 0;
    s.sao.samples = 16;
    ASSERT_EQ(obscura_get_setting(&s, "turns", &turns), OBSCURA_OK);
    EXPECT_EQ(int(turns), obscura::default_spiral_turns(16));
    s.sao.samples = 65;
    obscura_settings resolved;
    EXPECT_EQ(obscura_resolve_settings(nullptr, &s, &resolved), OBSCURA_STATUS_INVALID_SETTING);
}

TEST(SaoSettings, ReferenceIsAStepFalloffAtTheRadius) {
    obscura_settings s, reference;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_SAO, &s), OBSCURA_OK);
    s.sao.radius = 2.5f;
    ASSERT_EQ(obscura_reference_settings_for(&s, &reference), OBSCURA_OK);
    EXPECT_EQ(reference.method, OBSCURA_METHOD_REFERENCE);
    EXPECT_EQ(reference.reference.falloff, OBSCURA_FALLOFF_TABLE);
    EXPECT_EQ(reference.reference.radius, 2.5f);
    for (float value : reference.reference.falloff_table) EXPECT_EQ(value, 1.0f);
}

}  // namespace
