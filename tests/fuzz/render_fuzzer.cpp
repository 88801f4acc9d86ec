// libFuzzer target for the per-frame API on a real GL context: obscura_render, obscura_prepare,
// obscura_release_resources, obscura_get_timings, obscura_get_memory_usage and obscura_resolve_settings with a
// context, fed with fuzzed input / output / settings structs that name host GL objects from fixed pools.
//
// LLVMFuzzerInitialize creates one headless GL 4.3 context (llvmpipe in CI), two obscura contexts with
// OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES, the second also with OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS (the shader variants
// GPUs run: shared-memory tiles, storage buffers, runs of one pixel, at the fuzzer's odd sizes), the pools (depth-like textures of every kind the SDK must accept or
// refuse, normals, output targets) and then binds sentinel objects everywhere an SDK call may touch GL state.
// Each input is a short list of operations (see run_operation: the low 4 bits of an operation's byte pick it, bit 4
// the context it runs on); after every call the fuzzer checks that the
// status is a known code and one this call may return, that a failure left a message (and went to the log),
// that glGetError() is GL_NO_ERROR, and that every sentinel binding is still in place. It traps otherwise.
// Settings structs come in every released size (0.1 ... this header's), each in a heap buffer of exactly that
// size (AddressSanitizer reports a read past the caller's struct); a call refused on its fields (settings, input
// and output fields: stage 1, no GL) must answer that before WRONG_GL_CONTEXT or HOST_GL_ERROR.
//
// Renders stay cheap: the depth textures are at most 16x12, REFERENCE traces at most 4 rays (a 0.1 struct, which
// has no REFERENCE block, its default 256), obscura_prepare gets either a size up to 64x64 or an invalid one (never
// a valid large size, which would allocate gigabytes).
// The context keeps its resources and compiled variants from one input to the next, like a host's does: a
// crash input replays the operations of one input on a fresh process, which normally reproduces it.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "host_gl_error.h"
#include "headless_gl.h"
#include "host_gl.h"

using obscura::samples::HeadlessGL;
using obscura_fuzz::Reader;
using obscura_fuzz::SettingsBuffer;
using obscura_fuzz::is_released_input_size;
using obscura_fuzz::is_released_output_size;
using obscura_fuzz::is_released_settings_size;
using obscura_fuzz::load_raw;
using obscura_fuzz::status_code;
using obscura_fuzz::store_raw;

namespace {

constexpr int kDepthWidth = 16, kDepthHeight = 12;
constexpr int32_t kOk = OBSCURA_STATUS_OK;

// ---- Host GL objects ----------------------------------------------------------------------------------------

GLuint gen_texture(GLenum target) {
    GLuint name = 0;
    glGenTextures(1, &name);
    glBindTexture(target, name);
    if (target != GL_TEXTURE_2D_MULTISAMPLE && target != GL_TEXTURE_BUFFER) {
        glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    return name;
}

// A depth field in [0, 1] window depth: a sloped floor, a box, a column of sky (far plane) and one NaN-free
// nearest texel; `linear` gives view distances instead (sky = 0).
std::vector<float> depth_values(int width, int height, bool linear) {
    std::vector<float> values(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            double distance = 2.0 + 0.6 * y;                          // floor receding upwards
            if (x >= width / 3 && x < width / 2 && y < height / 2) distance = 1.5;  // a box in front
            bool sky = width > 1 && x == width - 1;
            float window = float(0.9 + 0.09 * (1.0 - 1.0 / distance));
            const float value = linear ? (sky ? 0.0f : float(distance)) : (sky ? 1.0f : window);
            values[size_t(y) * size_t(width) + size_t(x)] = value;
        }
    }
    return values;
}

GLuint make_depth(GLenum format, int width, int height) {
    GLuint texture = gen_texture(GL_TEXTURE_2D);
    std::vector<float> depth = depth_values(width, height, false);
    if (format == GL_DEPTH24_STENCIL8) {
        std::vector<uint32_t> packed(depth.size());
        for (size_t i = 0; i < depth.size(); ++i) {
            packed[i] = (uint32_t(std::lround(depth[i] * 16777215.0)) << 8) | 0x5A;  // stencil 0x5A
        }
        glTexImage2D(GL_TEXTURE_2D, 0, GLint(format), width, height, 0, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8,
                     packed.data());
    } else {
        glTexImage2D(GL_TEXTURE_2D, 0, GLint(format), width, height, 0, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    }
    return texture;
}

GLuint make_color(GLenum format, int width, int height) {
    GLuint texture = gen_texture(GL_TEXTURE_2D);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    return texture;
}

GLuint make_red_float(int width, int height, const std::vector<float>& values) {
    GLuint texture = make_color(GL_R32F, width, height);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RED, GL_FLOAT, values.data());
    return texture;
}

GLuint make_normals(GLenum format, int width, int height) {
    GLuint texture = make_color(format, width, height);
    std::vector<float> rgba(size_t(width) * size_t(height) * 4);
    for (size_t i = 0; i < rgba.size(); i += 4) {
        rgba[i] = 0.0f;
        rgba[i + 1] = format == GL_RGBA16F ? 0.0f : 0.5f;
        rgba[i + 2] = 1.0f;
        rgba[i + 3] = 1.0f;
    }
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
    return texture;
}

GLuint make_framebuffer(GLuint color_texture, GLuint color_renderbuffer) {
    GLuint framebuffer = 0;
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    if (color_texture) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_texture, 0);
    if (color_renderbuffer) {
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_renderbuffer);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return framebuffer;
}

GLuint make_buffer(GLenum target, GLsizeiptr size) {
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(target, buffer);  // a name becomes a buffer object when first bound
    glBufferData(target, size, nullptr, GL_STATIC_DRAW);
    glBindBuffer(target, 0);
    return buffer;
}

// ---- Pools ----------------------------------------------------------------------------------------------------

struct DepthEntry {
    const char* label;
    GLuint name;
    int width, height;         // the texture's size (the size a host would pass); 0 for non-textures
    int32_t kind;              // OBSCURA_DEPTH_* it holds, or -1 where no kind makes it usable
    bool not_a_texture = false;  // a buffer's or a deleted texture's name: GL may hand the number out again
};
struct NormalEntry {
    const char* label;
    GLuint name;
    int width, height;
    bool supported;            // a 2D texture of a normal format (usable when its size matches the depth's)
    bool not_a_texture = false;
};
struct OutputEntry {
    const char* label;
    GLuint texture;
    GLuint framebuffer;
    int width, height;         // what the result must fit
    bool usable;
    bool not_a_texture = false;
    bool read_back = false;    // a float texture whose result a successful render must leave in [0, 1]
};

struct Pools {
    std::vector<DepthEntry> depth;
    std::vector<NormalEntry> normals;
    std::vector<OutputEntry> outputs;
    GLuint stencil_mode_texture = 0;  // DEPTH24_STENCIL8 whose GL_DEPTH_STENCIL_TEXTURE_MODE the host set to stencil
    GLuint any_framebuffer = 0;       // a complete framebuffer, given beside an output texture
};

