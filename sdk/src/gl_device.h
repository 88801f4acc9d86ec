// GlDevice: the SDK's view of the host's GL context. It owns the private function table loaded through the
// host's get_proc_address, knows the context's identity (so calls from another GL context are refused rather
// than touching that context's objects), tracks context loss, and tells the host's pending errors from the
// SDK's own.
#ifndef OBSCURA_GL_DEVICE_H
#define OBSCURA_GL_DEVICE_H

#include "error.h"
#include "gl/gl_objects.h"
#include "gl/texture_probe.h"

namespace obscura {

class GlDevice {
public:
    static constexpr GLenum kContextLost = gl::kGlContextLostError;  // GL_CONTEXT_LOST (GL 4.5)

    explicit GlDevice(const obscura_context_desc& desc);
    GlDevice(const GlDevice&) = delete;
    GlDevice& operator=(const GlDevice&) = delete;

    // Loads GL from the current context and checks it: version, every function the SDK calls, no pending host
    // error, no reset; then creates the identity object. Errors as obscura_create_context.
    Error initialize();
    const gl::Table& gl() const { return gl_; }
    GLint uniform_alignment() const { return uniform_alignment_; }
    GLint max_texture_size() const { return max_texture_size_; }
    // GL_RENDERER names a CPU rasteriser (llvmpipe ...), and the context's flags do not ask for the GPU code paths:
    // which variants the passes compile.
    bool cpu_renderer() const { return cpu_renderer_; }
    // The context has GL_QUERY_BUFFER (GL 4.4, or GL_ARB_query_buffer_object), a binding that changes what
    // glGetQueryObject* does: the GPU timer sets the host's aside while it reads its queries.
    bool query_buffers() const { return query_buffers_; }
    // How validation learns host textures' targets (gl/texture_probe.h): asked where the context can be, without
    // the GL errors of probing binds.
    gl::TextureTargets texture_targets() const { return {gl_, get_texture_parameteriv_}; }

    // WRONG_GL_CONTEXT unless the GL context this device was initialised on is current.
    Error check_gl_context() const;
    // CONTEXT_LOST once the GL context has reported a reset (sticky: a lost context never comes back).
    Error check_context_lost();
    bool lost() const { return lost_reason_ != 0; }
    // A recorded loss; else check_gl_context (CONTEXT_LOST instead when the current context reports a reset, not
    // recorded: it may be another context's), then check_context_lost.
    Error check_current_context();
    // check_current_context, then HOST_GL_ERROR if the host left an error pending (consumed and reported, never
    // blamed on a pass), or CONTEXT_LOST if that error is GL_CONTEXT_LOST.
    Error check_host_state(const char* call);
    // Drains the GL error queue: gl::take_errors (GL_CONTEXT_LOST, else GL_OUT_OF_MEMORY if either was pending, else
    // the first error).
    GLenum take_error() const;
    // A GL error raised inside the SDK as a status: CONTEXT_LOST for GL_CONTEXT_LOST (the device is then
    // lost), OUT_OF_MEMORY for GL_OUT_OF_MEMORY (which GL may raise from any call that needs memory, the per-frame
    // re-specification of the uniform buffer among them), else GL_ERROR; the message names `where` ("while rendering", "in pass hbao").
    Error error_status(GLenum error, const char* where);
    // Whether initialize() got as far as the identity object (so the GL context can be recognised).
    bool has_identity() const { return static_cast<bool>(identity_framebuffer_); }
    // Turns the glDelete* entries into no-ops: destroying with another GL context current, or after a loss.
    void disarm_deletes();

    static const char* error_name(GLenum error);

private:
    using ResetStatusFn = GLenum(GLAD_API_PTR*)(void);
    ObscuraGlLoader loader_ = {};
    gl::Table gl_ = {};  // first: the objects below release through it
    GLint uniform_alignment_ = 256;
    GLint max_texture_size_ = 0;
    bool cpu_renderer_ = false;
    bool query_buffers_ = false;
    bool gpu_code_paths_ = false;  // OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS
    // glGetGraphicsResetStatus (GL 4.5) or its KHR/ARB_robustness form; null when the context has neither.
    ResetStatusFn get_reset_status_ = nullptr;
    // glGetTextureParameteriv (GL 4.5 or ARB_direct_state_access): texture targets without probing binds; null without.
    gl::TextureTargets::GetTextureParameterivFn get_texture_parameteriv_ = nullptr;
    GLenum lost_reason_ = 0;  // the reset status (or GL_CONTEXT_LOST) that marked the context lost; 0: alive
    char identity_label_[32] = {};  // process-unique label of identity_framebuffer_
    gl::Object identity_framebuffer_;
};

}  // namespace obscura

#endif  // OBSCURA_GL_DEVICE_H
