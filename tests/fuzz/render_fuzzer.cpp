// libFuzzer target for the per-frame API on a real GL context: obscura_render, obscura_prepare,
// obscura_release_resources, obscura_get_timings, obscura_get_memory_usage, obscura_resolve_settings with a
// context, obscura_create_view and obscura_destroy_view, fed with fuzzed input / output / settings structs that name
// host GL objects (and views) from fixed pools.
//
// LLVMFuzzerInitialize creates one headless GL 4.3 context (llvmpipe in CI), two obscura contexts with
// OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES, the second also with OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS (the shader variants
// GPUs run: shared-memory tiles, storage buffers, runs of one pixel, at the fuzzer's odd sizes), the pools
// (depth-like textures of every kind the SDK must accept or refuse, normals, output targets, motion vectors,
// bent-normal targets) and then binds sentinel objects (or sets non-default values) everywhere an SDK call may touch
// GL state.
// Each input is a short list of operations (see run_operation: the low 4 bits of an operation's byte pick it, bit 4
// the context it runs on, bit 5 adds the 0.5 per-frame fields to a render); after every call the fuzzer checks that
// the status is a known code and one this call may return, that a failure left a message (and went to the log),
// that glGetError() is GL_NO_ERROR, and that every sentinel binding is still in place. It traps otherwise.
// Settings structs come in every released size (0.1 ... this header's), each in a heap buffer of exactly that
// size (AddressSanitizer reports a read past the caller's struct); edits reach the method's rows and the shared ones
// (temporal accumulation, reduced resolution). A call refused on its fields (settings, input and output fields and
// the view: stage 1, no GL) must answer that before WRONG_GL_CONTEXT or HOST_GL_ERROR. The float targets (output and
// bent normals) are filled with a sentinel before each render: outside the result, and everywhere after a refusal, it
// must stay. A camera cut (OBSCURA_INPUT_FLAG_RESET_HISTORY) on a frame refused once its fields and view passed
// still drops the view's history (obscura.h, TEMPORAL ACCUMULATION): the view's next accepted frame in the same input
// (debug views aside) must equal that frame rendered with the flag through a view no fuzzed call names
// (check_frame_after_cut).
//
// Renders stay cheap: the depth textures are at most 16x12, REFERENCE traces at most 4 rays (a 0.1 struct, which
// has no REFERENCE block, its default 256), obscura_prepare gets either a size up to 64x64 or an invalid one (never
// a valid large size, which would allocate gigabytes).
// The context keeps its resources, compiled variants and views from one input to the next, like a host's does: a
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

// Motion vectors (obscura_input.motion_vector_texture) and bent normals (obscura_output.bent_normal_texture): textures
// of the formats each takes and others, and names that alias another field of the same frame (resolved when decoded).
enum class Alias { None, Output, Depth, Normals, Motion };
struct CompanionEntry {
    const char* label;
    GLuint name;
    int width, height;
    bool supported;              // a GL_TEXTURE_2D of a format the field takes (usable when its size fits)
    bool not_a_texture = false;  // a buffer's or a deleted texture's name
    bool read_back = false;      // a float RGBA bent-normal target whose texels a render is checked against
    Alias alias = Alias::None;   // the name of that field of the frame instead (0 there: none)
};

struct Pools {
    std::vector<DepthEntry> depth;
    std::vector<NormalEntry> normals;
    std::vector<OutputEntry> outputs;
    std::vector<CompanionEntry> motion, bent;
    GLuint stencil_mode_texture = 0;  // DEPTH24_STENCIL8 whose GL_DEPTH_STENCIL_TEXTURE_MODE the host set to stencil
    GLuint any_framebuffer = 0;       // a complete framebuffer, given beside an output texture
    GLuint any_framebuffer_texture = 0;  // its colour attachment 0
};

// RG motion vectors: small offsets in texels ("small"), offsets up to the texture's size and beyond ("large"), or
// NaN, infinities and huge values ("wild": they must not reach the AO).
GLuint make_motion(GLenum format, int width, int height, int pattern) {
    GLuint texture = make_color(format, width, height);
    const float wild[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(), 1e30f, -1e30f, std::numeric_limits<float>::max(),
                          std::numeric_limits<float>::denorm_min(), 0.0f, 0.5f};
    std::vector<float> rg(size_t(width) * size_t(height) * 2);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            float* v = &rg[(size_t(y) * size_t(width) + size_t(x)) * 2];
            if (pattern == 0) {
                v[0] = 0.25f * float(x % 3 - 1);
                v[1] = -0.5f * float(y % 2);
            } else if (pattern == 1) {
                v[0] = 1.5f * float(x - width / 2);
                v[1] = 2.0f * float(y - height / 2);
            } else {
                v[0] = wild[size_t(x + 3 * y) % (sizeof wild / sizeof wild[0])];
                v[1] = wild[size_t(2 * x + y) % (sizeof wild / sizeof wild[0])];
            }
        }
    }
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RG, GL_FLOAT, rg.data());
    return texture;
}

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
    p.any_framebuffer_texture = fb_texture;

    p.motion = {
        {"RG16F 16x12 (small)", make_motion(GL_RG16F, w, h, 0), w, h, true},
        {"RG32F 16x12 (large)", make_motion(GL_RG32F, w, h, 1), w, h, true},
        {"RG32F 16x12 (NaN, inf, 1e30)", make_motion(GL_RG32F, w, h, 2), w, h, true},
        {"RG16F 8x6", make_motion(GL_RG16F, 8, 6, 0), 8, 6, true},
        {"RG32F 33x5", make_motion(GL_RG32F, 33, 5, 1), 33, 5, true},
        {"RG16F 1x1", make_motion(GL_RG16F, 1, 1, 1), 1, 1, true},
        {"RG16F 7x9", make_motion(GL_RG16F, 7, 9, 0), 7, 9, true},
        {"RG8 16x12 (unsupported)", make_color(GL_RG8, w, h), w, h, false},
        {"RGBA16F 16x12 (unsupported)", make_color(GL_RGBA16F, w, h), w, h, false},
        {"R32F 16x12 (unsupported)", make_color(GL_R32F, w, h), w, h, false},
        {"the output texture", 0, 0, 0, false, false, false, Alias::Output},
        {"the depth texture", 0, 0, 0, false, false, false, Alias::Depth},
        {"the normal texture", 0, 0, 0, false, false, false, Alias::Normals},
        {"buffer object name", buffer, w, h, false, true},
        {"deleted texture name", deleted, w, h, false, true},
        {"R32F 3D texture", texture_3d, w, h, false},
        {"D32F 4x multisample texture", multisample, w, h, false},
    };
    p.bent = {
        {"RGBA16F 16x12", make_color(GL_RGBA16F, w, h), w, h, true, false, true},
        {"RGBA8 16x12", make_color(GL_RGBA8, w, h), w, h, true},
        {"RGBA32F 40x40", make_color(GL_RGBA32F, 40, 40), 40, 40, true, false, true},
        {"RGBA16F 8x6", make_color(GL_RGBA16F, 8, 6), 8, 6, true},
        {"RGBA8 1x1", make_color(GL_RGBA8, 1, 1), 1, 1, true},
        {"R8 16x12 (unsupported)", make_color(GL_R8, w, h), w, h, false},
        {"RG16F 16x12 (unsupported)", make_color(GL_RG16F, w, h), w, h, false},
        {"RGB8 16x12 (unsupported)", make_color(GL_RGB8, w, h), w, h, false},
        {"the output texture", 0, 0, 0, false, false, false, Alias::Output},
        {"the depth texture", 0, 0, 0, false, false, false, Alias::Depth},
        {"the normal texture", 0, 0, 0, false, false, false, Alias::Normals},
        {"the motion-vector texture", 0, 0, 0, false, false, false, Alias::Motion},
        // Usable, except beside the output framebuffer it is attached to.
        {"the RGBA8 texture of the output FBO", fb_texture, w, h, true},
        {"buffer object name", buffer, w, h, false, true},
        {"deleted texture name", deleted, w, h, false, true},
        {"D32F 4x multisample texture", multisample, w, h, false},
    };
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindTexture(GL_TEXTURE_3D, 0);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
    return p;
}

// ---- Sentinel state: host bindings the SDK must leave as it found them -----------------------------------------
// The same state as the GL tests' snapshot (tests/gl/gl_state_snapshot.cpp, which needs GoogleTest and is not built
// here), read through a fixed table of queries: program, active texture, every texture target, sampler and image
// unit (name, level, layering, layer, access, format) the SDK may touch and beyond, indexed and generic uniform and
// storage buffer bindings, the other buffer bindings (array, pixel pack / unpack, dispatch indirect, copy read /
// write, texture buffer), the vertex array, framebuffers with their read and draw buffers, renderbuffer, viewport,
// scissor box and test, blend, depth test, rasterizer discard, colour mask and the pixel store.