Pools make_pools() {
    Pools p;
    const int w = kDepthWidth, h = kDepthHeight;
    GLuint d32f = make_depth(GL_DEPTH_COMPONENT32F, w, h);
    GLuint d24s8 = make_depth(GL_DEPTH24_STENCIL8, w, h);
    GLuint d24s8_stencil = make_depth(GL_DEPTH24_STENCIL8, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);  // the SDK must read depth
    p.stencil_mode_texture = d24s8_stencil;
    GLuint d16 = make_depth(GL_DEPTH_COMPONENT16, w, h);
    GLuint d32f_small = make_depth(GL_DEPTH_COMPONENT32F, 8, 6);
    GLuint d32f_1x1 = make_depth(GL_DEPTH_COMPONENT32F, 1, 1);
    GLuint d32f_wide = make_depth(GL_DEPTH_COMPONENT32F, 33, 5);
    GLuint linear = make_red_float(w, h, depth_values(w, h, true));
    GLuint linear_f16 = make_color(GL_R16F, 7, 9);
    {
        const std::vector<float> values = depth_values(7, 9, true);
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 7, 9, GL_RED, GL_FLOAT, values.data());
    }

    // Multisample depth, cleared to one depth through a framebuffer (every sample the same).
    GLuint multisample = gen_texture(GL_TEXTURE_2D_MULTISAMPLE);
    glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, 4, GL_DEPTH_COMPONENT32F, w, h, GL_TRUE);
    GLuint clear_fb = 0;
    glGenFramebuffers(1, &clear_fb);
    glBindFramebuffer(GL_FRAMEBUFFER, clear_fb);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D_MULTISAMPLE, multisample, 0);
    const float clear_depth = 0.95f;
    glClearBufferfv(GL_DEPTH, 0, &clear_depth);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &clear_fb);

    GLuint texture_3d = gen_texture(GL_TEXTURE_3D);
    glTexStorage3D(GL_TEXTURE_3D, 1, GL_R32F, w, h, 2);
    GLuint rgba8 = make_color(GL_RGBA8, w, h);
    // A buffer whose number no texture has (names are per object type).
    GLuint buffer = make_buffer(GL_ARRAY_BUFFER, 64);
    while (glIsTexture(buffer)) buffer = make_buffer(GL_ARRAY_BUFFER, 64);
    GLuint deleted = gen_texture(GL_TEXTURE_2D);
    glDeleteTextures(1, &deleted);

    p.depth = {
        {"D32F 16x12", d32f, w, h, OBSCURA_DEPTH_HARDWARE},
        {"D24S8 16x12", d24s8, w, h, OBSCURA_DEPTH_HARDWARE},
        {"D24S8 16x12 in stencil mode", d24s8_stencil, w, h, OBSCURA_DEPTH_HARDWARE},
        {"D16 16x12", d16, w, h, OBSCURA_DEPTH_HARDWARE},
        {"D32F 8x6", d32f_small, 8, 6, OBSCURA_DEPTH_HARDWARE},
        {"R32F linear 16x12", linear, w, h, OBSCURA_DEPTH_LINEAR_VIEW},
        {"D32F 1x1", d32f_1x1, 1, 1, OBSCURA_DEPTH_HARDWARE},
        {"D32F 33x5", d32f_wide, 33, 5, OBSCURA_DEPTH_HARDWARE},
        {"R16F linear 7x9", linear_f16, 7, 9, OBSCURA_DEPTH_LINEAR_VIEW},
        {"D32F 4x multisample 16x12", multisample, w, h, OBSCURA_DEPTH_HARDWARE},
        {"R32F 3D texture", texture_3d, w, h, -1},
        {"RGBA8 colour texture", rgba8, w, h, -1},
        {"buffer object name", buffer, w, h, -1, true},
        {"deleted texture name", deleted, w, h, -1, true},
        {"0", 0, w, h, -1},
    };

    GLuint normals_f16 = make_normals(GL_RGBA16F, w, h);
    GLuint normals_unorm = make_normals(GL_RGBA8, w, h);
    GLuint normals_rg8 = make_color(GL_RG8, w, h);
    GLuint normals_small = make_normals(GL_RGBA16F, 8, 6);
    p.normals = {
        {"none", 0, 0, 0, true},
        {"RGBA16F 16x12", normals_f16, w, h, true},
        {"RGBA8 16x12", normals_unorm, w, h, true},
        {"RG8 16x12", normals_rg8, w, h, false},
        {"RGBA16F 8x6", normals_small, 8, 6, true},
        {"buffer object name", buffer, w, h, false, true},
        {"D32F depth texture", d32f, w, h, false},
    };

    GLuint out_r8 = make_color(GL_R8, w, h);
    GLuint out_rgba16f = make_color(GL_RGBA16F, w, h);
    GLuint out_rgb8 = make_color(GL_RGB8, w, h);
    GLuint out_small = make_color(GL_R8, 4, 4);
    GLuint out_large = make_color(GL_RGBA32F, 40, 40);
    GLuint fb_texture = make_color(GL_RGBA8, w, h);
    GLuint fb_with_texture = make_framebuffer(fb_texture, 0);
    GLuint renderbuffer = 0;
    glGenRenderbuffers(1, &renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    GLuint fb_with_renderbuffer = make_framebuffer(0, renderbuffer);
    GLuint fb_incomplete = make_framebuffer(0, 0);  // no attachment at all
    p.any_framebuffer = fb_with_texture;
    p.outputs = {
        {"R8 texture 16x12", out_r8, 0, w, h, true},
        {"RGBA16F texture 16x12", out_rgba16f, 0, w, h, true, false, true},
        {"RGB8 texture (unsupported)", out_rgb8, 0, w, h, false},
        {"R8 texture 4x4 (too small for most rects)", out_small, 0, 4, 4, true},
        {"FBO with an RGBA8 texture", 0, fb_with_texture, w, h, true},
        {"FBO with an RGBA8 renderbuffer (blit)", 0, fb_with_renderbuffer, w, h, true},
        {"incomplete FBO", 0, fb_incomplete, w, h, false},
        {"default framebuffer (none: surfaceless)", 0, 0, w, h, false},
        {"never generated framebuffer name", 0, 0x7FFF0, w, h, false},
        {"R32F linear depth as output", linear, 0, w, h, true},
        {"buffer object name as texture", buffer, 0, w, h, false, true},
        {"RGBA32F texture 40x40", out_large, 0, 40, 40, true, false, true},
    };
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindTexture(GL_TEXTURE_3D, 0);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
    return p;
}

// ---- Sentinel state: host bindings the SDK must leave as it found them -----------------------------------------

struct IndexedBinding {
    GLenum target;
    GLuint index;
    GLint name;
    GLint64 start, size;
};

struct Sentinels {
    GLint program = 0, active_texture = 0, draw_framebuffer = 0, read_framebuffer = 0, renderbuffer = 0;
    GLint uniform_buffer = 0, storage_buffer = 0, pixel_unpack = 0, pack_alignment = 0, unpack_alignment = 0;
    GLboolean scissor = GL_FALSE, discard = GL_FALSE;
    GLint texture_2d[8] = {}, texture_ms[8] = {}, texture_3d[8] = {}, texture_buffer[8] = {}, sampler[8] = {};
    GLint image[8] = {};
    std::vector<IndexedBinding> indexed;
};

GLint get_integer(GLenum pname) {
    GLint value = 0;
    glGetIntegerv(pname, &value);
    return value;
}

// Reads the state that `Sentinels` describes (switching the active unit and switching it back).
Sentinels read_state() {
    Sentinels s;
    s.program = get_integer(GL_CURRENT_PROGRAM);
    s.active_texture = get_integer(GL_ACTIVE_TEXTURE);
    s.draw_framebuffer = get_integer(GL_DRAW_FRAMEBUFFER_BINDING);
    s.read_framebuffer = get_integer(GL_READ_FRAMEBUFFER_BINDING);
    s.renderbuffer = get_integer(GL_RENDERBUFFER_BINDING);
    s.uniform_buffer = get_integer(GL_UNIFORM_BUFFER_BINDING);
    s.storage_buffer = get_integer(GL_SHADER_STORAGE_BUFFER_BINDING);
    s.pixel_unpack = get_integer(GL_PIXEL_UNPACK_BUFFER_BINDING);
    s.pack_alignment = get_integer(GL_PACK_ALIGNMENT);
    s.unpack_alignment = get_integer(GL_UNPACK_ALIGNMENT);
    s.scissor = glIsEnabled(GL_SCISSOR_TEST);
    s.discard = glIsEnabled(GL_RASTERIZER_DISCARD);
    for (int unit = 0; unit < 8; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        s.texture_2d[unit] = get_integer(GL_TEXTURE_BINDING_2D);
        s.texture_ms[unit] = get_integer(GL_TEXTURE_BINDING_2D_MULTISAMPLE);
        s.texture_3d[unit] = get_integer(GL_TEXTURE_BINDING_3D);
        s.texture_buffer[unit] = get_integer(GL_TEXTURE_BINDING_BUFFER);
        s.sampler[unit] = get_integer(GL_SAMPLER_BINDING);
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, GLuint(unit), &s.image[unit]);
    }
    glActiveTexture(GLenum(s.active_texture));
    const struct { GLenum target, binding, start, size; GLuint count; } kinds[] = {
        {GL_UNIFORM_BUFFER, GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE, 4},
        {GL_SHADER_STORAGE_BUFFER, GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
         GL_SHADER_STORAGE_BUFFER_SIZE, 4},
    };
    for (const auto& kind : kinds) {
        for (GLuint index = 0; index < kind.count; ++index) {
            IndexedBinding b{kind.target, index, 0, 0, 0};
            glGetIntegeri_v(kind.binding, index, &b.name);
            glGetInteger64i_v(kind.start, index, &b.start);
            glGetInteger64i_v(kind.size, index, &b.size);
            s.indexed.push_back(b);
        }
    }
    return s;
}

