// SAO's hierarchical z (sdk/glsl/z_pyramid.comp): MIP levels 1..n of the linear-depth texture, level 0
// being the depth preparation's output. Up to six levels per dispatch.
#ifndef OBSCURA_Z_PYRAMID_H
#define OBSCURA_Z_PYRAMID_H

#include "passes/pass_common.h"

namespace obscura {

class ZPyramidPass {
public:
    // Builds the program on first use: hosts that never render SAO never compile it.
    Error prepare(const PassEnv& env);
    // Levels a texture of this size can hold when the deepest level still has a source two texels wide on
    // both axes, capped at `wanted` (counting level 0).
    static int level_count(int width, int height, int wanted);
    // The uniform blocks of the dispatches that build levels 1..levels-1: push each, then run with them.
    static int dispatch_count(int levels);
    static ZPyramidConstants constants(int dispatch, int levels, int filter);
    // Builds levels 1..depth.levels()-1 from level 0, one dispatch per `passes` entry.
    void run(const PassEnv& env, const UniformRange* passes, int pass_count, const gl::Texture2D& depth);

private:
    gl::Object program_;
};

}  // namespace obscura

#endif  // OBSCURA_Z_PYRAMID_H
