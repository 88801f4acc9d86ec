#include "passes/gtao.h"

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "math_constants.h"

namespace obscura {

GtaoPresetCounts gtao_preset_counts(int preset) {
    static const GtaoPresetCounts kPresets[] = {{1, 2}, {2, 2}, {3, 3}, {9, 3}};  // low, medium, high, ultra
    return kPresets[preset >= 1 && preset <= 4 ? preset - 1 : 2];
}

// The step distribution compiled in: u^2 and u^1.5 without pow's exp2 and log2 (CPU rasterisers evaluate pow as both),
// any other exponent through pow.
int GtaoPass::step_distribution(const obscura_gtao_settings& settings) {
    if (settings.step_power == 2.0f) return 2;
    if (settings.step_power == 1.5f) return 1;
    return 0;
}

uint32_t GtaoPass::variant_key(const obscura_gtao_settings& settings, bool bent_normals) {
    // Resolved settings: slices in [1, 16], steps in [1, 32] (the metadata's ranges).
    return (settings.thickness_mode == OBSCURA_GTAO_MODE_BITMASK ? 1u : 0u) | uint32_t(step_distribution(settings)) << 1 |
           (bent_normals ? 8u : 0u) | uint32_t(settings.slices) << 4 | uint32_t(settings.steps) << 9 |
           (settings.thickness_blend != 0.0f ? 1u << 15 : 0u);
}

Error GtaoPass::prepare(const PassEnv& env, const obscura_gtao_settings& settings, bool bent_normals) {
    GLuint program = 0;
    return programs_.get(variant_key(settings, bent_normals), [&](gl::Object* built) {
        char defines[224];
        std::snprintf(defines, sizeof defines,
                      "OBSCURA_GTAO_MODE %d\nOBSCURA_GTAO_STEP_DISTRIBUTION %d\nOBSCURA_GTAO_BENT_NORMALS %d\n"
                      "OBSCURA_GTAO_SLICES %d\nOBSCURA_GTAO_STEPS %d\nOBSCURA_GTAO_THICKNESS_BLEND %d\n"
                      "OBSCURA_CPU_RASTERISER %d\n",
                      settings.thickness_mode == OBSCURA_GTAO_MODE_BITMASK ? 2 : 1, step_distribution(settings),
                      bent_normals ? 1 : 0, settings.slices, settings.steps, settings.thickness_blend != 0.0f ? 1 : 0,
                      env.cpu_renderer ? 1 : 0);
        return env.build("gtao.comp", defines, built);
    }, &program);
}

int GtaoPass::wanted_levels(const obscura_gtao_settings& settings) {
    if (settings.mip != OBSCURA_TOGGLE_ON) return 1;
    // The farthest step lies at the capped screen radius; it reads level log2(t) - mip_offset.
    const double deepest = std::floor(std::log2(double(settings.max_radius_pixels) + 1.0) - settings.mip_offset);
    return deepest > 0.0 ? int(deepest) + 1 : 1;
}

namespace {

// Frame n's turn of a 4x4 pattern in whole strata: n mod 16 with its 4 bits reversed.
uint32_t stratum_turn(uint64_t n) {
    const uint32_t f = uint32_t(n & 15u);
    return ((f & 1u) << 3) | ((f & 2u) << 1) | ((f & 4u) >> 1) | ((f & 8u) >> 3);
}

}  // namespace

GtaoConstants GtaoPass::constants(const obscura_gtao_settings& settings, const FrameInput& input, int deepest_level) {
    const float m2v = input.meters_to_view_units;
    const float radius = settings.radius * m2v;
    // weight(d) = clamp((radius - d) / (range * radius), 0, 1) = clamp(d * slope + offset).
    const float fade = settings.falloff_range * radius;
    GtaoConstants c = {};
    c.falloff[0] = radius;
    c.falloff[1] = -1.0f / fade;
    c.falloff[2] = radius / fade;
    c.falloff[3] = settings.max_radius_pixels;
    c.thickness[0] = settings.thickness * m2v;
    c.thickness[1] = settings.thickness_blend;
    c.thickness[2] = settings.step_power;
    c.thickness[3] = settings.mip_offset;
    c.shaping[0] = settings.intensity;
    c.shaping[1] = settings.power;
    c.shaping[2] = settings.albedo;
    c.config[2] = settings.sectors;  // (slices and steps are compiled in: GtaoPass::prepare)
    c.config[3] = deepest_level;
    // The frame moves the 4x4 patterns (frame 0 leaves them). With the denoise, whose window holds all 16 strata, it
    // moves each pixel's values inside their strata along an R2 sequence (and the bitmask's draws with the jitter):
    // every pixel keeps its stratum, so edges, where the denoise's window is cut, keep their values from frame to
    // frame. Without it the frames alone must cover the strata: the patterns turn as a whole, by whole strata in
    // bit-reversed order (each aligned run of 2^k frames spreads over the 16) plus the same R2 step inside them, and the
    // draws by an offset of their own. Every window still holds 16 evenly spaced values. (Turning whole strata with
    // the denoise as well flickered 8-17 % more on a moving camera: docs/quality.md.)
    const uint64_t frame = uint64_t(uint32_t(settings.frame_index)) + uint64_t(input.frame_index);
    const double rotation = 0.5 + double(frame) * 0.7548776662466927, jitter = 0.5 + double(frame) * 0.5698402909980532;
    const double inside_rotation = rotation - std::floor(rotation) - 0.5, inside_jitter = jitter - std::floor(jitter) - 0.5;
    if (settings.denoise == OBSCURA_TOGGLE_ON) {
        c.noise[0] = float(inside_rotation / 16.0);
        c.noise[1] = float(inside_jitter / 16.0);
        c.noise[2] = float(7.0 * inside_jitter / 16.0);
    } else {
        const double draws = double(frame) * 0.5497004779019703;
        c.noise[0] = float((double(stratum_turn(frame)) + inside_rotation) / 16.0);
        c.noise[1] = float((double(stratum_turn(frame * 7u)) + inside_jitter) / 16.0);
        c.noise[2] = float(draws - std::floor(draws));
    }
    c.rotation[0] = float(std::cos(kPi / settings.slices));
    c.rotation[1] = float(std::sin(kPi / settings.slices));
    c.rotation[2] = float(std::exp2(-double(settings.mip_offset)));
    return c;
}

void GtaoPass::run(const PassEnv& env, const obscura_gtao_settings& settings, bool bent_normals,
                   const UniformRange& frame, const UniformRange& pass, const Region& region,
                   const FrameResources& resources, const gl::Texture2D& destination) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(programs_.find(variant_key(settings, bent_normals)));
    env.bind_texture_mipmapped(OBSCURA_UNIT_LINEAR_DEPTH, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, destination.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                        bent_normals ? GL_RGBA16F : GL_R16F);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    env.dispatch(region.width, region.height, OBSCURA_GTAO_GROUP_X, OBSCURA_GTAO_GROUP_Y);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

int GtaoDenoisePass::run_length(const PassEnv& env) {
    return env.cpu_renderer ? OBSCURA_GTAO_DENOISE_RUN_CPU : OBSCURA_GTAO_DENOISE_RUN_GPU;
}

Error GtaoDenoisePass::prepare(const PassEnv& env, bool bent_normals, const TargetWrite& target) {
    for (int final = 0; final < 2; ++final) {
        gl::Object& program = programs_[bent_normals ? 1 : 0][final];
        if (program) continue;
        char defines[160];
        std::snprintf(defines, sizeof defines,
                      "OBSCURA_GTAO_BENT_NORMALS %d\nOBSCURA_GTAO_DENOISE_FINAL %d\nOBSCURA_GTAO_DENOISE_RUN %d\n"
                      "OBSCURA_GTAO_DENOISE_TARGET 0\n",
                      bent_normals ? 1 : 0, final, run_length(env));
        Error error = env.build("gtao_denoise.comp", defines, &program);
        if (error) return error;
    }
    target_ = target;
    if (target.format == 0) return Error();
    char defines[160];
    std::snprintf(defines, sizeof defines,
                  "OBSCURA_GTAO_BENT_NORMALS %d\nOBSCURA_GTAO_DENOISE_FINAL 1\nOBSCURA_GTAO_DENOISE_RUN %d\n"
                  "OBSCURA_GTAO_DENOISE_TARGET 1\n",
                  bent_normals ? 1 : 0, run_length(env));
    return target_variant(env, "gtao_denoise.comp", defines, target, &target_programs_, &target_program_);
}

GtaoDenoiseConstants GtaoDenoisePass::constants(const obscura_gtao_settings& settings, bool final) {
    GtaoDenoiseConstants c = {};
    c.params[0] = settings.denoise_sharpness;
    c.config[0] = final ? 0 : 1;  // the first pass runs along x, the final one along y
    c.config[1] = final ? 1 : 0;
    return c;
}

void GtaoDenoisePass::run(const PassEnv& env, bool bent_normals, bool final, const UniformRange& frame,
                          const UniformRange& pass, const Region& region, const FrameResources& resources,
                          const gl::Texture2D& source, const gl::Texture2D& destination, const gl::Texture2D* bent) const {
    env.gl.UseProgram(programs_[bent_normals ? 1 : 0][final ? 1 : 0].name());
    const bool rgba = bent_normals && !final;
    env.gl.BindImageTexture(OBSCURA_IMAGE_OUT0, destination.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                            rgba ? GL_RGBA16F : GL_R16F);
    dispatch(env, bent_normals, final, frame, pass, region, resources, source, bent);
}

void GtaoDenoisePass::run_into_target(const PassEnv& env, bool bent_normals, const UniformRange& frame,
                                      const UniformRange& pass, const Region& region, const FrameResources& resources,
                                      const gl::Texture2D& source, GLuint target_texture,
                                      const gl::Texture2D* bent) const {
    env.gl.UseProgram(target_program_);
    bind_target_image(env.gl, OBSCURA_IMAGE_OUT0, target_texture, target_);
    dispatch(env, bent_normals, true, frame, pass, region, resources, source, bent);
}

void GtaoDenoisePass::dispatch(const PassEnv& env, bool bent_normals, bool final, const UniformRange& frame,
                               const UniformRange& pass, const Region& region, const FrameResources& resources,
                               const gl::Texture2D& source, const gl::Texture2D* bent) const {
    const gl::Table& gl = env.gl;
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    if (bent_normals && final && bent) {
        gl.BindImageTexture(OBSCURA_IMAGE_OUT1, bent->name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    }
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    // One invocation per run of pixels along the axis.
    const int run = run_length(env);
    const bool along_x = !final;
    env.dispatch(along_x ? (region.width + run - 1) / run : region.width,
                 along_x ? region.height : (region.height + run - 1) / run, OBSCURA_GTAO_DENOISE_GROUP_X,
                 OBSCURA_GTAO_DENOISE_GROUP_Y);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