// Binds a sentinel object at every place Sentinels reads: the SDK's units and more, so that a leak shows.
Sentinels install_sentinels() {
    static const char* kCompute = "#version 430\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &kCompute, nullptr);
    glCompileShader(shader);
    GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    FUZZ_CHECK(linked == GL_TRUE, "render_fuzzer setup: the sentinel program did not link");

    GLuint tex_2d = make_color(GL_RGBA8, 4, 4);
    GLuint tex_2d_other = make_color(GL_RGBA8, 2, 2);
    GLuint tex_ms = gen_texture(GL_TEXTURE_2D_MULTISAMPLE);
    glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, 2, GL_RGBA8, 4, 4, GL_TRUE);
    GLuint tex_3d = gen_texture(GL_TEXTURE_3D);
    glTexStorage3D(GL_TEXTURE_3D, 1, GL_RGBA8, 2, 2, 2);
    GLuint texel_buffer = make_buffer(GL_TEXTURE_BUFFER, 256);
    GLuint tex_buffer = gen_texture(GL_TEXTURE_BUFFER);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, texel_buffer);
    GLuint sampler = 0;
    glGenSamplers(1, &sampler);
    GLint ubo_alignment = get_integer(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT);
    GLint ssbo_alignment = get_integer(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT);
    GLuint ubo = make_buffer(GL_UNIFORM_BUFFER, 4096);
    GLuint ssbo = make_buffer(GL_SHADER_STORAGE_BUFFER, 4096);
    GLuint draw_fb = make_framebuffer(make_color(GL_RGBA8, 4, 4), 0);
    GLuint read_fb = make_framebuffer(make_color(GL_RGBA8, 4, 4), 0);
    GLuint renderbuffer = 0;
    glGenRenderbuffers(1, &renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 4, 4);
    GLuint unpack_buffer = make_buffer(GL_PIXEL_UNPACK_BUFFER, 64);

    for (int unit = 0; unit < 8; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        glBindTexture(GL_TEXTURE_2D, unit == 0 ? tex_2d : tex_2d_other);
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, tex_ms);
        glBindTexture(GL_TEXTURE_3D, tex_3d);
        glBindTexture(GL_TEXTURE_BUFFER, tex_buffer);
        glBindSampler(GLuint(unit), sampler);
        glBindImageTexture(GLuint(unit), tex_2d, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    }
    for (GLuint index = 0; index < 4; ++index) {
        glBindBufferRange(GL_UNIFORM_BUFFER, index, ubo, GLintptr(ubo_alignment) * index, 256);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, index, ssbo, GLintptr(ssbo_alignment) * index, 256);
    }
    glBindBuffer(GL_UNIFORM_BUFFER, ubo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, ssbo);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, unpack_buffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, draw_fb);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fb);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 1, 1);
    glEnable(GL_RASTERIZER_DISCARD);
    glUseProgram(program);
    glActiveTexture(GL_TEXTURE5);
    return read_state();
}

using obscura::samples::gl_error_name;

// ---- Statistics (OBSCURA_FUZZ_STATS=1 prints them at exit: how often each call reached which status) ---------------

struct CallStats {
    const char* call;
    unsigned long counts[OBSCURA_STATUS_COUNT_] = {};
};
CallStats g_stats[] = {{"obscura_render"}, {"obscura_prepare"}};

// OBSCURA_FUZZ_TRACE=1 prints every render and prepare with its status (to replay a crash input by hand).
bool g_trace = false;

void count_status(int call, int32_t status, const std::string& what, obscura_context* context) {
    if (status >= 0 && status < int32_t(OBSCURA_STATUS_COUNT_)) ++g_stats[call].counts[status];
    if (g_trace) {
        std::fprintf(stderr, "render_fuzzer: %s\n  -> %s%s%s\n", what.c_str(), fuzz_status_string(status),
                     status ? ": " : "", status ? obscura_get_last_error(context) : "");
    }
}

void print_stats() {
    for (const CallStats& stats : g_stats) {
        std::fprintf(stderr, "render_fuzzer: %s:", stats.call);
        for (int32_t s = 0; s < int32_t(OBSCURA_STATUS_COUNT_); ++s) {
            if (!stats.counts[s]) continue;
            const char* name = fuzz_status_string(s) + 15;  // after "OBSCURA_STATUS_"
            std::fprintf(stderr, " %.*s %lu", int(std::strcspn(name, ":")), name, stats.counts[s]);
        }
        std::fprintf(stderr, "\n");
    }
}

// ---- The process-wide fixture -----------------------------------------------------------------------------------

struct LogRecord {
    int count = 0;
    int32_t status = 0;
    std::string message;
};

void log_callback(obscura_log_level level, obscura_status status, const char* message, void* user_data) {
    auto* record = static_cast<LogRecord*>(user_data);
    FUZZ_CHECK(message != nullptr, "the log callback received a NULL message");
    if (level != OBSCURA_LOG_ERROR) return;
    ++record->count;
    record->status = status_code(status);
    record->message = message;
}

struct Fixture {
    HeadlessGL* gl = nullptr;
    HeadlessGL* other_gl = nullptr;  // a second GL context, current only inside op_wrong_context
    // The context the current operation runs on (select()), and what the checks keep of it.
    obscura_context* context = nullptr;
    bool gpu_code_paths = false;  // created with OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS
    uint64_t baseline_memory = 0;
    uint64_t last_frame_index = 0;
    LogRecord log;
    Pools pools;
    Sentinels sentinels;
    GLint max_texture_size = 0;

    // Both contexts; `selected` is the one whose state the fields above hold.
    struct ContextState {
        obscura_context* context = nullptr;
        bool gpu_code_paths = false;
        uint64_t baseline_memory = 0, last_frame_index = 0;
    };
    ContextState states[2];
    int selected = 0;
    void select(int index) {
        states[selected] = ContextState{context, gpu_code_paths, baseline_memory, last_frame_index};
        selected = index;
        context = states[index].context;
        gpu_code_paths = states[index].gpu_code_paths;
        baseline_memory = states[index].baseline_memory;
        last_frame_index = states[index].last_frame_index;
    }
};
Fixture* g_fixture = nullptr;

void check_sentinels(const char* call) {
    const Sentinels now = read_state();
    const Sentinels& want = g_fixture->sentinels;
    auto same = [&](const char* what, GLint64 got, GLint64 expected) {
        FUZZ_CHECK(got == expected, "%s changed the host's %s: %lld, was %lld", call, what, (long long)got,
                   (long long)expected);
    };
    same("current program", now.program, want.program);
    same("active texture", now.active_texture, want.active_texture);
    same("draw framebuffer", now.draw_framebuffer, want.draw_framebuffer);
    same("read framebuffer", now.read_framebuffer, want.read_framebuffer);
    same("renderbuffer binding", now.renderbuffer, want.renderbuffer);
    same("GL_UNIFORM_BUFFER binding", now.uniform_buffer, want.uniform_buffer);
    same("GL_SHADER_STORAGE_BUFFER binding", now.storage_buffer, want.storage_buffer);
    same("GL_PIXEL_UNPACK_BUFFER binding", now.pixel_unpack, want.pixel_unpack);
    same("GL_PACK_ALIGNMENT", now.pack_alignment, want.pack_alignment);
    same("GL_UNPACK_ALIGNMENT", now.unpack_alignment, want.unpack_alignment);
    same("scissor test", now.scissor, want.scissor);
    same("rasterizer discard", now.discard, want.discard);
    char what[96];
    for (int unit = 0; unit < 8; ++unit) {
        std::snprintf(what, sizeof what, "GL_TEXTURE_BINDING_2D of unit %d", unit);
        same(what, now.texture_2d[unit], want.texture_2d[unit]);
        std::snprintf(what, sizeof what, "GL_TEXTURE_BINDING_2D_MULTISAMPLE of unit %d", unit);
        same(what, now.texture_ms[unit], want.texture_ms[unit]);
        std::snprintf(what, sizeof what, "GL_TEXTURE_BINDING_3D of unit %d", unit);
        same(what, now.texture_3d[unit], want.texture_3d[unit]);
        std::snprintf(what, sizeof what, "GL_TEXTURE_BINDING_BUFFER of unit %d", unit);
        same(what, now.texture_buffer[unit], want.texture_buffer[unit]);
        std::snprintf(what, sizeof what, "sampler of unit %d", unit);
        same(what, now.sampler[unit], want.sampler[unit]);
        std::snprintf(what, sizeof what, "image unit %d", unit);
        same(what, now.image[unit], want.image[unit]);
    }
    for (size_t i = 0; i < want.indexed.size(); ++i) {
        const IndexedBinding& a = now.indexed[i];
        const IndexedBinding& b = want.indexed[i];
        const char* target = b.target == GL_UNIFORM_BUFFER ? "uniform" : "storage";
        FUZZ_CHECK(a.name == b.name && a.start == b.start && a.size == b.size,
                   "%s changed the host's indexed %s buffer binding %u: buffer %d [%lld, +%lld], was %d [%lld, +%lld]",
                   call, target, b.index, a.name, (long long)a.start, (long long)a.size, b.name, (long long)b.start,
                   (long long)b.size);
    }
    // The SDK switches a depth-stencil texture to depth for a frame and must switch it back.
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_2D, g_fixture->pools.stencil_mode_texture);
    GLint mode = 0;
    glGetTexParameteriv(GL_TEXTURE_2D, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
    glBindTexture(GL_TEXTURE_2D, GLuint(want.texture_2d[7]));
    glActiveTexture(GLenum(want.active_texture));
    FUZZ_CHECK(mode == GL_STENCIL_INDEX,
               "%s left the host's depth-stencil texture in GL_DEPTH_STENCIL_TEXTURE_MODE 0x%04X", call,
               unsigned(mode));
}

