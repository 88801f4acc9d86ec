#include "gl_device.h"

#include <atomic>
#include <cstdio>
#include <cstring>

#include "gl/state_guard.h"

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

// GL 4.5 / KHR_robustness tokens; the SDK's loader is generated for GL 4.3.
constexpr GLenum kGlContextLost = GlDevice::kContextLost;
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

const char* error_name_of(GLenum error) {
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

}  // namespace

GlDevice::GlDevice(const obscura_context_desc& desc) {
    loader_.plain = desc.get_proc_address;
    loader_.with_user_data = desc.get_proc_address_with_user_data;
    loader_.user_data = desc.get_proc_address_user_data;
    gpu_code_paths_ = (desc.flags & OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS) != 0;
}

const char* GlDevice::error_name(GLenum error) { return error_name_of(error); }

GLenum GlDevice::take_error() const { return gl::take_errors(gl_); }

Error GlDevice::initialize() {
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
    cpu_renderer_ = !gpu_code_paths_ && is_cpu_renderer(reinterpret_cast<const char*>(get_string(GL_RENDERER)));
    query_buffers_ = version >= 40004 || has_extension(gl_, "GL_ARB_query_buffer_object");
    // Context loss: only robust contexts report a reset, through GL 4.5's query or its extension forms. A
    // loader may hand out stubs for any name, so the name is looked up only where the context has it.
    const char* reset_query = version >= 40005                                ? "glGetGraphicsResetStatus"
                              : has_extension(gl_, "GL_KHR_robustness")     ? "glGetGraphicsResetStatusKHR"
                              : has_extension(gl_, "GL_ARB_robustness")     ? "glGetGraphicsResetStatusARB"
                                                                            : nullptr;
    if (reset_query) {
        get_reset_status_ = reinterpret_cast<ResetStatusFn>(obscura_gl_lookup(&loader_, reset_query));
    }
    if (version >= 40005 || has_extension(gl_, "GL_ARB_direct_state_access")) {
        get_texture_parameteriv_ = reinterpret_cast<gl::TextureTargets::GetTextureParameterivFn>(
            obscura_gl_lookup(&loader_, "glGetTextureParameteriv"));
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
    GLenum pending = take_error();
    if (pending != GL_NO_ERROR) {
        return Error::make(OBSCURA_STATUS_HOST_GL_ERROR,
                           "the host left %s (0x%04X) pending before obscura_create_context; it was consumed",
                           GlDevice::error_name(pending), unsigned(pending));
    }

    gl::StateGuard guard(gl_);
    gl_.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &uniform_alignment_);
    gl_.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture_size_);
    // Identity of our GL context: a framebuffer object (never shared between contexts, unlike samplers or
    // textures) labelled with a process-unique string (names repeat across contexts, each counts from 1).
    static std::atomic<uint32_t> next_identity{0};
    std::snprintf(identity_label_, sizeof identity_label_, "obscura context %u", next_identity.fetch_add(1) + 1);
    identity_framebuffer_ = gl::create_framebuffer(gl_);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, identity_framebuffer_.name());  // a name becomes an object when bound
    gl_.ObjectLabel(GL_FRAMEBUFFER, identity_framebuffer_.name(), -1, identity_label_);
    return Error();
}

Error GlDevice::check_gl_context() const {
    const GLubyte* version = gl_.GetString(GL_VERSION);
    if (!version) return Error::make(OBSCURA_STATUS_WRONG_GL_CONTEXT, "no OpenGL context is current on this thread");
    // Our framebuffer exists only in our GL context (framebuffers are never shared); its label tells it
    // from another context's framebuffer of the same name.
    char label[sizeof identity_label_] = {};
    if (gl_.IsFramebuffer(identity_framebuffer_.name())) {
        gl_.GetObjectLabel(GL_FRAMEBUFFER, identity_framebuffer_.name(), GLsizei(sizeof label), nullptr, label);
    }
    if (std::strcmp(label, identity_label_) != 0) {
        // A lost context answers its queries with 0 too: when the host has already read its reset status
        // (glGetGraphicsResetStatus reports a reset once), a loss looks like this.
        return Error::make(OBSCURA_STATUS_WRONG_GL_CONTEXT,
                           "the current OpenGL context is not the one this obscura context was created on (or that "
                           "context was lost and its reset status already read: then destroy this obscura context "
                           "and create a new one on a new GL context)");
    }
    return Error();
}

Error GlDevice::check_context_lost() {
    if (!lost_reason_ && get_reset_status_) lost_reason_ = get_reset_status_();
    if (!lost_reason_) return Error();
    return Error::make(OBSCURA_STATUS_CONTEXT_LOST,
                       "the OpenGL context was lost (%s); destroy this obscura context and create a new one on a "
                       "new GL context",
                       reset_name(lost_reason_));
}

Error GlDevice::error_status(GLenum error, const char* where) {
    if (error == kGlContextLost) {
        lost_reason_ = kGlContextLost;
        return check_context_lost();
    }
    return Error::make(error == GL_OUT_OF_MEMORY ? OBSCURA_STATUS_OUT_OF_MEMORY : OBSCURA_STATUS_GL_ERROR,
                       "%s (0x%04X) raised %s", error_name(error), unsigned(error), where);
}

Error GlDevice::check_current_context() {
    // A loss already recorded is this context's for good. Otherwise the GL context comes first: the reset status
    // answers for whichever context is current, and another context's reset must not mark this one lost (it then
    // refused every call and leaked its objects on destroy, with its own healthy context current).
    if (lost_reason_) return check_context_lost();
    Error error = check_gl_context();
    if (error) {
        // The current context was reset (ours, whose queries now answer 0, or another): said as a loss, not recorded.
        const GLenum current_reset = get_reset_status_ ? get_reset_status_() : GLenum(GL_NO_ERROR);
        if (current_reset != GL_NO_ERROR) {
            return Error::make(OBSCURA_STATUS_CONTEXT_LOST,
                               "the current OpenGL context was lost (%s) and is not known to be this obscura "
                               "context's; if it is, destroy this obscura context and create a new one on a new GL "
                               "context",
                               reset_name(current_reset));
        }
        return error;
    }
    return check_context_lost();
}

Error GlDevice::check_host_state(const char* call) {
    Error error = check_current_context();
    if (error) return error;
    GLenum pending = take_error();
    if (pending == kGlContextLost) return error_status(pending, call);
    if (pending != GL_NO_ERROR) {
        return Error::make(OBSCURA_STATUS_HOST_GL_ERROR,
                           "the host left %s (0x%04X) pending before %s; it was consumed and nothing was done",
                           error_name(pending), unsigned(pending), call);
    }
    return Error();
}

namespace {
// Stand-ins for glDelete* when the obscura context is destroyed with another GL context current.
void GLAD_API_PTR keep_names(GLsizei, const GLuint*) {}
void GLAD_API_PTR keep_name(GLuint) {}
}  // namespace

void GlDevice::disarm_deletes() {
    gl_.DeleteTextures = &keep_names;
    gl_.DeleteBuffers = &keep_names;
    gl_.DeleteSamplers = &keep_names;
    gl_.DeleteQueries = &keep_names;
    gl_.DeleteFramebuffers = &keep_names;
    gl_.DeleteProgram = &keep_name;
}

}  // namespace obscura
