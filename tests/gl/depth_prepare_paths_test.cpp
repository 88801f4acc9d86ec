// The depth preparation pass (sdk/src/passes/depth_prepare.*, sdk/glsl/depth_prepare.comp) run directly:
// a GPU's program shares the depths a normal reconstruction reads through a tile in shared memory, a CPU
// rasteriser's reads each 4x4 block's footprint once per invocation. Both must give the same linear depths and
// normals, at the texture's edges (odd sizes: partial blocks), next to sky and with host normals of either kind too.
// Normals asked for part of the texture only (the AO region) must be the same there, and the linear depth the same
// everywhere.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <algorithm>

#include "frame_input.h"
#include "pass_test_support.h"
#include "passes/depth_prepare.h"

namespace {

namespace gl = obscura::gl;

// Not a multiple of the 8x8 groups, so the last groups are partial.
constexpr int kWidth = 53, kHeight = 37;

class DepthPreparePaths : public obscura_pass_test::PassTest {
protected:
    void SetUp() override {
        PassTest::SetUp();
        // Linear view depth: a tilted wavy wall, a box in front of it, a crease and a sky corner.
        std::vector<float> depth(size_t(kWidth) * kHeight);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                float d = 5.0f + 0.03f * x + 0.5f * std::sin(x * 0.3f) * std::cos(y * 0.2f);
                if (x >= 20 && x < 31 && y >= 9 && y < 22) d = 3.5f;
                if (x >= 40) d -= 0.08f * float(x - 40);  // a crease
                if (x + y < 8) d = INFINITY;              // sky
                depth[size_t(y) * kWidth + x] = d;
            }
        std::vector<float> normals(size_t(kWidth) * kHeight * 4);
        for (size_t i = 0; i < normals.size(); i += 4) {
            normals[i] = 0.3f * std::sin(float(i));
            normals[i + 1] = 0.2f;
            normals[i + 2] = 0.9f;
            normals[i + 3] = 0.0f;
        }
        host_depth_ = gl::Texture2D::create(gl_, GL_R32F, kWidth, kHeight);
        host_normals_ = gl::Texture2D::create(gl_, GL_RGBA32F, kWidth, kHeight);
        gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl_.BindTexture(GL_TEXTURE_2D, host_depth_.name());
        gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RED, GL_FLOAT, depth.data());
        gl_.BindTexture(GL_TEXTURE_2D, host_normals_.name());
        gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, normals.data());
        gl_.BindTexture(GL_TEXTURE_2D, 0);
        resources_.width = kWidth;
        resources_.height = kHeight;
        resources_.linear_depth = gl::Texture2D::create(gl_, GL_R32F, kWidth, kHeight);
        resources_.normals = gl::Texture2D::create(gl_, GL_RG16_SNORM, kWidth, kHeight);

        input_.depth_texture = host_depth_.name();
        input_.depth_linear = true;
        input_.width = kWidth;
        input_.height = kHeight;
        frame_ = obscura_pass_test::perspective_linear_depth_frame(kWidth, kHeight, input_.projection.m);
    }

    struct Prepared {
        std::vector<float> depth;
        std::vector<int16_t> normals;
    };

    // The frame constants of a dispatch over `rect`.
    obscura::UniformRange push_frame(const obscura::Region& rect) {
        return arena_.push(obscura::with_work_rect(frame_, rect));
    }

    // Runs the pass with the normals asked for `normals` (the whole texture by default); the textures hold sentinels
    // before it.
    Prepared prepare(int normal_mode, obscura::Region normals = {0, 0, kWidth, kHeight}) {
        obscura::DepthPreparePass pass;  // a new one: the program depends on cpu_renderer_
        input_.normal_texture = normal_mode == OBSCURA_NORMALS_RECONSTRUCT ? 0 : host_normals_.name();
        input_.normal_mode = normal_mode;
        frame_.depth_size[3] = normal_mode;
        EXPECT_FALSE(pass.prepare(env(), input_));
        const std::vector<float> depth_sentinel(size_t(kWidth) * kHeight, -7.0f);
        const std::vector<int16_t> normal_sentinel(size_t(kWidth) * kHeight * 2, int16_t(4321));
        gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 2);
        gl_.BindTexture(GL_TEXTURE_2D, resources_.linear_depth.name());
        gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RED, GL_FLOAT, depth_sentinel.data());
        gl_.BindTexture(GL_TEXTURE_2D, resources_.normals.name());
        gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RG, GL_SHORT, normal_sentinel.data());
        gl_.BindTexture(GL_TEXTURE_2D, 0);
        gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        GLint alignment = 256;
        gl_.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
        arena_.reset(alignment);
        const obscura::Region whole{0, 0, kWidth, kHeight};
        rects_ = obscura::depth_prepare_rects(whole, normals, obscura::DepthPreparePass::block(env()));
        obscura::DepthPrepareUniforms uniforms;
        uniforms.with_normals = push_frame(rects_.with_normals);
        for (int i = 0; i < rects_.depth_only_count; ++i) uniforms.depth_only[i] = push_frame(rects_.depth_only[i]);
        arena_.upload(gl_, uniforms_.name());
        pass.run(env(), input_, rects_, uniforms, resources_);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        Prepared out;
        out.depth.assign(size_t(kWidth) * kHeight, -1.0f);
        out.normals.assign(size_t(kWidth) * kHeight * 2, int16_t(-12345));
        gl_.PixelStorei(GL_PACK_ALIGNMENT, 2);
        gl_.BindTexture(GL_TEXTURE_2D, resources_.linear_depth.name());
        gl_.GetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, out.depth.data());
        gl_.BindTexture(GL_TEXTURE_2D, resources_.normals.name());
        gl_.GetTexImage(GL_TEXTURE_2D, 0, GL_RG, GL_SHORT, out.normals.data());
        gl_.BindTexture(GL_TEXTURE_2D, 0);
        return out;
    }

    gl::Texture2D host_depth_, host_normals_;
    obscura::DepthPrepareRects rects_;  // of the last prepare()
    obscura::FrameInput input_;
    FrameConstants frame_ = {};
    obscura::FrameResources resources_;
};

