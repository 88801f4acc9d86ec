#include "passes/lsao.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <new>

#include "falloff.h"

namespace obscura {
namespace {

// One RGBA32UI texel of common/lsao.glsl's line records.
struct GpuLine {
    float origin[2];
    uint32_t steps;       // first step (signed) in the low 16 bits, step count in the high 16
    int32_t value_base;   // values index of sample j = 0
};
static_assert(sizeof(GpuLine) == 16, "one RGBA32UI texel");

}  // namespace

LsaoDirections lsao_directions(const obscura_lsao_settings& settings, int phase, const AllocatorCallbacks& alloc) {
    if (settings.pattern == 1) {
        const int n = settings.directions / 8;
        return aligned_directions(n, aligned_step_multiple(n, settings.step_length), alloc);
    }
    return free_directions(settings.directions, settings.step_length, layout_phase_fraction(phase), alloc);
}

int lsao_segment_steps(const obscura_lsao_settings& settings, bool cpu_renderer) {
    if (settings.segment_steps < 0) return 0;
    if (settings.segment_steps == 0) return cpu_renderer ? 0 : kLsaoGpuSegmentSteps;
    return settings.segment_steps;
}

double lsao_warmup_distance(const obscura_lsao_settings& settings, float meters_to_view_units) {
    // An occluder at distance d casts at most A rho(d), A = 1 - sin t the widest gap between sin h and the
    // tangent (2 when receivers' own tangents take part). Solve A (r(1+C)/(r+d^2) - C) = tolerance for d.
    const double m2v = meters_to_view_units;
    const double r = double(settings.decay_rate) * m2v * m2v;
    const double c = settings.falloff == OBSCURA_FALLOFF_RHO0 ? double(settings.falloff_c) : 0.0;
    const double a = settings.tangent_strategy == 3 ? 1.0 - double(settings.tangent) : 2.0;
    return std::sqrt(std::max(0.0, rho0_distance_sq(r, c, double(settings.warmup_tolerance) / a)));
}

Error LsaoPass::program_for(const PassEnv& env, const char* shader, const gl::DefineLines& defines,
                            VariantCache* cache, GLuint* program) {
    return cache->get(defines, [&](gl::Object* built) { return env.build(shader, defines.text, built); }, program);
}

int lsao_gather_margin(const obscura_lsao_settings& settings) {
    // A pixel's nearest sample of a direction lies within half a step along the lines and half a spacing
    // across them, plus up to half a texel diagonal where aligned samples snap to texel centres.
    const int n = settings.directions / 8;
    const double longest_step = settings.pattern == 1 ? aligned_step_multiple(n, settings.step_length) * n * std::sqrt(2.0)
                                                      : double(settings.step_length);
    const double reach = 0.5 * std::hypot(longest_step, double(settings.line_spacing)) + 0.5 * std::sqrt(2.0);
    return std::clamp(int(std::ceil(reach)), 1, kLsaoMaxGatherMargin);
}

Error LsaoPass::prepare(const PassEnv& env, const obscura_lsao_settings& settings, const TargetWrite& target) {
    const int aligned = settings.pattern == 1 ? 1 : 0;
    const int cpu = env.cpu_renderer ? 1 : 0;
    gl::DefineLines defines;
    std::snprintf(defines.text, sizeof defines.text,
                  "OBSCURA_LSAO_ALIGNED %d\nOBSCURA_LSAO_HULL_CAPACITY %d\nOBSCURA_LSAO_EXACT_SWEEP %d\n"
                  "OBSCURA_LSAO_TANGENT_STRATEGY %d\nOBSCURA_CPU_RASTERISER %d\nOBSCURA_LSAO_SEGMENTS %d\n",
                  aligned, settings.hull_capacity, settings.exact == OBSCURA_TOGGLE_ON ? 1 : 0,
                  settings.tangent_strategy, cpu, lsao_segment_steps(settings, env.cpu_renderer) > 0 ? 1 : 0);
    Error error = program_for(env, "line_sweep.comp", defines, &sweep_variants_, &sweep_program_);
    if (error) return error;
    gather_group_[0] = cpu ? OBSCURA_LSAO_GATHER_GROUP_X : OBSCURA_LSAO_GPU_GATHER_GROUP;
    gather_group_[1] = cpu ? OBSCURA_LSAO_GATHER_GROUP_Y : OBSCURA_LSAO_GPU_GATHER_GROUP;
    target_ = target;
    // A frame runs one gather: into resources.ao, or with a target into the target's image.
    char gather_defines[384];
    std::snprintf(gather_defines, sizeof gather_defines,
                  "OBSCURA_LSAO_ALIGNED %d\nOBSCURA_LSAO_NORMAL_TEST %d\nOBSCURA_CPU_RASTERISER %d\n"
                  "OBSCURA_LSAO_DIRECTIONS %d\nOBSCURA_LSAO_GATHER_MARGIN %d\nOBSCURA_LSAO_GATHER_BATCH %d\n"
                  "OBSCURA_LSAO_TANGENT_STRATEGY %d\nOBSCURA_LSAO_GATHER_TARGET %d\n",
                  aligned, settings.normal_test == OBSCURA_TOGGLE_ON ? 1 : 0, cpu, settings.directions,
                  lsao_gather_margin(settings), cpu ? 1 : std::min(settings.directions, kLsaoGatherBatch),
                  settings.tangent_strategy, target.format != 0 ? 1 : 0);
    return target_variant(env, "lsao_gather.comp", gather_defines, target, &gather_variants_,
                          target.format != 0 ? &gather_target_program_ : &gather_program_);
}

Error LsaoPass::ensure_layout(const PassEnv& env, const obscura_lsao_settings& settings, int width, int height,
                              uint32_t frame_index) {
    // Every frame asks: compare what the layouts depend on before building anything.
    const LayoutKey key{width,      height, settings.pattern, settings.directions, settings.step_length,
                        settings.line_spacing, env.cpu_renderer};
    if (!(key == key_)) release();
    key_ = key;
    const int phase = layout_phase(frame_index);
    if (phases_[phase].lines.name() == 0) {
        Error error;
        try {
            error = build_phase(env, settings, phase);
        } catch (const std::bad_alloc&) {  // the layout's memory: HostAllocator throws when the host's allocator fails
            error = Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "building LSAO's %dx%d layout: the host allocator returned NULL",
                                width, height);
        }
        if (error) {
            release();
            return error;
        }
    }
    current_ = phase;
    return Error();
}

