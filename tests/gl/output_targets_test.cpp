// Output targets: every writable texture format, blend multiply, framebuffer objects with texture and
// renderbuffer attachments (the blit path), placement inside a larger target.
// The reference is always an R32F overwrite render of the same frame in the same context.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>

#include "analytic_scene.h"
#include "gl_test_support.h"

namespace obscura_test {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 96;

// A concave corner (floor + wall): visibility spans roughly 0.55 .. 1.
struct Frame {
    HostTexture depth;
    obscura_input input;
};

Frame corner_frame() {
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(),
                  look_at(glm::dvec3(0.3, 1.3, 2.8), glm::dvec3(0.0, 0.45, 0.0)));
    std::vector<Hit> hits = trace(camera, {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                                           plane(2, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0))});
    Frame frame;
    frame.depth = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, depth_values(camera, hits));
    frame.input = make_input(frame.depth.get(), kWidth, kHeight, camera.matrix(), camera.clip_depth());
    return frame;
}

Frame facing_plane_frame() {
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), glm::dmat4(1.0));
    std::vector<Hit> hits = trace(camera, {plane(1, glm::dvec3(0.0, 0.0, -5.0), glm::dvec3(0.0, 0.0, 1.0))});
    Frame frame;
    frame.depth = make_depth_texture(GL_DEPTH_COMPONENT32F, kWidth, kHeight, depth_values(camera, hits));
    frame.input = make_input(frame.depth.get(), kWidth, kHeight, camera.matrix(), camera.clip_depth());
    return frame;
}

// 8-bit unorm value GL stores for v (round to nearest).
int unorm8(double v) { return int(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

class OutputTargets : public GLTest {
protected:
    std::vector<float> reference(const obscura_input& input, const obscura_settings& settings) {
        return render_to_new_texture(ctx(), input, settings, GL_R32F, 1);
    }
};

// ---- Texture formats ------------------------------------------------------------------------------------

struct FormatCase {
    GLenum format;
    const char* name;
    double tolerance;  // storage precision of the red channel near [0.5, 1]
};

// Half floats: one ulp below 1, since drivers may truncate (llvmpipe does) what the last pass writes there.
const double kHalfUlp = std::ldexp(1.0, -11);

class OutputFormats : public OutputTargets, public ::testing::WithParamInterface<FormatCase> {};

TEST_P(OutputFormats, RedChannelHoldsVisibility) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> expected = reference(frame.input, settings);
    ASSERT_FALSE(expected.empty());
    std::vector<float> got = render_to_new_texture(ctx(), frame.input, settings, GetParam().format, 4);
    ASSERT_EQ(got.size(), expected.size() * 4);
    double worst = 0.0;
    for (size_t i = 0; i < expected.size(); ++i) worst = std::max(worst, std::fabs(double(got[4 * i]) - expected[i]));
    EXPECT_LE(worst, GetParam().tolerance) << GetParam().name;
    // The reference itself spans occluded and open texels (the comparison is not vacuous).
    auto [lo, hi] = std::minmax_element(expected.begin(), expected.end());
    EXPECT_LT(*lo, 0.8f);
    EXPECT_GT(*hi, 0.99f);
}

INSTANTIATE_TEST_SUITE_P(
    Formats, OutputFormats,
    ::testing::Values(FormatCase{GL_R8, "R8", 0.5 / 255 + 1e-6}, FormatCase{GL_R16, "R16", 0.5 / 65535 + 1e-6},
                      // R32F is the reference's own format: a determinism check, and the layout of a 4-channel read.
                      FormatCase{GL_R16F, "R16F", kHalfUlp}, FormatCase{GL_R32F, "R32F", 0.0},
                      FormatCase{GL_RG8, "RG8", 0.5 / 255 + 1e-6}, FormatCase{GL_RG16, "RG16", 0.5 / 65535 + 1e-6},
                      FormatCase{GL_RG16F, "RG16F", kHalfUlp}, FormatCase{GL_RG32F, "RG32F", 0.0},
                      FormatCase{GL_RGBA8, "RGBA8", 0.5 / 255 + 1e-6},
                      FormatCase{GL_RGBA16, "RGBA16", 0.5 / 65535 + 1e-6}, FormatCase{GL_RGBA16F, "RGBA16F", kHalfUlp},
                      FormatCase{GL_RGBA32F, "RGBA32F", 0.0}, FormatCase{GL_RGB10_A2, "RGB10_A2", 0.5 / 1023 + 1e-6},
                      // 6-bit mantissa: half an ulp below 1 is 2^-8.
                      FormatCase{GL_R11F_G11F_B10F, "R11F_G11F_B10F", std::ldexp(1.0, -7)}),
    [](const ::testing::TestParamInfo<FormatCase>& param_info) { return std::string(param_info.param.name); });

// One context, every target format with every blend mode, with and without a debug view that reads the depth or
// normals: each combination is its own composite program, and the context must hold all of them (it held 32 of
// the 56, and the 33rd failed with INTERNAL_ERROR).
TEST_F(OutputTargets, OneContextWritesEveryFormatBlendAndDebugView) {
    Frame frame = facing_plane_frame();
    obscura_settings settings = make_settings(1.0f);
    const GLenum formats[] = {GL_R8, GL_R16, GL_R16F, GL_R32F, GL_RG8, GL_RG16, GL_RG16F, GL_RG32F,
                              GL_RGBA8, GL_RGBA16, GL_RGBA16F, GL_RGBA32F, GL_RGB10_A2, GL_R11F_G11F_B10F};
    int checked = 0;
    for (GLenum format : formats) {
        HostTexture target = make_texture(format, kWidth, kHeight);
        for (obscura_blend_mode blend : {OBSCURA_BLEND_OVERWRITE, OBSCURA_BLEND_MULTIPLY}) {
            for (obscura_debug_view view : {OBSCURA_DEBUG_NONE, OBSCURA_DEBUG_LINEAR_DEPTH}) {
                obscura_output output = make_output(target.get(), view);
                output.blend = blend;
                EXPECT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK)
                    << "format 0x" << std::hex << format << std::dec << ", blend " << blend << ", debug view " << view
                    << ": " << obscura_get_last_error(ctx());
                if (blend == OBSCURA_BLEND_OVERWRITE && view == OBSCURA_DEBUG_NONE) {
                    // The first write into the new (zeroed) texture: the open plane's visibility, about 1, in red
                    // everywhere (HBAO leaves an R16F step below 1 on planes).
                    const std::vector<float> red = read_texture(target.get(), kWidth, kHeight, 1);
                    const float lowest = *std::min_element(red.begin(), red.end());
                    EXPECT_GT(lowest, 0.99f) << "format 0x" << std::hex << format << std::dec << ": not written";
                    ++checked;
                }
            }
        }
    }
    EXPECT_EQ(checked, int(sizeof formats / sizeof formats[0]));
}

