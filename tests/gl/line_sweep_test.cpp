// LSAO's sweep pass (sdk/src/passes/lsao.*, sdk/glsl/line_sweep.comp) run directly on a synthetic depth
// buffer, its counters and values read back: the work done is the layout's steps at any radius (the
// paper's radius independence), pops never outnumber steps (amortised O(1)), the GPU hull matches the
// GPU brute force, and what a bounded hull costs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "frame_input.h"
#include "pass_test_support.h"
#include "passes/lsao.h"
#include "testing/pass_inspection.h"
#include "settings.h"

namespace {

namespace gl = obscura::gl;

constexpr int kWidth = 192, kHeight = 128;
constexpr uint16_t kPoison = 0x7bff;  // 65504, the largest half: no sweep value comes near it
constexpr float kPoisonValue = 65504.0f;

class LineSweep : public obscura_pass_test::PassTest {
protected:
    void SetUp() override {
        PassTest::SetUp();
        // A wavy wall 6 m away with a box 1.5 m in front of it and a pillar.
        std::vector<float> depth(size_t(kWidth) * kHeight);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                float d = 6.0f + 0.8f * std::sin(x * 0.05f) * std::sin(y * 0.07f);
                if (x >= 60 && x < 120 && y >= 40 && y < 90) d = 4.5f;
                if (x >= 140 && x < 150) d = 3.0f;
                depth[size_t(y) * kWidth + x] = d;
            }
        obscura_pass_test::upload_linear_depth(gl_, depth, kWidth, kHeight, &resources_);

        input_.width = kWidth;
        input_.height = kHeight;
        frame_ = obscura_pass_test::perspective_linear_depth_frame(kWidth, kHeight, input_.projection.m);
    }

    struct Sweep {
        uint32_t steps = 0, pops = 0, dropped = 0;
        std::vector<float> values;
        std::vector<float> visibility;  // the gather's output, when asked for
    };

    Sweep sweep(obscura_lsao_settings lsao, bool gather = false) {
        obscura_settings settings;
        obscura_default_settings(OBSCURA_METHOD_LSAO, &settings);
        settings.lsao = lsao;
        obscura_settings resolved;
        EXPECT_FALSE(obscura::resolve_settings(settings, &resolved));
        EXPECT_FALSE(pass_.prepare(env(), resolved.lsao));
        obscura::LsaoPassInspection::collect_stats(pass_, true);
        EXPECT_FALSE(pass_.ensure_layout(env(), resolved.lsao, kWidth, kHeight));
        GLint alignment = 256;
        gl_.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
        arena_.reset(alignment);
        obscura::UniformRange frame = arena_.push(frame_);
        obscura::UniformRange pass = arena_.push(pass_.constants(resolved.lsao, input_, env().cpu_renderer));
        arena_.upload(gl_, uniforms_.name());
        obscura::LsaoPassInspection::fill_values(pass_, gl_, kPoison);  // what the sweep does not write keeps it
        pass_.run_sweeps(env(), resolved.lsao, frame, pass, resources_);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        Sweep out;
        uint32_t stats[3] = {};
        obscura::LsaoPassInspection::read_stats(pass_, gl_, stats);
        out.steps = stats[0];
        out.pops = stats[1];
        out.dropped = stats[2];
        out.values = obscura::LsaoPassInspection::read_values(pass_, gl_);
        if (gather) {
            if (!resources_.ao.name()) resources_.ao = gl::Texture2D::create(gl_, GL_R16F, kWidth, kHeight);
            pass_.run_gather(env(), frame, pass, obscura::Region{0, 0, kWidth, kHeight}, resources_);
            gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
            out.visibility.assign(size_t(kWidth) * kHeight, -1.0f);
            gl_.BindTexture(GL_TEXTURE_2D, resources_.ao.name());
            gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
            gl_.GetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, out.visibility.data());
            gl_.BindTexture(GL_TEXTURE_2D, 0);
        }
        return out;
    }

    // The defaults with the paper's fixed tangent: the fixture's normals texture is all zero (every normal faces the
    // camera), so the receiver's tangent (the default strategy) would sweep with made-up tangents. The scene tests
    // of lsao_test.cpp run the defaults on real normals.
    static obscura_lsao_settings defaults() {
        obscura_settings s;
        obscura_default_settings(OBSCURA_METHOD_LSAO, &s);
        s.lsao.tangent_strategy = 3;
        return s.lsao;
    }

    int64_t layout_steps() const {
        int64_t total = 0;
        for (const obscura::LsaoLine& line : pass_.layout().lines) total += line.steps;
        return total;
    }

    // Mean |a - b| over samples that have a value in both.
    static double mean_difference(const std::vector<float>& a, const std::vector<float>& b) {
        double sum = 0.0;
        int count = 0;
        for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
            if (a[i] > 2.0f || b[i] > 2.0f) continue;
            sum += std::fabs(double(a[i]) - b[i]);
            ++count;
        }
        return count > 0 ? sum / count : 0.0;
    }

    obscura::FrameResources resources_;
    obscura::FrameInput input_;
    FrameConstants frame_ = {};
    obscura::LsaoPass pass_;
};

