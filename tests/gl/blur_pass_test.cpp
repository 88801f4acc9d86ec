// HBAO's bilateral blur and SAO's blur (sdk/src/passes/bilateral_blur.*, sao.*; sdk/glsl/bilateral_blur.comp,
// sao_blur.comp) run directly. CPU rasterisers filter runs of 16 pixels per invocation from one window of reads and
// GPUs one pixel (OBSCURA_BLUR_RUN_* / OBSCURA_SAO_BLUR_RUN_*): for every compiled-in radius and stride both must
// give the same image, bit for bit, over exactly the pass's region; HBAO's x pass must also match the filter's
// formula computed here.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "pass_test_support.h"
#include "passes/bilateral_blur.h"
#include "passes/sao.h"

namespace {

namespace gl = obscura::gl;

// Odd sizes: the runs end inside the region on both axes.
constexpr int kWidth = 71, kHeight = 43;
constexpr float kSentinel = -7.0f;

// A wavy wall with a box in front of it (depth edges) and a patch of sky.
float scene_depth(int x, int y) {
    if (x < 7 && y > 35) return OBSCURA_SKY_DEPTH;
    if (x >= 22 && x < 41 && y >= 9 && y < 31) return 4.0f;
    return 6.0f + 0.8f * std::sin(float(x) * 0.21f) * std::sin(float(y) * 0.17f);
}

// Noise in [0, 1), the same for every run.
float noise(int x, int y) { return float((uint32_t(y * kWidth + x) * 2654435761u) % 1000u) / 999.0f; }

class BlurPass : public obscura_pass_test::PassTest {
protected:
    void SetUp() override {
        PassTest::SetUp();
        std::vector<float> depth(size_t(kWidth) * kHeight);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) depth[size_t(y) * kWidth + x] = scene_depth(x, y);
        obscura_pass_test::upload_linear_depth(gl_, depth, kWidth, kHeight, &resources_);
        float matrix[16];
        frame_ = obscura_pass_test::perspective_linear_depth_frame(kWidth, kHeight, matrix);
    }

    gl::Texture2D texture(GLenum format, const std::vector<float>& rgba) {
        gl::Texture2D t = gl::Texture2D::create(gl_, format, kWidth, kHeight);
        gl_.BindTexture(GL_TEXTURE_2D, t.name());
        gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, rgba.data());
        gl_.BindTexture(GL_TEXTURE_2D, 0);
        return t;
    }
    std::vector<float> filled(float value) const { return std::vector<float>(size_t(kWidth) * kHeight * 4, value); }

    std::vector<float> read_red(const gl::Texture2D& t) {
        std::vector<float> red(size_t(kWidth) * kHeight);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl_.BindTexture(GL_TEXTURE_2D, t.name());
        gl_.GetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, red.data());
        gl_.BindTexture(GL_TEXTURE_2D, 0);
        return red;
    }

    // The frame constants of a pass over `region`, and the pass's own, uploaded together.
    template <typename Constants>
    std::pair<obscura::UniformRange, obscura::UniformRange> uniforms(const obscura::Region& region,
                                                                      const Constants& pass) {
        const FrameConstants frame = obscura::with_work_rect(frame_, region);
        GLint alignment = 256;
        gl_.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
        arena_.reset(alignment);
        const obscura::UniformRange frame_range = arena_.push(frame), pass_range = arena_.push(pass);
        arena_.upload(gl_, uniforms_.name());
        return {frame_range, pass_range};
    }

    // `render()` as a CPU rasteriser runs it (runs of pixels) and as a GPU does (one pixel per invocation).
    template <typename Render>
    std::pair<std::vector<float>, std::vector<float>> on_cpu_and_gpu(Render render) {
        cpu_renderer_ = true;
        std::vector<float> cpu = render();
        cpu_renderer_ = false;
        std::vector<float> gpu = render();
        cpu_renderer_ = true;
        return {cpu, gpu};
    }

    static std::string region_name(const obscura::Region& r) {
        return ", region at (" + std::to_string(r.x) + ", " + std::to_string(r.y) + ")";
    }

    static bool inside(const obscura::Region& r, int x, int y) {
        return x >= r.x && x < r.x + r.width && y >= r.y && y < r.y + r.height;
    }

    // Bitwise differences between two images, and checks that `cpu` was written inside `region` (the sky's NaN
    // passed through included) and holds the sentinel outside it.
    static void expect_same_over(const std::vector<float>& cpu, const std::vector<float>& gpu,
                                 const obscura::Region& region, const std::string& name) {
        int differing = 0, written = 0, untouched = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const size_t i = size_t(y) * kWidth + x;
                differing += std::memcmp(&cpu[i], &gpu[i], sizeof(float)) != 0;
                if (inside(region, x, y)) {
                    written += cpu[i] != kSentinel;
                } else {
                    untouched += cpu[i] == kSentinel;
                }
            }
        }
        EXPECT_EQ(differing, 0) << name;
        EXPECT_EQ(written, region.width * region.height) << name;
        EXPECT_EQ(untouched, kWidth * kHeight - region.width * region.height) << name;
    }

    obscura::FrameResources resources_;
    FrameConstants frame_ = {};
};