constexpr int kSentinelUnits = 8;

enum class QueryKind { Integer, Component, Enabled, Indexed, Indexed64, Unit };
struct StateQuery {
    std::string name;
    QueryKind kind;
    GLenum pname;
    GLuint index;  // the component, the indexed binding's index or the texture unit
};
using StateValues = std::vector<long long>;

std::vector<StateQuery> make_state_queries() {
    std::vector<StateQuery> q;
    auto integer = [&](const char* name, GLenum pname) { q.push_back({name, QueryKind::Integer, pname, 0}); };
    auto enabled = [&](const char* name, GLenum cap) { q.push_back({name, QueryKind::Enabled, cap, 0}); };
    integer("GL_ACTIVE_TEXTURE", GL_ACTIVE_TEXTURE);  // first: read_state restores it
    integer("GL_CURRENT_PROGRAM", GL_CURRENT_PROGRAM);
    integer("GL_DRAW_FRAMEBUFFER_BINDING", GL_DRAW_FRAMEBUFFER_BINDING);
    integer("GL_READ_FRAMEBUFFER_BINDING", GL_READ_FRAMEBUFFER_BINDING);
    integer("GL_READ_BUFFER (of the read framebuffer)", GL_READ_BUFFER);
    integer("GL_DRAW_BUFFER0 (of the draw framebuffer)", GL_DRAW_BUFFER0);
    integer("GL_RENDERBUFFER_BINDING", GL_RENDERBUFFER_BINDING);
    integer("GL_VERTEX_ARRAY_BINDING", GL_VERTEX_ARRAY_BINDING);
    integer("GL_ARRAY_BUFFER_BINDING", GL_ARRAY_BUFFER_BINDING);
    integer("GL_UNIFORM_BUFFER_BINDING", GL_UNIFORM_BUFFER_BINDING);
    integer("GL_SHADER_STORAGE_BUFFER_BINDING", GL_SHADER_STORAGE_BUFFER_BINDING);
    integer("GL_PIXEL_PACK_BUFFER_BINDING", GL_PIXEL_PACK_BUFFER_BINDING);
    integer("GL_PIXEL_UNPACK_BUFFER_BINDING", GL_PIXEL_UNPACK_BUFFER_BINDING);
    integer("GL_DISPATCH_INDIRECT_BUFFER_BINDING", GL_DISPATCH_INDIRECT_BUFFER_BINDING);
    integer("GL_COPY_READ_BUFFER_BINDING", GL_COPY_READ_BUFFER_BINDING);
    integer("GL_COPY_WRITE_BUFFER_BINDING", GL_COPY_WRITE_BUFFER_BINDING);
    integer("GL_TEXTURE_BUFFER (buffer binding)", GL_TEXTURE_BUFFER);
    integer("GL_PACK_ALIGNMENT", GL_PACK_ALIGNMENT);
    integer("GL_PACK_ROW_LENGTH", GL_PACK_ROW_LENGTH);
    integer("GL_PACK_SKIP_ROWS", GL_PACK_SKIP_ROWS);
    integer("GL_PACK_SKIP_PIXELS", GL_PACK_SKIP_PIXELS);
    integer("GL_UNPACK_ALIGNMENT", GL_UNPACK_ALIGNMENT);
    integer("GL_UNPACK_ROW_LENGTH", GL_UNPACK_ROW_LENGTH);
    integer("GL_UNPACK_SKIP_ROWS", GL_UNPACK_SKIP_ROWS);
    integer("GL_UNPACK_SKIP_PIXELS", GL_UNPACK_SKIP_PIXELS);
    integer("GL_UNPACK_IMAGE_HEIGHT", GL_UNPACK_IMAGE_HEIGHT);
    enabled("GL_SCISSOR_TEST", GL_SCISSOR_TEST);
    enabled("GL_RASTERIZER_DISCARD", GL_RASTERIZER_DISCARD);
    enabled("GL_BLEND", GL_BLEND);
    enabled("GL_DEPTH_TEST", GL_DEPTH_TEST);
    static const char* const kViewport[4] = {"GL_VIEWPORT x", "GL_VIEWPORT y", "GL_VIEWPORT width",
                                             "GL_VIEWPORT height"};
    static const char* const kScissor[4] = {"GL_SCISSOR_BOX x", "GL_SCISSOR_BOX y", "GL_SCISSOR_BOX width",
                                            "GL_SCISSOR_BOX height"};
    static const char* const kMask[4] = {"GL_COLOR_WRITEMASK red", "GL_COLOR_WRITEMASK green",
                                         "GL_COLOR_WRITEMASK blue", "GL_COLOR_WRITEMASK alpha"};
    for (GLuint c = 0; c < 4; ++c) {
        q.push_back({kViewport[c], QueryKind::Component, GL_VIEWPORT, c});
        q.push_back({kScissor[c], QueryKind::Component, GL_SCISSOR_BOX, c});
        q.push_back({kMask[c], QueryKind::Component, GL_COLOR_WRITEMASK, c});
    }
    const struct { GLenum binding, start, size; const char* name; } buffers[] = {
        {GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE, "uniform buffer"},
        {GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START, GL_SHADER_STORAGE_BUFFER_SIZE,
         "shader storage buffer"},
    };
    for (const auto& kind : buffers) {
        for (GLuint index = 0; index < 4; ++index) {
            const std::string at = std::string("indexed ") + kind.name + " " + std::to_string(index);
            q.push_back({at + " binding", QueryKind::Indexed, kind.binding, index});
            q.push_back({at + " start", QueryKind::Indexed64, kind.start, index});
            q.push_back({at + " size", QueryKind::Indexed64, kind.size, index});
        }
    }
    const std::pair<GLenum, const char*> images[] = {
        {GL_IMAGE_BINDING_NAME, "name"},       {GL_IMAGE_BINDING_LEVEL, "level"},
        {GL_IMAGE_BINDING_LAYERED, "layered"}, {GL_IMAGE_BINDING_LAYER, "layer"},
        {GL_IMAGE_BINDING_ACCESS, "access"},   {GL_IMAGE_BINDING_FORMAT, "format"},
    };
    for (GLuint unit = 0; unit < kSentinelUnits; ++unit) {
        for (const auto& [pname, name] : images) {
            q.push_back({"image unit " + std::to_string(unit) + " " + name, QueryKind::Indexed, pname, unit});
        }
    }
    const std::pair<GLenum, const char*> targets[] = {
        {GL_TEXTURE_BINDING_2D, "GL_TEXTURE_BINDING_2D"},
        {GL_TEXTURE_BINDING_2D_MULTISAMPLE, "GL_TEXTURE_BINDING_2D_MULTISAMPLE"},
        {GL_TEXTURE_BINDING_3D, "GL_TEXTURE_BINDING_3D"},
        {GL_TEXTURE_BINDING_2D_ARRAY, "GL_TEXTURE_BINDING_2D_ARRAY"},
        {GL_TEXTURE_BINDING_CUBE_MAP, "GL_TEXTURE_BINDING_CUBE_MAP"},
        {GL_TEXTURE_BINDING_BUFFER, "GL_TEXTURE_BINDING_BUFFER"},
        {GL_SAMPLER_BINDING, "GL_SAMPLER_BINDING"},
    };
    for (GLuint unit = 0; unit < kSentinelUnits; ++unit) {
        for (const auto& [pname, name] : targets) {
            q.push_back({std::string(name) + " of unit " + std::to_string(unit), QueryKind::Unit, pname, unit});
        }
    }
    return q;
}

GLint get_integer(GLenum pname) {
    GLint value = 0;
    glGetIntegerv(pname, &value);
    return value;
}

