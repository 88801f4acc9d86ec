// The code paths written for GPUs, run under llvmpipe (OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS). A CPU rasteriser
// otherwise gets variants of its own (blocks and runs per invocation, buffer textures instead of storage buffers,
// no shared-memory tiles, whole LSAO lines), so a whole frame of what studios run never ran in CI, only some of its
// passes alone (the pass tests that set cpu_renderer_ = false): the shared-memory tiles of the depth preparation and
// LSAO's gather, LSAO's shared hull and segments, the storage buffers of LSAO and FFAO, the early returns of GTAO and
// the temporal pass, the blurs' runs of one pixel, and the settings derived for a GPU.
//
// Each case renders a built-in scene through two contexts, one with the flag (and VALIDATE_PASSES, so that a GL
// error names its pass) and one without, and compares the images. The variants compute the same arithmetic, so
// the images are the same: measured bit for bit (Mesa 22.3.6) for every case but LSAO's segments; the bound allows
// r16f rounding, which another compiler may reach by contracting differently. LSAO's segments are an approximation
// of the GPU path only (each segment sweeps a warm-up before it instead of the whole line before it): they have a
// measured bound of their own.
#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "ao_test_scene.h"
#include "demo_scene.h"
#include "gl_test_support.h"
#include "method_spec_parser.h"
#include "scene_library.h"