TEST_F(OutputTargets, OverwriteRgba8WritesGreyAndOpaqueAlpha) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> expected = reference(frame.input, settings);
    HostTexture target = make_texture(GL_RGBA8, kWidth, kHeight);
    fill_texture(target.get(), kWidth, kHeight, 0.1f, 0.2f, 0.3f, 0.4f);
    obscura_output output = make_output(target.get());
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<uint8_t> bytes = read_texture_rgba8(target.get(), kWidth, kHeight);
    int bad = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        int v = unorm8(expected[i]);
        if (std::abs(bytes[4 * i] - v) > 1 || bytes[4 * i + 1] != bytes[4 * i] || bytes[4 * i + 2] != bytes[4 * i] ||
            bytes[4 * i + 3] != 255)
            ++bad;
    }
    EXPECT_EQ(bad, 0);
}

// ---- Blend multiply -------------------------------------------------------------------------------------

TEST_F(OutputTargets, MultiplyKeepsHalfFilledTargetWhereUnoccluded) {
    // The corner: open floor and wall (visibility above 0.995) and the crease, so that a multiply that wrote nothing
    // fails too (MultiplyIsTargetTimesVisibility measures the product itself).
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    const std::vector<float> visibility = reference(frame.input, settings);
    ASSERT_FALSE(visibility.empty());
    HostTexture target = make_texture(GL_RGBA8, kWidth, kHeight);
    fill_texture(target.get(), kWidth, kHeight, 0.5f, 0.5f, 0.5f, 0.8f);
    obscura_output output = make_output(target.get());
    output.blend = OBSCURA_BLEND_MULTIPLY;
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<uint8_t> bytes = read_texture_rgba8(target.get(), kWidth, kHeight);
    // 0.5 is stored as 128; times visibility in [0.995, 1] is 127.4 .. 128: 127 or 128. Below 0.9 it is under 116.
    // Alpha (204) is kept everywhere.
    int bad = 0, open = 0, darkened = 0;
    for (size_t i = 0; i < visibility.size(); ++i) {
        const uint8_t* texel = &bytes[4 * i];
        if (visibility[i] > 0.995f) {
            ++open;
            for (int c = 0; c < 3; ++c) bad += texel[c] < 127 || texel[c] > 128;
        } else if (visibility[i] < 0.9f) {
            ++darkened;
            for (int c = 0; c < 3; ++c) bad += texel[c] >= 116;
        }
        bad += texel[3] != 204;
    }
    EXPECT_EQ(bad, 0);
    EXPECT_GT(open, 100);
    EXPECT_GT(darkened, 20);
}

TEST_F(OutputTargets, MultiplyIsTargetTimesVisibility) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> v = reference(frame.input, settings);
    ASSERT_FALSE(v.empty());
    HostTexture target = make_texture(GL_RGBA32F, kWidth, kHeight);
    const float fill[4] = {0.5f, 0.25f, 1.0f, 0.7f};
    fill_texture(target.get(), kWidth, kHeight, fill[0], fill[1], fill[2], fill[3]);
    obscura_output output = make_output(target.get());
    output.blend = OBSCURA_BLEND_MULTIPLY;
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<float> got = read_texture(target.get(), kWidth, kHeight, 4);
    double worst = 0.0;
    for (size_t i = 0; i < v.size(); ++i) {
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(double(got[4 * i + c]) - double(fill[c]) * v[i]));
        EXPECT_EQ(got[4 * i + 3], fill[3]) << "alpha changed at " << i;
        if (HasFailure()) break;
    }
    EXPECT_LT(worst, 1e-6);
}

TEST_F(OutputTargets, MultiplyTwiceSquares) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> v = reference(frame.input, settings);
    HostTexture target = make_texture(GL_R32F, kWidth, kHeight);
    fill_texture(target.get(), kWidth, kHeight, 1.0f, 0, 0, 1);
    obscura_output output = make_output(target.get());
    output.blend = OBSCURA_BLEND_MULTIPLY;
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK);
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK);
    std::vector<float> got = read_texture(target.get(), kWidth, kHeight, 1);
    double worst = 0.0;
    for (size_t i = 0; i < v.size(); ++i) worst = std::max(worst, std::fabs(double(got[i]) - double(v[i]) * v[i]));
    EXPECT_LT(worst, 1e-6);
}

// ---- Framebuffer objects -------------------------------------------------------------------------------

TEST_F(OutputTargets, FramebufferTextureAttachment) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> expected = reference(frame.input, settings);
    HostTexture texture = make_texture(GL_R32F, kWidth, kHeight);
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.get(), 0);
    ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    obscura_output output = make_output(0);
    output.framebuffer = framebuffer.get();
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<float> got = read_texture(texture.get(), kWidth, kHeight, 1);
    ASSERT_EQ(got.size(), expected.size());
    EXPECT_EQ(std::memcmp(got.data(), expected.data(), got.size() * sizeof(float)), 0)
        << "a 2D level-0 attachment is written directly: bit-identical to the texture target";
}

// Reads an RGBA8 colour attachment 0 of `framebuffer` with glReadPixels.
std::vector<uint8_t> read_framebuffer_rgba8(GLuint framebuffer, int width, int height) {
    std::vector<uint8_t> bytes(size_t(width) * height * 4);
    GLint previous = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(previous));
    return bytes;
}

void clear_framebuffer(GLuint framebuffer, float r, float g, float b, float a) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    const GLfloat colour[4] = {r, g, b, a};
    glClearBufferfv(GL_COLOR, 0, colour);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
}