// Reads every query (switching the active unit for the per-unit ones, and switching it back).
StateValues read_state(const std::vector<StateQuery>& queries) {
    StateValues values;
    values.reserve(queries.size());
    const GLint active = get_integer(GL_ACTIVE_TEXTURE);
    GLint unit_set = active;
    for (const StateQuery& query : queries) {
        GLint value[4] = {};
        GLint64 value64 = 0;
        switch (query.kind) {
            case QueryKind::Integer: values.push_back(get_integer(query.pname)); break;
            case QueryKind::Component:
                glGetIntegerv(query.pname, value);
                values.push_back(value[query.index]);
                break;
            case QueryKind::Enabled: values.push_back(glIsEnabled(query.pname)); break;
            case QueryKind::Indexed:
                glGetIntegeri_v(query.pname, query.index, value);
                values.push_back(value[0]);
                break;
            case QueryKind::Indexed64:
                glGetInteger64i_v(query.pname, query.index, &value64);
                values.push_back(value64);
                break;
            case QueryKind::Unit:
                if (unit_set != GLint(GL_TEXTURE0 + query.index)) {
                    unit_set = GLint(GL_TEXTURE0 + query.index);
                    glActiveTexture(GLenum(unit_set));
                }
                values.push_back(get_integer(query.pname));
                break;
        }
    }
    if (unit_set != active) glActiveTexture(GLenum(active));
    return values;
}

// The fuzzer's own uploads and read-backs run with a neutral pixel store and no pixel buffer bound (the sentinels
// bind some); the host's values come back when the scope ends.
class NeutralPixelStore {
public:
    NeutralPixelStore() {
        for (size_t i = 0; i < kCount; ++i) saved_[i] = get_integer(kParams[i].pname);
        pack_buffer_ = get_integer(GL_PIXEL_PACK_BUFFER_BINDING);
        unpack_buffer_ = get_integer(GL_PIXEL_UNPACK_BUFFER_BINDING);
        for (const Param& p : kParams) glPixelStorei(p.pname, p.neutral);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    }
    ~NeutralPixelStore() {
        for (size_t i = 0; i < kCount; ++i) glPixelStorei(kParams[i].pname, saved_[i]);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(pack_buffer_));
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpack_buffer_));
    }
    NeutralPixelStore(const NeutralPixelStore&) = delete;
    NeutralPixelStore& operator=(const NeutralPixelStore&) = delete;

private:
    struct Param {
        GLenum pname;
        GLint neutral;
    };
    static constexpr size_t kCount = 9;
    static constexpr Param kParams[kCount] = {
        {GL_PACK_ALIGNMENT, 4},     {GL_PACK_ROW_LENGTH, 0},    {GL_PACK_SKIP_ROWS, 0},
        {GL_PACK_SKIP_PIXELS, 0},   {GL_UNPACK_ALIGNMENT, 4},   {GL_UNPACK_ROW_LENGTH, 0},
        {GL_UNPACK_SKIP_ROWS, 0},   {GL_UNPACK_SKIP_PIXELS, 0}, {GL_UNPACK_IMAGE_HEIGHT, 0},
    };
    GLint saved_[kCount] = {};
    GLint pack_buffer_ = 0, unpack_buffer_ = 0;
};

// Binds a sentinel object, or sets a value other than GL's default, at every place read_state reads: the SDK's units
// and more, so that a leak shows.
StateValues install_sentinels(const std::vector<StateQuery>& queries) {
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
    GLuint tex_r32f = make_color(GL_R32F, 4, 4);
    GLuint tex_ms = gen_texture(GL_TEXTURE_2D_MULTISAMPLE);
    glTexImage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, 2, GL_RGBA8, 4, 4, GL_TRUE);
    GLuint tex_3d = gen_texture(GL_TEXTURE_3D);
    glTexStorage3D(GL_TEXTURE_3D, 1, GL_RGBA8, 2, 2, 2);
    GLuint tex_array = gen_texture(GL_TEXTURE_2D_ARRAY);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 2, GL_RGBA8, 8, 8, 4);
    GLuint tex_cube = gen_texture(GL_TEXTURE_CUBE_MAP);
    glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_RGBA8, 4, 4);
    GLuint texel_buffer = make_buffer(GL_TEXTURE_BUFFER, 256);
    GLuint tex_buffer = gen_texture(GL_TEXTURE_BUFFER);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, texel_buffer);
    GLuint sampler = 0;
    glGenSamplers(1, &sampler);
    GLint ubo_alignment = get_integer(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT);
    GLint ssbo_alignment = get_integer(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT);
    GLuint ubo = make_buffer(GL_UNIFORM_BUFFER, 4096);
    GLuint ssbo = make_buffer(GL_SHADER_STORAGE_BUFFER, 4096);
    // Framebuffers with two colour attachments: the read one reads attachment 1, the draw one draws to it.
    GLuint draw_fb = make_framebuffer(make_color(GL_RGBA8, 4, 4), 0);
    GLuint read_fb = make_framebuffer(make_color(GL_RGBA8, 4, 4), 0);
    for (GLuint fb : {draw_fb, read_fb}) {
        glBindFramebuffer(GL_FRAMEBUFFER, fb);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, make_color(GL_RGBA8, 4, 4), 0);
        const GLenum attachment1 = GL_COLOR_ATTACHMENT1;
        if (fb == read_fb) glReadBuffer(attachment1);
        else glDrawBuffers(1, &attachment1);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    GLuint renderbuffer = 0;
    glGenRenderbuffers(1, &renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 4, 4);
    GLuint unpack_buffer = make_buffer(GL_PIXEL_UNPACK_BUFFER, 64);
    GLuint pack_buffer = make_buffer(GL_PIXEL_PACK_BUFFER, 64);
    GLuint indirect_buffer = make_buffer(GL_DISPATCH_INDIRECT_BUFFER, 64);
    GLuint copy_read = make_buffer(GL_COPY_READ_BUFFER, 64);
    GLuint copy_write = make_buffer(GL_COPY_WRITE_BUFFER, 64);
    GLuint array_buffer = make_buffer(GL_ARRAY_BUFFER, 64);
    GLuint vao = 0;
    glGenVertexArrays(1, &vao);

    for (int unit = 0; unit < kSentinelUnits; ++unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        glBindTexture(GL_TEXTURE_2D, unit == 0 ? tex_2d : tex_2d_other);
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, tex_ms);
        glBindTexture(GL_TEXTURE_3D, tex_3d);
        glBindTexture(GL_TEXTURE_2D_ARRAY, tex_array);
        glBindTexture(GL_TEXTURE_CUBE_MAP, tex_cube);
        glBindTexture(GL_TEXTURE_BUFFER, tex_buffer);
        glBindSampler(GLuint(unit), sampler);
        // Image units: level, layering, layer, access and format unlike GL's defaults (and unlike each other).
        switch (unit % 4) {
            case 0: glBindImageTexture(GLuint(unit), tex_array, 1, GL_FALSE, 2, GL_READ_ONLY, GL_RGBA8); break;
            case 1: glBindImageTexture(GLuint(unit), tex_r32f, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F); break;
            case 2: glBindImageTexture(GLuint(unit), tex_3d, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA8); break;
            default: glBindImageTexture(GLuint(unit), tex_2d, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8); break;
        }
    }
    for (GLuint index = 0; index < 4; ++index) {
        glBindBufferRange(GL_UNIFORM_BUFFER, index, ubo, GLintptr(ubo_alignment) * index, 256);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, index, ssbo, GLintptr(ssbo_alignment) * index, 256);
    }
    glBindBuffer(GL_UNIFORM_BUFFER, ubo);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, ssbo);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, unpack_buffer);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, indirect_buffer);
    glBindBuffer(GL_COPY_READ_BUFFER, copy_read);
    glBindBuffer(GL_COPY_WRITE_BUFFER, copy_write);
    glBindBuffer(GL_TEXTURE_BUFFER, texel_buffer);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, array_buffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 13);
    glPixelStorei(GL_PACK_SKIP_ROWS, 3);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 2);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 17);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 1);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 5);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 3);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, draw_fb);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_fb);
    glViewport(3, 5, 77, 41);
    glEnable(GL_SCISSOR_TEST);
    glScissor(1, 2, 30, 40);
    glEnable(GL_RASTERIZER_DISCARD);
    glEnable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glUseProgram(program);
    glActiveTexture(GL_TEXTURE5);
    return read_state(queries);
}

using obscura::samples::gl_error_name;

// ---- Statistics (OBSCURA_FUZZ_STATS=1 prints them at exit: how often each call reached which status) ---------------

