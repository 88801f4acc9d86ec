#include "context.h"

#include <cstdio>
#include <cstring>
#include <new>

#include "gl/state_guard.h"
#include "method_registry.h"
#include "reduced_resolution.h"
#include "settings.h"

namespace obscura {
namespace {

// Ends a frame's passes: the timer's mark, and with VALIDATE_PASSES the pass that raised a GL error.
class FramePassRecorder final : public PassRecorder {
public:
    FramePassRecorder(GlDevice& device, GpuTimer& timer, bool validate)
        : device_(device), timer_(timer), validate_(validate) {}
    Error end(PassId pass) override {
        if (error_) return error_;
        timer_.mark(pass);
        if (!validate_) return error_;
        const GLenum e = device_.take_error();
        if (e != GL_NO_ERROR) {
            char where[64];
            std::snprintf(where, sizeof where, "in pass %s", pass_label(pass));
            error_ = device_.error_status(e, where);
        }
        return error_;
    }
    void flush() override { device_.gl().Flush(); }

private:
    GlDevice& device_;
    GpuTimer& timer_;
    bool validate_;
    Error error_;
};

// What a history was computed with: the method and its settings blocks (FNV-1a over the bytes), and what of the
// frame's input changes the AO as a setting would: the scale of a metre (the radius in view units), the host's
// normals or the reconstructed ones, linear or hardware depth. GTAO's own frame_index and REFERENCE's first_ray only
// move the noise, as obscura_input.frame_index does, so they are left out. A change starts anew.
uint64_t history_signature(const obscura_settings& settings, const FrameInput& input, bool bent_normals) {
    const MethodDescriptor* row = find_method(settings.method);
    obscura_settings copy = settings;
    copy.gtao.frame_index = 0;
    copy.reference.first_ray = 0;  // likewise: REFERENCE's frames advance it to trace new rays
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(&copy) + row->settings_offset;
    uint64_t hash = 1469598103934665603ull;
    auto mix = [&](unsigned char b) { hash = (hash ^ b) * 1099511628211ull; };
    for (size_t i = 0; i < row->settings_size; ++i) mix(bytes[i]);
    const unsigned char* added = reinterpret_cast<const unsigned char*>(&copy) + row->added_offset;
    for (size_t i = 0; i < row->added_size; ++i) mix(added[i]);
    mix(static_cast<unsigned char>(settings.method));
    mix(bent_normals ? 1 : 0);
    mix(static_cast<unsigned char>(settings.resolution.scale));  // a 1x1 frame is 1x1 at every resolution
    unsigned char scale[sizeof input.meters_to_view_units];
    std::memcpy(scale, &input.meters_to_view_units, sizeof scale);
    for (unsigned char b : scale) mix(b);
    mix(static_cast<unsigned char>(input.normal_mode));
    mix(input.depth_linear ? 1 : 0);
    return hash;
}

// Whether frames of these settings end with the technique's own write of the host's target (no composite) when
// they show no debug view: full resolution, no accumulation, and a last pass that can (TechniquePlan::writes_target).
// The one rule for both the frame's plan and the working textures it keeps.
bool ends_with_technique_write(const TechniquePlan& plan, int shift, const obscura_settings& settings) {
    return plan.writes_target && shift == 0 && settings.temporal.enabled != OBSCURA_TOGGLE_ON;
}

}  // namespace

Context::Context(const obscura_context_desc& desc)
    : alloc_(AllocatorCallbacks::from(desc.allocator)),
      log_(desc.log),
      log_user_data_(desc.log_user_data),
      flags_(desc.flags),
      device_(desc) {}

Context::~Context() {
    while (views_) {
        View* view = views_;
        views_ = view->next;
        view->~View();
        alloc_.release(view);
    }
    for (Technique*& technique : techniques_) {
        destroy_technique(technique, alloc_);
        technique = nullptr;
    }
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
        destroy(context);  // a failed allocation while creating objects: free the GL objects made so far
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
    GlDevice& device = context->device_;
    // A lost GL context took the objects with it; deleting names there would at best do nothing.
    if (device.lost()) {
        device.disarm_deletes();
    } else if (device.has_identity() && device.check_gl_context()) {
        // Deleting GL names with another context current would delete that context's objects: leak instead.
        if (context->log_) {
            context->log_(OBSCURA_LOG_WARNING, OBSCURA_STATUS_WRONG_GL_CONTEXT,
                          "obscura_destroy_context: the context's GL context is not current; its GL objects are "
                          "leaked rather than deleted in another context",
                          context->log_user_data_);
        }
        device.disarm_deletes();
    }
    AllocatorCallbacks alloc = context->alloc_;
    context->~Context();
    alloc.release(context);
}

PassEnv Context::env() const {
    return PassEnv{device_.gl(),          alloc_, log_, log_user_data_, sampler_.name(), sampler_mipmap_.name(),
                   planner_.uniform_buffer(), device_.cpu_renderer()};
}

Error Context::initialize() {
    Error error = device_.initialize();
    if (error) return error;
    const gl::Table& gl = device_.gl();
    {
        gl::StateGuard guard(gl);
        sampler_ = gl::create_sampler_nearest_clamp(gl);
        sampler_mipmap_ = gl::create_sampler_nearest_mipmap_clamp(gl);
        planner_.create(gl, device_.uniform_alignment());
        timer_.create(gl, (flags_ & OBSCURA_CONTEXT_FLAG_SYNC_TIMING) != 0, device_.query_buffers());
    }
    // Buffer::create consumes the GL error of a failed allocation and returns an empty buffer: checked here, or
    // the context would be created without its uniform buffer and every render would fail.
    if (planner_.uniform_buffer() == 0) {
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %d-byte uniform buffer failed (a GL error)",
                           int(UniformArena::kCapacity));
    }
    const GLenum gl_error = device_.take_error();
    if (gl_error != GL_NO_ERROR) return device_.error_status(gl_error, "while creating the context's GL objects");
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
    uint64_t bytes = resources_.bytes() + planner_.bytes() + output_.bytes() + upsample_.bytes() +
                     own_view_.history.bytes();
    for (const View* view = views_; view; view = view->next) bytes += view->history.bytes();
    for (const Technique* technique : techniques_) bytes += technique ? technique->memory_bytes() : 0;
    return bytes;
}

