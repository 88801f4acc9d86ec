// DepthPrepare: host depth (any projection, MSAA sample 0, or linear) -> linear view depth + view-space
// normals for the whole depth texture. Shared by every method. Shader: sdk/glsl/depth_prepare.comp.
#ifndef OBSCURA_DEPTH_PREPARE_H
#define OBSCURA_DEPTH_PREPARE_H

#include "frame_input.h"
#include "passes/pass_common.h"

namespace obscura {

class DepthPreparePass {
public:
    // Compiles the variant for this input kind if it is not built yet.
    Error prepare(const PassEnv& env, const FrameInput& input);
    void run(const PassEnv& env, const FrameInput& input, const UniformRange& frame, FrameResources& resources);

private:
    gl::Object& program_for(const FrameInput& input) {
        return programs_[(input.depth_linear ? 2 : 0) + (input.depth_multisample ? 1 : 0)];
    }
    gl::Object programs_[4];  // {hardware, linear} x {single-sample, multisample}
};

}  // namespace obscura

#endif  // OBSCURA_DEPTH_PREPARE_H