struct CallStats {
    const char* call;
    unsigned long counts[OBSCURA_STATUS_COUNT_] = {};
};
CallStats g_stats[] = {{"obscura_render"}, {"obscura_prepare"}};
// How many successful renders reached the 0.5 features.
struct FeatureStats {
    unsigned long temporal = 0, matrices = 0, motion = 0, view = 0, reduced = 0, bent = 0;
    // Camera cuts on refused frames (Fixture::pending_cuts): refused after stage 1; the view's next accepted frame
    // compared with a fresh history; or not compared (temporal accumulation off, which frees the history, or a
    // target the fuzzer does not read back).
    unsigned long cuts_refused = 0, cuts_checked = 0, cuts_unchecked = 0;
};
FeatureStats g_features;

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
    std::fprintf(stderr,
                 "render_fuzzer: successful renders with temporal accumulation %lu (matrices %lu, motion vectors %lu, "
                 "a view %lu), reduced resolution %lu, bent normals %lu\n",
                 g_features.temporal, g_features.matrices, g_features.motion, g_features.view, g_features.reduced,
                 g_features.bent);
    std::fprintf(stderr,
                 "render_fuzzer: camera cuts on refused frames %lu; the next accepted frame compared with a fresh "
                 "history %lu, not compared %lu\n",
                 g_features.cuts_refused, g_features.cuts_checked, g_features.cuts_unchecked);
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
    std::vector<StateQuery> state_queries;
    StateValues sentinels;            // read_state(state_queries) as install_sentinels left it
    GLint sentinel_active_texture = 0;
    GLint sentinel_unit7_texture_2d = 0;
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

    // Each context's live views (obscura_create_view), oldest first, and the frame index its renders advance; handles
    // of destroyed views (never dereferenced: the SDK tells views apart by address, and may reuse one).
    static constexpr size_t kMaxViews = 4;
    struct Views {
        std::vector<obscura_view*> live;
        uint32_t frame_index = 0;
    };
    Views views[2];
    std::vector<obscura_view*> destroyed_views;
    Views& own_views() { return views[selected]; }
    Views& other_views() { return views[1 - selected]; }
    bool is_live_view(const obscura_view* view) const {
        const std::vector<obscura_view*>& live = views[selected].live;
        return std::find(live.begin(), live.end(), view) != live.end();
    }

    // Camera cuts on refused frames (obscura.h, TEMPORAL ACCUMULATION): a frame with OBSCURA_INPUT_FLAG_RESET_HISTORY
    // that is refused once its fields and its view are valid (stage 1 passed: a refusal of its textures, its target,
    // what its settings need, a host GL error, another GL context current) still drops its view's history, so the
    // view's next accepted frame that is not a debug view (which leaves the history as it is) starts a new one. The
    // views with such a cut pending, per context; cleared at the start of every input, so that an input that fails
    // the check holds the cut it checks.
    struct PendingCut {
        int context = 0;               // index into states
        obscura_view* view = nullptr;  // NULL: the context's own view
        int32_t status = 0;            // how the cut's frame was refused
        std::string frame;             // describe() of it
    };
    std::vector<PendingCut> pending_cuts;
    std::vector<PendingCut>::iterator find_cut(int context_index, const obscura_view* view) {
        return std::find_if(pending_cuts.begin(), pending_cuts.end(), [&](const PendingCut& cut) {
            return cut.context == context_index && cut.view == view;
        });
    }
    // Per context, a view that no fuzzed call names: the fresh history a frame after a cut is compared with is the
    // same frame rendered through it with RESET_HISTORY.
    obscura_view* fresh_views[2] = {};
};
Fixture* g_fixture = nullptr;

void check_sentinels(const char* call) {
    const StateValues now = read_state(g_fixture->state_queries);
    const StateValues& want = g_fixture->sentinels;
    for (size_t i = 0; i < want.size(); ++i) {
        FUZZ_CHECK(now[i] == want[i], "%s changed the host's %s: %lld, was %lld", call,
                   g_fixture->state_queries[i].name.c_str(), now[i], want[i]);
    }
    // The SDK switches a depth-stencil texture to depth for a frame and must switch it back.
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_2D, g_fixture->pools.stencil_mode_texture);
    GLint mode = 0;
    glGetTexParameteriv(GL_TEXTURE_2D, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
    glBindTexture(GL_TEXTURE_2D, GLuint(g_fixture->sentinel_unit7_texture_2d));
    glActiveTexture(GLenum(g_fixture->sentinel_active_texture));
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
    const uint8_t version_byte = in.u8();
    const uint8_t version = version_byte & 15;
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
    // Edits through the metadata (any value: out-of-range ones are refused and leave the struct as it was): a row byte
    // below 192 picks one of the method's rows, 192 and above one of the rows every method shares (temporal.*,
    // resolution.*, which a struct older than 0.5 does not have: UNKNOWN_SETTING, nothing changed).
    const int32_t info_method = valid_method(method) ? method : int32_t(OBSCURA_METHOD_HBAO);
    const obscura_setting_info* infos = nullptr;
    uint32_t count = 0;
    fuzz_get_setting_infos(info_method, &infos, &count);
    const obscura_setting_info* shared = nullptr;
    uint32_t shared_count = 0;
    FUZZ_CHECK(obscura_get_shared_setting_infos(&shared, &shared_count) == OBSCURA_OK && shared_count > 0,
               "obscura_get_shared_setting_infos failed");
    const int edits = in.u8() % 8;
    for (int i = 0; i < edits; ++i) {
        const uint8_t row = in.u8();
        const obscura_setting_info& info = row >= 192 ? shared[(row - 192u) % shared_count] : infos[row % count];
        const double value = obscura_fuzz::pick_setting_value(info, in.u8(), in);
        const int32_t status = status_code(obscura_set_setting(settings, info.name, value));
        if (g_trace) {
            std::fprintf(stderr, "render_fuzzer: edit %s = %.17g: %s\n", info.name, value, fuzz_status_string(status));
        }
    }
    // Bit 7 of the version byte: a byte of shared settings follows, set through their names (refused by a struct older
    // than 0.5): bit 0 temporal accumulation on, bits 1-2 resolution.scale (0 leaves it), bits 3-5
    // temporal.max_frames 1 + 9n, so that temporal accumulation and reduced resolution are reached often.
    if (version_byte & 0x80) {
        const uint8_t shared_bits = in.u8();
        auto set = [&](const char* name, double value) {
            const int32_t status = status_code(obscura_set_setting(settings, name, value));
            if (g_trace) {
                std::fprintf(stderr, "render_fuzzer: edit %s = %g: %s\n", name, value, fuzz_status_string(status));
            }
        };
        if (shared_bits & 1) set("temporal.enabled", 1.0);
        if (shared_bits & 6) set("resolution.scale", double((shared_bits >> 1) & 3));
        if (shared_bits & 0x38) set("temporal.max_frames", 1.0 + 9.0 * ((shared_bits >> 3) & 7));
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
    // The 0.5 per-frame fields (decode_frame_fields; without them all zero: the context's own view, no matrices).
    bool frame_fields = false;
    bool view_valid = true;                  // NULL or a live view of the context the call runs on
    const char* view_label = "none";
    const char* matrices_label = "none";
    const CompanionEntry* motion = nullptr;  // NULL: none
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
    const CompanionEntry* bent = nullptr;  // NULL: none
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

// ---- The 0.5 per-frame fields ---------------------------------------------------------------------------------

// Column-major 4x4 product a * b.
void multiply(const float a[16], const float b[16], float out[16]) {
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            double sum = 0.0;
            for (int k = 0; k < 4; ++k) sum += double(a[k * 4 + row]) * double(b[column * 4 + k]);
            out[column * 4 + row] = float(sum);
        }
    }
}

void transpose(float m[16]) {
    for (int r = 0; r < 4; ++r)
        for (int c = r + 1; c < 4; ++c) std::swap(m[c * 4 + r], m[r * 4 + c]);
}

// A camera's world -> view matrix (column-major): a turn about y by `yaw` radians, then a move.
void view_matrix(double yaw, double tx, double ty, double tz, float out[16]) {
    std::memset(out, 0, 16 * sizeof(float));
    const double c = std::cos(yaw), s = std::sin(yaw);
    out[0] = float(c), out[2] = float(-s);
    out[5] = 1.0f;
    out[8] = float(s), out[10] = float(c);
    out[12] = float(tx), out[13] = float(ty), out[14] = float(tz), out[15] = 1.0f;
}

// A few entries off a little, the whole matrix scaled to the extremes, or an entry replaced by NaN, an infinity, 0,
// a denormal, FLT_MAX, -1 or any float.
void perturb(float m[16], Reader& in) {
    const int count = 1 + in.u8() % 3;
    for (int i = 0; i < count; ++i) {
        float& value = m[in.u8() % 16];
        const uint8_t how = in.u8();
        if (how < 96) {
            value *= 1.0f + float(int8_t(in.u8())) / 256.0f;
        } else if (how < 128) {
            static const float kScales[4] = {1e30f, 1e-12f, -1.0f, 1e-30f};
            for (int k = 0; k < 16; ++k) m[k] *= kScales[how % 4];
        } else {
            value = special_float(how, in);
        }
    }
}