// After every call on the context: a known status, a message for failures, no GL error, sentinels in place.
void check_after_call(const char* call, int32_t status, int log_count_before, bool reports_to_context) {
    FUZZ_CHECK(status >= 0 && status < int32_t(OBSCURA_STATUS_COUNT_), "%s returned %d, not an obscura_status", call,
               status);
    if (reports_to_context && status != kOk) {
        const char* message = obscura_get_last_error(g_fixture->context);
        FUZZ_CHECK(message != nullptr && message[0] != '\0', "%s failed with %s but obscura_get_last_error is empty",
                   call, fuzz_status_string(status));
        const LogRecord& log = g_fixture->log;
        FUZZ_CHECK(log.count == log_count_before + 1 && log.status == status && log.message == message,
                   "%s failed with %s but the log received %d errors (last: %d \"%s\")", call,
                   fuzz_status_string(status), log.count - log_count_before, log.status, log.message.c_str());
    }
    GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        while (glGetError() != GL_NO_ERROR) {}
        obscura_fuzz::fail("%s (status %s) left %s (0x%04X) pending", call, fuzz_status_string(status),
                           gl_error_name(error), unsigned(error));
    }
    check_sentinels(call);
}

// ---- Decoding the structs --------------------------------------------------------------------------------------

bool valid_method(int32_t method) { return method >= 0 && method < int32_t(OBSCURA_METHOD_COUNT_); }

// A host's settings struct: exactly struct_size bytes for a released size (this header's or an older one), the
// whole struct for a size no header had.
struct DecodedSettings {
    SettingsBuffer buffer{0, sizeof(obscura_settings)};
    const obscura_settings* get() const { return buffer.get(); }
    uint32_t struct_size() const { return buffer.struct_size(); }
    int32_t method() const {
        int32_t method;
        std::memcpy(&method, buffer.bytes() + offsetof(obscura_settings, method), sizeof method);
        return method;
    }
};

// Known issue (settings_fuzzer.cpp, kTolerateEnumArgumentLoads): the library loads the method argument of
// obscura_default_settings* through the C++ enum type; only valid methods are passed here, so it does not matter.

DecodedSettings decode_settings(Reader& in) {
    const uint8_t mode = in.u8();
    static const int32_t kMethods[8] = {OBSCURA_METHOD_DEFAULT, OBSCURA_METHOD_HBAO,      OBSCURA_METHOD_SAO,
                                        OBSCURA_METHOD_LSAO,    OBSCURA_METHOD_FFAO,      OBSCURA_METHOD_REFERENCE,
                                        OBSCURA_METHOD_GTAO,    OBSCURA_METHOD_COUNT_};
    int32_t method = kMethods[mode % 8];
    if ((mode & 0xF8) == 0xF8) method = in.i32();
    // The struct's version: mostly this header's, or an older released one (0.3's from the 0.3 symbol), or any size.
    const uint8_t version = in.u8() & 15;
    uint32_t size = sizeof(obscura_settings);
    bool raw_size = false;
    uint32_t raw = 0;
    switch (version) {
        case 12: size = obscura_fuzz::kSettingsSize01; break;
        case 13: size = obscura_fuzz::kSettingsSize02; break;
        case 14: size = obscura_fuzz::kSettingsSize03; break;
        case 11: size = obscura_fuzz::kSettingsSize04; break;
        case 15: raw_size = true, raw = in.u32(); break;
        default: break;
    }
    DecodedSettings d;
    d.buffer = SettingsBuffer(0, size);
    obscura_settings* settings = d.buffer.get();
    if (valid_method(method) && (mode & 0x08) == 0) {
        const int32_t status = size == sizeof(obscura_settings)       ? fuzz_default_settings(method, settings)
                               : size == obscura_fuzz::kSettingsSize03 ? fuzz_default_settings_03(method, settings)
                                                                       : fuzz_default_settings_sized(method, settings, size);
        FUZZ_CHECK(status == kOk && d.struct_size() == size, "default settings of method %d (size %u) failed: %d",
                   method, size, status);
    } else {
        std::memcpy(d.buffer.get(), &size, sizeof size);
        std::memcpy(reinterpret_cast<unsigned char*>(settings) + offsetof(obscura_settings, method), &method,
                    sizeof method);
    }
    // Edits through the metadata (any value: out-of-range ones are refused and leave the struct as it was).
    const int32_t info_method = valid_method(method) ? method : int32_t(OBSCURA_METHOD_HBAO);
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    fuzz_get_setting_infos(info_method, &infos, &count);
    const int edits = in.u8() % 8;
    for (int i = 0; i < edits; ++i) {
        const obscura_setting_info& info = infos[in.index(count)];
        const double value = obscura_fuzz::pick_setting_value(info, in.u8(), in);
        obscura_set_setting(settings, info.name, value);
    }
    // Raw pokes anywhere in the struct (other methods' fields, the falloff tables, the flags, the method and size).
    const int pokes = in.u8() % 4;
    for (int i = 0; i < pokes; ++i) {
        const size_t offset = in.u16() % (size - 3);
        const uint32_t bits = in.u32();
        unsigned char* field = reinterpret_cast<unsigned char*>(settings) + offset;
        for (int b = 0; b < 4; ++b) field[b] ^= uint8_t(bits >> (8 * b));
    }
    // A poke may turn struct_size into a released size larger than the buffer: a host that says its struct is
    // bigger than it is, which no library can detect (it reads the bytes the size promises). Such a poke is undone;
    // unknown sizes, larger or not, stay (they are refused before any read).
    const uint32_t poked_size = d.struct_size();
    if (poked_size > size && std::find(std::begin(obscura_fuzz::kReleasedSettingsSizes),
                                       std::end(obscura_fuzz::kReleasedSettingsSizes),
                                       poked_size) != std::end(obscura_fuzz::kReleasedSettingsSizes)) {
        std::memcpy(d.buffer.get(), &size, sizeof size);
    }
    if (raw_size) std::memcpy(d.buffer.get(), &raw, sizeof raw);
    // Keep the ray-traced reference cheap: at most 4 rays per pixel (values outside the range stay invalid). A 0.1
    // struct has no REFERENCE block: its rays read as the default 256, cheap enough at these sizes.
    const size_t rays_offset = offsetof(obscura_settings, reference) + offsetof(obscura_reference_settings, rays);
    if (d.method() == OBSCURA_METHOD_REFERENCE && rays_offset + 4 <= size) {
        unsigned char* field = reinterpret_cast<unsigned char*>(settings) + rays_offset;
        int32_t rays;
        std::memcpy(&rays, field, sizeof rays);
        if (rays == 0 || (rays > 4 && rays <= 65536)) rays = 1 + (rays & 3);
        std::memcpy(field, &rays, sizeof rays);
    }
    return d;
}

// obscura_resolve_settings without a context, into a buffer of the struct's size.
int32_t resolve_status_of(const DecodedSettings& settings) {
    SettingsBuffer out(0, settings.buffer.size());
    return status_code(obscura_resolve_settings(nullptr, settings.get(), out.get()));
}

// obscura_get_last_error(NULL) belongs to the calls made without a context: one made with the context must leave it.
class NoContextMessage {
public:
    NoContextMessage() : before_(obscura_get_last_error(nullptr)) {}
    void check(const char* call) const {
        FUZZ_CHECK(before_ == obscura_get_last_error(nullptr),
                   "%s, made with a context, changed obscura_get_last_error(NULL) from \"%s\" to \"%s\"", call,
                   before_.c_str(), obscura_get_last_error(nullptr));
    }

private:
    std::string before_;
};

void perspective(float m[16], double fovy_degrees, double aspect, double n, double f, bool infinite, bool reversed,
                 bool zero_to_one) {
    std::memset(m, 0, 16 * sizeof(float));
    const double t = std::tan(0.5 * fovy_degrees * M_PI / 180.0);
    m[0] = float(1.0 / (t * aspect));
    m[5] = float(1.0 / t);
    m[11] = -1.0f;
    if (reversed) {  // [0, 1] clip depth: near -> 1, far -> 0
        m[10] = infinite ? 0.0f : float(n / (f - n));
        m[14] = infinite ? float(n) : float(f * n / (f - n));
    } else if (zero_to_one) {
        m[10] = infinite ? -1.0f : float(-f / (f - n));
        m[14] = infinite ? float(-n) : float(-f * n / (f - n));
    } else {
        m[10] = infinite ? -1.0f : float(-(f + n) / (f - n));
        m[14] = infinite ? float(-2.0 * n) : float(-2.0 * f * n / (f - n));
    }
}

void orthographic(float m[16], double half_width, double half_height, double n, double f, bool reversed,
                  bool zero_to_one) {
    std::memset(m, 0, 16 * sizeof(float));
    m[0] = float(1.0 / half_width);
    m[5] = float(1.0 / half_height);
    m[15] = 1.0f;
    if (reversed) {
        m[10] = float(1.0 / (f - n));
        m[14] = float(f / (f - n));
    } else if (zero_to_one) {
        m[10] = float(-1.0 / (f - n));
        m[14] = float(-n / (f - n));
    } else {
        m[10] = float(-2.0 / (f - n));
        m[14] = float(-(f + n) / (f - n));
    }
}

float special_float(uint8_t selector, Reader& in) {
    switch (selector % 8) {
        case 0: return std::numeric_limits<float>::quiet_NaN();
        case 1: return std::numeric_limits<float>::infinity();
        case 2: return -std::numeric_limits<float>::infinity();
        case 3: return 0.0f;
        case 4: return std::numeric_limits<float>::denorm_min();
        case 5: return std::numeric_limits<float>::max();
        case 6: return -1.0f;
        default: return in.f32();
    }
}

