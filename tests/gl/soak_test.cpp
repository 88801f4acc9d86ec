// Soak: 2,000 frames of random methods, settings (drawn from the SDK's own metadata), sizes (1x1, 3x7, 4097x9,
// 9x4097 among ordinary ones), reduced resolutions, depth kinds, output targets, prepares, releases, context
// re-creations (half of them on the GPUs' shader variants, OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS) and temporal
// frames (random history settings, matrices, camera cuts, views created and destroyed), the way
// an engine's editor drives the SDK for hours. Every call must return OK or, for random settings outside what
// the method accepts together, INVALID_SETTING; no GL error may be left; sampled outputs are finite and in
// [0, 1]; the memory report for one fixed configuration never drifts; and at the end no GL object and no byte
// of the host allocator is left. The AddressSanitizer/LeakSanitizer build runs the same test.
//
// OBSCURA_SOAK_FRAMES and OBSCURA_SOAK_SEED override the frame count and the seed (printed on failure).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "analytic_scene.h"
#include "gl_test_support.h"

namespace obscura_test {
namespace {

// The host allocator, counting live blocks and bytes.
struct CountingAllocator {
    long long live_blocks = 0;
    long long live_bytes = 0;
    static void* alloc(size_t size, void* user) {
        auto* self = static_cast<CountingAllocator*>(user);
        auto* block = static_cast<size_t*>(std::malloc(size + sizeof(std::max_align_t)));
        if (!block) return nullptr;
        *block = size;
        ++self->live_blocks;
        self->live_bytes += static_cast<long long>(size);
        return reinterpret_cast<char*>(block) + sizeof(std::max_align_t);
    }
    static void release(void* ptr, void* user) {
        if (!ptr) return;
        auto* self = static_cast<CountingAllocator*>(user);
        auto* block = reinterpret_cast<size_t*>(static_cast<char*>(ptr) - sizeof(std::max_align_t));
        --self->live_blocks;
        self->live_bytes -= static_cast<long long>(*block);
        std::free(block);
    }
};

// A depth buffer of one size: a box on a floor, as hardware D32F and as linear view depth, and its targets.
struct SizedInputs {
    int width = 0, height = 0;
    std::unique_ptr<Camera> hardware_camera, linear_camera;
    HostTexture hardware_depth, linear_depth;
    HostTexture target_r16f, target_rgba8;
};

std::unique_ptr<SizedInputs> make_inputs(int width, int height) {
    auto inputs = std::make_unique<SizedInputs>();
    inputs->width = width;
    inputs->height = height;
    const glm::dmat4 view = look_at(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0));
    const std::vector<Primitive> scene = {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                                          box(2, glm::dvec3(-0.5, 0.0, -0.5), glm::dvec3(0.5, 0.7, 0.5))};
    inputs->hardware_camera = std::make_unique<Camera>(Projection::Perspective, width, height, Lens(), view);
    inputs->linear_camera = std::make_unique<Camera>(Projection::LinearView, width, height, Lens(), view);
    inputs->hardware_depth = make_depth_texture(
        GL_DEPTH_COMPONENT32F, width, height,
        depth_values(*inputs->hardware_camera, trace(*inputs->hardware_camera, scene)));
    inputs->linear_depth = make_red_texture(GL_R32F, width, height,
                                            depth_values(*inputs->linear_camera, trace(*inputs->linear_camera, scene)));
    inputs->target_r16f = make_texture(GL_R16F, width, height);
    inputs->target_rgba8 = make_texture(GL_RGBA8, width, height);
    return inputs;
}

// Settings the random draw leaves alone or bounds, so 2,000 frames stay within a minute or two on llvmpipe:
// cost per pixel (the draw covers the range of everything else) and shader variants (each new LSAO or HBAO
// variant is a compile; the context keeps a few, so a small set still exercises the cache's eviction).
void bound_cost(obscura_settings* s, int pixels, std::mt19937& rng) {
    auto pick = [&](std::initializer_list<int> values) {
        std::vector<int> v(values);
        return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)];
    };
    const bool large = pixels > 20000;
    s->hbao.directions = std::min(s->hbao.directions, large ? 8 : 16);
    s->hbao.steps = std::min(s->hbao.steps, large ? 12 : 32);
    s->sao.samples = std::min(s->sao.samples, 32);
    s->lsao.hull_capacity = pick({16, 24, 32});
    s->lsao.directions = std::min(s->lsao.directions, 32);
    if (large) s->lsao.exact = OBSCURA_TOGGLE_OFF;
    s->ffao.sectors = std::min(s->ffao.sectors, 36);
    s->reference.rays = std::min(s->reference.rays, 4);
    // GTAO compiles slices x steps in: a few pairs (0: the preset's).
    s->gtao.slices = pick({0, 1, 3});
    s->gtao.steps = pick({0, 2, 3});
    s->reference.rays_per_dispatch = std::min(s->reference.rays_per_dispatch, 4);
}

