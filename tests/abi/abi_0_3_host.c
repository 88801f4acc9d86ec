/* abi_0_3_host.c - a host built against the released 0.3 API, linked with today's library
 * (ctest Abi.Host03RendersWithTodaysLibrary; issue 22, point 6: ABI growth).
 *
 * It sees only tests/abi/obscura_0_3.h, a frozen copy of the 0.3 header: every struct it passes has the 0.3
 * size and layout, every struct_size is a 0.3 sizeof and header_version is 0.3's OBSCURA_VERSION (300). When
 * the SDK appends fields to its structs and bumps its version, the library must still accept these sizes, keep
 * the 0.3 behaviour of the symbols a 0.3 binary calls (obscura_default_settings, obscura_get_setting_infos, ...)
 * and never write past the end of a 0.3 struct; this program fails otherwise.
 *
 * What it does, as a 0.3 host would: creates a GL 4.3 core context with EGL (surfaceless, no pbuffer), a linear
 * depth texture of a small scene (a floor, a wall behind it and a box on the floor) and an R16F output texture,
 * then for HBAO, SAO, LSAO, FFAO and REFERENCE (few rays): default settings, a few fields set directly and by
 * name, resolve, the settings table walked with the 0.3 row layout, render, timings, memory, and the AO read
 * back (finite, in [0, 1], clearly occluded in places, not constant). Every settings struct the library writes
 * sits in front of a canary that must stay untouched. Exit 0 when every check passes; otherwise every failed
 * check is printed and the exit status is 1.
 *
 * C99, -Wall -Wextra -pedantic. GL comes through eglGetProcAddress only: no GL header is included. */
#define EGL_NO_X11 1
#define MESA_EGL_NO_X11_HEADERS 1
#include <EGL/egl.h>

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "obscura_0_3.h"

#ifdef OBSCURA_OBSCURA_H
#error "the 0.3 ABI host must not see the current obscura.h"
#endif
#if OBSCURA_VERSION != 300
#error "obscura_0_3.h is not the 0.3 header"
#endif

/* ---- GL, declared here (no GL header): the few types, constants and entry points this host uses ---------- */
#if defined(_WIN32)
#define HOST_GL_APIENTRY __stdcall
#else
#define HOST_GL_APIENTRY
#endif
typedef unsigned int host_GLenum;
typedef unsigned int host_GLuint;
typedef int host_GLint;
typedef int host_GLsizei;
typedef unsigned char host_GLubyte;

#define GL_NO_ERROR 0
#define GL_TEXTURE_2D 0x0DE1
#define GL_UNPACK_ALIGNMENT 0x0CF5
#define GL_PACK_ALIGNMENT 0x0D05
#define GL_TEXTURE_MAG_FILTER 0x2800
#define GL_TEXTURE_MIN_FILTER 0x2801
#define GL_NEAREST 0x2600
#define GL_RED 0x1903
#define GL_FLOAT 0x1406
#define GL_R16F 0x822D
#define GL_R32F 0x822E
#define GL_RENDERER 0x1F01
#define GL_VERSION 0x1F02
#define GL_MAJOR_VERSION 0x821B
#define GL_MINOR_VERSION 0x821C

typedef host_GLenum(HOST_GL_APIENTRY* host_glGetError_fn)(void);
typedef const host_GLubyte*(HOST_GL_APIENTRY* host_glGetString_fn)(host_GLenum name);
typedef void(HOST_GL_APIENTRY* host_glGetIntegerv_fn)(host_GLenum name, host_GLint* data);
typedef void(HOST_GL_APIENTRY* host_glGenTextures_fn)(host_GLsizei n, host_GLuint* textures);
typedef void(HOST_GL_APIENTRY* host_glDeleteTextures_fn)(host_GLsizei n, const host_GLuint* textures);
typedef void(HOST_GL_APIENTRY* host_glBindTexture_fn)(host_GLenum target, host_GLuint texture);
typedef void(HOST_GL_APIENTRY* host_glTexParameteri_fn)(host_GLenum target, host_GLenum name, host_GLint value);
typedef void(HOST_GL_APIENTRY* host_glTexStorage2D_fn)(host_GLenum target, host_GLsizei levels,
                                                       host_GLenum internal_format, host_GLsizei width,
                                                       host_GLsizei height);
typedef void(HOST_GL_APIENTRY* host_glTexSubImage2D_fn)(host_GLenum target, host_GLint level, host_GLint x,
                                                        host_GLint y, host_GLsizei width, host_GLsizei height,
                                                        host_GLenum format, host_GLenum type, const void* pixels);
typedef void(HOST_GL_APIENTRY* host_glGetTexImage_fn)(host_GLenum target, host_GLint level, host_GLenum format,
                                                      host_GLenum type, void* pixels);
typedef void(HOST_GL_APIENTRY* host_glPixelStorei_fn)(host_GLenum name, host_GLint value);

