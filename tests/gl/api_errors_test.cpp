// API errors: every failing call returns its documented status, explains itself through
// obscura_get_last_error() (or the log callback when there is no context yet), leaves no GL error
// behind, and renders nothing.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "gl_test_support.h"

namespace obscura_test {
namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr float kSentinel = 0.25f;

class ApiErrors : public GLTest {
protected:
    void SetUp() override {
        GLTest::SetUp();
        if (HasFatalFailure()) return;
        standard_projection(float(kWidth) / kHeight, projection_);
        // A plane 5 m away facing the camera: window depth of view z = -5 under the projection.
        double z = -5.0;
        double d = ((projection_[10] * z + projection_[14]) / -z) * 0.5 + 0.5;
        depth_ = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight,
                                    std::vector<float>(size_t(kWidth) * kHeight, float(d)));
        target_ = make_texture(GL_R32F, kWidth, kHeight);
        fill_texture(target_.get(), kWidth, kHeight, kSentinel, 0, 0, 1);
        input_ = make_input(depth_.get(), kWidth, kHeight, projection_);
        output_ = make_output(target_.get());
        settings_ = make_settings(1.0f);
    }

    obscura_status render() { return obscura_render(ctx(), &input_, &settings_, &output_); }

    // The render fails with `expected`, explains it, logs it, leaves no GL error, writes nothing.
    void expect_render_fails(obscura_status expected, const char* must_mention = nullptr) {
        size_t logged_before = log_.entries.size();
        obscura_status status = render();
        EXPECT_EQ(status, expected) << "got " << obscura_status_string(status) << ": " << obscura_get_last_error(ctx());
        std::string message = obscura_get_last_error(ctx());
        EXPECT_FALSE(message.empty()) << "obscura_get_last_error is empty after " << obscura_status_string(status);
        if (must_mention) {
            EXPECT_NE(message.find(must_mention), std::string::npos) << message;
        }
        ASSERT_EQ(log_.entries.size(), logged_before + 1) << "the log callback must receive the error";
        EXPECT_EQ(log_.entries.back().status, expected);
        EXPECT_EQ(log_.entries.back().level, OBSCURA_LOG_ERROR);
        EXPECT_EQ(log_.entries.back().message, message);
        GLenum error = take_gl_error();
        EXPECT_EQ(error, GLenum(GL_NO_ERROR)) << "left " << gl_error_name(error);
        expect_target_untouched();
    }

    void expect_target_untouched() {
        std::vector<float> values = read_texture(target_.get(), kWidth, kHeight, 1);
        int changed = 0;
        for (float v : values) changed += v != kSentinel;
        EXPECT_EQ(changed, 0) << "a failed render wrote into the output";
    }

    float projection_[16];
    HostTexture depth_;
    HostTexture target_;
    obscura_input input_{};
    obscura_output output_{};
    obscura_settings settings_{};
};

TEST_F(ApiErrors, BaselineRenders) {
    ASSERT_EQ(render(), OBSCURA_OK) << obscura_get_last_error(ctx());
    EXPECT_STREQ(obscura_get_last_error(ctx()), "");
    std::vector<float> values = read_texture(target_.get(), kWidth, kHeight, 1);
    for (float v : values) ASSERT_GT(v, 0.99f);  // a plane facing the camera: no occlusion
}

TEST_F(ApiErrors, LastErrorClearedBySuccess) {
    settings_.hbao.radius = std::numeric_limits<float>::quiet_NaN();
    ASSERT_EQ(render(), OBSCURA_STATUS_INVALID_SETTING);
    ASSERT_STRNE(obscura_get_last_error(ctx()), "");
    settings_.hbao.radius = 1.0f;
    ASSERT_EQ(render(), OBSCURA_OK);
    EXPECT_STREQ(obscura_get_last_error(ctx()), "");
}

// ---- Null pointers -----------------------------------------------------------------------------------

