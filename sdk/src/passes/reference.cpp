#include "passes/reference.h"

#include <cmath>

#include "falloff.h"

namespace obscura {
namespace {
// Locations of `u_batch` and `u_tile` in reference.comp.
constexpr GLint kBatchLocation = 0, kTileLocation = 1;
// The longest ray of falloffs that never reach zero: rays end where they leave the depth buffer.
constexpr float kUnboundedRay = 1e20f;
}  // namespace

Error ReferencePass::prepare(const PassEnv& env) {
    if (program_) return Error();
    return env.build("reference.comp", "", &program_);
}

ReferenceConstants ReferencePass::constants(const obscura_reference_settings& settings, const FrameInput& input) {
    const float m2v = input.meters_to_view_units;
    ReferenceConstants c = {};
    const float r = settings.decay_rate * m2v * m2v;  // r is in m^2; the shader works in view units
    const float radius = settings.radius * m2v;
    c.falloff[0] = r;
    c.falloff[1] = settings.falloff_c;
    c.falloff[2] = radius;
    switch (settings.falloff) {
        case OBSCURA_FALLOFF_RHO0: c.falloff[3] = rho0_reach(r, settings.falloff_c); break;
        case OBSCURA_FALLOFF_TABLE: c.falloff[3] = radius; break;
        default: c.falloff[3] = kUnboundedRay; break;
    }
    c.params[0] = settings.thickness * m2v;
    c.params[1] = 1.0f / float(settings.rays);
    c.config[0] = settings.falloff;
    c.config[1] = settings.rays;
    for (int i = 0; i < OBSCURA_FALLOFF_TABLE_SIZE; ++i) c.table[i / 4][i % 4] = settings.falloff_table[i];
    return c;
}

void ReferencePass::bind(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                         const FrameResources& resources, const gl::Texture2D& accumulator) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(program_.name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, accumulator.name(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
}

void ReferencePass::dispatch_tile(const PassEnv& env, const Region& region, const Region& tile, uint32_t first_ray,
                                  int count, bool first, bool last, bool batch_done) {
    const gl::Table& gl = env.gl;
    // The first ray's index as the int's bits: the shader reads it back as a uint (the sequence wraps modulo 2^32).
    gl.Uniform4i(kBatchLocation, int32_t(first_ray), count, first ? 1 : 0, last ? 1 : 0);
    gl.Uniform2i(kTileLocation, tile.x - region.x, tile.y - region.y);
    env.dispatch(tile.width, tile.height, OBSCURA_REFERENCE_GROUP_X, OBSCURA_REFERENCE_GROUP_Y);
    // The next batch reads what this one accumulated; after the last, the composite samples it.
    if (batch_done) gl.MemoryBarrier(last ? GL_TEXTURE_FETCH_BARRIER_BIT : GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace obscura