const obscura::Region kRegions[] = {{0, 0, kWidth, kHeight}, {5, 3, 57, 33}};

// HBAO's blur, one pass along `axis` over `region` of noise (NaN on the sky, which must not leak into its
// neighbours).
class BilateralBlur : public BlurPass {
protected:
    std::vector<float> blur(int radius, bool along_x, const obscura::Region& region) {
        std::vector<float> source = filled(0.0f);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                source[4 * (size_t(y) * kWidth + x)] = scene_depth(x, y) == OBSCURA_SKY_DEPTH ? NAN : noise(x, y);
        gl::Texture2D source_texture = texture(GL_R16F, source);
        gl::Texture2D destination = texture(GL_R16F, filled(kSentinel));
        obscura::BilateralBlurPass pass;  // a new one: its programs depend on cpu_renderer_
        EXPECT_FALSE(pass.prepare(env(), radius));
        const auto [frame, constants] =
            uniforms(region, obscura::BilateralBlurPass::constants(radius, kSharpness, along_x ? 1 : 0, along_x ? 0 : 1));
        pass.run(env(), along_x, frame, constants, region, resources_.linear_depth, source_texture,
                 destination);
        return read_red(destination);
    }
    static constexpr float kSharpness = 8.0f;
};

TEST_F(BilateralBlur, CpuAndGpuRunLengthsGiveTheSameImage) {
    ASSERT_NE(OBSCURA_BLUR_RUN_CPU, OBSCURA_BLUR_RUN_GPU);
    for (int radius : {1, 2, 5, obscura::BilateralBlurPass::kMaxRadius}) {
        for (bool along_x : {true, false}) {
            for (const obscura::Region& region : kRegions) {
                const auto [cpu, gpu] = on_cpu_and_gpu([&] { return blur(radius, along_x, region); });
                expect_same_over(cpu, gpu, region,
                                 "radius " + std::to_string(radius) + (along_x ? " along x" : " along y") +
                                     region_name(region));
            }
        }
    }
}