Error Context::technique_for(obscura_method method, Technique** out) {
    Technique*& technique = techniques_[method];
    if (!technique) technique = find_method(method)->create_technique(alloc_);
    if (method != current_method_) {
        for (Technique* other : techniques_) {
            if (other && other != technique) other->release();
        }
        current_method_ = method;
    }
    *out = technique;
    return Error();
}

Error Context::ensure_resources(int width, int height, const TechniquePlan& plan, int shift,
                                const obscura_settings& settings) {
    const PassEnv pass_env = env();
    const int depth_levels = plan.depth_levels;
    if (resources_.width != width || resources_.height != height || !resources_.linear_depth) {
        release_frame_resources(/*sized_only=*/true);  // the views' histories stay: each follows its own view's size
        FrameResources r;
        r.width = width;
        r.height = height;
        r.linear_depth = pass_env.create_texture(GL_R32F, width, height, depth_levels);
        r.normals = pass_env.create_texture(GL_RG16_SNORM, width, height);
        if (!r.linear_depth || !r.normals) {
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d working textures failed", width,
                               height);
        }
        resources_ = std::move(r);
    } else if (resources_.linear_depth.levels() != depth_levels) {
        // The depth preparation rewrites it every frame: replacing it loses nothing.
        resources_.linear_depth = pass_env.create_texture(GL_R32F, width, height, depth_levels);
        if (!resources_.linear_depth) {
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d z pyramid (%d levels) failed",
                               width, height, depth_levels);
        }
    }
    // Where frames end with the technique's own target write nothing reads the reconstruction's result texture
    // (debug views skip the reconstruction).
    const bool ends_with_target_write = ends_with_technique_write(plan, shift, settings);
    const struct {
        gl::Texture2D* texture;
        bool needed;
    } working[] = {{&resources_.ao, plan.uses_ao},
                   {&resources_.blur_temp, plan.uses_blur_temp},
                   {&resources_.ao_blurred, plan.uses_ao_blurred && !ends_with_target_write}};
    for (const auto& w : working) {
        if (!w.needed) {
            *w.texture = gl::Texture2D();  // the context holds what its latest configuration needs
        } else if (!*w.texture) {
            *w.texture = pass_env.create_texture(GL_R16F, width, height);
            if (!*w.texture) {
                return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d working textures failed",
                                   width, height);
            }
        }
    }
    return Error();
}