struct DecodedInput {
    obscura_input input;
    const DepthEntry* depth;
    const NormalEntry* normals;
    // Every field was decoded from a valid choice (no raw size, rect, enum, projection or units): the fields alone
    // (stage 1) pass, whatever the textures they name.
    bool fields_valid = true;
};

DecodedInput decode_input(Reader& in) {
    const Pools& pools = g_fixture->pools;
    DecodedInput d;
    obscura_input& input = d.input;
    std::memset(&input, 0, sizeof input);
    d.depth = &pools.depth[in.index(uint32_t(pools.depth.size()))];
    const uint8_t flags = in.u8();
    input.struct_size = (flags & 15) == 15 ? in.u32() : uint32_t(sizeof input);
    input.depth_texture = d.depth->name;

    // Depth kind: mostly what the texture holds, sometimes the other one, rarely any int.
    const uint8_t kind = in.u8();
    int32_t depth_kind = d.depth->kind >= 0 ? d.depth->kind : OBSCURA_DEPTH_HARDWARE;
    if (kind >= 200) depth_kind = kind >= 245 ? in.i32() : int32_t(kind & 1);
    store_raw(&input.depth_kind, depth_kind);

    // Size: the texture's, or raw ints.
    if (kind >= 245) d.fields_valid = false;  // a raw int (200-244: HARDWARE or LINEAR_VIEW, maybe the wrong one)
    input.depth_width = d.depth->width;
    input.depth_height = d.depth->height;
    if (flags & 0x10) {
        d.fields_valid = false;
        input.depth_width = in.i32();
        input.depth_height = in.i32();
    }
    // Output rectangle: zero (whole texture), one inside the texture, small ints, or raw ints.
    switch ((flags >> 5) & 3) {
        case 0: break;
        case 1: {
            const int w = d.depth->width > 0 ? d.depth->width : kDepthWidth;
            const int h = d.depth->height > 0 ? d.depth->height : kDepthHeight;
            input.output_rect.x = in.u8() % w;
            input.output_rect.y = in.u8() % h;
            input.output_rect.width = 1 + in.u8() % (w - input.output_rect.x);
            input.output_rect.height = 1 + in.u8() % (h - input.output_rect.y);
            break;
        }
        case 2:
            input.output_rect = {int8_t(in.u8()), int8_t(in.u8()), int8_t(in.u8()), int8_t(in.u8())};
            d.fields_valid = false;
            break;
        default:
            input.output_rect = {in.i32(), in.i32(), in.i32(), in.i32()};
            d.fields_valid = false;
            break;
    }

    // Projection: a valid perspective or orthographic matrix of any depth convention, then perturbed; or raw.
    const uint8_t projection = in.u8();
    const double aspect = double(kDepthWidth) / kDepthHeight;
    const bool reversed = projection & 0x10, infinite = projection & 0x40;
    const bool zero_to_one = reversed || (projection & 0x20);
    const double n = 0.01 * (1 + in.u8()), f = n * (1.5 + in.u8());
    if ((projection & 7) < 5) {
        perspective(input.projection, 10.0 + 160.0 * in.u8() / 255.0, aspect, n, f, infinite, reversed, zero_to_one);
        if (projection & 0x80) {  // off-centre
            input.projection[8] = float(int8_t(in.u8())) / 64.0f;
            input.projection[9] = float(int8_t(in.u8())) / 64.0f;
        }
    } else if ((projection & 7) < 7) {
        const double half_width = 0.5 + in.u8() / 16.0;
        const double half_height = (0.5 + in.u8() / 16.0) / aspect;
        orthographic(input.projection, half_width, half_height, n, f, reversed, zero_to_one);
        if (projection & 0x80) {
            input.projection[12] = float(int8_t(in.u8())) / 64.0f;
            input.projection[13] = float(int8_t(in.u8())) / 64.0f;
        }
    } else {
        for (float& value : input.projection) value = in.f32();
        d.fields_valid = false;
    }
    store_raw(&input.clip_depth, zero_to_one ? OBSCURA_CLIP_DEPTH_ZERO_TO_ONE : OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    const int perturbations = in.u8() % 4;
    if (perturbations) d.fields_valid = false;
    for (int i = 0; i < perturbations; ++i) {
        float& value = input.projection[in.u8() % 16];
        const uint8_t how = in.u8();
        if (how < 128) value *= 1.0f + float(int8_t(in.u8())) / 256.0f;  // a little off
        else value = special_float(how, in);
    }
    const uint8_t layout = in.u8();
    if (layout >= 160 && !(layout >= 176 && layout < 192)) d.fields_valid = false;
    if (layout >= 192) {  // given row-major: transposed, with the layout said (or any int)
        float transposed[16];
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) transposed[c * 4 + r] = input.projection[r * 4 + c];
        std::memcpy(input.projection, transposed, sizeof transposed);
        store_raw(&input.projection_layout, layout >= 250 ? in.i32() : int32_t(layout & 1));
    }
    if (layout >= 160 && layout < 176) store_raw(&input.clip_depth, in.i32());

    // Units: default, a plausible scale, or any float.
    const uint8_t units = in.u8();
    if (units >= 224) d.fields_valid = false;
    input.meters_to_view_units = units < 128   ? 0.0f
                                 : units < 224 ? 0.01f * float(1 + units % 96)
                                               : special_float(units, in);

    const uint8_t normals = in.u8();
    d.normals = &pools.normals[normals < 160 ? 0 : in.index(uint32_t(pools.normals.size()))];
    input.normal_texture = d.normals->name;
    return d;
}

struct DecodedOutput {
    obscura_output output;
    const OutputEntry* target;
    bool fields_valid = true;  // blend, debug view and position decoded from valid choices (stage 1 passes)
};

DecodedOutput decode_output(Reader& in) {
    const Pools& pools = g_fixture->pools;
    DecodedOutput d;
    obscura_output& output = d.output;
    std::memset(&output, 0, sizeof output);
    d.target = &pools.outputs[in.index(uint32_t(pools.outputs.size()))];
    const uint8_t flags = in.u8();
    output.struct_size = (flags & 15) == 15 ? in.u32() : uint32_t(sizeof output);
    output.texture = d.target->texture;
    output.framebuffer = d.target->framebuffer;
    if ((flags & 0x30) == 0x30 && output.texture != 0) {  // both names given: the texture wins
        output.framebuffer = pools.any_framebuffer;
    }
    const uint8_t position = in.u8();
    if (position >= 240) d.fields_valid = false;
    if (position >= 160) {
        output.x = position >= 240 ? in.i32() : in.u8() % 8;
        output.y = position >= 240 ? in.i32() : in.u8() % 8;
    }
    const uint8_t blend = in.u8();
    if (blend >= 250) d.fields_valid = false;
    store_raw(&output.blend, blend < 250 ? int32_t(blend & 1) : in.i32());
    const uint8_t view = in.u8();
    if (view >= 250) d.fields_valid = false;
    store_raw(&output.debug_view, view < 160 ? 0 : view < 250 ? int32_t(view % 5) : in.i32());
    return d;
}

// ---- Operations --------------------------------------------------------------------------------------------------

// Statuses a render of host-made structs may return here (a GL 4.3 context that is current and never lost, every
// method available): anything else (GL_ERROR from a pass, SHADER_COMPILE_FAILED, OUT_OF_MEMORY at these sizes,
// INTERNAL_ERROR, CONTEXT_LOST ...) is a bug.
bool render_status_allowed(int32_t status, bool host_error_pending) {
    switch (status) {
        case OBSCURA_STATUS_OK: case OBSCURA_STATUS_NULL_ARGUMENT: case OBSCURA_STATUS_INVALID_STRUCT_SIZE:
        case OBSCURA_STATUS_INVALID_SIZE: case OBSCURA_STATUS_INVALID_RECT: case OBSCURA_STATUS_INVALID_TEXTURE:
        case OBSCURA_STATUS_UNSUPPORTED_FORMAT: case OBSCURA_STATUS_INVALID_PROJECTION:
        case OBSCURA_STATUS_PROJECTION_TRANSPOSED: case OBSCURA_STATUS_INVALID_SETTING:
        case OBSCURA_STATUS_INVALID_ENUM:
        case OBSCURA_STATUS_INVALID_FRAMEBUFFER:
            return true;
        case OBSCURA_STATUS_HOST_GL_ERROR: return host_error_pending;
        default: return false;
    }
}

// What obscura_render may answer from the fields alone (stage 1, before it looks at GL: the struct sizes, the
// settings, the input and output fields), and so before WRONG_GL_CONTEXT or HOST_GL_ERROR.
bool stage_one_status(int32_t status) {
    switch (status) {
        case OBSCURA_STATUS_INVALID_STRUCT_SIZE: case OBSCURA_STATUS_INVALID_SETTING: case OBSCURA_STATUS_INVALID_ENUM:
        case OBSCURA_STATUS_INVALID_SIZE: case OBSCURA_STATUS_INVALID_RECT: case OBSCURA_STATUS_INVALID_PROJECTION:
        case OBSCURA_STATUS_PROJECTION_TRANSPOSED:
            return true;
        default: return false;
    }
}

