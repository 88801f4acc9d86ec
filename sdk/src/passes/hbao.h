// HBAO: K directions x N steps horizon search per pixel (sdk/glsl/hbao.comp), the baseline every other
// method is measured against.
#ifndef OBSCURA_HBAO_H
#define OBSCURA_HBAO_H

#include "frame_input.h"
#include "passes/pass_common.h"

namespace obscura {

class HbaoPass {
public:
    Error create(const PassEnv& env) { return env.build("hbao.comp", "", &program_); }
    // Converts resolved settings (metres) to the shader's constants (view units).
    static HbaoConstants constants(const obscura_hbao_settings& settings, const FrameInput& input);
    // Writes visibility into resources.ao over `region` (frame.work_rect must equal it).
    void run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
             FrameResources& resources);

private:
    gl::Object program_;
};

}  // namespace obscura

#endif  // OBSCURA_HBAO_H