namespace obscura_test {
namespace {

using obscura::samples::Camera;
using obscura::samples::RenderedScene;
using obscura::samples::SceneRenderOptions;

constexpr int kWidth = 256, kHeight = 144;

struct PathCase {
    const char* name;
    const char* scene;
    const char* spec;  // a method spec (samples/common/method_spec_parser.h)
    int frames = 1;    // > 1: a camera orbiting 1 degree a frame, each frame reprojecting the last (temporal cases)
    bool bent_normals = false;
    // The largest difference allowed at any pixel, and on average over the image.
    double max_abs = 1e-3, mean_abs = 1e-4;
};

const PathCase kCases[] = {
    {"hbao", "atrium", "hbao"},
    {"hbao_half_resolution", "clutter", "hbao:resolution.scale=half"},
    {"hbao_quarter_resolution", "objects", "hbao:resolution.scale=quarter"},
    {"hbao_temporal_moving", "atrium", "hbao:temporal.enabled=on", 3},
    {"sao", "atrium", "sao"},
    {"sao_half_resolution", "objects", "sao:resolution.scale=half"},
    {"gtao", "atrium", "gtao"},
    {"gtao_bitmask_bent_normals", "clutter", "gtao:thickness_mode=bitmask", 1, true},
    {"gtao_temporal_bent_normals", "atrium", "gtao:temporal.enabled=on", 3, true},
    {"gtao_half_resolution", "atrium", "gtao:resolution.scale=half"},
    // Whole lines on both paths: the GPU path's shared hull, storage buffers and gather tile against the CPU's.
    {"lsao_whole_lines", "atrium", "lsao:segment_steps=-1"},
    {"lsao_free_whole_lines", "clutter", "lsao:pattern=free:segment_steps=-1"},
    // The GPU path's default: 128-step segments with warm-ups. Measured at this size (atrium): the receiver's
    // tangent (the default) moves 219 pixels (0.59 %) by more than 1/255, at most by 0.084, the mean by 0.00026: the
    // warm-up's strided hull keeps other points where the receivers' own tangents decide the pops. The fixed tangent
    // moves none, at most by 0.002. The error against the geometry truth was no higher (atrium, 320x180, 256 rays:
    // 0.03921 with segments, 0.03945 with whole lines, before the gather took two lines' samples).
    {"lsao_segments", "atrium", "lsao", 1, false, 0.15, 0.001},
    {"lsao_segments_fixed_tangent", "atrium", "lsao:tangent_strategy=fixed", 1, false, 0.01, 1e-4},
    {"ffao", "atrium", "ffao"},
    {"ffao_saao", "terrain", "ffao:saao=on:sectors=18"},
    {"ffao_mipmap", "objects", "ffao:geometry=2"},
    {"ffao_thickness", "atrium", "ffao:thickness=0.3"},
    {"reference", "objects", "reference:rays=8"},
};

std::string case_name(const ::testing::TestParamInfo<PathCase>& info) { return info.param.name; }
void PrintTo(const PathCase& c, std::ostream* out) { *out << c.name << " (" << c.spec << ")"; }

struct Images {
    std::vector<float> visibility;
    std::vector<float> bent;  // rgba, when the case asks for bent normals
};

class GpuCodePaths : public GLTest, public ::testing::WithParamInterface<PathCase> {
protected:
    // Renders the case's frames through `context`; the last frame's images.
    Images render(obscura_context* context) {
        const PathCase& c = GetParam();
        const obscura_settings settings = obscura::samples::parse_method_spec(c.spec);
        const obscura::samples::Scene scene = obscura::samples::load_scene(c.scene);
        HostTexture ao = make_texture(GL_R32F, kWidth, kHeight);
        HostTexture bent = make_texture(GL_RGBA32F, kWidth, kHeight);
        obscura_view* view = nullptr;
        EXPECT_EQ(obscura_create_view(context, &view), OBSCURA_OK);
        Camera camera = scene.viewpoints[0].camera;
        std::optional<RenderedScene> previous;
        for (int frame = 0; frame < c.frames; ++frame) {
            SceneRenderOptions options;
            options.width = kWidth;
            options.height = kHeight;
            options.camera = camera;
            RenderedScene rendered = obscura::samples::render_scene(scene.mesh, options);
            obscura_input input = rendered->make_input(false, previous ? &previous->frame() : nullptr, uint32_t(frame));
            input.view = view;
            obscura_output output = make_output(ao.get());
            if (c.bent_normals) output.bent_normal_texture = bent.get();
            EXPECT_EQ(obscura_render(context, &input, &settings, &output), OBSCURA_OK)
                << c.spec << ", frame " << frame << ": " << obscura_get_last_error(context);
            previous.emplace(std::move(rendered));
            camera = obscura::samples::orbit_camera(camera, 1.0f);
        }
        EXPECT_EQ(obscura_destroy_view(context, view), OBSCURA_OK);
        Images images;
        images.visibility = read_texture(ao.get(), kWidth, kHeight, 1);
        if (c.bent_normals) images.bent = read_texture(bent.get(), kWidth, kHeight, 4);
        return images;
    }
};

// How far two images are apart: the largest and the mean absolute difference, and how many values differ by more
// than one 8-bit level.
struct Difference {
    double largest = 0.0, mean = 0.0;
    size_t over_level = 0;
};

Difference difference(const std::vector<float>& a, const std::vector<float>& b) {
    Difference d;
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        // NaN on either side counts as the largest difference there is.
        const double e = std::isfinite(a[i]) && std::isfinite(b[i]) ? std::fabs(double(a[i]) - double(b[i])) : 1e30;
        d.largest = std::max(d.largest, e);
        sum += std::min(e, 1.0);
        d.over_level += e > 1.0 / 255.0 ? 1 : 0;
    }
    d.mean = a.empty() ? 0.0 : sum / double(a.size());
    return d;
}

TEST_P(GpuCodePaths, RenderWhatTheCpuPathsRender) {
    const PathCase& c = GetParam();
    ContextPtr gpu = create_context(OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS | OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES);
    ASSERT_NE(gpu, nullptr);
    const Images on_gpu_paths = render(gpu.get());
    const Images on_cpu_paths = render(ctx());
    ASSERT_EQ(on_gpu_paths.visibility.size(), size_t(kWidth) * kHeight);
    ASSERT_EQ(on_cpu_paths.visibility.size(), on_gpu_paths.visibility.size());
    // Not a blank image on both sides: the case renders AO.
    const float darkest = *std::min_element(on_cpu_paths.visibility.begin(), on_cpu_paths.visibility.end());
    EXPECT_LT(darkest, 0.8f) << c.spec;

    const Difference ao = difference(on_gpu_paths.visibility, on_cpu_paths.visibility);
    EXPECT_LE(ao.largest, c.max_abs) << c.spec << ": mean " << ao.mean << ", " << ao.over_level
                                     << " pixels differ by more than 1/255";
    EXPECT_LE(ao.mean, c.mean_abs) << c.spec << ": largest " << ao.largest;
    if (c.bent_normals) {
        const Difference bent = difference(on_gpu_paths.bent, on_cpu_paths.bent);
        EXPECT_LE(bent.largest, c.max_abs) << c.spec << " (bent normals): mean " << bent.mean;
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, GpuCodePaths, ::testing::ValuesIn(kCases), case_name);

class GpuCodePathsFlag : public GLTest {};

// Odd sizes, where the GPU variants' tiles, runs and workgroups end part of the way (a shared-memory tile past the
// texture's edge, a run of one pixel where the CPU's run of 16 is cut short, an LSAO segment shorter than the others):
// a box on a floor at each size, the output rectangle inside a guard band where there is room, each method with
// the variants that have GPU paths of their own. LSAO runs whole lines and explicit 16-step segments, the same
// algorithm on both paths (its derived 128-step segments are the GPU's alone: the cases above).
TEST_F(GpuCodePathsFlag, OddSizesRenderWhatTheCpuPathsRender) {
    ContextPtr gpu = create_context(OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS | OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES);
    ASSERT_NE(gpu, nullptr);
    const char* const specs[] = {"hbao", "hbao:resolution.scale=half", "sao", "gtao", "gtao:thickness_mode=bitmask",
                                 "lsao:segment_steps=-1", "lsao:segment_steps=16", "ffao", "ffao:saao=on:sectors=18",
                                 "reference:rays=4"};
    const int sizes[][2] = {{1, 1}, {2, 3}, {3, 7}, {33, 5}, {5, 33}, {61, 47}, {150, 9}};
    for (const auto& size : sizes) {
        const int width = size[0], height = size[1];
        AoScene scene = make_ao_scene(Projection::Perspective, look_at(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0)),
                                      {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                                       box(2, glm::dvec3(-0.5, 0.0, -0.5), glm::dvec3(0.5, 0.7, 0.5))},
                                      Lens(), width, height);
        if (width >= 20 && height >= 20) scene.input.output_rect = obscura_rect{3, 2, width - 6, height - 5};
        for (const char* spec : specs) {
            const obscura_settings settings = obscura::samples::parse_method_spec(spec);
            const std::vector<float> on_gpu_paths = render_to_new_texture(gpu.get(), scene.input, settings, GL_R32F, 1);
            const std::vector<float> on_cpu_paths = render_to_new_texture(ctx(), scene.input, settings, GL_R32F, 1);
            ASSERT_EQ(on_gpu_paths.size(), on_cpu_paths.size()) << spec << " at " << width << "x" << height;
            ASSERT_FALSE(on_cpu_paths.empty()) << spec << " at " << width << "x" << height;
            const Difference d = difference(on_gpu_paths, on_cpu_paths);
            EXPECT_LE(d.largest, 1e-3) << spec << " at " << width << "x" << height << ": mean " << d.mean;
        }
    }
}

// The flag is what the settings derive from as well: obscura_resolve_settings with the context gives LSAO's GPU
// segments (128 steps) with it, whole lines (-1) without.
TEST_F(GpuCodePathsFlag, SettingsDeriveForAGpu) {
    ContextPtr gpu = create_context(OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS);
    ASSERT_NE(gpu, nullptr);
    obscura_settings settings, on_gpu_paths, on_cpu_paths;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_LSAO, &settings), OBSCURA_OK);
    ASSERT_EQ(obscura_resolve_settings(gpu.get(), &settings, &on_gpu_paths), OBSCURA_OK);
    ASSERT_EQ(obscura_resolve_settings(ctx(), &settings, &on_cpu_paths), OBSCURA_OK);
    EXPECT_EQ(on_gpu_paths.lsao.segment_steps, 128);
    EXPECT_EQ(on_cpu_paths.lsao.segment_steps, -1);
}

}  // namespace
}  // namespace obscura_test