TEST_F(ApiErrors, NullInput) {
    EXPECT_EQ(obscura_render(ctx(), nullptr, &settings_, &output_), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, NullSettings) {
    EXPECT_EQ(obscura_render(ctx(), &input_, nullptr, &output_), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, NullOutput) {
    EXPECT_EQ(obscura_render(ctx(), &input_, &settings_, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, NullQueryOutputs) {
    // A call that names a valid context reports to it (its last error and log), not to the thread's record.
    const size_t logged = log_.entries.size();
    EXPECT_EQ(obscura_get_memory_usage(ctx(), nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_NE(std::string(obscura_get_last_error(ctx())).find("out_bytes"), std::string::npos);
    EXPECT_EQ(obscura_create_view(ctx(), nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_NE(std::string(obscura_get_last_error(ctx())).find("out_view"), std::string::npos);
    EXPECT_EQ(log_.entries.size(), logged + 2);
    EXPECT_EQ(obscura_get_timings(ctx(), nullptr, 4, nullptr, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_NE(std::string(obscura_get_last_error(ctx())).find("out_count"), std::string::npos);
    uint32_t count = 99;
    EXPECT_EQ(obscura_get_timings(ctx(), nullptr, 4, &count, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    // Asking only for the count is allowed.
    EXPECT_EQ(obscura_get_timings(ctx(), nullptr, 0, &count, nullptr), OBSCURA_OK);
    EXPECT_EQ(obscura_prepare(ctx(), kWidth, kHeight, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(obscura_resolve_settings(ctx(), nullptr, &settings_), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

// ---- Sizes and rectangles ----------------------------------------------------------------------------

TEST_F(ApiErrors, ZeroDepthWidth) {
    input_.depth_width = 0;
    expect_render_fails(OBSCURA_STATUS_INVALID_SIZE);
}

TEST_F(ApiErrors, NegativeDepthHeight) {
    input_.depth_height = -48;
    expect_render_fails(OBSCURA_STATUS_INVALID_SIZE);
}

TEST_F(ApiErrors, DepthLargerThanGlAllows) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    input_.depth_width = max_size + 1;
    expect_render_fails(OBSCURA_STATUS_INVALID_SIZE);
}

TEST_F(ApiErrors, PrepareRejectsBadSizes) {
    EXPECT_EQ(obscura_prepare(ctx(), 0, 10, &settings_), OBSCURA_STATUS_INVALID_SIZE);
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(obscura_prepare(ctx(), 10, -1, &settings_), OBSCURA_STATUS_INVALID_SIZE);
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
    EXPECT_EQ(obscura_prepare(ctx(), kWidth, kHeight, &settings_), OBSCURA_OK);
}

TEST_F(ApiErrors, DepthSizeDiffersFromTexture) {
    input_.depth_width = kWidth - 1;
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
}

TEST_F(ApiErrors, OutputRectOutsideDepth) {
    input_.output_rect = obscura_rect{kWidth / 2, 0, kWidth / 2 + 1, kHeight};
    expect_render_fails(OBSCURA_STATUS_INVALID_RECT);
}

TEST_F(ApiErrors, OutputRectNegativeOrigin) {
    input_.output_rect = obscura_rect{-1, 0, 8, 8};
    expect_render_fails(OBSCURA_STATUS_INVALID_RECT);
}

TEST_F(ApiErrors, OutputRectEmpty) {
    input_.output_rect = obscura_rect{4, 4, 0, 8};
    expect_render_fails(OBSCURA_STATUS_INVALID_RECT);
}

TEST_F(ApiErrors, OutputRectOverflowDoesNotWrap) {
    input_.output_rect = obscura_rect{8, 8, std::numeric_limits<int32_t>::max(), 8};
    expect_render_fails(OBSCURA_STATUS_INVALID_RECT);
}

// ---- Settings ------------------------------------------------------------------------------------------

TEST_F(ApiErrors, NaNRadius) {
    settings_.hbao.radius = std::numeric_limits<float>::quiet_NaN();
    expect_render_fails(OBSCURA_STATUS_INVALID_SETTING, "radius");
}

TEST_F(ApiErrors, InfiniteRadius) {
    settings_.hbao.radius = std::numeric_limits<float>::infinity();
    expect_render_fails(OBSCURA_STATUS_INVALID_SETTING, "radius");
}

TEST_F(ApiErrors, DirectionsOutOfRange) {
    settings_.hbao.directions = 33;
    expect_render_fails(OBSCURA_STATUS_INVALID_SETTING, "directions");
}

TEST_F(ApiErrors, StepsOutOfRange) {
    settings_.hbao.steps = 129;
    expect_render_fails(OBSCURA_STATUS_INVALID_SETTING, "steps");
}

TEST_F(ApiErrors, NegativeSteps) {
    settings_.hbao.steps = -1;
    expect_render_fails(OBSCURA_STATUS_INVALID_SETTING, "steps");
}

TEST_F(ApiErrors, MetersToViewUnitsInvalid) {
    input_.meters_to_view_units = std::numeric_limits<float>::quiet_NaN();
    expect_render_fails(OBSCURA_STATUS_INVALID_SETTING);
    input_.meters_to_view_units = -1.0f;
    expect_render_fails(OBSCURA_STATUS_INVALID_SETTING);
}

TEST_F(ApiErrors, BadMethodEnum) {
    store_raw(&settings_.method, 99);
    expect_render_fails(OBSCURA_STATUS_INVALID_ENUM);
}

// ---- Enums of the input and output ---------------------------------------------------------------------

TEST_F(ApiErrors, BadDepthKind) {
    store_raw(&input_.depth_kind, 5);
    expect_render_fails(OBSCURA_STATUS_INVALID_ENUM);
}

TEST_F(ApiErrors, BadClipDepth) {
    store_raw(&input_.clip_depth, 2);
    expect_render_fails(OBSCURA_STATUS_INVALID_ENUM);
}

TEST_F(ApiErrors, BadMatrixLayout) {
    store_raw(&input_.projection_layout, -1);
    expect_render_fails(OBSCURA_STATUS_INVALID_ENUM);
}

TEST_F(ApiErrors, BadBlendMode) {
    store_raw(&output_.blend, 2);
    expect_render_fails(OBSCURA_STATUS_INVALID_ENUM);
}

TEST_F(ApiErrors, BadDebugView) {
    store_raw(&output_.debug_view, OBSCURA_DEBUG_TAP_COUNT + 1);
    expect_render_fails(OBSCURA_STATUS_INVALID_ENUM);
}

// ---- Projection ----------------------------------------------------------------------------------------

TEST_F(ApiErrors, TransposedProjection) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) input_.projection[c * 4 + r] = projection_[r * 4 + c];
    expect_render_fails(OBSCURA_STATUS_PROJECTION_TRANSPOSED, "transposed");
}

TEST_F(ApiErrors, GarbageProjection) {
    for (int i = 0; i < 16; ++i) input_.projection[i] = float(i % 5) - 1.5f;
    expect_render_fails(OBSCURA_STATUS_INVALID_PROJECTION);
}

TEST_F(ApiErrors, NaNProjection) {
    input_.projection[5] = std::numeric_limits<float>::quiet_NaN();
    expect_render_fails(OBSCURA_STATUS_INVALID_PROJECTION);
}

// ---- Textures ------------------------------------------------------------------------------------------

TEST_F(ApiErrors, DepthNameIsNotATexture) {
    input_.depth_texture = 987654;
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
}

TEST_F(ApiErrors, DepthNameIsABuffer) {
    // A live buffer name that is not also a texture name (names are per object type).
    std::vector<HostBuffer> buffers;
    do {
        buffers.push_back(HostBuffer::create());
        glBindBuffer(GL_ARRAY_BUFFER, buffers.back().get());
        glBindBuffer(GL_ARRAY_BUFFER, 0);
    } while (glIsTexture(buffers.back().get()));
    ASSERT_TRUE(glIsBuffer(buffers.back().get()));
    input_.depth_texture = buffers.back().get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
}

TEST_F(ApiErrors, DepthZero) {
    input_.depth_texture = 0;
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
}

TEST_F(ApiErrors, DepthTexture3D) {
    HostTexture volume = HostTexture::create();
    glBindTexture(GL_TEXTURE_3D, volume.get());
    glTexStorage3D(GL_TEXTURE_3D, 1, GL_R32F, kWidth, kHeight, 2);
    glBindTexture(GL_TEXTURE_3D, 0);
    input_.depth_texture = volume.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
    // The probing bind must not have disturbed the 3D texture.
    GLint width = 0;
    glBindTexture(GL_TEXTURE_3D, volume.get());
    glGetTexLevelParameteriv(GL_TEXTURE_3D, 0, GL_TEXTURE_WIDTH, &width);
    glBindTexture(GL_TEXTURE_3D, 0);
    EXPECT_EQ(width, kWidth);
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, DepthTextureCubeMap) {
    HostTexture cube = HostTexture::create();
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube.get());
    glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_DEPTH_COMPONENT32F, 32, 32);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    input_.depth_texture = cube.get();
    input_.depth_width = 32;
    input_.depth_height = 32;
    target_ = make_texture(GL_R32F, kWidth, kHeight);
    fill_texture(target_.get(), kWidth, kHeight, kSentinel, 0, 0, 1);
    output_.texture = target_.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
}

TEST_F(ApiErrors, ColourTextureAsHardwareDepth) {
    HostTexture colour = make_texture(GL_RGBA8, kWidth, kHeight);
    input_.depth_texture = colour.get();
    expect_render_fails(OBSCURA_STATUS_UNSUPPORTED_FORMAT);
}

TEST_F(ApiErrors, R32FAsHardwareDepth) {
    HostTexture linear = make_texture(GL_R32F, kWidth, kHeight);
    input_.depth_texture = linear.get();
    expect_render_fails(OBSCURA_STATUS_UNSUPPORTED_FORMAT, "LINEAR_VIEW");
}

TEST_F(ApiErrors, DepthFormatAsLinearDepth) {
    input_.depth_kind = OBSCURA_DEPTH_LINEAR_VIEW;
    expect_render_fails(OBSCURA_STATUS_UNSUPPORTED_FORMAT);
}

// A texture the frame writes that it also reads, or writes twice (found by a read-only review: each rendered with
// status OK, reading and writing one texture in a dispatch).
TEST_F(ApiErrors, OutputTextureThatTheFrameReadsIsRefused) {
    // The output as the host's normals (the target is RGBA16F, a format both accept).
    HostTexture shared = make_texture(GL_RGBA16F, kWidth, kHeight);
    input_.normal_texture = shared.get();
    output_.texture = shared.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE, "output.texture and input.normal_texture");
    input_.normal_texture = 0;
    // The output as the motion vectors.
    HostTexture vectors = make_texture(GL_RG16F, kWidth, kHeight);
    input_.motion_vector_texture = vectors.get();
    output_.texture = vectors.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE, "output.texture and input.motion_vector_texture");
    input_.motion_vector_texture = 0;
    // The bent normals into the output texture itself.
    output_.texture = shared.get();
    output_.bent_normal_texture = shared.get();
    settings_.method = OBSCURA_METHOD_GTAO;
    obscura_default_settings(OBSCURA_METHOD_GTAO, &settings_);
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE, "output.texture and output.bent_normal_texture");
    // Linear depth written over by its own AO.
    input_.depth_kind = OBSCURA_DEPTH_LINEAR_VIEW;
    HostTexture linear = make_texture(GL_R32F, kWidth, kHeight);
    input_.depth_texture = linear.get();
    output_.texture = linear.get();
    output_.bent_normal_texture = 0;
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE, "output.texture and input.depth_texture");
}

// The same through a framebuffer whose colour attachment 0 is an input (written directly: RGBA16F; blitted into:
// RGBA8I is refused as integer, so a cube map face's blit): both rendered with status OK before 2026-12-06.
TEST_F(ApiErrors, OutputFramebufferAttachmentThatTheFrameReadsIsRefused) {
    HostTexture shared = make_texture(GL_RGBA16F, kWidth, kHeight);
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, shared.get(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    input_.normal_texture = shared.get();
    output_.texture = 0;
    output_.framebuffer = framebuffer.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE, "colour attachment 0 and input.normal_texture");
    // The blit path: an attachment the compute pass cannot write (RGB8: no image format), the host's normals too.
    HostTexture rgb = make_texture(GL_RGB8, kWidth, kHeight);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, rgb.get(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    input_.normal_texture = rgb.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE, "colour attachment 0 and input.normal_texture");
    // Not an input: renders.
    input_.normal_texture = 0;
    EXPECT_EQ(render(), OBSCURA_OK) << obscura_get_last_error(ctx());
}

// A host GL error left pending is reported before the aliased textures (the render fuzzer found INVALID_TEXTURE
// returned over it).
TEST_F(ApiErrors, PendingHostErrorComesBeforeAliasedTextures) {
    HostTexture shared = make_texture(GL_RGBA16F, kWidth, kHeight);
    input_.normal_texture = shared.get();
    output_.texture = shared.get();
    glBindTexture(GL_TEXTURE_2D, 4242424);  // not a texture name: GL_INVALID_OPERATION, left pending
    expect_render_fails(OBSCURA_STATUS_HOST_GL_ERROR);
}

TEST_F(ApiErrors, NormalTextureWrongSize) {
    HostTexture normals = make_texture(GL_RGBA16F, kWidth / 2, kHeight);
    input_.normal_texture = normals.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
}

TEST_F(ApiErrors, NormalTextureWrongFormat) {
    HostTexture normals = make_texture(GL_R32F, kWidth, kHeight);
    input_.normal_texture = normals.get();
    expect_render_fails(OBSCURA_STATUS_UNSUPPORTED_FORMAT);
}

TEST_F(ApiErrors, NormalTextureFailureRestoresStencilMode) {
    // The depth-stencil mode is switched for the frame before the normals are checked: a failure on the
    // normals must still restore it.
    std::vector<float> depth(size_t(kWidth) * kHeight, 0.99f);
    HostTexture ds = make_depth_texture(GL_DEPTH24_STENCIL8, kWidth, kHeight, depth);
    glBindTexture(GL_TEXTURE_2D, ds.get());
    glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
    glBindTexture(GL_TEXTURE_2D, 0);
    HostTexture normals = make_texture(GL_R8, kWidth, kHeight);
    input_.depth_texture = ds.get();
    input_.normal_texture = normals.get();
    expect_render_fails(OBSCURA_STATUS_UNSUPPORTED_FORMAT);
    GLint mode = 0;
    glBindTexture(GL_TEXTURE_2D, ds.get());
    glGetTexParameteriv(GL_TEXTURE_2D, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
    glBindTexture(GL_TEXTURE_2D, 0);
    EXPECT_EQ(mode, GL_STENCIL_INDEX);
}

TEST_F(ApiErrors, OutputTextureTooSmall) {
    target_ = make_texture(GL_R32F, kWidth - 8, kHeight);
    fill_texture(target_.get(), kWidth - 8, kHeight, kSentinel, 0, 0, 1);
    output_.texture = target_.get();
    // Reported as INVALID_RECT: the output rectangle placed at (x, y) does not fit the target.
    obscura_status status = render();
    EXPECT_EQ(status, OBSCURA_STATUS_INVALID_RECT) << obscura_get_last_error(ctx());
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, OutputOffsetPushesOutside) {
    output_.x = 1;
    expect_render_fails(OBSCURA_STATUS_INVALID_RECT);
}

TEST_F(ApiErrors, OutputNegativeOffset) {
    output_.y = -1;
    expect_render_fails(OBSCURA_STATUS_INVALID_RECT);
}

TEST_F(ApiErrors, OutputFormatRGB8) {
    HostTexture rgb = make_texture(GL_RGB8, kWidth, kHeight);
    output_.texture = rgb.get();
    obscura_status status = render();
    EXPECT_EQ(status, OBSCURA_STATUS_UNSUPPORTED_FORMAT) << obscura_get_last_error(ctx());
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, OutputFormatDepth) {
    std::vector<float> depth(size_t(kWidth) * kHeight, 0.5f);
    HostTexture d = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, depth);
    output_.texture = d.get();
    obscura_status status = render();
    EXPECT_EQ(status, OBSCURA_STATUS_UNSUPPORTED_FORMAT) << obscura_get_last_error(ctx());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, OutputNameIsNotATexture) {
    output_.texture = 55555;
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
}

TEST_F(ApiErrors, OutputTextureWrongTarget) {
    HostTexture array = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D_ARRAY, array.get());
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_R32F, kWidth, kHeight, 2);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    output_.texture = array.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_TEXTURE);
}

TEST_F(ApiErrors, OutputFramebufferNotAFramebuffer) {
    output_.texture = 0;
    output_.framebuffer = 4242;
    expect_render_fails(OBSCURA_STATUS_INVALID_FRAMEBUFFER);
}

TEST_F(ApiErrors, OutputFramebufferIncomplete) {
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    output_.texture = 0;
    output_.framebuffer = framebuffer.get();
    expect_render_fails(OBSCURA_STATUS_INVALID_FRAMEBUFFER);
    GLint bound = -1;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    EXPECT_EQ(bound, 0);
}

// ---- Struct sizes and versions --------------------------------------------------------------------------

TEST_F(ApiErrors, InputStructSize) {
    input_.struct_size = sizeof(obscura_input) - 4;
    expect_render_fails(OBSCURA_STATUS_INVALID_STRUCT_SIZE, "obscura_input");
}

TEST_F(ApiErrors, OutputStructSize) {
    output_.struct_size = 0;
    expect_render_fails(OBSCURA_STATUS_INVALID_STRUCT_SIZE, "obscura_output");
}

TEST_F(ApiErrors, SettingsStructSize) {
    settings_.struct_size = sizeof(obscura_settings) + 8;
    expect_render_fails(OBSCURA_STATUS_INVALID_STRUCT_SIZE, "obscura_settings");
}

TEST_F(ApiErrors, DescStructSize) {
    obscura_context_desc desc = make_desc();
    LogCapture log;
    log.attach(&desc);
    desc.struct_size = sizeof desc + 4;
    obscura_context* context = reinterpret_cast<obscura_context*>(0x10);
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_INVALID_STRUCT_SIZE);
    EXPECT_EQ(context, nullptr);
    ASSERT_EQ(log.entries.size(), 1u);
    EXPECT_EQ(log.entries[0].status, OBSCURA_STATUS_INVALID_STRUCT_SIZE);
    EXPECT_FALSE(log.entries[0].message.empty());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, HeaderVersionOfAnotherMajor) {
    obscura_context_desc desc = make_desc();
    LogCapture log;
    log.attach(&desc);
    desc.header_version = OBSCURA_VERSION + 10000;
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_VERSION_MISMATCH);
    EXPECT_EQ(context, nullptr);
    ASSERT_EQ(log.entries.size(), 1u);
    EXPECT_EQ(log.entries[0].status, OBSCURA_STATUS_VERSION_MISMATCH);
    EXPECT_FALSE(log.entries[0].message.empty());
}

TEST_F(ApiErrors, HeaderNewerThanLibrary) {
    obscura_context_desc desc = make_desc();
    desc.header_version = OBSCURA_VERSION + 100;  // same major, newer minor: its structs may be larger
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_VERSION_MISMATCH);
    EXPECT_EQ(context, nullptr);
}

// header_version is required: 0 is the field left unset (a zeroed desc), not version 0.0.0, and was accepted.
TEST_F(ApiErrors, HeaderVersionLeftUnset) {
    obscura_context_desc desc = make_desc();
    desc.header_version = 0;
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_VERSION_MISMATCH);
    EXPECT_EQ(context, nullptr);
}

