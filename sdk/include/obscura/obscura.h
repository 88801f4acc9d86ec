/*
 * obscura.h - Obscura: real-time ambient obscurance for OpenGL 4.3 renderers.
 *
 * This header is the whole public API. It is C99 and C++ compatible, includes no GL header
 * (GL object names are uint32_t) and no C++ types.
 *
 * OVERVIEW
 *   A host renderer creates one obscura_context per GL context with its own GL function loader,
 *   fills an obscura_settings struct, and each frame calls obscura_render() with its depth buffer
 *   (and optionally view-space normals). Obscura writes ambient *visibility* (1 = unoccluded,
 *   0 = fully occluded) into a texture or framebuffer the host names. Every pass is a GLSL compute
 *   shader embedded in the library; the SDK loads GL through the host's get_proc_address into a
 *   private function table and defines no global gl* or glad* symbols.
 *
 * METHODS (papers in docs/algorithms.md)
 *   OBSCURA_METHOD_HBAO       Horizon-based AO: K directions x N steps ray marching with the
 *                             falloff rho0 of Timonen, "Line-Sweep Ambient Obscurance" (EGSR 2013), sec. 6.
 *   OBSCURA_METHOD_SAO        McGuire et al., "Scalable Ambient Obscurance" (HPG 2012): z-MIP hierarchy,
 *                             spiral taps and the AlchemyAO estimator, 2x2 + separable bilateral reconstruction.
 *   OBSCURA_METHOD_LSAO       Timonen, "Line-Sweep Ambient Obscurance" (EGSR 2013): obscure-hull line sweeps in K
 *                             directions, sparse lines gathered per pixel; cost independent of the radius.
 *   OBSCURA_METHOD_FFAO       Timonen, "Screen-Space Far-Field Ambient Obscurance" (HPG 2013): scans in K/2 line
 *                             orientations keep depth peaks per interval in a 1D pyramid, prefix sums average them
 *                             over each sector, and a precomputed table integrates the falloff over slabs; a
 *                             near-field search covers the first 1-2 intervals. The whole depth buffer, any radius.
 *   OBSCURA_METHOD_REFERENCE  The screen-space reference: eq. 1 of the FFAO paper evaluated by cosine-weighted
 *                             rays stepped through the whole depth buffer (its sec. 8), the depth field infinitely
 *                             thick unless `thickness` is set. The ceiling of what a screen-space method can compute
 *                             from a depth buffer (the limit the other methods converge to), not what a viewer
 *                             sees, which the samples' geometry truth (rays against the scene's triangles) measures.
 *   OBSCURA_METHOD_GTAO       Jimenez et al., "Practical Realtime Strategies for Accurate Indirect Occlusion" (2016):
 *                             S slices x N steps per side, the two horizons of each slice integrated in closed form
 *                             against the projected normal (cosine-weighted); or (thickness_mode bitmask) Therrien et
 *                             al., "Screen Space Indirect Lighting with Visibility Bitmask" (2023): occluders of finite
 *                             thickness mark sectors of a 32-bit mask, so light passes behind thin objects.
 *   All six are available in this version; obscura_method_available() and OBSCURA_STATUS_METHOD_NOT_AVAILABLE
 *   remain for a declared method a build leaves out (none does today). A value that names no method of this
 *   library (one from a later header) is INVALID_ENUM.
 *
 * INTEGRATION
 *   1. obscura_context_desc desc = {0};
 *      desc.struct_size = sizeof desc; desc.header_version = OBSCURA_VERSION;
 *      desc.get_proc_address = eglGetProcAddress;             // or glfwGetProcAddress, (obscura_get_proc_address_fn)SDL_GL_GetProcAddress
 *   2. obscura_context* ctx; if (obscura_create_context(&desc, &ctx) != OBSCURA_OK) ... ;
 *   3. obscura_settings settings; obscura_default_settings(OBSCURA_METHOD_HBAO, &settings);
 *      settings.hbao.radius = 1.5f;                           // metres: the falloff now ends at 1.5 m
 *   4. each frame: obscura_input in = {0}; in.struct_size = sizeof in;
 *      in.depth_texture = depth_tex; memcpy(in.projection, proj, sizeof in.projection) (column-major, as given to GL);
 *      in.depth_width/height = depth size; in.output_rect = the visible part (guard band around it);
 *      obscura_output out = {0}; out.struct_size = sizeof out; out.texture = ao_tex;
 *      obscura_render(ctx, &in, &settings, &out);
 *   5. obscura_destroy_context(ctx) with the GL context current.
 *
 * INPUT CONTRACT
 *   - Depth: a GL_TEXTURE_2D or GL_TEXTURE_2D_MULTISAMPLE (sample 0 is used) holding either
 *     hardware depth (GL_DEPTH_COMPONENT16/24/32/32F, DEPTH24_STENCIL8, DEPTH32F_STENCIL8) written
 *     with `projection`, or linear view depth (R16F/R32F: positive distance from the eye plane,
 *     in view units). Hardware depth may come from any projection GL can express: perspective or
 *     orthographic, standard or reversed-Z, finite or infinite far plane, [-1,1] or [0,1] clip depth
 *     (glClipControl), written with the default glDepthRange(0, 1) (a reversed or narrowed depth range is not
 *     in the matrix and is not seen). Not supported: an oblique near plane (a clip plane folded into the
 *     depth row) is refused, possibly as PROJECTION_TRANSPOSED; an oblique orthographic projection (m8, m9
 *     non-zero) is accepted but its view direction taken as -z.
 *     The projection is decoded from the matrix itself; its near/far layout is
 *     validated ("looks transposed" is reported as such). The SDK reads a GL_TEXTURE_2D at its
 *     GL_TEXTURE_BASE_LEVEL (texelFetch's level 0), whose size must be the depth size; so do the normal
 *     and motion-vector textures.
 *   - Pixels at the far-plane clear value (1, or 0 with reversed-Z), NaN or inf, linear depths that are
 *     zero, negative or denormal, and distances of 1e18 view units or more (a ray tracer's "miss"), are
 *     "sky": they receive visibility 1, occlude nothing and do not enter their neighbours' normals or
 *     filters. Every input depth gives finite AO in [0, 1].
 *   - Guard band: the depth texture covers more than the visible image. Occluders are read from the
 *     whole depth texture; AO is written only for `output_rect`. The papers use 10-20 % per side.
 *   - Units: view units are the units of the host's view space; settings distances are metres and
 *     are multiplied by `meters_to_view_units` (default 1).
 *   - Normals (optional): view-space normals in a GL_TEXTURE_2D (RGB, signed float and snorm formats as
 *     is; unsigned formats, R11F_G11F_B10F included since it has no sign bit, decoded as n*2-1) the size
 *     of the depth texture. Without them the SDK reconstructs face normals from depth. A normal facing away
 *     from the eye is taken for a back face's and negated; a zero or non-finite one reads as +z. Smooth-shaded
 *     silhouettes whose interpolated normals face slightly away should be bent towards the eye before they are
 *     passed (e.g. n - min(0, dot(n, v)) v, v towards the eye), or negation turns them into the surface.
 *
 * GL STATE CONTRACT
 *   obscura_render() leaves every GL binding it touches as it found it (program, texture and
 *   sampler bindings on the units it uses, image units, SSBO/UBO bindings, read/draw framebuffers,
 *   active texture, pixel-store state) and leaves no GL error. It never calls glFinish or reads data
 *   back, except when OBSCURA_CONTEXT_FLAG_SYNC_TIMING is set. It issues a glMemoryBarrier (texture
 *   fetch, image access, framebuffer) before its first pass, so inputs the host wrote with image stores
 *   or compute just before the call are seen. Host textures' targets are asked of GL 4.5 (or
 *   ARB_direct_state_access); a 4.3/4.4 context without it can only be probed by binding, whose refusals
 *   (GL_INVALID_OPERATION, consumed) a host's debug output may report. One context per GL context, used
 *   from the thread where that GL context is current.
 *
 * PERFORMANCE (docs/performance.md; NVIDIA H100, GL timer queries, 10 % guard band, median of 200 frames)
 *   method / settings            1280x720          1920x1080         3840x2160     GPU memory, 1080p (0.5)
 *   HBAO K=8  N=12, blur         0.35 ms           0.82 ms           3.83 ms       34.2 MiB
 *   HBAO K=16 N=48, blur         1.86 ms           4.01 ms          15.74 ms       34.2 MiB
 */
#ifndef OBSCURA_OBSCURA_H
#define OBSCURA_OBSCURA_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Export ---------------------------------------------------------------------------------- */
#if defined(OBSCURA_SHARED_LIBRARY)
#  if defined(_WIN32)
#    if defined(OBSCURA_BUILDING_LIBRARY)
#      define OBSCURA_API __declspec(dllexport)
#    else
#      define OBSCURA_API __declspec(dllimport)
#    endif
#  else
#    define OBSCURA_API __attribute__((visibility("default")))
#  endif
#else
#  define OBSCURA_API
#endif