static struct {
    host_glGetError_fn GetError;
    host_glGetString_fn GetString;
    host_glGetIntegerv_fn GetIntegerv;
    host_glGenTextures_fn GenTextures;
    host_glDeleteTextures_fn DeleteTextures;
    host_glBindTexture_fn BindTexture;
    host_glTexParameteri_fn TexParameteri;
    host_glTexStorage2D_fn TexStorage2D;
    host_glTexSubImage2D_fn TexSubImage2D;
    host_glGetTexImage_fn GetTexImage;
    host_glPixelStorei_fn PixelStorei;
} gl;

/* EGL 1.5 / extension tokens, in case egl.h predates them. */
#ifndef EGL_CONTEXT_MAJOR_VERSION
#define EGL_CONTEXT_MAJOR_VERSION 0x3098
#endif
#ifndef EGL_CONTEXT_MINOR_VERSION
#define EGL_CONTEXT_MINOR_VERSION 0x30FB
#endif
#ifndef EGL_CONTEXT_OPENGL_PROFILE_MASK
#define EGL_CONTEXT_OPENGL_PROFILE_MASK 0x30FD
#endif
#ifndef EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT
#define EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT 0x00000001
#endif
#define HOST_EGL_PLATFORM_SURFACELESS_MESA 0x31DD /* EGL_MESA_platform_surfaceless */
typedef EGLDisplay (*host_eglGetPlatformDisplayEXT_fn)(EGLenum platform, void* native_display,
                                                      const EGLint* attributes);

/* ---- Checks ---------------------------------------------------------------------------------------------- */
static int failures = 0;

#define CHECK(cond) check_((cond) != 0, #cond, __FILE__, __LINE__, "")
#define CHECK_MSG(cond, context) check_((cond) != 0, #cond, __FILE__, __LINE__, (context))

static int check_(int ok, const char* text, const char* file, int line, const char* context) {
    if (!ok) {
        fprintf(stderr, "%s:%d: FAILED: %s%s%s\n", file, line, text, context[0] ? "  -- " : "", context);
        ++failures;
    }
    return ok;
}

static int check_status_(obscura_status status, obscura_status expected, const char* call, const char* file,
                         int line, obscura_context* context) {
    if (status == expected) return 1;
    fprintf(stderr, "%s:%d: FAILED: %s returned %s, expected %s", file, line, call, obscura_status_string(status),
            obscura_status_string(expected));
    if (context) fprintf(stderr, " (last error: %s)", obscura_get_last_error(context));
    fputc('\n', stderr);
    ++failures;
    return 0;
}
#define CHECK_STATUS(call, expected, context) check_status_((call), (expected), #call, __FILE__, __LINE__, (context))
#define CHECK_OK(call, context) CHECK_STATUS(call, OBSCURA_OK, context)

/* Messages of calls that are expected to fail are not printed. */
static int quiet_log = 0;
static void host_log(obscura_log_level level, obscura_status status, const char* message, void* user_data) {
    (void)user_data;
    if (quiet_log && level == OBSCURA_LOG_ERROR) return;
    fprintf(stderr, "obscura %s (%s): %s\n", level == OBSCURA_LOG_ERROR ? "error" : level == OBSCURA_LOG_WARNING ? "warning" : "info",
            obscura_status_string(status), message);
}

/* A 0.3-sized obscura_settings followed by bytes the library must never write: a library that wrote a newer,
   larger obscura_settings into a 0.3 host's struct would overwrite them. */
#define CANARY_BYTES 64
#define CANARY_VALUE 0xA5
typedef struct guarded_settings {
    obscura_settings s;
    unsigned char canary[CANARY_BYTES];
} guarded_settings;

static void guard(guarded_settings* g) {
    memset(&g->s, 0, sizeof g->s);
    memset(g->canary, CANARY_VALUE, sizeof g->canary);
}

static int canary_intact(const guarded_settings* g) {
    size_t i;
    for (i = 0; i < sizeof g->canary; ++i)
        if (g->canary[i] != CANARY_VALUE) return 0;
    return 1;
}

/* ---- The scene: linear view depth of a floor, a wall and a box, seen through a perspective camera --------- */
enum { DEPTH_W = 96, DEPTH_H = 64, GUARD = 8, OUT_W = DEPTH_W - 2 * GUARD, OUT_H = DEPTH_H - 2 * GUARD };

static const double kFovY = 1.0471975511965976; /* 60 degrees */
static const double kNear = 0.1, kFar = 100.0;

static void make_projection(float m[16]) {
    const double f = 1.0 / tan(kFovY / 2.0), aspect = (double)DEPTH_W / DEPTH_H;
    memset(m, 0, 16 * sizeof m[0]);
    m[0] = (float)(f / aspect);
    m[5] = (float)f;
    m[10] = (float)((kFar + kNear) / (kNear - kFar));
    m[11] = -1.0f;
    m[14] = (float)(2.0 * kFar * kNear / (kNear - kFar));
}

