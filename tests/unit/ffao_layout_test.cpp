// FFAO's CPU geometry (sdk/src/passes/ffao_layout.*, ffao.cpp): the scan lines cover the texture, every
// interval column's run of lines is written by each of its lines, and the estimator integral agrees with its
// closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "passes/ffao_estimator.h"
#include "passes/ffao_layout.h"

namespace {

constexpr double kPi = 3.14159265358979323846;

bool inside(const float p[2], int width, int height) {
    return std::floor(p[0]) >= 0.0f && std::floor(p[1]) >= 0.0f && std::floor(p[0]) < float(width) &&
           std::floor(p[1]) < float(height);
}

struct Case {
    int sectors, base_interval, width, height;
};

class FfaoLayoutCases : public ::testing::TestWithParam<Case> {};

// The layout phases a test walks (layout_phase.h): none, and line shifts of 3/8 and 7/8.
const double kPhaseFractions[] = {0.0, 0.375, 0.875};

// Every texel a line passes over is walked, and each orientation's lines reach every texel row or column
// they cross, in every layout phase.
TEST_P(FfaoLayoutCases, LinesWalkEveryStepInsideTheTexture) {
    const Case c = GetParam();
    for (double phase : kPhaseFractions) {
    SCOPED_TRACE("phase " + std::to_string(phase));
    const obscura::FfaoLayout layout =
        obscura::make_ffao_layout(c.sectors, c.base_interval, c.width, c.height, phase);
    ASSERT_EQ(int(layout.orientations.size()), c.sectors / 2);
    for (const obscura::FfaoOrientation& o : layout.orientations) {
        int64_t inside_steps = 0;
        for (int l = 0; l < o.line_count; ++l) {
            const obscura::FfaoLine& line = layout.lines[size_t(o.first_line + l)];
            for (int j = 0; j < o.steps; ++j) {
                float p[2];
                obscura::ffao_step_position(line, o, j, p);
                if (!inside(p, c.width, c.height)) continue;
                ++inside_steps;
                ASSERT_GE(j, line.first_step) << "line " << l;
                ASSERT_LT(j, line.first_step + line.steps) << "line " << l;
            }
        }
        // One step per texel of area, give or take the border: the lines are one texel apart.
        EXPECT_NEAR(double(inside_steps), double(c.width) * c.height, 2.0 * (c.width + c.height) + 4.0);
    }
    }
}

// A phase moves the lines across by its fraction of a texel, with one line more before them; phase 0 is the layout
// without one.
TEST(FfaoLayout, PhasesShiftTheLines) {
    const obscura::FfaoLayout plain = obscura::make_ffao_layout(16, 10, 97, 61);
    const obscura::FfaoLayout zero = obscura::make_ffao_layout(16, 10, 97, 61, 0.0);
    const obscura::FfaoLayout moved = obscura::make_ffao_layout(16, 10, 97, 61, 0.5);
    ASSERT_EQ(plain.lines.size(), zero.lines.size());
    EXPECT_EQ(plain.entries, zero.entries);
    for (size_t i = 0; i < plain.lines.size(); ++i) {
        EXPECT_EQ(plain.lines[i].origin[0], zero.lines[i].origin[0]);
        EXPECT_EQ(plain.lines[i].origin[1], zero.lines[i].origin[1]);
    }
    for (size_t k = 0; k < plain.orientations.size(); ++k) {
        const obscura::FfaoOrientation &a = plain.orientations[k], &b = moved.orientations[k];
        EXPECT_EQ(a.dir[0], b.dir[0]);
        EXPECT_EQ(a.dir[1], b.dir[1]);
        // Line l sits at v = v_min + l + 0.5 across the orientation.
        EXPECT_NEAR(b.v_min, a.v_min - 0.5, 1e-9) << k;
        EXPECT_EQ(b.line_count, a.line_count + 1) << k;
        const obscura::FfaoLine& line = moved.lines[size_t(b.first_line + 1)];
        const double v = -b.dir[1] * line.origin[0] + b.dir[0] * line.origin[1];
        EXPECT_NEAR(v, a.v_min + 1.0, 1e-3) << k;
    }
}

// The scan writes column (k, n, i) for exactly the lines whose walk enters the interval; the layout's run
// [first_line, first_line + lines) must be those lines, with the entries packed one after another.
TEST_P(FfaoLayoutCases, EveryLineOfAColumnsRunWritesIt) {
    const Case c = GetParam();
    for (double phase : kPhaseFractions) {
    SCOPED_TRACE("phase " + std::to_string(phase));
    const obscura::FfaoLayout layout =
        obscura::make_ffao_layout(c.sectors, c.base_interval, c.width, c.height, phase);
    int64_t offset = 0;
    for (int k = 0; k < c.sectors / 2; ++k) {
        const obscura::FfaoOrientation& o = layout.orientations[size_t(k)];
        for (int n = 0; n < layout.levels; ++n) {
            const size_t index = size_t(k) * obscura::kFfaoMaxLevels + size_t(n);
            const int length = c.base_interval << n;
            ASSERT_EQ(layout.column_count[index], (o.steps + length - 1) / length);
            for (int i = 0; i < layout.column_count[index]; ++i) {
                const obscura::FfaoColumn& column = layout.columns[size_t(layout.column_base[index] + i)];
                ASSERT_EQ(column.offset, offset);
                offset += column.lines;
                for (int l = 0; l < o.line_count; ++l) {
                    const obscura::FfaoLine& line = layout.lines[size_t(o.first_line + l)];
                    const bool walks = line.steps > 0 && line.first_step < (i + 1) * length &&
                                       line.first_step + line.steps > i * length;
                    const bool in_run = l >= column.first_line && l < column.first_line + column.lines;
                    ASSERT_EQ(walks, in_run) << "k " << k << " level " << n << " interval " << i << " line " << l;
                }
            }
        }
        // The top level's intervals are at least half the longest line: the walk reaches the far end in
        // a few steps.
        EXPECT_GE(c.base_interval << (layout.levels - 1), o.steps / 2);
    }
    EXPECT_EQ(layout.entries, offset);
    }
}

INSTANTIATE_TEST_SUITE_P(Sizes, FfaoLayoutCases,
                         ::testing::Values(Case{16, 10, 352, 198}, Case{4, 5, 64, 40}, Case{18, 10, 97, 131},
                                           Case{32, 20, 200, 120}, Case{8, 10, 1, 1}, Case{16, 3, 3, 7}));

// With rho = 1 at every distance (a falloff table of ones reached at b = 0), the slab integral is the cosine
// lobe's: integral from a to pi/2 of cos(theta - d) sin(theta) for a slab straight down (c = pi).
TEST(FfaoEstimator, SlabIntegralHasTheCosineLobesClosedForm) {
    obscura::FfaoFalloffShape ones;
    ones.kind = OBSCURA_FALLOFF_TABLE;
    for (float& v : ones.table) v = 1.0f;
    for (double a : {0.0, 0.3, 0.9, 1.4}) {
        EXPECT_NEAR(obscura::ffao_slab_integral(ones, a, 0.0, kPi, 0.0), 0.5 * std::cos(a) * std::cos(a), 1e-7) << a;
        // Normal tilted by d towards the sector: the lobe's edge moves to d + pi/2.
        const double d = 0.4, hi = d + 0.5 * kPi;
        // cos(t - d) sin t = (sin(2t - d) + sin d) / 2.
        const double exact = 0.25 * std::cos(d) + 0.25 * std::cos(2.0 * a - d) + 0.5 * (hi - a) * std::sin(d);
        EXPECT_NEAR(obscura::ffao_slab_integral(ones, a, 0.0, kPi, d), exact, 1e-7) << a;
    }
    // Over the whole hemisphere (2 pi of azimuth, divided by pi) a receiver under full occlusion gets AO 1.
    EXPECT_NEAR(2.0 * kPi * obscura::ffao_slab_integral(ones, 0.0, 0.0, kPi, 0.0) / kPi, 1.0, 1e-7);
    // Nothing below the receiver's tangent and nothing past the slab's own direction.
    EXPECT_EQ(obscura::ffao_slab_integral(ones, 1.2, 0.3, 1.1, 0.0), 0.0);
    EXPECT_NEAR(obscura::ffao_slab_integral(ones, 0.5 * kPi + 0.01, 0.0, kPi, 0.0), 0.0, 1e-12);
}

// A slab far away (b much larger than the falloff's scale) casts next to nothing; a near one more.
TEST(FfaoEstimator, FartherSlabsCastLess) {
    obscura::FfaoFalloffShape exponential;
    double previous = 1.0;
    for (double beta : {0.0, 0.1, 0.5, 2.0, 10.0}) {
        const double value = obscura::ffao_slab_integral(exponential, 0.6, beta, 2.9, 0.1);
        EXPECT_LT(value, previous) << beta;
        previous = value;
    }
    EXPECT_LT(previous, 1e-4);
}

}  // namespace
