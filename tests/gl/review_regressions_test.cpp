// Regressions for defects found in review, each reproduced before its fix:
//   - a y-flipped projection (m5 < 0, render-to-texture conventions) gave no AO at all;
//   - an orthographic projection with its near plane behind the eye (glOrtho(..., -8, 12)) gave no AO;
//   - the blit path wrote every draw buffer of a multi-render-target host framebuffer;
//   - MULTIPLY into a float renderbuffer clamped HDR colour to 1 (RGBA8 staging);
//   - obscura_prepare mistook a host GL error for its own allocation failure and swallowed it;
//   - a host buffer bound to GL_QUERY_BUFFER (GL 4.4) made the GPU timer's query reads fail: frames reported GL_ERROR
//     from the second on, and obscura_get_timings stayed empty;
//   - a host program deleted while current could not be restored: the SDK's program stayed bound and the frame
//     reported GL_ERROR;
//   - a depth texture whose GL_TEXTURE_BASE_LEVEL is not 0 was checked at level 0 but read at its base level.
#include <algorithm>
#include <cmath>
#include <string>

#include "analytic_scene.h"
#include "gl_test_support.h"

namespace obscura_test {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 96;

class ReviewRegressions : public GLTest {};

// The floor/wall corner of hbao_test.cpp, traced with `camera`.
struct CornerDepth {
    std::vector<float> depth;
    std::vector<Hit> hits;
};
CornerDepth corner_depth(const Camera& camera) {
    CornerDepth c;
    c.hits = trace(camera, {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                            plane(2, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0))});
    c.depth = depth_values(camera, c.hits);
    return c;
}
glm::dmat4 corner_view() { return look_at(glm::dvec3(0.3, 1.3, 2.8), glm::dvec3(0.0, 0.45, 0.0)); }

double mean(const std::vector<float>& v) {
    double sum = 0.0;
    for (float x : v) sum += x;
    return v.empty() ? 0.0 : sum / double(v.size());
}

// Every method on a y-flipped projection (render-to-texture conventions: m5 < 0) gives the upright image mirrored.
// GTAO once weighed its slices by a signed pixel area there: every slice negative, so no AO at all, and bent normals
// tilted towards the walls.
struct FlipCase {
    const char* name;
    obscura_method method;
    void (*tweak)(obscura_settings*);
};
const FlipCase kFlipCases[] = {
    {"hbao", OBSCURA_METHOD_HBAO, nullptr},
    {"gtao", OBSCURA_METHOD_GTAO, nullptr},
    {"gtao_bitmask", OBSCURA_METHOD_GTAO, [](obscura_settings* s) { s->gtao.thickness_mode = 2; }},
    {"sao", OBSCURA_METHOD_SAO, nullptr},
    {"lsao", OBSCURA_METHOD_LSAO, nullptr},
    {"ffao", OBSCURA_METHOD_FFAO, nullptr},
};

class YFlippedProjection : public GLTest, public ::testing::WithParamInterface<FlipCase> {};

TEST_P(YFlippedProjection, GivesTheMirroredAo) {
    obscura_settings settings;
    ASSERT_EQ(obscura_default_settings(GetParam().method, &settings), OBSCURA_OK);
    if (GetParam().tweak) GetParam().tweak(&settings);
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), corner_view());
    CornerDepth corner = corner_depth(camera);
    HostTexture depth = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, corner.depth);
    obscura_input input = make_input(depth.get(), kWidth, kHeight, camera.matrix());
    std::vector<float> upright = render_to_new_texture(ctx(), input, settings, GL_R32F, 1);
    ASSERT_FALSE(upright.empty());

    // The same image stored upside down, with the projection that renders it so (y row and column negated).
    std::vector<float> flipped_depth(corner.depth.size());
    for (int y = 0; y < kHeight; ++y)
        std::copy_n(&corner.depth[size_t(kHeight - 1 - y) * kWidth], kWidth, &flipped_depth[size_t(y) * kWidth]);
    HostTexture flipped = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, flipped_depth);
    float matrix[16];
    std::copy_n(camera.matrix(), 16, matrix);
    matrix[5] = -matrix[5];
    matrix[9] = -matrix[9];
    matrix[13] = -matrix[13];
    obscura_input flipped_input = make_input(flipped.get(), kWidth, kHeight, matrix);
    std::vector<float> mirrored = render_to_new_texture(ctx(), flipped_input, settings, GL_R32F, 1);
    ASSERT_FALSE(mirrored.empty());

    // Per-pixel noise differs between mirrored pixels, so compare the images' statistics and rows.
    EXPECT_LT(mean(upright), 0.99) << "the corner must be occluded";
    EXPECT_NEAR(mean(mirrored), mean(upright), 0.005);
    double row_error = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        double a = 0.0, b = 0.0;
        for (int x = 0; x < kWidth; ++x) {
            a += upright[size_t(y) * kWidth + x];
            b += mirrored[size_t(kHeight - 1 - y) * kWidth + x];
        }
        row_error = std::max(row_error, std::fabs(a - b) / kWidth);
    }
    EXPECT_LT(row_error, 0.02) << "row means of the mirrored result must match the upright one";
}

