#include "context.h"

#include <atomic>
#include <cmath>
#include <cstring>
#include <new>
#include <optional>

#include "gl/state_guard.h"
#include "settings.h"

namespace obscura {
namespace {

// Mesa's and Google's CPU rasterisers: they run a dispatch on a few cores, so work that only adds
// parallelism for a GPU (LSAO's line segments) is pure overhead there.
bool is_cpu_renderer(const char* renderer) {
    if (!renderer) return false;
    for (const char* name : {"llvmpipe", "softpipe", "SwiftShader", "Software Rasterizer"}) {
        if (std::strstr(renderer, name)) return true;
    }
    return false;
}

// A frame's shared constants for a pass computing `work`.
FrameConstants frame_constants(const FrameInput& input, const OutputTarget& target, const Region& work,
                               float debug_depth_scale) {
    const float* m = input.projection.m;
    FrameConstants c = {};
    c.proj_scale[0] = m[0]; c.proj_scale[1] = m[5]; c.proj_scale[2] = m[8]; c.proj_scale[3] = m[9];
    c.proj_depth[0] = m[10]; c.proj_depth[1] = m[14]; c.proj_depth[2] = m[11]; c.proj_depth[3] = m[15];
    c.proj_offset[0] = m[12]; c.proj_offset[1] = m[13];
    c.proj_offset[2] = input.projection.clip_scale; c.proj_offset[3] = input.projection.clip_bias;
    c.depth_params[0] = input.projection.sky_window_depth;
    c.depth_params[1] = input.meters_to_view_units;
    c.depth_params[2] = 1.0f / float(input.width);
    c.depth_params[3] = 1.0f / float(input.height);
    int source = input.depth_linear ? OBSCURA_DEPTH_SOURCE_LINEAR : OBSCURA_DEPTH_SOURCE_HARDWARE;
    if (input.depth_multisample) source += 1;
    c.depth_size[0] = input.width; c.depth_size[1] = input.height;
    c.depth_size[2] = source; c.depth_size[3] = input.normal_mode;
    c.output_rect[0] = input.output_rect.x; c.output_rect[1] = input.output_rect.y;
    c.output_rect[2] = input.output_rect.width; c.output_rect[3] = input.output_rect.height;
    c.work_rect[0] = work.x; c.work_rect[1] = work.y; c.work_rect[2] = work.width; c.work_rect[3] = work.height;
    c.target_params[0] = target.kind == TargetKind::Image ? target.x : 0;
    c.target_params[1] = target.kind == TargetKind::Image ? target.y : 0;
    c.target_params[2] = int(target.blend);
    c.target_params[3] = int(target.debug_view);
    c.debug_params[0] = debug_depth_scale;
    return c;
}

// GL 4.5 / KHR_robustness tokens; the SDK's loader is generated for GL 4.3.
constexpr GLenum kGlContextLost = 0x0507;
constexpr GLenum kGlGuiltyContextReset = 0x8253;
constexpr GLenum kGlInnocentContextReset = 0x8254;
constexpr GLenum kGlUnknownContextReset = 0x8255;

const char* reset_name(GLenum status) {
    switch (status) {
        case kGlGuiltyContextReset: return "GL_GUILTY_CONTEXT_RESET: a command of this context caused the reset";
        case kGlInnocentContextReset: return "GL_INNOCENT_CONTEXT_RESET: another context caused the reset";
        case kGlUnknownContextReset: return "GL_UNKNOWN_CONTEXT_RESET";
        case kGlContextLost: return "glGetError returned GL_CONTEXT_LOST";
        default: return "unknown reset status";
    }
}

bool has_extension(const gl::Table& gl, const char* name) {
    GLint count = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const char* extension = reinterpret_cast<const char*>(gl.GetStringi(GL_EXTENSIONS, GLuint(i)));
        if (extension && std::strcmp(extension, name) == 0) return true;
    }
    return false;
}

const char* gl_error_name(GLenum error) {
    switch (error) {
        case kGlContextLost: return "GL_CONTEXT_LOST";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
        case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
        default: return "unknown GL error";
    }
}

// Drains the GL error queue; returns the first error.
GLenum take_gl_error(const gl::Table& gl) {
    GLenum first = gl.GetError();
    if (first == GL_NO_ERROR) return first;
    for (int i = 0; i < 16 && gl.GetError() != GL_NO_ERROR; ++i) {}
    return first;
}

}  // namespace

Context::Context(const obscura_context_desc& desc)
    : alloc_(AllocatorCallbacks::from(desc.allocator)),
      log_(desc.log),
      log_user_data_(desc.log_user_data),
      flags_(desc.flags) {
    loader_.plain = desc.get_proc_address;
    loader_.with_user_data = desc.get_proc_address_with_user_data;
    loader_.user_data = desc.get_proc_address_user_data;
}

Context::~Context() {
    // Members release their GL objects through gl_ (declared first, destroyed last).
    timer_.destroy();
}