// Resolves an aliasing pool entry to the name the other field holds (0: none, so the entry is none too).
const CompanionEntry* resolve_alias(const CompanionEntry* entry, GLuint* name, const DecodedInput& input,
                                    const DecodedOutput& output) {
    switch (entry->alias) {
        case Alias::None: *name = entry->name; break;
        case Alias::Output: *name = output.output.texture; break;
        case Alias::Depth: *name = input.input.depth_texture; break;
        case Alias::Normals: *name = input.input.normal_texture; break;
        case Alias::Motion: *name = input.input.motion_vector_texture; break;
    }
    return *name ? entry : nullptr;
}

// Decodes the fields 0.5 added to obscura_input (view, frame_index, flags, the two view-projection matrices, motion
// vectors and their units) and obscura_output (bent_normal_texture), after the rest of both structs:
//   view: u8 (< 96 NULL, < 192 one of the context's live views, < 216 a destroyed view's handle, < 240 a view of
//         the other context, else a pointer that never was a view), u8 which one (NULL where the list is empty);
//   frame_index: u8 (< 96 the context's counter as it is, < 224 the counter advanced, else a raw u32);
//   flags: u8 (< 192 none, < 240 RESET_HISTORY, else a raw u32);
//   matrices: u8, bits 0-1 view_projection (0 none, 1 projection * a camera, 2 that perturbed, 3 raw floats), bits 2-3
//         previous_view_projection (0 none, 1 the same, 2 the camera nudged, 3 that perturbed), with the camera's
//         bytes and the perturbations after it;
//   motion vectors: u8 (< 160 none, else a pool entry by the next byte), units: u8 (< 250 PIXELS / NDC, else raw);
//   bent normals: u8 (< 160 none, else a pool entry by the next byte).
void decode_frame_fields(Reader& in, DecodedInput& d, DecodedOutput& o) {
    Fixture& fx = *g_fixture;
    const Pools& pools = fx.pools;
    obscura_input& input = d.input;
    d.frame_fields = true;

    static int never_a_view = 0;
    const uint8_t view = in.u8();
    const uint8_t pick = in.u8();  // which one of a list (read always: the layout never depends on earlier inputs)
    if (view < 96) {
        input.view = nullptr;
    } else if (view < 192) {
        const std::vector<obscura_view*>& live = fx.own_views().live;
        input.view = live.empty() ? nullptr : live[pick % live.size()];
        d.view_label = live.empty() ? "none (no view yet)" : "a live view";
    } else if (view < 216) {
        const std::vector<obscura_view*>& gone = fx.destroyed_views;
        input.view = gone.empty() ? nullptr : gone[pick % gone.size()];
        d.view_label = gone.empty() ? "none (none destroyed yet)" : "a destroyed view";
    } else if (view < 240) {
        const std::vector<obscura_view*>& other = fx.other_views().live;
        input.view = other.empty() ? nullptr : other[pick % other.size()];
        d.view_label = other.empty() ? "none (the other context has none)" : "the other context's view";
    } else {
        input.view = reinterpret_cast<obscura_view*>(&never_a_view);
        d.view_label = "a pointer that never was a view";
    }
    // A destroyed view's address may have been reused by a view created since: then it names that view.
    d.view_valid = input.view == nullptr || fx.is_live_view(input.view);

    const uint8_t frame = in.u8();
    Fixture::Views& counter = fx.own_views();
    if (frame < 96) input.frame_index = counter.frame_index;
    else if (frame < 224) input.frame_index = ++counter.frame_index;
    else input.frame_index = in.u32();

    const uint8_t flags = in.u8();
    input.flags = flags < 192 ? 0u : flags < 240 ? uint32_t(OBSCURA_INPUT_FLAG_RESET_HISTORY) : in.u32();
    if (input.flags & ~uint32_t(OBSCURA_INPUT_FLAG_RESET_HISTORY)) d.fields_valid = false;

    // The matrices, in the projection's layout: the projection times a camera.
    const uint8_t matrices = in.u8();
    const int current = matrices & 3, previous = (matrices >> 2) & 3;
    static const char* const kCurrent[4] = {"none", "camera", "camera perturbed", "raw"};
    static const char* const kPrevious[4] = {"none", "same", "nudged", "nudged perturbed"};
    static char label[64];
    std::snprintf(label, sizeof label, "%s / %s", kCurrent[current], kPrevious[previous]);
    d.matrices_label = label;
    const bool row_major = load_raw(input.projection_layout) == OBSCURA_MATRIX_ROW_MAJOR;
    float projection[16];
    std::memcpy(projection, input.projection, sizeof projection);
    if (row_major) transpose(projection);
    const double yaw = double(int8_t(in.u8())) / 128.0 * 0.3;
    const double tx = double(int8_t(in.u8())) / 64.0, ty = double(int8_t(in.u8())) / 64.0,
                 tz = double(int8_t(in.u8())) / 64.0;
    float camera[16], camera_view_projection[16];
    view_matrix(yaw, tx, ty, tz, camera);
    multiply(projection, camera, camera_view_projection);
    if (current == 1 || current == 2) {
        std::memcpy(input.view_projection, camera_view_projection, sizeof camera_view_projection);
        if (row_major) transpose(input.view_projection);
        if (current == 2) perturb(input.view_projection, in);
    } else if (current == 3) {
        for (float& value : input.view_projection) value = in.f32();
    }
    if (previous == 1) {
        std::memcpy(input.previous_view_projection, input.view_projection, sizeof input.view_projection);
    } else if (previous >= 2) {  // the camera a little elsewhere (a near-identity reprojection)
        float nudged[16];
        view_matrix(yaw + double(int8_t(in.u8())) / 4096.0, tx + double(int8_t(in.u8())) / 1024.0, ty,
                    tz + double(int8_t(in.u8())) / 1024.0, nudged);
        multiply(projection, nudged, input.previous_view_projection);
        if (row_major) transpose(input.previous_view_projection);
        if (previous == 3) perturb(input.previous_view_projection, in);
    }
    if (current >= 2 || previous == 3) d.fields_valid = false;  // may be non-finite or singular

    // Motion vectors, then the bent normals (which may name them).
    const uint8_t motion = in.u8();
    if (motion >= 160) {
        d.motion = &pools.motion[in.index(uint32_t(pools.motion.size()))];
        GLuint name = 0;
        d.motion = resolve_alias(d.motion, &name, d, o);
        input.motion_vector_texture = name;
    }
    const uint8_t units = in.u8();
    if (units >= 250) d.fields_valid = false;
    store_raw(&input.motion_vector_units, units < 250 ? int32_t(units & 1) : in.i32());

    const uint8_t bent = in.u8();
    if (bent >= 160) {
        o.bent = &pools.bent[in.index(uint32_t(pools.bent.size()))];
        GLuint name = 0;
        o.bent = resolve_alias(o.bent, &name, d, o);
        o.output.bent_normal_texture = name;
    }
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
        case OBSCURA_STATUS_INVALID_ENUM: case OBSCURA_STATUS_INVALID_VIEW:
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
        case OBSCURA_STATUS_PROJECTION_TRANSPOSED: case OBSCURA_STATUS_INVALID_VIEW:
            return true;
        default: return false;
    }
}

// What a render's arguments promise about stage 1: known sizes (settings: any released size) and settings that
// resolve; `fields_pass`: also fields decoded from valid choices, so only the view (checked last) may fail stage 1;
// `passes`: and a valid view, so stage 1 must pass.
struct StageOne {
    bool sizes_valid = false;
    int32_t resolve_status = -1;
    bool fields_pass = false;
    bool view_valid = true;
    bool passes = false;
};

// Whether the SDK reads the 0.5 fields: a struct of the 0.4 size ends before them (they read as zero).
bool reads_05_fields(const DecodedInput& input) { return input.input.struct_size == sizeof(obscura_input); }
bool reads_05_fields(const DecodedOutput& output) { return output.output.struct_size == sizeof(obscura_output); }

StageOne stage_one(const DecodedInput& input, const DecodedOutput& output, const DecodedSettings& settings) {
    StageOne s;
    s.sizes_valid = is_released_input_size(input.input.struct_size) &&
                    is_released_output_size(output.output.struct_size) &&
                    is_released_settings_size(settings.struct_size());
    s.resolve_status = resolve_status_of(settings);
    s.fields_pass = s.sizes_valid && s.resolve_status == kOk && input.fields_valid && output.fields_valid;
    s.view_valid = input.view_valid || !reads_05_fields(input);
    s.passes = s.fields_pass && s.view_valid;
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
    std::string described = text;
    if (in.frame_fields) {  // only then, so that the trace of an input without them reads as it always did
        std::snprintf(text, sizeof text,
                      "; 0.5 fields: view %s (%s), frame_index %u, flags 0x%x, matrices %s, motion vectors %s (units "
                      "%d), bent normals %s",
                      in.view_label, in.view_valid ? "valid" : "invalid", in.input.frame_index, in.input.flags,
                      in.matrices_label, in.motion ? in.motion->label : "none",
                      load_raw(in.input.motion_vector_units), out.bent ? out.bent->label : "none");
        described += text;
    }
    return described;
}