TEST_F(OutputTargets, FramebufferRenderbufferBlit) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    // The same result composed into an RGBA8 texture directly.
    HostTexture direct = make_texture(GL_RGBA8, kWidth, kHeight);
    obscura_output direct_output = make_output(direct.get());
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &direct_output), OBSCURA_OK);
    std::vector<uint8_t> expected = read_texture_rgba8(direct.get(), kWidth, kHeight);

    RenderbufferTarget target = make_renderbuffer_target(GL_RGBA8, kWidth, kHeight);
    clear_framebuffer(target.framebuffer.get(), 0.2f, 0.4f, 0.6f, 0.8f);
    obscura_output output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<uint8_t> got = read_framebuffer_rgba8(target.framebuffer.get(), kWidth, kHeight);
    EXPECT_EQ(got, expected) << "the blit path must give the RGBA8 result of the direct path";
}

// The framebuffers the SDK creates in the host's context (their names are the context's, so a scan finds them)
// must hold no image the frame no longer needs: after a blit, not the host's renderbuffer (a host that deletes it,
// on a window resize, would not get its memory back), and once the host renders into a texture again, not the
// staging texture either (a texture deleted while attached to an unbound framebuffer lives on).
std::vector<GLuint> framebuffers_with_colour(std::initializer_list<GLuint> except) {
    std::vector<GLuint> found;
    for (GLuint name = 1; name < 512; ++name) {
        if (std::find(except.begin(), except.end(), name) != except.end() || !glIsFramebuffer(name)) continue;
        glBindFramebuffer(GL_FRAMEBUFFER, name);
        GLint type = GL_NONE;
        glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                              GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
        if (type != GL_NONE) found.push_back(name);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return found;
}

TEST_F(OutputTargets, TheSdksFramebuffersKeepNoImageAfterTheFrame) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    RenderbufferTarget target = make_renderbuffer_target(GL_RGBA8, kWidth, kHeight);
    obscura_output output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    for (GLuint name : framebuffers_with_colour({target.framebuffer.get()})) {
        glBindFramebuffer(GL_FRAMEBUFFER, name);
        GLint type = GL_NONE, object = 0;
        glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                              GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
        glGetFramebufferAttachmentParameteriv(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                              GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &object);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        EXPECT_FALSE(type == GL_RENDERBUFFER && GLuint(object) == target.renderbuffer.get())
            << "framebuffer " << name << " still holds the host's renderbuffer";
    }
    EXPECT_EQ(framebuffers_with_colour({target.framebuffer.get()}).size(), 1u) << "the staging framebuffer";

    HostTexture texture = make_texture(GL_RGBA8, kWidth, kHeight);
    obscura_output texture_output = make_output(texture.get());
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &texture_output), OBSCURA_OK);
    EXPECT_TRUE(framebuffers_with_colour({target.framebuffer.get()}).empty());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(OutputTargets, FramebufferRenderbufferOffsetWritesOnlyTheRect) {
    Frame frame = corner_frame();
    frame.input.output_rect = obscura_rect{10, 6, 100, 60};
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> expected = reference(frame.input, settings);
    const int fw = 200, fh = 120, ox = 37, oy = 21;
    RenderbufferTarget target = make_renderbuffer_target(GL_RGBA8, fw, fh);
    clear_framebuffer(target.framebuffer.get(), 0.2f, 0.4f, 0.6f, 0.8f);
    obscura_output output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    output.x = ox;
    output.y = oy;
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<uint8_t> got = read_framebuffer_rgba8(target.framebuffer.get(), fw, fh);
    int outside_changed = 0, inside_wrong = 0;
    for (int y = 0; y < fh; ++y)
        for (int x = 0; x < fw; ++x) {
            const uint8_t* p = &got[(size_t(y) * fw + x) * 4];
            bool inside = x >= ox && x < ox + 100 && y >= oy && y < oy + 60;
            if (!inside) {
                outside_changed += p[0] != 51 || p[1] != 102 || p[2] != 153 || p[3] != 204;
            } else {
                int v = unorm8(expected[size_t(y - oy) * 100 + (x - ox)]);
                inside_wrong += std::abs(p[0] - v) > 1 || p[3] != 255;
            }
        }
    EXPECT_EQ(outside_changed, 0);
    EXPECT_EQ(inside_wrong, 0);
}

TEST_F(OutputTargets, FramebufferRenderbufferMultiply) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    std::vector<float> v = reference(frame.input, settings);
    RenderbufferTarget target = make_renderbuffer_target(GL_RGBA8, kWidth, kHeight);
    clear_framebuffer(target.framebuffer.get(), 0.5f, 1.0f, 0.25f, 0.8f);
    obscura_output output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    output.blend = OBSCURA_BLEND_MULTIPLY;
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<uint8_t> got = read_framebuffer_rgba8(target.framebuffer.get(), kWidth, kHeight);
    const double fill[3] = {128.0 / 255, 1.0, 64.0 / 255};  // the cleared colour as stored
    int bad = 0;
    for (size_t i = 0; i < v.size(); ++i) {
        for (int c = 0; c < 3; ++c) bad += std::abs(got[4 * i + c] - unorm8(fill[c] * v[i])) > 1;
        bad += got[4 * i + 3] != 204;
    }
    EXPECT_EQ(bad, 0);
}

TEST_F(OutputTargets, FramebufferMipLevelAttachmentUsesBlit) {
    // Level 1 of a mipmapped RGBA8 texture: not a level-0 image, so the SDK must blit into it.
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    HostTexture direct = make_texture(GL_RGBA8, kWidth, kHeight);
    obscura_output direct_output = make_output(direct.get());
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &direct_output), OBSCURA_OK);
    std::vector<uint8_t> expected = read_texture_rgba8(direct.get(), kWidth, kHeight);

    HostTexture mipmapped = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, mipmapped.get());
    glTexStorage2D(GL_TEXTURE_2D, 2, GL_RGBA8, kWidth * 2, kHeight * 2);
    glBindTexture(GL_TEXTURE_2D, 0);
    fill_texture(mipmapped.get(), kWidth * 2, kHeight * 2, 0.0f, 0.0f, 0.0f, 0.0f);  // level 0 (storage is undefined)
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, mipmapped.get(), 1);
    ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    obscura_output output = make_output(0);
    output.framebuffer = framebuffer.get();
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    std::vector<uint8_t> got = read_framebuffer_rgba8(framebuffer.get(), kWidth, kHeight);
    EXPECT_EQ(got, expected);
    // Level 0 was not touched by a blit that went to the wrong level: it still holds the zeros written above.
    std::vector<uint8_t> level0(size_t(kWidth) * 2 * kHeight * 2 * 4, 1);
    glBindTexture(GL_TEXTURE_2D, mipmapped.get());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, level0.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D, 0);
    EXPECT_TRUE(std::all_of(level0.begin(), level0.end(), [](uint8_t b) { return b == 0; }));
}

