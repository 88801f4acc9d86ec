#include "passes/z_pyramid.h"

#include <cstdio>

namespace obscura {

Error ZPyramidPass::prepare(const PassEnv& env, int filter) {
    if (filter < OBSCURA_MIP_FILTER_ROTATED_GRID || filter >= kFilters) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "z pyramid filter %d is not an OBSCURA_MIP_FILTER_*", filter);
    }
    gl::Object& program = programs_[filter];
    if (program) return Error();
    char defines[96];
    std::snprintf(defines, sizeof defines, "OBSCURA_CPU_RASTERISER %d\nOBSCURA_Z_PYRAMID_FILTER %d\n",
                  env.cpu_renderer ? 1 : 0, filter);
    return env.build("z_pyramid.comp", defines, &program);
}

int ZPyramidPass::level_count(int width, int height, int wanted) {
    int levels = 1;
    int smaller = width < height ? width : height;
    // Level m+1 is built from level m: keep at least two source texels on the short axis.
    while (levels < wanted && (smaller >> (levels - 1)) >= 2) ++levels;
    return levels;
}

int ZPyramidPass::dispatch_count(int levels) {
    const int built = levels - 1;
    return (built + OBSCURA_Z_PYRAMID_LEVELS_PER_DISPATCH - 1) / OBSCURA_Z_PYRAMID_LEVELS_PER_DISPATCH;
}

ZPyramidConstants ZPyramidPass::constants(int dispatch, int levels) {
    ZPyramidConstants c = {};
    const int source = dispatch * OBSCURA_Z_PYRAMID_LEVELS_PER_DISPATCH;
    const int remaining = levels - 1 - source;
    c.config[0] = source;
    c.config[1] = remaining < OBSCURA_Z_PYRAMID_LEVELS_PER_DISPATCH ? remaining : OBSCURA_Z_PYRAMID_LEVELS_PER_DISPATCH;
    return c;
}

void ZPyramidPass::run(const PassEnv& env, int filter, const UniformRange* passes, int pass_count,
                       const gl::Texture2D& depth) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(programs_[filter].name());
    env.bind_texture_mipmapped(OBSCURA_UNIT_LINEAR_DEPTH, depth.name());
    const int last_level = depth.levels() - 1;
    for (int d = 0; d < pass_count; ++d) {
        const int source = d * OBSCURA_Z_PYRAMID_LEVELS_PER_DISPATCH;
        // Every image unit the shader declares gets a level of this texture; those past the last level
        // repeat it and are never stored to (config.y limits the levels written).
        for (int i = 0; i < OBSCURA_Z_PYRAMID_LEVELS_PER_DISPATCH; ++i) {
            int level = source + 1 + i > last_level ? last_level : source + 1 + i;
            gl.BindImageTexture(GLuint(OBSCURA_IMAGE_OUT0 + i), depth.name(), level, GL_FALSE, 0, GL_WRITE_ONLY,
                                GL_R32F);
        }
        env.bind_uniforms(OBSCURA_UBO_PASS, passes[d]);
        int first_w = depth.width() >> (source + 1), first_h = depth.height() >> (source + 1);
        env.dispatch(first_w > 0 ? first_w : 1, first_h > 0 ? first_h : 1, OBSCURA_Z_PYRAMID_TILE,
                     OBSCURA_Z_PYRAMID_TILE);
        // The next dispatch samples what this one stored; after the last, the SAO pass does.
        gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
}

}  // namespace obscura
