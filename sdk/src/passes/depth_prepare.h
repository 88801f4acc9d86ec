// DepthPrepare: host depth (any projection, MSAA sample 0, or linear) -> linear view depth + view-space
// normals for the whole depth texture. Shared by every method. Shader: sdk/glsl/depth_prepare.comp.
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

class DepthPreparePass {
public:
    // Compiles the variant for this input kind (host depth kind and normal source) if it is not built yet.
    Error prepare(const PassEnv& env, const FrameInput& input);
    void run(const PassEnv& env, const FrameInput& input, const UniformRange& frame, FrameResources& resources);

private:
    gl::Object& program_for(const FrameInput& input) {
        return programs_[host_depth_variant(input)][input.normal_mode];
    }
    // {hardware, linear} x {single-sample, multisample}, by OBSCURA_NORMALS_* (reconstructed, signed, unsigned).
    gl::Object programs_[4][3];
};

}  // namespace obscura

#endif  // OBSCURA_DEPTH_PREPARE_H
