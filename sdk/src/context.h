// Context: one per host GL context. Owns the GL function table (loaded from the host's
// get_proc_address), the compiled passes, the per-size resources and the timers, and runs a frame:
// validate -> (re)allocate -> constants -> passes -> composite, all under one StateGuard.
#ifndef OBSCURA_CONTEXT_H
#define OBSCURA_CONTEXT_H

#include "error.h"
#include "frame_input.h"
#include "gl/gl_objects.h"
#include "gpu_timer.h"
#include "host_allocator.h"
#include "passes/bilateral_blur.h"
#include "passes/composite.h"
#include "passes/depth_prepare.h"
#include "passes/ffao.h"
#include "passes/hbao.h"
#include "passes/lsao.h"
#include "passes/pass_common.h"
#include "passes/reference.h"
#include "passes/sao.h"
#include "passes/z_pyramid.h"

struct obscura_context {};  // the opaque handle type; Context derives from it

namespace obscura {

class Context : public obscura_context {
public:
    // Creates a context in memory from the desc's allocator. Errors as obscura_create_context.
    static Error create(const obscura_context_desc& desc, Context** out);
    static void destroy(Context* context);

    Error render(const obscura_input& input, const obscura_settings& settings, const obscura_output& output);
    Error prepare(int width, int height, const obscura_settings& settings);
    void release_resources();
    // obscura_release_resources: release_resources, unless another GL context is current (a warning, nothing freed:
    // our names would denote that context's objects there).
    void release_resources_from_host();
    uint32_t timings(obscura_timing* out, uint32_t capacity, uint64_t* frame_index) {
        return timer_.latest(out, capacity, frame_index);
    }
    uint64_t memory_bytes() const;

    // Records an error for obscura_get_last_error and forwards it to the log callback; returns its status.
    obscura_status report(const Error& error);
    const char* last_error() const { return last_error_; }

private:
    explicit Context(const obscura_context_desc& desc);
    ~Context();
    Error initialize();
    PassEnv env() const;
    Error check_gl_context();
    // CONTEXT_LOST once the GL context has reported a reset (sticky: a lost context never comes back).
    Error check_context_lost();
    // Turns a GL error raised inside the SDK into a status: CONTEXT_LOST for GL_CONTEXT_LOST, else GL_ERROR.
    Error gl_error_status(GLenum error, const char* where);
    // check_context_lost, check_gl_context, then HOST_GL_ERROR if the host left an error pending (consumed and
    // reported), or CONTEXT_LOST if that error is GL_CONTEXT_LOST.
    Error check_host_state(const char* call);
    // The framebuffer a blit reaches the host's target through: 0 (default) or ours with the host's
    // colour attachment 0 attached, so only that attachment is read and written.
    GLuint blit_framebuffer(const OutputTarget& target);
    // Turns the glDelete* entries of the table into no-ops (destroy with another GL context current).
    void disarm_gl_deletes();
    Error ensure_resources(int width, int height);
    // The REFERENCE method's R32F accumulator, allocated the first time the method renders at this size.
    Error ensure_reference_accumulator();
    // SAO's resources: `levels` MIP levels on the linear depth (the z pyramid) and the packed AO textures.
    Error ensure_sao_resources(int levels);
    // MIP levels 0..levels-1 on the linear depth (SAO's z pyramid, FFAO's mipmap baseline).
    Error ensure_depth_pyramid(int levels);
    // The method-specific resources a render with these resolved settings needs.
    Error ensure_method_resources(const obscura_settings& settings);
    Error record_frame(const FrameInput& input, const obscura_settings& settings, const OutputTarget& target);

    AllocatorCallbacks alloc_;
    obscura_log_fn log_;
    void* log_user_data_;
    uint32_t flags_;
    ObscuraGlLoader loader_ = {};
    gl::Table gl_ = {};
    GLint uniform_alignment_ = 256;
    GLint max_texture_size_ = 0;
    char identity_label_[32] = {};  // process-unique label of identity_framebuffer_
    gl::Object identity_framebuffer_;
    gl::Object target_framebuffer_;  // see blit_framebuffer()

    gl::Object sampler_;
    gl::Object sampler_mipmap_;
    bool cpu_renderer_ = false;  // GL_RENDERER names a CPU rasteriser (is_cpu_renderer)
    // glGetGraphicsResetStatus (GL 4.5) or its KHR/ARB_robustness form; null when the context has neither.
    using ResetStatusFn = GLenum(GLAD_API_PTR*)(void);
    ResetStatusFn get_reset_status_ = nullptr;
    GLenum lost_reason_ = 0;  // the reset status (or GL_CONTEXT_LOST) that marked the context lost; 0: alive
    gl::Buffer uniform_buffer_;
    UniformArena uniforms_;
    DepthPreparePass depth_prepare_;
    HbaoPass hbao_;
    ReferencePass reference_;
    ZPyramidPass z_pyramid_;
    SaoPass sao_;
    SaoBlurPass sao_blur_;
    LsaoPass lsao_;
    FfaoPass ffao_;
    BilateralBlurPass blur_;
    CompositePass composite_;
    FrameResources resources_;
    GpuTimer timer_;
    char last_error_[1024] = {};
};

}  // namespace obscura

#endif  // OBSCURA_CONTEXT_H