std::string flip_case_name(const ::testing::TestParamInfo<FlipCase>& param) { return param.param.name; }
INSTANTIATE_TEST_SUITE_P(Methods, YFlippedProjection, ::testing::ValuesIn(kFlipCases), flip_case_name);

TEST_F(ReviewRegressions, OrthographicNearPlaneBehindEyeKeepsAo) {
    // The same parallel view twice: from the usual eye with near 0.1, and from an eye moved 4 units forward,
    // past the corner, with the near plane 8 units behind it, so the whole corner lies behind the eye plane.
    const glm::dvec3 eye(0.3, 1.3, 2.8), target(0.0, 0.45, 0.0);
    const glm::dvec3 forward = glm::normalize(target - eye);
    Lens in_front;  // near 0.1, far 100
    Lens behind;
    behind.near_plane = -8.0;
    behind.far_plane = 12.0;
    const glm::dvec3 moved_eye = eye + 4.0 * forward;
    std::vector<std::vector<float>> results;
    for (int i = 0; i < 2; ++i) {
        Camera camera(Projection::Orthographic, kWidth, kHeight, i == 0 ? in_front : behind,
                      i == 0 ? look_at(eye, target) : look_at(moved_eye, moved_eye + forward));
        CornerDepth corner = corner_depth(camera);
        HostTexture depth = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, corner.depth);
        obscura_input input = make_input(depth.get(), kWidth, kHeight, camera.matrix());
        results.push_back(render_to_new_texture(ctx(), input, make_settings(1.0f), GL_R32F, 1));
        ASSERT_FALSE(results.back().empty());
    }
    EXPECT_LT(mean(results[0]), 0.99);
    EXPECT_NEAR(mean(results[1]), mean(results[0]), 0.002) << "moving an orthographic eye must not change AO";
}

// A framebuffer with two colour renderbuffers, both drawn to.
struct TwoTargetFramebuffer {
    HostRenderbuffer colour0, colour1;
    HostFramebuffer framebuffer;
};
TwoTargetFramebuffer make_two_target_framebuffer(GLenum format) {
    TwoTargetFramebuffer t;
    t.colour0 = HostRenderbuffer::create();
    t.colour1 = HostRenderbuffer::create();
    for (GLuint rb : {t.colour0.get(), t.colour1.get()}) {
        glBindRenderbuffer(GL_RENDERBUFFER, rb);
        glRenderbufferStorage(GL_RENDERBUFFER, format, kWidth, kHeight);
    }
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    t.framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.colour0.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, t.colour1.get());
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, buffers);
    const float c0[] = {4.0f, 2.0f, 0.5f, 1.0f};
    const float c1[] = {1.0f, 0.0f, 0.0f, 1.0f};
    glClearBufferfv(GL_COLOR, 0, c0);
    glClearBufferfv(GL_COLOR, 1, c1);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return t;
}

std::vector<float> read_attachment(GLuint framebuffer, GLenum attachment) {
    std::vector<float> pixels(size_t(kWidth) * kHeight * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadBuffer(attachment);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, pixels.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return pixels;
}

obscura_input corner_input(HostTexture* depth_out) {
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), corner_view());
    CornerDepth corner = corner_depth(camera);
    *depth_out = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, corner.depth);
    return make_input(depth_out->get(), kWidth, kHeight, camera.matrix());
}

