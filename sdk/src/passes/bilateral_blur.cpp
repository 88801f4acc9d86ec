#include "passes/bilateral_blur.h"

#include <cstdio>

namespace obscura {

int BilateralBlurPass::run_length(const PassEnv& env) {
    return env.cpu_renderer ? OBSCURA_BLUR_RUN_CPU : OBSCURA_BLUR_RUN_GPU;
}

Error BilateralBlurPass::prepare(const PassEnv& env, int radius, const TargetWrite& target) {
    if (radius < 1 || radius > kMaxRadius) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "blur radius %d is outside [1, %d]", radius, kMaxRadius);
    }
    // The x pass and, without a target, the y pass write a texture; with one the y pass writes the target's image.
    for (const int into_target : {0, 1}) {
        if (into_target && target.format == 0) break;
        char defines[96];
        std::snprintf(defines, sizeof defines, "OBSCURA_BLUR_RADIUS %d\nOBSCURA_BLUR_RUN %d\nOBSCURA_BLUR_TARGET %d\n",
                      radius, run_length(env), into_target);
        Error error;
        if (into_target) {
            error = target_variant(env, "bilateral_blur.comp", defines, target, &target_programs_, &target_program_);
        } else if (!programs_[radius]) {
            error = env.build("bilateral_blur.comp", defines, &programs_[radius]);
        }
        if (error) return error;
    }
    program_ = programs_[radius].name();
    target_ = target;
    return Error();
}

BlurConstants BilateralBlurPass::constants(int radius, float sharpness, int axis_x, int axis_y) {
    BlurConstants c = {};
    // sigma = (radius + 1) / 2: the outermost tap weighs exp(-2 R^2 / (R + 1)^2), e^-0.5 at R = 1 and e^-2 only for
    // large R.
    float sigma = 0.5f * float(radius + 1);
    c.params[0] = sharpness;
    c.params[1] = 1.0f / (2.0f * sigma * sigma);
    c.config[1] = axis_x;
    c.config[2] = axis_y;
    return c;
}

void BilateralBlurPass::run(const PassEnv& env, bool along_x, const UniformRange& frame, const UniformRange& pass,
                            const Region& region, const gl::Texture2D& linear_depth, const gl::Texture2D& source,
                            const gl::Texture2D& destination) const {
    env.gl.UseProgram(program_);
    env.gl.BindImageTexture(OBSCURA_IMAGE_OUT0, destination.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    dispatch(env, along_x, frame, pass, region, linear_depth, source);
}

void BilateralBlurPass::run_into_target(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                                        const Region& region, const gl::Texture2D& linear_depth,
                                        const gl::Texture2D& source, GLuint target_texture) const {
    env.gl.UseProgram(target_program_);
    bind_target_image(env.gl, OBSCURA_IMAGE_OUT0, target_texture, target_);
    dispatch(env, false, frame, pass, region, linear_depth, source);
}

void BilateralBlurPass::dispatch(const PassEnv& env, bool along_x, const UniformRange& frame, const UniformRange& pass,
                                 const Region& region, const gl::Texture2D& linear_depth, const gl::Texture2D& source) const {
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    // One invocation per run of pixels along the axis.
    const int run = run_length(env);
    const int width = along_x ? (region.width + run - 1) / run : region.width;
    const int height = along_x ? region.height : (region.height + run - 1) / run;
    env.dispatch(width, height, OBSCURA_BLUR_GROUP_X, OBSCURA_BLUR_GROUP_Y);
    env.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