/* ---- Version --------------------------------------------------------------------------------- */
#define OBSCURA_VERSION_MAJOR 0
#define OBSCURA_VERSION_MINOR 5
#define OBSCURA_VERSION_PATCH 0
/* Packed version: major * 10000 + minor * 100 + patch. */
#define OBSCURA_VERSION (OBSCURA_VERSION_MAJOR * 10000 + OBSCURA_VERSION_MINOR * 100 + OBSCURA_VERSION_PATCH)

/* Returns the packed version of the library that is linked (compare with OBSCURA_VERSION). */
OBSCURA_API uint32_t obscura_version(void);

/* ---- Status codes ---------------------------------------------------------------------------- */
/* One table generates the enum and obscura_status_string(): X(name, value, description). */
#define OBSCURA_STATUS_LIST(X)                                                                        \
    X(OK, 0, "success")                                                                               \
    X(NULL_ARGUMENT, 1, "a required pointer argument is NULL")                                        \
    X(INVALID_STRUCT_SIZE, 2, "struct_size does not match any version of the struct")                 \
    X(VERSION_MISMATCH, 3, "header_version is not compatible with the linked library")                \
    X(NO_GL_CONTEXT, 4, "no OpenGL context is current, or get_proc_address returned nothing")         \
    X(GL_VERSION_UNSUPPORTED, 5, "the current OpenGL context is older than 4.3 core")                 \
    X(MISSING_GL_FUNCTION, 6, "get_proc_address did not return a required OpenGL function")           \
    X(WRONG_GL_CONTEXT, 7, "the current GL context is not the one the obscura context was created on") \
    X(INVALID_SIZE, 8, "a size is zero, negative or larger than the GL implementation allows")        \
    X(INVALID_RECT, 9, "the output rectangle is empty or not inside the depth texture")               \
    X(INVALID_TEXTURE, 10, "a GL name is not a texture of the expected target, or its size differs")  \
    X(UNSUPPORTED_FORMAT, 11, "a texture has an internal format the SDK cannot read or write")        \
    X(INVALID_PROJECTION, 12, "the projection matrix is not a GL perspective or orthographic matrix") \
    X(PROJECTION_TRANSPOSED, 13, "the projection matrix looks transposed (row-major given as column-major)") \
    X(INVALID_SETTING, 14, "a setting is NaN, infinite or outside its documented range")              \
    X(INVALID_ENUM, 15, "an enum field holds a value the SDK does not know")                          \
    X(METHOD_NOT_AVAILABLE, 16, "the requested method is not implemented in this version")            \
    X(INVALID_FRAMEBUFFER, 17, "the output framebuffer is incomplete or has no colour attachment 0")   \
    X(SHADER_COMPILE_FAILED, 18, "an embedded shader failed to compile or link (log: log callback)")  \
    X(OUT_OF_MEMORY, 19, "the allocator or the GL implementation ran out of memory")                  \
    X(HOST_GL_ERROR, 20, "the host left a GL error pending before the call; nothing was rendered")    \
    X(GL_ERROR, 21, "a GL error was raised inside the SDK; the message names the pass")               \
    X(UNKNOWN_SETTING, 22, "no setting of that name exists for the method")                           \
    X(INTERNAL_ERROR, 23, "an unexpected internal failure; please report it")                         \
    X(CONTEXT_LOST, 24, "the GL context was lost (GPU reset); destroy the obscura context, recreate both") \
    X(INVALID_VIEW, 25, "the view was not created by this context, or was destroyed")

#define OBSCURA_STATUS_ENUM_ENTRY_(name, value, desc) OBSCURA_STATUS_##name = value,
typedef enum obscura_status {
    OBSCURA_STATUS_LIST(OBSCURA_STATUS_ENUM_ENTRY_)
    OBSCURA_STATUS_COUNT_
} obscura_status;
#undef OBSCURA_STATUS_ENUM_ENTRY_
#define OBSCURA_OK OBSCURA_STATUS_OK

/* Returns "OBSCURA_STATUS_<NAME>: <description>" for a status, or a fixed string for unknown codes. */
OBSCURA_API const char* obscura_status_string(obscura_status status);

/* ---- Host callbacks -------------------------------------------------------------------------- */
/* A GL function pointer as loaders return it; eglGetProcAddress, glfwGetProcAddress, SDL3's
   SDL_GL_GetProcAddress and glad's GLADloadfunc all have the shape of obscura_get_proc_address_fn (SDL2's returns
   void*: cast it). */
typedef void (*obscura_gl_function)(void);
typedef obscura_gl_function (*obscura_get_proc_address_fn)(const char* name);
/* The same with the host's pointer passed back, for loaders that need state (several GL contexts). */
typedef obscura_gl_function (*obscura_get_proc_address_with_user_data_fn)(void* user_data, const char* name);

typedef enum obscura_log_level {
    OBSCURA_LOG_ERROR = 0,
    OBSCURA_LOG_WARNING = 1,
    OBSCURA_LOG_INFO = 2
} obscura_log_level;

/* Receives every error (with the status it returns) and warnings such as shader logs. */
typedef void (*obscura_log_fn)(obscura_log_level level, obscura_status status, const char* message,
                               void* user_data);

/* Optional allocator for all the CPU memory of the context (both functions or neither): the context, its views and
   techniques, LSAO's and FFAO's line layouts (megabytes at 4K, one per layout phase) and the scratch of building
   them, shader sources and logs. (One exception: while obscura_create_context loads GL, the generated loader reads
   the extension list into memory of its own, malloc'd and freed within the call.) `alloc` must return memory aligned for any type, as malloc does (16 bytes on 64-bit
   platforms): the context holds 16-byte aligned members. It may return NULL: the call that needed the memory
   returns OUT_OF_MEMORY and the context stays usable. */
typedef struct obscura_allocator {
    void* (*alloc)(size_t size, void* user_data);
    void (*free)(void* ptr, void* user_data);
    void* user_data;
} obscura_allocator;

/* ---- Context --------------------------------------------------------------------------------- */
typedef struct obscura_context obscura_context;

enum {
    /* Time every pass by glFinish + CPU clock instead of GL timer queries (for benchmarks on
       drivers whose timer queries read 0, such as llvmpipe). Stalls: never use in production. */
    OBSCURA_CONTEXT_FLAG_SYNC_TIMING = 1u << 0,
    /* Check glGetError after every pass and report the pass that raised one (debugging aid). */
    OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES = 1u << 1,
    /* Run the code paths written for GPUs even where GL_RENDERER names a CPU rasteriser (llvmpipe, softpipe,
       SwiftShader), which otherwise get variants of their own: a pass per texel block or run, buffer textures
       instead of storage buffers, no shared-memory tiles, whole LSAO lines. For testing what GPUs run on a
       machine without one (CI under llvmpipe); the images match the CPU paths' within rounding, except LSAO's,
       whose segment_steps then derives the GPUs' 128-step segments (segment_steps = -1 gives the same image).
       Slower there. No effect on a GPU. */
    OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS = 1u << 2
};

typedef struct obscura_context_desc {
    uint32_t struct_size;                       /* sizeof(obscura_context_desc); required */
    uint32_t header_version;                    /* OBSCURA_VERSION; required (0: VERSION_MISMATCH) */
    obscura_get_proc_address_fn get_proc_address; /* the host's GL loader: this ... */
    obscura_get_proc_address_with_user_data_fn get_proc_address_with_user_data; /* ... or this, not both */
    void* get_proc_address_user_data;           /* passed to get_proc_address_with_user_data */
    obscura_allocator allocator;                /* zero: malloc/free */
    obscura_log_fn log;                         /* zero: no logging */
    void* log_user_data;
    uint32_t flags;                             /* OBSCURA_CONTEXT_FLAG_* */
} obscura_context_desc;

/* Creates a context for the GL context current on this thread (programs are built by obscura_prepare() or by
   the first render that needs them).
   Returns OK, NULL_ARGUMENT, INVALID_STRUCT_SIZE, VERSION_MISMATCH, INVALID_SETTING (flags with bits that are
   no OBSCURA_CONTEXT_FLAG_*), NO_GL_CONTEXT, GL_VERSION_UNSUPPORTED, MISSING_GL_FUNCTION, HOST_GL_ERROR, OUT_OF_MEMORY, GL_ERROR, CONTEXT_LOST,
   INTERNAL_ERROR (no program is built here, so no SHADER_COMPILE_FAILED). On failure the message goes to desc->log (there is no context to ask). */
OBSCURA_API obscura_status obscura_create_context(const obscura_context_desc* desc, obscura_context** out_context);

/* Destroys the context and every GL object it owns. The same GL context must be current: with another one
   current the GL objects are leaked (a warning is logged) rather than deleted there. NULL is a no-op. */
OBSCURA_API void obscura_destroy_context(obscura_context* context);

/* Returns the message of the last error on this context ("" if none). Valid until the next call. With NULL:
   the message of the calling thread's last call made without a context: obscura_create_context,
   obscura_resolve_settings(NULL, ...), the other settings functions and a call given a NULL context ("" if it
   succeeded), so tools without a GL context still learn why settings were refused. */
OBSCURA_API const char* obscura_get_last_error(const obscura_context* context);