// Unknown context flags are refused, as obscura_input's and obscura_settings' unknown flags are (they were ignored).
TEST_F(ApiErrors, UnknownContextFlags) {
    obscura_context_desc desc = make_desc();
    LogCapture log;
    log.attach(&desc);
    desc.flags = OBSCURA_CONTEXT_FLAG_SYNC_TIMING | (1u << 5);
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_EQ(context, nullptr);
    ASSERT_EQ(log.entries.size(), 1u);
    EXPECT_NE(log.entries[0].message.find("0x21"), std::string::npos) << log.entries[0].message;
    desc.flags = OBSCURA_CONTEXT_FLAG_SYNC_TIMING | OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES | OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS;
    ASSERT_EQ(obscura_create_context(&desc, &context), OBSCURA_OK);
    obscura_destroy_context(context);
}

TEST_F(ApiErrors, AllocatorNeedsBothFunctions) {
    obscura_context_desc desc = make_desc();
    desc.allocator.alloc = [](size_t size, void*) { return std::malloc(size); };
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(context, nullptr);
}

TEST_F(ApiErrors, AllocatorFailureIsOutOfMemory) {
    obscura_context_desc desc = make_desc();
    LogCapture log;
    log.attach(&desc);
    desc.allocator.alloc = [](size_t, void*) -> void* { return nullptr; };
    desc.allocator.free = [](void*, void*) {};
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_OUT_OF_MEMORY);
    EXPECT_EQ(context, nullptr);
    ASSERT_EQ(log.entries.size(), 1u);
    EXPECT_EQ(log.entries[0].status, OBSCURA_STATUS_OUT_OF_MEMORY);
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