TEST_F(DepthPreparePaths, SharedMemoryTileMatchesTexelFetches) {
    for (int mode : {OBSCURA_NORMALS_RECONSTRUCT, OBSCURA_NORMALS_SIGNED, OBSCURA_NORMALS_UNSIGNED}) {
        cpu_renderer_ = true;
        const Prepared cpu = prepare(mode);
        cpu_renderer_ = false;
        const Prepared gpu = prepare(mode);
        const std::string name = "normal mode " + std::to_string(mode);
        int depth_different = 0, normals_different = 0, sky = 0, tilted = 0;
        for (size_t i = 0; i < cpu.depth.size(); ++i) {
            depth_different += std::memcmp(&cpu.depth[i], &gpu.depth[i], sizeof(float)) != 0;
            normals_different += cpu.normals[2 * i] != gpu.normals[2 * i] || cpu.normals[2 * i + 1] != gpu.normals[2 * i + 1];
            sky += cpu.depth[i] > 1e29f;
            tilted += std::abs(int(gpu.normals[2 * i])) > 1000;  // octahedral x of a normal that is not +z
        }
        EXPECT_EQ(depth_different, 0) << name;
        EXPECT_EQ(normals_different, 0) << name;
        EXPECT_GT(sky, 20) << name << ": the sky corner";
        EXPECT_GT(tilted, kWidth * kHeight / 4) << name << ": the wall is tilted and wavy, the host normals too";
    }
}