// What a render's arguments promise about stage 1: known sizes (settings: any released size) and settings that
// resolve; `passes`: also fields decoded from valid choices, so stage 1 must pass.
struct StageOne {
    bool sizes_valid = false;
    int32_t resolve_status = -1;
    bool passes = false;
};
StageOne stage_one(const DecodedInput& input, const DecodedOutput& output, const DecodedSettings& settings) {
    StageOne s;
    // The decoders never set the fields past the 0.4 layouts, so those sizes render as today's do.
    s.sizes_valid = is_released_input_size(input.input.struct_size) &&
                    is_released_output_size(output.output.struct_size) &&
                    is_released_settings_size(settings.struct_size());
    s.resolve_status = resolve_status_of(settings);
    s.passes = s.sizes_valid && s.resolve_status == kOk && input.fields_valid && output.fields_valid;
    return s;
}

std::string describe(const DecodedInput& in, const DecodedOutput& out, const DecodedSettings& settings) {
    char text[1024];
    std::snprintf(text, sizeof text,
                  "obscura_render: depth %s (size %dx%d, kind %d, rect %d,%d %dx%d), normals %s, output %s at (%d, %d) "
                  "blend %d view %d, settings method %d struct_size %u",
                  in.depth->label, in.input.depth_width, in.input.depth_height, load_raw(in.input.depth_kind),
                  in.input.output_rect.x, in.input.output_rect.y, in.input.output_rect.width,
                  in.input.output_rect.height, in.normals->label, out.target->label, out.output.x, out.output.y,
                  load_raw(out.output.blend), load_raw(out.output.debug_view), settings.method(),
                  settings.struct_size());
    return text;
}

// The visible result of a successful render into the RGBA16F target: finite and within [0, 1] (every debug view
// is scaled into [0, 1] too; MULTIPLY keeps [0, 1] contents within it).
void check_float_result(const DecodedInput& in, const DecodedOutput& out) {
    if (!out.target->read_back || out.output.texture != out.target->texture) return;
    const int w = out.target->width, h = out.target->height;
    std::vector<float> rgba(size_t(w) * size_t(h) * 4);
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_2D, out.target->texture);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
    glBindTexture(GL_TEXTURE_2D, GLuint(g_fixture->sentinels.texture_2d[7]));
    glActiveTexture(GLenum(g_fixture->sentinels.active_texture));
    obscura_rect rect = in.input.output_rect;
    if (rect.width == 0 && rect.height == 0 && rect.x == 0 && rect.y == 0) {
        rect = {0, 0, in.input.depth_width, in.input.depth_height};
    }
    for (int y = 0; y < rect.height; ++y) {
        for (int x = 0; x < rect.width; ++x) {
            const int tx = out.output.x + x, ty = out.output.y + y;
            const float value = rgba[(size_t(ty) * size_t(w) + size_t(tx)) * 4];
            FUZZ_CHECK(std::isfinite(value) && value >= 0.0f && value <= 1.0f,
                       "a successful render wrote %g at (%d, %d) of the RGBA16F target (debug view %d)", double(value),
                       tx, ty, load_raw(out.output.debug_view));
        }
    }
}

void op_render(Reader& in, bool inject_host_error) {
    Fixture& fx = *g_fixture;
    const DecodedSettings settings = decode_settings(in);
    const DecodedInput input = decode_input(in);
    const DecodedOutput output = decode_output(in);
    const std::string what = describe(input, output, settings);
    obscura_fuzz::set_failure_context(what);

    const NoContextMessage message;
    if (inject_host_error) glEnable(0xBAD);  // GL_INVALID_ENUM, pending when the SDK is called
    const int log_before = fx.log.count;
    const int32_t status = status_code(obscura_render(fx.context, &input.input, settings.get(), &output.output));
    if (inject_host_error && status != OBSCURA_STATUS_HOST_GL_ERROR) {
        // Refused on its fields before it looked at GL: the error is still the host's, and nothing else is pending.
        const GLenum pending = glGetError();
        GLenum more = GL_NO_ERROR;
        while (GLenum error = glGetError()) more = error;
        FUZZ_CHECK(pending == GL_INVALID_ENUM && more == GL_NO_ERROR,
                   "obscura_render refused (%s) with a host GL error pending, which is now %s (then %s)",
                   fuzz_status_string(status), gl_error_name(pending), gl_error_name(more));
    }
    message.check("obscura_render");
    const StageOne stage = stage_one(input, output, settings);
    if (inject_host_error) {
        FUZZ_CHECK(status == OBSCURA_STATUS_HOST_GL_ERROR || stage_one_status(status),
                   "obscura_render with a host GL error pending returned %s, neither HOST_GL_ERROR nor a field error",
                   fuzz_status_string(status));
        FUZZ_CHECK(status != OBSCURA_STATUS_HOST_GL_ERROR || (stage.sizes_valid && stage.resolve_status == kOk),
                   "obscura_render reported the host GL error before its sizes or settings (resolve: %s)",
                   fuzz_status_string(stage.resolve_status));
        FUZZ_CHECK(!stage.passes || status == OBSCURA_STATUS_HOST_GL_ERROR,
                   "obscura_render with a host GL error pending and valid fields returned %s, not HOST_GL_ERROR",
                   fuzz_status_string(status));
    }
    count_status(0, status, what, fx.context);
    check_after_call("obscura_render", status, log_before, true);
    FUZZ_CHECK(render_status_allowed(status, inject_host_error), "obscura_render returned %s (\"%s\")",
               fuzz_status_string(status), obscura_get_last_error(fx.context));

    // Settings the SDK refuses make the render fail the same way (after the struct sizes, before the host state).
    FUZZ_CHECK(!stage.sizes_valid || stage.resolve_status == kOk || status == stage.resolve_status,
               "obscura_render returned %s for settings that resolve to %s", fuzz_status_string(status),
               fuzz_status_string(stage.resolve_status));
    FUZZ_CHECK(status != kOk || stage.sizes_valid, "obscura_render accepted struct sizes %u / %u / %u",
               input.input.struct_size, output.output.struct_size, settings.struct_size());
    // A buffer's or a deleted texture's number may have become a texture since (GL reuses names, the SDK's own
    // textures included): then nothing is known about it.
    const bool names_known = !(input.depth->not_a_texture && glIsTexture(input.depth->name)) &&
                             !(input.normals->not_a_texture && glIsTexture(input.normals->name)) &&
                             !(output.target->not_a_texture && glIsTexture(output.target->texture));
    if (status == kOk && names_known) {
        // Success needs a usable depth texture of the kind given, normals that fit, and a usable target.
        const int32_t kind = load_raw(input.input.depth_kind);
        FUZZ_CHECK(input.depth->kind >= 0 && kind == input.depth->kind, "obscura_render accepted depth %s as kind %d",
                   input.depth->label, kind);
        const bool normals_fit = input.normals->supported && input.normals->width == input.depth->width &&
                                 input.normals->height == input.depth->height;
        FUZZ_CHECK(input.normals->name == 0 || normals_fit,
                   "obscura_render accepted normals %s with depth %s", input.normals->label, input.depth->label);
        FUZZ_CHECK(output.target->usable, "obscura_render accepted output %s", output.target->label);
        FUZZ_CHECK(input.input.depth_width == input.depth->width && input.input.depth_height == input.depth->height,
                   "obscura_render accepted size %dx%d for the %s", input.input.depth_width, input.input.depth_height,
                   input.depth->label);
        check_float_result(input, output);
    }
    if (status == kOk) {
        uint64_t memory = 0;
        FUZZ_CHECK(obscura_get_memory_usage(fx.context, &memory) == OBSCURA_OK && memory > fx.baseline_memory,
                   "after a successful render the context reports %llu bytes (baseline %llu)",
                   (unsigned long long)memory, (unsigned long long)fx.baseline_memory);
    }
}