// The paper's headline: the work is the number of steps, fixed by the layout, at any radius; pops are
// bounded by pushes.
TEST_F(LineSweep, WorkDoesNotDependOnTheRadius) {
    for (float radius : {0.1f, 1.0f, 10.0f}) {
        obscura_lsao_settings lsao = defaults();
        lsao.radius = radius;
        lsao.decay_rate = 0.0f;  // derived from the radius again (0.3 r^2)
        Sweep s = sweep(lsao);
        EXPECT_EQ(int64_t(s.steps), layout_steps()) << "radius " << radius;
        EXPECT_LE(s.pops, s.steps) << "radius " << radius;
        RecordProperty("pops_at_radius_" + std::to_string(radius), std::to_string(s.pops));
    }
    EXPECT_GT(layout_steps(), kWidth * kHeight * 3);  // K / (D_S D_L) = 4 values per pixel
}

// The hull against the brute force on the GPU, per sample (the per-pixel AO error is in lsao_test.cpp).
TEST_F(LineSweep, HullMatchesBruteForce) {
    obscura_lsao_settings hull = defaults();
    obscura_lsao_settings exact = hull;
    exact.exact = OBSCURA_TOGGLE_ON;
    Sweep a = sweep(hull);
    Sweep b = sweep(exact);
    ASSERT_EQ(a.values.size(), b.values.size());
    int worse = 0;
    for (size_t i = 0; i < a.values.size(); ++i) {
        if (b.values[i] > 2.0f) continue;
        EXPECT_LE(a.values[i], b.values[i] + 2e-3f) << i;  // the hull returns an earlier point: never more
        worse += a.values[i] < b.values[i] - 2e-3f;
    }
    const double mean = mean_difference(a.values, b.values);
    EXPECT_LT(mean, 0.01);
    RecordProperty("mean_abs_hull_vs_exact_per_sample", std::to_string(mean));
    RecordProperty("samples_below_exact", std::to_string(worse));
}

// A GPU's programs take other memory paths than a CPU rasteriser's: the hulls in shared memory rather than a
// private array, line records and values from storage buffers rather than buffer textures, and the gather's
// depths from a tile in shared memory. Both compute the same values and the same image, for every preset
// (margins of 2 to 4 texels) and with the free pattern.
TEST_F(LineSweep, GpuProgramsMatchCpuPrograms) {
    for (int preset = 1; preset <= 5; ++preset) {
        obscura_lsao_settings lsao = defaults();
        lsao.directions = 0;  // the preset's K, D_S and D_L
        lsao.step_length = 0.0f;
        lsao.line_spacing = 0.0f;
        if (preset <= 4) {
            lsao.preset = preset;
        } else {
            lsao.pattern = 2;  // free directions
            lsao.directions = 12;
        }
        lsao.segment_steps = -1;  // whole lines on both
        cpu_renderer_ = true;
        const Sweep cpu = sweep(lsao, true);
        cpu_renderer_ = false;
        const Sweep gpu = sweep(lsao, true);
        const std::string name = "case " + std::to_string(preset);
        ASSERT_EQ(gpu.values.size(), cpu.values.size()) << name;
        EXPECT_EQ(gpu.pops, cpu.pops) << name;
        EXPECT_GT(gpu.pops, 0u) << name;
        int different = 0;
        for (size_t i = 0; i < cpu.values.size(); ++i) different += gpu.values[i] != cpu.values[i];
        EXPECT_EQ(different, 0) << name;
        ASSERT_EQ(gpu.visibility.size(), cpu.visibility.size());
        int different_pixels = 0, unwritten = 0;
        float darkest = 1.0f;
        for (size_t i = 0; i < cpu.visibility.size(); ++i) {
            different_pixels += gpu.visibility[i] != cpu.visibility[i];
            unwritten += gpu.visibility[i] < 0.0f;
            darkest = std::min(darkest, gpu.visibility[i]);
        }
        EXPECT_EQ(different_pixels, 0) << name;
        EXPECT_EQ(unwritten, 0) << name;
        // The box and the pillar occlude the wall (the longer steps of K = 24 and 32 leave this small scene's
        // receivers with less than the fixed tangent's bias).
        if (preset == 1 || preset == 2 || preset == 5) {
            EXPECT_LT(darkest, 0.95f) << name;
        }
    }
}

