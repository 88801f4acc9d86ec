// DepthPrepare: host depth (any projection, MSAA sample 0, or linear) -> linear view depth for the whole depth
// texture, and view-space normals where the method reads them. Shared by every method. Shader:
// sdk/glsl/depth_prepare.comp.
#ifndef OBSCURA_DEPTH_PREPARE_H
#define OBSCURA_DEPTH_PREPARE_H

#include "frame_input.h"
#include "passes/pass_common.h"

namespace obscura {

// Binds the host's depth texture on OBSCURA_UNIT_DEPTH for the dispatches of its scope, read as depth: a
// depth-stencil texture the host samples as stencil is switched to depth and back when the scope ends (GL runs a
// dispatch with the state it was issued with, so the host's mode can be put back right after).
class HostDepthBinding {
public:
    HostDepthBinding(const PassEnv& env, const FrameInput& input);
    ~HostDepthBinding();
    HostDepthBinding(const HostDepthBinding&) = delete;
    HostDepthBinding& operator=(const HostDepthBinding&) = delete;

private:
    const PassEnv& env_;
    const FrameInput& input_;
};

// The program variant of a pass that reads the host's depth: {hardware, linear} x {single-sample, multisample}.
inline int host_depth_variant(const FrameInput& input) {
    return (input.depth_linear ? 2 : 0) + (input.depth_multisample ? 1 : 0);
}

// The rectangles one frame's depth preparation covers: the linear depth and the normals over `with_normals`, the
// linear depth alone over the others (the guard band around it, whose texels only occlude: a normal reconstruction
// costs most of the pass on CPU rasterisers). Together they tile the whole texture, each texel once.
struct DepthPrepareRects {
    static constexpr int kMaxDepthOnly = 4;
    Region with_normals;
    Region depth_only[kMaxDepthOnly];  // the strips above and below it, then left and right of it
    int depth_only_count = 0;
};

// `normals` (within `whole`) grown outwards to multiples of `block` texels (an invocation's block on CPU
// rasterisers: no block then straddles two rectangles), clamped to `whole`, and the non-empty strips around it.
DepthPrepareRects depth_prepare_rects(const Region& whole, const Region& normals, int block);

// The frame constants of each rectangle (work_rect: the rectangle), in DepthPrepareRects' order.
struct DepthPrepareUniforms {
    UniformRange with_normals, depth_only[DepthPrepareRects::kMaxDepthOnly];
};

class DepthPreparePass {
public:
    // Texels an invocation covers on each axis: a block on CPU rasterisers (depth_prepare.comp), else one.
    static int block(const PassEnv& env) { return env.cpu_renderer ? OBSCURA_DEPTH_PREPARE_CPU_BLOCK : 1; }
    // Compiles the variants for this input kind (host depth kind and normal source) if they are not built yet.
    Error prepare(const PassEnv& env, const FrameInput& input);
    // `rects`: depth_prepare_rects(whole, where the method reads normals, block(env)).
    void run(const PassEnv& env, const FrameInput& input, const DepthPrepareRects& rects,
             const DepthPrepareUniforms& uniforms, FrameResources& resources);

private:
    gl::Object& program_for(const FrameInput& input) {
        return programs_[host_depth_variant(input)][input.normal_mode];
    }
    // {hardware, linear} x {single-sample, multisample}, by OBSCURA_NORMALS_* (reconstructed, signed, unsigned).
    gl::Object programs_[4][3];
    gl::Object depth_only_programs_[4];  // the linear depth alone, by the host depth's kind
};

}  // namespace obscura

#endif  // OBSCURA_DEPTH_PREPARE_H