// ---- GL context problems ---------------------------------------------------------------------------------

TEST_F(ApiErrors, NoGlContextAtCreate) {
    obscura_context_desc desc = make_desc();
    LogCapture log;
    log.attach(&desc);
    shared_gl().release();
    ASSERT_FALSE(shared_gl().is_current());
    obscura_context* context = reinterpret_cast<obscura_context*>(0x10);
    obscura_status status = obscura_create_context(&desc, &context);
    shared_gl().make_current();
    EXPECT_EQ(status, OBSCURA_STATUS_NO_GL_CONTEXT);
    EXPECT_EQ(context, nullptr);
    ASSERT_EQ(log.entries.size(), 1u);
    EXPECT_EQ(log.entries[0].status, OBSCURA_STATUS_NO_GL_CONTEXT);
    EXPECT_FALSE(log.entries[0].message.empty());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, NoGlContextAtRender) {
    shared_gl().release();
    obscura_status status = render();
    std::string message = obscura_get_last_error(ctx());
    shared_gl().make_current();
    EXPECT_EQ(status, OBSCURA_STATUS_WRONG_GL_CONTEXT);
    EXPECT_FALSE(message.empty());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
    expect_target_untouched();
    // Current again: it renders.
    EXPECT_EQ(render(), OBSCURA_OK) << obscura_get_last_error(ctx());
}

