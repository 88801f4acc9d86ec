/*
 * obscura_integration.c - the integration guide's path (docs/integration.md) as a program: a C99 host with its
 * own GL context and GL loader hands Obscura a depth texture and gets ambient visibility back.
 *
 * The "engine" here is headless: an EGL context (EGL_PLATFORM=surfaceless for machines without a display) and
 * a depth buffer computed on the CPU for a floor meeting a wall, written through the same projection matrix an
 * engine would have rasterised it with. Everything from "1." on is what an engine does.
 *
 * Exit status: 0 when the AO is plausible (finite, in [0, 1], darker in the corner than on the open floor), 1
 * otherwise. It is built against the installed SDK by the packaging test (tests/package).
 */
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <GL/glcorearb.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <obscura/obscura.h>

enum { VISIBLE_W = 160, VISIBLE_H = 90, GUARD_X = 16, GUARD_Y = 9 };
enum { DEPTH_W = VISIBLE_W + 2 * GUARD_X, DEPTH_H = VISIBLE_H + 2 * GUARD_Y };

static const float kNear = 0.1f, kFar = 100.0f, kFovY = 1.0471976f; /* 60 degrees over the depth texture */

/* The engine's projection: GL's perspective matrix, column-major as glUniformMatrix4fv takes it. */
static void perspective(float aspect, float m[16]) {
    const float f = 1.0f / tanf(kFovY * 0.5f);
    memset(m, 0, 16 * sizeof m[0]);
    m[0] = f / aspect;
    m[5] = f;
    m[10] = (kFar + kNear) / (kNear - kFar);
    m[11] = -1.0f;
    m[14] = 2.0f * kFar * kNear / (kNear - kFar);
}

/* Window-space depth of every texel: a floor at y = -1 and a wall at z = -6, seen from the origin. Both planes
   run across the whole view, so the depth depends on the row only. */
static void rasterise_depth(const float projection[16], float* depth) {
    const float tan_half = tanf(kFovY * 0.5f);
    for (int y = 0; y < DEPTH_H; ++y) {
        const float dy = (2.0f * (y + 0.5f) / DEPTH_H - 1.0f) * tan_half; /* the view ray is (dx, dy, -1) */
        float t = 6.0f;                                  /* it reaches the wall's z = -6 at t = 6 ... */
        if (dy < 0.0f && -1.0f / dy < t) t = -1.0f / dy; /* ... unless it meets the floor first */
        const float z_eye = -t;
        const float clip_z = projection[10] * z_eye + projection[14], clip_w = -z_eye;
        for (int x = 0; x < DEPTH_W; ++x) depth[y * DEPTH_W + x] = 0.5f * (clip_z / clip_w) + 0.5f;
    }
}

static void log_message(obscura_log_level level, obscura_status status, const char* message, void* user_data) {
    (void)user_data;
    fprintf(stderr, "obscura %s (%d): %s\n", level == OBSCURA_LOG_ERROR ? "error" : "warning", (int)status, message);
}

static int fail(const char* what) {
    fprintf(stderr, "obscura_integration: %s\n", what);
    return 1;
}

