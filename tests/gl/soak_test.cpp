// Soak: 2,000 frames of random methods, settings (drawn from the SDK's own metadata), sizes (1x1, 3x7, 4097x9,
// 9x4097 among ordinary ones), reduced resolutions, depth kinds, output targets and positions, prepares, releases,
// context re-creations (half of them on the GPUs' shader variants, OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS) and temporal
// frames (random history settings, matrices, camera cuts, views created and destroyed), the way
// an engine's editor drives the SDK for hours. Every call must return OK or, for random settings outside what
// the method accepts together, INVALID_SETTING, and then only when obscura_resolve_settings refuses the same settings
// too; no GL error may be left; the host's GL state, set to sentinels once (every binding and setting of
// gl_state_snapshot.h), is unchanged after every obscura_* call; sampled outputs are finite and in [0, 1] inside the
// result and untouched outside it (and everywhere after a refusal); the memory report for one fixed configuration
// never drifts; and at the end no GL object and no byte of the host allocator is left. The
// AddressSanitizer/LeakSanitizer build runs the same test.
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
#include "gl_state_snapshot.h"
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

// A depth buffer of one size: a box on a floor, as hardware D32F and as linear view depth, and its targets (one
// larger than the depth by kMargin texels on each axis, where results land anywhere).
constexpr int kMarginX = 5, kMarginY = 3;
struct SizedInputs {
    int width = 0, height = 0;
    std::unique_ptr<Camera> hardware_camera, linear_camera;
    HostTexture hardware_depth, linear_depth;
    HostTexture target_r16f, target_rgba8, target_large;
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
    inputs->target_large = make_texture(GL_R16F, width + kMarginX, height + kMarginY);
    return inputs;
}

// The host's GL state during the soak: a sentinel object bound, or a value other than GL's default set, at every place
// gl_state_snapshot.h captures (the SDK's texture, sampler and image units and more, uniform and storage buffers
// indexed and generic, the other buffer bindings, vertex array, framebuffers and the read buffer, renderbuffer,
// program, viewport, scissor, blend, depth test, rasterizer discard, colour mask, pixel store), as a host's renderer
// leaves it between its own passes. apply() sets it; neutral() gives the test's own uploads and read-backs a default
// pixel store without pixel buffers (the test then applies the sentinels again before the next SDK call).
class HostSentinels {
public:
    // 2D textures for every unit and three more for the framebuffers, whose read one reads attachment 1.
    HostSentinels()
        : objects_(kSnapshotTextureUnits + 3, 1, kSnapshotTextureUnits, SentinelObjects::ReadAttachment::One) {}