Error Context::create(const obscura_context_desc& desc, Context** out) {
    AllocatorCallbacks alloc = AllocatorCallbacks::from(desc.allocator);
    void* memory = alloc.allocate(sizeof(Context));
    if (!memory) return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the context failed");
    Context* context = new (memory) Context(desc);
    Error error;
    try {
        error = context->initialize();
    } catch (...) {
        destroy(context);  // a failed allocation while compiling: free the GL objects made so far
        throw;
    }
    if (error) {
        destroy(context);
        return error;
    }
    *out = context;
    return Error();
}

void Context::destroy(Context* context) {
    if (!context) return;
    // A lost GL context took the objects with it; deleting names there would at best do nothing.
    if (context->lost_reason_) {
        context->disarm_gl_deletes();
    } else if (context->gl_.GetString && context->identity_framebuffer_ && context->check_gl_context()) {
        // Deleting GL names with another context current would delete that context's objects: leak instead.
        if (context->log_) {
            context->log_(OBSCURA_LOG_WARNING, OBSCURA_STATUS_WRONG_GL_CONTEXT,
                          "obscura_destroy_context: the context's GL context is not current; its GL objects are "
                          "leaked rather than deleted in another context",
                          context->log_user_data_);
        }
        context->disarm_gl_deletes();
    }
    AllocatorCallbacks alloc = context->alloc_;
    context->~Context();
    alloc.release(context);
}

PassEnv Context::env() const {
    return PassEnv{gl_,           alloc_, log_, log_user_data_, sampler_.name(), sampler_mipmap_.name(),
                   uniform_buffer_.name(), cpu_renderer_};
}

Error Context::initialize() {
    // Probe for a current context before loading: glad would otherwise read a NULL version string.
    using GetStringFn = const GLubyte* (*)(GLenum);
    auto get_string = reinterpret_cast<GetStringFn>(obscura_gl_lookup(&loader_, "glGetString"));
    if (!get_string || !get_string(GL_VERSION)) {
        return Error::make(OBSCURA_STATUS_NO_GL_CONTEXT,
                           "no OpenGL context is current on this thread (glGetString(GL_VERSION) returned NULL)");
    }
    int version = obscura_gl_load_table(&gl_, &loader_);
    if (version == 0) {
        return Error::make(OBSCURA_STATUS_NO_GL_CONTEXT, "loading OpenGL through get_proc_address failed");
    }
    if (version < 40003) {
        return Error::make(OBSCURA_STATUS_GL_VERSION_UNSUPPORTED,
                           "OpenGL %d.%d is current; Obscura needs 4.3 core (GL_VERSION \"%s\")", version / 10000,
                           version % 10000, reinterpret_cast<const char*>(get_string(GL_VERSION)));
    }
    cpu_renderer_ = is_cpu_renderer(reinterpret_cast<const char*>(get_string(GL_RENDERER)));
    // Context loss: only robust contexts report a reset, through GL 4.5's query or its extension forms. A
    // loader may hand out stubs for any name, so the name is looked up only where the context has it.
    const char* reset_query = version >= 40005                                ? "glGetGraphicsResetStatus"
                              : has_extension(gl_, "GL_KHR_robustness")     ? "glGetGraphicsResetStatusKHR"
                              : has_extension(gl_, "GL_ARB_robustness")     ? "glGetGraphicsResetStatusARB"
                                                                            : nullptr;
    if (reset_query) {
        get_reset_status_ = reinterpret_cast<ResetStatusFn>(obscura_gl_lookup(&loader_, reset_query));
    }
    if (Error lost = check_context_lost()) return lost;
    // Every function the SDK calls must have loaded (a host loader may return NULL for some).
    struct Required { const void* fn; const char* name; };
    const Required required[] = {
        {reinterpret_cast<const void*>(gl_.DispatchCompute), "glDispatchCompute"},
        {reinterpret_cast<const void*>(gl_.BindImageTexture), "glBindImageTexture"},
        {reinterpret_cast<const void*>(gl_.MemoryBarrier), "glMemoryBarrier"},
        {reinterpret_cast<const void*>(gl_.TexStorage2D), "glTexStorage2D"},
        {reinterpret_cast<const void*>(gl_.TexStorage3D), "glTexStorage3D"},
        {reinterpret_cast<const void*>(gl_.TexBuffer), "glTexBuffer"},
        {reinterpret_cast<const void*>(gl_.QueryCounter), "glQueryCounter"},
        {reinterpret_cast<const void*>(gl_.GetQueryObjectui64v), "glGetQueryObjectui64v"},
        {reinterpret_cast<const void*>(gl_.BindBufferRange), "glBindBufferRange"},
        {reinterpret_cast<const void*>(gl_.GetIntegeri_v), "glGetIntegeri_v"},
        {reinterpret_cast<const void*>(gl_.GetInteger64i_v), "glGetInteger64i_v"},
        {reinterpret_cast<const void*>(gl_.BindSampler), "glBindSampler"},
        {reinterpret_cast<const void*>(gl_.BlitFramebuffer), "glBlitFramebuffer"},
        {reinterpret_cast<const void*>(gl_.CreateShader), "glCreateShader"},
        {reinterpret_cast<const void*>(gl_.GetTexLevelParameteriv), "glGetTexLevelParameteriv"},
        {reinterpret_cast<const void*>(gl_.FramebufferTexture2D), "glFramebufferTexture2D"},
        {reinterpret_cast<const void*>(gl_.FramebufferTexture), "glFramebufferTexture"},
        {reinterpret_cast<const void*>(gl_.DrawBuffers), "glDrawBuffers"},
        {reinterpret_cast<const void*>(gl_.ReadBuffer), "glReadBuffer"},
        {reinterpret_cast<const void*>(gl_.FramebufferRenderbuffer), "glFramebufferRenderbuffer"},
        {reinterpret_cast<const void*>(gl_.ObjectLabel), "glObjectLabel"},
        {reinterpret_cast<const void*>(gl_.GetObjectLabel), "glGetObjectLabel"},
        {reinterpret_cast<const void*>(gl_.IsEnabledi), "glIsEnabledi"},
        {reinterpret_cast<const void*>(gl_.Enablei), "glEnablei"},
        {reinterpret_cast<const void*>(gl_.Uniform4i), "glUniform4i"},
        {reinterpret_cast<const void*>(gl_.Flush), "glFlush"},
    };
    for (const Required& r : required) {
        if (!r.fn) return Error::make(OBSCURA_STATUS_MISSING_GL_FUNCTION, "get_proc_address returned NULL for %s", r.name);
    }
    GLenum pending = take_gl_error(gl_);
    if (pending != GL_NO_ERROR) {
        return Error::make(OBSCURA_STATUS_HOST_GL_ERROR,
                           "the host left %s (0x%04X) pending before obscura_create_context; it was consumed",
                           gl_error_name(pending), unsigned(pending));
    }

    gl::StateGuard guard(gl_);
    gl_.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &uniform_alignment_);
    sampler_ = gl::create_sampler_nearest_clamp(gl_);
    sampler_mipmap_ = gl::create_sampler_nearest_mipmap_clamp(gl_);
    gl_.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size_);
    // Identity of our GL context: a framebuffer object (never shared between contexts, unlike samplers or
    // textures) labelled with a process-unique string (names repeat across contexts, each counts from 1).
    static std::atomic<uint32_t> next_identity{0};
    std::snprintf(identity_label_, sizeof identity_label_, "obscura context %u", next_identity.fetch_add(1) + 1);
    identity_framebuffer_ = gl::create_framebuffer(gl_);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, identity_framebuffer_.name());  // a name becomes an object when bound
    gl_.ObjectLabel(GL_FRAMEBUFFER, identity_framebuffer_.name(), -1, identity_label_);
    uniform_buffer_ = gl::Buffer::create(gl_, GL_UNIFORM_BUFFER, UniformArena::kCapacity);
    timer_.create(gl_, (flags_ & OBSCURA_CONTEXT_FLAG_SYNC_TIMING) != 0);
    PassEnv pass_env = env();
    Error error = hbao_.create(pass_env);
    if (!error) error = blur_.create(pass_env);
    if (error) return error;
    GLenum gl_error = take_gl_error(gl_);
    if (gl_error != GL_NO_ERROR) {
        return Error::make(OBSCURA_STATUS_GL_ERROR, "%s while creating the context's GL objects", gl_error_name(gl_error));
    }
    return Error();
}