// What bounding the hull costs: capacity 4 drops points (and changes values); 16 agrees with 64, the
// default and the largest (OBSCURA_LSAO_MAX_HULL, the shared-memory hull's size).
TEST_F(LineSweep, BoundedHullError) {
    obscura_lsao_settings lsao = defaults();
    lsao.hull_capacity = OBSCURA_LSAO_MAX_HULL;
    Sweep wide = sweep(lsao);
    lsao.hull_capacity = 16;
    Sweep normal = sweep(lsao);
    lsao.hull_capacity = 4;
    Sweep tiny = sweep(lsao);
    EXPECT_GT(tiny.dropped, 0u);
    const double normal_error = mean_difference(normal.values, wide.values);
    const double tiny_error = mean_difference(tiny.values, wide.values);
    EXPECT_LT(normal_error, 1e-3);
    EXPECT_GT(tiny_error, normal_error);
    RecordProperty("dropped_at_16", std::to_string(normal.dropped));
    RecordProperty("error_at_16", std::to_string(normal_error));
    RecordProperty("dropped_at_4", std::to_string(tiny.dropped));
    RecordProperty("error_at_4", std::to_string(tiny_error));
}

// Segments (one GPU thread each) after a warm-up the falloff bounds. rho0 reaches zero at the radius, so a
// warm-up past it loses nothing: the values match whole lines. r/(r+d^2) never does: the tolerance bounds
// what an occluder before the warm-up could cast, and the error stays well under it. Every value is written.
TEST_F(LineSweep, SegmentsMatchWholeLines) {
    struct Case {
        int falloff;
        float tolerance;
        double mean_limit;
    };
    for (const Case& c : {Case{1, 1e-3f, 1e-4}, Case{2, 0.01f, 2e-3}, Case{2, 0.05f, 0.01}, Case{2, 1.0f, 1.0}}) {
        obscura_lsao_settings lsao = defaults();
        lsao.falloff = c.falloff;
        lsao.radius = 0.5f;
        lsao.decay_rate = 0.0f;
        lsao.segment_steps = -1;
        const Sweep whole = sweep(lsao);
        lsao.segment_steps = 8;
        lsao.warmup_tolerance = c.tolerance;
        const Sweep segments = sweep(lsao);
        const std::string name = "falloff " + std::to_string(c.falloff) + " tolerance " + std::to_string(c.tolerance);
        ASSERT_EQ(segments.values.size(), whole.values.size());
        int unwritten = 0;
        for (const float v : segments.values) unwritten += v == kPoisonValue;
        EXPECT_EQ(unwritten, 0) << name << ": each line's values and the padding after them are all stored";
        double max_error = 0.0;
        for (size_t i = 0; i < whole.values.size(); ++i) {
            if (!(whole.values[i] < 2.0f) || !(segments.values[i] < 2.0f)) continue;
            max_error = std::max(max_error, std::fabs(double(whole.values[i]) - segments.values[i]));
        }
        const double mean = mean_difference(segments.values, whole.values);
        EXPECT_LT(mean, c.mean_limit) << name;
        EXPECT_GT(int64_t(segments.steps), layout_steps()) << name << ": the warm-ups are extra steps";
        RecordProperty(name + " mean", std::to_string(mean));
        RecordProperty(name + " max", std::to_string(max_error));
        RecordProperty(name + " work", std::to_string(double(segments.steps) / double(layout_steps())));
    }
}

}  // namespace

namespace {

// The warm-up's far part at a stride: fewer steps than a dense warm-up, and nearly the same values (a coarse
// hull of far occluders casts nearly what the full one does; the last 16 warm-up steps stay dense).
TEST_F(LineSweep, StridedWarmupCostsLittle) {
    obscura_lsao_settings lsao = defaults();
    lsao.falloff = 2;
    lsao.radius = 3.0f;  // a wide falloff: warm-ups of dozens of steps
    lsao.decay_rate = 0.0f;
    lsao.segment_steps = -1;
    const Sweep whole = sweep(lsao);
    lsao.segment_steps = 16;
    lsao.warmup_tolerance = 0.02f;
    lsao.warmup_stride = 1;
    const Sweep dense = sweep(lsao);
    lsao.warmup_stride = 8;
    const Sweep strided = sweep(lsao);
    int unwritten = 0;
    for (const float v : strided.values) unwritten += v == kPoisonValue;
    EXPECT_EQ(unwritten, 0);
    EXPECT_LT(strided.steps * 10, dense.steps * 9) << "the stride skips warm-up steps";
    const double dense_error = mean_difference(dense.values, whole.values);
    const double strided_error = mean_difference(strided.values, whole.values);
    EXPECT_LT(strided_error, 2e-3);
    EXPECT_LT(strided_error, dense_error + 1e-3);
    RecordProperty("dense_warmup_steps", std::to_string(dense.steps));
    RecordProperty("strided_warmup_steps", std::to_string(strided.steps));
    RecordProperty("dense_error", std::to_string(dense_error));
    RecordProperty("strided_error", std::to_string(strided_error));
}

}  // namespace
