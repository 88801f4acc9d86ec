#include "passes/hbao.h"

namespace obscura {

Error HbaoPass::prepare(const PassEnv& env) {
    if (programs_[1]) return Error();
    Error error = env.build("hbao.comp", "OBSCURA_HBAO_ESTIMATOR 1\n", &programs_[0]);
    if (!error) error = env.build("hbao.comp", "OBSCURA_HBAO_ESTIMATOR 2\n", &programs_[1]);
    return error;
}

HbaoConstants HbaoPass::constants(const obscura_hbao_settings& settings, const FrameInput& input) {
    float m2v = input.meters_to_view_units;
    HbaoConstants c = {};
    c.falloff[0] = settings.decay_rate * m2v * m2v;  // r is in m^2; distances reach the shader in view units
    c.falloff[1] = settings.falloff_c;
    c.falloff[2] = settings.radius * m2v;
    c.falloff[3] = settings.max_radius_pixels;
    c.shaping[0] = settings.bias;
    c.shaping[1] = settings.intensity;
    c.shaping[2] = settings.power;
    c.counts[0] = settings.directions;
    c.counts[1] = settings.steps;
    return c;
}

void HbaoPass::run(const PassEnv& env, const obscura_hbao_settings& settings, const UniformRange& frame,
                   const UniformRange& pass, const Region& region, FrameResources& resources) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(programs_[settings.estimator == 2 ? 1 : 0].name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, resources.ao.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    env.dispatch(region.width, region.height, OBSCURA_HBAO_GROUP_X, OBSCURA_HBAO_GROUP_Y);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
