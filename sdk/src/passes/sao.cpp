#include "passes/sao.h"

#include <cmath>
#include <cstdio>

#include "math_constants.h"

namespace obscura {

int default_spiral_turns(int samples) {
    if (samples <= 2) return 1;
    auto coprime = [samples](int t) {
        int a = samples, b = t;
        while (b != 0) {
            int r = a % b;
            a = b;
            b = r;
        }
        return a == 1;
    };
    // Nearest to 7s/9 (the paper's ratio), the larger on a tie; 1 is coprime with everything.
    const double target = 7.0 * samples / 9.0;
    int best = 1;
    for (int t = 1; t < samples; ++t) {
        if (!coprime(t)) continue;
        if (std::fabs(t - target) <= std::fabs(best - target)) best = t;
    }
    return best;
}

SpiralTap spiral_tap(int i, int samples, int turns) {
    const double alpha = (double(i) + 0.5) / double(samples);
    // Reduced to one turn here in double precision: the shader only rotates it.
    double turns_done = alpha * double(turns);
    turns_done -= std::floor(turns_done);
    return SpiralTap{float(alpha), float(kTwoPi * turns_done)};
}

float spiral_rotation(int x, int y) {
    const uint32_t ux = uint32_t(x), uy = uint32_t(y);
    const double n = double((30u * ux) ^ uy) + double(10u * ux * uy);
    const double turns = n * (1.0 / kTwoPi);
    return float((turns - std::floor(turns)) * kTwoPi);
}

Error SaoPass::prepare(const PassEnv& env, const obscura_sao_settings& settings) {
    const int filter = settings.mip_filter;
    if (filter < OBSCURA_MIP_FILTER_ROTATED_GRID || filter > kMaxFilter) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "SAO's mip_filter %d is not an OBSCURA_MIP_FILTER_*", filter);
    }
    gl::Object& built = programs_[filter];
    if (built) return Error();
    char defines[64];
    std::snprintf(defines, sizeof defines, "OBSCURA_SAO_MIP_FILTER %d\n", filter);
    return env.build("sao.comp", defines, &built);
}

int SaoPass::wanted_levels(const obscura_sao_settings& settings) {
    if (settings.mip != OBSCURA_TOGGLE_ON) return 1;
    // The outermost tap sits at alpha = (s - 0.5) / s of the capped screen radius.
    const double outermost = double(settings.max_radius_pixels) * (settings.samples - 0.5) / settings.samples;
    int msb = 0;
    for (int h = int(outermost); h > 1; h >>= 1) ++msb;
    int deepest = msb - settings.log_q;
    return deepest > 0 ? deepest + 1 : 1;
}

SaoConstants SaoPass::constants(const obscura_sao_settings& settings, const FrameInput& input, int deepest_level) {
    const float m2v = input.meters_to_view_units;
    const float r = settings.radius * m2v;
    SaoConstants c = {};
    c.ball[0] = r;
    c.ball[1] = r * r;
    // sigma and epsilon are relative to r: the estimator's sum has units of 1/length.
    c.ball[2] = 2.0f * settings.intensity * r / float(settings.samples);
    c.ball[3] = settings.epsilon * r * r;
    c.shaping[0] = settings.bias;
    c.shaping[1] = settings.contrast;
    c.shaping[2] = settings.max_radius_pixels;
    const float depth_range = settings.blur_depth_range * m2v;
    c.shaping[3] = settings.blur_sharpness / depth_range;
    c.packing[0] = 1.0f / depth_range;
    // The key counts from the eye (perspective) or from the near plane (orthographic: the eye plane may sit anywhere
    // behind it, 1000 units back the whole view lay past the range and the blur stopped at no edge).
    if (!input.projection.perspective) {
        const double near_window_depth = input.projection.reversed_z ? 1.0 : 0.0;
        c.packing[1] = float(-view_z_from_window_depth(input.projection, near_window_depth));
    }
    // (The MIP filter is compiled in: SaoPass::prepare.)
    c.config[0] = settings.samples;
    c.config[1] = settings.log_q;
    c.config[2] = deepest_level;
    c.config[3] = settings.quad_filter == OBSCURA_TOGGLE_ON ? 1 : 0;
    for (int i = 0; i < settings.samples && i < OBSCURA_SAO_MAX_SAMPLES; ++i) {
        SpiralTap tap = spiral_tap(i, settings.samples, settings.turns);
        c.taps[i][0] = std::cos(tap.angle);
        c.taps[i][1] = std::sin(tap.angle);
        c.taps[i][2] = tap.alpha;
    }
    return c;
}