/* Ray from the eye along d (d.z = -1, so the hit's view depth is t) against an axis-aligned box. */
static double hit_box(const double d[3], const double lo[3], const double hi[3]) {
    double t_enter = 0.0, t_exit = 1e30;
    int axis;
    for (axis = 0; axis < 3; ++axis) {
        double t0, t1;
        if (d[axis] == 0.0) {
            if (lo[axis] > 0.0 || hi[axis] < 0.0) return -1.0;
            continue;
        }
        t0 = lo[axis] / d[axis];
        t1 = hi[axis] / d[axis];
        if (t0 > t1) {
            double swap = t0;
            t0 = t1;
            t1 = swap;
        }
        if (t0 > t_enter) t_enter = t0;
        if (t1 < t_exit) t_exit = t1;
    }
    return t_enter <= t_exit && t_enter > 0.0 ? t_enter : -1.0;
}

static void make_depth(float* depth) {
    const double tan_y = tan(kFovY / 2.0), tan_x = tan_y * DEPTH_W / DEPTH_H;
    const double floor_y = -1.0, wall_z = -5.0;
    const double box_lo[3] = {-0.6, -1.0, -3.4}, box_hi[3] = {0.4, -0.2, -2.6};
    int x, y;
    for (y = 0; y < DEPTH_H; ++y) {
        for (x = 0; x < DEPTH_W; ++x) {
            const double u = 2.0 * (x + 0.5) / DEPTH_W - 1.0, v = 2.0 * (y + 0.5) / DEPTH_H - 1.0;
            const double d[3] = {u * tan_x, v * tan_y, -1.0};
            double t = -wall_z; /* the wall z = -5 fills the view behind everything */
            double t_box;
            if (d[1] < 0.0 && floor_y / d[1] < t) t = floor_y / d[1];
            t_box = hit_box(d, box_lo, box_hi);
            if (t_box > 0.0 && t_box < t) t = t_box;
            depth[y * DEPTH_W + x] = (float)t; /* row 0 is the bottom row, as GL stores it */
        }
    }
}

/* ---- EGL ------------------------------------------------------------------------------------------------- */
static int has_extension(const char* list, const char* name) {
    const size_t length = strlen(name);
    const char* at;
    if (!list) return 0;
    for (at = strstr(list, name); at; at = strstr(at + 1, name)) {
        if ((at == list || at[-1] == ' ') && (at[length] == '\0' || at[length] == ' ')) return 1;
    }
    return 0;
}

static obscura_gl_function host_get_proc_address(const char* name) {
    return (obscura_gl_function)eglGetProcAddress(name);
}

typedef struct egl_state {
    EGLDisplay display;
    EGLContext context;
} egl_state;

static int create_gl_context(egl_state* egl) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS); /* NULL without client extensions */
    const char* extensions;
    EGLint major = 0, minor = 0;
    EGLConfig config = (EGLConfig)0;
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    egl->display = EGL_NO_DISPLAY;
    egl->context = EGL_NO_CONTEXT;
    if (has_extension(client, "EGL_MESA_platform_surfaceless") && has_extension(client, "EGL_EXT_platform_base")) {
        host_eglGetPlatformDisplayEXT_fn get_platform_display =
            (host_eglGetPlatformDisplayEXT_fn)eglGetProcAddress("eglGetPlatformDisplayEXT");
        if (get_platform_display)
            egl->display = get_platform_display(HOST_EGL_PLATFORM_SURFACELESS_MESA, NULL, NULL);
    }
    if (egl->display == EGL_NO_DISPLAY) egl->display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (egl->display == EGL_NO_DISPLAY) {
        fprintf(stderr, "no EGL display (eglGetError 0x%04x)\n", (unsigned)eglGetError());
        return 0;
    }
    if (!eglInitialize(egl->display, &major, &minor)) {
        fprintf(stderr, "eglInitialize failed (0x%04x)\n", (unsigned)eglGetError());
        egl->display = EGL_NO_DISPLAY;
        return 0;
    }
    extensions = eglQueryString(egl->display, EGL_EXTENSIONS);
    if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
        fprintf(stderr, "the EGL display has no EGL_KHR_surfaceless_context\n");
        return 0;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        fprintf(stderr, "eglBindAPI(EGL_OPENGL_API) failed (0x%04x)\n", (unsigned)eglGetError());
        return 0;
    }
    if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
        /* A desktop-GL config; no surface is ever created with it. */
        const EGLint config_attributes[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint count = 0;
        if (!eglChooseConfig(egl->display, config_attributes, &config, 1, &count) || count == 0) {
            fprintf(stderr, "eglChooseConfig found no desktop-GL config (0x%04x)\n", (unsigned)eglGetError());
            return 0;
        }
    }
    egl->context = eglCreateContext(egl->display, config, EGL_NO_CONTEXT, context_attributes);
    if (egl->context == EGL_NO_CONTEXT) {
        fprintf(stderr, "eglCreateContext(GL 4.3 core) failed (0x%04x)\n", (unsigned)eglGetError());
        return 0;
    }
    if (!eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl->context)) {
        fprintf(stderr, "eglMakeCurrent without a surface failed (0x%04x)\n", (unsigned)eglGetError());
        return 0;
    }
    printf("EGL %d.%d %s\n", (int)major, (int)minor, eglQueryString(egl->display, EGL_VENDOR));
    return 1;
}