void op_prepare(Reader& in) {
    Fixture& fx = *g_fixture;
    const DecodedSettings settings = decode_settings(in);
    int32_t width = 0, height = 0;
    const uint8_t mode = in.u8();
    auto size = [&](uint8_t m) -> int32_t {
        switch (m % 6) {
            case 0: case 1: case 2: return 1 + in.u8() % 64;                       // small
            case 3: return -int32_t(in.u8());                                     // zero or negative
            case 4: return fx.max_texture_size + 1 + in.u8();                     // just too large
            default: return in.i32() < 0 ? std::numeric_limits<int32_t>::min() : std::numeric_limits<int32_t>::max();
        }
    };
    width = size(mode);
    height = size(mode >> 4);
    // Never a valid large size: it would allocate gigabytes.
    if (width > 64 && width <= fx.max_texture_size) width = 64;
    if (height > 64 && height <= fx.max_texture_size) height = 64;
    char what[160];
    std::snprintf(what, sizeof what, "obscura_prepare(%d, %d) with settings method %d struct_size %u", width, height,
                  settings.method(), settings.struct_size());
    obscura_fuzz::set_failure_context(what);
    const NoContextMessage message;
    const int log_before = fx.log.count;
    const int32_t status = status_code(obscura_prepare(fx.context, width, height, settings.get()));
    message.check("obscura_prepare");
    count_status(1, status, what, fx.context);
    check_after_call("obscura_prepare", status, log_before, true);
    const bool size_ok = width > 0 && height > 0 && width <= fx.max_texture_size && height <= fx.max_texture_size;
    FUZZ_CHECK(status == kOk || status == OBSCURA_STATUS_INVALID_SIZE || status == OBSCURA_STATUS_INVALID_SETTING ||
                   status == OBSCURA_STATUS_INVALID_ENUM || status == OBSCURA_STATUS_INVALID_STRUCT_SIZE,
               "%s returned %s (\"%s\")", what, fuzz_status_string(status), obscura_get_last_error(fx.context));
    FUZZ_CHECK(size_ok || status != kOk, "%s accepted the size", what);
    const int32_t resolve_status = resolve_status_of(settings);
    FUZZ_CHECK(resolve_status == kOk || status == resolve_status, "%s returned %s for settings that resolve to %s",
               what, fuzz_status_string(status), fuzz_status_string(resolve_status));
    FUZZ_CHECK(!(resolve_status == kOk && size_ok) || status == kOk, "%s failed (%s) with valid settings and size: %s",
               what, fuzz_status_string(status), obscura_get_last_error(fx.context));
}

void op_release() {
    Fixture& fx = *g_fixture;
    obscura_fuzz::set_failure_context("obscura_release_resources");
    obscura_release_resources(fx.context);
    check_after_call("obscura_release_resources", kOk, fx.log.count, false);
    uint64_t memory = 0;
    FUZZ_CHECK(obscura_get_memory_usage(fx.context, &memory) == OBSCURA_OK && memory == fx.baseline_memory,
               "after obscura_release_resources the context still reports %llu bytes (%llu right after creation)",
               (unsigned long long)memory, (unsigned long long)fx.baseline_memory);
}

void op_queries(Reader& in) {
    Fixture& fx = *g_fixture;
    obscura_fuzz::set_failure_context("obscura_get_timings / obscura_get_memory_usage");
    obscura_timing timings[16];
    const uint32_t capacity = in.u8() % 17;
    uint32_t count = 12345;
    uint64_t frame = 0;
    obscura_timing* out = capacity ? timings : nullptr;
    int32_t status = status_code(obscura_get_timings(fx.context, out, capacity, &count, &frame));
    check_after_call("obscura_get_timings", status, fx.log.count, false);
    FUZZ_CHECK(status == kOk, "obscura_get_timings returned %s", fuzz_status_string(status));
    FUZZ_CHECK(count <= 64, "obscura_get_timings reports %u timings", count);
    FUZZ_CHECK(frame >= fx.last_frame_index, "the timings' frame index went back from %llu to %llu",
               (unsigned long long)fx.last_frame_index, (unsigned long long)frame);
    FUZZ_CHECK((frame == 0) == (count == 0), "timings: %u entries for frame %llu", count, (unsigned long long)frame);
    fx.last_frame_index = frame;
    for (uint32_t i = 0; i < count && i < capacity; ++i) {
        FUZZ_CHECK(timings[i].label != nullptr && timings[i].label[0] != '\0', "timing %u has no label", i);
        FUZZ_CHECK(std::isfinite(timings[i].milliseconds) && timings[i].milliseconds >= 0.0, "timing %s is %g ms",
                   timings[i].label, timings[i].milliseconds);
        FUZZ_CHECK(i != 0 || std::strcmp(timings[0].label, "total") == 0, "the first timing is \"%s\", not \"total\"",
                   timings[0].label);
    }
    status = status_code(obscura_get_timings(fx.context, nullptr, 1 + capacity, &count, nullptr));
    FUZZ_CHECK(status == OBSCURA_STATUS_NULL_ARGUMENT, "obscura_get_timings(NULL, capacity > 0) returned %d", status);
    uint64_t memory = 0;
    status = status_code(obscura_get_memory_usage(fx.context, &memory));
    check_after_call("obscura_get_memory_usage", status, fx.log.count, false);
    FUZZ_CHECK(status == kOk && memory >= fx.baseline_memory && memory < (uint64_t(512) << 20),
               "obscura_get_memory_usage returned %s, %llu bytes", fuzz_status_string(status),
               (unsigned long long)memory);
}

// obscura_resolve_settings with the context: failures are reported on it like every other call.
void op_resolve_with_context(Reader& in) {
    Fixture& fx = *g_fixture;
    const DecodedSettings settings = decode_settings(in);
    obscura_fuzz::set_failure_context("obscura_resolve_settings with the context");
    SettingsBuffer out(0x5A, settings.buffer.size());
    const NoContextMessage message;
    const int log_before = fx.log.count;
    const int32_t status = status_code(obscura_resolve_settings(fx.context, settings.get(), out.get()));
    message.check("obscura_resolve_settings");
    check_after_call("obscura_resolve_settings", status, log_before, true);
    // The same answer and bytes as without a context, but for what the context derives for its renderer: LSAO's
    // segment_steps, 0 ("the renderer decides") without one, -1 (whole lines, CPU renderers) or 128 (GPUs) with it.
    SettingsBuffer out_without(0x5A, settings.buffer.size());
    const int32_t status_without = status_code(obscura_resolve_settings(nullptr, settings.get(), out_without.get()));
    const size_t segment_steps = offsetof(obscura_settings, lsao) + offsetof(obscura_lsao_settings, segment_steps);
    if (status == kOk && status_without == kOk && out.size() >= segment_steps + sizeof(int32_t)) {
        int32_t with_context = 0, without_context = 0;
        std::memcpy(&with_context, out.bytes() + segment_steps, sizeof with_context);
        std::memcpy(&without_context, out_without.bytes() + segment_steps, sizeof without_context);
        if (without_context == 0) {
            FUZZ_CHECK(with_context == 128 || (with_context == -1 && !fx.gpu_code_paths),
                       "obscura_resolve_settings with the %s context derived lsao.segment_steps = %d",
                       fx.gpu_code_paths ? "GPU code paths'" : "default", int(with_context));
            std::memcpy(out.get_bytes() + segment_steps, &without_context, sizeof without_context);
        }
    }
    FUZZ_CHECK(status == status_without && out == out_without,
               "obscura_resolve_settings with the context returned %s (or other bytes), without one %s",
               fuzz_status_string(status), fuzz_status_string(status_without));
}

// A call while another GL context is current: WRONG_GL_CONTEXT, and nothing done in either context.
void op_wrong_context(Reader& in) {
    Fixture& fx = *g_fixture;
    const DecodedSettings settings = decode_settings(in);
    const DecodedInput input = decode_input(in);
    const DecodedOutput output = decode_output(in);
    const bool prepare = in.u8() & 1;
    const std::string what = std::string(prepare ? "obscura_prepare(16, 12)" : describe(input, output, settings)) +
                             ", with another GL context current";
    obscura_fuzz::set_failure_context(what);
    fx.other_gl->make_current();
    const NoContextMessage message;
    const int log_before = fx.log.count;
    const int32_t status =
        status_code(prepare ? obscura_prepare(fx.context, kDepthWidth, kDepthHeight, settings.get())
                            : obscura_render(fx.context, &input.input, settings.get(), &output.output));
    const GLenum other_error = glGetError();
    fx.gl->make_current();
    message.check(prepare ? "obscura_prepare" : "obscura_render");
    FUZZ_CHECK(other_error == GL_NO_ERROR, "%s left %s in the other GL context", what.c_str(),
               gl_error_name(other_error));
    check_after_call(prepare ? "obscura_prepare" : "obscura_render", status, log_before, true);
    if (prepare) {
        // Settings first (then the size, valid here), then the GL context.
        const int32_t resolve_status = resolve_status_of(settings);
        FUZZ_CHECK(status == (resolve_status == kOk ? int32_t(OBSCURA_STATUS_WRONG_GL_CONTEXT) : resolve_status),
                   "%s returned %s (settings resolve to %s)", what.c_str(), fuzz_status_string(status),
                   fuzz_status_string(resolve_status));
        return;
    }
    // A render checks its fields (stage 1) before the GL context.
    const StageOne stage = stage_one(input, output, settings);
    FUZZ_CHECK(status != kOk, "%s returned OK", what.c_str());
    FUZZ_CHECK(status == OBSCURA_STATUS_WRONG_GL_CONTEXT || stage_one_status(status),
               "%s returned %s, neither WRONG_GL_CONTEXT nor a field error", what.c_str(), fuzz_status_string(status));
    FUZZ_CHECK(!stage.passes || status == OBSCURA_STATUS_WRONG_GL_CONTEXT, "%s returned %s, not WRONG_GL_CONTEXT",
               what.c_str(), fuzz_status_string(status));
    FUZZ_CHECK(status != OBSCURA_STATUS_WRONG_GL_CONTEXT || (stage.sizes_valid && stage.resolve_status == kOk),
               "%s reported WRONG_GL_CONTEXT before its sizes or settings (resolve: %s)", what.c_str(),
               fuzz_status_string(stage.resolve_status));
    FUZZ_CHECK(!stage.sizes_valid || stage.resolve_status == kOk || status == stage.resolve_status,
               "%s returned %s for settings that resolve to %s", what.c_str(), fuzz_status_string(status),
               fuzz_status_string(stage.resolve_status));
}

