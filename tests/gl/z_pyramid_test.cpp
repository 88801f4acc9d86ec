// SAO's z pyramid pass (sdk/src/passes/z_pyramid.*) run directly on a test pattern, every level read back
// and compared texel by texel with the rules of the SAO paper's Table 1 evaluated on the CPU. Built as
// its own executable against the SDK's private headers (static library builds only): the public API
// never exposes the pyramid's levels.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "pass_test_support.h"
#include "passes/z_pyramid.h"

namespace {

namespace gl = obscura::gl;

// The SAO paper's Table 1, z^(m+1)(x, y) from z^m, on the CPU.
float reduce_cpu(const std::vector<float>& level, int width, int x, int y, int filter) {
    auto at = [&](int sx, int sy) { return level[size_t(sy) * size_t(width) + size_t(sx)]; };
    if (filter == OBSCURA_MIP_FILTER_ROTATED_GRID) return at(2 * x + ((y & 1) ^ 1), 2 * y + ((x & 1) ^ 1));
    float a = at(2 * x, 2 * y), b = at(2 * x + 1, 2 * y), c = at(2 * x, 2 * y + 1), d = at(2 * x + 1, 2 * y + 1);
    switch (filter) {
        case OBSCURA_MIP_FILTER_MEAN: return 0.25f * (a + b + c + d);
        case OBSCURA_MIP_FILTER_HARMONIC_MEAN: return 4.0f / (1.0f / a + 1.0f / b + 1.0f / c + 1.0f / d);
        case OBSCURA_MIP_FILTER_MIN: return std::fmin(std::fmin(a, b), std::fmin(c, d));
        default: return std::fmax(std::fmax(a, b), std::fmax(c, d));
    }
}

class ZPyramid : public obscura_pass_test::PassTest, public ::testing::WithParamInterface<int> {
public:
    // Builds the pyramid of a width x height pattern with `filter` with the CPU rasteriser's program or the GPU's;
    // checks every level against the CPU.
    void check_path(bool cpu_program, int width, int height, int wanted_levels, int filter) {
        cpu_renderer_ = cpu_program;
        check(width, height, wanted_levels, filter);
        cpu_renderer_ = true;
    }

protected:
    void check(int width, int height, int wanted_levels, int filter) {
        const int levels = obscura::ZPyramidPass::level_count(width, height, wanted_levels);
        ASSERT_GT(levels, 1);
        // A pattern with every texel distinct, depths in [1, 50] m, plus sky texels.
        std::vector<float> level0(size_t(width) * size_t(height));
        uint32_t state = 12345u;
        for (size_t i = 0; i < level0.size(); ++i) {
            state = state * 1664525u + 1013904223u;
            level0[i] = (state >> 8) % 97u == 0 ? float(OBSCURA_SKY_DEPTH) : 1.0f + float(state >> 8) * (49.0f / 16777216.0f);
        }
        gl::Texture2D depth = gl::Texture2D::create(gl_, GL_R32F, width, height, levels);
        ASSERT_TRUE(depth);
        gl_.BindTexture(GL_TEXTURE_2D, depth.name());
        gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RED, GL_FLOAT, level0.data());

        obscura::ZPyramidPass pass;  // a new one: its program depends on cpu_renderer_
        ASSERT_FALSE(pass.prepare(env(), filter));
        const int dispatches = obscura::ZPyramidPass::dispatch_count(levels);
        std::vector<obscura::UniformRange> ranges;
        for (int d = 0; d < dispatches; ++d) ranges.push_back(arena_.push(obscura::ZPyramidPass::constants(d, levels)));
        arena_.upload(gl_, uniforms_.name());
        pass.run(env(), filter, ranges.data(), int(ranges.size()), depth);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);

