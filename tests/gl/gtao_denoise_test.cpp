// GTAO's denoise (sdk/src/passes/gtao.*, sdk/glsl/gtao_denoise.comp) run directly: CPU rasterisers filter long runs
// of pixels per invocation and GPUs short ones (OBSCURA_GTAO_DENOISE_RUN_CPU / _GPU); both must give the same
// image, bit for bit, clipped to the same regions.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "frame_input.h"
#include "pass_test_support.h"
#include "passes/gtao.h"
#include "settings.h"

#include <glm/gtc/packing.hpp>

namespace {

namespace gl = obscura::gl;

// Odd sizes: the runs end inside the region on both axes.
constexpr int kWidth = 67, kHeight = 41;

// A wavy wall with a box in front of it (depth edges) and a patch of sky.
float scene_depth(int x, int y) {
    if (x < 6 && y > 33) return float(OBSCURA_SKY_DEPTH);
    if (x >= 20 && x < 37 && y >= 9 && y < 30) return 4.0f;
    return 6.0f + 0.8f * std::sin(x * 0.21f) * std::sin(y * 0.17f);
}
bool is_sky(int x, int y) { return scene_depth(x, y) == float(OBSCURA_SKY_DEPTH); }

class GtaoDenoise : public obscura_pass_test::PassTest {
protected:
    void SetUp() override {
        PassTest::SetUp();
        std::vector<float> depth(size_t(kWidth) * kHeight);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) depth[size_t(y) * kWidth + x] = scene_depth(x, y);
        obscura_pass_test::upload_linear_depth(gl_, depth, kWidth, kHeight, &resources_);
        float matrix[16];
        frame_ = obscura_pass_test::perspective_linear_depth_frame(kWidth, kHeight, matrix);
        obscura_settings settings;
        obscura_default_settings(OBSCURA_METHOD_GTAO, &settings);
        obscura_settings resolved;
        ASSERT_FALSE(obscura::resolve_settings(settings, &resolved));
        settings_ = resolved.gtao;
    }

    struct Denoised {
        std::vector<float> visibility;  // the final pass's R16F output
        std::vector<float> bent;        // with bent normals: its RGBA16F output
    };

    // The denoise's two passes as the technique runs them: along x over `output` grown by the 2-texel apron
    // vertically, then along y over `output`, on a 4-channel source of noisy values (the visibility in r).
    Denoised run(bool bent_normals, const obscura::Region& output) {
        const GLenum format = bent_normals ? GL_RGBA16F : GL_R16F;
        std::vector<float> noisy(size_t(kWidth) * kHeight * 4);
        for (size_t i = 0; i < noisy.size(); ++i) noisy[i] = float((i * 2654435761u) % 1000u) / 999.0f;
        gl::Texture2D source = gl::Texture2D::create(gl_, format, kWidth, kHeight);
        gl_.BindTexture(GL_TEXTURE_2D, source.name());
        gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, noisy.data());
        gl::Texture2D temp = gl::Texture2D::create(gl_, format, kWidth, kHeight);
        gl::Texture2D destination = gl::Texture2D::create(gl_, GL_R16F, kWidth, kHeight);
        gl::Texture2D bent = gl::Texture2D::create(gl_, GL_RGBA16F, kWidth, kHeight);
        const std::vector<float> sentinel(size_t(kWidth) * kHeight * 4, -7.0f);
        for (const gl::Texture2D* t : {&destination, &bent}) {
            gl_.BindTexture(GL_TEXTURE_2D, t->name());
            gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, sentinel.data());
        }
        gl_.BindTexture(GL_TEXTURE_2D, 0);

        obscura::GtaoDenoisePass pass;  // a new one: its programs depend on cpu_renderer_
        EXPECT_FALSE(pass.prepare(env(), bent_normals));
        const obscura::Region along_x = output.expanded(0, 2, kWidth, kHeight);
        const FrameConstants x_frame = obscura::with_work_rect(frame_, along_x);
        const FrameConstants y_frame = obscura::with_work_rect(frame_, output);
        GLint alignment = 256;
        gl_.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
        arena_.reset(alignment);
        const obscura::UniformRange x_range = arena_.push(x_frame), y_range = arena_.push(y_frame);
        const obscura::UniformRange x_pass = arena_.push(obscura::GtaoDenoisePass::constants(settings_, false));
        const obscura::UniformRange y_pass = arena_.push(obscura::GtaoDenoisePass::constants(settings_, true));
        arena_.upload(gl_, uniforms_.name());
        pass.run(env(), bent_normals, false, x_range, x_pass, along_x, resources_, source, temp, nullptr);
        pass.run(env(), bent_normals, true, y_range, y_pass, output, resources_, temp, destination,
                 bent_normals ? &bent : nullptr);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);

        Denoised out;
        out.visibility.assign(size_t(kWidth) * kHeight, 0.0f);
        gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl_.BindTexture(GL_TEXTURE_2D, destination.name());
        gl_.GetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, out.visibility.data());
        if (bent_normals) {
            out.bent.assign(size_t(kWidth) * kHeight * 4, 0.0f);
            gl_.BindTexture(GL_TEXTURE_2D, bent.name());
            gl_.GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, out.bent.data());
        }
        gl_.BindTexture(GL_TEXTURE_2D, 0);
        // The input, for the caller's check that the filter changed something.
        source_visibility_.assign(size_t(kWidth) * kHeight, 0.0f);
        for (size_t i = 0; i < source_visibility_.size(); ++i) source_visibility_[i] = noisy[4 * i];
        return out;
    }

    obscura::FrameResources resources_;
    FrameConstants frame_ = {};
    obscura_gtao_settings settings_ = {};
    std::vector<float> source_visibility_;
};