// The filter's formula (bilateral_blur.comp), computed here for the CPU rasteriser's runs: the centre plus the
// weighted mean of the differences, weights exp(-j^2 / (2 sigma^2) - (sharpness dz / z)^2) over the taps inside the
// texture and off the sky; sky passed through (NaN here).
TEST_F(BilateralBlur, MatchesTheFormula) {
    for (int radius : {1, 3, obscura::BilateralBlurPass::kMaxRadius}) {
        const obscura::Region region = kRegions[1];
        const std::vector<float> out = blur(radius, true, region);
        const float sigma = 0.5f * float(radius + 1), spatial = 1.0f / (2.0f * sigma * sigma);
        int checked = 0, far_off = 0;
        for (int y = region.y; y < region.y + region.height; ++y) {
            for (int x = region.x; x < region.x + region.width; ++x) {
                const float d = scene_depth(x, y), got = out[size_t(y) * kWidth + x];
                if (d == OBSCURA_SKY_DEPTH) {
                    EXPECT_TRUE(std::isnan(got)) << "sky at (" << x << ", " << y << ") is passed through";
                    continue;
                }
                const float centre = noise(x, y);
                double delta = 0.0, weights = 1.0;
                for (int j = -radius; j <= radius; ++j) {
                    const int q = x + j;
                    if (j == 0 || q < 0 || q >= kWidth || scene_depth(q, y) == OBSCURA_SKY_DEPTH) continue;
                    const double dz = (scene_depth(q, y) - d) * (kSharpness / d);
                    const double w = std::exp(-double(j * j) * spatial - dz * dz);
                    delta += w * (double(noise(q, y)) - centre);
                    weights += w;
                }
                const double expected = centre + delta / weights;
                // R16F: half a unit in the last place is 2^-12 below 1; the source's own rounding adds as much.
                far_off += !(std::fabs(got - expected) <= 1e-3);  // a NaN leaked from the sky counts
                ++checked;
            }
        }
        EXPECT_GT(checked, region.width * region.height / 2);
        EXPECT_EQ(far_off, 0) << "radius " << radius;
    }
}

// SAO's blur as its technique runs it: along x over `output` grown by the y pass's reach (RGBA8: AO, the 16-bit key,
// the geometry flag), then along y over `output` into R16F visibility.
class SaoBlur : public BlurPass {
protected:
    static constexpr float kDepthRange = 200.0f;  // SAO's blur_depth_range default
    std::vector<float> blur(int radius, int stride, const obscura::Region& output) {
        std::vector<float> packed = filled(0.0f);
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                float* t = &packed[4 * (size_t(y) * kWidth + x)];
                const float d = scene_depth(x, y);
                const bool sky = d == OBSCURA_SKY_DEPTH;
                const int key = sky ? 65535 : int(d / kDepthRange * 65535.0f);  // as sao.comp packs it
                t[0] = noise(x, y);
                t[1] = float(key >> 8) / 255.0f;
                t[2] = float(key & 255) / 255.0f;
                t[3] = sky ? 0.0f : 1.0f;
            }
        }
        gl::Texture2D source = texture(GL_RGBA8, packed);
        gl::Texture2D temp = texture(GL_RGBA8, filled(0.0f));
        gl::Texture2D destination = texture(GL_R16F, filled(kSentinel));
        obscura_sao_settings settings = {};
        settings.blur_radius = radius;
        settings.blur_stride = stride;
        // The wall's slope (up to 0.17 m a pixel) stays below the edge weight's cut-off, the box's 2 m step does not.
        settings.blur_sharpness = 200.0f;
        obscura::SaoBlurPass pass;  // a new one: its programs depend on cpu_renderer_
        EXPECT_FALSE(pass.prepare(env(), radius));
        const obscura::Region along_x = output.expanded(0, radius * stride, kWidth, kHeight);
        {
            const auto [frame, constants] = uniforms(along_x, obscura::SaoBlurPass::constants(settings, 1, 0));
            pass.run(env(), settings, frame, constants, along_x, source, temp, false);
        }
        {
            const auto [frame, constants] = uniforms(output, obscura::SaoBlurPass::constants(settings, 0, 1));
            pass.run(env(), settings, frame, constants, output, temp, destination, true);
        }
        return read_red(destination);
    }
};

TEST_F(SaoBlur, CpuAndGpuRunLengthsGiveTheSameImage) {
    ASSERT_NE(OBSCURA_SAO_BLUR_RUN_CPU, OBSCURA_SAO_BLUR_RUN_GPU);
    for (int radius : {1, 3, obscura::SaoBlurPass::kMaxRadius}) {
        for (int stride = 1; stride <= 4; ++stride) {
            for (const obscura::Region& output : kRegions) {
                const std::string name =
                    "radius " + std::to_string(radius) + ", stride " + std::to_string(stride) + region_name(output);
                const auto [cpu, gpu] = on_cpu_and_gpu([&] { return blur(radius, stride, output); });
                expect_same_over(cpu, gpu, output, name);
                // The filter smoothed the noise: most pixels moved.
                int changed = 0;
                for (int y = output.y; y < output.y + output.height; ++y)
                    for (int x = output.x; x < output.x + output.width; ++x)
                        changed += std::fabs(cpu[size_t(y) * kWidth + x] - noise(x, y)) > 1e-2f;
                EXPECT_GT(changed, output.width * output.height / 2) << name;
            }
        }
    }
}