static void destroy_gl_context(egl_state* egl) {
    if (egl->display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (egl->context != EGL_NO_CONTEXT) eglDestroyContext(egl->display, egl->context);
    eglTerminate(egl->display);
    eglReleaseThread();
}

/* eglGetProcAddress returns every GL function as one function-pointer type; each is cast to its own. */
#define LOAD_GL(member, type, name)                                                  \
    do {                                                                             \
        gl.member = (type)host_get_proc_address(name);                               \
        if (!gl.member) {                                                            \
            fprintf(stderr, "eglGetProcAddress(\"%s\") returned NULL\n", name);      \
            return 0;                                                                \
        }                                                                            \
    } while (0)

static int load_gl(void) {
    host_GLint major = 0, minor = 0;
    LOAD_GL(GetError, host_glGetError_fn, "glGetError");
    LOAD_GL(GetString, host_glGetString_fn, "glGetString");
    LOAD_GL(GetIntegerv, host_glGetIntegerv_fn, "glGetIntegerv");
    LOAD_GL(GenTextures, host_glGenTextures_fn, "glGenTextures");
    LOAD_GL(DeleteTextures, host_glDeleteTextures_fn, "glDeleteTextures");
    LOAD_GL(BindTexture, host_glBindTexture_fn, "glBindTexture");
    LOAD_GL(TexParameteri, host_glTexParameteri_fn, "glTexParameteri");
    LOAD_GL(TexStorage2D, host_glTexStorage2D_fn, "glTexStorage2D");
    LOAD_GL(TexSubImage2D, host_glTexSubImage2D_fn, "glTexSubImage2D");
    LOAD_GL(GetTexImage, host_glGetTexImage_fn, "glGetTexImage");
    LOAD_GL(PixelStorei, host_glPixelStorei_fn, "glPixelStorei");
    gl.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl.GetIntegerv(GL_MINOR_VERSION, &minor);
    printf("GL %s, %s\n", (const char*)gl.GetString(GL_VERSION), (const char*)gl.GetString(GL_RENDERER));
    if (major * 10 + minor < 43) {
        fprintf(stderr, "the context is GL %d.%d, not 4.3 or newer\n", (int)major, (int)minor);
        return 0;
    }
    return 1;
}

static host_GLuint make_texture(host_GLenum format, int width, int height, const float* pixels) {
    host_GLuint texture = 0;
    gl.GenTextures(1, &texture);
    gl.BindTexture(GL_TEXTURE_2D, texture);
    gl.TexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RED, GL_FLOAT, pixels);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    return texture;
}

/* ---- The settings table, read with the 0.3 row layout ---------------------------------------------------- */
static size_t method_block_offset(obscura_method method, size_t* size) {
    switch (method) {
    case OBSCURA_METHOD_HBAO: *size = sizeof(obscura_hbao_settings); return offsetof(obscura_settings, hbao);
    case OBSCURA_METHOD_SAO: *size = sizeof(obscura_sao_settings); return offsetof(obscura_settings, sao);
    case OBSCURA_METHOD_LSAO: *size = sizeof(obscura_lsao_settings); return offsetof(obscura_settings, lsao);
    case OBSCURA_METHOD_FFAO: *size = sizeof(obscura_ffao_settings); return offsetof(obscura_settings, ffao);
    case OBSCURA_METHOD_REFERENCE:
        *size = sizeof(obscura_reference_settings);
        return offsetof(obscura_settings, reference);
    default: *size = 0; return 0;
    }
}

static const obscura_setting_info* find_row(const obscura_setting_info* infos, uint32_t count, const char* name) {
    uint32_t i;
    for (i = 0; i < count; ++i)
        if (infos[i].name && strcmp(infos[i].name, name) == 0) return &infos[i];
    return NULL;
}

