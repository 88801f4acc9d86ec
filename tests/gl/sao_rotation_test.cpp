// SAO's per-pixel spiral rotation (eq. 8: rotation() in sdk/glsl/sao.comp) observed on the GPU and compared with the
// host's copy, obscura::spiral_rotation, which tests/unit/sao_pattern_test.cpp checks against the equation. That unit
// test never runs the shader: a swapped x and y, a float reduction or a wrong constant in the shader's own rotation
// passed every test. Run directly through the private headers (passes/sao.h): the test needs the host's rotation and
// spiral, and sets the frame's noise offset itself.
//
// The observable: the tap-count debug view of the SAO pass (target_params.w = TAP_COUNT) writes, per pixel, how many
// of its taps fell inside the texture. With one tap (s = 1: alpha 0.5 at the angle pi) and a ball far larger on
// screen than max_radius_pixels, every pixel's tap lies at p + 0.5 + h (cos, sin)(pi + phi(p)), h = the cap / 2,
// and nothing else in the pass depends on p: near a border the count is 0 exactly where the rotated tap points out
// past it, a half-plane test of the pixel's rotation angle, predicted here from spiral_rotation and spiral_tap.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "frame_input.h"
#include "pass_test_support.h"
#include "passes/sao.h"
#include "settings.h"

namespace {

namespace gl = obscura::gl;

// A 4K frame: at its far corner 10 x y reaches 8e7, where eq. 8's integer is no longer exact in a float and a float
// reduction gives unrelated angles (in the corner at the origin it is off by about 1e-3 rad, too little to show).
constexpr int kWidth = 3840, kHeight = 2160;
constexpr float kDepth = 5.0f;       // a plane facing the camera: every pixel at the same depth, none sky
constexpr float kRadius = 2.0f;      // m: about 750 px on screen at kDepth, so radius_px is the cap below
constexpr float kCapPixels = 80.0f;  // max_radius_pixels: h = 40 px, so most pixels within 40 px of a border tell
// Predicted tap positions closer than this to a border line count as either side: the shader's float arithmetic
// (its sin and cos included) moves a tap by far less (about 1e-3 px at 4K coordinates).
constexpr double kMargin = 0.05;
constexpr double kTwoPi = 6.283185307179586;

// The two corners of the texture, 64x48 each (starting on even coordinates, as SAO's regions do): near the origin
// the left and bottom borders, at the far corner the right and top ones with 4K coordinates.
const obscura::Region kRegions[] = {{0, 0, 64, 48}, {kWidth - 64, kHeight - 48, 64, 48}};

enum class Tap { Inside, Outside, Either };

class SaoRotation : public obscura_pass_test::PassTest {
protected:
    void SetUp() override {
        PassTest::SetUp();
        frame_ = obscura_pass_test::perspective_linear_depth_frame(kWidth, kHeight, input_.projection.m);
        frame_.target_params[3] = OBSCURA_DEBUG_VIEW_TAP_COUNT;
        input_.width = kWidth;
        input_.height = kHeight;
        input_.meters_to_view_units = 1.0f;
        obscura_pass_test::upload_linear_depth(gl_, std::vector<float>(size_t(kWidth) * kHeight, kDepth), kWidth,
                                               kHeight, &resources_);
        packed_ = gl::Texture2D::create(gl_, GL_RGBA8, kWidth, kHeight);
        obscura_settings settings;
        obscura_default_settings(OBSCURA_METHOD_SAO, &settings);
        settings.sao.samples = 1;
        settings.sao.radius = kRadius;
        settings.sao.max_radius_pixels = kCapPixels;
        settings.sao.mip = OBSCURA_TOGGLE_OFF;  // level 0 only (no pyramid to build): which level is read changes
                                                // nothing in the count
        obscura_settings resolved;
        ASSERT_FALSE(obscura::resolve_settings(settings, &resolved));
        sao_ = resolved.sao;
        ASSERT_FALSE(pass_.prepare(env(), sao_));
    }

    // The tap count (0 or 1) of each pixel of `region` (row-major, bottom row first) with the frame's noise offset
    // `noise` (noise_offset.x, in turns).
    std::vector<int> tap_counts(const obscura::Region& region, float noise) {
        FrameConstants frame = obscura::with_work_rect(frame_, region);
        frame.noise_offset[0] = noise;
        GLint alignment = 256;
        gl_.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
        arena_.reset(alignment);
        const obscura::UniformRange frame_range = arena_.push(frame);
        const obscura::UniformRange pass_range = arena_.push(obscura::SaoPass::constants(sao_, input_, 0));
        arena_.upload(gl_, uniforms_.name());
        pass_.run(env(), sao_, frame_range, pass_range, region, resources_, packed_);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        // R holds taps / 256 in 8 bits: 1 tap reads back as the byte 1.
        std::vector<uint8_t> red(size_t(kWidth) * kHeight);
        gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl_.BindTexture(GL_TEXTURE_2D, packed_.name());
        gl_.GetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_UNSIGNED_BYTE, red.data());
        gl_.BindTexture(GL_TEXTURE_2D, 0);
        std::vector<int> counts;
        for (int y = region.y; y < region.y + region.height; ++y)
            for (int x = region.x; x < region.x + region.width; ++x) counts.push_back(red[size_t(y) * kWidth + x]);
        return counts;
    }