        std::vector<float> previous = level0;
        int previous_width = width;
        int mismatches = 0;
        for (int m = 1; m < levels; ++m) {
            const int w = std::max(width >> m, 1), h = std::max(height >> m, 1);
            std::vector<float> gpu(size_t(w) * size_t(h), -1.0f);
            gl_.BindTexture(GL_TEXTURE_2D, depth.name());
            gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
            gl_.GetTexImage(GL_TEXTURE_2D, m, GL_RED, GL_FLOAT, gpu.data());
            std::vector<float> cpu(gpu.size());
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    cpu[size_t(y) * w + x] = reduce_cpu(previous, previous_width, x, y, filter);
                    const float g = gpu[size_t(y) * w + x], c = cpu[size_t(y) * w + x];
                    // Subsampling, min and max select a texel: exact. The means may round differently.
                    const bool selects = filter == OBSCURA_MIP_FILTER_ROTATED_GRID || filter == OBSCURA_MIP_FILTER_MIN ||
                                         filter == OBSCURA_MIP_FILTER_MAX;
                    const bool equal = selects ? g == c : std::fabs(g - c) <= 1e-5f * std::fabs(c);
                    if (!equal && ++mismatches <= 5) {
                        ADD_FAILURE() << "level " << m << " (" << x << ", " << y << "): gpu " << g << ", cpu " << c;
                    }
                }
            // The next level is checked against the GPU's own level (each level follows from the one above).
            previous = gpu;
            previous_width = w;
        }
        EXPECT_EQ(mismatches, 0) << width << "x" << height << ", " << levels << " levels, filter " << filter;
        gl_.BindTexture(GL_TEXTURE_2D, 0);
    }
};

// Both programs: CPU rasterisers' (three levels in registers per invocation, shared memory from the fourth) and
// GPUs' (shared memory from the second).
void check_both_paths(ZPyramid* test, int width, int height, int wanted_levels, int filter) {
    for (bool cpu : {true, false}) {
        SCOPED_TRACE(cpu ? "CPU rasteriser program" : "GPU program");
        test->check_path(cpu, width, height, wanted_levels, filter);
    }
}

// An odd size (odd levels drop their last row/column), levels within one dispatch.
TEST_P(ZPyramid, OddSizeOneDispatch) { check_both_paths(this, 203, 117, 6, GetParam()); }

// Nine levels: two dispatches, the second starting from level 6.
TEST_P(ZPyramid, NineLevelsTwoDispatches) { check_both_paths(this, 600, 520, 9, GetParam()); }

// One to three levels built: the CPU program stops inside its registers, before shared memory.
TEST_P(ZPyramid, UpToThreeLevels) {
    for (int wanted = 2; wanted <= 4; ++wanted) check_both_paths(this, 77, 45, wanted, GetParam());
}

std::string filter_name(const ::testing::TestParamInfo<int>& param_info) {
    static const char* const kNames[] = {"", "rotated_grid", "mean", "harmonic_mean", "min", "max"};
    return kNames[param_info.param];
}

INSTANTIATE_TEST_SUITE_P(Filters, ZPyramid,
                         ::testing::Values(OBSCURA_MIP_FILTER_ROTATED_GRID, OBSCURA_MIP_FILTER_MEAN,
                                           OBSCURA_MIP_FILTER_HARMONIC_MEAN, OBSCURA_MIP_FILTER_MIN,
                                           OBSCURA_MIP_FILTER_MAX),
                         filter_name);

TEST(ZPyramidLevels, CountFollowsTheShortAxisAndTheWish) {
    EXPECT_EQ(obscura::ZPyramidPass::level_count(1920, 1080, 6), 6);
    EXPECT_EQ(obscura::ZPyramidPass::level_count(1920, 1080, 1), 1);
    EXPECT_EQ(obscura::ZPyramidPass::level_count(64, 8, 10), 4);  // 8 -> 4 -> 2 -> 1: the last source is 2 wide
    EXPECT_EQ(obscura::ZPyramidPass::level_count(1, 1, 5), 1);
    EXPECT_EQ(obscura::ZPyramidPass::dispatch_count(1), 0);
    EXPECT_EQ(obscura::ZPyramidPass::dispatch_count(7), 1);
    EXPECT_EQ(obscura::ZPyramidPass::dispatch_count(8), 2);
}

}  // namespace