Error Context::create_view(View** out) {
    void* memory = alloc_.allocate(sizeof(View));
    if (!memory) return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating a view failed");
    View* view = new (memory) View();
    view->next = views_;
    views_ = view;
    *out = view;
    return Error();
}

Error Context::destroy_view(obscura_view* handle) {
    View** link = &views_;
    while (*link && *link != handle) link = &(*link)->next;
    if (!*link) {
        return Error::make(OBSCURA_STATUS_INVALID_VIEW, "obscura_destroy_view: %p is not a view of this context",
                           static_cast<void*>(handle));
    }
    if (!device_.lost() && device_.check_gl_context()) {
        return Error::make(OBSCURA_STATUS_WRONG_GL_CONTEXT,
                           "obscura_destroy_view: the context's GL context is not current; nothing was freed");
    }
    View* view = *link;
    *link = view->next;
    if (device_.lost()) device_.disarm_deletes();  // its textures went with the GL context
    view->~View();
    alloc_.release(view);
    return Error();
}

View* Context::find_view(const obscura_view* handle) {
    if (!handle) return &own_view_;
    for (View* view = views_; view; view = view->next) {
        if (view == handle) return view;
    }
    return nullptr;
}

void Context::release_frame_resources(bool sized_only) {
    resources_ = FrameResources();
    output_.release();
    upsample_.release();
    for (Technique* technique : techniques_) {
        if (!technique) continue;
        if (sized_only) {
            technique->release_sized();
        } else {
            technique->release();
        }
    }
}

void Context::release_resources() {
    release_frame_resources();
    own_view_.history.release();
    for (View* view = views_; view; view = view->next) view->history.release();
}

void Context::release_resources_from_host() {
    if (device_.lost() || device_.check_gl_context()) {
        if (log_ && !device_.lost()) {
            log_(OBSCURA_LOG_WARNING, OBSCURA_STATUS_WRONG_GL_CONTEXT,
                 "obscura_release_resources: the context's GL context is not current; nothing was freed", log_user_data_);
        }
        return;
    }
    release_resources();
}

Error Context::prepare(int width, int height, const obscura_settings& settings) {
    obscura_settings resolved;
    Error error = resolve_settings(settings, &resolved);
    if (error) return error;
    const GLint max_size = device_.max_texture_size();
    if (width <= 0 || height <= 0 || width > max_size || height > max_size) {
        return Error::make(OBSCURA_STATUS_INVALID_SIZE, "size %dx%d must be within 1..%d", width, height, max_size);
    }
    error = device_.check_host_state("obscura_prepare");
    if (error) return error;
    {
        gl::StateGuard guard(device_.gl());
        error = prepare_resources(width, height, resolved);
        // A GL error no call checked itself (an upload, a link that ran out of memory) is this call's, as in a
        // render: left pending, the next call would blame it on the host.
        error = take_pending_error(error, "while preparing");
    }
    return take_pending_error(error, "while restoring the host's GL state");
}

Error Context::take_pending_error(Error error, const char* where) {
    // A loss a step reported itself (a shader build's drained errors) is recorded like one seen here: every later
    // call must answer CONTEXT_LOST, not WRONG_GL_CONTEXT once the lost context's queries answer 0.
    if (error.status() == OBSCURA_STATUS_CONTEXT_LOST && !device_.lost()) {
        return device_.error_status(GlDevice::kContextLost, where);
    }
    const GLenum gl_error = device_.take_error();
    // Out of memory is what failed, whatever it made fail after it (a link without memory reads as a failed link),
    // and a lost context is lost; any other GL error only explains a call that succeeded otherwise.
    const bool reported = error.status() == OBSCURA_STATUS_OUT_OF_MEMORY || error.status() == OBSCURA_STATUS_CONTEXT_LOST;
    if (gl_error == GlDevice::kContextLost || (gl_error == GL_OUT_OF_MEMORY && !reported) ||
        (!error && gl_error != GL_NO_ERROR)) {
        return device_.error_status(gl_error, where);
    }
    // A step that failed may have drained a GL_CONTEXT_LOST with its own errors (an allocation or a build through
    // gl::take_errors, a texture probe reading its bind's error as a wrong target): the reset status tells a loss
    // from memory that ran out or a texture that was refused.
    if (error && !device_.lost()) {
        Error lost = device_.check_context_lost();
        if (lost) return lost;
    }
    return error;
}