/* ---- Methods and settings -------------------------------------------------------------------- */
typedef enum obscura_method {
    OBSCURA_METHOD_DEFAULT = 0, /* HBAO */
    OBSCURA_METHOD_HBAO = 1,
    OBSCURA_METHOD_SAO = 2,
    OBSCURA_METHOD_LSAO = 3,
    OBSCURA_METHOD_FFAO = 4,
    OBSCURA_METHOD_REFERENCE = 5,
    OBSCURA_METHOD_GTAO = 6,     /* 0.5 */
    OBSCURA_METHOD_COUNT_
} obscura_method;

/* Returns "hbao", "sao", "lsao", "ffao", "reference", "gtao", or NULL for an unknown method. */
OBSCURA_API const char* obscura_method_name(obscura_method method);

/* Returns 1 if the method is implemented in this library version, 0 otherwise. */
OBSCURA_API int obscura_method_available(obscura_method method);

/* Returns 1 if the method writes obscura_output.bent_normal_texture (0.5: GTAO), 0 otherwise. */
OBSCURA_API int obscura_method_writes_bent_normals(obscura_method method);

typedef enum obscura_toggle {
    OBSCURA_TOGGLE_DEFAULT = 0,
    OBSCURA_TOGGLE_ON = 1,
    OBSCURA_TOGGLE_OFF = 2
} obscura_toggle;

/* HBAO: LSAO paper sec. 3 and 6. Every field: 0 selects the default given after it ("derive" for derived ones).
   The sampling, estimator, shaping and blur defaults were tuned against ray-traced geometry (docs/parameters.md);
   before 0.5 they were 12 steps, horizon split, intensity 1, power 1, a 4-tap blur at sharpness 16. */
typedef struct obscura_hbao_settings {
    float radius;         /* metres, [1e-3, 1e4]: distance where the falloff rho0 reaches 0; steps cover it. Default 1 */
    float falloff_c;      /* C of rho0(d) = max(0, r(1+C)/(r+d^2) - C), [1e-3, 0.999]. Default 0.3 */
    float decay_rate;     /* r of rho0 in m^2, [1e-10, 1e8]. Derived: C*radius^2, so rho0 reaches 0 at radius
                             (the steps stop at the radius whatever r: a larger r is cut off there) */
    int32_t directions;   /* K azimuthal directions, [1, 32]. Default 8 */
    int32_t steps;        /* N steps per direction, [1, 128]. Default 7 */
    int32_t estimator;    /* 1: horizon-split integration (Bavoil 2008); 2: largest falloff-weighted occluder
                             only (LSAO paper eq. 1, what LSAO computes). Default 2 */
    float bias;           /* subtracted from sin(h) - sin(t), [0, 0.5]. Default 0 (zero is the default) */
    float intensity;      /* obscurance multiplier, [1e-3, 16]. Default 2 */
    float power;          /* visibility exponent, [1e-3, 16]. Default 0.5 */
    float max_radius_pixels; /* screen-space cap of the marched radius, [1, 4096]. Default 256 */
    obscura_toggle blur;  /* depth-aware bilateral blur. Default on */
    int32_t blur_radius;  /* taps each side, [1, 16]. Default 1 */
    float blur_sharpness; /* depth edge sharpness, [1e-3, 1000]. Default 89.3 */
} obscura_hbao_settings;

/* SAO: McGuire, Mara, Luebke, "Scalable Ambient Obscurance" (HPG 2012). s taps on a spiral (eq. 6-8) read
   camera-space z from a MIP hierarchy (level from the tap's screen radius, eq. 9-10), feed the AlchemyAO
   estimator A = max(0, 1 - (2 sigma r / s) sum max(0, v.n + z_C beta) / (v.v + epsilon r^2))^k over the taps
   inside the ball of radius r (SAO eq. 1; sigma and epsilon are relative to r so the result does not change
   with the scene's scale), then a 2x2 bilateral step and a separable 7-tap bilateral blur. Every field: 0
   selects the default given after it. */
typedef struct obscura_sao_settings {
    float radius;         /* metres, [1e-3, 1e4]: world-space radius r of the sample ball (eq. 5). Default 1 */
    int32_t samples;      /* s taps per pixel, [1, 64]. Default 9 */
    int32_t turns;        /* tau turns of the spiral, [1, 1024]. Derived: the integer nearest 7s/9 that shares no
                             factor with s, so the s angles are all different (the paper's 7 for s = 9) */
    obscura_toggle mip;   /* z-MIP hierarchy; off: every tap reads level 0 (the paper's quality baseline). Default on */
    int32_t mip_filter;   /* z^(m+1) from z^m (Table 1): 1 rotated-grid subsample, 2 arithmetic mean, 3 harmonic
                             mean, 4 min, 5 max, [1, 5]. Default 1 */
    int32_t log_q;        /* log2 of q', the screen radius (px) at which taps move one level down (eq. 9), [1, 8].
                             Default 3 */
    float intensity;      /* sigma, [1e-3, 16]. Default 1 */
    float bias;           /* beta: v.n must exceed beta times the receiver's distance, [1e-6, 0.1]. Default 1e-3 */
    float contrast;       /* k, [1e-3, 16]. Default 1 */
    float epsilon;        /* epsilon / r^2, [1e-6, 1]. Default 0.01 */
    float max_radius_pixels; /* cap of the screen radius r' (eq. 5), [1, 4096]. Default 256 */
    obscura_toggle quad_filter; /* the 2x2 bilateral step at the end of the AO pass. Default on */
    obscura_toggle blur;  /* the separable bilateral blur. Default on */
    int32_t blur_radius;  /* taps each side, [1, 8]. Default 3 (the paper's 7 taps) */
    int32_t blur_stride;  /* pixels between taps, [1, 4]. Default 3 (the paper's, after the 2x2 step) */
    float blur_sharpness; /* edge weight max(0, 1 - sharpness |z - z_tap| / blur_depth_range), [1, 1e6].
                             Default 2048 (the paper's 2^11) */
    float blur_depth_range; /* metres over which z is packed in 16 bits beside the AO (the paper's z_min),
                             [1e-2, 1e5]. Default 200 */
} obscura_sao_settings;

/* LSAO: Timonen, "Line-Sweep Ambient Obscurance" (EGSR 2013). Lines D_L texels apart cross the whole depth
   texture in K directions; each is walked in steps of D_S texels, keeping the obscure hull (Algorithm 1) of
   the points behind, so each step finds its largest falloff-weighted occluder in amortised O(1): the cost
   does not depend on the radius. A gather pass takes, per pixel and direction, the nearest line sample that
   is on the same surface and averages them weighted by azimuthal coverage (eq. 1). obscura_input.frame_index
   moves the lines through 8 layout phases (frame index mod 8, bit-reversed): each shifts every line across by
   phase/8 of D_L, and turns free directions by phase/8 of the angle between them (aligned ones are fixed by
   their texel template); a phase's line records are built on its first frame. Every field: 0 selects the
   default given after it; `preset` fills K, D_S and D_L where those are 0. */
typedef struct obscura_lsao_settings {
    float radius;         /* metres, [1e-3, 1e4]: falloff scale, the decay rate defaults to C*radius^2. Default 1 */
    int32_t falloff;      /* 1: rho0 (HBAO's, LSAO eq. 3), 2: r/(r+d^2) (LSAO eq. 2), [1, 2]. Default 2 */
    float falloff_c;      /* C, [1e-3, 0.999]: rho0's sink, and the decay-rate default. Default 0.3 */
    float decay_rate;     /* r in m^2, [1e-10, 1e8]. Derived: C*radius^2 */
    int32_t preset;       /* K, D_S, D_L of the paper: 1: 8, 1.41, 1.41; 2: 16, 2.43, 1.64; 3: 24, 3.56, 1.69;
                             4: 32, 4.69, 1.70 (Table 2); 5: 8, 2.83, 2.12 (Figure 1); 6: 16, 4.87, 2.46
                             (Figure 13), [1, 6]. Derived: 1 (with the receiver's tangent as close to the
                             geometry truth as 2 at less cost; its step, the shortest, keeps reduced resolution
                             within 0.01 of full resolution's error at half size) */
    int32_t pattern;      /* 1: aligned 8n directions on texel centres (sec. 5.2); 2: free: any K, interpolated
                             depth, snapped at depth edges, [1, 2]. Default 1 */
    int32_t directions;   /* K, [1, 64]; aligned: a multiple of 8. Derived: the preset's */
    float step_length;    /* D_S in texels, [0.5, 16]; aligned patterns walk the nearest whole number of template
                             steps (at least 1). Derived: the preset's */
    float line_spacing;   /* D_L in texels, [0.5, 16]. Derived: the preset's */
    float tangent;        /* the fixed sin(t), [-1, 0.5]; read with tangent_strategy 3 (and 2's hull). Default -0.85 */
    int32_t tangent_strategy; /* sec. 4.1: 1 the receiver's tangent for hull and occlusion, 2 fixed for the hull
                             and the receiver's for occlusion, 3 fixed for both, [1, 3]. Default 1 (half the
                             error of 3 against the geometry truth, docs/quality.md; 3 reads no normals) */
    int32_t hull_capacity; /* points kept per line (the oldest is dropped when full), [2, 64]. Default 24: on the
                             H100 the sweep takes 0.37 ms at 24 and 0.43 at 32 (shared memory per group), and
                             the AO moves by at most 0.0007 mean on the built-in scenes (docs/performance.md;
                             both measured with K = 16 and the fixed tangent, the defaults before 0.5) */
    obscura_toggle exact; /* brute-force largest occluder over all earlier samples instead of the hull (O(M^2)
                             per line, for validation). Default off */
    int32_t segment_steps; /* lines are swept in segments of this many steps (rounded up to a multiple of 8), one
                             GPU thread each, every segment after a warm-up run; -1: whole lines, one thread each,
                             [-1, 4096]. Derived (0): whole lines on CPU renderers (llvmpipe, softpipe), which
                             have no idle lanes to fill, and 128 on GPUs */
    float warmup_tolerance; /* segments: the most obscurance an occluder before a segment's warm-up may cast; the
                             falloff turns it into the warm-up's length (exact for rho0 beyond its reach). The
                             hull's top is nearly always a near point: at 0.1 the AO moved by < 1e-5 on every
                             built-in scene (docs/performance.md), [1e-4, 1]. Default 0.1 */
    int32_t warmup_stride; /* segments: the warm-up samples every n-th step except its last 16 steps, which are
                             dense: far occluders need less detail. At 4 the H100's sweep takes 0.38 instead of
                             0.68 ms at 1080p and the AO moves by 0.0003 (atrium) to 0.0016 (clutter) mean
                             against whole lines (docs/performance.md), [1, 64]. Default 4 */
    float depth_threshold; /* gather: values whose depth differs by more than this fraction are rejected,
                             [1e-4, 10]. Default 0.05 */
    obscura_toggle normal_test; /* gather: also reject values whose normal differs. Default off */
    float normal_threshold; /* gather: minimum dot of the two normals, [-1, 1]. Default 0.8 */
    float intensity;      /* obscurance multiplier, [1e-3, 16]. Default 1 */
    float power;          /* visibility exponent, [1e-3, 16]. Default 1 */
} obscura_lsao_settings;