// NULL arguments on a live context: NULL_ARGUMENT with a message, nothing touched.
// (obscura_get_setting_infos, obscura_get_timings and obscura_get_memory_usage given NULL recorded no message for
// obscura_get_last_error(NULL); fixed, the tolerance stays off: settings_fuzzer.cpp, kTolerateUnrecordedMessages.)
constexpr bool kTolerateUnrecordedMessages = false;

// A call without a context (or given a NULL one): its message for obscura_get_last_error(NULL), "" after a success.
void check_no_context_message(const char* call, int32_t status, bool recorded = true) {
    const char* message = obscura_get_last_error(nullptr);
    FUZZ_CHECK(message != nullptr, "obscura_get_last_error(NULL) returned NULL after %s", call);
    if (!recorded && kTolerateUnrecordedMessages) return;
    FUZZ_CHECK((status == kOk) == (message[0] == '\0'),
               "%s returned %s but obscura_get_last_error(NULL) is \"%s\"", call, fuzz_status_string(status),
               message);
}

// A call without a context that succeeds (so that the next one's message shows).
void succeed_without_context() {
    SettingsBuffer defaults(0, sizeof(obscura_settings));
    const int32_t status = fuzz_default_settings(OBSCURA_METHOD_SAO, defaults.get());
    check_no_context_message("obscura_default_settings", status);
    FUZZ_CHECK(status == kOk, "obscura_default_settings(SAO) returned %s", fuzz_status_string(status));
}

// NULL arguments on a live context: NULL_ARGUMENT with a message, nothing touched. Calls given a NULL context
// leave their message for obscura_get_last_error(NULL).
void op_null_arguments(Reader& in) {
    Fixture& fx = *g_fixture;
    obscura_fuzz::set_failure_context("NULL arguments");
    const DecodedSettings settings = decode_settings(in);
    obscura_input input;
    std::memset(&input, 0, sizeof input);
    input.struct_size = sizeof input;
    obscura_output output;
    std::memset(&output, 0, sizeof output);
    output.struct_size = sizeof output;
    const uint8_t which = in.u8() % 4;
    const NoContextMessage message;
    const int log_before = fx.log.count;
    int32_t status = 0;
    switch (which) {
        case 0: status = status_code(obscura_render(fx.context, nullptr, settings.get(), &output)); break;
        case 1: status = status_code(obscura_render(fx.context, &input, nullptr, &output)); break;
        case 2: status = status_code(obscura_render(fx.context, &input, settings.get(), nullptr)); break;
        default: status = status_code(obscura_prepare(fx.context, 8, 8, nullptr)); break;
    }
    message.check("a call with a NULL argument");
    check_after_call("a call with a NULL argument", status, log_before, true);
    FUZZ_CHECK(status == OBSCURA_STATUS_NULL_ARGUMENT, "a call with a NULL argument returned %s",
               fuzz_status_string(status));

    succeed_without_context();
    status = status_code(obscura_render(nullptr, &input, settings.get(), &output));
    FUZZ_CHECK(status == OBSCURA_STATUS_NULL_ARGUMENT, "obscura_render(NULL context) returned %s",
               fuzz_status_string(status));
    check_no_context_message("obscura_render(NULL context)", status);
    succeed_without_context();
    status = status_code(obscura_prepare(nullptr, 8, 8, settings.get()));
    FUZZ_CHECK(status == OBSCURA_STATUS_NULL_ARGUMENT, "obscura_prepare(NULL context) returned %s",
               fuzz_status_string(status));
    check_no_context_message("obscura_prepare(NULL context)", status);
    succeed_without_context();
    uint32_t count = 0;
    status = status_code(obscura_get_timings(nullptr, nullptr, 0, &count, nullptr));
    FUZZ_CHECK(status == OBSCURA_STATUS_NULL_ARGUMENT, "obscura_get_timings(NULL context) returned %s",
               fuzz_status_string(status));
    check_no_context_message("obscura_get_timings(NULL context)", status, false);
    succeed_without_context();
    uint64_t bytes = 0;
    status = status_code(obscura_get_memory_usage(nullptr, &bytes));
    FUZZ_CHECK(status == OBSCURA_STATUS_NULL_ARGUMENT, "obscura_get_memory_usage(NULL context) returned %s",
               fuzz_status_string(status));
    check_no_context_message("obscura_get_memory_usage(NULL context)", status, false);
    obscura_release_resources(nullptr);  // a no-op
    // obscura_create_context refused before it looks at GL: its reason goes to obscura_get_last_error(NULL).
    succeed_without_context();
    obscura_context* created = reinterpret_cast<obscura_context*>(&count);
    status = status_code(obscura_create_context(nullptr, &created));
    FUZZ_CHECK(status == OBSCURA_STATUS_NULL_ARGUMENT && created == nullptr,
               "obscura_create_context(NULL desc) returned %s", fuzz_status_string(status));
    check_no_context_message("obscura_create_context(NULL desc)", status);
    succeed_without_context();
    obscura_context_desc desc;
    std::memset(&desc, 0, sizeof desc);
    desc.struct_size = sizeof desc + 4;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = &HeadlessGL::get_proc_address;
    status = status_code(obscura_create_context(&desc, &created));
    FUZZ_CHECK(status == OBSCURA_STATUS_INVALID_STRUCT_SIZE && created == nullptr,
               "obscura_create_context(struct_size + 4) returned %s", fuzz_status_string(status));
    check_no_context_message("obscura_create_context(struct_size + 4)", status);
    check_after_call("the calls without a context", kOk, fx.log.count, false);
}

void run_operation(uint8_t op, Reader& in) {
    g_fixture->select((op >> 4) & 1);
    switch (op % 16) {
        case 0: case 1: case 2: case 3: case 4: case 5: case 6: case 7: op_render(in, false); break;
        case 8: case 9: op_prepare(in); break;
        case 10: op_release(); break;
        case 11: op_queries(in); break;
        case 12: op_wrong_context(in); break;
        case 13: op_render(in, true); break;
        case 14: op_resolve_with_context(in); break;
        default: op_null_arguments(in); break;
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // The software renderer unless told otherwise (the ctest sets these too; OBSCURA_GPU keeps the machine's GL).
    if (!std::getenv("OBSCURA_GPU")) {
        setenv("EGL_PLATFORM", "surfaceless", 0);
        setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    }
    g_fixture = new Fixture();  // lives until exit, like the GL context
    Fixture& fx = *g_fixture;
    try {
        fx.gl = new HeadlessGL();
    } catch (const std::exception& error) {
        std::fprintf(stderr, "render_fuzzer: no GL 4.3 context: %s\n", error.what());
        std::exit(1);
    }
    std::fprintf(stderr, "render_fuzzer: %s\n", fx.gl->describe().c_str());
    obscura_context_desc desc;
    std::memset(&desc, 0, sizeof desc);
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = &HeadlessGL::get_proc_address;
    desc.log = &log_callback;
    desc.log_user_data = &fx.log;
    for (int i = 0; i < 2; ++i) {
        desc.flags = OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES | (i == 1 ? uint32_t(OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS) : 0u);
        Fixture::ContextState& state = fx.states[i];
        state.gpu_code_paths = i == 1;
        const int32_t status = status_code(obscura_create_context(&desc, &state.context));
        FUZZ_CHECK(status == kOk, "render_fuzzer setup: obscura_create_context returned %s", fuzz_status_string(status));
        FUZZ_CHECK(obscura_get_memory_usage(state.context, &state.baseline_memory) == OBSCURA_OK, "memory usage failed");
    }
    fx.selected = 0;
    fx.context = fx.states[0].context;
    fx.baseline_memory = fx.states[0].baseline_memory;
    fx.max_texture_size = get_integer(GL_MAX_TEXTURE_SIZE);
    fx.other_gl = new HeadlessGL();  // current now: switch back
    fx.gl->make_current();
    fx.pools = make_pools();
    GLenum error = glGetError();
    FUZZ_CHECK(error == GL_NO_ERROR, "render_fuzzer setup raised %s", gl_error_name(error));
    fx.sentinels = install_sentinels();
    error = glGetError();
    FUZZ_CHECK(error == GL_NO_ERROR, "render_fuzzer setup of the sentinels raised %s", gl_error_name(error));
    check_sentinels("render_fuzzer setup");
    const char* stats = std::getenv("OBSCURA_FUZZ_STATS");
    if (stats && std::strcmp(stats, "0") != 0) std::atexit(&print_stats);
    const char* trace = std::getenv("OBSCURA_FUZZ_TRACE");
    g_trace = trace && std::strcmp(trace, "0") != 0;
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Reader in(data, size);
    const int operations = 1 + in.u8() % 4;
    for (int i = 0; i < operations; ++i) run_operation(in.u8(), in);
    return 0;
}