Error Context::prepare_resources(int width, int height, const obscura_settings& resolved) {
    Technique* technique = nullptr;
    Error error = technique_for(resolved.method, &technique);
    if (error) return error;
    FrameRequest request;  // no output yet: the AO, and whatever extra outputs the last render asked for
    request.output_known = false;
    const int shift = resolution_shift(resolved);
    const int working_width = reduced_extent(width, shift), working_height = reduced_extent(height, shift);
    const TechniquePlan plan = technique->plan(resolved, working_width, working_height, request);
    // Whether the last render asked for bent normals, read before ensure_resources, which may release the upsample
    // (GTAO keeps its own record of the request).
    const bool upsample_bent = upsample_.bent() != nullptr;
    const bool upsample_result = upsample_.has_result();  // made for a debug view with bent normals (record_frame)
    error = ensure_resources(working_width, working_height, plan, shift, resolved);
    if (!error) error = technique->prepare(env(), resolved, request, resources_);
    if (!error && shift > 0) error = upsample_.allocate(env(), width, height, upsample_bent, upsample_result);
    if (!error && shift == 0) upsample_.release();
    return error;
}

Error Context::render(const obscura_input& input, const obscura_settings& settings, const obscura_output& output) {
    // Stage 1: what needs no GL.
    obscura_settings resolved;
    Error error = resolve_settings(settings, &resolved);
    FrameInput frame;
    OutputTarget target;
    if (!error) error = check_input_fields(input, device_.max_texture_size(), &frame);
    if (!error) error = check_output_fields(output, &target);
    if (!error && !find_view(frame.view)) {
        error = Error::make(OBSCURA_STATUS_INVALID_VIEW, "obscura_input.view %p is not a view of this context",
                            static_cast<void*>(frame.view));
    }
    if (error) return error;
    // A camera cut drops the view's history as soon as the view is known, before anything else can refuse the frame
    // (its textures, its output, a setting its method cannot fill, memory, a shader): otherwise the cut was lost and
    // the next frame continued the history from before it. (A debug view shows this frame alone and otherwise leaves
    // the history as it is.)
    if (frame.reset_history) find_view(frame.view)->history.invalidate();
    // Stage 2: the GL context, then the objects the input and output name (first whether they name one texture
    // twice: a host GL error left pending is still reported before that, as before every GL name's check).
    error = device_.check_host_state("obscura_render");
    if (error) return error;
    error = check_output_aliasing(input, output);
    if (error) return error;
    const gl::Table& gl = device_.gl();
    bool recorded = false;  // record_frame succeeded: the view's history (with temporal on) is this frame's
    {
        gl::StateGuard guard(gl);
        const gl::TextureTargets targets = device_.texture_targets();
        error = check_input_textures(targets, input, &frame);
        if (!error) error = check_output_target(targets, output, frame.output_rect, &target);
        if (!error) error = check_attachment_aliasing(input, output, target);
        if (!error) error = check_bent_normal_target(targets, output, frame.output_rect, &target);
        if (!error) error = record_frame(frame, resolved, target);
        recorded = !error;
        // A failed validation may leave a probing error (wrong texture target) behind: drain it.
        error = take_pending_error(error, "while rendering");
        // A frame whose passes raised a GL error (seen here unless OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES checked each
        // pass) may not have written the history it swapped in: the next frame starts anew. (A frame refused inside
        // record_frame, before its passes, left the history as it was: still the previous frame's.)
        if (error && recorded) find_view(frame.view)->history.invalidate();
    }
    const Error restored = take_pending_error(error, "while restoring the host's GL state");
    if (restored.status() != error.status() && recorded) find_view(frame.view)->history.invalidate();
    return restored;
}

Error Context::timings(obscura_timing* out, uint32_t capacity, uint32_t* count, uint64_t* frame_index) {
    *count = 0;
    *frame_index = 0;
    // As obscura_render checks it (without the host's pending errors, which are not this call's to take): a recorded
    // loss first, then the GL context, a reset of the current context reported as CONTEXT_LOST like render does.
    Error error = device_.check_current_context();
    if (error) return error;
    *count = timer_.latest(out, capacity, frame_index);
    return Error();
}