/* Falloff rho(d) of the obscurance integral (FFAO paper eq. 1), d in metres, r = decay_rate in m^2. */
typedef enum obscura_falloff {
    OBSCURA_FALLOFF_DEFAULT = 0,           /* RHO0 */
    OBSCURA_FALLOFF_RHO0 = 1,              /* max(0, r(1+C)/(r+d^2) - C): HBAO's (LSAO paper eq. 3); 0 from d = sqrt(r/C) */
    OBSCURA_FALLOFF_INVERSE_QUADRATIC = 2, /* r/(r+d^2) (LSAO paper eq. 2); never reaches 0 */
    OBSCURA_FALLOFF_EXPONENTIAL = 3,       /* exp(-d/sqrt(r)) ("light-emitting fog"); never reaches 0 */
    OBSCURA_FALLOFF_TABLE = 4              /* falloff_table[i] = rho(i/(N-1) * radius), linear in between, 0 beyond */
} obscura_falloff;

#define OBSCURA_FALLOFF_TABLE_SIZE 16

/* REFERENCE: for every receiver pixel, `rays` cosine-weighted rays over the hemisphere of its normal are
   stepped texel by texel through the whole depth buffer (guard band included) until they pass behind the
   depth field; visibility = 1 - mean(rho(hit distance)), misses count 0. Slow by design: the screen-space
   reference other methods are measured against and converge to. It sees only the depth buffer, so it is not
   the geometry truth (rays against the scene's triangles, in the samples): with thickness 0 every ray that
   passes behind a silhouette counts as blocked, which darkens the sides of convex objects, the insides of
   arches and the floor behind thin objects. The rays are cast in dispatches of rays_per_dispatch (progressive
   accumulation: no single dispatch runs long). Frame n (obscura_input.frame_index) traces the rays first_ray +
   n * rays ... of one low-discrepancy sequence per pixel, so frames that advance frame_index (temporal accumulation
   included) trace new rays each; hosts that keep frame_index may instead average renders with first_ray = 0,
   rays, 2 * rays, ... (the same rays).
   obscura_reference_settings_for() makes these settings match another method's falloff. */
typedef struct obscura_reference_settings {
    float radius;         /* metres, [1e-3, 1e4]: where RHO0 (with the default decay rate) and TABLE reach 0. Default 1 */
    int32_t falloff;      /* obscura_falloff, [1, 4]. Default 1 (RHO0) */
    float falloff_c;      /* C of RHO0, [1e-3, 0.999]. Default 0.3 */
    float decay_rate;     /* r in m^2, [1e-10, 1e8]. Derived: C*radius^2 (RHO0 then reaches 0 at the radius) */
    float thickness;      /* metres of solid assumed behind every depth texel, [0, 1e4]: a ray that passes more
                             than that behind the depth field goes on (one that crosses the front of a continuous
                             surface hits it). Default 0: infinitely thick (every ray behind a silhouette is
                             blocked). 0.3 brought the atrium (320x180) from 0.086 to 0.034 mean abs error against
                             the geometry truth (0.026 before 2026-12-06, when steep surfaces let rays through) */
    int32_t rays;         /* rays per pixel, [1, 65536]. Default 256 */
    int32_t rays_per_dispatch; /* [1, 1024]. Default 16 */
    int32_t first_ray;    /* index of the first ray in the per-pixel sequence, [0, 16777216]. Default 0 */
    float falloff_table[OBSCURA_FALLOFF_TABLE_SIZE]; /* TABLE only: values in [0, 1], not all 0 */
} obscura_reference_settings;

/* FFAO: Timonen, "Screen-Space Far-Field Ambient Obscurance" (HPG 2013). Parallel lines one texel apart in K/2
   orientations are scanned once; every B0 steps each keeps the peaks (m0, m1) of the depth field as seen along
   two receiver angles, in a 1D pyramid of intervals B0 * 2^n (sec. 6). Prefix sums across lines (sec. 7) let
   every pixel average the peaks over each sector segment at every distance; the virtual points they give are
   slabs whose falloff-weighted, cosine-weighted visibility comes from a table L(a, b, c, d) integrated once
   per falloff shape (sec. 4, eq. 3). A direct search covers the pixel's first B0 to 2 B0 texels (sec. 9).
   Converges to the screen-space reference (REFERENCE) with the same falloff and thickness, not to the geometry:
   with thickness 0 it assumes the same infinitely thick depth field. obscura_input.frame_index moves the scan
   lines through 8 layout phases as LSAO's: each shifts them across by phase/8 of a texel. Every field: 0 selects
   the default given after it. */
typedef struct obscura_ffao_settings {
    float radius;         /* metres, [1e-3, 1e4]: where RHO0 (default decay rate) and TABLE reach 0. Default 1 */
    int32_t falloff;      /* obscura_falloff, [1, 4]. Default 3 (EXPONENTIAL, the paper's) */
    float falloff_c;      /* C of RHO0 and of the decay-rate default, [1e-3, 0.999]. Default 0.3 */
    float decay_rate;     /* r in m^2, [1e-10, 1e8]. Derived: C*radius^2 */
    int32_t sectors;      /* K azimuthal sectors, an even number (a line orientation serves two), [4, 64]. Derived:
                             16, or 18 with saao */
    int32_t segments;     /* evaluated parts of each sector, averaged separately (the paper's "x2"), [1, 4]. Default 2.
                             geometry 2 samples each sector's centre line only: segments and jitter then change
                             nothing */
    int32_t base_interval; /* B0: scan steps per level-0 interval; the near field covers B0 to 2 B0 texels,
                             [2, 64]. Default 10 */
    int32_t geometry;     /* the far field's scene points: 1 the scanned peaks (sec. 6-7); 2 the paper's baseline
                             (sec. 5), a depth MIP pyramid (mean, or max height with a thickness) sampled along
                             each sector's centre at distances growing by 1.5, [1, 2]. Default 1 */
    float thickness;      /* metres of solid behind every depth texel (sec. 11), [0, 1e4]; > 0 also reads single
                             lines instead of sector averages (a finite field cannot be averaged); 0: infinitely
                             thick (0 before 0.5). Default 0.4 */
    obscura_toggle jitter; /* offset every sector's lines per pixel (sec. 11.1): banding becomes noise. Default off */
    obscura_toggle saao;  /* SAAO interleaving (sec. 10): in every 3x3 pixel group each pixel evaluates the far field
                             of K/9 of the sectors (x2 segments) at its group's edge-aware averaged depth and normal;
                             a gather adds the accepted neighbours' far fields to each pixel's full near field.
                             Needs K a multiple of 18; derived sectors become 18 (the paper's 18x2). Default off */
    obscura_toggle saao_blur; /* SAAO: the paper's 5x5 box blur over values within 7 % of the pixel's. Default on */
    float intensity;      /* obscurance multiplier, [1e-3, 16]. Default 1 */
    float power;          /* visibility exponent, [1e-3, 16]. Default 1 */
    float falloff_table[OBSCURA_FALLOFF_TABLE_SIZE]; /* TABLE only: rho at i/(N-1) * radius, values in [0, 1] */
} obscura_ffao_settings;