int main(void) {
    /* ---- The engine's GL context (headless here) ---------------------------------------------------- */
    EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, NULL, NULL)) return fail("no EGL display");
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("EGL has no desktop OpenGL");
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config;
    EGLint config_count = 0;
    if (!eglChooseConfig(display, config_attribs, &config, 1, &config_count) || config_count < 1)
        return fail("no EGL config for OpenGL");
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext gl_context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    if (gl_context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, gl_context))
        return fail("no OpenGL 4.3 core context");

    /* The engine's depth buffer: in a real engine, the depth attachment of its G-buffer. */
    float projection[16];
    perspective((float)DEPTH_W / DEPTH_H, projection);
    float* depth = malloc(sizeof(float) * DEPTH_W * DEPTH_H);
    if (!depth) return fail("out of memory");
    rasterise_depth(projection, depth);
    GLuint depth_texture, ao_texture;
    glGenTextures(1, &depth_texture);
    glBindTexture(GL_TEXTURE_2D, depth_texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, DEPTH_W, DEPTH_H);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, DEPTH_W, DEPTH_H, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    free(depth);
    /* Where the AO goes: any R8/R16F/R32F/RG/RGBA texture, or a framebuffer (obscura_output.framebuffer). */
    glGenTextures(1, &ao_texture);
    glBindTexture(GL_TEXTURE_2D, ao_texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_R8, VISIBLE_W, VISIBLE_H);
    glBindTexture(GL_TEXTURE_2D, 0);

    /* ---- 1. One Obscura context per GL context, with the host's own GL loader ------------------------ */
    obscura_context_desc desc;
    memset(&desc, 0, sizeof desc);
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = (obscura_get_proc_address_fn)eglGetProcAddress;
    desc.log = log_message;
    obscura_context* ao = NULL;
    obscura_status status = obscura_create_context(&desc, &ao);
    if (status != OBSCURA_OK) return fail(obscura_status_string(status));

    /* ---- 2. Settings: defaults of a method, then the fields the game tunes --------------------------- */
    obscura_settings settings;
    obscura_default_settings(OBSCURA_METHOD_HBAO, &settings);
    settings.hbao.radius = 1.0f; /* metres (meters_to_view_units converts) */

    /* ---- 3. Each frame: input (depth + projection + visible rectangle) and output ------------------- */
    obscura_input input;
    memset(&input, 0, sizeof input);
    input.struct_size = sizeof input;
    input.depth_texture = depth_texture;
    input.depth_kind = OBSCURA_DEPTH_HARDWARE;
    input.depth_width = DEPTH_W;
    input.depth_height = DEPTH_H;
    input.output_rect.x = GUARD_X; /* the guard band around it feeds occluders, gets no AO */
    input.output_rect.y = GUARD_Y;
    input.output_rect.width = VISIBLE_W;
    input.output_rect.height = VISIBLE_H;
    memcpy(input.projection, projection, sizeof projection);
    obscura_output output;
    memset(&output, 0, sizeof output);
    output.struct_size = sizeof output;
    output.texture = ao_texture;

    status = obscura_render(ao, &input, &settings, &output);
    if (status != OBSCURA_OK) {
        fprintf(stderr, "obscura_render: %s\n", obscura_get_last_error(ao));
        return 1;
    }

    /* ---- The engine samples ao_texture in its lighting; here, read it back and check it -------------- */
    static float visibility[VISIBLE_W * VISIBLE_H];
    glBindTexture(GL_TEXTURE_2D, ao_texture);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, visibility);
    glBindTexture(GL_TEXTURE_2D, 0);
    int bad = 0;
    for (int i = 0; i < VISIBLE_W * VISIBLE_H; ++i) bad += !(visibility[i] >= 0.0f && visibility[i] <= 1.0f);
    /* The floor meets the wall at the row where the view ray through y = -1 reaches z = -6: the darkest row
       around that crease against the floor near the bottom of the image. */
    const float tan_half = tanf(kFovY * 0.5f);
    const int crease = (int)((0.5f - 0.5f / (6.0f * tan_half)) * DEPTH_H) - GUARD_Y;
    double corner = 1.0, open = 0.0;
    for (int y = crease - 3; y <= crease + 3; ++y) {
        double row = 0.0;
        for (int x = 0; x < VISIBLE_W; ++x) row += visibility[y * VISIBLE_W + x];
        if (row / VISIBLE_W < corner) corner = row / VISIBLE_W;
    }
    for (int x = 0; x < VISIBLE_W; ++x) open += visibility[2 * VISIBLE_W + x];
    open /= VISIBLE_W;
    const GLenum gl_error = glGetError();
    uint64_t bytes = 0;
    obscura_get_memory_usage(ao, &bytes);
    printf("obscura %u.%u.%u: visibility at the crease %.3f, open floor %.3f; %d pixels outside [0, 1]; "
           "GPU memory %.1f KiB; GL error 0x%x\n",
           obscura_version() / 10000, obscura_version() / 100 % 100, obscura_version() % 100, corner, open, bad,
           bytes / 1024.0, gl_error);

    /* ---- 4. Shutdown, with the GL context still current ---------------------------------------------- */
    obscura_destroy_context(ao);
    glDeleteTextures(1, &ao_texture);
    glDeleteTextures(1, &depth_texture);
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, gl_context);
    eglTerminate(display);

    if (bad != 0 || gl_error != GL_NO_ERROR) return fail("visibility outside [0, 1] or a GL error");
    if (!(corner < open - 0.05 && open > 0.9)) return fail("the crease is not darker than the open floor");
    return 0;
}