obscura_status Context::report(const Error& error) {
    if (error.ok()) {
        last_error_[0] = '\0';
        return OBSCURA_STATUS_OK;
    }
    std::snprintf(last_error_, sizeof last_error_, "%s", error.message());
    if (log_) log_(OBSCURA_LOG_ERROR, error.status(), error.message(), log_user_data_);
    return error.status();
}

uint64_t Context::memory_bytes() const {
    return resources_.bytes() + uniform_buffer_.bytes() + lsao_.bytes() + ffao_.bytes();
}

Error Context::check_gl_context() {
    const GLubyte* version = gl_.GetString(GL_VERSION);
    if (!version) return Error::make(OBSCURA_STATUS_WRONG_GL_CONTEXT, "no OpenGL context is current on this thread");
    // Our framebuffer exists only in our GL context (framebuffers are never shared); its label tells it
    // from another context's framebuffer of the same name.
    char label[sizeof identity_label_] = {};
    if (gl_.IsFramebuffer(identity_framebuffer_.name())) {
        gl_.GetObjectLabel(GL_FRAMEBUFFER, identity_framebuffer_.name(), GLsizei(sizeof label), nullptr, label);
    }
    if (std::strcmp(label, identity_label_) != 0) {
        return Error::make(OBSCURA_STATUS_WRONG_GL_CONTEXT,
                           "the current OpenGL context is not the one this obscura context was created on");
    }
    return Error();
}

Error Context::ensure_resources(int width, int height) {
    if (resources_.width == width && resources_.height == height && resources_.linear_depth) return Error();
    release_resources();
    // Texture2D::create binds on the active unit: make it one the StateGuard restores (obscura_prepare
    // reaches here with the host's active unit, e.g. GL_TEXTURE5).
    gl_.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE));
    FrameResources r;
    r.width = width;
    r.height = height;
    r.linear_depth = gl::Texture2D::create(gl_, GL_R32F, width, height);
    r.normals = gl::Texture2D::create(gl_, GL_RG16_SNORM, width, height);
    r.ao = gl::Texture2D::create(gl_, GL_R16F, width, height);
    r.blur_temp = gl::Texture2D::create(gl_, GL_R16F, width, height);
    r.ao_blurred = gl::Texture2D::create(gl_, GL_R16F, width, height);
    if (!r.linear_depth || !r.normals || !r.ao || !r.blur_temp || !r.ao_blurred) {
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d working textures failed", width, height);
    }
    resources_ = std::move(r);
    return Error();
}

