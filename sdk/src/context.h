// Context: one per host GL context, the thin owner that sequences a frame. It holds the GL device (function
// table, identity, loss), one technique per method used so far (created from the method registry), the depth
// preparation every method shares, the frame planner, the output writer and the timer, and runs a frame:
// check the host's state -> resolve settings -> validate input and output -> plan -> prepare -> constants ->
// depth preparation -> the technique's passes -> [temporal] -> [upsample] -> output, all under one StateGuard. At
// reduced resolution everything from the depth preparation to the temporal pass runs on the reduced frame
// (reduced_resolution.h), the upsample and the output on the host's.
#ifndef OBSCURA_CONTEXT_H
#define OBSCURA_CONTEXT_H

#include "error.h"
#include "frame_input.h"
#include "frame_planner.h"
#include "gl_device.h"
#include "gpu_timer.h"
#include "host_allocator.h"
#include "output_writer.h"
#include "passes/depth_prepare.h"
#include "passes/pass_common.h"
#include "passes/temporal.h"
#include "passes/upsample.h"
#include "technique.h"

struct obscura_context {};  // the opaque handle type; Context derives from it
struct obscura_view {};     // the opaque handle type; View derives from it

namespace obscura {

// A view: one camera's temporal history, owned by its context (a list, so a handle can be checked).
class View : public obscura_view {
public:
    TemporalHistory history;
    View* next = nullptr;
};

class Context : public obscura_context {
public:
    // Creates a context in memory from the desc's allocator. Errors as obscura_create_context.
    static Error create(const obscura_context_desc& desc, Context** out);
    static void destroy(Context* context);

    Error render(const obscura_input& input, const obscura_settings& settings, const obscura_output& output);
    Error prepare(int width, int height, const obscura_settings& settings);
    // obscura_release_resources: frees every per-size resource, unless another GL context is current (a warning,
    // nothing freed: our names would denote that context's objects there).
    void release_resources_from_host();
    // obscura_get_timings: the timer's latest complete frame. Reads GL queries, so only with this context's GL
    // context current (WRONG_GL_CONTEXT) and not after a loss (CONTEXT_LOST): nothing is read then.
    Error timings(obscura_timing* out, uint32_t capacity, uint32_t* count, uint64_t* frame_index);
    uint64_t memory_bytes() const;
    // Whether the GL renderer is a CPU rasteriser (what some settings derive from: obscura_resolve_settings).
    bool cpu_renderer() const { return device_.cpu_renderer(); }
    // obscura_create_view / obscura_destroy_view. Views are freed with the context.
    Error create_view(View** out);
    Error destroy_view(obscura_view* view);

    // Records an error for obscura_get_last_error and forwards it to the log callback; returns its status.
    obscura_status report(const Error& error);
    const char* last_error() const { return last_error_; }

private:
    explicit Context(const obscura_context_desc& desc);
    ~Context();
    Error initialize();
    PassEnv env() const;
    // obscura_prepare's work under its state guard: the technique, the shared resources and the upsample's.
    Error prepare_resources(int width, int height, const obscura_settings& resolved);
    // Drains the GL errors left pending: `error` unless there was one, or unless it is GL_OUT_OF_MEMORY or a loss
    // (then that, `where` in its message).
    Error take_pending_error(Error error, const char* where);
    // The technique of a resolved method, created on first use; every other technique's resources are freed
    // when the method changes (the context holds what its latest configuration needs and nothing else).
    Error technique_for(obscura_method method, Technique** out);
    // The shared per-size textures, the linear depth's MIP levels, and the reconstruction's targets when the
    // technique's plan writes them (freed when it does not).
    // The shared working textures the plan's passes use at this size (FrameResources), and nothing else; ao_blurred
    // only where a frame of these settings without a debug view does not end with the technique's target write.
    Error ensure_resources(int width, int height, const TechniquePlan& plan, int shift, const obscura_settings& settings);
    // Every per-size resource: the frame's (shared textures, output staging, the techniques') and the views'.
    void release_resources();
    // The frame's resources (shared textures, output staging, the techniques'); with `sized_only` (a resize) the
    // techniques keep what does not depend on the size.
    void release_frame_resources(bool sized_only = false);
    Error record_frame(const FrameInput& input, const obscura_settings& settings, const OutputTarget& target);
    // The view a frame names (null: the context's own); null if it is none of this context's.
    View* find_view(const obscura_view* view);

    AllocatorCallbacks alloc_;
    obscura_log_fn log_;
    void* log_user_data_;
    uint32_t flags_;
    GlDevice device_;  // first: every GL object below releases through its table
    gl::Object sampler_;
    gl::Object sampler_mipmap_;
    FramePlanner planner_;
    DepthPreparePass depth_prepare_;
    OutputWriter output_;
    Technique* techniques_[OBSCURA_METHOD_COUNT_] = {};
    obscura_method current_method_ = OBSCURA_METHOD_COUNT_;
    FrameResources resources_;
    TemporalPass temporal_;
    UpsamplePass upsample_;    // reduced resolution: the full-size result
    View own_view_;            // the history of renders that name no view
    View* views_ = nullptr;    // obscura_create_view's, newest first
    GpuTimer timer_;
    char last_error_[1024] = {};
};

}  // namespace obscura

#endif  // OBSCURA_CONTEXT_H