static int printable_name(const char* name) {
    size_t i;
    if (!name || !name[0]) return 0;
    for (i = 0; name[i]; ++i) {
        const char c = name[i];
        if (i >= 64 || !((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return 0;
    }
    return 1;
}

/* Every row: a plausible name, a known type, a range, an offset inside the method's block of the 0.3 struct.
   Then each row's setting is written by name into a zeroed 0.3 struct and must land at that offset. */
static void check_setting_table(obscura_method method, const char* method_name) {
    const obscura_setting_info* infos = NULL;
    uint32_t count = 0, i;
    size_t block_size = 0;
    const size_t block = method_block_offset(method, &block_size);
    guarded_settings scratch;
    char where[160];

    if (!CHECK_OK(obscura_get_setting_infos(method, &infos, &count), NULL)) return;
    snprintf(where, sizeof where, "%s settings table", method_name);
    if (!CHECK_MSG(infos != NULL && count > 0, where)) return;
    /* Rows are read with the 0.3 stride: a table of another layout gives garbage names, types and offsets. */
    guard(&scratch);
    scratch.s.struct_size = sizeof scratch.s;
    scratch.s.method = method;
    for (i = 0; i < count; ++i) {
        const obscura_setting_info* row = &infos[i];
        const char* name = row->name;
        double value;
        snprintf(where, sizeof where, "%s row %u of %u (\"%.40s\")", method_name, (unsigned)i, (unsigned)count,
                 printable_name(name) ? name : "?");
        if (!CHECK_MSG(printable_name(name), where)) continue;
        if (!CHECK_MSG(row->type == OBSCURA_SETTING_FLOAT || row->type == OBSCURA_SETTING_INT ||
                           row->type == OBSCURA_SETTING_TOGGLE,
                       where))
            continue;
        CHECK_MSG(isfinite(row->min_value) && isfinite(row->max_value) && isfinite(row->default_value), where);
        CHECK_MSG(row->min_value <= row->max_value, where);
        CHECK_MSG(row->unit != NULL && row->description != NULL && row->description[0] != '\0', where);
        if (!CHECK_MSG(row->offset < sizeof(obscura_settings) && row->offset + 4 <= sizeof(obscura_settings), where))
            continue;
        CHECK_MSG(row->offset % 4 == 0, where);
        if (!CHECK_MSG(row->offset >= block && row->offset + 4 <= block + block_size, where)) continue;
        if (row->type == OBSCURA_SETTING_TOGGLE) CHECK_MSG(row->min_value == 0.0 && row->max_value == 1.0, where);

        /* Written by name, read back at the table's offset in the 0.3 layout. */
        value = row->type == OBSCURA_SETTING_TOGGLE ? 1.0 : row->max_value != 0.0 ? row->max_value : row->min_value;
        if (!CHECK_OK(obscura_set_setting(&scratch.s, name, value), NULL)) continue;
        {
            const unsigned char* field = (const unsigned char*)&scratch.s + row->offset;
            if (row->type == OBSCURA_SETTING_FLOAT) {
                float stored;
                memcpy(&stored, field, sizeof stored);
                CHECK_MSG(stored == (float)value, where);
            } else {
                int32_t stored;
                memcpy(&stored, field, sizeof stored);
                CHECK_MSG(stored == (row->type == OBSCURA_SETTING_TOGGLE ? (int32_t)OBSCURA_TOGGLE_ON : (int32_t)value),
                          where);
            }
        }
    }
    snprintf(where, sizeof where, "%s: obscura_set_setting wrote past the 0.3 obscura_settings", method_name);
    CHECK_MSG(canary_intact(&scratch), where);
    CHECK_MSG(scratch.s.struct_size == sizeof(obscura_settings) && scratch.s.method == method, where);

    /* Rows every 0.3 host may rely on, at the offsets this compiler gives the 0.3 struct. */
    {
        const struct {
            obscura_method method;
            const char* name;
            size_t offset;
        } known[] = {
            {OBSCURA_METHOD_HBAO, "radius", offsetof(obscura_settings, hbao.radius)},
            {OBSCURA_METHOD_HBAO, "directions", offsetof(obscura_settings, hbao.directions)},
            {OBSCURA_METHOD_HBAO, "steps", offsetof(obscura_settings, hbao.steps)},
            {OBSCURA_METHOD_HBAO, "blur_sharpness", offsetof(obscura_settings, hbao.blur_sharpness)},
            {OBSCURA_METHOD_SAO, "radius", offsetof(obscura_settings, sao.radius)},
            {OBSCURA_METHOD_SAO, "samples", offsetof(obscura_settings, sao.samples)},
            {OBSCURA_METHOD_SAO, "blur_depth_range", offsetof(obscura_settings, sao.blur_depth_range)},
            {OBSCURA_METHOD_LSAO, "radius", offsetof(obscura_settings, lsao.radius)},
            {OBSCURA_METHOD_LSAO, "preset", offsetof(obscura_settings, lsao.preset)},
            {OBSCURA_METHOD_LSAO, "power", offsetof(obscura_settings, lsao.power)},
            {OBSCURA_METHOD_FFAO, "radius", offsetof(obscura_settings, ffao.radius)},
            {OBSCURA_METHOD_FFAO, "sectors", offsetof(obscura_settings, ffao.sectors)},
            {OBSCURA_METHOD_FFAO, "power", offsetof(obscura_settings, ffao.power)},
            {OBSCURA_METHOD_REFERENCE, "radius", offsetof(obscura_settings, reference.radius)},
            {OBSCURA_METHOD_REFERENCE, "rays", offsetof(obscura_settings, reference.rays)},
            {OBSCURA_METHOD_REFERENCE, "first_ray", offsetof(obscura_settings, reference.first_ray)},
        };
        size_t k;
        for (k = 0; k < sizeof known / sizeof known[0]; ++k) {
            const obscura_setting_info* row;
            if (known[k].method != method) continue;
            row = find_row(infos, count, known[k].name);
            snprintf(where, sizeof where, "%s.%s in the table at offset %u", method_name, known[k].name,
                     (unsigned)known[k].offset);
            if (CHECK_MSG(row != NULL, where)) CHECK_MSG(row->offset == known[k].offset, where);
        }
    }
}

/* ---- One method, as a 0.3 host renders it ---------------------------------------------------------------- */
typedef struct frame {
    obscura_context* context;
    host_GLuint depth_texture;
    host_GLuint output_texture;
    float projection[16];
    uint64_t renders; /* obscura_render calls that returned OK on this context */
} frame;

/* What the host changes: a couple of fields set directly, and one setting set by name (`name` to `value`, which
   must land in `field`, a float or an int32_t), and the radius set directly (metres). */
typedef struct customisation {
    float radius;
    const char* name;
    double value;
    const void* field;
    int field_is_float;
} customisation;

static customisation customise(obscura_settings* s, obscura_method method) {
    customisation c;
    c.field_is_float = 0;
    switch (method) {
    case OBSCURA_METHOD_HBAO:
        c.radius = s->hbao.radius = 1.5f;
        s->hbao.directions = 8;
        c.name = "steps";
        c.value = 8;
        c.field = &s->hbao.steps;
        break;
    case OBSCURA_METHOD_SAO:
        c.radius = s->sao.radius = 1.25f;
        c.name = "samples";
        c.value = 11;
        c.field = &s->sao.samples;
        break;
    case OBSCURA_METHOD_LSAO:
        c.radius = s->lsao.radius = 1.5f;
        c.name = "preset";
        c.value = 1;
        c.field = &s->lsao.preset;
        break;
    case OBSCURA_METHOD_FFAO:
        c.radius = s->ffao.radius = 2.0f;
        c.name = "intensity";
        c.value = 1.25;
        c.field = &s->ffao.intensity;
        c.field_is_float = 1;
        break;
    case OBSCURA_METHOD_REFERENCE:
    default:
        c.radius = s->reference.radius = 1.5f;
        s->reference.rays_per_dispatch = 8;
        c.name = "rays"; /* few rays: the reference is slow by design */
        c.value = 8;
        c.field = &s->reference.rays;
        break;
    }
    return c;
}

static void run_method(frame* f, obscura_method method) {
    const char* method_name = obscura_method_name(method);
    guarded_settings settings, resolved, reference;
    obscura_input input;
    obscura_output output;
    obscura_timing timings[32];
    uint32_t timing_count = 0, i;
    uint64_t frame_index = 0, memory = 0;
    customisation c;
    double read = -1.0;
    float* ao;
    float fill[OUT_W * OUT_H];
    char where[160];

    if (!CHECK(method_name != NULL)) return;
    printf("-- %s\n", method_name);
    CHECK_MSG(obscura_method_available(method) == 1, method_name);

    /* Defaults into a 0.3 struct: the 0.3 size, the method, and nothing written beyond. */
    guard(&settings);
    if (!CHECK_OK(obscura_default_settings(method, &settings.s), NULL)) return;
    snprintf(where, sizeof where, "%s: obscura_default_settings", method_name);
    CHECK_MSG(settings.s.struct_size == sizeof(obscura_settings), where);
    CHECK_MSG(settings.s.method == method, where);
    CHECK_MSG(canary_intact(&settings), where);

    c = customise(&settings.s, method);
    CHECK_OK(obscura_set_setting(&settings.s, c.name, c.value), NULL);
    snprintf(where, sizeof where, "%s: obscura_set_setting(\"%s\", %g)", method_name, c.name, c.value);
    if (c.field_is_float) {
        float stored;
        memcpy(&stored, c.field, sizeof stored);
        CHECK_MSG(stored == (float)c.value, where);
    } else {
        int32_t stored;
        memcpy(&stored, c.field, sizeof stored);
        CHECK_MSG(stored == (int32_t)c.value, where);
    }
    CHECK_MSG(canary_intact(&settings), where);
    if (CHECK_OK(obscura_get_setting(&settings.s, c.name, &read), NULL)) CHECK_MSG(read == c.value, where);
    snprintf(where, sizeof where, "%s: obscura_get_setting(\"radius\") after radius = %g", method_name, c.radius);
    if (CHECK_OK(obscura_get_setting(&settings.s, "radius", &read), NULL)) CHECK_MSG(read == (double)c.radius, where);
    CHECK_STATUS(obscura_get_setting(&settings.s, "no_such_setting", &read), OBSCURA_STATUS_UNKNOWN_SETTING, NULL);

    /* Resolve into another 0.3 struct. */
    guard(&resolved);
    if (CHECK_OK(obscura_resolve_settings(f->context, &settings.s, &resolved.s), f->context)) {
        snprintf(where, sizeof where, "%s: obscura_resolve_settings", method_name);
        CHECK_MSG(resolved.s.struct_size == sizeof(obscura_settings), where);
        CHECK_MSG(resolved.s.method == method, where);
        CHECK_MSG(canary_intact(&resolved), where);
        if (CHECK_OK(obscura_get_setting(&resolved.s, "radius", &read), NULL)) CHECK_MSG(read == (double)c.radius, where);
        if (CHECK_OK(obscura_get_setting(&resolved.s, c.name, &read), NULL)) CHECK_MSG(read == c.value, where);
    }
    /* The matching reference settings, also a 0.3 struct written by the library. */
    guard(&reference);
    if (CHECK_OK(obscura_reference_settings_for(&settings.s, &reference.s), NULL)) {
        snprintf(where, sizeof where, "%s: obscura_reference_settings_for", method_name);
        CHECK_MSG(reference.s.struct_size == sizeof(obscura_settings), where);
        CHECK_MSG(reference.s.method == OBSCURA_METHOD_REFERENCE, where);
        CHECK_MSG(canary_intact(&reference), where);
    }
    {
        const float distances[4] = {0.0f, 0.25f, 1.0f, 100.0f};
        float rho[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
        if (CHECK_OK(obscura_evaluate_falloff(&settings.s, distances, rho, 4), NULL)) {
            snprintf(where, sizeof where, "%s: obscura_evaluate_falloff", method_name);
            for (i = 0; i < 4; ++i) CHECK_MSG(rho[i] >= 0.0f && rho[i] <= 1.0f, where);
            CHECK_MSG(rho[0] >= rho[3], where);
        }
    }

    check_setting_table(method, method_name);

    /* Render with 0.3-sized input and output. The output is filled with 7 first: every value must be rewritten. */
    memset(&input, 0, sizeof input);
    input.struct_size = sizeof input;
    input.depth_texture = f->depth_texture;
    input.depth_kind = OBSCURA_DEPTH_LINEAR_VIEW;
    input.depth_width = DEPTH_W;
    input.depth_height = DEPTH_H;
    input.output_rect.x = GUARD;
    input.output_rect.y = GUARD;
    input.output_rect.width = OUT_W;
    input.output_rect.height = OUT_H;
    memcpy(input.projection, f->projection, sizeof input.projection);
    input.projection_layout = OBSCURA_MATRIX_COLUMN_MAJOR;
    input.meters_to_view_units = 1.0f;
    memset(&output, 0, sizeof output);
    output.struct_size = sizeof output;
    output.texture = f->output_texture;

    for (i = 0; i < OUT_W * OUT_H; ++i) fill[i] = 7.0f;
    gl.BindTexture(GL_TEXTURE_2D, f->output_texture);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, OUT_W, OUT_H, GL_RED, GL_FLOAT, fill);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    CHECK(gl.GetError() == GL_NO_ERROR);

    CHECK_OK(obscura_prepare(f->context, DEPTH_W, DEPTH_H, &settings.s), f->context);
    if (!CHECK_OK(obscura_render(f->context, &input, &settings.s, &output), f->context)) return;
    ++f->renders;
    snprintf(where, sizeof where, "%s: GL error after obscura_render", method_name);
    CHECK_MSG(gl.GetError() == GL_NO_ERROR, where);

    /* The AO, read back. */
    ao = (float*)malloc(sizeof(float) * OUT_W * OUT_H);
    if (!CHECK(ao != NULL)) return;
    gl.BindTexture(GL_TEXTURE_2D, f->output_texture);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.GetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, ao);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    CHECK(gl.GetError() == GL_NO_ERROR);
    {
        int finite_in_range = 1, occluded = 0;
        float lo = 1e30f, hi = -1e30f;
        double sum = 0.0;
        for (i = 0; i < OUT_W * OUT_H; ++i) {
            const float v = ao[i];
            if (!isfinite(v) || v < 0.0f || v > 1.0f) {
                if (finite_in_range)
                    fprintf(stderr, "%s: AO at (%u, %u) is %g\n", method_name, (unsigned)(i % OUT_W),
                            (unsigned)(i / OUT_W), (double)v);
                finite_in_range = 0;
                continue;
            }
            if (v < lo) lo = v;
            if (v > hi) hi = v;
            if (v < 0.9f) ++occluded;
            sum += v;
        }
        printf("   AO over %dx%d: min %.3f  max %.3f  mean %.3f  below 0.9: %d px\n", OUT_W, OUT_H, (double)lo,
               (double)hi, sum / (OUT_W * OUT_H), occluded);
        snprintf(where, sizeof where, "%s: every AO value finite and in [0, 1]", method_name);
        CHECK_MSG(finite_in_range, where);
        snprintf(where, sizeof where, "%s: the floor by the box and the wall is occluded", method_name);
        CHECK_MSG(lo < 0.8f && occluded >= OUT_W * OUT_H / 100, where); /* at least 1 % of the pixels */
        snprintf(where, sizeof where, "%s: the AO is not constant", method_name);
        CHECK_MSG(hi - lo > 0.1f, where);
    }
    free(ao);

    /* Timings: the frame was read back, so its timer queries are complete. */
    if (CHECK_OK(obscura_get_timings(f->context, timings, 32, &timing_count, &frame_index), f->context)) {
        snprintf(where, sizeof where, "%s: obscura_get_timings (%u entries, frame %llu of %llu)", method_name,
                 (unsigned)timing_count, (unsigned long long)frame_index, (unsigned long long)f->renders);
        CHECK_MSG(timing_count > 0 && frame_index >= 1 && frame_index <= f->renders, where);
        for (i = 0; i < timing_count && i < 32; ++i) {
            CHECK_MSG(timings[i].label != NULL && timings[i].label[0] != '\0', where);
            CHECK_MSG(isfinite(timings[i].milliseconds) && timings[i].milliseconds >= 0.0, where);
        }
        if (timing_count > 0 && timings[0].label) CHECK_MSG(strcmp(timings[0].label, "total") == 0, where);
    }
    if (CHECK_OK(obscura_get_memory_usage(f->context, &memory), f->context)) {
        snprintf(where, sizeof where, "%s: obscura_get_memory_usage = %llu bytes", method_name,
                 (unsigned long long)memory);
        CHECK_MSG(memory > 0, where);
    }

    /* A struct_size that no version ever had is still refused, and nothing is rendered. */
    {
        obscura_settings bad = settings.s;
        bad.struct_size = 1;
        quiet_log = 1;
        CHECK_STATUS(obscura_render(f->context, &input, &bad, &output), OBSCURA_STATUS_INVALID_STRUCT_SIZE, NULL);
        quiet_log = 0;
        CHECK(gl.GetError() == GL_NO_ERROR);
    }
}

int main(void) {
    egl_state egl;
    obscura_context_desc desc;
    obscura_context* rejected = NULL;
    frame f;
    float depth[DEPTH_W * DEPTH_H];
    float zero[OUT_W * OUT_H];
    const obscura_method methods[] = {OBSCURA_METHOD_HBAO, OBSCURA_METHOD_SAO, OBSCURA_METHOD_LSAO,
                                      OBSCURA_METHOD_FFAO, OBSCURA_METHOD_REFERENCE};
    size_t m;

    printf("0.3 host (header %d, obscura_settings %u bytes, obscura_setting_info %u bytes) against library %u\n",
           OBSCURA_VERSION, (unsigned)sizeof(obscura_settings), (unsigned)sizeof(obscura_setting_info),
           (unsigned)obscura_version());
    CHECK(obscura_version() / 10000 == OBSCURA_VERSION_MAJOR && obscura_version() >= OBSCURA_VERSION);

    if (!create_gl_context(&egl) || !load_gl()) {
        fprintf(stderr, "FAILED: no GL 4.3 core context\n");
        destroy_gl_context(&egl);
        return 1;
    }

    /* The context, described with the 0.3 desc and the 0.3 header version. */
    memset(&desc, 0, sizeof desc);
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = host_get_proc_address;
    desc.log = host_log;
    memset(&f, 0, sizeof f);
    {
        /* Another major version, and a struct_size no version had, are refused. */
        obscura_context_desc other = desc;
        quiet_log = 1;
        other.header_version = (OBSCURA_VERSION_MAJOR + 1) * 10000 + OBSCURA_VERSION_MINOR * 100;
        CHECK_STATUS(obscura_create_context(&other, &rejected), OBSCURA_STATUS_VERSION_MISMATCH, NULL);
        other.header_version = OBSCURA_VERSION;
        other.struct_size = 1;
        CHECK_STATUS(obscura_create_context(&other, &rejected), OBSCURA_STATUS_INVALID_STRUCT_SIZE, NULL);
        quiet_log = 0;
        CHECK(rejected == NULL);
    }
    if (!CHECK_OK(obscura_create_context(&desc, &f.context), NULL)) {
        fprintf(stderr, "FAILED: obscura_create_context refused the 0.3 header (version %d)\n", OBSCURA_VERSION);
        destroy_gl_context(&egl);
        return 1;
    }

    make_depth(depth);
    make_projection(f.projection);
    memset(zero, 0, sizeof zero);
    f.depth_texture = make_texture(GL_R32F, DEPTH_W, DEPTH_H, depth);
    f.output_texture = make_texture(GL_R16F, OUT_W, OUT_H, zero);
    CHECK(gl.GetError() == GL_NO_ERROR);

    for (m = 0; m < sizeof methods / sizeof methods[0]; ++m) run_method(&f, methods[m]);

    obscura_destroy_context(f.context);
    gl.DeleteTextures(1, &f.depth_texture);
    gl.DeleteTextures(1, &f.output_texture);
    CHECK(gl.GetError() == GL_NO_ERROR);
    destroy_gl_context(&egl);

    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("all checks passed\n");
    return 0;
}
