#include "passes/bilateral_blur.h"

namespace obscura {

BlurConstants BilateralBlurPass::constants(int radius, float sharpness, int axis_x, int axis_y) {
    BlurConstants c = {};
    // sigma = (radius + 1) / 2 keeps the outermost tap at a weight of about e^-2.
    float sigma = 0.5f * float(radius + 1);
    c.params[0] = sharpness;
    c.params[1] = 1.0f / (2.0f * sigma * sigma);
    c.config[0] = radius;
    c.config[1] = axis_x;
    c.config[2] = axis_y;
    return c;
}

void BilateralBlurPass::run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                            const Region& region, const gl::Texture2D& linear_depth, const gl::Texture2D& source,
                            const gl::Texture2D& destination) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(program_.name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, destination.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    env.dispatch(region.width, region.height, OBSCURA_BLUR_GROUP_X, OBSCURA_BLUR_GROUP_Y);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