/* FFAO's fields added in 0.5. They are a block of their own at the end of obscura_settings (ffao_added), since
   obscura_settings.ffao keeps the layout that hosts built against 0.3 and 0.4 hold; their metadata rows are FFAO's
   like the others ("frame_split"). Every field: 0 selects the default given after it. */
typedef struct obscura_ffao_added_settings {
    int32_t frame_split;  /* N: spread the K/2 orientations over N frames for temporal accumulation. A pixel evaluates
                             every Nth orientation (all segments, near and far field) from its share, (its place in
                             a 2x2 pattern + frame_index) mod N, and weighs their sum N times; the layout phase
                             moves once per N frames. A frame costs about 1/N of the obscurance pass, and the mean
                             of N consecutive frames (from a multiple of N) is the image of every orientation, with
                             power 1 (power applies per frame) and where no share's N-fold sum reaches full
                             obscurance. The host must advance obscura_input.frame_index each frame and accumulate
                             (temporal.enabled): a still view's running mean then converges to it; past
                             temporal.max_frames the exponential blend keeps a small ripple of the N shares. A
                             single frame shows the 2x2 pattern. [1, 4], at most K/2; not with saao. Default 1 */
} obscura_ffao_added_settings;

/* GTAO: Jimenez, Wu, Pesce, Jarabo, "Practical Realtime Strategies for Accurate Indirect Occlusion" (2016).
   Per pixel, S slices (planes through the eye and a screen direction, rotated per pixel over a 4x4 pattern that
   frame_index moves) are searched N steps to each side along the projected radius, the steps reading a z pyramid
   where they are far apart. thickness_mode 1 (horizon): each side keeps its highest horizon; the arc a sample
   adds to it counts as occluded with the sample's falloff weight (HBAO's horizon split, cosine-weighted), and the
   arcs are integrated in closed form against the normal projected into the slice (the paper's eq. 10).
   thickness_mode 2 (bitmask, Therrien et al. 2023): every sample occupies the sectors of the slice between its
   front and `thickness` metres behind it, in a mask of `sectors` bits (a sector where the ray through it meets
   the slab at a falloff weight above a threshold drawn per slice), and the free sectors are integrated with the
   same cosine weight, so light passes behind thin objects. A separable edge-aware 5x5 denoise averages the 4x4 pattern. Visibility is the ratio of
   the visible to the unoccluded slice integrals, so planes are exactly 1 at any slice count. The falloff it is
   compared with (obscura_reference_settings_for): 1 up to radius * (1 - falloff_range), linear to 0 at the
   radius, and the bitmask's thickness.
   Every field: 0 selects the default given after it ("derive" for derived ones). */
typedef struct obscura_gtao_settings {
    float radius;         /* metres, [1e-3, 1e4]: occluders farther than this do not count. Default 1 */
    int32_t preset;       /* slices x steps per side, as XeGTAO names them: 1 low 1x2, 2 medium 2x2, 3 high 3x3,
                             4 ultra 9x3, [1, 4]. Default 3 */
    int32_t slices;       /* S, [1, 16]. Derived: the preset's */
    int32_t steps;        /* N steps to each side, [1, 32]. Derived: the preset's */
    int32_t thickness_mode; /* 1 horizon (the paper's two horizons), 2 bitmask (finite thickness), [1, 2].
                             Default 1 (measured closer to the geometry truth at 3 steps, docs/quality.md) */
    float thickness;      /* bitmask: metres of solid behind every depth sample, [1e-3, 1e4]. Default 0.4 */
    float thickness_blend; /* horizon: the paper's thickness heuristic; a sample below the current horizon pulls
                             it this fraction of the way down, [0, 1]. Default 0 (zero is the default) */
    int32_t sectors;      /* bitmask: sectors per slice, [4, 32]. Default 32 */
    float falloff_range;  /* fraction of the radius over which an occluder's weight fades to 0 at the radius,
                             [0.01, 1]. Default 1: the weight is 1 - d / radius (tuned, docs/quality.md) */
    float step_power;     /* the steps sit at radius * ((j + jitter) / N)^step_power: denser near the pixel,
                             [1, 4]. Default 1.5 (XeGTAO's 2 measured further from the truth, docs/quality.md) */
    obscura_toggle mip;   /* steps read the z pyramid where they are far apart. Default on */
    float mip_offset;     /* log2 of the step's distance in pixels at which it reads one level down, [0, 8].
                             Default 3.3 */
    float intensity;      /* obscurance multiplier, [1e-3, 16]. Default 1 */
    float power;          /* visibility exponent, [1e-3, 16]: makes up for the occluders 3 steps miss. Derived:
                             1.75 in horizon mode, 1.5 in bitmask mode */
    float albedo;         /* the paper's multi-bounce fit for this surface albedo, [0, 0.95]; 0: none. Default 0 */
    float max_radius_pixels; /* cap of the radius on screen, [1, 4096]. Default 256 */
    obscura_toggle denoise; /* edge-aware 5x5 denoise over the 4x4 noise pattern. Default on */
    float denoise_sharpness; /* how strongly the denoise stops at a neighbour off the pixel's plane, [1e-3, 1000].
                             Default 256 (tuned) */
    int32_t frame_index;  /* moves the per-pixel noise; hosts accumulating frames advance it each frame,
                             [0, 16777216]. Default 0 */
} obscura_gtao_settings;

/* TEMPORAL ACCUMULATION (0.5), for every method: a pass after the method blends its result into a history kept per
   view (obscura_view), reprojected from the frame's depth and the two view-projection matrices of obscura_input (or
   its motion vectors; the projection is taken as unchanged between the two frames, jitter and, under perspective,
   the near and far planes aside: a changed field of view moves the history's expected depths and fails the
   disocclusion test everywhere). A history pixel
   is dropped where the reprojected surface does not lie on the stored one's plane (disocclusion), clamped to the
   current frame's neighbourhood (7 texels: mean +- clamp * deviation, and the pixel's own value) to bound
   ghosting, and blended with weight 1 / (frames seen + 1) up to max_frames, so a static view converges to the
   mean of that many frames. Each method moves its noise with obscura_input.frame_index. Without the matrices and
   motion vectors, or with OBSCURA_INPUT_FLAG_RESET_HISTORY, the frame starts a new history; so does a change of
   size (the host's too at reduced resolution), output rectangle, method, method settings, bent-normal output,
   meters_to_view_units, host normals (given or not) or depth kind. A debug view (obscura_output.debug_view)
   shows its frame alone and leaves the history as it is (a reset flag on it still drops the history); a frame with
   `enabled` off frees the view's history. With matrices the history is reprojected from the view-projection of the
   frame that made it, which is previous_view_projection unless the host's previous frame rendered this view with a
   debug view or not at all: such a frame costs nothing. Motion vectors span one frame, so with them the history
   continues only when frame_index is the history's + 1 (or equal, for a host that keeps it constant). A frame that
   fails while rendering (GL_ERROR, OUT_OF_MEMORY, SHADER_COMPILE_FAILED ...) leaves no history, the next starts
   anew; one refused before rendering (an invalid input or output) leaves the history as it was, except that its
   reset flag (a camera cut) still drops it once the input's and output's fields and the view are valid (a refusal
   of its textures, its output target or what its settings need, a host GL error left pending, another GL context
   current).
   Timing label "temporal" (after the method's passes; at full resolution it also writes the output, the bent-normal
   texture and a blit target's blit included, and the frame has no "composite"). Memory: 16 bytes per depth texel per view, 48 with bent
   normals (per texel of the reduced grid at half or quarter resolution), allocated by the first temporal render
   of the view (obscura_prepare does not know the views); and once per context, for methods whose last pass would
   otherwise write the target (HBAO, SAO, GTAO, LSAO), 2 bytes per texel for the result the temporal pass reads.
   Every field: 0 selects the default given after it. */
typedef struct obscura_temporal_settings {
    obscura_toggle enabled; /* accumulate frames. Default off */
    int32_t max_frames;     /* N: the history weighs at most N - 1 frames against the current one's 1, [1, 64].
                               Default 8 */
    float clamp;            /* neighbourhood clamp: the history is held within mean +- clamp * standard deviation of
                               the current frame's 7-texel neighbourhood, [0.25, 64]. Default 3 */
    float plane_tolerance;  /* disocclusion: a history texel farther from the pixel's tangent plane than this fraction
                               of its distance is dropped, [1e-4, 1]. Default 0.01 (0.02 before 0.5) */
} obscura_temporal_settings;

