#include "gl_test_support.h"
#include "host_gl_error.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace obscura_test {

HeadlessGL& shared_gl() {
    // Leaked on purpose: destroying it during static destruction would race Mesa's own atexit work.
    static HeadlessGL* gl = new HeadlessGL();
    return *gl;
}

obscura_context_desc make_desc(uint32_t flags) {
    obscura_context_desc desc{};
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = &HeadlessGL::get_proc_address;
    desc.flags = flags;
    return desc;
}

ContextPtr create_context(uint32_t flags) {
    obscura_context_desc desc = make_desc(flags);
    obscura_context* context = nullptr;
    obscura_status status = obscura_create_context(&desc, &context);
    EXPECT_EQ(status, OBSCURA_OK) << obscura_status_string(status);
    return ContextPtr(context);
}

const char* gl_error_name(GLenum error) { return obscura::samples::gl_error_name(error); }

GLenum take_gl_error() {
    GLenum first = glGetError();
    for (int i = 0; i < 32 && first != GL_NO_ERROR && glGetError() != GL_NO_ERROR; ++i) {}
    return first;
}

void LogCapture::callback(obscura_log_level level, obscura_status status, const char* message, void* user_data) {
    static_cast<LogCapture*>(user_data)->entries.push_back(LogEntry{level, status, message ? message : ""});
}

void LogCapture::attach(obscura_context_desc* desc) {
    desc->log = &LogCapture::callback;
    desc->log_user_data = this;
}

void GLTest::SetUp() {
    HeadlessGL& gl = shared_gl();
    gl.make_current();
    ASSERT_EQ(take_gl_error(), GLenum(GL_NO_ERROR)) << "a GL error was pending before the test";
    obscura_context_desc desc = make_desc(context_flags_);
    log_.attach(&desc);
    obscura_context* context = nullptr;
    obscura_status status = obscura_create_context(&desc, &context);
    ASSERT_EQ(status, OBSCURA_OK) << obscura_status_string(status);
    context_.reset(context);
    EXPECT_TRUE(log_.entries.empty());
}

void GLTest::TearDown() {
    shared_gl().make_current();
    GLenum error = take_gl_error();
    EXPECT_EQ(error, GLenum(GL_NO_ERROR)) << "GL error left behind: " << gl_error_name(error);
    context_.reset();
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR)) << "obscura_destroy_context left a GL error";
}

// ---- Textures ------------------------------------------------------------------------------------

namespace {
void set_nearest_clamp(GLenum target) {
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

// Keeps the test's own binding of GL_TEXTURE_2D on the active unit intact.
struct TextureBindingScope {
    GLint previous = 0;
    TextureBindingScope() { glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous); }
    ~TextureBindingScope() { glBindTexture(GL_TEXTURE_2D, GLuint(previous)); }
};

struct UnpackScope {
    GLint alignment = 4, row_length = 0, buffer = 0;
    UnpackScope() {
        glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
        glGetIntegerv(GL_UNPACK_ROW_LENGTH, &row_length);
        glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &buffer);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    }
    ~UnpackScope() {
        glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, row_length);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(buffer));
    }
};

struct PackScope {
    GLint alignment = 4, row_length = 0, buffer = 0;
    PackScope() {
        glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
        glGetIntegerv(GL_PACK_ROW_LENGTH, &row_length);
        glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &buffer);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    }
    ~PackScope() {
        glPixelStorei(GL_PACK_ALIGNMENT, alignment);
        glPixelStorei(GL_PACK_ROW_LENGTH, row_length);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(buffer));
    }
};
}  // namespace

HostTexture make_texture(GLenum internal_format, int width, int height) {
    TextureBindingScope scope;
    HostTexture texture = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
    set_nearest_clamp(GL_TEXTURE_2D);
    return texture;
}

HostTexture make_depth_texture(GLenum internal_format, int width, int height, const std::vector<float>& depth,
                               uint8_t stencil) {
    if (depth.size() != size_t(width) * size_t(height)) throw std::invalid_argument("depth size mismatch");
    TextureBindingScope scope;
    UnpackScope unpack;
    HostTexture texture = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    set_nearest_clamp(GL_TEXTURE_2D);
    if (internal_format == GL_DEPTH24_STENCIL8) {
        std::vector<uint32_t> packed(depth.size());
        for (size_t i = 0; i < depth.size(); ++i) {
            double d = std::fmin(std::fmax(double(depth[i]), 0.0), 1.0);
            uint32_t q = uint32_t(std::lround(d * double(0xFFFFFF)));
            packed[i] = (q << 8) | stencil;
        }
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH24_STENCIL8, width, height, 0, GL_DEPTH_STENCIL,
                     GL_UNSIGNED_INT_24_8, packed.data());
    } else if (internal_format == GL_DEPTH32F_STENCIL8) {
        // GL_FLOAT_32_UNSIGNED_INT_24_8_REV: a float, then a word with the stencil in its low byte.
        std::vector<uint32_t> packed(depth.size() * 2);
        for (size_t i = 0; i < depth.size(); ++i) {
            std::memcpy(&packed[2 * i], &depth[i], 4);
            packed[2 * i + 1] = stencil;
        }
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH32F_STENCIL8, width, height, 0, GL_DEPTH_STENCIL,
                     GL_FLOAT_32_UNSIGNED_INT_24_8_REV, packed.data());
    } else {
        glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), width, height, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                     depth.data());
    }
    return texture;
}