void Context::release_resources() {
    resources_ = FrameResources();
    lsao_.release();
    ffao_.release();
    ffao_.release_table();
}

void Context::release_resources_from_host() {
    if (lost_reason_ || check_gl_context()) {
        if (log_ && !lost_reason_) {
            log_(OBSCURA_LOG_WARNING, OBSCURA_STATUS_WRONG_GL_CONTEXT,
                 "obscura_release_resources: the context's GL context is not current; nothing was freed", log_user_data_);
        }
        return;
    }
    release_resources();
}

Error Context::ensure_reference_accumulator() {
    if (resources_.reference) return Error();
    gl_.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE));  // a unit the StateGuard restores
    resources_.reference = gl::Texture2D::create(gl_, GL_R32F, resources_.width, resources_.height);
    if (!resources_.reference) {
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d reference accumulator failed",
                           resources_.width, resources_.height);
    }
    return Error();
}

Error Context::ensure_depth_pyramid(int levels) {
    gl_.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE));  // a unit the StateGuard restores
    if (resources_.linear_depth.levels() != levels) {
        // Its contents are rewritten by the depth preparation every frame: replacing it loses nothing.
        resources_.linear_depth = gl::Texture2D::create(gl_, GL_R32F, resources_.width, resources_.height, levels);
        if (!resources_.linear_depth) {
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d z pyramid (%d levels) failed",
                               resources_.width, resources_.height, levels);
        }
    }
    return Error();
}

Error Context::ensure_sao_resources(int levels) {
    Error error = ensure_depth_pyramid(levels);
    if (error) return error;
    gl_.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE));  // a unit the StateGuard restores
    if (!resources_.packed_ao) resources_.packed_ao = gl::Texture2D::create(gl_, GL_RGBA8, resources_.width, resources_.height);
    if (!resources_.packed_temp) {
        resources_.packed_temp = gl::Texture2D::create(gl_, GL_RGBA8, resources_.width, resources_.height);
    }
    if (!resources_.packed_ao || !resources_.packed_temp) {
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d SAO textures failed", resources_.width,
                           resources_.height);
    }
    return Error();
}

Error Context::ensure_method_resources(const obscura_settings& settings) {
    // The context holds what the latest configuration needs and nothing else: switching methods frees the
    // others' resources (re-created when they come back), so the memory report depends on the configuration
    // only, never on the history of the session.
    const obscura_method method = settings.method;
    if (method != OBSCURA_METHOD_REFERENCE) resources_.reference = gl::Texture2D();
    if (method != OBSCURA_METHOD_SAO) {
        resources_.packed_ao = gl::Texture2D();
        resources_.packed_temp = gl::Texture2D();
    }
    if (method != OBSCURA_METHOD_LSAO) lsao_.release();
    if (method != OBSCURA_METHOD_FFAO) {
        ffao_.release();
        ffao_.release_table();
    }
    const bool pyramid = method == OBSCURA_METHOD_SAO || (method == OBSCURA_METHOD_FFAO && ffao_uses_mipmap(settings.ffao));
    if (!pyramid) {
        Error error = ensure_depth_pyramid(1);
        if (error) return error;
    }
    switch (method) {
        case OBSCURA_METHOD_REFERENCE: return ensure_reference_accumulator();
        case OBSCURA_METHOD_SAO:
            return ensure_sao_resources(
                ZPyramidPass::level_count(resources_.width, resources_.height, SaoPass::wanted_levels(settings.sao)));
        case OBSCURA_METHOD_LSAO: return lsao_.ensure_layout(env(), settings.lsao, resources_.width, resources_.height);
        case OBSCURA_METHOD_FFAO: {
            Error error = ffao_.prepare(env(), settings.ffao);
            if (!error && ffao_uses_mipmap(settings.ffao)) {
                error = ensure_depth_pyramid(
                    ZPyramidPass::level_count(resources_.width, resources_.height, kFfaoMipmapLevels));
            }
            if (error) return error;
            return ffao_.ensure_layout(env(), settings.ffao, resources_.width, resources_.height);
        }
        default: return Error();
    }
}

Error Context::prepare(int width, int height, const obscura_settings& settings) {
    obscura_settings resolved;
    Error error = resolve_settings(settings, &resolved);
    if (error) return error;
    if (!obscura_method_available(resolved.method)) {
        return Error::make(OBSCURA_STATUS_METHOD_NOT_AVAILABLE, "method %s is not available in this version",
                           obscura_method_name(resolved.method));
    }
    if (width <= 0 || height <= 0 || width > max_texture_size_ || height > max_texture_size_) {
        return Error::make(OBSCURA_STATUS_INVALID_SIZE, "size %dx%d must be within 1..%d", width, height,
                           max_texture_size_);
    }
    error = check_host_state("obscura_prepare");
    if (error) return error;
    gl::StateGuard guard(gl_);
    error = ensure_resources(width, height);
    if (!error) error = ensure_method_resources(resolved);
    return error;
}