// ---- One image of an array, 3D, cube or cube-array texture --------------------------------------------

struct LayerCase {
    GLenum target;
    int images;        // layers, slices or faces of level 0 (a cube map array: 6 per cube)
    int image;         // the one attached
    const char* name;
};

class OutputLayers : public OutputTargets, public ::testing::WithParamInterface<LayerCase> {};

GLenum cube_face(int index) { return GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + index); }

// Every image of level 0, one after another, RGBA8 of kSide x kSide each.
std::vector<uint8_t> read_all_images(GLenum target, GLuint texture, int side, int images) {
    std::vector<uint8_t> bytes(size_t(side) * side * 4 * images, 1);
    glBindTexture(target, texture);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (target == GL_TEXTURE_CUBE_MAP) {
        for (int face = 0; face < images; ++face)
            glGetTexImage(cube_face(face), 0, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data() + size_t(side) * side * 4 * face);
    } else {
        glGetTexImage(target, 0, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glBindTexture(target, 0);
    return bytes;
}

TEST_P(OutputLayers, BlitWritesTheAttachedImageOnly) {
    // The host attached one image of a texture that has several; the blit must reach that image, not
    // layer 0 (what glFramebufferTexture's layered attachment of the whole level would write).
    const LayerCase& param = GetParam();
    constexpr int kSide = kWidth;  // square: cube faces must be
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    HostTexture direct = make_texture(GL_RGBA8, kWidth, kHeight);
    obscura_output direct_output = make_output(direct.get());
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &direct_output), OBSCURA_OK);
    const std::vector<uint8_t> expected = read_texture_rgba8(direct.get(), kWidth, kHeight);

    HostTexture texture = HostTexture::create();
    glBindTexture(param.target, texture.get());
    const std::vector<uint8_t> zeros(size_t(kSide) * kSide * 4 * param.images, 0);
    if (param.target == GL_TEXTURE_CUBE_MAP) {
        glTexStorage2D(param.target, 1, GL_RGBA8, kSide, kSide);
        for (int face = 0; face < param.images; ++face)
            glTexSubImage2D(cube_face(face), 0, 0, 0, kSide, kSide, GL_RGBA, GL_UNSIGNED_BYTE, zeros.data());
    } else {
        glTexStorage3D(param.target, 1, GL_RGBA8, kSide, kSide, param.images);
        glTexSubImage3D(param.target, 0, 0, 0, 0, kSide, kSide, param.images, GL_RGBA, GL_UNSIGNED_BYTE, zeros.data());
    }
    glBindTexture(param.target, 0);
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    if (param.target == GL_TEXTURE_CUBE_MAP) {
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, cube_face(param.image), texture.get(), 0);
    } else {
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, texture.get(), 0, param.image);
    }
    // Unusual draw and read buffers of the host's framebuffer, which must survive the blit.
    const GLenum host_draw_buffers[2] = {GL_NONE, GL_COLOR_ATTACHMENT0};
    glDrawBuffers(2, host_draw_buffers);
    glReadBuffer(GL_NONE);
    ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    // Host bindings on targets the passes never use, which the output probe must leave as they were.
    const GLenum kHostTargets[] = {GL_TEXTURE_2D_ARRAY, GL_TEXTURE_CUBE_MAP, GL_TEXTURE_CUBE_MAP_ARRAY,
                                   GL_TEXTURE_RECTANGLE, GL_TEXTURE_1D, GL_TEXTURE_1D_ARRAY,
                                   GL_TEXTURE_2D_MULTISAMPLE_ARRAY};
    const GLenum kHostBindings[] = {GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_CUBE_MAP,
                                    GL_TEXTURE_BINDING_CUBE_MAP_ARRAY, GL_TEXTURE_BINDING_RECTANGLE,
                                    GL_TEXTURE_BINDING_1D, GL_TEXTURE_BINDING_1D_ARRAY,
                                    GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY};
    constexpr int kUnits = 16;
    std::vector<HostTexture> sentinels;
    for (size_t t = 0; t < std::size(kHostTargets); ++t) sentinels.push_back(HostTexture::create());
    for (int unit = 0; unit < kUnits; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        for (size_t t = 0; t < std::size(kHostTargets); ++t) glBindTexture(kHostTargets[t], sentinels[t].get());
    }
    glActiveTexture(GL_TEXTURE0);

    obscura_output output = make_output(0);
    output.framebuffer = framebuffer.get();
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));

    int moved = 0;
    for (int unit = 0; unit < kUnits; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        for (size_t t = 0; t < std::size(kHostTargets); ++t) {
            GLint bound = 0;
            glGetIntegerv(kHostBindings[t], &bound);
            moved += GLuint(bound) != sentinels[t].get();
            glBindTexture(kHostTargets[t], 0);
        }
    }
    glActiveTexture(GL_TEXTURE0);
    EXPECT_EQ(moved, 0) << "host texture bindings changed by the output probe";
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    GLint draw0 = -1, draw1 = -1, read = -1;
    glGetIntegerv(GL_DRAW_BUFFER0, &draw0);
    glGetIntegerv(GL_DRAW_BUFFER1, &draw1);
    glGetIntegerv(GL_READ_BUFFER, &read);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    EXPECT_EQ(draw0, GL_NONE);
    EXPECT_EQ(draw1, GL_COLOR_ATTACHMENT0);
    EXPECT_EQ(read, GL_NONE);

    const std::vector<uint8_t> images = read_all_images(param.target, texture.get(), kSide, param.images);
    const size_t image_bytes = size_t(kSide) * kSide * 4;
    int wrong = 0, touched = 0;
    for (int image = 0; image < param.images; ++image) {
        for (int y = 0; y < kSide; ++y) {
            for (int x = 0; x < kSide; ++x) {
                const size_t at = image_bytes * image + (size_t(y) * kSide + x) * 4;
                const bool written = image == param.image && y < kHeight;
                for (int c = 0; c < 4; ++c) {
                    const uint8_t want = written ? expected[(size_t(y) * kWidth + x) * 4 + c] : 0;
                    if (written) wrong += images[at + c] != want;
                    else touched += images[at + c] != 0;
                }
            }
        }
    }
    EXPECT_EQ(wrong, 0) << "the attached " << param.name << " does not hold the AO";
    EXPECT_EQ(touched, 0) << "bytes outside the result (other images or rows above it) changed";

    // MULTIPLY reads the attached image back first: v * v in the colour channels.
    output.blend = OBSCURA_BLEND_MULTIPLY;
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    const std::vector<uint8_t> squared = read_all_images(param.target, texture.get(), kSide, param.images);
    int off = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const int v = expected[(size_t(y) * kWidth + x) * 4];
            const int want = unorm8((v / 255.0) * (v / 255.0));
            off += std::abs(int(squared[image_bytes * param.image + (size_t(y) * kSide + x) * 4]) - want) > 2;
        }
    }
    EXPECT_EQ(off, 0) << "MULTIPLY into the " << param.name;
}