// Normals for a rectangle inside the texture (an AO region with a guard band around it): the linear depth as with
// normals everywhere, each texel written once; the normals the same inside the rectangle (their reconstruction reads
// the depths beyond it), not written outside the block-aligned rectangle.
TEST_F(DepthPreparePaths, NormalsOnlyInTheirRegion) {
    struct Case {
        obscura::Region region;
        int strips;  // depth-only strips around it
    };
    // Not on the 4x4 blocks; inside, and reaching the texture's last column and row (odd sizes: partial blocks).
    const Case cases[] = {{{9, 6, 30, 21}, 4}, {{22, 17, kWidth - 22, kHeight - 17}, 2}};
    for (int run = 0; run < 8; ++run) {
        const Case& c = cases[run & 1];
        const int mode = (run & 2) ? OBSCURA_NORMALS_SIGNED : OBSCURA_NORMALS_RECONSTRUCT;
        cpu_renderer_ = (run & 4) == 0;
        const obscura::Region& region = c.region;
        const Prepared everywhere = prepare(mode);
        ASSERT_EQ(rects_.depth_only_count, 0);
        const Prepared part = prepare(mode, region);
        const obscura::Region& n = rects_.with_normals;
        const std::string name = std::string(cpu_renderer_ ? "CPU blocks" : "GPU tiles") + ", normal mode " +
                                 std::to_string(mode) + ", region at " + std::to_string(region.x) + "," +
                                 std::to_string(region.y);
        EXPECT_EQ(rects_.depth_only_count, c.strips) << name;
        EXPECT_TRUE(n.x <= region.x && n.y <= region.y && n.x + n.width >= region.x + region.width &&
                    n.y + n.height >= region.y + region.height) << name;
        int depth_different = 0, normals_different = 0, written_outside = 0, inside = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const size_t i = size_t(y) * kWidth + x;
                depth_different += std::memcmp(&everywhere.depth[i], &part.depth[i], sizeof(float)) != 0;
                const bool in = x >= n.x && x < n.x + n.width && y >= n.y && y < n.y + n.height;
                const bool same = everywhere.normals[2 * i] == part.normals[2 * i] &&
                                  everywhere.normals[2 * i + 1] == part.normals[2 * i + 1];
                const bool sentinel = part.normals[2 * i] == 4321 && part.normals[2 * i + 1] == 4321;
                inside += in;
                normals_different += in && !same;
                written_outside += !in && !sentinel;
            }
        }
        EXPECT_EQ(depth_different, 0) << name;
        EXPECT_EQ(normals_different, 0) << name;
        EXPECT_EQ(written_outside, 0) << name;
        EXPECT_GE(inside, region.width * region.height) << name;
        EXPECT_LT(inside, kWidth * kHeight / 2) << name;
    }
}

// The rectangles tile the whole texture, each texel once, the normals' one holding the region asked for and starting
// on the block grid.
TEST(DepthPrepareRects, TileTheTextureOnce) {
    const obscura::Region whole{0, 0, 37, 23};
    const obscura::Region regions[] = {{0, 0, 37, 23}, {5, 3, 20, 11}, {0, 4, 9, 19}, {33, 0, 4, 23}, {36, 22, 1, 1},
                                       {1, 1, 35, 21}};
    for (int block : {1, 4}) {
        for (const obscura::Region& region : regions) {
            const obscura::DepthPrepareRects rects = obscura::depth_prepare_rects(whole, region, block);
            std::vector<int> covered(size_t(whole.width) * whole.height, 0);
            const auto cover = [&](const obscura::Region& r) {
                for (int y = r.y; y < r.y + r.height; ++y) {
                    for (int x = r.x; x < r.x + r.width; ++x) ++covered[size_t(y) * whole.width + x];
                }
            };
            cover(rects.with_normals);
            for (int i = 0; i < rects.depth_only_count; ++i) {
                EXPECT_GT(rects.depth_only[i].width, 0);
                EXPECT_GT(rects.depth_only[i].height, 0);
                cover(rects.depth_only[i]);
            }
            EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), long(covered.size()))
                << "block " << block << ", region at " << region.x << "," << region.y;
            const obscura::Region& n = rects.with_normals;
            EXPECT_EQ(n.x % block, 0);
            EXPECT_EQ(n.y % block, 0);
            EXPECT_TRUE(n.x <= region.x && n.y <= region.y && n.x + n.width >= region.x + region.width &&
                        n.y + n.height >= region.y + region.height);
            if (block == 1) {
                EXPECT_EQ(n.width * n.height, region.width * region.height);
            }
        }
    }
}

}  // namespace