HostTexture make_red_texture(GLenum internal_format, int width, int height, const std::vector<float>& values) {
    if (values.size() != size_t(width) * size_t(height)) throw std::invalid_argument("value count mismatch");
    TextureBindingScope scope;
    UnpackScope unpack;
    HostTexture texture = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
    set_nearest_clamp(GL_TEXTURE_2D);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RED, GL_FLOAT, values.data());
    return texture;
}

namespace {
GLuint compile(GLenum type, const char* source) {
    GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw std::runtime_error(std::string("test shader failed to compile: ") + log);
    }
    return shader;
}
}  // namespace

HostTexture make_multisample_depth_texture(int width, int height, int samples, const std::vector<float>& depth,
                                           float other_samples) {
    static const char* kVertex = R"(#version 430 core
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})";
    // Reading gl_SampleID makes the shader run once per sample.
    static const char* kFragment = R"(#version 430 core
layout(binding = 0) uniform sampler2D u_depth;
layout(location = 0) uniform float u_other;
void main() {
    float d = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
    gl_FragDepth = gl_SampleID == 0 ? d : u_other;
})";
    HostTexture source = make_red_texture(GL_R32F, width, height, depth);
    HostTexture texture = HostTexture::create();
    GLint previous_ms = 0, previous_unit0 = 0, active = 0, program_before = 0, vao_before = 0, fb_before = 0;
    GLint viewport[4];
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE, &previous_ms);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous_unit0);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_before);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_before);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb_before);
    glGetIntegerv(GL_VIEWPORT, viewport);
    GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST);
    GLint depth_func = GL_LESS;
    glGetIntegerv(GL_DEPTH_FUNC, &depth_func);

    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, texture.get());
    glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, GL_DEPTH_COMPONENT32F, width, height, GL_TRUE);
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer.get());
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D_MULTISAMPLE, texture.get(), 0);
    glDrawBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("multisample depth framebuffer incomplete");

    HostProgram program = HostProgram::create();
    GLuint vs = compile(GL_VERTEX_SHADER, kVertex);
    GLuint fs = compile(GL_FRAGMENT_SHADER, kFragment);
    glAttachShader(program.get(), vs);
    glAttachShader(program.get(), fs);
    glLinkProgram(program.get());
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint linked = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &linked);
    if (!linked) throw std::runtime_error("multisample depth program failed to link");
    HostVertexArray vao = HostVertexArray::create();
    glBindVertexArray(vao.get());
    glUseProgram(program.get());
    glUniform1f(0, other_samples);
    glBindTexture(GL_TEXTURE_2D, source.get());
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();

    glDepthFunc(GLenum(depth_func));
    if (!depth_test) glDisable(GL_DEPTH_TEST);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glUseProgram(GLuint(program_before));
    glBindVertexArray(GLuint(vao_before));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(fb_before));
    glBindTexture(GL_TEXTURE_2D, GLuint(previous_unit0));
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, GLuint(previous_ms));
    glActiveTexture(GLenum(active));
    return texture;
}

void fill_texture(GLuint texture, int width, int height, float r, float g, float b, float a) {
    TextureBindingScope scope;
    UnpackScope unpack;
    std::vector<float> values(size_t(width) * size_t(height) * 4);
    for (size_t i = 0; i < values.size(); i += 4) {
        values[i] = r;
        values[i + 1] = g;
        values[i + 2] = b;
        values[i + 3] = a;
    }
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, values.data());
}

std::vector<float> read_texture(GLuint texture, int width, int height, int channels) {
    TextureBindingScope scope;
    PackScope pack;
    std::vector<float> values(size_t(width) * size_t(height) * size_t(channels));
    glBindTexture(GL_TEXTURE_2D, texture);
    glGetTexImage(GL_TEXTURE_2D, 0, channels == 1 ? GL_RED : GL_RGBA, GL_FLOAT, values.data());
    return values;
}

std::vector<uint8_t> read_texture_rgba8(GLuint texture, int width, int height) {
    TextureBindingScope scope;
    PackScope pack;
    std::vector<uint8_t> values(size_t(width) * size_t(height) * 4);
    glBindTexture(GL_TEXTURE_2D, texture);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, values.data());
    return values;
}

// ---- API structs ---------------------------------------------------------------------------------

obscura_input make_input(GLuint depth_texture, int width, int height, const float projection[16],
                         obscura_clip_depth clip_depth) {
    obscura_input input{};
    input.struct_size = sizeof input;
    input.depth_texture = depth_texture;
    input.depth_width = width;
    input.depth_height = height;
    std::memcpy(input.projection, projection, sizeof input.projection);
    input.clip_depth = clip_depth;
    return input;
}