Error Context::check_context_lost() {
    if (!lost_reason_ && get_reset_status_) lost_reason_ = get_reset_status_();
    if (!lost_reason_) return Error();
    return Error::make(OBSCURA_STATUS_CONTEXT_LOST,
                       "the OpenGL context was lost (%s); destroy this obscura context and create a new one on a "
                       "new GL context",
                       reset_name(lost_reason_));
}

Error Context::gl_error_status(GLenum error, const char* where) {
    if (error == kGlContextLost) {
        lost_reason_ = kGlContextLost;
        return check_context_lost();
    }
    return Error::make(OBSCURA_STATUS_GL_ERROR, "%s (0x%04X) raised %s", gl_error_name(error), unsigned(error), where);
}

Error Context::check_host_state(const char* call) {
    Error error = check_context_lost();
    if (error) return error;
    error = check_gl_context();
    if (error) return error;
    GLenum pending = take_gl_error(gl_);
    if (pending == kGlContextLost) return gl_error_status(pending, call);
    if (pending != GL_NO_ERROR) {
        return Error::make(OBSCURA_STATUS_HOST_GL_ERROR,
                           "the host left %s (0x%04X) pending before %s; it was consumed and nothing was done",
                           gl_error_name(pending), unsigned(pending), call);
    }
    return Error();
}

Error Context::render(const obscura_input& input, const obscura_settings& settings, const obscura_output& output) {
    Error error = check_host_state("obscura_render");
    if (error) return error;
    obscura_settings resolved;
    error = resolve_settings(settings, &resolved);
    if (error) return error;
    if (!obscura_method_available(resolved.method)) {
        return Error::make(OBSCURA_STATUS_METHOD_NOT_AVAILABLE,
                           "method %s is not available in this version of Obscura (%d.%d.%d)",
                           obscura_method_name(resolved.method), OBSCURA_VERSION_MAJOR, OBSCURA_VERSION_MINOR,
                           OBSCURA_VERSION_PATCH);
    }
    {
        gl::StateGuard guard(gl_);
        FrameInput frame;
        error = validate_input(gl_, input, max_texture_size_, &frame);
        if (!error) {
            // Undoes validate_input's texture-parameter change even if a pass throws (allocation failure).
            struct InputStateRestorer {
                const gl::Table& gl;
                const FrameInput& frame;
                ~InputStateRestorer() { restore_input_state(gl, frame); }
            } restorer{gl_, frame};
            OutputTarget target;
            error = validate_output(gl_, output, frame.output_rect, &target);
            if (!error) error = ensure_resources(frame.width, frame.height);
            if (!error) error = record_frame(frame, resolved, target);
        }
        // A failed validation may leave a probing error (wrong texture target) behind: drain it.
        GLenum gl_error = take_gl_error(gl_);
        if (gl_error == kGlContextLost || (!error && gl_error != GL_NO_ERROR)) {
            error = gl_error_status(gl_error, "while rendering");
        }
    }
    GLenum restore_error = take_gl_error(gl_);
    if (restore_error == kGlContextLost || (!error && restore_error != GL_NO_ERROR)) {
        error = gl_error_status(restore_error, "while restoring the host's GL state");
    }
    return error;
}

GLuint Context::blit_framebuffer(const OutputTarget& target) {
    if (target.framebuffer == 0) return 0;  // the default framebuffer: its own draw/read buffer
    // A layer of an array, 3D or cube-map-array texture: the host's framebuffer itself (narrowed to
    // attachment 0 by the caller), because the layer cannot be read back everywhere (Mesa 22 reports
    // GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER 0 for a cube-map-array layer it renders to correctly).
    if (target.attachment_by_layer) return target.framebuffer;
    if (!target_framebuffer_) target_framebuffer_ = gl::create_framebuffer(gl_);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, target_framebuffer_.name());
    if (target.attachment_type == GL_RENDERBUFFER) {
        gl_.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        gl_.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target.attachment_name);
    } else {
        // Attach the very image the host attached: glFramebufferTexture would attach a whole cube level
        // as a layered image, and a blit into that writes face 0 only.
        gl_.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, 0);
        if (target.attachment_face != GL_NONE) {
            gl_.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target.attachment_face,
                                     target.attachment_name, target.attachment_level);
        } else {
            gl_.FramebufferTexture(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target.attachment_name,
                                   target.attachment_level);
        }
    }
    return target_framebuffer_.name();
}

namespace {
// Stand-ins for glDelete* when the obscura context is destroyed with another GL context current.
void GLAD_API_PTR keep_names(GLsizei, const GLuint*) {}
void GLAD_API_PTR keep_name(GLuint) {}
}  // namespace

void Context::disarm_gl_deletes() {
    gl_.DeleteTextures = &keep_names;
    gl_.DeleteBuffers = &keep_names;
    gl_.DeleteSamplers = &keep_names;
    gl_.DeleteQueries = &keep_names;
    gl_.DeleteFramebuffers = &keep_names;
    gl_.DeleteProgram = &keep_name;
}

