// SAO's hierarchical z (sdk/glsl/z_pyramid.comp): MIP levels 1..n of the linear-depth texture, level 0
// being the depth preparation's output. Up to six levels per dispatch.
#ifndef OBSCURA_Z_PYRAMID_H
#define OBSCURA_Z_PYRAMID_H

#include "passes/pass_common.h"

namespace obscura {

class ZPyramidPass {
public:
    // Builds the program of `filter` (OBSCURA_MIP_FILTER_*, compiled in: CPU rasterisers would otherwise run every
    // filter's arithmetic for each texel) on first use: hosts that never render a pyramid never compile it.
    Error prepare(const PassEnv& env, int filter);
    // Levels a texture of this size can hold when the deepest level still has a source two texels wide on
    // both axes, capped at `wanted` (counting level 0).
    static int level_count(int width, int height, int wanted);
    // The uniform blocks of the dispatches that build levels 1..levels-1: push each, then run with them.
    static int dispatch_count(int levels);
    static ZPyramidConstants constants(int dispatch, int levels);
    // Builds levels 1..depth.levels()-1 from level 0 with `filter` (prepared), one dispatch per `passes` entry.
    void run(const PassEnv& env, int filter, const UniformRange* passes, int pass_count, const gl::Texture2D& depth);

private:
    static constexpr int kFilters = OBSCURA_MIP_FILTER_HARMONIC_MEAN_OF_GEOMETRY + 1;  // indexed by the filter
    gl::Object programs_[kFilters];
};

}  // namespace obscura

#endif  // OBSCURA_Z_PYRAMID_H