    // Where pixel (x, y)'s one tap falls with the rotation `rotation(x, y)`: the shader's angle phi (a float: the
    // reduced eq. 8 plus the noise offset's turns) added to the unrotated tap's, at h = radius_px alpha.
    template <class Rotation>
    Tap predicted(int x, int y, float noise, Rotation rotation) const {
        const obscura::SpiralTap tap = obscura::spiral_tap(0, sao_.samples, sao_.turns);
        const float phi = rotation(x, y) + noise * float(kTwoPi);
        const double angle = double(tap.angle) + double(phi), h = double(kCapPixels) * double(tap.alpha);
        const double tx = x + 0.5 + h * std::cos(angle), ty = y + 0.5 + h * std::sin(angle);
        auto near = [](double v, double edge) { return std::fabs(v - edge) < kMargin; };
        if (near(tx, 0.0) || near(tx, kWidth) || near(ty, 0.0) || near(ty, kHeight)) return Tap::Either;
        return tx >= 0.0 && tx < kWidth && ty >= 0.0 && ty < kHeight ? Tap::Inside : Tap::Outside;
    }

    obscura::FrameInput input_;
    FrameConstants frame_ = {};
    obscura::FrameResources resources_;
    gl::Texture2D packed_;
    obscura_sao_settings sao_ = {};
    obscura::SaoPass pass_;
};

// With frame 0's noise offset (frame_planner.cpp's R2 point of index 0: 0) and frame 1's (0.75487767 turns), which the
// shader adds to eq. 8's angle.
TEST_F(SaoRotation, ShaderRotatesTheTapAsSpiralRotation) {
    ASSERT_EQ(sao_.samples, 1);
    const obscura::SpiralTap tap = obscura::spiral_tap(0, sao_.samples, sao_.turns);
    ASSERT_FLOAT_EQ(tap.alpha, 0.5f);
    const auto eq8 = [](int x, int y) { return obscura::spiral_rotation(x, y); };
    const auto swapped = [](int x, int y) { return obscura::spiral_rotation(y, x); };
    for (float noise : {0.0f, float(0.7548776662466927)}) {
        for (const obscura::Region& region : kRegions) {
            const std::string name = "noise " + std::to_string(noise) + ", region at (" + std::to_string(region.x) +
                                     ", " + std::to_string(region.y) + ")";
            const std::vector<int> counts = tap_counts(region, noise);
            int outside = 0, inside = 0, either = 0, wrong = 0, told_from_swapped = 0;
            std::string first_wrong;
            for (int j = 0; j < region.height; ++j)
                for (int i = 0; i < region.width; ++i) {
                    const int x = region.x + i, y = region.y + j;
                    const Tap expected = predicted(x, y, noise, eq8);
                    const int count = counts[size_t(j) * region.width + i];
                    if (expected == Tap::Either) {
                        ++either;
                        EXPECT_TRUE(count == 0 || count == 1) << name << ": (" << x << ", " << y << ") " << count;
                        continue;
                    }
                    (expected == Tap::Inside ? inside : outside) += 1;
                    if (count != (expected == Tap::Inside ? 1 : 0)) {
                        if (wrong++ < 8) {
                            first_wrong += " (" + std::to_string(x) + ", " + std::to_string(y) + "): " +
                                           std::to_string(count) + " taps, phi " +
                                           std::to_string(obscura::spiral_rotation(x, y));
                        }
                    }
                    const Tap other = predicted(x, y, noise, swapped);
                    told_from_swapped += other != Tap::Either && other != expected ? 1 : 0;
                }
            EXPECT_EQ(wrong, 0) << name << ": " << outside << " outside, " << inside << " inside, " << either
                                << " either;" << first_wrong;
            // The observable tells rotations apart: both outcomes are common, few pixels are undecided, and eq. 8
            // with x and y swapped predicts other counts at many pixels (measured in each case: about 1300 outside,
            // 1750 inside, at most 6 undecided, 1200 told from the swapped rotation, of 3072).
            EXPECT_GT(outside, 1000) << name;
            EXPECT_GT(inside, 1000) << name;
            EXPECT_LT(either, 30) << name;
            EXPECT_GT(told_from_swapped, 800) << name;
        }
    }
}

}  // namespace
