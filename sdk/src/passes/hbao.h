// HBAO: K directions x N steps horizon search per pixel (sdk/glsl/hbao.comp), the baseline every other
// method is measured against.
#ifndef OBSCURA_HBAO_H
#define OBSCURA_HBAO_H

#include "frame_input.h"
#include "passes/pass_common.h"

namespace obscura {

class HbaoPass {
public:
    // Builds one program per estimator on first use (compiled in: CPU rasterisers run both sides of a branch
    // on a uniform).
    Error prepare(const PassEnv& env);
    // Converts resolved settings (metres) to the shader's constants (view units).
    static HbaoConstants constants(const obscura_hbao_settings& settings, const FrameInput& input);
    // Writes visibility into resources.ao over `region` (frame.work_rect must equal it).
    void run(const PassEnv& env, const obscura_hbao_settings& settings, const UniformRange& frame,
             const UniformRange& pass, const Region& region, FrameResources& resources);

private:
    gl::Object programs_[2];  // estimator 1 (horizon split), 2 (largest occluder)
};

}  // namespace obscura

#endif  // OBSCURA_HBAO_H