Error Context::record_frame(const FrameInput& host_input, const obscura_settings& settings,
                            const OutputTarget& target) {
    const PassEnv pass_env = env();
    Technique* technique = nullptr;
    Error error = technique_for(settings.method, &technique);
    if (error) return error;
    View* view = find_view(host_input.view);
    const bool debug_view = target.debug_view != OBSCURA_DEBUG_NONE;
    const bool temporal = settings.temporal.enabled == OBSCURA_TOGGLE_ON && !debug_view;
    // With matrices the history is reprojected from the frame it was made at. That is the host's previous frame
    // unless the host rendered that one with a debug view (or not at all): then its previous_view_projection would
    // miss a frame of motion. (On the host's grid: the reprojection maps view spaces, before any reduction.)
    FrameInput host = host_input;
    if (temporal && host.has_matrices && view->history.valid() && view->history.view_projection()) {
        set_reprojection(view->history.view_projection(), &host);
    }
    // The frame the method runs on: the host's, or at reduced resolution the reduced grid's.
    const int shift = resolution_shift(settings);
    const FrameInput input = shift > 0 ? reduced_frame_input(host, shift) : host;
    FrameRequest request;
    // Every debug view skips the reconstruction: none shows its result (the AO pass's own output, depth or normals).
    request.raw_view = debug_view;
    request.bent_normals = target.bent_texture != 0;
    request.frame_index = input.frame_index;
    const TechniquePlan plan = technique->plan(settings, input.width, input.height, request);
    if (request.bent_normals && !plan.bent_normals) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "output.bent_normal_texture is set but %s computes no bent normals (GTAO does)",
                           find_method(settings.method)->name);
    }
    const bool raw_view = request.raw_view;
    const FrameRegions regions = FramePlanner::regions(input, plan);
    request.ao_region = regions.ao;
    // At full resolution without accumulation the method's last reconstruction pass writes the target itself where it
    // can (the composite would only copy its result there), unless a debug view needs the composite's other sources.
    const bool technique_writes_target = ends_with_technique_write(plan, shift, settings) && !debug_view;
    if (technique_writes_target) request.target = target_write(target);
    error = ensure_resources(input.width, input.height, plan, shift, settings);
    if (!error) error = technique->prepare(pass_env, settings, request, resources_);
    if (!error) error = depth_prepare_.prepare(pass_env, input);
    // At reduced resolution the upsample writes the target itself (the composite would only copy its result there),
    // unless a debug view needs the composite's other sources.
    const bool upsample_writes_target = shift > 0 && target.debug_view == OBSCURA_DEBUG_NONE;
    // So does the temporal pass at full resolution (`temporal` excludes debug views): it is the frame's last pass.
    const bool temporal_writes_target = temporal && shift == 0;
    const TargetWrite upsample_destination = upsample_writes_target ? target_write(target) : TargetWrite();
    const TargetWrite temporal_destination = temporal_writes_target ? target_write(target) : TargetWrite();
    if (!error) {
        error = output_.prepare(pass_env, target, host.output_rect,
                                !upsample_writes_target && !temporal_writes_target && !technique_writes_target);
    }
    // A debug view shows the reduced grid itself (the composite reads it at pixel >> k): the upsample runs there only
    // for the bent normals, which every view upsamples.
    const bool upsample_runs = shift > 0 && (!debug_view || request.bent_normals);
    if (!error && upsample_runs) error = upsample_.prepare(pass_env, host, request.bent_normals, upsample_destination);
    if (error) return error;
    if (shift == 0) upsample_.release();  // the context holds what its latest configuration needs
    // Temporal accumulation: the view's history continues when the frame can be reprojected and nothing it was
    // computed with changed.
    bool history_continues = false;
    if (temporal) {
        const bool reproject = input.has_matrices || input.motion_vector_texture != 0;
        error = view->history.prepare(pass_env, input, request.bent_normals,
                                      history_signature(settings, input, request.bent_normals), reproject,
                                      &history_continues);
        if (!error) {
            error = temporal_.prepare(pass_env, request.bent_normals, TemporalPass::reprojection(input),
                                      temporal_destination);
        }
        if (error) return error;
    } else if (!debug_view) {
        view->history.release();  // the context holds what its latest configuration needs
    }

    const FrameUniforms uniforms = planner_.begin(input, OutputWriter::composite_target(target), regions, plan);
    const Frame frame{pass_env, input, settings, regions, uniforms, resources_, raw_view, request.bent_normals,
                      request.target};
    // Depth preparation's rectangles: the normals where the method reads them, the linear depth alone around them.
    const DepthPrepareRects depth_rects =
        depth_prepare_rects(regions.whole, regions.normals, DepthPreparePass::block(pass_env));
    DepthPrepareUniforms depth_uniforms;
    depth_uniforms.with_normals = planner_.frame_constants(depth_rects.with_normals);
    for (int i = 0; i < depth_rects.depth_only_count; ++i) {
        depth_uniforms.depth_only[i] = planner_.frame_constants(depth_rects.depth_only[i]);
    }
    technique->write_constants(frame, planner_);
    const UniformRange bent_pass = request.bent_normals ? planner_.push(OutputWriter::bent_constants(target)) : UniformRange();
    const UniformRange temporal_pass =
        temporal ? planner_.push(TemporalPass::constants(settings.temporal, input, history_continues)) : UniformRange();
    // The passes on the host's texels: at full resolution the frame's own output constants.
    const UniformRange host_output =
        shift > 0 ? planner_.host_constants(host, OutputWriter::composite_target(target), plan, shift, raw_view)
                  : uniforms.output;
    const UniformRange upsample_pass =
        shift > 0 ? planner_.push(UpsamplePass::constants(settings.resolution, input)) : UniformRange();
    planner_.upload(device_.gl());

    // The host's inputs (and, for MULTIPLY, its target) may come from its own image stores or compute writes just
    // before this call: GL orders those before the frame's fetches and image loads only through a barrier (GL 4.3,
    // 7.12.2), which a host calling middleware seldom knows it owes. One barrier a frame costs nothing measurable.
    device_.gl().MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                               GL_FRAMEBUFFER_BARRIER_BIT);
    FramePassRecorder recorder(device_, timer_, (flags_ & OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES) != 0);
    timer_.begin_frame();
    depth_prepare_.run(pass_env, input, depth_rects, depth_uniforms, resources_);
    error = recorder.end(PassId::DepthPrepare);
    TechniqueOutput result;
    if (!error) error = technique->record(frame, recorder, &result);
    // The temporal pass's write of the target (full resolution), which the output writer runs in the composite's
    // place; otherwise it runs here, before the upsample.
    const gl::Texture2D* method_result = result.result;
    const gl::Texture2D* method_bent = result.bent;
    const TemporalImageWrite temporal_write(temporal_, uniforms.output, temporal_pass, regions.output, input,
                                            resources_, method_result, method_bent, view->history);
    if (!error && temporal) {
        if (!temporal_writes_target) {
            temporal_.run(pass_env, uniforms.output, temporal_pass, regions.output, input, resources_, *method_result,
                          method_bent, view->history);
            error = recorder.end(PassId::Temporal);
        }
        result.result = &view->history.next();
        if (result.bent) result.bent = &view->history.next_bent();
    }
    // The upsample's write of the target, which the output writer runs in the composite's place.
    const UpsampleImageWrite upsample_write(upsample_, host_output, upsample_pass, host, resources_, result.result,
                                            result.bent);
    if (!error && upsample_runs) {
        // Without a debug view as the output's write; with one (which shows the reduced grid) for the bent normals.
        if (!upsample_writes_target) {
            upsample_.run(pass_env, host_output, upsample_pass, host, resources_, *result.result, result.bent);
            error = recorder.end(PassId::Upsample);
        }
        result.bent = upsample_.bent();
    }
    if (!error && technique_writes_target && !result.target_write) {
        error = Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "%s planned to write the target but left no pass for it",
                            find_method(settings.method)->name);
    }
    if (!error) {
        const OutputImageWrite* image_write = upsample_writes_target    ? static_cast<const OutputImageWrite*>(&upsample_write)
                                              : temporal_writes_target  ? &temporal_write
                                              : technique_writes_target ? result.target_write
                                                                        : nullptr;
        output_.write(pass_env, host_output, host, raw_view ? *result.raw : *result.result, resources_, target,
                      result.bent, bent_pass, image_write);
        error = recorder.end(upsample_writes_target    ? PassId::Upsample
                             : temporal_writes_target  ? PassId::Temporal
                             : technique_writes_target ? result.target_pass
                                                       : PassId::Composite);
    }
    // The frame's blend is the view's history from now on (a failed frame leaves it for the next to start anew).
    if (temporal) {
        if (error) view->history.invalidate();
        else view->history.swap(input);
    }
    // The host may read the result any way (sampling, image load, framebuffer, readback).
    device_.gl().MemoryBarrier(GL_ALL_BARRIER_BITS);
    timer_.end_frame();
    return error;
}

}  // namespace obscura