LsaoLayout lsao_layout(const obscura_lsao_settings& settings, int width, int height, int phase,
                       const AllocatorCallbacks& alloc) {
    return make_lsao_layout(lsao_directions(settings, phase, alloc), settings.line_spacing, width, height,
                            settings.pattern == 1, layout_phase_fraction(phase), alloc);
}

Error LsaoPass::build_phase(const PassEnv& env, const obscura_lsao_settings& settings, int phase) {
    const int width = key_.width, height = key_.height;
    Phase& built = phases_[phase];
    built.layout = lsao_layout(settings, width, height, phase, env.alloc);
    const gl::Table& gl = env.gl;
    // The sweep writes the values as one storage block, whose size GL bounds (at least 16 MiB in 4.3; 2 GiB
    // on NVIDIA's driver, 128 MiB on llvmpipe, where K = 16 at 1920x1080 + 10 % takes 24 MiB). CPU
    // rasterisers' gathers also read them as a buffer texture, which GL bounds in texels (at least 65536;
    // 2^27 on llvmpipe). GPUs read storage buffers and create no buffer textures.
    const long long values = static_cast<long long>(built.layout.values);
    GLint64 max_block_bytes = 0;
    gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
    GLint max_texels = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    // The line records and the sweeps index the values with 32-bit integers (LsaoLine::offset, GpuLine::value_base),
    // whatever a driver's storage block allows (NVIDIA reports more than 4 GiB).
    if (values > INT32_MAX) {
        return Error::make(OBSCURA_STATUS_INVALID_SIZE,
                           "LSAO at %dx%d needs %lld sweep values, past 32-bit indices: use fewer directions or larger "
                           "step_length / line_spacing",
                           width, height, values);
    }
    const bool over_block = values * 2 + 4 > max_block_bytes;
    if (over_block || (env.cpu_renderer && values + 2 > max_texels)) {
        return Error::make(OBSCURA_STATUS_INVALID_SIZE,
                           "LSAO at %dx%d needs %lld sweep values, over %s (%lld): use fewer directions or larger "
                           "step_length / line_spacing",
                           width, height, values,
                           over_block ? "GL_MAX_SHADER_STORAGE_BLOCK_SIZE bytes" : "GL_MAX_TEXTURE_BUFFER_SIZE texels",
                           over_block ? static_cast<long long>(max_block_bytes) : static_cast<long long>(max_texels));
    }
    HostVector<GpuLine> lines(built.layout.lines.size(), GpuLine{}, HostAllocator<GpuLine>(&env.alloc));
    for (size_t i = 0; i < lines.size(); ++i) {
        const LsaoLine& l = built.layout.lines[i];
        // A line's origin is near the texture's centre: |first step| is at most half its diagonal in steps.
        if (l.first_step < -32768 || l.first_step > 32767 || l.steps > 65535) {
            return Error::make(OBSCURA_STATUS_INVALID_SIZE,
                               "LSAO at %dx%d has lines of over 65535 steps: use a larger step_length", width, height);
        }
        const uint32_t packed = (uint32_t(l.first_step) & 0xffffu) | (uint32_t(l.steps) << 16);
        lines[i] = GpuLine{{l.origin[0], l.origin[1]}, packed, l.offset - l.first_step};
    }
    // Created and filled through the storage-buffer target, whose generic binding the StateGuard restores.
    built.lines = gl::Buffer::create(gl, GL_SHADER_STORAGE_BUFFER, lines.size() * sizeof(GpuLine));
    // The phases share the values: the buffer grows to the largest phase's (their counts differ by a few lines).
    const uint64_t value_bytes = uint64_t(built.layout.values) * 2 + 4;
    if (values_.bytes() < value_bytes) {
        values_texture_ = gl::Object();
        values_ = gl::Buffer::create(gl, GL_SHADER_STORAGE_BUFFER, value_bytes);
    }
    if (!stats_.name()) stats_ = gl::Buffer::create(gl, GL_SHADER_STORAGE_BUFFER, 16);
    if (env.cpu_renderer && built.lines.name() && values_.name()) {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_LSAO_LINES));  // a unit the StateGuard restores
        built.lines_texture = gl::create_buffer_texture(gl, GL_RGBA32UI, built.lines.name());
        if (!values_texture_) values_texture_ = gl::create_buffer_texture(gl, GL_R16F, values_.name());
    }
    const bool textures_ok = !env.cpu_renderer || (built.lines_texture && values_texture_);
    if (!built.lines.name() || !values_.name() || !textures_ok || !stats_.name()) {
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating LSAO's line buffers (%lld values) failed", values);
    }
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, built.lines.name());
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(lines.size() * sizeof(GpuLine)), lines.data());
    return Error();
}