/* REDUCED RESOLUTION (0.5), for every method: the method (and the temporal pass) runs on a grid of 1/2 or 1/4 of the
   depth texture's size on each axis (rounded up), whose texel i is the depth texture's texel (2^k i): the depth
   preparation reads that texel alone (its exact position, so planes stay planes) and reconstructs the normals on
   the reduced grid; the guard band, the radius in pixels and the noise patterns scale with it. An upsample then
   writes every pixel of the output rectangle from the 2x2 reduced texels around it: bilinear weights times
   exp(-(d / (upsample_tolerance * z))^2), d the pixel's distance from each texel's tangent plane and z its own
   distance, so AO does not cross depth edges or creases; where all four are off the pixel's plane, the nearest
   plane's texel alone. The raw debug views (ao-before-blur, tap-count) and the depth and normal views show the
   reduced grid, each texel covering its 2^k x 2^k pixels. Without a debug view the upsample writes the output
   itself (timing label "upsample", which then holds the whole output write, and no "composite"); with one the
   composite shows the reduced grid and the upsample runs only for the bent normals (writing, beside them, a
   full-size R16F visibility that the debug view does not show). Memory: the working textures at the reduced size,
   plus with bent normals a full-size RGBA16F result, and once a debug view has run with bent normals the full-size
   R16F one (kept until the size changes or obscura_release_resources).
   Every field: 0 selects the default given after it. */
typedef enum obscura_resolution {
    OBSCURA_RESOLUTION_DEFAULT = 0, /* full */
    OBSCURA_RESOLUTION_FULL = 1,
    OBSCURA_RESOLUTION_HALF = 2,
    OBSCURA_RESOLUTION_QUARTER = 3
} obscura_resolution;

typedef struct obscura_resolution_settings {
    obscura_resolution scale;  /* the size the method runs at. Default FULL */
    float upsample_tolerance;  /* the upsample's scale of "off the pixel's plane": a fraction of the pixel's distance,
                                  [1e-4, 1]. Default 0.02 */
} obscura_resolution_settings;

/* SETTINGS: what a user edits and what the SDK uses.
   The editable form is what obscura_default_settings() returns and what hosts, UIs and files keep: every field
   holds its default, except the derived fields (the metadata flags them OBSCURA_SETTING_FLAG_DERIVED), which
   hold 0, "derive": decay rates from C and the radius, LSAO's K, D_S and D_L from its preset, SAO's spiral turns
   from the tap count, FFAO's K from SAAO. So setting `radius` moves the falloff's reach, and choosing a preset
   moves K, D_S and D_L; writing a value into a derived field fixes it. The effective form, every value the SDK
   will use, exists only as the output of obscura_resolve_settings() (for logs and UIs); obscura_render()
   resolves the same way.
   Zero-initialised structs (struct_size and method set, the rest 0) also work: every zero field means its
   default. In them a field whose range includes 0 but whose default is not 0 (lsao.tangent,
   lsao.normal_threshold, gtao.mip_offset, ffao.thickness) cannot be 0; the editable form carries OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE,
   under which 0 in such a field is 0, and obscura_set_setting() sets the flag when it stores such a 0.
   Struct sizes: the library accepts the obscura_settings of every released header (0.1 to this one); the fields
   an older header does not have hold their defaults (with the flag too). A 0.1-0.3 struct has no flags, so its 0 in
   such a field means the default: there ffao.thickness 0 (infinitely thick, the default before 0.5) now reads 0.4 m,
   and infinitely thick FFAO needs a 0.4 or newer header. One exception, which the library cannot
   detect: a binary built against 0.1 or 0.2 that calls obscura_default_settings gets the 0.3 symbol (below), which
   writes 428 bytes into its 60- or 156-byte struct. Such binaries must be rebuilt (or fill their struct with zeros
   and struct_size instead of calling it). */
enum {
    /* 0 in a field whose range includes 0 is the value 0 (not the default). Derived fields still derive. */
    OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE = 1u << 0
};

typedef struct obscura_settings {
    uint32_t struct_size;   /* sizeof(obscura_settings); required */
    obscura_method method;  /* which method renders. Default HBAO */
    obscura_hbao_settings hbao;
    obscura_reference_settings reference;
    obscura_sao_settings sao;
    obscura_lsao_settings lsao;
    obscura_ffao_settings ffao;
    uint32_t flags;         /* OBSCURA_SETTINGS_FLAG_* (0.4). obscura_default_settings sets ZERO_IS_VALUE */
    obscura_gtao_settings gtao; /* 0.5 */
    obscura_temporal_settings temporal; /* 0.5: every method's (the shared metadata rows, below) */
    obscura_resolution_settings resolution; /* 0.5: every method's (the shared metadata rows, below) */
    obscura_ffao_added_settings ffao_added; /* 0.5: FFAO's fields added after its block's layout was released */
} obscura_settings;

/* Fills `out` with the editable form of `method`'s defaults (see SETTINGS above; struct_size set). Writes
   `out_size` bytes, the size of the caller's obscura_settings: the macro below passes the header's. A binary
   built against 0.3 calls the plain symbol, which writes the 0.3 struct. Returns OK, NULL_ARGUMENT,
   INVALID_STRUCT_SIZE, INVALID_ENUM. */
OBSCURA_API obscura_status obscura_default_settings_sized(obscura_method method, obscura_settings* out,
                                                          uint32_t out_size);
#define obscura_default_settings(method, out) \
    obscura_default_settings_sized((method), (out), (uint32_t)sizeof(obscura_settings))

/* Replaces zero fields of `in` with their defaults, derives the derived fields, validates every field, and
   writes the effective values to `out` (may alias `in`; `in->struct_size` bytes, so both are the caller's
   struct version); for UIs and logs. With a context, the fields that depend on its GL renderer are derived too, as
   its renders derive them (lsao.segment_steps: -1 on CPU renderers, 128 on GPUs); with NULL they stay 0 and the
   error detail goes to obscura_get_last_error(NULL). Returns OK, NULL_ARGUMENT, INVALID_STRUCT_SIZE, INVALID_ENUM
   (resolution.scale too), INVALID_SETTING. */
OBSCURA_API obscura_status obscura_resolve_settings(obscura_context* context, const obscura_settings* in,
                                                    obscura_settings* out);

/* Writes to `out` the REFERENCE settings that evaluate the same falloff (kind, radius, C, decay rate) as
   `method_settings` (resolved first; a REFERENCE input is copied, without temporal accumulation and at full
   resolution: the reference of one frame), and FFAO's thickness, with the default ray counts, at full resolution,
   so an error measured against that screen-space reference compares like with like. Writes
   `method_settings->struct_size` bytes. Returns OK,
   NULL_ARGUMENT, INVALID_STRUCT_SIZE, INVALID_ENUM, INVALID_SETTING. */
OBSCURA_API obscura_status obscura_reference_settings_for(const obscura_settings* method_settings,
                                                          obscura_settings* out);

/* Writes rho(distances[i]) to rho[i] for `count` distances in metres: the falloff that `method_settings` weigh
   an occluder with, as the SDK's own integrals define it (the REFERENCE settings' falloff; any other method's
   as obscura_reference_settings_for() maps it). For tools that integrate the same obscurance by other means,
   such as the samples' geometry truth (rays against the scene's triangles). The settings are resolved once
   per call, so pass many distances at a time. A negative distance counts as 0, +infinity and NaN as a miss
   (rho 0). `distances` and `rho` may alias; with count 0 both may be NULL; on failure nothing is written.
   Returns OK, NULL_ARGUMENT, INVALID_STRUCT_SIZE, INVALID_ENUM, INVALID_SETTING. */
OBSCURA_API obscura_status obscura_evaluate_falloff(const obscura_settings* method_settings, const float* distances,
                                                    float* rho, uint32_t count);

/* ---- Settings metadata: declared once, read by the CLI, the viewer and the docs ----------------- */
typedef enum obscura_setting_type {
    OBSCURA_SETTING_FLOAT = 0,
    OBSCURA_SETTING_INT = 1,
    OBSCURA_SETTING_TOGGLE = 2,     /* obscura_toggle; min 0 (off) max 1 (on) in the table, named "off", "on" */
    OBSCURA_SETTING_ENUM = 3,       /* an int32_t field of named values min..max (0.4; INT before) */
    OBSCURA_SETTING_FLOAT_ARRAY = 4 /* value_count floats, each in [min, max] (0.4): a falloff table */
} obscura_setting_type;

enum {
    /* 0 derives the field from other settings (the description says how); default_value is then 0. */
    OBSCURA_SETTING_FLAG_DERIVED = 1u << 0
};

typedef struct obscura_setting_info {
    const char* name;        /* spec key, e.g. "radius" */
    obscura_setting_type type;
    double default_value;    /* in the editable form (0 for derived fields) */
    double min_value;        /* inclusive */
    double max_value;        /* inclusive */
    const char* unit;        /* "m", "m^2", "px", "" ... */
    const char* description; /* one line */
    size_t offset;           /* byte offset of the field inside obscura_settings */
    /* 0.4: */
    uint32_t flags;          /* OBSCURA_SETTING_FLAG_* */
    uint32_t value_count;    /* ENUM, TOGGLE: the named values; FLOAT_ARRAY: the array's length; else 0 */
    const char* const* value_names; /* ENUM, TOGGLE: value_names[i] names the value min_value + i ("exponential") */
    /* 0.5: */
    uint32_t added_in;       /* OBSCURA_VERSION of the header that added the row to its method's table (500: 0.5.0);
                                0 for the rows the method has had since its first release. A caller built against
                                an older header gets the table without the rows added after it (their fields lie
                                beyond its obscura_settings) */
} obscura_setting_info;