namespace {
// The blur's reach on each side and the regions of a frame's passes for one method.
struct FramePlan {
    bool blur = false;
    int apron = 0;       // pixels the blur reads beyond the output rectangle on each side
    Region ao_region;    // where the AO pass computes
    Region blur_x_region;
};

// SAO's quad filter pairs pixels of 2x2 quads in absolute coordinates: start its region on even ones.
Region aligned_to_quads(Region r) {
    const int x0 = r.x & ~1, y0 = r.y & ~1;
    r.width += r.x - x0;
    r.height += r.y - y0;
    r.x = x0;
    r.y = y0;
    return r;
}
}  // namespace

Error Context::record_frame(const FrameInput& input, const obscura_settings& settings, const OutputTarget& target) {
    PassEnv pass_env = env();
    const obscura_method method = settings.method;
    // Before the depth preparation: SAO may replace the linear-depth texture with one that has MIP levels.
    Error error = ensure_method_resources(settings);
    if (error) return error;
    error = depth_prepare_.prepare(pass_env, input);
    if (error) return error;
    // Blit targets compose into a staging texture: RGBA16F for float attachments (MULTIPLY keeps HDR).
    GLenum staging_format = target.attachment_float ? GL_RGBA16F : GL_RGBA8;
    GLenum composite_format = target.kind == TargetKind::Image ? target.format : staging_format;
    error = composite_.prepare(pass_env, composite_format);
    if (error) return error;
    if (method == OBSCURA_METHOD_REFERENCE) error = reference_.prepare(pass_env);
    if (method == OBSCURA_METHOD_LSAO) error = lsao_.prepare(pass_env, settings.lsao);
    if (method == OBSCURA_METHOD_SAO || (method == OBSCURA_METHOD_FFAO && ffao_uses_mipmap(settings.ffao))) {
        error = z_pyramid_.prepare(pass_env);
    }
    if (!error && method == OBSCURA_METHOD_SAO) {
        error = sao_.prepare(pass_env);
        if (!error) error = sao_blur_.prepare(pass_env);
    }
    if (error) return error;

    // The raw-AO debug views show the AO pass's own output: no blur runs.
    const bool raw_view =
        target.debug_view == OBSCURA_DEBUG_AO_BEFORE_BLUR || target.debug_view == OBSCURA_DEBUG_TAP_COUNT;
    const obscura_hbao_settings& hbao = settings.hbao;
    const obscura_sao_settings& sao = settings.sao;
    Region rect{input.output_rect.x, input.output_rect.y, input.output_rect.width, input.output_rect.height};
    Region whole{0, 0, input.width, input.height};
    FramePlan plan;
    if (method == OBSCURA_METHOD_HBAO) {
        plan.blur = !raw_view && hbao.blur == OBSCURA_TOGGLE_ON;
        plan.apron = plan.blur ? hbao.blur_radius : 0;
    } else if (method == OBSCURA_METHOD_SAO) {
        plan.blur = !raw_view && sao.blur == OBSCURA_TOGGLE_ON;
        plan.apron = plan.blur ? sao.blur_radius * sao.blur_stride : 0;
    } else if (method == OBSCURA_METHOD_FFAO && ffao_uses_saao(settings.ffao)) {
        plan.blur = !raw_view && settings.ffao.saao_blur == OBSCURA_TOGGLE_ON;
        plan.apron = plan.blur ? 2 : 0;  // the 5x5 box
    }
    // AO is computed where the blur will read it: the output rect plus the apron on both axes.
    plan.ao_region = rect.expanded(plan.apron, plan.apron, input.width, input.height);
    if (method == OBSCURA_METHOD_SAO) plan.ao_region = aligned_to_quads(plan.ao_region);
    plan.blur_x_region = rect.expanded(0, plan.apron, input.width, input.height);

    // Blit targets: compose into the staging texture at (0, 0), then blit it to the host framebuffer.
    OutputTarget composite_target = target;
    if (target.kind == TargetKind::Blit) {
        composite_target.x = 0;
        composite_target.y = 0;
        if (!resources_.staging || resources_.staging.width() != rect.width ||
            resources_.staging.height() != rect.height || resources_.staging.internal_format() != staging_format) {
            gl_.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE));  // a unit the StateGuard restores
            resources_.staging = gl::Texture2D::create(gl_, staging_format, rect.width, rect.height);
            if (!resources_.staging_framebuffer) resources_.staging_framebuffer = gl::create_framebuffer(gl_);
            if (!resources_.staging) return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the staging texture failed");
            gl_.BindFramebuffer(GL_FRAMEBUFFER, resources_.staging_framebuffer.name());
            gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, resources_.staging.name(), 0);
        }
    } else if (resources_.staging) {
        resources_.staging = gl::Texture2D();  // a texture target again: the blit's staging is not needed
    }
    float radius = method == OBSCURA_METHOD_REFERENCE ? settings.reference.radius
                   : method == OBSCURA_METHOD_SAO     ? sao.radius
                   : method == OBSCURA_METHOD_LSAO    ? settings.lsao.radius
                   : method == OBSCURA_METHOD_FFAO    ? settings.ffao.radius
                                                     : hbao.radius;
    float debug_depth_scale = 1.0f / (4.0f * radius * input.meters_to_view_units);

    // The z pyramid's levels (1: no hierarchy, or the texture is too small for a level 1): SAO's, or FFAO's
    // mipmap baseline.
    const bool ffao_mipmap = method == OBSCURA_METHOD_FFAO && ffao_uses_mipmap(settings.ffao);
    const int pyramid_levels =
        method == OBSCURA_METHOD_SAO ? ZPyramidPass::level_count(input.width, input.height, SaoPass::wanted_levels(sao))
        : ffao_mipmap                ? ZPyramidPass::level_count(input.width, input.height, kFfaoMipmapLevels)
                                     : 1;
    const int pyramid_filter = method == OBSCURA_METHOD_SAO ? sao.mip_filter : ffao_mipmap_filter(settings.ffao);
    const int pyramid_dispatches = ZPyramidPass::dispatch_count(pyramid_levels);
    static_assert(OBSCURA_DEBUG_VIEW_TAP_COUNT == OBSCURA_DEBUG_TAP_COUNT, "shader_interface.h mirrors the API");

    uniforms_.reset(uniform_alignment_);
    UniformRange frame_whole = uniforms_.push(frame_constants(input, composite_target, whole, debug_depth_scale));
    UniformRange frame_ao = uniforms_.push(frame_constants(input, composite_target, plan.ao_region, debug_depth_scale));
    UniformRange frame_blur_x =
        uniforms_.push(frame_constants(input, composite_target, plan.blur_x_region, debug_depth_scale));
    UniformRange frame_blur_y = uniforms_.push(frame_constants(input, composite_target, rect, debug_depth_scale));
    // FFAO's SAAO gather reads the 3x3 neighbours of its region: the box average and the obscurance cover one
    // pixel more.
    const Region saao_region = plan.ao_region.expanded(1, 1, input.width, input.height);
    UniformRange frame_saao;
    if (method == OBSCURA_METHOD_FFAO && ffao_uses_saao(settings.ffao)) {
        frame_saao = uniforms_.push(frame_constants(input, composite_target, saao_region, debug_depth_scale));
    }
    UniformRange method_pass, blur_x_pass, blur_y_pass, table_pass;
    UniformRange pyramid_passes[4];
    switch (method) {
        case OBSCURA_METHOD_REFERENCE:
            method_pass = uniforms_.push(ReferencePass::constants(settings.reference, input));
            break;
        case OBSCURA_METHOD_LSAO:
            method_pass = uniforms_.push(lsao_.constants(settings.lsao, input, cpu_renderer_));
            break;
        case OBSCURA_METHOD_FFAO:
            for (int d = 0; d < pyramid_dispatches && d < 4; ++d) {
                pyramid_passes[d] = uniforms_.push(ZPyramidPass::constants(d, pyramid_levels, pyramid_filter));
            }
            method_pass = uniforms_.push(ffao_.constants(settings.ffao, input, pyramid_levels));
            table_pass = uniforms_.push(FfaoPass::table_constants(settings.ffao));
            break;
        case OBSCURA_METHOD_SAO:
            for (int d = 0; d < pyramid_dispatches && d < 4; ++d) {
                pyramid_passes[d] = uniforms_.push(ZPyramidPass::constants(d, pyramid_levels, pyramid_filter));
            }
            method_pass = uniforms_.push(SaoPass::constants(sao, input, pyramid_levels - 1));
            blur_x_pass = uniforms_.push(SaoBlurPass::constants(sao, 1, 0));
            blur_y_pass = uniforms_.push(SaoBlurPass::constants(sao, 0, 1));
            break;
        default:
            method_pass = uniforms_.push(HbaoPass::constants(hbao, input));
            blur_x_pass = uniforms_.push(BilateralBlurPass::constants(plan.apron, hbao.blur_sharpness, 1, 0));
            blur_y_pass = uniforms_.push(BilateralBlurPass::constants(plan.apron, hbao.blur_sharpness, 0, 1));
            break;
    }
    uniforms_.upload(gl_, uniform_buffer_.name());

    bool validate = (flags_ & OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES) != 0;
    auto after_pass = [&](const char* label) -> Error {
        timer_.mark(label);
        if (!validate) return Error();
        GLenum e = take_gl_error(gl_);
        if (e == GL_NO_ERROR) return Error();
        if (e == kGlContextLost) return gl_error_status(e, label);
        return Error::make(OBSCURA_STATUS_GL_ERROR, "%s raised in pass %s", gl_error_name(e), label);
    };

    timer_.begin_frame();
    depth_prepare_.run(pass_env, input, frame_whole, resources_);
    error = after_pass("depth_prepare");
    const gl::Texture2D* raw = &resources_.ao;  // the AO pass's output
    const gl::Texture2D* result = raw;          // what the composite shows without a debug view
    if (!error && method == OBSCURA_METHOD_REFERENCE) {
        // Each batch is flushed so the GPU starts on it while the next is recorded, and no single
        // submission runs long (watchdogs, a responsive desktop).
        reference_.run(pass_env, frame_ao, method_pass, plan.ao_region, settings.reference, resources_,
                       resources_.reference, [&] { gl_.Flush(); });
        raw = result = &resources_.reference;
        error = after_pass("reference");
    } else if (!error && method == OBSCURA_METHOD_LSAO) {
        lsao_.run_sweeps(pass_env, settings.lsao, frame_whole, method_pass, resources_);
        error = after_pass("line_sweep");
        if (!error) {
            lsao_.run_gather(pass_env, frame_ao, method_pass, plan.ao_region, resources_);
            error = after_pass("gather");
        }
    } else if (!error && method == OBSCURA_METHOD_FFAO) {
        if (ffao_.table_stale(settings.ffao)) {
            ffao_.run_table(pass_env, settings.ffao, table_pass);
            error = after_pass("ffao_table");
        }
        if (!error && ffao_mipmap && pyramid_levels > 1) {
            z_pyramid_.run(pass_env, pyramid_passes, pyramid_dispatches, resources_.linear_depth);
            error = after_pass("z_pyramid");
        }
        if (!error && !ffao_mipmap) {
            ffao_.run_scan(pass_env, frame_whole, method_pass, resources_);
            error = after_pass("ffao_scan");
        }
        if (!error && !ffao_mipmap && !ffao_single_lines(settings.ffao)) {
            ffao_.run_prefix(pass_env, frame_whole, method_pass);
            error = after_pass("ffao_prefix");
        }
        const bool saao = ffao_uses_saao(settings.ffao);
        if (!error && saao) {
            ffao_.run_box_average(pass_env, frame_saao, method_pass, saao_region, resources_);
            error = after_pass("ffao_box_average");
        }
        if (!error) {
            ffao_.run_obscurance(pass_env, settings.ffao, saao ? frame_saao : frame_ao, method_pass,
                                 saao ? saao_region : plan.ao_region, resources_);
            error = after_pass("ffao_obscurance");
        }
        if (!error && saao) {
            ffao_.run_gather(pass_env, frame_ao, method_pass, plan.ao_region, resources_);
            error = after_pass("ffao_gather");
        }
        if (!error && plan.blur) {
            ffao_.run_saao_blur(pass_env, frame_blur_y, method_pass, rect, resources_);
            result = &resources_.ao_blurred;
            error = after_pass("blur");
        }
    } else if (!error && method == OBSCURA_METHOD_SAO) {
        if (pyramid_levels > 1) {
            z_pyramid_.run(pass_env, pyramid_passes, pyramid_dispatches, resources_.linear_depth);
            error = after_pass("z_pyramid");
        }
        if (!error) {
            sao_.run(pass_env, frame_ao, method_pass, plan.ao_region, resources_);
            raw = result = &resources_.packed_ao;
            error = after_pass("sao");
        }
        if (!error && plan.blur) {
            sao_blur_.run(pass_env, frame_blur_x, blur_x_pass, plan.blur_x_region, resources_.packed_ao,
                          resources_.packed_temp, false);
            sao_blur_.run(pass_env, frame_blur_y, blur_y_pass, rect, resources_.packed_temp, resources_.ao_blurred,
                          true);
            result = &resources_.ao_blurred;
            error = after_pass("blur");
        }
    } else if (!error) {
        hbao_.run(pass_env, settings.hbao, frame_ao, method_pass, plan.ao_region, resources_);
        error = after_pass("hbao");
        if (!error && plan.blur) {
            blur_.run(pass_env, frame_blur_x, blur_x_pass, plan.blur_x_region, resources_.linear_depth, resources_.ao,
                      resources_.blur_temp);
            blur_.run(pass_env, frame_blur_y, blur_y_pass, rect, resources_.linear_depth, resources_.blur_temp,
                      resources_.ao_blurred);
            result = &resources_.ao_blurred;
            error = after_pass("blur");
        }
    }
    if (!error) {
        const gl::Texture2D& source = raw_view ? *raw : *result;
        if (target.kind == TargetKind::Image) {
            composite_.run(pass_env, frame_blur_y, input.output_rect, source, resources_, target.texture, target.format);
        } else {
            gl::BlitStateGuard blit_state(gl_);
            const GLuint host = blit_framebuffer(target);
            std::optional<gl::AttachmentZeroScope> attachment_zero;
            if (host != 0 && host == target.framebuffer) attachment_zero.emplace(gl_, host);
            // Multiply needs the framebuffer's colour first: blit it into the staging texture.
            if (target.blend == OBSCURA_BLEND_MULTIPLY) {
                gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, host);
                gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resources_.staging_framebuffer.name());
                gl_.BlitFramebuffer(target.x, target.y, target.x + rect.width, target.y + rect.height, 0, 0, rect.width,
                                    rect.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            }
            composite_.run(pass_env, frame_blur_y, input.output_rect, source, resources_, resources_.staging.name(),
                           resources_.staging.internal_format());
            gl_.MemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
            gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, resources_.staging_framebuffer.name());
            gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, host);
            gl_.BlitFramebuffer(0, 0, rect.width, rect.height, target.x, target.y, target.x + rect.width,
                                target.y + rect.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        }
        error = after_pass("composite");
    }
    // The host may read the result any way (sampling, image load, framebuffer, readback).
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    timer_.end_frame();
    return error;
}

}  // namespace obscura