// Defaults of `method`, then each setting of the method's metadata redrawn with probability 1/2: uniformly in
// its range, or log-uniformly for ranges over more than two decades.
obscura_settings random_settings(obscura_method method, int pixels, std::mt19937& rng) {
    obscura_settings s;
    EXPECT_EQ(obscura_default_settings(method, &s), OBSCURA_OK);
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    EXPECT_EQ(obscura_get_setting_infos(method, &infos, &count), OBSCURA_OK);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (uint32_t i = 0; i < count; ++i) {
        if (unit(rng) < 0.5) continue;
        const obscura_setting_info& info = infos[i];
        if (info.type == OBSCURA_SETTING_FLOAT_ARRAY) {
            // A falloff table: written through its offset (never all zero, so falloff=table resolves).
            float* values = reinterpret_cast<float*>(reinterpret_cast<unsigned char*>(&s) + info.offset);
            for (uint32_t v = 0; v < info.value_count; ++v) values[v] = float(unit(rng));
            values[0] = 1.0f;
            continue;
        }
        double value = 0.0;
        if (info.type == OBSCURA_SETTING_FLOAT) {
            if (info.min_value > 0.0 && info.max_value / info.min_value > 100.0) {
                value = info.min_value * std::pow(info.max_value / info.min_value, unit(rng));
            } else {
                value = info.min_value + (info.max_value - info.min_value) * unit(rng);
            }
            value = std::clamp(value, info.min_value, info.max_value);
        } else {
            value = double(std::uniform_int_distribution<long long>(static_cast<long long>(info.min_value),
                                                                   static_cast<long long>(info.max_value))(rng));
        }
        EXPECT_EQ(obscura_set_setting(&s, info.name, value), OBSCURA_OK) << info.name << " = " << value;
    }
    bound_cost(&s, pixels, rng);
    return s;
}

int env_int(const char* name, int fallback) {
    const char* text = std::getenv(name);
    return text && *text ? std::atoi(text) : fallback;
}

class Soak : public GLTest {};