/* Sets *out_infos to the method's static table of settings and *out_count to its length. `info_size` is the
   caller's sizeof(obscura_setting_info) (the macro below passes the header's): the table has that layout, less the
   rows added to the method after that header (0.4's size: no `added_in`, and no FFAO frame_split, whose field lies
   beyond a 0.4 obscura_settings; a method newer than the header, which its caller cannot name, keeps its rows). A
   binary built against 0.3 calls the plain symbol, which returns the 0.3 layout (ENUM rows as INT, no array
   rows). Returns OK, NULL_ARGUMENT, INVALID_STRUCT_SIZE, INVALID_ENUM. */
OBSCURA_API obscura_status obscura_get_setting_infos_sized(obscura_method method,
                                                           const obscura_setting_info** out_infos,
                                                           uint32_t* out_count, uint32_t info_size);
#define obscura_get_setting_infos(method, out_infos, out_count) \
    obscura_get_setting_infos_sized((method), (out_infos), (out_count), (uint32_t)sizeof(obscura_setting_info))

/* Sets *out_infos to the static table of the settings every method shares (0.5: obscura_temporal_settings and
   obscura_resolution_settings, the rows "temporal.enabled", "temporal.max_frames", ..., "resolution.scale", ...: the
   block's name, a dot and the C field's name; offsets inside obscura_settings), *out_count to its length. The
   get/set functions below find these names for every method. Returns OK, NULL_ARGUMENT. */
OBSCURA_API obscura_status obscura_get_shared_setting_infos(const obscura_setting_info** out_infos,
                                                            uint32_t* out_count);

/* Sets the setting `name` of settings->method to `value` (toggles: 0 off, 1 on; enums: their value). The value
   is range-checked. 0 in a derived field derives it; 0 in a field whose range includes 0 is stored as 0 (and
   sets OBSCURA_SETTINGS_FLAG_ZERO_IS_VALUE, the fields whose zero meant "default" then holding their
   defaults). Array settings are written through their offset. Returns OK, NULL_ARGUMENT, UNKNOWN_SETTING (also
   a setting the caller's struct version does not have), INVALID_SETTING, INVALID_STRUCT_SIZE, INVALID_ENUM. */
OBSCURA_API obscura_status obscura_set_setting(obscura_settings* settings, const char* name, double value);

/* Reads the setting `name` of settings->method as it will be used: zero fields report their default
   (derived fields their derived value); toggles read 0 (off) or 1 (on). Array settings: INVALID_SETTING.
   While the settings do not resolve (K = 12 with LSAO's aligned pattern, a table falloff without its table) there
   is no derived value: a derived field left 0 reads 0, "derive", and obscura_resolve_settings() says why.
   lsao.segment_steps 0 reads 0: it depends on the renderer (obscura_resolve_settings() with a context gives it).
   A setting beyond an older caller's struct reads as it will be used (its default), where obscura_set_setting
   cannot store it. Returns OK, NULL_ARGUMENT, UNKNOWN_SETTING, INVALID_SETTING, INVALID_STRUCT_SIZE, INVALID_ENUM. */
OBSCURA_API obscura_status obscura_get_setting(const obscura_settings* settings, const char* name, double* out_value);

/* ---- Per-frame input ------------------------------------------------------------------------- */
typedef enum obscura_depth_kind {
    OBSCURA_DEPTH_HARDWARE = 0,    /* window-space depth written through `projection` */
    OBSCURA_DEPTH_LINEAR_VIEW = 1  /* positive distance from the eye plane in view units (R16F/R32F) */
} obscura_depth_kind;

typedef enum obscura_clip_depth {
    OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE = 0, /* GL default */
    OBSCURA_CLIP_DEPTH_ZERO_TO_ONE = 1          /* glClipControl(..., GL_ZERO_TO_ONE), usual with reversed-Z */
} obscura_clip_depth;

typedef enum obscura_matrix_layout {
    OBSCURA_MATRIX_COLUMN_MAJOR = 0, /* as glUniformMatrix4fv(..., GL_FALSE, m) expects (GLM, most engines) */
    OBSCURA_MATRIX_ROW_MAJOR = 1
} obscura_matrix_layout;

typedef struct obscura_rect {
    int32_t x, y, width, height; /* pixels, origin at the bottom-left as in GL */
} obscura_rect;

/* A view: one camera's temporal history (split screen, stereo eyes, a mirror: one view each, so histories never
   mix). Created and destroyed with the context's GL context current; obscura_destroy_context destroys the views
   it still has. A render that names no view uses the context's own. */
typedef struct obscura_view obscura_view;

/* Creates a view of `context`. Returns OK, NULL_ARGUMENT, OUT_OF_MEMORY. */
OBSCURA_API obscura_status obscura_create_view(obscura_context* context, obscura_view** out_view);

/* Destroys a view of `context` and frees its history textures (NULL: nothing). Returns OK, NULL_ARGUMENT (no
   context), INVALID_VIEW (not this context's view), WRONG_GL_CONTEXT (nothing freed). A destroyed view's handle is
   refused with INVALID_VIEW as far as the context can tell: views are told apart by address, so once a new view
   reuses it the old handle names the new view. Do not keep handles past obscura_destroy_view. */
OBSCURA_API obscura_status obscura_destroy_view(obscura_context* context, obscura_view* view);

typedef enum obscura_motion_units {
    OBSCURA_MOTION_PIXELS = 0, /* texels of the depth texture */
    OBSCURA_MOTION_NDC = 1     /* normalised device coordinates: the whole depth texture spans 2 on each axis */
} obscura_motion_units;

enum {
    /* A camera cut, or anything else that makes the previous frame unrelated: the view's history is dropped. */
    OBSCURA_INPUT_FLAG_RESET_HISTORY = 1u << 0
};

typedef struct obscura_input {
    uint32_t struct_size;           /* sizeof(obscura_input); required */
    uint32_t depth_texture;         /* GL texture name; required */
    obscura_depth_kind depth_kind;  /* default HARDWARE */
    int32_t depth_width;            /* size of the whole depth texture (guard band included); required */
    int32_t depth_height;
    obscura_rect output_rect;       /* visible part of the depth texture; zero: the whole texture */
    float projection[16];           /* the projection the depth was rendered with, covering the whole texture; required */
    obscura_matrix_layout projection_layout; /* default column-major */
    obscura_clip_depth clip_depth;  /* default [-1, 1] */
    float meters_to_view_units;     /* view units per metre, (0, 1e6]; default 1 */
    uint32_t normal_texture;        /* optional view-space normals, same size as the depth; 0: reconstruct */
    /* 0.5, temporal accumulation (settings.temporal; without it these only move the noise): */
    obscura_view* view;             /* the history this frame reads and writes; NULL: the context's own view */
    uint32_t frame_index;           /* advance by 1 each frame: every method moves its per-pixel noise with it
                                       (LSAO and FFAO their lines) */
    uint32_t flags;                 /* OBSCURA_INPUT_FLAG_* */
    float view_projection[16];      /* world -> clip of this frame, the depth's (projection_layout; jitter included);
                                       all zero: none, and without motion vectors the frame starts a new history
                                       (with them the history continues, read where the vectors point) */
    float previous_view_projection[16]; /* the same of the previous frame; all zero: none */
    uint32_t motion_vector_texture; /* optional GL_TEXTURE_2D (RG16F or RG32F, the depth's size): per texel, the offset
                                       from this frame's position to the previous frame's (previous = current +
                                       vector), in GL's texture axes: +y is up, towards higher rows (a D3D-style
                                       vector in UV, +y down, needs its y negated). They move the history's read;
                                       the matrices still map the pixel's point into the previous view for the
                                       history's plane test, so without them (all zero) the history survives only a
                                       nearly still camera: give both (the vectors for objects that move). 0: none */
    obscura_motion_units motion_vector_units; /* default PIXELS */
} obscura_input;

/* ---- Per-frame output ------------------------------------------------------------------------ */
typedef enum obscura_blend_mode {
    OBSCURA_BLEND_OVERWRITE = 0, /* target = visibility */
    OBSCURA_BLEND_MULTIPLY = 1   /* target.rgb *= visibility (alpha kept) */
} obscura_blend_mode;

typedef enum obscura_debug_view {
    OBSCURA_DEBUG_NONE = 0,        /* final AO */
    OBSCURA_DEBUG_LINEAR_DEPTH = 1, /* view depth / (4 * radius), clamped: near = black */
    OBSCURA_DEBUG_NORMALS = 2,     /* view-space normal * 0.5 + 0.5 in rgb (single-channel targets get z) */
    OBSCURA_DEBUG_AO_BEFORE_BLUR = 3,
    OBSCURA_DEBUG_TAP_COUNT = 4    /* depth texels the AO pass read for the pixel / 256 (HBAO, SAO, GTAO; others 0);
                                      with a float target, round(value * 256) is the count (SAO's packing keeps
                                      up to 127; HBAO's and GTAO's are exact through R16F up to 2048) */
} obscura_debug_view;