// ---- What a render wrote ------------------------------------------------------------------------------------------

// Every texel of a checked float target holds this before a render (exact in RGBA16F): what a render leaves outside
// its result, and what a refused render leaves everywhere.
constexpr float kTargetSentinel[4] = {0.3125f, 0.4375f, 0.5625f, 0.6875f};

// Uploads to / reads back a host texture through unit 7, leaving the sentinel bindings as they were.
void write_rgba(GLuint texture, int width, int height, const std::vector<float>& rgba) {
    const NeutralPixelStore store;
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
    glBindTexture(GL_TEXTURE_2D, GLuint(g_fixture->sentinel_unit7_texture_2d));
    glActiveTexture(GLenum(g_fixture->sentinel_active_texture));
}

void fill_with_sentinel(GLuint texture, int width, int height) {
    std::vector<float> rgba(size_t(width) * size_t(height) * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = kTargetSentinel[i % 4];
    write_rgba(texture, width, height, rgba);
}

std::vector<float> read_rgba(GLuint texture, int width, int height) {
    const NeutralPixelStore store;
    std::vector<float> rgba(size_t(width) * size_t(height) * 4);
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_2D, texture);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
    glBindTexture(GL_TEXTURE_2D, GLuint(g_fixture->sentinel_unit7_texture_2d));
    glActiveTexture(GLenum(g_fixture->sentinel_active_texture));
    return rgba;
}

// The float targets a render is checked against: the output's (RGBA16F, RGBA32F) and the bent normals' (RGBA16F,
// RGBA32F).
bool output_checked(const DecodedOutput& out) {
    return out.target->read_back && out.output.texture == out.target->texture;
}
bool bent_checked(const DecodedOutput& out) { return out.bent && out.bent->read_back && reads_05_fields(out); }

void fill_checked_targets(const DecodedOutput& out) {
    if (output_checked(out)) fill_with_sentinel(out.target->texture, out.target->width, out.target->height);
    if (bent_checked(out)) fill_with_sentinel(out.bent->name, out.bent->width, out.bent->height);
}

// After a render: texels outside the result (the output rectangle's size at output.x, output.y) and every texel after
// a failure keep the sentinel; inside, a successful render wrote finite visibility in [0, 1] (every debug view is
// scaled into [0, 1] too, but the tap count, taps / 256, which may pass 1; MULTIPLY keeps [0, 1] contents within it)
// and unit bent normals (view space) with the visibility in alpha.
void check_targets(int32_t status, const DecodedInput& in, const DecodedOutput& out) {
    const bool tap_count = load_raw(out.output.debug_view) == OBSCURA_DEBUG_TAP_COUNT;
    obscura_rect rect = in.input.output_rect;
    if (rect.width == 0 && rect.height == 0 && rect.x == 0 && rect.y == 0) {
        rect = {0, 0, in.input.depth_width, in.input.depth_height};
    }
    auto check = [&](GLuint texture, int width, int height, bool bent, const char* label) {
        const std::vector<float> rgba = read_rgba(texture, width, height);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const float* v = &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
                const bool inside = status == kOk && x >= out.output.x && y >= out.output.y &&
                                    x - out.output.x < rect.width && y - out.output.y < rect.height;
                if (!inside) {
                    FUZZ_CHECK(v[0] == kTargetSentinel[0] && v[1] == kTargetSentinel[1] && v[2] == kTargetSentinel[2] &&
                                   v[3] == kTargetSentinel[3],
                               "obscura_render (%s) wrote (%g, %g, %g, %g) at (%d, %d) of the %s target %s, outside "
                               "its %dx%d result at (%d, %d)",
                               fuzz_status_string(status), double(v[0]), double(v[1]), double(v[2]), double(v[3]), x,
                               y, bent ? "bent-normal" : "output", label, rect.width, rect.height, out.output.x,
                               out.output.y);
                } else if (!bent) {
                    FUZZ_CHECK(std::isfinite(v[0]) && v[0] >= 0.0f && (v[0] <= 1.0f || tap_count),
                               "a successful render wrote %g at (%d, %d) of the %s target (debug view %d)",
                               double(v[0]), x, y, label, load_raw(out.output.debug_view));
                } else {
                    const double length = std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
                    FUZZ_CHECK(std::isfinite(length) && std::fabs(length - 1.0) <= 0.01 && std::isfinite(v[3]) &&
                                   v[3] >= 0.0f && v[3] <= 1.0f,
                               "a successful render wrote the bent normal (%g, %g, %g) (length %g), visibility %g at "
                               "(%d, %d) of the %s bent-normal target (debug view %d)",
                               double(v[0]), double(v[1]), double(v[2]), length, double(v[3]), x, y, label,
                               load_raw(out.output.debug_view));
                }
            }
        }
    };
    if (output_checked(out)) {
        check(out.target->texture, out.target->width, out.target->height, false, out.target->label);
    }
    if (bent_checked(out)) check(out.bent->name, out.bent->width, out.bent->height, true, out.bent->label);
}

// A texture the frame writes (the output texture or its framebuffer's attachment, the bent normals) that is also one
// it reads or the other one it writes: INVALID_TEXTURE.
bool frame_aliases(const DecodedInput& in, const DecodedOutput& out) {
    const Pools& pools = g_fixture->pools;
    const GLuint motion = reads_05_fields(in) ? in.input.motion_vector_texture : 0;
    const GLuint bent = reads_05_fields(out) ? out.output.bent_normal_texture : 0;
    GLuint target = out.output.texture;
    if (target == 0 && out.output.framebuffer == pools.any_framebuffer) target = pools.any_framebuffer_texture;
    for (GLuint written : {target, bent}) {
        if (written == 0) continue;
        if (written == in.input.depth_texture || written == in.input.normal_texture || written == motion) return true;
    }
    return target != 0 && target == bent;
}

// The method the settings resolve to (-1 when they do not resolve).
int32_t resolved_method(const DecodedSettings& settings) {
    SettingsBuffer out(0, settings.buffer.size());
    if (status_code(obscura_resolve_settings(nullptr, settings.get(), out.get())) != kOk) return -1;
    int32_t method;
    std::memcpy(&method, out.bytes() + offsetof(obscura_settings, method), sizeof method);
    return method;
}

// Stage 1 ends with the view: fields that pass and a view that is not a live one of this context are INVALID_VIEW,
// and INVALID_VIEW means such a view.
void check_view_status(const char* what, int32_t status, const StageOne& stage, const DecodedInput& input) {
    FUZZ_CHECK(status != OBSCURA_STATUS_INVALID_VIEW || !stage.view_valid, "%s returned INVALID_VIEW for view %s",
               what, input.view_label);
    FUZZ_CHECK(!stage.fields_pass || stage.view_valid || status == OBSCURA_STATUS_INVALID_VIEW,
               "%s returned %s for view %s, not INVALID_VIEW", what, fuzz_status_string(status), input.view_label);
}

// ---- Camera cuts on refused frames (Fixture::pending_cuts) ----------------------------------------------------------

// The view whose history a frame reads and writes: a 0.4 input has no view field (the context's own).
obscura_view* history_view(const DecodedInput& input) { return reads_05_fields(input) ? input.input.view : nullptr; }

// A refused frame with RESET_HISTORY whose fields and view passed (stage 1) has dropped its view's history: the view's
// next accepted frame must start a new one. A cut refused in stage 1 (its fields or its view) leaves the history as it
// was, as does any other refused frame (a pending cut stays pending).
void note_refused_cut(int32_t status, const StageOne& stage, const DecodedInput& input, const std::string& what) {
    Fixture& fx = *g_fixture;
    if (status == kOk || !stage.passes || !reads_05_fields(input) ||
        (input.input.flags & OBSCURA_INPUT_FLAG_RESET_HISTORY) == 0) {
        return;
    }
    ++g_features.cuts_refused;
    auto cut = fx.find_cut(fx.selected, input.input.view);
    if (cut == fx.pending_cuts.end()) {
        fx.pending_cuts.push_back(Fixture::PendingCut{fx.selected, input.input.view, status, what});
    } else {
        cut->status = status, cut->frame = what;
    }
}