TEST_F(ReviewRegressions, BlitWritesOnlyColourAttachmentZeroAndKeepsHdrWhenMultiplying) {
    HostTexture depth;
    obscura_input input = corner_input(&depth);
    TwoTargetFramebuffer target = make_two_target_framebuffer(GL_RGBA16F);
    obscura_output output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    output.blend = OBSCURA_BLEND_MULTIPLY;
    obscura_settings settings = make_settings(1.0f);
    ASSERT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());

    std::vector<float> visibility = render_to_new_texture(ctx(), input, settings, GL_R32F, 1);
    std::vector<float> c0 = read_attachment(target.framebuffer.get(), GL_COLOR_ATTACHMENT0);
    std::vector<float> c1 = read_attachment(target.framebuffer.get(), GL_COLOR_ATTACHMENT1);
    double worst_hdr = 0.0, worst_other = 0.0;
    for (size_t i = 0; i < visibility.size(); ++i) {
        // RGBA16F staging: the product keeps values above 1 (half precision: 2^-10 relative).
        worst_hdr = std::max(worst_hdr, std::fabs(c0[4 * i] - 4.0 * visibility[i]) / 4.0);
        worst_other = std::max({worst_other, std::fabs(c1[4 * i] - 1.0), std::fabs(double(c1[4 * i + 1])),
                                std::fabs(double(c1[4 * i + 2]))});
    }
    EXPECT_LT(worst_hdr, 4e-3) << "attachment 0 must hold 4 * visibility, not a clamped 1";
    EXPECT_EQ(worst_other, 0.0) << "attachment 1 must be untouched";
}

TEST_F(ReviewRegressions, PrepareReportsPendingHostErrorInsteadOfSwallowingIt) {
    glEnable(0xDEAD);  // GL_INVALID_ENUM, left pending by the "host"
    obscura_settings settings = make_settings(1.0f);
    EXPECT_EQ(obscura_prepare(ctx(), 64, 64, &settings), OBSCURA_STATUS_HOST_GL_ERROR);
    EXPECT_NE(std::string(obscura_get_last_error(ctx())).find("GL_INVALID_ENUM"), std::string::npos)
        << obscura_get_last_error(ctx());
    EXPECT_EQ(obscura_prepare(ctx(), 64, 64, &settings), OBSCURA_OK) << obscura_get_last_error(ctx());
}

// GL 4.4's GL_QUERY_BUFFER, not in the 4.3 loader the tests use.
constexpr GLenum kQueryBuffer = 0x9192, kQueryBufferBinding = 0x9193;

// With a buffer bound to GL_QUERY_BUFFER, glGetQueryObject* writes into it at the offset its pointer names. The GPU
// timer read its timestamps that way: GL_INVALID_OPERATION on the stack address, so every frame from the second
// returned GL_ERROR (and dropped the temporal history), and the timings never completed. The timer now sets the
// host's binding aside while it reads, and puts it back.
TEST_F(ReviewRegressions, HostQueryBufferBindingLeavesFramesAndTimingsAlone) {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 44) GTEST_SKIP() << "GL_QUERY_BUFFER needs GL 4.4";
    HostTexture depth;
    obscura_input input = corner_input(&depth);
    HostTexture target = make_texture(GL_RGBA8, kWidth, kHeight);
    obscura_output output = make_output(target.get());
    obscura_settings settings = make_settings(1.0f);
    HostBuffer query_buffer = HostBuffer::create();
    glBindBuffer(kQueryBuffer, query_buffer.get());
    glBufferData(kQueryBuffer, 256, nullptr, GL_DYNAMIC_READ);
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    obscura_timing timings[32];
    uint32_t count = 0;
    uint64_t frame = 0;
    for (int f = 0; f < 8 && count == 0; ++f) {
        ASSERT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_OK)
            << "frame " << f << ": " << obscura_get_last_error(ctx());
        glFinish();
        ASSERT_EQ(obscura_get_timings(ctx(), timings, 32, &count, &frame), OBSCURA_OK) << obscura_get_last_error(ctx());
    }
    EXPECT_GT(count, 0u) << "the timings never completed";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    GLint bound = 0;
    glGetIntegerv(kQueryBufferBinding, &bound);
    EXPECT_EQ(GLuint(bound), query_buffer.get()) << "the host's query buffer binding must be left as it was";
    glBindBuffer(kQueryBuffer, 0);
}

// glDeleteProgram on the current program only flags it: it lives while bound. The SDK binds its own programs, so GL
// deletes the host's during the call, and restoring it raised GL_INVALID_VALUE: the frame returned GL_ERROR and the
// SDK's compute program stayed current. Now the call succeeds and leaves no program bound (the host's is gone).
TEST_F(ReviewRegressions, HostProgramDeletedWhileCurrentLeavesNoSdkProgramBound) {
    HostTexture depth;
    obscura_input input = corner_input(&depth);
    HostTexture target = make_texture(GL_RGBA8, kWidth, kHeight);
    obscura_output output = make_output(target.get());
    obscura_settings settings = make_settings(1.0f);
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    const char* source = "#version 430 core\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    ASSERT_EQ(linked, GL_TRUE);
    glUseProgram(program);
    glDeleteProgram(program);  // flagged: alive while current
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    GLint current = -1;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    EXPECT_EQ(current, 0) << "the SDK's program was left bound";
}