INSTANTIATE_TEST_SUITE_P(Images, OutputLayers,
                         ::testing::Values(LayerCase{GL_TEXTURE_2D_ARRAY, 3, 1, "array layer 1"},
                                           LayerCase{GL_TEXTURE_3D, 4, 2, "3D slice 2"},
                                           LayerCase{GL_TEXTURE_CUBE_MAP, 6, 4, "cube face +Z"},
                                           LayerCase{GL_TEXTURE_CUBE_MAP_ARRAY, 12, 7, "cube array layer-face 7"}),
                         [](const ::testing::TestParamInfo<LayerCase>& test) {
                             switch (test.param.target) {
                                 case GL_TEXTURE_2D_ARRAY: return std::string("Array");
                                 case GL_TEXTURE_3D: return std::string("Slice3D");
                                 case GL_TEXTURE_CUBE_MAP: return std::string("CubeFace");
                                 default: return std::string("CubeArray");
                             }
                         });

TEST_F(OutputTargets, DefaultFramebufferWithoutSurface) {
    // Surfaceless EGL has no default framebuffer. When it is complete (a windowed or pbuffer context)
    // the blit path is exercised by the renderbuffer tests above; here only its absence is checked.
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE) GTEST_SKIP() << "this context has a default framebuffer";
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    obscura_output output = make_output(0);
    obscura_status result = obscura_render(ctx(), &frame.input, &settings, &output);
    EXPECT_EQ(result, OBSCURA_STATUS_INVALID_FRAMEBUFFER) << obscura_get_last_error(ctx());
    EXPECT_STRNE(obscura_get_last_error(ctx()), "");
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

// MULTIPLY into the default framebuffer reads back the buffer it draws to, whatever the host's read buffer (it read
// the read buffer: a host reading GL_FRONT while drawing to GL_BACK got the front's colour times the AO), and leaves
// the host's read buffer as it was. Needs a context with a default framebuffer: ctest runs it under OSMesa
// (OutputTargets.DefaultFramebufferUnderOsmesa); surfaceless EGL has none and skips.
TEST_F(OutputTargets, DefaultFramebufferMultiplyReadsTheDrawBuffer) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        GTEST_SKIP() << "this context has no default framebuffer";
    }
    GLint viewport[4] = {};
    glGetIntegerv(GL_VIEWPORT, viewport);  // the default framebuffer's size at first use
    const int side = std::min({viewport[2], viewport[3], 16});
    ASSERT_GT(side, 0);
    Frame frame = corner_frame();
    frame.input.output_rect = obscura_rect{kWidth / 2 - side / 2, kHeight / 2 - side / 2, side, side};
    obscura_settings settings = make_settings(1.0f);
    HostTexture direct = make_texture(GL_RGBA8, side, side);
    obscura_output direct_output = make_output(direct.get());
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &direct_output), OBSCURA_OK) << obscura_get_last_error(ctx());
    const std::vector<uint8_t> ao = read_texture_rgba8(direct.get(), side, side);

    GLint draw_buffer = GL_NONE;
    glGetIntegerv(GL_DRAW_BUFFER0, &draw_buffer);
    const GLfloat grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    glClearBufferfv(GL_COLOR, 0, grey);
    glReadBuffer(GL_NONE);  // the host reads nothing (or another buffer) while it draws to draw_buffer
    obscura_output output = make_output(0);
    output.blend = OBSCURA_BLEND_MULTIPLY;
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    GLint read_buffer = -1;
    glGetIntegerv(GL_READ_BUFFER, &read_buffer);
    EXPECT_EQ(read_buffer, GL_NONE) << "the host's read buffer must be restored";
    glReadBuffer(GLenum(draw_buffer == GL_FRONT_AND_BACK ? GL_FRONT : draw_buffer));
    std::vector<uint8_t> got(size_t(side) * side * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, side, side, GL_RGBA, GL_UNSIGNED_BYTE, got.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadBuffer(GLenum(read_buffer));
    int off = 0, occluded = 0;
    for (int i = 0; i < side * side; ++i) {
        const int expected = int(std::lround(0.5 * ao[4 * size_t(i)]));  // grey 128/255 times the AO
        off += std::abs(int(got[4 * size_t(i)]) - expected) > 2;
        occluded += ao[4 * size_t(i)] < 250;
    }
    EXPECT_GT(occluded, 0) << "the rectangle must hold occlusion for the product to show";
    EXPECT_EQ(off, 0) << "MULTIPLY must read back the colour of the buffer it draws to";
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

// GL 4.3 forbids blitting into a multisample framebuffer (18.3.1; Mesa allows it, NVIDIA does not): the SDK refuses
// such a target on every driver before rendering, with a validation status (until 2026-12-06 a conforming driver
// reported the blit's GL_INVALID_OPERATION as GL_ERROR), and leaves it and the GL error queue untouched.
TEST_F(OutputTargets, MultisampleFramebufferIsRefusedAsInvalidFramebuffer) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    RenderbufferTarget target = make_renderbuffer_target(GL_RGBA8, kWidth, kHeight, 4);
    clear_framebuffer(target.framebuffer.get(), 0.25f, 0.5f, 0.75f, 1.0f);
    obscura_output output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    EXPECT_EQ(obscura_render(ctx(), &frame.input, &settings, &output), OBSCURA_STATUS_INVALID_FRAMEBUFFER);
    EXPECT_NE(std::string(obscura_get_last_error(ctx())).find("multisampled (4 samples)"), std::string::npos)
        << obscura_get_last_error(ctx());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
    // Untouched: resolve it and read the clear colour back.
    RenderbufferTarget resolved = make_renderbuffer_target(GL_RGBA8, kWidth, kHeight);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer.get());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved.framebuffer.get());
    glBlitFramebuffer(0, 0, kWidth, kHeight, 0, 0, kWidth, kHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, resolved.framebuffer.get());
    std::vector<uint8_t> pixels(size_t(kWidth) * kHeight * 4);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    int changed = 0;
    for (size_t i = 0; i < pixels.size(); i += 4) changed += std::abs(int(pixels[i + 1]) - 128) > 1 ? 1 : 0;
    EXPECT_EQ(changed, 0);
}