    void apply() const {
        glUseProgram(objects_.program());
        for (int unit = 0; unit < kSnapshotTextureUnits; ++unit) {
            glActiveTexture(GLenum(GL_TEXTURE0 + unit));
            glBindTexture(GL_TEXTURE_2D, objects_.texture_2d(unit));
            glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, unit % 3 == 0 ? objects_.multisample(0) : 0);
            glBindTexture(GL_TEXTURE_3D, unit % 2 == 1 ? objects_.texture_3d() : 0);
            glBindTexture(GL_TEXTURE_2D_ARRAY, unit % 3 == 1 ? objects_.texture_array() : 0);
            glBindTexture(GL_TEXTURE_CUBE_MAP, unit % 4 == 0 ? objects_.texture_cube() : 0);
            glBindTexture(GL_TEXTURE_BUFFER, unit >= 4 ? objects_.texture_buffer() : 0);
            glBindSampler(GLuint(unit), objects_.sampler(unit % 5));
        }
        // Image units: level / layering / layer / access / format unlike GL's defaults.
        for (int unit = 0; unit < kSnapshotImageUnits; ++unit) {
            switch (unit % 3) {
                case 0:
                    glBindImageTexture(GLuint(unit), objects_.texture_array(), 1, GL_FALSE, 2, GL_READ_ONLY, GL_RGBA8);
                    break;
                case 1:
                    glBindImageTexture(GLuint(unit), objects_.image_r32f(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
                    break;
                default:
                    glBindImageTexture(GLuint(unit), objects_.texture_3d(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA16F);
                    break;
            }
        }
        GLint ubo_align = 256, ssbo_align = 256;
        glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &ubo_align);
        glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &ssbo_align);
        for (int index = 0; index < kSnapshotBufferIndices; ++index) {
            glBindBufferRange(GL_UNIFORM_BUFFER, GLuint(index), objects_.buffer(1 + index % 2),
                              ubo_align * (index + 1), 256);
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, GLuint(index), objects_.buffer(3 + index % 2),
                              ssbo_align * (index + 1), 128);
        }
        glBindBuffer(GL_UNIFORM_BUFFER, objects_.buffer(0));
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, objects_.buffer(3));
        glBindBuffer(GL_TEXTURE_BUFFER, objects_.buffer(2));
        glBindVertexArray(objects_.vertex_array());
        glBindBuffer(GL_ARRAY_BUFFER, objects_.buffer(4));
        glBindBuffer(GL_PIXEL_PACK_BUFFER, objects_.buffer(2));
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, objects_.buffer(1));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, objects_.buffer(0));
        glBindBuffer(GL_COPY_READ_BUFFER, objects_.buffer(3));
        glBindRenderbuffer(GL_RENDERBUFFER, objects_.renderbuffer());
        glBindFramebuffer(GL_READ_FRAMEBUFFER, objects_.framebuffer(0));
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, objects_.framebuffer(1));
        glViewport(3, 5, 77, 41);
        glScissor(1, 2, 30, 40);
        glEnable(GL_SCISSOR_TEST);
        glEnable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_RASTERIZER_DISCARD);
        glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
        set_sentinel_pixel_store();
        glActiveTexture(GL_TEXTURE5);
    }

    static void neutral() {
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        set_default_pixel_store();
    }

    // Back to GL's defaults (before the objects are deleted), with the viewport and scissor box `initial` held.
    static void restore_defaults(const GLint viewport[4], const GLint scissor[4]) {
        neutral();
        glUseProgram(0);
        for (int unit = 0; unit < kSnapshotTextureUnits; ++unit) {
            glActiveTexture(GLenum(GL_TEXTURE0 + unit));
            for (GLenum target : {GL_TEXTURE_2D, GL_TEXTURE_2D_MULTISAMPLE, GL_TEXTURE_3D, GL_TEXTURE_2D_ARRAY,
                                  GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BUFFER})
                glBindTexture(target, 0);
            glBindSampler(GLuint(unit), 0);
        }
        glActiveTexture(GL_TEXTURE0);
        for (int unit = 0; unit < kSnapshotImageUnits; ++unit) {
            glBindImageTexture(GLuint(unit), 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
        }
        for (int index = 0; index < kSnapshotBufferIndices; ++index) {
            glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(index), 0);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(index), 0);
        }
        for (GLenum target : {GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER, GL_TEXTURE_BUFFER, GL_ARRAY_BUFFER,
                              GL_DISPATCH_INDIRECT_BUFFER, GL_COPY_READ_BUFFER})
            glBindBuffer(target, 0);
        glBindVertexArray(0);
        glBindRenderbuffer(GL_RENDERBUFFER, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
        glScissor(scissor[0], scissor[1], scissor[2], scissor[3]);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_RASTERIZER_DISCARD);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }

private:
    SentinelObjects objects_;
};

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
    const Snapshot state_before = capture();
    GLint initial_viewport[4] = {}, initial_scissor[4] = {};
    glGetIntegerv(GL_VIEWPORT, initial_viewport);
    glGetIntegerv(GL_SCISSOR_BOX, initial_scissor);

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
        // The host's state: sentinels, applied before every SDK call that follows the test's own GL work; every
        // obscura_* call must leave it (and no GL error) as it found it.
        const HostSentinels sentinels;
        sentinels.apply();
        const Snapshot sentinel_state = capture();
        ASSERT_FALSE(diff(state_before, sentinel_state).empty());
        bool host_state_dirty = false;
        auto before_sdk = [&] {
            if (host_state_dirty) sentinels.apply();
            host_state_dirty = false;
        };
        auto host_work = [&] {  // the test's own uploads, read-backs and objects
            if (!host_state_dirty) HostSentinels::neutral();
            host_state_dirty = true;
        };
        int frame = -1;
        int state_checks = 0;
        auto state_kept = [&](const char* call) -> ::testing::AssertionResult {
            ++state_checks;
            const GLenum error = take_gl_error();
            const std::string changed = diff(sentinel_state, capture());
            if (error == GL_NO_ERROR && changed.empty()) return ::testing::AssertionSuccess();
            return ::testing::AssertionFailure() << "frame " << frame << ": " << call << " left "
                                                 << gl_error_name(error) << " and changed the host's GL state:\n"
                                                 << changed;
        };

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
            before_sdk();
            EXPECT_EQ(obscura_create_context(&desc, &raw), OBSCURA_OK);
            EXPECT_TRUE(state_kept("obscura_create_context"));
            return ContextPtr(raw);
        };
        ContextPtr context = create(false);
        ASSERT_NE(context, nullptr);
        std::vector<obscura_view*> views;  // the current context's (destroyed with it)
        // INVALID_SETTING is the answer to settings that obscura_resolve_settings refuses too (with the context, which
        // derives what its renderer needs): a configuration it accepts must render.
        auto resolve_refuses = [&](const obscura_settings& s) {
            obscura_settings resolved;
            before_sdk();
            const obscura_status status = obscura_resolve_settings(context.get(), &s, &resolved);
            EXPECT_TRUE(state_kept("obscura_resolve_settings"));
            return status == OBSCURA_STATUS_INVALID_SETTING;
        };

        // The anchor: one fixed configuration rendered every 100 frames; its memory report must never change.
        obscura_settings anchor_settings;
        obscura_default_settings(OBSCURA_METHOD_HBAO, &anchor_settings);
        const size_t anchor_size = 6;  // 64x36
        uint64_t anchor_bytes = 0;

        std::map<int, int> statuses;
        int checked_outputs = 0, offset_outputs = 0, recreated = 0;
        for (frame = 0; frame < frames && !HasFatalFailure(); ++frame) {
            const bool anchor = frame % 100 == 0;
            const size_t size_index = anchor ? anchor_size : pick_size(rng);
            auto& slot = inputs[size_index];
            if (!slot) {
                host_work();
                slot = make_inputs(sizes[size_index].first, sizes[size_index].second);
            }
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
            // The result's size (a zero rectangle is the whole depth), and where it lands: the depth-sized targets
            // at (0, 0) or, with a guard band, anywhere it fits; the larger target anywhere it fits.
            const int result_width = input.output_rect.width > 0 ? input.output_rect.width : in.width;
            const int result_height = input.output_rect.width > 0 ? input.output_rect.height : in.height;
            const double target_draw = anchor ? 0.0 : unit(rng);
            const bool large = target_draw >= 0.55 && target_draw < 0.75;
            const GLuint target = target_draw < 0.55 ? in.target_r16f.get() : large ? in.target_large.get()
                                                                                    : in.target_rgba8.get();
            const int target_width = in.width + (large ? kMarginX : 0);
            const int target_height = in.height + (large ? kMarginY : 0);
            obscura_output output = make_output(target);
            if (!anchor && (large || unit(rng) < 0.3)) {
                output.x = std::uniform_int_distribution<int>(0, target_width - result_width)(rng);
                output.y = std::uniform_int_distribution<int>(0, target_height - result_height)(rng);
            }
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
                    before_sdk();
                    ASSERT_EQ(obscura_create_view(context.get(), &view), OBSCURA_OK);
                    ASSERT_TRUE(state_kept("obscura_create_view"));
                    views.push_back(view);
                }
                if (!views.empty() && unit(rng) < 0.6) input.view = views[size_t(frame) % views.size()];
            }
            if (!views.empty() && unit(rng) < 0.01) {
                before_sdk();
                ASSERT_EQ(obscura_destroy_view(context.get(), views.back()), OBSCURA_OK);
                ASSERT_TRUE(state_kept("obscura_destroy_view"));
                if (input.view == views.back()) input.view = nullptr;
                views.pop_back();
            }
            if (action < 0.006) {
                views.clear();  // destroyed with the context
                input.view = nullptr;
                before_sdk();
                context.reset();
                ASSERT_TRUE(state_kept("obscura_destroy_context"));
                context = create(unit(rng) < 0.5);
                ASSERT_NE(context, nullptr);
                ++recreated;
            } else if (action < 0.046) {
                before_sdk();
                obscura_release_resources(context.get());
                ASSERT_TRUE(state_kept("obscura_release_resources"));
            } else if (action < 0.086) {
                before_sdk();
                const obscura_status status = obscura_prepare(context.get(), in.width, in.height, &settings);
                ASSERT_TRUE(state_kept("obscura_prepare"));
                ASSERT_TRUE(status == OBSCURA_OK ||
                            (status == OBSCURA_STATUS_INVALID_SETTING && resolve_refuses(settings)))
                    << "frame " << frame << ": prepare " << obscura_status_string(status) << ": "
                    << obscura_get_last_error(context.get());
            }

            // Frames whose output is checked start from a sentinel outside [0, 1] in the whole target: a render that
            // returns OK but leaves texels of its result unwritten (the last frame's values still there), or writes
            // outside it, fails the check; so does a refused render that writes anything.
            const bool check_output = output.texture != in.target_rgba8.get() && (anchor || frame % 3 == 0);
            if (check_output) {
                host_work();
                const std::vector<float> sentinel(size_t(target_width) * size_t(target_height), -1.0f);
                glBindTexture(GL_TEXTURE_2D, output.texture);
                glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, target_width, target_height, GL_RED, GL_FLOAT, sentinel.data());
                glBindTexture(GL_TEXTURE_2D, 0);
            }
            before_sdk();
            const obscura_status status = obscura_render(context.get(), &input, &settings, &output);
            ASSERT_TRUE(state_kept("obscura_render"));
            ++statuses[status];
            ASSERT_TRUE(status == OBSCURA_OK || (status == OBSCURA_STATUS_INVALID_SETTING && resolve_refuses(settings)))
                << "frame " << frame << " (" << obscura_method_name(settings.method) << ", " << in.width << "x"
                << in.height << "): " << obscura_status_string(status) << ": " << obscura_get_last_error(context.get());

            if (check_output) {
                // Inside the result (the output rectangle's size at output.x, output.y): a visibility in [0, 1] (a
                // debug view's value too, but for the tap count, taps / 256, which may pass 1), or with MULTIPLY the
                // sentinel times one, in [-1, 0]; outside it, and everywhere after a refusal, the sentinel.
                host_work();
                const std::vector<float> ao = read_texture(output.texture, target_width, target_height, 1);
                const bool multiply = output.blend == OBSCURA_BLEND_MULTIPLY;
                const float most = output.debug_view == OBSCURA_DEBUG_TAP_COUNT ? INFINITY : 1.0f;
                int bad_inside = 0, bad_outside = 0, first_x = -1, first_y = -1;
                for (int y = 0; y < target_height; ++y)
                    for (int x = 0; x < target_width; ++x) {
                        const float v = ao[size_t(y) * size_t(target_width) + size_t(x)];
                        const bool inside = status == OBSCURA_OK && x >= output.x && y >= output.y &&
                                            x < output.x + result_width && y < output.y + result_height;
                        const bool ok = !inside ? v == -1.0f
                                        : multiply ? std::isfinite(v) && v >= -most && v <= 0.0f
                                                   : std::isfinite(v) && v >= 0.0f && v <= most;
                        if (!ok && first_x < 0) first_x = x, first_y = y;
                        (inside ? bad_inside : bad_outside) += ok ? 0 : 1;
                    }
                ASSERT_EQ(bad_inside, 0) << "frame " << frame << ": visibility outside [0, 1] or not written ("
                                         << obscura_method_name(settings.method) << ", " << in.width << "x" << in.height
                                         << ", debug view " << int(output.debug_view) << ", first at " << first_x
                                         << ", " << first_y << ")";
                ASSERT_EQ(bad_outside, 0) << "frame " << frame << ": " << obscura_status_string(status) << " wrote "
                                          << bad_outside << " texels outside the " << result_width << "x"
                                          << result_height << " result at (" << output.x << ", " << output.y
                                          << ") of the " << target_width << "x" << target_height << " target ("
                                          << obscura_method_name(settings.method) << ", first at " << first_x << ", "
                                          << first_y << ")";
                ++checked_outputs;
                if (output.x || output.y) ++offset_outputs;
            }
            if (anchor) {
                ASSERT_EQ(status, OBSCURA_OK);
                // Release first: what the report counts for this configuration is what it allocates again.
                before_sdk();
                obscura_release_resources(context.get());
                ASSERT_TRUE(state_kept("obscura_release_resources"));
                ASSERT_EQ(obscura_render(context.get(), &input, &settings, &output), OBSCURA_OK);
                ASSERT_TRUE(state_kept("obscura_render"));
                uint64_t bytes = 0;
                ASSERT_EQ(obscura_get_memory_usage(context.get(), &bytes), OBSCURA_OK);
                ASSERT_TRUE(state_kept("obscura_get_memory_usage"));
                if (frame == 0) anchor_bytes = bytes;
                EXPECT_EQ(bytes, anchor_bytes) << "frame " << frame << ": the anchor configuration's memory changed";
            }
        }
        before_sdk();
        context.reset();
        EXPECT_TRUE(state_kept("obscura_destroy_context"));
        EXPECT_EQ(allocator.live_blocks, 0) << "host allocator blocks left after the last context was destroyed";
        EXPECT_EQ(allocator.live_bytes, 0);
        EXPECT_GE(statuses[OBSCURA_STATUS_OK], frames * 3 / 5) << "most random frames must render";
        EXPECT_GT(checked_outputs, frames / 20);
        EXPECT_GT(offset_outputs, frames / 100);
        EXPECT_GT(recreated, 0);
        std::printf("soak: %d frames, %d OK, %d INVALID_SETTING, %d outputs checked (%d at an offset), %d contexts "
                    "re-created (%d on the GPU code paths), %d host-state checks, anchor %.1f KiB\n",
                    frames, statuses[OBSCURA_STATUS_OK], statuses[OBSCURA_STATUS_INVALID_SETTING], checked_outputs,
                    offset_outputs, recreated, gpu_code_path_contexts, state_checks, anchor_bytes / 1024.0);
        inputs.clear();
        HostSentinels::restore_defaults(initial_viewport, initial_scissor);
    }
    glFinish();
    EXPECT_EQ(diff(state_before, capture()), "") << "the test left the host's GL state changed";
    const std::map<std::string, int> objects_after = count_gl_objects();
    EXPECT_EQ(objects_before, objects_after) << "before: " << describe(objects_before)
                                             << "\nafter:  " << describe(objects_after);
}

}  // namespace
}  // namespace obscura_test