uint64_t LsaoPass::bytes() const {
    uint64_t total = values_.bytes() + stats_.bytes();
    for (const Phase& phase : phases_) total += phase.lines.bytes();
    return total;
}

void LsaoPass::release() {
    for (Phase& phase : phases_) phase = Phase();
    current_ = 0;
    values_texture_ = gl::Object();
    values_ = gl::Buffer();
    stats_ = gl::Buffer();
    key_ = LayoutKey();
}

LsaoConstants LsaoPass::constants(const obscura_lsao_settings& settings, const FrameInput& input,
                                  bool cpu_renderer) const {
    const float m2v = input.meters_to_view_units;
    const LsaoLayout& layout = phases_[current_].layout;
    LsaoConstants c = {};
    c.falloff[0] = settings.decay_rate * m2v * m2v;
    c.falloff[1] = settings.falloff == OBSCURA_FALLOFF_RHO0 ? settings.falloff_c : 0.0f;
    c.falloff[2] = settings.tangent;
    c.falloff[3] = settings.line_spacing;
    c.gather[0] = settings.depth_threshold;
    c.gather[1] = settings.normal_threshold;
    c.gather[2] = settings.intensity;
    c.gather[3] = settings.power;
    c.config[0] = int32_t(layout.directions.size());
    c.config[3] = collect_stats_ ? OBSCURA_LSAO_FLAG_STATS : 0;
    c.sweep[0] = settings.warmup_stride;
    c.sweep[1] = lsao_segment_steps(settings, cpu_renderer);
    c.warmup[0] = float(lsao_warmup_distance(settings, m2v));
    for (size_t k = 0; k < layout.directions.size() && k < OBSCURA_LSAO_MAX_DIRECTIONS; ++k) {
        const LsaoDirection& d = layout.directions[k];
        const LsaoDirectionLines& lines = layout.direction_lines[k];
        c.directions[k][0] = float(d.dir[0]);
        c.directions[k][1] = float(d.dir[1]);
        c.directions[k][2] = float(d.step[0]);
        c.directions[k][3] = float(d.step[1]);
        c.coverage[k][0] = float(d.weight);
        c.coverage[k][1] = float(lines.line_origin_v);
        c.coverage[k][2] = float(lines.first_line);
        c.coverage[k][3] = float(lines.line_count);
        // View-space positions at a fixed clip w are affine in the texel coordinate with these slopes.
        const double ax = d.dir[0] * 2.0 / (double(input.projection.m[0]) * input.width);
        const double ay = d.dir[1] * 2.0 / (double(input.projection.m[5]) * input.height);
        const double length = std::hypot(ax, ay);
        c.axes[k][0] = float(ax / length);
        c.axes[k][1] = float(ay / length);
        c.axes[k][2] = 0.0f;
        c.axes[k][3] = float(1.0 / (d.step[0] * d.step[0] + d.step[1] * d.step[1]));
    }
    return c;
}

