// GL state contract: obscura_render (and create/prepare/destroy) leave every binding and setting the
// host made as they found it, and no GL error. The host sets distinctive sentinel values for all the
// state listed below, the SDK runs, and everything is queried back and compared field by field.
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "analytic_scene.h"
#include "gl_state_snapshot.h"
#include "gl_test_support.h"

namespace obscura_test {
namespace {

constexpr int kWidth = 96;
constexpr int kHeight = 64;

// Which variants the passes compile: a CPU rasteriser's own (what llvmpipe gets) or, through
// OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS, the GPUs' (storage buffers, shared memory): every test runs with both.
enum class CodePaths { Cpu, Gpu };

// The host's objects and the sentinel state made from them.
class StatePreservation : public GLTest, public ::testing::WithParamInterface<CodePaths> {
public:
    StatePreservation() {
        context_flags_ = GetParam() == CodePaths::Gpu ? uint32_t(OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS) : 0u;
    }

protected:
    void SetUp() override {
        GLTest::SetUp();
        if (HasFatalFailure()) return;
        // Put back in TearDown: the sentinel's viewport would otherwise be the next test's default state, against
        // which SentinelStateIsDistinctive compares.
        glGetIntegerv(GL_VIEWPORT, viewport_);
        build_frame();
        build_host_objects();
    }

    void TearDown() override {
        // Back to a neutral state before the host objects are deleted.
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        set_default_pixel_store();
        for (GLenum target : {GL_ARRAY_BUFFER, GL_PIXEL_PACK_BUFFER, GL_PIXEL_UNPACK_BUFFER,
                              GL_DISPATCH_INDIRECT_BUFFER, GL_COPY_READ_BUFFER, GL_UNIFORM_BUFFER,
                              GL_SHADER_STORAGE_BUFFER})
            glBindBuffer(target, 0);
        glBindVertexArray(0);
        glBindRenderbuffer(GL_RENDERBUFFER, 0);
        for (int unit = 0; unit < kSnapshotTextureUnits; ++unit) glBindSampler(GLuint(unit), 0);
        glActiveTexture(GL_TEXTURE0);
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
        GLTest::TearDown();
    }

    void build_frame() {
        // A box on a floor, D24S8 depth with the stencil mode selected by the host.
        Camera camera(Projection::Perspective, kWidth, kHeight, Lens(),
                      look_at(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0)));
        std::vector<Hit> hits = trace(camera, {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                                               box(2, glm::dvec3(-0.5, 0.0, -0.5), glm::dvec3(0.5, 0.7, 0.5))});
        depth_ = make_depth_texture(GL_DEPTH24_STENCIL8, kWidth, kHeight, depth_values(camera, hits));
        glBindTexture(GL_TEXTURE_2D, depth_.get());
        glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
        glBindTexture(GL_TEXTURE_2D, 0);
        input_ = make_input(depth_.get(), kWidth, kHeight, camera.matrix(), camera.clip_depth());
        settings_ = make_settings(1.0f);
        output_texture_ = make_texture(GL_RGBA8, kWidth, kHeight);
        fill_texture(output_texture_.get(), kWidth, kHeight, 0.5f, 0.5f, 0.5f, 1.0f);
        blit_target_ = make_renderbuffer_target(GL_RGBA8, kWidth, kHeight);
    }

    void build_host_objects() {
        // A 2D texture for every unit, the last two also the framebuffers' (which read GL's default attachment), and
        // multisample textures for the three units set_sentinel_state() binds them on.
        host_.emplace(kSnapshotTextureUnits, 3, kSnapshotTextureUnits - 2, SentinelObjects::ReadAttachment::Zero);
        ASSERT_EQ(take_gl_error(), GLenum(GL_NO_ERROR)) << "building the host objects";
    }