void SaoPass::run(const PassEnv& env, const obscura_sao_settings& settings, const UniformRange& frame,
                  const UniformRange& pass, const Region& region, const FrameResources& resources,
                  const gl::Texture2D& packed_ao) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(programs_[settings.mip_filter].name());
    env.bind_texture_mipmapped(OBSCURA_UNIT_LINEAR_DEPTH, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, packed_ao.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    env.dispatch(region.width, region.height, OBSCURA_SAO_GROUP_X, OBSCURA_SAO_GROUP_Y);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

int SaoBlurPass::run_length(const PassEnv& env) {
    return env.cpu_renderer ? OBSCURA_SAO_BLUR_RUN_CPU : OBSCURA_SAO_BLUR_RUN_GPU;
}

Error SaoBlurPass::prepare(const PassEnv& env, int radius, const TargetWrite& target) {
    if (radius < 1 || radius > kMaxRadius) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "SAO blur radius %d is outside [1, %d]", radius, kMaxRadius);
    }
    for (int final = 0; final < 2; ++final) {
        gl::Object& program = programs_[radius][final];
        if (program) continue;
        char defines[160];
        std::snprintf(defines, sizeof defines,
                      "FINAL_OUTPUT %d\nOBSCURA_SAO_BLUR_RADIUS %d\nOBSCURA_SAO_BLUR_RUN %d\nOBSCURA_SAO_BLUR_TARGET 0\n",
                      final, radius, run_length(env));
        Error error = env.build("sao_blur.comp", defines, &program);
        if (error) return error;
    }
    target_ = target;
    if (target.format == 0) return Error();
    char defines[160];
    std::snprintf(defines, sizeof defines,
                  "FINAL_OUTPUT 1\nOBSCURA_SAO_BLUR_RADIUS %d\nOBSCURA_SAO_BLUR_RUN %d\nOBSCURA_SAO_BLUR_TARGET 1\n",
                  radius, run_length(env));
    return target_variant(env, "sao_blur.comp", defines, target, &target_programs_, &target_program_);
}

SaoBlurConstants SaoBlurPass::constants(const obscura_sao_settings& settings, int axis_x, int axis_y) {
    SaoBlurConstants c = {};
    // sigma = (R + 1) / 2 taps, as the HBAO blur: the outermost tap weighs exp(-2 R^2 / (R + 1)^2), 0.32 at the
    // default R = 3 (e^-2 only for large R).
    const float sigma = 0.5f * float(settings.blur_radius + 1);
    c.params[0] = settings.blur_sharpness;
    c.params[1] = 1.0f / (2.0f * sigma * sigma);
    c.config[1] = settings.blur_stride;
    c.config[2] = axis_x;
    c.config[3] = axis_y;
    return c;
}

void SaoBlurPass::run(const PassEnv& env, const obscura_sao_settings& settings, const UniformRange& frame,
                      const UniformRange& pass, const Region& region, const gl::Texture2D& source,
                      const gl::Texture2D& destination, bool final) const {
    env.gl.UseProgram(programs_[settings.blur_radius][final ? 1 : 0].name());
    env.gl.BindImageTexture(OBSCURA_IMAGE_OUT0, destination.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                            final ? GL_R16F : GL_RGBA8);
    dispatch(env, settings, frame, pass, region, source, final);
}

void SaoBlurPass::run_into_target(const PassEnv& env, const obscura_sao_settings& settings, const UniformRange& frame,
                                  const UniformRange& pass, const Region& region, const gl::Texture2D& source,
                                  GLuint target_texture) const {
    env.gl.UseProgram(target_program_);
    bind_target_image(env.gl, OBSCURA_IMAGE_OUT0, target_texture, target_);
    dispatch(env, settings, frame, pass, region, source, true);
}

void SaoBlurPass::dispatch(const PassEnv& env, const obscura_sao_settings& settings, const UniformRange& frame,
                           const UniformRange& pass, const Region& region, const gl::Texture2D& source,
                           bool final) const {
    const gl::Table& gl = env.gl;
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    // Along the axis, one invocation per residue (mod the stride) of each block of run x stride pixels.
    const int run = run_length(env), stride = settings.blur_stride;
    const bool along_x = !final;
    const int extent = along_x ? region.width : region.height;
    const int invocations = (extent + run * stride - 1) / (run * stride) * stride;
    env.dispatch(along_x ? invocations : region.width, along_x ? region.height : invocations, OBSCURA_BLUR_GROUP_X,
                 OBSCURA_BLUR_GROUP_Y);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