TEST_F(Soak, TwoThousandRandomFramesLeakNothing) {
    const int frames = env_int("OBSCURA_SOAK_FRAMES", 2000);
    const unsigned seed = unsigned(env_int("OBSCURA_SOAK_SEED", 20261123));
    SCOPED_TRACE("OBSCURA_SOAK_SEED=" + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);

    context_.reset();  // this test makes its own contexts, with a counting allocator
    glFinish();
    const std::map<std::string, int> objects_before = count_gl_objects();

    // Sizes, weighted towards the small ones; the odd ones exercise 1-texel images, odd dimensions and lines
    // longer than a GPU group.
    const std::vector<std::pair<int, int>> sizes = {{1, 1},   {3, 7},   {4097, 9}, {9, 4097}, {16, 16},
                                                    {33, 17}, {64, 36}, {96, 54},  {128, 72}, {2, 2}};
    const std::vector<double> size_weights = {3, 3, 1, 1, 4, 4, 6, 4, 2, 2};
    std::discrete_distribution<size_t> pick_size(size_weights.begin(), size_weights.end());
    const obscura_method methods[] = {OBSCURA_METHOD_HBAO, OBSCURA_METHOD_SAO,       OBSCURA_METHOD_LSAO,
                                      OBSCURA_METHOD_FFAO, OBSCURA_METHOD_REFERENCE, OBSCURA_METHOD_GTAO};
    const int method_count = int(sizeof methods / sizeof methods[0]);
    {
        std::map<size_t, std::unique_ptr<SizedInputs>> inputs;  // host textures, made on first use
        CountingAllocator allocator;
        // Re-created contexts run the GPUs' shader variants half of the time (OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS).
        int gpu_code_path_contexts = 0;
        auto create = [&](bool gpu_code_paths) {
            obscura_context_desc desc = make_desc(gpu_code_paths ? uint32_t(OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS) : 0u);
            gpu_code_path_contexts += gpu_code_paths ? 1 : 0;
            desc.allocator.alloc = &CountingAllocator::alloc;
            desc.allocator.free = &CountingAllocator::release;
            desc.allocator.user_data = &allocator;
            log_.attach(&desc);
            obscura_context* raw = nullptr;
            EXPECT_EQ(obscura_create_context(&desc, &raw), OBSCURA_OK);
            return ContextPtr(raw);
        };
        ContextPtr context = create(false);
        ASSERT_NE(context, nullptr);
        std::vector<obscura_view*> views;  // the current context's (destroyed with it)

        // The anchor: one fixed configuration rendered every 100 frames; its memory report must never change.
        obscura_settings anchor_settings;
        obscura_default_settings(OBSCURA_METHOD_HBAO, &anchor_settings);
        const size_t anchor_size = 6;  // 64x36
        uint64_t anchor_bytes = 0;

        std::map<int, int> statuses;
        int checked_outputs = 0, recreated = 0;
        for (int frame = 0; frame < frames && !HasFatalFailure(); ++frame) {
            const bool anchor = frame % 100 == 0;
            const size_t size_index = anchor ? anchor_size : pick_size(rng);
            auto& slot = inputs[size_index];
            if (!slot) slot = make_inputs(sizes[size_index].first, sizes[size_index].second);
            const SizedInputs& in = *slot;
            const int pixels = in.width * in.height;
            const obscura_method method = methods[std::uniform_int_distribution<int>(0, method_count - 1)(rng)];
            obscura_settings settings = anchor ? anchor_settings : random_settings(method, pixels, rng);
            const bool linear = !anchor && unit(rng) < 0.3;
            const Camera& camera = linear ? *in.linear_camera : *in.hardware_camera;
            obscura_input input = make_input(linear ? in.linear_depth.get() : in.hardware_depth.get(), in.width,
                                             in.height, camera.matrix(), camera.clip_depth());
            if (linear) input.depth_kind = OBSCURA_DEPTH_LINEAR_VIEW;
            if (!anchor && unit(rng) < 0.4 && in.width > 2 && in.height > 2) {  // a guard band
                const int gx = std::uniform_int_distribution<int>(0, (in.width - 1) / 2)(rng);
                const int gy = std::uniform_int_distribution<int>(0, (in.height - 1) / 2)(rng);
                input.output_rect = obscura_rect{gx, gy, in.width - 2 * gx, in.height - 2 * gy};
            }
            obscura_output output = make_output(unit(rng) < 0.7 ? in.target_r16f.get() : in.target_rgba8.get());
            if (!anchor && unit(rng) < 0.2) output.blend = OBSCURA_BLEND_MULTIPLY;
            if (!anchor && unit(rng) < 0.1) {
                store_raw(&output.debug_view, std::uniform_int_distribution<int>(1, 4)(rng));
            }

            const double action = anchor ? 1.0 : unit(rng);
            // Temporal frames: a random history length and clamp, the camera's matrices (the same camera, or a
            // previous one nudged aside), a camera cut now and then, and one of the context's views.
            if (!anchor && unit(rng) < 0.3) {
                settings.temporal.enabled = OBSCURA_TOGGLE_ON;
                settings.temporal.max_frames = std::uniform_int_distribution<int>(1, 64)(rng);
                settings.temporal.clamp = float(0.25 * std::pow(256.0, unit(rng)));
                settings.temporal.plane_tolerance = float(1e-4 * std::pow(1e4, unit(rng)));
            }
            // Reduced resolution now and then: half or quarter, a random upsample tolerance.
            if (!anchor && unit(rng) < 0.3) {
                settings.resolution.scale = unit(rng) < 0.5 ? OBSCURA_RESOLUTION_HALF : OBSCURA_RESOLUTION_QUARTER;
                settings.resolution.upsample_tolerance = float(1e-4 * std::pow(1e4, unit(rng)));
            }
            if (!anchor && unit(rng) < 0.5) {
                glm::dmat4 projection;
                for (int i = 0; i < 16; ++i) projection[i / 4][i % 4] = camera.matrix()[i];
                const glm::dmat4 view_projection = projection * camera.view();
                const glm::dvec3 nudge(0.05 * (unit(rng) - 0.5), 0.05 * (unit(rng) - 0.5), 0.0);
                const glm::dmat4 previous = unit(rng) < 0.5 ? view_projection
                                                            : view_projection * glm::translate(glm::dmat4(1.0), nudge);
                for (int i = 0; i < 16; ++i) {
                    input.view_projection[i] = float(view_projection[i / 4][i % 4]);
                    input.previous_view_projection[i] = float(previous[i / 4][i % 4]);
                }
                input.frame_index = uint32_t(frame);
                if (unit(rng) < 0.1) input.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
                if (views.size() < 2 && unit(rng) < 0.05) {
                    obscura_view* view = nullptr;
                    ASSERT_EQ(obscura_create_view(context.get(), &view), OBSCURA_OK);
                    views.push_back(view);
                }
                if (!views.empty() && unit(rng) < 0.6) input.view = views[size_t(frame) % views.size()];
            }
            if (!views.empty() && unit(rng) < 0.01) {
                ASSERT_EQ(obscura_destroy_view(context.get(), views.back()), OBSCURA_OK);
                if (input.view == views.back()) input.view = nullptr;
                views.pop_back();
            }
            if (action < 0.006) {
                views.clear();  // destroyed with the context
                input.view = nullptr;
                context.reset();
                context = create(unit(rng) < 0.5);
                ASSERT_NE(context, nullptr);
                ++recreated;
            } else if (action < 0.046) {
                obscura_release_resources(context.get());
            } else if (action < 0.086) {
                const obscura_status status = obscura_prepare(context.get(), in.width, in.height, &settings);
                ASSERT_TRUE(status == OBSCURA_OK || status == OBSCURA_STATUS_INVALID_SETTING)
                    << "frame " << frame << ": prepare " << obscura_status_string(status) << ": "
                    << obscura_get_last_error(context.get());
            }

            // Frames whose output is checked start from a sentinel outside [0, 1], so a render that returns OK but
            // leaves texels unwritten (the last frame's values still there) fails the check.
            const bool check_output = output.debug_view == OBSCURA_DEBUG_NONE && output.blend == OBSCURA_BLEND_OVERWRITE &&
                                      output.texture == in.target_r16f.get() && (anchor || frame % 3 == 0);
            if (check_output) {
                const std::vector<float> sentinel(size_t(pixels), -1.0f);
                glBindTexture(GL_TEXTURE_2D, output.texture);
                glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, in.width, in.height, GL_RED, GL_FLOAT, sentinel.data());
                glBindTexture(GL_TEXTURE_2D, 0);
            }
            const obscura_status status = obscura_render(context.get(), &input, &settings, &output);
            ++statuses[status];
            ASSERT_TRUE(status == OBSCURA_OK || status == OBSCURA_STATUS_INVALID_SETTING)
                << "frame " << frame << " (" << obscura_method_name(method) << ", " << in.width << "x" << in.height
                << "): " << obscura_status_string(status) << ": " << obscura_get_last_error(context.get());
            ASSERT_EQ(take_gl_error(), GLenum(GL_NO_ERROR)) << "frame " << frame;

            if (status == OBSCURA_OK && check_output) {
                // The output rectangle's size (a zero rectangle is the whole texture), landing at (output.x,
                // output.y) in the target: every texel of it must be written with a visibility in [0, 1].
                const int width = input.output_rect.width > 0 ? input.output_rect.width : in.width;
                const int height = input.output_rect.width > 0 ? input.output_rect.height : in.height;
                const std::vector<float> ao = read_texture(output.texture, in.width, in.height, 1);
                int bad = 0;
                for (int y = output.y; y < output.y + height; ++y)
                    for (int x = output.x; x < output.x + width; ++x) {
                        const float v = ao[size_t(y) * in.width + x];
                        bad += !(std::isfinite(v) && v >= 0.0f && v <= 1.0f);
                    }
                ASSERT_GT(width * height, 0);
                ASSERT_EQ(bad, 0) << "frame " << frame << ": visibility outside [0, 1] or not written ("
                                  << obscura_method_name(method) << ", " << in.width << "x" << in.height << ")";
                ++checked_outputs;
            }
            if (anchor) {
                ASSERT_EQ(status, OBSCURA_OK);
                // Release first: what the report counts for this configuration is what it allocates again.
                obscura_release_resources(context.get());
                ASSERT_EQ(obscura_render(context.get(), &input, &settings, &output), OBSCURA_OK);
                uint64_t bytes = 0;
                ASSERT_EQ(obscura_get_memory_usage(context.get(), &bytes), OBSCURA_OK);
                if (frame == 0) anchor_bytes = bytes;
                EXPECT_EQ(bytes, anchor_bytes) << "frame " << frame << ": the anchor configuration's memory changed";
            }
        }
        context.reset();
        EXPECT_EQ(allocator.live_blocks, 0) << "host allocator blocks left after the last context was destroyed";
        EXPECT_EQ(allocator.live_bytes, 0);
        EXPECT_GE(statuses[OBSCURA_STATUS_OK], frames * 3 / 5) << "most random frames must render";
        EXPECT_GT(checked_outputs, frames / 20);
        EXPECT_GT(recreated, 0);
        std::printf("soak: %d frames, %d OK, %d INVALID_SETTING, %d outputs checked, %d contexts re-created (%d on "
                    "the GPU code paths), anchor %.1f KiB\n",
                    frames, statuses[OBSCURA_STATUS_OK], statuses[OBSCURA_STATUS_INVALID_SETTING], checked_outputs,
                    recreated, gpu_code_path_contexts, anchor_bytes / 1024.0);
    }
    glFinish();
    const std::map<std::string, int> objects_after = count_gl_objects();
    EXPECT_EQ(objects_before, objects_after) << "before: " << describe(objects_before)
                                             << "\nafter:  " << describe(objects_after);
}

}  // namespace
}  // namespace obscura_test
