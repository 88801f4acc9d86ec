// Technique: one method's passes and resources behind one interface, which Context drives without knowing
// the method. A frame is: plan (what the frame needs before anything is recorded) -> prepare (programs and
// resources, created or reused) -> write_constants (the passes' uniform blocks, uploaded together) -> record
// (the dispatches, each pass ended through the recorder). Each method's technique lives in
// sdk/src/methods/<method>.cpp beside its settings metadata and registry row (method_registry.h).
#ifndef OBSCURA_TECHNIQUE_H
#define OBSCURA_TECHNIQUE_H

#include "error.h"
#include "frame_input.h"
#include "host_allocator.h"
#include "output_writer.h"
#include "pass_id.h"
#include "passes/pass_common.h"

#include <new>

namespace obscura {

// What the host asked of a frame beyond the AO (from its output), known before anything is planned.
struct FrameRequest {
    bool raw_view = false;      // a debug view: no reconstruction (it shows the AO pass's own output, or depth or normals)
    bool bent_normals = false;  // output.bent_normal_texture is set (only techniques whose plan says so write it)
    // false in obscura_prepare, which knows no output: a technique prepares for what the last render's output
    // needed, so a host that renders bent normals every frame allocates nothing on the frame after a prepare.
    bool output_known = true;
    uint32_t frame_index = 0;   // obscura_input.frame_index: selects the layout phase of LSAO and FFAO (layout_phase.h)
    // Where the AO pass will compute (FrameRegions::ao), for resources sized to it rather than to the guard band.
    // Set after plan(), which decides it; empty in obscura_prepare.
    Region ao_region;
    // The host's target image the technique's last pass writes in the composite's place (format 0: it writes its
    // own result). Set after plan(), where the plan says it can (TechniquePlan::writes_target) and the frame ends with
    // that pass: full resolution, no accumulation, no debug view.
    TargetWrite target;
};

// What a technique needs of a frame before anything is allocated or recorded.
struct TechniquePlan {
    int apron = 0;             // texels its reconstruction reads beyond the output rectangle on each side
    bool ao_on_quads = false;  // the AO region starts on even coordinates (a filter over absolute 2x2 quads)
    int depth_levels = 1;      // MIP levels the linear depth needs (a z pyramid over level 0); 1: none
    float radius = 1.0f;       // the method's radius in metres: the linear-depth debug view's scale
    bool bent_normals = false; // the technique writes bent normals (TechniqueOutput::bent) when requested
    // The shared working textures (FrameResources) its passes write, from the settings and the output kind alone (a
    // debug view, which skips the reconstruction, does not free and reallocate them): the AO pass's R16F result,
    // a separable reconstruction's intermediate, and the reconstruction's result. The context allocates ao_blurred
    // only where the frame does not end with the technique's own target write (writes_target): at reduced resolution
    // or with accumulation, whose passes read it.
    bool uses_ao = true;
    bool uses_blur_temp = false;
    bool uses_ao_blurred = false;
    // Texels beyond the AO region where its passes read the normals (depth preparation reconstructs them there
    // only; the guard band around gets the linear depth alone); kNormalsEverywhere: the whole texture.
    int normals_margin = 0;
    // Its last reconstruction pass can write the host's target image itself (FrameRequest::target): the composite
    // would only copy its result there. From the settings alone; the context asks it only at full resolution, without
    // accumulation and without a debug view.
    bool writes_target = false;
    static constexpr int kNormalsEverywhere = -1;
};

// The regions of a frame's passes, in depth-texture texels (frame_planner.h computes them from the plan).
struct FrameRegions {
    Region whole;   // the whole depth texture: depth preparation (split around `normals`), sweeps, scans
    Region output;  // the output rectangle: the last reconstruction pass and the composite
    Region ao;      // where the AO pass computes: the output rectangle and the apron around it
    Region blur_x;  // a separable reconstruction's horizontal pass: the output rectangle grown vertically
    Region normals; // where the normals are read: the AO region and the plan's normals_margin
};

// The frame's shared constants (FrameConstants, work_rect = the region) for those regions.
struct FrameUniforms {
    UniformRange whole, output, ao, blur_x;
};

// A frame as a technique sees it while it writes its constants and records its passes.
struct Frame {
    const PassEnv& env;
    const FrameInput& input;
    const obscura_settings& settings;  // resolved
    const FrameRegions& regions;
    const FrameUniforms& uniforms;
    FrameResources& resources;         // the shared per-size textures (depth, normals, AO, blur targets)
    bool raw_view;                     // a debug view: no reconstruction (FrameRequest::raw_view)
    bool bent_normals;                 // requested, and the technique's plan writes them
    TargetWrite target;                // FrameRequest::target: the last pass writes the host's target image
};

// Collects the frame's uniform blocks (one upload for the whole frame).
class UniformWriter {
public:
    virtual ~UniformWriter() = default;
    template <class Block>
    UniformRange push(const Block& block) { return arena().push(block); }
    // The frame's shared constants for a pass computing `work` (a region the planner does not provide).
    virtual UniformRange frame_constants(const Region& work) = 0;

protected:
    virtual UniformArena& arena() = 0;
};

// Ends passes: marks the timer and, with OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES, reports the pass that raised a
// GL error. Once a pass failed every later end() returns that error, so a technique may record on and return
// the last result.
class PassRecorder {
public:
    virtual ~PassRecorder() = default;
    virtual Error end(PassId pass) = 0;
    // Starts the GPU on what was recorded so far (long passes split into dispatches).
    virtual void flush() = 0;
};

// Where the technique left its result.
struct TechniqueOutput {
    const gl::Texture2D* raw = nullptr;     // the AO pass's own output (the raw debug views)
    const gl::Texture2D* result = nullptr;  // after the reconstruction: what the composite shows
    const gl::Texture2D* bent = nullptr;    // with bent normals: RGBA16F visibility, unit view-space bent normal xyz
    // With Frame::target: the last pass, not yet run, which the output writer runs into the target's image (it lives
    // in the technique and holds the frame's references until the frame's output is written; `result` is then not
    // written), and the label its time is reported under.
    const OutputImageWrite* target_write = nullptr;
    PassId target_pass = PassId::Composite;
};

// A technique's last pass, run by the output writer into the target's image (Frame::target) in the composite's place:
// T::write_target(env, frame, texture) for the frame that deferred it. The technique owns one; it holds that frame
// until the frame's output is written.
template <class T>
class LastPassTargetWrite final : public OutputImageWrite {
public:
    explicit LastPassTargetWrite(const T& technique) : technique_(technique) {}
    // Hands the pass to the output writer (TechniqueOutput::target_write), its time under `label`.
    Error defer(const Frame& frame, PassId label, TechniqueOutput* out) {
        frame_ = &frame;
        out->target_write = this;
        out->target_pass = label;
        return Error();
    }
    void write_image(const PassEnv& env, GLuint texture, GLenum) const override {
        technique_.write_target(env, *frame_, texture);
    }

private:
    const T& technique_;
    const Frame* frame_ = nullptr;
};

class Technique {
public:
    virtual ~Technique() = default;
    // What a frame with these resolved settings needs at a width x height depth texture.
    virtual TechniquePlan plan(const obscura_settings& settings, int width, int height,
                               const FrameRequest& request) const = 0;
    // Builds the programs the settings run and creates or reuses the technique's resources for the size of
    // `resources` (whose linear depth already has the plan's levels) and the request (bent normals only where the
    // plan writes them). Called by obscura_prepare and by every frame: cheap when nothing changed. Programs are
    // kept; resources follow the latest settings only.
    virtual Error prepare(const PassEnv& env, const obscura_settings& settings, const FrameRequest& request,
                          FrameResources& resources) = 0;
    // Pushes the uniform blocks of the passes record() will run.
    virtual void write_constants(const Frame& frame, UniformWriter& uniforms) = 0;
    // Records the passes, ending each through `recorder`.
    virtual Error record(const Frame& frame, PassRecorder& recorder, TechniqueOutput* out) = 0;
    // GPU memory of the technique's own resources.
    virtual uint64_t memory_bytes() const = 0;
    // Frees the technique's resources (not its programs): another method renders now, or the host released the
    // context's resources.
    virtual void release() = 0;
    // Frees what depends on the frame's size (the size changed); resources of another kind (FFAO's estimator table,
    // which only its falloff's shape changes) are kept. The default frees everything.
    virtual void release_sized() { release(); }
};

// Techniques live in the host allocator's memory, like every CPU allocation of the SDK.
template <class T>
Technique* create_technique(const AllocatorCallbacks& alloc) {
    void* memory = alloc.allocate(sizeof(T));
    if (!memory) throw std::bad_alloc();
    return new (memory) T();
}

inline void destroy_technique(Technique* technique, const AllocatorCallbacks& alloc) {
    if (!technique) return;
    technique->~Technique();
    alloc.release(technique);
}

}  // namespace obscura

#endif  // OBSCURA_TECHNIQUE_H