TEST_F(GtaoDenoise, CpuAndGpuRunLengthsGiveTheSameImage) {
    ASSERT_NE(OBSCURA_GTAO_DENOISE_RUN_CPU, OBSCURA_GTAO_DENOISE_RUN_GPU);
    for (bool bent_normals : {false, true}) {
        for (const obscura::Region& output : {obscura::Region{0, 0, kWidth, kHeight}, obscura::Region{3, 5, 59, 29}}) {
            const std::string name = std::string(bent_normals ? "bent normals" : "visibility") + ", region at (" +
                                     std::to_string(output.x) + ", " + std::to_string(output.y) + ")";
            cpu_renderer_ = true;
            const Denoised cpu = run(bent_normals, output);
            cpu_renderer_ = false;
            const Denoised gpu = run(bent_normals, output);
            cpu_renderer_ = true;
            int differing = 0, changed = 0, written = 0, untouched = 0;
            for (int y = 0; y < kHeight; ++y) {
                for (int x = 0; x < kWidth; ++x) {
                    const size_t i = size_t(y) * kWidth + x;
                    differing += std::memcmp(&cpu.visibility[i], &gpu.visibility[i], sizeof(float)) != 0;
                    if (bent_normals) differing += std::memcmp(&cpu.bent[4 * i], &gpu.bent[4 * i], 4 * sizeof(float)) != 0;
                    const bool inside = x >= output.x && x < output.x + output.width && y >= output.y &&
                                        y < output.y + output.height;
                    if (inside) {
                        written += cpu.visibility[i] != -7.0f;
                        changed += std::fabs(cpu.visibility[i] - source_visibility_[i]) > 1e-3f;
                    } else {
                        untouched += cpu.visibility[i] == -7.0f;
                    }
                }
            }
            EXPECT_EQ(differing, 0) << name;
            EXPECT_EQ(written, output.width * output.height) << name;
            EXPECT_EQ(untouched, kWidth * kHeight - output.width * output.height) << name;
            EXPECT_GT(changed, output.width * output.height / 2) << name << ": the filter did not smooth the noise";
        }
    }
}

// The filter's formula (gtao_denoise.comp), computed here: per pass, the centre plus the weighted mean of the
// differences over the taps -2..2 along the pass's axis, tap weights (1/2, 1, 1, 1/2) / (1 + (sharpness * the tap's
// distance from the centre's tangent plane / the centre's distance)^2), taps outside the texture or on sky left out,
// sky passed through; both passes store R16F. The upload gives every texel the normal (0, 0, 1), so a tap's plane
// distance is its depth difference (the box's 2 m step weighs about 1e-4: no blur across it).
TEST_F(GtaoDenoise, MatchesTheFormula) {
    const auto half = [](double v) { return double(glm::unpackHalf1x16(glm::packHalf1x16(float(v)))); };
    const double sharpness = settings_.denoise_sharpness;
    const double m0 = 1.0 / std::tan(0.5 * 1.0471976) * kHeight / kWidth, m5 = 1.0 / std::tan(0.5 * 1.0471976);
    const auto distance = [&](int x, int y) {  // |view position| of the texel's centre
        const double d = scene_depth(x, y);
        const double ndc_x = (x + 0.5) / kWidth * 2.0 - 1.0, ndc_y = (y + 0.5) / kHeight * 2.0 - 1.0;
        return std::sqrt(std::pow(ndc_x * d / m0, 2) + std::pow(ndc_y * d / m5, 2) + d * d);
    };
    const auto filter = [&](const std::vector<double>& in, int dx, int dy) {
        std::vector<double> out(in.size());
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const size_t i = size_t(y) * kWidth + x;
                const double d = scene_depth(x, y);
                if (is_sky(x, y)) {
                    out[i] = in[i];
                    continue;
                }
                double delta = 0.0, weights = 1.0;
                for (int j : {-2, -1, 1, 2}) {
                    const int qx = x + j * dx, qy = y + j * dy;
                    if (qx < 0 || qy < 0 || qx >= kWidth || qy >= kHeight || is_sky(qx, qy))
                        continue;
                    const double plane = (scene_depth(qx, qy) - d) * sharpness / distance(x, y);
                    const double w = (j == -2 || j == 2 ? 0.5 : 1.0) / (1.0 + plane * plane);
                    delta += w * (in[size_t(qy) * kWidth + qx] - in[i]);
                    weights += w;
                }
                out[i] = half(in[i] + delta / weights);
            }
        }
        return out;
    };
    for (bool cpu : {true, false}) {
        cpu_renderer_ = cpu;
        const obscura::Region whole{0, 0, kWidth, kHeight};
        const Denoised got = run(false, whole);
        cpu_renderer_ = true;
        std::vector<double> source(source_visibility_.size());
        for (size_t i = 0; i < source.size(); ++i) source[i] = half(source_visibility_[i]);
        const std::vector<double> expected = filter(filter(source, 1, 0), 0, 1);
        int far_off = 0;
        double worst = 0.0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const size_t i = size_t(y) * kWidth + x;
                const double error = std::fabs(got.visibility[i] - expected[i]);
                worst = std::max(worst, std::isfinite(error) ? error : 1.0);
                far_off += !(error <= 2e-3);  // a NaN counts
            }
        }
        EXPECT_EQ(far_off, 0) << (cpu ? "CPU" : "GPU") << " code path: worst difference " << worst;
    }
}

}  // namespace