typedef struct obscura_output {
    uint32_t struct_size;          /* sizeof(obscura_output); required */
    uint32_t texture;              /* GL_TEXTURE_2D (R8, R16, R16F, R32F, RG8, RG16, RG16F, RG32F, RGBA8, RGBA16,
                                      RGBA16F, RGBA32F, RGB10_A2, R11F_G11F_B10F) ... */
    uint32_t framebuffer;          /* ... or a framebuffer object (colour attachment 0) when texture is 0.
                                      Both 0: the default framebuffer. A blit target (a renderbuffer, another
                                      texture format, the default framebuffer) receives the result through an
                                      RGBA8 staging texture (RGBA16F for float attachments): 8 bits for unorm
                                      attachments deeper than that, and for multiply the target's colour read
                                      back through it. A multisampled framebuffer (an MSAA window, renderbuffer or
                                      texture) is INVALID_FRAMEBUFFER: GL does not blit into one; resolve first, or
                                      write the AO to a single-sample texture and composite it yourself. */
    int32_t x, y;                  /* where the output rectangle lands in the target; default (0, 0) */
    obscura_blend_mode blend;      /* default OVERWRITE */
    obscura_debug_view debug_view; /* default NONE */
    /* 0.5: */
    uint32_t bent_normal_texture;  /* optional GL_TEXTURE_2D (RGBA8, RGBA16F or RGBA32F) that receives, at (x, y) like
                                      the AO, the pixel's bent normal: the cosine-weighted mean unoccluded direction,
                                      unit length, in view space (camera looking down -z), in rgb (RGBA8: n * 0.5 +
                                      0.5), and the visibility in a. Sky: (0, 0, 1) and 1. GTAO only (its slices, the
                                      same denoise); with another method INVALID_SETTING. 0: none */
} obscura_output;

/* ---- Rendering ------------------------------------------------------------------------------- */

/* Renders AO for input->output_rect with `settings` into `output`. Allocates per-size resources on the
   first call and when the size or the settings' resource needs change (see obscura_prepare).
   Sizes: a depth texture whose size differs from depth_width/height is INVALID_TEXTURE; an output
   rectangle outside the depth, or a result that does not fit the output target, is INVALID_RECT (the
   default framebuffer excepted: GL cannot tell a window's size, and the blit clips what lies outside it).
   A texture the frame writes (output->texture, output->framebuffer's colour attachment 0,
   output->bent_normal_texture) that is also one it reads (the input's depth, normal or motion-vector texture)
   or the other one it writes is INVALID_TEXTURE.
   Returns OK or NULL_ARGUMENT, INVALID_STRUCT_SIZE, WRONG_GL_CONTEXT, HOST_GL_ERROR, INVALID_SIZE,
   INVALID_RECT, INVALID_TEXTURE, UNSUPPORTED_FORMAT, INVALID_PROJECTION, PROJECTION_TRANSPOSED,
   INVALID_SETTING, INVALID_ENUM, INVALID_VIEW (input->view is not a live view of this context),
   METHOD_NOT_AVAILABLE, INVALID_FRAMEBUFFER, SHADER_COMPILE_FAILED (a variant built on first use), OUT_OF_MEMORY,
   GL_ERROR, CONTEXT_LOST, and INTERNAL_ERROR (a defect of the SDK: please report it with the message).
   Host errors and context loss: a GL error the host left pending is consumed and reported as HOST_GL_ERROR
   before anything is done (never blamed on a pass). A reset reported by glGetGraphicsResetStatus (GL 4.5,
   KHR/ARB_robustness; only robust contexts report one) on this context's GL context, or GL_CONTEXT_LOST from
   glGetError, makes this and every later obscura_render, obscura_prepare and obscura_get_timings on the context
   return CONTEXT_LOST (after the checks of their arguments, which need no GL; a reset of another GL context, current
   by mistake, is CONTEXT_LOST for that call only); calls that touch no GL (settings, views, memory
   usage) go on answering, and obscura_destroy_context deletes nothing.
   Out of memory: an allocation that fails, or GL_OUT_OF_MEMORY raised by any call of the frame, returns
   OUT_OF_MEMORY; the context stays usable: what was allocated stays, and the next render or prepare allocates
   what is missing (tests/gl/allocation_failure_test.cpp fails each allocation of every method in turn). */
OBSCURA_API obscura_status obscura_render(obscura_context* context, const obscura_input* input,
                                          const obscura_settings* settings, const obscura_output* output);

/* Allocates the textures a render of this size and these settings needs, so the first frame does not.
   Shader variants that depend on the input and output (MSAA or linear depth, the target's format) are
   still compiled on the first render that needs them; outputs beyond the AO (GTAO's bent normals, reduced
   resolution's full-size result for debug views) are allocated when the context's renders asked for them, and textures sized to the output rectangle (FFAO's
   running total at sizes it splits into chunks, 4K) take the last render's, or the depth's size. Optional. Returns OK, NULL_ARGUMENT,
   INVALID_STRUCT_SIZE, INVALID_SETTING, INVALID_ENUM, METHOD_NOT_AVAILABLE, INVALID_SIZE,
   WRONG_GL_CONTEXT, HOST_GL_ERROR, SHADER_COMPILE_FAILED (it builds the method's programs), OUT_OF_MEMORY,
   GL_ERROR (a GL error its calls raised, left for no later call to be blamed on), CONTEXT_LOST. */
OBSCURA_API obscura_status obscura_prepare(obscura_context* context, int32_t depth_width, int32_t depth_height,
                                           const obscura_settings* settings);

/* Frees the per-size resources and FFAO's table (they are recreated on the next render); programs stay. With
   another GL context current it frees nothing and logs a warning. */
OBSCURA_API void obscura_release_resources(obscura_context* context);

/* ---- Queries --------------------------------------------------------------------------------- */
typedef struct obscura_timing {
    const char* label; /* "total" first, then one entry per pass that ran, in order: "depth_prepare"; then
                          HBAO "hbao" ["blur"]; REFERENCE "reference"; SAO ["z_pyramid"] "sao" ["blur"]; LSAO
                          "line_sweep" "gather"; FFAO ["ffao_table" when the falloff's shape changed], then
                          ["ffao_box_average"] (saao) "ffao_scan" ["ffao_prefix"] (geometry=mipmap: ["z_pyramid"]
                          instead, before ["ffao_box_average"]), "ffao_obscurance" ["ffao_gather" "blur"] (saao); at sizes whose scan runs in
                          chunks (4K) each of these three entries is the sum over the chunks;
                          GTAO ["z_pyramid"] "gtao" ["gtao_denoise"]; then ["temporal"] (settings.temporal on),
                          ["upsample"] (settings.resolution below full), then "composite", unless the last pass
                          writes the output itself (no debug view): "upsample" at reduced resolution, else
                          "temporal" with settings.temporal on, else the method's last reconstruction pass (HBAO's
                          and SAO's "blur", GTAO's "gtao_denoise", LSAO's "gather"; REFERENCE, FFAO and a method with
                          its blur or denoise off keep "composite"). The pass that writes the output also holds the
                          bent-normal write and a blit target's blit. Static strings */
    double milliseconds;
} obscura_timing;

/* Copies the latest complete per-pass GPU timings (a few frames old; never waits on the GPU) into
   `out` (up to `capacity` entries) and sets *out_count to the number available. *out_frame_index (may be
   NULL) receives the 1-based index of the frame they belong to, counting the obscura_render calls that
   passed validation and reached the GPU, so a caller can
   tell a new result from the same one read twice; 0 and *out_count = 0 until a frame's queries have
   completed. It reads the context's GL queries: with another GL context current it returns WRONG_GL_CONTEXT, after
   a loss CONTEXT_LOST, and reads nothing (*out_count = 0). Returns OK, NULL_ARGUMENT, WRONG_GL_CONTEXT,
   CONTEXT_LOST. */
OBSCURA_API obscura_status obscura_get_timings(obscura_context* context, obscura_timing* out, uint32_t capacity,
                                               uint32_t* out_count, uint64_t* out_frame_index);

/* Sets *out_bytes to the GPU memory the context has allocated (textures and buffers). The context holds what its
   latest configuration (size, method, settings, output kind) needs and nothing else, so the same configuration
   reports the same bytes; LSAO and FFAO build the line layout of each of their 8 layout phases on the first frame
   that uses it (frame_index chooses the phase), so theirs may grow over a host's first 8 frames. Returns OK,
   NULL_ARGUMENT. */
OBSCURA_API obscura_status obscura_get_memory_usage(const obscura_context* context, uint64_t* out_bytes);

/* ---- The 0.3 ABI ----------------------------------------------------------------------------- */
/* Binaries built against the 0.3 header call these two names; here they are macros (above), which the
   parentheses keep from expanding. obscura_default_settings writes a 0.3-sized obscura_settings (428 bytes: too
   many for a 0.1 or 0.2 binary's struct, which has no size to tell it by; those binaries must be rebuilt), and
   obscura_get_setting_infos returns the table in the 0.3 layout of obscura_setting_info (its first eight
   fields). New code calls the macros. */
OBSCURA_API obscura_status(obscura_default_settings)(obscura_method method, obscura_settings* out);
OBSCURA_API obscura_status(obscura_get_setting_infos)(obscura_method method, const obscura_setting_info** out_infos,
                                                      uint32_t* out_count);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* OBSCURA_OBSCURA_H */