TEST_F(ApiErrors, OtherGlContextAtRender) {
    obscura_status status;
    std::string message;
    {
        HeadlessGL other;
        ASSERT_TRUE(other.is_current());
        status = render();
        message = obscura_get_last_error(ctx());
        EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR)) << "error left on the other context";
    }
    shared_gl().make_current();
    EXPECT_EQ(status, OBSCURA_STATUS_WRONG_GL_CONTEXT);
    EXPECT_FALSE(message.empty());
    expect_target_untouched();
}

TEST_F(ApiErrors, Gl33CoreContext) {
    HeadlessGL::Options options;
    options.major = 3;
    options.minor = 3;
    std::unique_ptr<HeadlessGL> old_gl;
    try {
        old_gl = std::make_unique<HeadlessGL>(options);
    } catch (const std::exception& error) {
        shared_gl().make_current();
        GTEST_SKIP() << "no GL 3.3 core context: " << error.what();
    }
    int version = old_gl->gl_major() * 100 + old_gl->gl_minor();
    if (version >= 403) {
        old_gl.reset();
        shared_gl().make_current();
        GTEST_SKIP() << "asked for GL 3.3 core, the driver gave " << version / 100 << "." << version % 100
                     << " (Mesa hands out its highest core version); GlVersionReportedAs33 covers the check";
    }
    obscura_context_desc desc = make_desc();
    LogCapture log;
    log.attach(&desc);
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_GL_VERSION_UNSUPPORTED);
    EXPECT_EQ(context, nullptr);
    EXPECT_EQ(log.entries.size(), 1u);
    old_gl.reset();
    shared_gl().make_current();
}