// ---- Reduced resolution: the upsample writes the target ---------------------------------------------------

// What a pass that writes the target's image in the composite's place (no debug view) must give: every format, the
// multiply blend, a blit target and a placement inside a larger texture receive what an R32F overwrite of the same
// frame holds (`expected`, width x height, to the format's precision), as the composite's targets do; a debug view,
// which needs the composite, and the plain output alternate in one context. Each render must give the same frame.
void expect_every_target_receives(obscura_context* context, Frame& frame, const obscura_settings& settings,
                                  const std::vector<float>& expected, int width, int height) {
    struct Format {
        GLenum format;
        // The red channel's storage precision near [0.5, 1]. Half floats: one ulp, since drivers may truncate
        // (llvmpipe does) what the pass writes there.
        double tolerance;
    };
    const Format formats[] = {{GL_R8, 0.5 / 255 + 1e-6},         {GL_R16, 0.5 / 65535 + 1e-6},
                              {GL_R16F, std::ldexp(1.0, -11)},  {GL_RG32F, 0.0},
                              {GL_RGBA8, 0.5 / 255 + 1e-6},      {GL_RGBA16F, std::ldexp(1.0, -11)},
                              {GL_RGB10_A2, 0.5 / 1023 + 1e-6}, {GL_R11F_G11F_B10F, std::ldexp(1.0, -7)}};
    for (const Format& f : formats) {
        std::vector<float> got = render_to_new_texture(context, frame.input, settings, f.format, 4);
        ASSERT_EQ(got.size(), expected.size() * 4);
        double worst = 0.0;
        for (size_t i = 0; i < expected.size(); ++i) worst = std::max(worst, std::fabs(double(got[4 * i]) - expected[i]));
        EXPECT_LE(worst, f.tolerance) << "format 0x" << std::hex << f.format;
    }

    // Multiply: the target's colour times the visibility, alpha kept.
    HostTexture multiplied = make_texture(GL_RGBA32F, width, height);
    const float fill[4] = {0.5f, 0.25f, 1.0f, 0.7f};
    fill_texture(multiplied.get(), width, height, fill[0], fill[1], fill[2], fill[3]);
    obscura_output output = make_output(multiplied.get());
    output.blend = OBSCURA_BLEND_MULTIPLY;
    ASSERT_EQ(obscura_render(context, &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(context);
    std::vector<float> got = read_texture(multiplied.get(), width, height, 4);
    double worst = 0.0;
    int alpha_changed = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(double(got[4 * i + c]) - double(fill[c]) * expected[i]));
        alpha_changed += got[4 * i + 3] != fill[3];
    }
    EXPECT_LT(worst, 1e-6);
    EXPECT_EQ(alpha_changed, 0);

    // Placed at (3, 2) in a larger texture: the rectangle lands there, the rest keeps its contents.
    HostTexture larger = make_texture(GL_R32F, width + 5, height + 4);
    fill_texture(larger.get(), width + 5, height + 4, -1.0f, 0, 0, 1);
    output = make_output(larger.get());
    output.x = 3;
    output.y = 2;
    ASSERT_EQ(obscura_render(context, &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(context);
    got = read_texture(larger.get(), width + 5, height + 4, 1);
    int misplaced = 0;
    for (int y = 0; y < height + 4; ++y) {
        for (int x = 0; x < width + 5; ++x) {
            const bool inside = x >= 3 && x < 3 + width && y >= 2 && y < 2 + height;
            const float want = inside ? expected[size_t(y - 2) * width + (x - 3)] : -1.0f;
            misplaced += got[size_t(y) * (width + 5) + x] != want;
        }
    }
    EXPECT_EQ(misplaced, 0);

    // A renderbuffer, reached through the blit's staging texture, overwriting and multiplying.
    HostTexture direct = make_texture(GL_RGBA8, width, height);
    obscura_output direct_output = make_output(direct.get());
    ASSERT_EQ(obscura_render(context, &frame.input, &settings, &direct_output), OBSCURA_OK);
    const std::vector<uint8_t> direct_bytes = read_texture_rgba8(direct.get(), width, height);
    RenderbufferTarget target = make_renderbuffer_target(GL_RGBA8, width, height);
    output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    ASSERT_EQ(obscura_render(context, &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(context);
    EXPECT_EQ(read_framebuffer_rgba8(target.framebuffer.get(), width, height), direct_bytes);
    clear_framebuffer(target.framebuffer.get(), 1.0f, 1.0f, 1.0f, 0.6f);
    output.blend = OBSCURA_BLEND_MULTIPLY;
    ASSERT_EQ(obscura_render(context, &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(context);
    const std::vector<uint8_t> blended = read_framebuffer_rgba8(target.framebuffer.get(), width, height);
    int bad = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        bad += std::abs(blended[4 * i] - unorm8(expected[i])) > 1 || blended[4 * i + 3] != 153;
    }
    EXPECT_EQ(bad, 0);

    // A debug view (the composite, reading the depth), then the AO again, bit for bit.
    HostTexture depth_view = make_texture(GL_R32F, width, height);
    output = make_output(depth_view.get(), OBSCURA_DEBUG_LINEAR_DEPTH);
    ASSERT_EQ(obscura_render(context, &frame.input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(context);
    got = read_texture(depth_view.get(), width, height, 1);
    EXPECT_NE(std::memcmp(got.data(), expected.data(), got.size() * sizeof(float)), 0) << "the view shows depth";
    got = render_to_new_texture(context, frame.input, settings, GL_R32F, 1);
    ASSERT_EQ(got.size(), expected.size());
    EXPECT_EQ(std::memcmp(got.data(), expected.data(), got.size() * sizeof(float)), 0);
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

// At full resolution without accumulation the method's last reconstruction pass writes the target's image in the
// composite's place (no debug view): HBAO's and SAO's blur, GTAO's denoise (bent normals still beside it), LSAO's
// gather. Its values are those the same pass writes into the method's own R16F result, which the temporal pass
// passes on unchanged on a frame that starts a new history: equal to R16F's rounding.
TEST_F(OutputTargets, MethodsLastPassWritesEveryTarget) {
    Frame frame = corner_frame();
    frame.input.output_rect = obscura_rect{7, 5, kWidth - 14, kHeight - 10};
    const int width = kWidth - 14, height = kHeight - 10;
    // (Their timings, which end with that pass and no composite: SyncTimings.AtOnceAfterRenderWithExactlyTheMethodsPasses.)
    struct Case {
        const char* what;
        obscura_method method;
    };
    const Case cases[] = {{"hbao", OBSCURA_METHOD_HBAO},
                          {"gtao", OBSCURA_METHOD_GTAO},
                          {"sao", OBSCURA_METHOD_SAO},
                          {"lsao", OBSCURA_METHOD_LSAO}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        obscura_settings settings;
        obscura_default_settings(c.method, &settings);
        const std::vector<float> expected = render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1);
        ASSERT_EQ(expected.size(), size_t(width) * height);
        auto [lo, hi] = std::minmax_element(expected.begin(), expected.end());
        EXPECT_LT(*lo, 0.8f) << "the corner darkens: the comparisons below are not vacuous";
        EXPECT_LE(*hi, 1.0f);

        obscura_settings accumulated = settings;
        accumulated.temporal.enabled = OBSCURA_TOGGLE_ON;
        obscura_input reset = frame.input;
        reset.flags |= OBSCURA_INPUT_FLAG_RESET_HISTORY;
        const std::vector<float> own_result = render_to_new_texture(ctx(), reset, accumulated, GL_R32F, 1);
        ASSERT_EQ(own_result.size(), expected.size());
        double worst = 0.0;
        for (size_t i = 0; i < expected.size(); ++i) worst = std::max(worst, std::fabs(double(expected[i]) - own_result[i]));
        EXPECT_LE(worst, std::ldexp(1.0, -11)) << "the pass's own R16F result, to its rounding";

        expect_every_target_receives(ctx(), frame, settings, expected, width, height);
        if (HasFatalFailure()) return;
    }

    // GTAO with bent normals: the denoise writes them beside the target, as without the target write.
    obscura_settings gtao;
    obscura_default_settings(OBSCURA_METHOD_GTAO, &gtao);
    HostTexture target = make_texture(GL_R32F, width, height), bent = make_texture(GL_RGBA32F, width, height);
    obscura_output output = make_output(target.get());
    output.bent_normal_texture = bent.get();
    ASSERT_EQ(obscura_render(ctx(), &frame.input, &gtao, &output), OBSCURA_OK) << obscura_get_last_error(ctx());
    const std::vector<float> visibility = read_texture(target.get(), width, height, 1);
    const std::vector<float> bent_values = read_texture(bent.get(), width, height, 4);
    const std::vector<float> without_bent = render_to_new_texture(ctx(), frame.input, gtao, GL_R32F, 1);
    ASSERT_EQ(visibility.size(), without_bent.size());
    int differ = 0, alpha_off = 0, not_unit = 0;
    for (size_t i = 0; i < visibility.size(); ++i) {
        differ += visibility[i] != without_bent[i];
        alpha_off += std::fabs(bent_values[4 * i + 3] - visibility[i]) > std::ldexp(1.0, -10);  // rgb n, a visibility
        const double length = std::sqrt(double(bent_values[4 * i]) * bent_values[4 * i] +
                                        double(bent_values[4 * i + 1]) * bent_values[4 * i + 1] +
                                        double(bent_values[4 * i + 2]) * bent_values[4 * i + 2]);
        not_unit += std::fabs(length - 1.0) > 0.01;
    }
    EXPECT_EQ(differ, 0) << "the bent normals change nothing of the visibility";
    EXPECT_EQ(alpha_off, 0) << "the bent-normal texture's visibility is the target's, to R16F's rounding";
    EXPECT_EQ(not_unit, 0);
}

// At reduced resolution the upsample writes the target's image in the composite's place (no debug view).
TEST_F(OutputTargets, ReducedResolutionUpsampleWritesEveryTarget) {
    Frame frame = corner_frame();
    // An output rectangle inside the depth texture (a guard band): the upsample's destination is the target's
    // position plus the pixel's place in the rectangle, not the pixel itself.
    frame.input.output_rect = obscura_rect{7, 5, kWidth - 14, kHeight - 10};
    const int width = kWidth - 14, height = kHeight - 10;
    obscura_settings settings = make_settings(1.0f);
    settings.resolution.scale = OBSCURA_RESOLUTION_HALF;
    std::vector<float> expected = render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1);
    ASSERT_EQ(expected.size(), size_t(width) * height);
    auto [lo, hi] = std::minmax_element(expected.begin(), expected.end());
    EXPECT_LT(*lo, 0.8f) << "the corner darkens: the comparisons below are not vacuous";
    EXPECT_LE(*hi, 1.0f) << "the upsample holds the visibility to [0, 1]";
    expect_every_target_receives(ctx(), frame, settings, expected, width, height);
}

// At full resolution the temporal pass writes the target's image in the composite's place (no debug view). Without
// the frame's matrices every frame starts a new history, whose value is the method's own R16F result: what the
// frame without accumulation writes, to that rounding (its blur writes the target at the target's precision). With a
// history, two views given the same frames write the same values into an R32F and an RGBA32F target.
TEST_F(OutputTargets, TemporalPassWritesEveryTarget) {
    Frame frame = corner_frame();
    frame.input.output_rect = obscura_rect{7, 5, kWidth - 14, kHeight - 10};
    const int width = kWidth - 14, height = kHeight - 10;
    obscura_settings settings = make_settings(1.0f);
    const std::vector<float> plain = render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1);
    ASSERT_EQ(plain.size(), size_t(width) * height);
    EXPECT_LT(*std::min_element(plain.begin(), plain.end()), 0.8f) << "the corner darkens";
    settings.temporal.enabled = OBSCURA_TOGGLE_ON;
    const std::vector<float> expected = render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1);
    ASSERT_EQ(expected.size(), plain.size());
    double rounding = 0.0;
    for (size_t i = 0; i < plain.size(); ++i) rounding = std::max(rounding, std::fabs(double(expected[i]) - plain[i]));
    EXPECT_LE(rounding, std::ldexp(1.0, -11)) << "R16F's step below 1";
    expect_every_target_receives(ctx(), frame, settings, expected, width, height);
    if (HasFatalFailure()) return;

    // A history: the same still camera's matrices, the noise moving with the frame index (few directions, so frames
    // differ), accumulated in two views.
    settings.hbao.directions = 2;
    const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::memcpy(frame.input.view_projection, identity, sizeof identity);
    std::memcpy(frame.input.previous_view_projection, identity, sizeof identity);
    obscura_view* views[2] = {};
    ASSERT_EQ(obscura_create_view(ctx(), &views[0]), OBSCURA_OK);
    ASSERT_EQ(obscura_create_view(ctx(), &views[1]), OBSCURA_OK);
    HostTexture r32f = make_texture(GL_R32F, width, height), rgba32f = make_texture(GL_RGBA32F, width, height);
    obscura_output outputs[2] = {make_output(r32f.get()), make_output(rgba32f.get())};
    std::vector<float> first;
    for (uint32_t f = 0; f < 3; ++f) {
        frame.input.frame_index = f;
        for (int v = 0; v < 2; ++v) {
            frame.input.view = views[v];
            ASSERT_EQ(obscura_render(ctx(), &frame.input, &settings, &outputs[v]), OBSCURA_OK)
                << obscura_get_last_error(ctx());
        }
        if (f == 0) first = read_texture(r32f.get(), width, height, 1);
    }
    const std::vector<float> one = read_texture(r32f.get(), width, height, 1);
    const std::vector<float> four = read_texture(rgba32f.get(), width, height, 4);
    int differ = 0, moved = 0;
    for (size_t i = 0; i < one.size(); ++i) {
        differ += one[i] != four[4 * i];
        moved += std::fabs(one[i] - first[i]) > 1e-4f;
    }
    EXPECT_EQ(differ, 0);
    EXPECT_GT(moved, 0) << "the frames differ: the two views are compared on more than one image";
    for (obscura_view* view : views) EXPECT_EQ(obscura_destroy_view(ctx(), view), OBSCURA_OK);

    // The target holds the blend, the history's visibility: GTAO's bent-normal texture carries it in alpha (written
    // from the bent history, RGBA16F), and it is not the frame's own value.
    obscura_settings gtao;
    obscura_default_settings(OBSCURA_METHOD_GTAO, &gtao);
    gtao.temporal.enabled = OBSCURA_TOGGLE_ON;
    obscura_view* view = nullptr;
    ASSERT_EQ(obscura_create_view(ctx(), &view), OBSCURA_OK);
    HostTexture bent = make_texture(GL_RGBA32F, width, height);
    obscura_output with_bent = make_output(r32f.get());
    with_bent.bent_normal_texture = bent.get();
    frame.input.view = view;
    for (uint32_t f = 0; f < 3; ++f) {
        frame.input.frame_index = f;
        ASSERT_EQ(obscura_render(ctx(), &frame.input, &gtao, &with_bent), OBSCURA_OK) << obscura_get_last_error(ctx());
    }
    const std::vector<float> blended = read_texture(r32f.get(), width, height, 1);
    const std::vector<float> bent_values = read_texture(bent.get(), width, height, 4);
    obscura_settings alone = gtao;
    alone.temporal.enabled = OBSCURA_TOGGLE_OFF;
    frame.input.view = nullptr;
    const std::vector<float> last_alone = render_to_new_texture(ctx(), frame.input, alone, GL_R32F, 1);
    ASSERT_EQ(last_alone.size(), blended.size());
    double worst = 0.0;
    int blend_differs = 0;
    for (size_t i = 0; i < blended.size(); ++i) {
        worst = std::max(worst, std::fabs(double(blended[i]) - bent_values[4 * i + 3]));
        blend_differs += std::fabs(blended[i] - last_alone[i]) > 1e-3f;
    }
    EXPECT_LE(worst, std::ldexp(1.0, -11)) << "the target is the history's visibility (to the f16 history's rounding)";
    EXPECT_GT(blend_differs, 0) << "the blend differs from the frame alone: the check above is not vacuous";
    EXPECT_EQ(obscura_destroy_view(ctx(), view), OBSCURA_OK);
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(OutputTargets, IntegerRenderbufferIsRejected) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    RenderbufferTarget target = make_renderbuffer_target(GL_RGBA8UI, kWidth, kHeight);
    obscura_output output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    obscura_status result = obscura_render(ctx(), &frame.input, &settings, &output);
    EXPECT_EQ(result, OBSCURA_STATUS_UNSUPPORTED_FORMAT) << obscura_get_last_error(ctx());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(OutputTargets, RenderbufferTooSmallIsRejected) {
    Frame frame = corner_frame();
    obscura_settings settings = make_settings(1.0f);
    RenderbufferTarget target = make_renderbuffer_target(GL_RGBA8, kWidth / 2, kHeight);
    obscura_output output = make_output(0);
    output.framebuffer = target.framebuffer.get();
    obscura_status result = obscura_render(ctx(), &frame.input, &settings, &output);
    EXPECT_EQ(result, OBSCURA_STATUS_INVALID_RECT) << obscura_get_last_error(ctx());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

}  // namespace
}  // namespace obscura_test