// The texture of the pool that a render of `out` writes and the fuzzer can read back and restore (the 2D textures,
// also the one attached to the output FBO); 0 for the others (a renderbuffer, the default framebuffer, ...).
struct ReadableTarget {
    GLuint texture = 0;
    int width = 0, height = 0;
};
ReadableTarget readable_target(const DecodedOutput& out) {
    const Pools& pools = g_fixture->pools;
    if (out.output.texture != 0) {
        if (out.output.texture != out.target->texture || !out.target->usable || out.target->not_a_texture) return {};
        return {out.target->texture, out.target->width, out.target->height};
    }
    if (out.output.framebuffer != 0 && out.output.framebuffer == pools.any_framebuffer) {
        return {pools.any_framebuffer_texture, kDepthWidth, kDepthHeight};  // make_pools: the 16x12 RGBA8 attachment
    }
    return {};
}

// Whether the settings, as obscura_render reads them, accumulate frames (a struct older than 0.5 has no temporal block).
bool accumulates(const DecodedSettings& settings) {
    if (settings.struct_size() != sizeof(obscura_settings) || settings.buffer.size() != sizeof(obscura_settings)) {
        return false;
    }
    SettingsBuffer resolved(0, sizeof(obscura_settings));
    if (status_code(obscura_resolve_settings(nullptr, settings.get(), resolved.get())) != kOk) return false;
    return resolved.get()->temporal.enabled == OBSCURA_TOGGLE_ON;
}

// After an accepted frame of a view with a pending cut: unless it is a debug view (the cut stays pending), the frame
// must equal the same frame rendered with RESET_HISTORY through the context's fresh view, into the target as it was
// before (`target_before`, read from `readable` before the frame). Both start a new history, so the renders are the
// same computation (deterministic: bit for bit, as tests/gl/robustness_test.cpp's Determinism checks); a frame that
// continued the history from before the cut differs wherever that history moved the blend. One more render and three
// small transfers, only on such a frame.
void check_frame_after_cut(const DecodedInput& input, const DecodedOutput& output, const DecodedSettings& settings,
                           const ReadableTarget& readable, const std::vector<float>& target_before,
                           const std::string& what) {
    Fixture& fx = *g_fixture;
    auto pending = fx.find_cut(fx.selected, history_view(input));
    if (pending == fx.pending_cuts.end() || load_raw(output.output.debug_view) != OBSCURA_DEBUG_NONE) return;
    const Fixture::PendingCut cut = *pending;
    fx.pending_cuts.erase(pending);
    // Without accumulation the frame frees the history; a target not read back cannot be compared.
    if (!accumulates(settings) || readable.texture == 0) {
        ++g_features.cuts_unchecked;
        return;
    }
    ++g_features.cuts_checked;
    const std::vector<float> accepted = read_rgba(readable.texture, readable.width, readable.height);
    write_rgba(readable.texture, readable.width, readable.height, target_before);
    // The frame as obscura_render read it (a 0.4 input's 0.5 fields read 0), through the fresh view, with the cut.
    obscura_input fresh = input.input;
    if (!reads_05_fields(input)) {
        std::memset(reinterpret_cast<unsigned char*>(&fresh) + obscura_fuzz::kInputSize04, 0,
                    sizeof fresh - obscura_fuzz::kInputSize04);
    }
    fresh.struct_size = sizeof fresh;
    fresh.view = fx.fresh_views[fx.selected];
    fresh.flags |= OBSCURA_INPUT_FLAG_RESET_HISTORY;
    const std::string context = what + "; rendered again through a fresh view with RESET_HISTORY, after the camera cut "
                                       "on the refused frame (" + fuzz_status_string(cut.status) + ") " + cut.frame;
    obscura_fuzz::set_failure_context(context);
    const NoContextMessage message;
    const int log_before = fx.log.count;
    const int32_t status = status_code(obscura_render(fx.context, &fresh, settings.get(), &output.output));
    message.check("obscura_render");
    check_after_call("obscura_render (a fresh history)", status, log_before, true);
    FUZZ_CHECK(status == kOk, "an accepted frame, rendered again through a fresh view with RESET_HISTORY, returned %s "
               "(\"%s\")", fuzz_status_string(status), obscura_get_last_error(fx.context));
    const std::vector<float> fresh_image = read_rgba(readable.texture, readable.width, readable.height);
    for (size_t i = 0; i < accepted.size(); ++i) {
        if (accepted[i] == fresh_image[i] || (std::isnan(accepted[i]) && std::isnan(fresh_image[i]))) continue;
        double largest = 0.0;
        size_t differing = 0;
        for (size_t j = 0; j < accepted.size(); ++j) {
            const double difference = std::fabs(double(accepted[j]) - double(fresh_image[j]));
            differing += accepted[j] != fresh_image[j];
            if (difference > largest) largest = difference;
        }
        const size_t texel = i / 4;
        obscura_fuzz::fail("the frame after a camera cut on a refused frame (%s) did not start a new history: "
                           "channel %zu of texel (%zu, %zu) of the %s target is %.9g, %.9g from a fresh history (%zu "
                           "of %zu values differ, by up to %.9g)",
                           fuzz_status_string(cut.status), i % 4, texel % size_t(readable.width),
                           texel / size_t(readable.width), output.target->label, double(accepted[i]),
                           double(fresh_image[i]), differing, accepted.size(), largest);
    }
}

void op_render(Reader& in, bool inject_host_error, bool frame_fields) {
    Fixture& fx = *g_fixture;
    const DecodedSettings settings = decode_settings(in);
    DecodedInput input = decode_input(in);
    DecodedOutput output = decode_output(in);
    if (frame_fields) decode_frame_fields(in, input, output);
    const std::string what = describe(input, output, settings);
    obscura_fuzz::set_failure_context(what);
    fill_checked_targets(output);
    // A frame of a view with a camera cut pending may have to be rendered again into its target as it is now.
    const ReadableTarget readable = readable_target(output);
    std::vector<float> target_before;
    if (readable.texture && fx.find_cut(fx.selected, history_view(input)) != fx.pending_cuts.end()) {
        target_before = read_rgba(readable.texture, readable.width, readable.height);
    }

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
    check_view_status("obscura_render", status, stage, input);

    // Settings the SDK refuses make the render fail the same way (after the struct sizes, before the host state).
    FUZZ_CHECK(!stage.sizes_valid || stage.resolve_status == kOk || status == stage.resolve_status,
               "obscura_render returned %s for settings that resolve to %s", fuzz_status_string(status),
               fuzz_status_string(stage.resolve_status));
    FUZZ_CHECK(status != kOk || stage.sizes_valid, "obscura_render accepted struct sizes %u / %u / %u",
               input.input.struct_size, output.output.struct_size, settings.struct_size());
    check_targets(status, input, output);
    // A buffer's or a deleted texture's number may have become a texture since (GL reuses names, the SDK's own
    // textures included): then nothing is known about it.
    auto known = [](bool not_a_texture, GLuint name) { return !(not_a_texture && glIsTexture(name)); };
    const bool names_known = known(input.depth->not_a_texture, input.depth->name) &&
                             known(input.normals->not_a_texture, input.normals->name) &&
                             known(output.target->not_a_texture, output.target->texture) &&
                             (!input.motion || known(input.motion->not_a_texture, input.motion->name)) &&
                             (!output.bent || known(output.bent->not_a_texture, output.bent->name));
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
        // ... and, of the 0.5 fields, a live view, RG16F / RG32F motion vectors of the depth's size, a bent-normal
        // target of a format it takes that holds the result (for a method that writes bent normals), and no texture
        // both written and read (or written twice).
        FUZZ_CHECK(stage.view_valid, "obscura_render accepted view %s", input.view_label);
        FUZZ_CHECK(!frame_aliases(input, output), "obscura_render accepted a frame that writes a texture it reads");
        if (input.motion && reads_05_fields(input)) {
            FUZZ_CHECK(input.motion->supported && input.motion->width == input.depth->width &&
                           input.motion->height == input.depth->height,
                       "obscura_render accepted motion vectors %s with depth %s", input.motion->label,
                       input.depth->label);
        }
        if (output.bent && reads_05_fields(output)) {
            const obscura_rect rect = input.input.output_rect.width ? input.input.output_rect
                                                                    : obscura_rect{0, 0, input.input.depth_width,
                                                                                   input.input.depth_height};
            FUZZ_CHECK(output.bent->supported && rect.width <= output.bent->width - output.output.x &&
                           rect.height <= output.bent->height - output.output.y,
                       "obscura_render accepted bent normals %s for a %dx%d result at (%d, %d)", output.bent->label,
                       rect.width, rect.height, output.output.x, output.output.y);
            const int32_t method = resolved_method(settings);
            FUZZ_CHECK(valid_method(method) && obscura_method_writes_bent_normals(static_cast<obscura_method>(method)),
                       "obscura_render accepted bent normals for method %d", method);
        }
    }
    if (status == kOk) {
        SettingsBuffer resolved(0, settings.buffer.size());
        if (settings.buffer.size() == sizeof(obscura_settings) &&
            status_code(obscura_resolve_settings(nullptr, settings.get(), resolved.get())) == kOk) {
            const obscura_settings& r = *resolved.get();
            const bool temporal = r.temporal.enabled == OBSCURA_TOGGLE_ON && load_raw(output.output.debug_view) == 0;
            g_features.temporal += temporal;
            const float* m = input.input.view_projection;
            g_features.matrices += temporal && reads_05_fields(input) &&
                                   std::any_of(m, m + 16, [](float v) { return v != 0.0f; });
            g_features.motion += temporal && reads_05_fields(input) && input.input.motion_vector_texture != 0;
            g_features.view += temporal && reads_05_fields(input) && input.input.view != nullptr;
            g_features.reduced += load_raw(r.resolution.scale) > OBSCURA_RESOLUTION_FULL;
        }
        g_features.bent += reads_05_fields(output) && output.output.bent_normal_texture != 0;
        uint64_t memory = 0;
        FUZZ_CHECK(obscura_get_memory_usage(fx.context, &memory) == OBSCURA_OK && memory > fx.baseline_memory,
                   "after a successful render the context reports %llu bytes (baseline %llu)",
                   (unsigned long long)memory, (unsigned long long)fx.baseline_memory);
        check_frame_after_cut(input, output, settings, readable, target_before, what);
    }
    note_refused_cut(status, stage, input, what);
}