// get_proc_address wrappers that make the current 4.5 context look different to the SDK.
namespace shim {
using GetStringFn = const GLubyte* (*)(GLenum);
GetStringFn real_get_string = nullptr;
const char* fake_version = "3.3 (Core Profile) Mesa fake";
const char* missing_function = "";

const GLubyte* get_string(GLenum name) {
    if (name == GL_VERSION) return reinterpret_cast<const GLubyte*>(fake_version);
    return real_get_string(name);
}

obscura_gl_function old_version_loader(const char* name) {
    if (std::strcmp(name, "glGetString") == 0) {
        real_get_string = reinterpret_cast<GetStringFn>(HeadlessGL::get_proc_address(name));
        return reinterpret_cast<obscura_gl_function>(&get_string);
    }
    return HeadlessGL::get_proc_address(name);
}

obscura_gl_function missing_function_loader(const char* name) {
    if (std::strcmp(name, missing_function) == 0) return nullptr;
    return HeadlessGL::get_proc_address(name);
}

obscura_gl_function null_loader(const char*) { return nullptr; }
}  // namespace shim

TEST_F(ApiErrors, GlVersionReportedAs33) {
    // The loader and the version check read GL_VERSION through get_proc_address("glGetString"): a
    // context reporting 3.3 must be refused before anything is created.
    obscura_context_desc desc = make_desc();
    LogCapture log;
    log.attach(&desc);
    desc.get_proc_address = &shim::old_version_loader;
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_GL_VERSION_UNSUPPORTED);
    EXPECT_EQ(context, nullptr);
    ASSERT_EQ(log.entries.size(), 1u);
    EXPECT_NE(log.entries[0].message.find("3.3"), std::string::npos) << log.entries[0].message;
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, MissingGlFunction) {
    obscura_context_desc desc = make_desc();
    LogCapture log;
    log.attach(&desc);
    shim::missing_function = "glDispatchCompute";
    desc.get_proc_address = &shim::missing_function_loader;
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_MISSING_GL_FUNCTION);
    EXPECT_EQ(context, nullptr);
    ASSERT_EQ(log.entries.size(), 1u);
    EXPECT_NE(log.entries[0].message.find("glDispatchCompute"), std::string::npos) << log.entries[0].message;
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, LoaderReturnsNothing) {
    obscura_context_desc desc = make_desc();
    desc.get_proc_address = &shim::null_loader;
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_NO_GL_CONTEXT);
    EXPECT_EQ(context, nullptr);
}