void LsaoPass::run_sweeps(const PassEnv& env, const obscura_lsao_settings& settings, const UniformRange& frame,
                          const UniformRange& pass, FrameResources& resources) {
    const gl::Table& gl = env.gl;
    const Phase& phase = phases_[current_];
    const uint32_t zero[4] = {0, 0, 0, 0};
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, stats_.name());
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
    gl.UseProgram(sweep_program_);
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    if (phase.lines_texture) env.bind_texture(OBSCURA_UNIT_LSAO_LINES, GL_TEXTURE_BUFFER, phase.lines_texture.name());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_LSAO_LINES, phase.lines.name());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_LSAO_VALUES, values_.name());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_LSAO_STATS, stats_.name());
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    const int segment_steps = lsao_segment_steps(settings, env.cpu_renderer);
    const int segments = segment_steps > 0 ? (phase.layout.longest_line + segment_steps - 1) / segment_steps : 1;
    // Groups of OBSCURA_LSAO_SWEEP_GROUP lines of one direction (z), one segment each (y).
    int most_lines = 0;
    for (const LsaoDirectionLines& d : phase.layout.direction_lines) most_lines = std::max(most_lines, d.line_count);
    gl.DispatchCompute(GLuint((most_lines + OBSCURA_LSAO_SWEEP_GROUP - 1) / OBSCURA_LSAO_SWEEP_GROUP),
                       GLuint(std::max(segments, 1)), GLuint(phase.layout.directions.size()));
    // The gather reads the values as texels (CPU rasterisers) or from the buffer; read_values and the stats
    // read the buffers back.
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void LsaoPass::run_gather(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                          const Region& region, const FrameResources& resources) const {
    env.gl.UseProgram(gather_program_);
    env.gl.BindImageTexture(OBSCURA_IMAGE_OUT0, resources.ao.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    dispatch_gather(env, frame, pass, region, resources);
}

void LsaoPass::run_gather_into_target(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                                      const Region& region, const FrameResources& resources,
                                      GLuint target_texture) const {
    env.gl.UseProgram(gather_target_program_);
    bind_target_image(env.gl, OBSCURA_IMAGE_OUT0, target_texture, target_);
    dispatch_gather(env, frame, pass, region, resources);
}

void LsaoPass::dispatch_gather(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                               const Region& region, const FrameResources& resources) const {
    const gl::Table& gl = env.gl;
    const Phase& phase = phases_[current_];
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    if (phase.lines_texture) {  // CPU rasterisers
        env.bind_texture(OBSCURA_UNIT_LSAO_LINES, GL_TEXTURE_BUFFER, phase.lines_texture.name());
        env.bind_texture(OBSCURA_UNIT_LSAO_VALUES, GL_TEXTURE_BUFFER, values_texture_.name());
    }
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_LSAO_LINES, phase.lines.name());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_LSAO_VALUES, values_.name());
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    env.dispatch(region.width, region.height, gather_group_[0], gather_group_[1]);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