    void set_sentinel_state() {
        glUseProgram(host_->program());
        for (int unit = 0; unit < kSnapshotTextureUnits; ++unit) {
            glActiveTexture(GLenum(GL_TEXTURE0 + unit));
            glBindTexture(GL_TEXTURE_2D, host_->texture_2d(unit));
        }
        // Multisample textures on units the SDK uses (0, 2) and one it does not (5); other targets too.
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, host_->multisample(0));
        glBindTexture(GL_TEXTURE_CUBE_MAP, host_->texture_cube());
        glActiveTexture(GL_TEXTURE2);
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, host_->multisample(1));
        glActiveTexture(GL_TEXTURE3);
        glBindTexture(GL_TEXTURE_3D, host_->texture_3d());
        glActiveTexture(GL_TEXTURE4);  // where FFAO binds its 3D table
        glBindTexture(GL_TEXTURE_3D, host_->texture_3d());
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D_ARRAY, host_->texture_array());
        glActiveTexture(GL_TEXTURE5);
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, host_->multisample(2));
        // Buffer textures on the units LSAO reads its lines and values through (4, 5) and on one it does not.
        for (int unit : {4, 5, 7}) {
            glActiveTexture(GLenum(GL_TEXTURE0 + unit));
            glBindTexture(GL_TEXTURE_BUFFER, host_->texture_buffer());
        }
        glBindBuffer(GL_TEXTURE_BUFFER, host_->buffer(2));
        for (int unit = 0; unit < kSnapshotSamplerUnits; ++unit) glBindSampler(GLuint(unit), host_->sampler(unit));
        glBindSampler(6, host_->sampler(4));
        // Image units: level / layer / access / format all distinctive.
        glBindImageTexture(0, host_->texture_array(), 1, GL_FALSE, 2, GL_READ_ONLY, GL_RGBA8);
        glBindImageTexture(1, host_->image_r32f(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        glBindImageTexture(2, host_->texture_3d(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA16F);
        // Uniform and storage buffers: indexed ranges and bases, then the generic bindings.
        GLint ubo_align = 256, ssbo_align = 256;
        glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &ubo_align);
        glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &ssbo_align);
        glBindBufferRange(GL_UNIFORM_BUFFER, 0, host_->buffer(1), ubo_align, 256);
        glBindBufferRange(GL_UNIFORM_BUFFER, 1, host_->buffer(2), 2 * ubo_align, 512);
        glBindBufferBase(GL_UNIFORM_BUFFER, 2, host_->buffer(1));
        glBindBuffer(GL_UNIFORM_BUFFER, host_->buffer(0));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, host_->buffer(3), ssbo_align, 128);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, host_->buffer(4));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, host_->buffer(2), 2 * ssbo_align, 64);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, host_->buffer(3));
        glBindBuffer(GL_ARRAY_BUFFER, host_->buffer(4));
        glBindBuffer(GL_PIXEL_PACK_BUFFER, host_->buffer(2));
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, host_->buffer(1));
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, host_->buffer(0));
        glBindBuffer(GL_COPY_READ_BUFFER, host_->buffer(3));
        glBindVertexArray(host_->vertex_array());
        glBindRenderbuffer(GL_RENDERBUFFER, host_->renderbuffer());
        glBindFramebuffer(GL_READ_FRAMEBUFFER, host_->framebuffer(0));
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, host_->framebuffer(1));
        glViewport(3, 5, 77, 41);
        glScissor(1, 2, 30, 40);
        glEnable(GL_SCISSOR_TEST);
        glEnable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
        glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
        set_sentinel_pixel_store();
        glActiveTexture(GL_TEXTURE5);
        ASSERT_EQ(take_gl_error(), GLenum(GL_NO_ERROR)) << "setting the sentinel state";
    }

    GLint depth_stencil_mode() {
        // Queried through a unit the sentinel state does not care about, restored afterwards.
        GLint active = 0, previous = 0, mode = 0;
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
        glActiveTexture(GL_TEXTURE7);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous);
        glBindTexture(GL_TEXTURE_2D, depth_.get());
        glGetTexParameteriv(GL_TEXTURE_2D, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
        glBindTexture(GL_TEXTURE_2D, GLuint(previous));
        glActiveTexture(GLenum(active));
        return mode;
    }

    void expect_unchanged(const Snapshot& before, const char* what) {
        Snapshot after = capture();
        ASSERT_EQ(before.values.size(), after.values.size());
        std::string differences = diff(before, after);
        EXPECT_TRUE(differences.empty()) << what << " changed GL state:\n" << differences;
        EXPECT_EQ(depth_stencil_mode(), GL_STENCIL_INDEX) << what;
        GLenum error = take_gl_error();
        EXPECT_EQ(error, GLenum(GL_NO_ERROR)) << what << " left " << gl_error_name(error);
    }

    void clear_output_framebuffer() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, blit_target_.framebuffer.get());
        const GLfloat zero[4] = {0, 0, 0, 0};
        glClearBufferfv(GL_COLOR, 0, zero);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    }

    // Texels of the output renderbuffer whose alpha is not 1 (the AO writes alpha 1 everywhere).
    int count_unwritten_output_texels() {
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glPixelStorei(GL_PACK_SKIP_ROWS, 0);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, blit_target_.framebuffer.get());
        std::vector<uint8_t> bytes(size_t(kWidth) * kHeight * 4);
        glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        int unwritten = 0;
        for (size_t i = 0; i < bytes.size(); i += 4) unwritten += bytes[i + 3] != 255;
        return unwritten;
    }

    obscura_output texture_output() {
        obscura_output output = make_output(output_texture_.get());
        output.blend = OBSCURA_BLEND_MULTIPLY;
        return output;
    }
    obscura_output framebuffer_output() {
        obscura_output output = make_output(0);
        output.framebuffer = blit_target_.framebuffer.get();
        output.blend = OBSCURA_BLEND_MULTIPLY;
        return output;
    }

    GLint viewport_[4] = {};
    HostTexture depth_;
    obscura_input input_{};
    obscura_settings settings_{};
    HostTexture output_texture_;
    RenderbufferTarget blit_target_;  // the output as a framebuffer with a renderbuffer

    std::optional<SentinelObjects> host_;  // made in SetUp, once the shared context is current
};