// obscura_create_view / obscura_destroy_view on the selected context. `kind` 1: create a view (at most kMaxViews
// live: the oldest is destroyed first); 2: destroy one by a selector byte (< 128 a live view, < 160 NULL, < 192 a
// destroyed view's handle, < 224 the other context's view, else a pointer that never was a view; NULL where the list
// is empty), a byte for which one of the list, and with the other GL context current when the next byte is 224 or
// more (WRONG_GL_CONTEXT: nothing destroyed).
void destroy_view(obscura_view* view, bool other_gl_current, const char* label) {
    Fixture& fx = *g_fixture;
    char what[160];
    std::snprintf(what, sizeof what, "obscura_destroy_view(%s)%s", label,
                  other_gl_current ? " with another GL context current" : "");
    obscura_fuzz::set_failure_context(what);
    const bool live = fx.is_live_view(view);
    const NoContextMessage message;
    const int log_before = fx.log.count;
    if (other_gl_current) fx.other_gl->make_current();
    const int32_t status = status_code(obscura_destroy_view(fx.context, view));
    if (other_gl_current) fx.gl->make_current();
    message.check("obscura_destroy_view");
    check_after_call("obscura_destroy_view", status, log_before, true);
    const int32_t expected = view == nullptr ? kOk
                             : !live         ? int32_t(OBSCURA_STATUS_INVALID_VIEW)
                             : other_gl_current ? int32_t(OBSCURA_STATUS_WRONG_GL_CONTEXT)
                                                : kOk;
    FUZZ_CHECK(status == expected, "%s returned %s, not %s", what, fuzz_status_string(status),
               fuzz_status_string(expected));
    if (status == kOk && view) {
        std::vector<obscura_view*>& views = fx.own_views().live;
        views.erase(std::find(views.begin(), views.end(), view));
        auto cut = fx.find_cut(fx.selected, view);  // its address may name a new view from now on
        if (cut != fx.pending_cuts.end()) fx.pending_cuts.erase(cut);
        if (fx.destroyed_views.size() >= 8) fx.destroyed_views.erase(fx.destroyed_views.begin());
        fx.destroyed_views.push_back(view);
    }
}

void op_view(Reader& in, int kind) {
    Fixture& fx = *g_fixture;
    Fixture::Views& own = fx.own_views();
    static int never_a_view = 0;
    if (kind == 2) {
        const uint8_t selector = in.u8();
        const uint8_t pick = in.u8();
        const bool other_gl = in.u8() >= 224;
        obscura_view* view = nullptr;
        const char* label = "NULL";
        if (selector < 128 && !own.live.empty()) {
            view = own.live[pick % own.live.size()], label = "a live view";
        } else if (selector >= 160 && selector < 192 && !fx.destroyed_views.empty()) {
            view = fx.destroyed_views[pick % fx.destroyed_views.size()], label = "a destroyed view";
        } else if (selector >= 192 && selector < 224 && !fx.other_views().live.empty()) {
            view = fx.other_views().live[pick % fx.other_views().live.size()];
            label = "the other context's view";
        } else if (selector >= 224) {
            view = reinterpret_cast<obscura_view*>(&never_a_view), label = "a pointer that never was a view";
        }
        destroy_view(view, other_gl, label);
        return;
    }
    if (own.live.size() >= Fixture::kMaxViews) destroy_view(own.live.front(), false, "the oldest live view");
    obscura_fuzz::set_failure_context("obscura_create_view");
    const NoContextMessage message;
    obscura_view* view = nullptr;
    const int32_t status = status_code(obscura_create_view(fx.context, &view));
    message.check("obscura_create_view");
    check_after_call("obscura_create_view", status, fx.log.count, false);
    FUZZ_CHECK(status == kOk && view != nullptr, "obscura_create_view returned %s (view %p)",
               fuzz_status_string(status), static_cast<void*>(view));
    FUZZ_CHECK(!fx.is_live_view(view) && std::find(fx.other_views().live.begin(), fx.other_views().live.end(), view) ==
                                             fx.other_views().live.end(),
               "obscura_create_view returned a live view's handle");
    own.live.push_back(view);
    // The address may be a destroyed view's: from now on that handle names this view (is_live_view says so).
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
void op_wrong_context(Reader& in, bool frame_fields) {
    Fixture& fx = *g_fixture;
    const DecodedSettings settings = decode_settings(in);
    DecodedInput input = decode_input(in);
    DecodedOutput output = decode_output(in);
    const bool prepare = in.u8() & 1;
    if (frame_fields) decode_frame_fields(in, input, output);
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
    check_view_status(what.c_str(), status, stage, input);
    note_refused_cut(status, stage, input, what);  // the fields and the view come before the GL context
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

// An operation's byte: the low 4 bits pick the operation, bit 4 the context; bit 5 adds the 0.5 per-frame fields to a
// render's structs (decode_frame_fields, after the rest); operation 10 is obscura_release_resources, or with bits 5-6
// 1 obscura_create_view and 2 obscura_destroy_view (op_view).
void run_operation(uint8_t op, Reader& in) {
    g_fixture->select((op >> 4) & 1);
    if (g_trace) std::fprintf(stderr, "render_fuzzer: operation 0x%02x\n", unsigned(op));
    const bool frame_fields = (op & 0x20) != 0;
    switch (op % 16) {
        case 0: case 1: case 2: case 3: case 4: case 5: case 6: case 7: op_render(in, false, frame_fields); break;
        case 8: case 9: op_prepare(in); break;
        case 10: {
            const int kind = (op >> 5) & 3;
            if (kind == 1 || kind == 2) op_view(in, kind);
            else op_release();
            break;
        }
        case 11: op_queries(in); break;
        case 12: op_wrong_context(in, frame_fields); break;
        case 13: op_render(in, true, frame_fields); break;
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
        FUZZ_CHECK(obscura_create_view(state.context, &fx.fresh_views[i]) == OBSCURA_OK && fx.fresh_views[i],
                   "render_fuzzer setup: obscura_create_view failed");
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
    fx.state_queries = make_state_queries();
    fx.sentinels = install_sentinels(fx.state_queries);
    fx.sentinel_active_texture = get_integer(GL_ACTIVE_TEXTURE);
    glActiveTexture(GL_TEXTURE7);
    fx.sentinel_unit7_texture_2d = get_integer(GL_TEXTURE_BINDING_2D);
    glActiveTexture(GLenum(fx.sentinel_active_texture));
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
    g_fixture->pending_cuts.clear();  // the histories stay, but a check needs its cut in the input that fails it
    const int operations = 1 + in.u8() % 4;
    for (int i = 0; i < operations; ++i) run_operation(in.u8(), in);
    return 0;
}