// The passes read a GL_TEXTURE_2D at its base level (texelFetch's level 0): its size is what must match the depth size.
// A host's depth pyramid with the base level moved to level 1 (the scene's depth) renders as the plain texture does,
// and one whose base level is smaller than the depth size is refused. Until 2026-12-06 level 0 was checked: the first
// was refused, and the second rendered level 1 (and zeros outside it) with status OK (found by a read-only review).
TEST_F(ReviewRegressions, DepthTextureIsReadAndCheckedAtItsBaseLevel) {
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), corner_view());
    const CornerDepth corner = corner_depth(camera);
    HostTexture plain = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, corner.depth);
    const std::vector<float> expected =
        render_to_new_texture(ctx(), make_input(plain.get(), kWidth, kHeight, camera.matrix()), make_settings(1.0f),
                              GL_R32F, 1);
    ASSERT_FALSE(expected.empty());

    HostTexture pyramid = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, pyramid.get());
    glTexStorage2D(GL_TEXTURE_2D, 2, GL_DEPTH_COMPONENT32F, 2 * kWidth, 2 * kHeight);
    const std::vector<float> level0(size_t(4) * kWidth * kHeight, 0.25f);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 2 * kWidth, 2 * kHeight, GL_DEPTH_COMPONENT, GL_FLOAT, level0.data());
    glTexSubImage2D(GL_TEXTURE_2D, 1, 0, 0, kWidth, kHeight, GL_DEPTH_COMPONENT, GL_FLOAT, corner.depth.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 1);
    glBindTexture(GL_TEXTURE_2D, 0);
    const std::vector<float> from_pyramid =
        render_to_new_texture(ctx(), make_input(pyramid.get(), kWidth, kHeight, camera.matrix()), make_settings(1.0f),
                              GL_R32F, 1);
    ASSERT_EQ(from_pyramid.size(), expected.size()) << obscura_get_last_error(ctx());
    for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(from_pyramid[i], expected[i]) << i;

    HostTexture moved = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, moved.get());
    glTexStorage2D(GL_TEXTURE_2D, 2, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_DEPTH_COMPONENT, GL_FLOAT, corner.depth.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 1);
    glBindTexture(GL_TEXTURE_2D, 0);
    HostTexture target = make_texture(GL_R32F, kWidth, kHeight);
    obscura_input input = make_input(moved.get(), kWidth, kHeight, camera.matrix());
    obscura_settings settings = make_settings(1.0f);
    obscura_output output = make_output(target.get());
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_TEXTURE);
    EXPECT_NE(std::string(obscura_get_last_error(ctx())).find("base level 1"), std::string::npos)
        << obscura_get_last_error(ctx());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// The outputs are written at level 0 through image units, which GL leaves invalid below a texture's base level (the
// stores are dropped): an output or bent-normal texture whose base level is not 0 is refused, and a framebuffer whose
// colour attachment is such a texture's level 0 is reached by the blit instead. Until 2026-12-06 all three rendered
// nothing with status OK (found by a read-only review).
TEST_F(ReviewRegressions, OutputTexturesWithAMovedBaseLevel) {
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), corner_view());
    const CornerDepth corner = corner_depth(camera);
    HostTexture depth = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, corner.depth);
    obscura_input input = make_input(depth.get(), kWidth, kHeight, camera.matrix());
    obscura_settings settings = make_settings(1.0f);
    const std::vector<float> expected = render_to_new_texture(ctx(), input, settings, GL_RGBA8, 1);
    ASSERT_FALSE(expected.empty());
    const auto moved_texture = [](GLenum format) {
        HostTexture texture = HostTexture::create();
        glBindTexture(GL_TEXTURE_2D, texture.get());
        glTexStorage2D(GL_TEXTURE_2D, 2, format, kWidth, kHeight);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 1);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glBindTexture(GL_TEXTURE_2D, 0);
        return texture;
    };
    HostTexture moved = moved_texture(GL_RGBA8);
    obscura_output output = make_output(moved.get());
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_TEXTURE);
    EXPECT_NE(std::string(obscura_get_last_error(ctx())).find("GL_TEXTURE_BASE_LEVEL 1"), std::string::npos)
        << obscura_get_last_error(ctx());

    obscura_settings gtao;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_GTAO, &gtao), OBSCURA_OK);
    HostTexture target = make_texture(GL_R32F, kWidth, kHeight);
    HostTexture bent = moved_texture(GL_RGBA16F);
    output = make_output(target.get());
    output.bent_normal_texture = bent.get();
    EXPECT_EQ(obscura_render(ctx(), &input, &gtao, &output), OBSCURA_STATUS_INVALID_TEXTURE);
    EXPECT_NE(std::string(obscura_get_last_error(ctx())).find("output.bent_normal_texture"), std::string::npos)
        << obscura_get_last_error(ctx());

    // Level 0 of the moved texture attached to a framebuffer: written, through the blit.
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, moved.get(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    output = make_output(0);
    output.framebuffer = framebuffer.get();
    ASSERT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<uint8_t> written(size_t(kWidth) * kHeight * 4);
    glBindTexture(GL_TEXTURE_2D, moved.get());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, written.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D, 0);
    int off = 0;
    for (size_t i = 0; i < expected.size(); ++i) off += std::abs(int(written[4 * i]) - int(std::lround(expected[i] * 255.0))) > 1;
    EXPECT_EQ(off, 0) << "the attachment's level 0 must hold the AO";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// Validation learns host textures' targets by asking GL 4.5's glGetTextureParameteriv where the context has it: no GL