obscura_output make_output(GLuint texture, obscura_debug_view debug_view) {
    obscura_output output{};
    output.struct_size = sizeof output;
    output.texture = texture;
    output.debug_view = debug_view;
    return output;
}

obscura_settings make_settings(float radius) {
    obscura_settings settings{};
    obscura_default_settings(OBSCURA_METHOD_HBAO, &settings);
    settings.hbao.radius = radius;
    settings.hbao.decay_rate = 0.0f;  // derive C * radius^2 again
    return settings;
}

void standard_projection(float aspect, float out[16]) {
    const double n = 0.1, f = 100.0, t = std::tan(0.5 * 60.0 * M_PI / 180.0);
    std::memset(out, 0, 16 * sizeof(float));
    out[0] = float(1.0 / (t * aspect));
    out[5] = float(1.0 / t);
    out[10] = float(-(f + n) / (f - n));
    out[11] = -1.0f;
    out[14] = float(-2.0 * f * n / (f - n));
}

std::vector<float> render_to_new_texture(obscura_context* context, const obscura_input& input,
                                         const obscura_settings& settings, GLenum format, int channels,
                                         obscura_debug_view debug_view) {
    int width = input.output_rect.width ? input.output_rect.width : input.depth_width;
    int height = input.output_rect.height ? input.output_rect.height : input.depth_height;
    HostTexture target = make_texture(format, width, height);
    obscura_output output = make_output(target.get(), debug_view);
    obscura_status status = obscura_render(context, &input, &settings, &output);
    EXPECT_EQ(status, OBSCURA_OK) << obscura_status_string(status) << ": " << obscura_get_last_error(context);
    if (status != OBSCURA_OK) return {};
    return read_texture(target.get(), width, height, channels);
}

Stats stats(const std::vector<float>& values, const std::vector<bool>& mask) {
    Stats s;
    // An empty selection has no statistics: NaN fails every comparison, so a check on a mask that selected nothing
    // (a scene or camera that moved) fails instead of passing on a mean of 0.
    s.min = s.max = s.mean = std::numeric_limits<double>::quiet_NaN();
    double sum = 0;
    for (size_t i = 0; i < values.size() && i < mask.size(); ++i) {
        if (!mask[i]) continue;
        double v = values[i];
        if (s.count == 0) s.min = s.max = v;
        s.min = std::fmin(s.min, v);
        s.max = std::fmax(s.max, v);
        sum += v;
        ++s.count;
    }
    if (s.count) s.mean = sum / s.count;
    return s;
}

// Counts live GL objects of each type by asking glIs* for every name in [1, kNameRange]. GL names are
// small integers chosen by the implementation (Mesa reuses the lowest free ones), and glIs* is true
// exactly for names that denote an existing object of that type (textures, buffers, framebuffers,
// renderbuffers, vertex arrays and queries once first bound or used; samplers, programs, shaders once
// generated). Counting per type before and after create/render/destroy cycles shows whether the SDK
// leaves any object behind; Contexts.ObjectScanSeesLiveContexts confirms the scan does see the SDK's objects
// while a context is alive, so the comparison is not vacuous. (Queries generated but never used are invisible
// to glIsQuery; the SDK's timer queries are used by every render.) The range is wide because a long
// test process (the whole suite in one binary, as on a GPU run) pushes query names past a few thousand.
constexpr GLuint kNameRange = 1u << 16;

RenderbufferTarget make_renderbuffer_target(GLenum format, int width, int height, int samples) {
    RenderbufferTarget t;
    t.renderbuffer = HostRenderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, t.renderbuffer.get());
    if (samples > 0) glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
    else glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    t.framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.renderbuffer.get());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return t;
}

std::map<std::string, int> count_gl_objects() {
    std::map<std::string, int> counts;
    const std::pair<const char*, GLboolean (*)(GLuint)> kinds[] = {
        {"texture", [](GLuint n) { return glIsTexture(n); }},
        {"buffer", [](GLuint n) { return glIsBuffer(n); }},
        {"program", [](GLuint n) { return glIsProgram(n); }},
        {"shader", [](GLuint n) { return glIsShader(n); }},
        {"sampler", [](GLuint n) { return glIsSampler(n); }},
        {"query", [](GLuint n) { return glIsQuery(n); }},
        {"framebuffer", [](GLuint n) { return glIsFramebuffer(n); }},
        {"renderbuffer", [](GLuint n) { return glIsRenderbuffer(n); }},
        {"vertex array", [](GLuint n) { return glIsVertexArray(n); }},
    };
    for (const auto& [name, is] : kinds) {
        int count = 0;
        for (GLuint n = 1; n <= kNameRange; ++n) count += is(n) ? 1 : 0;
        counts[name] = count;
    }
    return counts;
}

std::string describe(const std::map<std::string, int>& counts) {
    std::string text;
    for (const auto& [name, count] : counts) text += name + "=" + std::to_string(count) + " ";
    return text;
}

}  // namespace obscura_test