TEST_P(StatePreservation, SentinelStateIsDistinctive) {
    // Guards the test itself: the sentinel state differs from the default in the fields that matter.
    Snapshot defaults = capture();
    set_sentinel_state();
    Snapshot sentinel = capture();
    std::string differences = diff(defaults, sentinel);
    for (const char* field : {"CURRENT_PROGRAM", "ACTIVE_TEXTURE", "unit 0 TEXTURE_BINDING_2D_MS", "unit 3 SAMPLER_BINDING",
                              "image 0 LEVEL", "image 0 LAYER", "image 1 FORMAT", "image 2 LAYERED", "UBO start [0]",
                              "UBO size [1]", "SSBO start [0]", "READ_FRAMEBUFFER_BINDING", "DRAW_FRAMEBUFFER_BINDING",
                              "VIEWPORT[2]", "SCISSOR_TEST", "PACK_ROW_LENGTH", "UNPACK_ALIGNMENT"})
        EXPECT_NE(differences.find(std::string("  ") + field + ":"), std::string::npos) << field;
}

TEST_P(StatePreservation, RenderIntoTexture) {
    set_sentinel_state();
    Snapshot before = capture();
    obscura_output output = texture_output();
    ASSERT_EQ(obscura_render(ctx(), &input_, &settings_, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    expect_unchanged(before, "render into a texture (multiply)");
}

TEST_P(StatePreservation, RenderIntoRenderbufferFramebuffer) {
    set_sentinel_state();
    Snapshot before = capture();
    obscura_output output = framebuffer_output();
    ASSERT_EQ(obscura_render(ctx(), &input_, &settings_, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    expect_unchanged(before, "render into a renderbuffer FBO (blit, multiply)");
}

TEST_P(StatePreservation, RenderDebugViews) {
    set_sentinel_state();
    Snapshot before = capture();
    for (obscura_debug_view view : {OBSCURA_DEBUG_LINEAR_DEPTH, OBSCURA_DEBUG_NORMALS, OBSCURA_DEBUG_AO_BEFORE_BLUR}) {
        obscura_output output = texture_output();
        output.debug_view = view;
        ASSERT_EQ(obscura_render(ctx(), &input_, &settings_, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    }
    expect_unchanged(before, "debug-view renders");
}

// Every method binds its own passes' resources: SAO six image units and a mipmapped sampler, LSAO storage
// buffers (buffer textures on the CPU paths), FFAO a 3D table with a linear sampler, the reference its accumulator,
// GTAO the z pyramid's levels.
TEST_P(StatePreservation, EveryMethod) {
    set_sentinel_state();
    Snapshot before = capture();
    for (obscura_method method : {OBSCURA_METHOD_HBAO, OBSCURA_METHOD_SAO, OBSCURA_METHOD_LSAO, OBSCURA_METHOD_FFAO,
                                  OBSCURA_METHOD_REFERENCE, OBSCURA_METHOD_GTAO}) {
        obscura_settings settings;
        ASSERT_EQ(obscura_default_settings(method, &settings), OBSCURA_OK);
        settings.reference.rays = 4;
        for (obscura_debug_view view : {OBSCURA_DEBUG_NONE, OBSCURA_DEBUG_TAP_COUNT}) {
            obscura_output output = texture_output();
            output.debug_view = view;
            ASSERT_EQ(obscura_render(ctx(), &input_, &settings, &output), OBSCURA_OK)
                << obscura_method_name(method) << ": " << obscura_get_last_error(ctx());
        }
    }
    ASSERT_EQ(obscura_prepare(ctx(), input_.depth_width, input_.depth_height, &settings_), OBSCURA_OK);
    expect_unchanged(before, "a render of every method");
}

// Reduced resolution adds the upsample: the host's depth on unit 0 again, the reduced depth, normals and AO (or bent
// normals, with GTAO's bent output and temporal frames) as samplers, one or two image units; the composite reads the
// reduced textures in the debug views.
TEST_P(StatePreservation, ReducedResolution) {
    HostTexture bent = make_texture(GL_RGBA16F, kWidth, kHeight);
    set_sentinel_state();
    Snapshot before = capture();
    for (obscura_resolution scale : {OBSCURA_RESOLUTION_HALF, OBSCURA_RESOLUTION_QUARTER}) {
        for (obscura_method method : {OBSCURA_METHOD_HBAO, OBSCURA_METHOD_SAO, OBSCURA_METHOD_LSAO,
                                      OBSCURA_METHOD_FFAO, OBSCURA_METHOD_GTAO, OBSCURA_METHOD_REFERENCE}) {
            obscura_settings settings;
            ASSERT_EQ(obscura_default_settings(method, &settings), OBSCURA_OK);
            settings.reference.rays = 4;
            settings.resolution.scale = scale;
            settings.temporal.enabled = method == OBSCURA_METHOD_GTAO ? OBSCURA_TOGGLE_ON : OBSCURA_TOGGLE_OFF;
            for (obscura_debug_view view : {OBSCURA_DEBUG_NONE, OBSCURA_DEBUG_LINEAR_DEPTH, OBSCURA_DEBUG_AO_BEFORE_BLUR}) {
                obscura_output output = texture_output();
                output.debug_view = view;
                output.bent_normal_texture = method == OBSCURA_METHOD_GTAO ? bent.get() : 0;
                ASSERT_EQ(obscura_render(ctx(), &input_, &settings, &output), OBSCURA_OK)
                    << obscura_method_name(method) << ": " << obscura_get_last_error(ctx());
            }
        }
    }
    expect_unchanged(before, "reduced-resolution renders");
}

// Temporal accumulation binds the history, the bent-normal history, the motion vectors (unit 0) and two image
// units. A view's sequence that runs every variant of the pass: the first frame starts the history, the camera
// then slides back and forth (the matrices' reprojection reads it), motion vectors replace the matrices (the
// motion variant reads it), bent normals start their own history and the next frame reads both; the context's
// own view renders in between (its own history).
TEST_P(StatePreservation, TemporalAccumulation) {
    HostTexture motion = make_texture(GL_RG16F, input_.depth_width, input_.depth_height);
    fill_texture(motion.get(), input_.depth_width, input_.depth_height, 0.25f, -0.5f, 0.0f, 0.0f);
    HostTexture bent = make_texture(GL_RGBA16F, kWidth, kHeight);
    obscura_view* view = nullptr;
    ASSERT_EQ(obscura_create_view(ctx(), &view), OBSCURA_OK);
    set_sentinel_state();
    Snapshot before = capture();
    obscura_settings settings;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_GTAO, &settings), OBSCURA_OK);
    settings.temporal.enabled = OBSCURA_TOGGLE_ON;
    float slid[16];
    std::memcpy(slid, input_.projection, sizeof slid);
    slid[12] += 0.02f;  // the camera a little to the side: clip x moves by 0.02 w
    const float* cameras[2] = {input_.projection, slid};
    for (uint32_t frame = 0; frame < 6; ++frame) {
        obscura_input input = input_;
        input.frame_index = frame;
        input.view = view;
        std::memcpy(input.view_projection, cameras[frame % 2], sizeof input.view_projection);
        std::memcpy(input.previous_view_projection, cameras[(frame + 1) % 2], sizeof input.previous_view_projection);
        input.motion_vector_texture = frame == 2 ? motion.get() : 0;
        obscura_output output = texture_output();
        output.bent_normal_texture = frame >= 4 ? bent.get() : 0;
        ASSERT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_OK)
            << "frame " << frame << ": " << obscura_get_last_error(ctx());
        if (frame == 2) {
            input.view = nullptr;  // the context's own view, between two of the view's frames
            ASSERT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
        }
    }
    ASSERT_EQ(obscura_destroy_view(ctx(), view), OBSCURA_OK);
    expect_unchanged(before, "temporal frames");
}

TEST_P(StatePreservation, FailedRender) {
    set_sentinel_state();
    Snapshot before = capture();
    obscura_output output = texture_output();
    output.x = 5;  // does not fit: INVALID_RECT after the input was validated (stencil mode switched)
    ASSERT_EQ(obscura_render(ctx(), &input_, &settings_, &output), OBSCURA_STATUS_INVALID_RECT);
    expect_unchanged(before, "a render failing in output validation");
}

TEST_P(StatePreservation, FailedRenderOnWrongTextureTarget) {
    set_sentinel_state();
    Snapshot before = capture();
    obscura_input input = input_;
    input.depth_texture = host_->texture_3d();
    input.depth_width = input.depth_height = 4;
    obscura_output output = texture_output();
    ASSERT_EQ(obscura_render(ctx(), &input, &settings_, &output), OBSCURA_STATUS_INVALID_TEXTURE);
    expect_unchanged(before, "a render failing on a 3D depth texture");
}

TEST_P(StatePreservation, PrepareAndRelease) {
    set_sentinel_state();
    Snapshot before = capture();
    ASSERT_EQ(obscura_prepare(ctx(), 128, 72, &settings_), OBSCURA_OK) << obscura_get_last_error(ctx());
    obscura_release_resources(ctx());
    expect_unchanged(before, "obscura_prepare + obscura_release_resources");
}

TEST_P(StatePreservation, CreateAndDestroy) {
    set_sentinel_state();
    Snapshot before = capture();
    ContextPtr other = create_context(context_flags_);
    ASSERT_NE(other, nullptr);
    obscura_output output = texture_output();
    ASSERT_EQ(obscura_render(other.get(), &input_, &settings_, &output), OBSCURA_OK);
    other.reset();
    expect_unchanged(before, "obscura_create_context + render + obscura_destroy_context");
}

TEST_P(StatePreservation, ResultStillCorrectUnderSentinelState) {
    // The host's bound objects and pixel-store state must not leak into the SDK's work: the result
    // under sentinel state equals the result under default state.
    obscura_output output = make_output(output_texture_.get());
    ASSERT_EQ(obscura_render(ctx(), &input_, &settings_, &output), OBSCURA_OK);
    std::vector<uint8_t> clean = read_texture_rgba8(output_texture_.get(), kWidth, kHeight);
    fill_texture(output_texture_.get(), kWidth, kHeight, 0, 0, 0, 0);
    set_sentinel_state();
    ASSERT_EQ(obscura_render(ctx(), &input_, &settings_, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    // Read back under neutral pack state, then restore nothing: TearDown resets.
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    std::vector<uint8_t> dirty = read_texture_rgba8(output_texture_.get(), kWidth, kHeight);
    EXPECT_EQ(clean, dirty);
}

TEST_P(StatePreservation, BlitTargetWrittenDespiteHostScissorAndMask) {
    // The host's scissor box (1, 2, 30x40) and colour mask (r, b only) must not clip the blit into the
    // output framebuffer.
    obscura_output output = make_output(0);
    output.framebuffer = blit_target_.framebuffer.get();
    clear_output_framebuffer();
    set_sentinel_state();
    ASSERT_EQ(obscura_render(ctx(), &input_, &settings_, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    glDisable(GL_SCISSOR_TEST);
    EXPECT_EQ(count_unwritten_output_texels(), 0);
}

TEST_P(StatePreservation, BlitTargetWrittenDespiteRasterizerDiscard) {
    // GL_RASTERIZER_DISCARD left enabled by the host (transform-feedback passes) must not swallow the
    // blit into the output framebuffer, and must still be enabled afterwards.
    obscura_output output = make_output(0);
    output.framebuffer = blit_target_.framebuffer.get();
    clear_output_framebuffer();
    glEnable(GL_RASTERIZER_DISCARD);
    obscura_status status = obscura_render(ctx(), &input_, &settings_, &output);
    GLboolean still_enabled = glIsEnabled(GL_RASTERIZER_DISCARD);
    glDisable(GL_RASTERIZER_DISCARD);
    ASSERT_EQ(status, OBSCURA_OK) << obscura_get_last_error(ctx());
    EXPECT_TRUE(still_enabled);
    EXPECT_EQ(count_unwritten_output_texels(), 0);
}

INSTANTIATE_TEST_SUITE_P(CodePaths, StatePreservation, ::testing::Values(CodePaths::Cpu, CodePaths::Gpu),
                         [](const ::testing::TestParamInfo<CodePaths>& paths) {
                             return std::string(paths.param == CodePaths::Gpu ? "gpu" : "cpu");
                         });

}  // namespace
}  // namespace obscura_test