// The filter's formula (sao_blur.comp), computed here: per pass the centre plus the weighted mean of the differences
// over taps j = -R..R, `stride` texels apart, weights exp(-j^2 / (2 sigma^2)) max(0, 1 - sharpness |key difference|)
// with sigma = (R + 1) / 2, taps outside the texture or on sky left out, sky passed through; the first pass stores
// RGBA8 (the AO rounded to 8 bits, the key kept), the second R16F.
TEST_F(SaoBlur, MatchesTheFormula) {
    constexpr float kSharpness = 200.0f;  // blur() sets it
    const auto key_of = [](int x, int y) {
        const float d = scene_depth(x, y);
        return d == OBSCURA_SKY_DEPTH ? 1.0 : double(int(d / kDepthRange * 65535.0f)) / 65535.0;
    };
    const auto sky = [](int x, int y) { return scene_depth(x, y) == OBSCURA_SKY_DEPTH; };
    for (int radius : {1, 3}) {
        for (int stride : {1, 3}) {
            const obscura::Region output = kRegions[1];
            const std::vector<float> got = blur(radius, stride, output);
            const double sigma = 0.5 * (radius + 1), spatial = 1.0 / (2.0 * sigma * sigma);
            const auto filter = [&](const std::vector<double>& in, int dx, int dy) {
                std::vector<double> out(in);
                for (int y = 0; y < kHeight; ++y) {
                    for (int x = 0; x < kWidth; ++x) {
                        if (sky(x, y)) continue;
                        const size_t i = size_t(y) * kWidth + x;
                        double delta = 0.0, weights = 1.0;
                        for (int j = -radius; j <= radius; ++j) {
                            const int qx = x + j * stride * dx, qy = y + j * stride * dy;
                            if (j == 0 || qx < 0 || qy < 0 || qx >= kWidth || qy >= kHeight || sky(qx, qy)) continue;
                            const double w = std::exp(-double(j * j) * spatial) *
                                             std::max(0.0, 1.0 - kSharpness * std::fabs(key_of(qx, qy) - key_of(x, y)));
                            delta += w * (in[size_t(qy) * kWidth + qx] - in[i]);
                            weights += w;
                        }
                        out[i] = in[i] + delta / weights;
                    }
                }
                return out;
            };
            std::vector<double> source(size_t(kWidth) * kHeight);
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) source[size_t(y) * kWidth + x] = std::round(noise(x, y) * 255.0) / 255.0;
            std::vector<double> horizontal = filter(source, 1, 0);
            for (double& v : horizontal) v = std::round(v * 255.0) / 255.0;  // the RGBA8 intermediate
            const std::vector<double> expected = filter(horizontal, 0, 1);
            int checked = 0, far_off = 0;
            double worst = 0.0;
            for (int y = output.y; y < output.y + output.height; ++y) {
                for (int x = output.x; x < output.x + output.width; ++x) {
                    if (sky(x, y)) continue;
                    const double error = std::fabs(got[size_t(y) * kWidth + x] - expected[size_t(y) * kWidth + x]);
                    worst = std::max(worst, std::isfinite(error) ? error : 1.0);
                    // The 8-bit intermediate may round the other way: one step of 1/255, plus R16F's rounding.
                    far_off += !(error <= 1.0 / 255.0 + 1e-3);
                    ++checked;
                }
            }
            EXPECT_GT(checked, output.width * output.height / 2);
            EXPECT_EQ(far_off, 0) << "radius " << radius << ", stride " << stride << ": worst " << worst;
        }
    }
}

}  // namespace