// error then reaches a host's debug output. Until 2026-12-06 it always probed by binding, and a multisampled depth
// texture, or a framebuffer whose colour attachment is a cube face or an array layer, raised GL_INVALID_OPERATION
// every frame (consumed, but a host breaking on debug errors stopped there; found by a read-only review). Without the
// query (a loader that has none, as on a 4.3 context) the probes still find the targets.
struct DebugErrors {
    static int count;
    static void GLAD_API_PTR callback(GLenum, GLenum type, GLuint, GLenum, GLsizei, const GLchar*, const void*) {
        if (type == GL_DEBUG_TYPE_ERROR) ++count;
    }
};
int DebugErrors::count = 0;

obscura_gl_function without_texture_parameter_query(void*, const char* name) {
    if (std::string(name) == "glGetTextureParameteriv") return nullptr;
    return obscura::samples::HeadlessGL::get_proc_address(name);
}

TEST_F(ReviewRegressions, ValidationRaisesNoGlErrorWhereGlCanBeAsked) {
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), corner_view());
    const CornerDepth corner = corner_depth(camera);
    HostTexture depth = make_multisample_depth_texture(kWidth, kHeight, 4, corner.depth, 0.5f);
    obscura_input input = make_input(depth.get(), kWidth, kHeight, camera.matrix());
    HostTexture cube = HostTexture::create();
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube.get());
    glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_RGBA8, kWidth, kWidth);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_CUBE_MAP_POSITIVE_Z, cube.get(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    obscura_settings settings = make_settings(1.0f);
    obscura_output output = make_output(0);
    output.framebuffer = framebuffer.get();

    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(&DebugErrors::callback, nullptr);
    DebugErrors::count = 0;
    glBindTexture(GL_TEXTURE_2D, depth.get());  // a multisampled texture to GL_TEXTURE_2D: the callback must see it
    const int host_error = DebugErrors::count;
    (void)glGetError();
    DebugErrors::count = 0;
    const obscura_status status = obscura_render(ctx(), &input, &settings, &output);
    const int with_query = DebugErrors::count;

    obscura_context_desc desc = make_desc();
    desc.get_proc_address = nullptr;
    desc.get_proc_address_with_user_data = &without_texture_parameter_query;
    obscura_context* probing = nullptr;
    ASSERT_EQ(obscura_create_context(&desc, &probing), OBSCURA_OK);
    DebugErrors::count = 0;
    const obscura_status probed = obscura_render(probing, &input, &settings, &output);
    const int with_probes = DebugErrors::count;
    obscura_destroy_context(probing);
    glDebugMessageCallback(nullptr, nullptr);
    glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDisable(GL_DEBUG_OUTPUT);

    ASSERT_GT(host_error, 0) << "this context's debug output does not report API errors";
    EXPECT_EQ(status, OBSCURA_OK) << obscura_get_last_error(ctx());
    EXPECT_EQ(with_query, 0) << "GL errors raised by validation with glGetTextureParameteriv";
    EXPECT_EQ(probed, OBSCURA_OK);
    EXPECT_GT(with_probes, 0) << "the probing binds (no query) raise errors: the test's premise";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace
}  // namespace obscura_test