TEST_F(ApiErrors, HostErrorPendingBeforeCreate) {
    glEnable(0xFFFF);  // GL_INVALID_ENUM, left pending on purpose
    obscura_context_desc desc = make_desc();
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_HOST_GL_ERROR);
    EXPECT_EQ(context, nullptr);
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(ApiErrors, HostErrorPendingBeforeRender) {
    glEnable(0xFFFF);  // GL_INVALID_ENUM, left pending on purpose
    expect_render_fails(OBSCURA_STATUS_HOST_GL_ERROR, "GL_INVALID_ENUM");
    // The next frame renders normally.
    EXPECT_EQ(render(), OBSCURA_OK) << obscura_get_last_error(ctx());
}

// ---- Every method renders ------------------------------------------------------------------------------
// (OBSCURA_STATUS_METHOD_NOT_AVAILABLE stays in the API for methods a later version adds; since FFAO landed
// every obscura_method renders.)

class ApiEveryMethod : public ApiErrors, public ::testing::WithParamInterface<obscura_method> {};

TEST_P(ApiEveryMethod, RendersAndLeavesNoGlError) {
    settings_.method = GetParam();
    if (GetParam() == OBSCURA_METHOD_REFERENCE) settings_.reference.rays = 4;
    EXPECT_EQ(render(), OBSCURA_OK) << obscura_get_last_error(ctx());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

INSTANTIATE_TEST_SUITE_P(Methods, ApiEveryMethod,
                         ::testing::Values(OBSCURA_METHOD_HBAO, OBSCURA_METHOD_SAO, OBSCURA_METHOD_LSAO,
                                           OBSCURA_METHOD_FFAO, OBSCURA_METHOD_REFERENCE),
                         [](const ::testing::TestParamInfo<obscura_method>& param_info) {
                             return std::string(obscura_method_name(param_info.param));
                         });

}  // namespace
}  // namespace obscura_test
