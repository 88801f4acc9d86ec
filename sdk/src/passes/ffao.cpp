#include "passes/ffao.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>

namespace obscura {
namespace {

constexpr int kTableColumns = OBSCURA_FFAO_TABLE_B * OBSCURA_FFAO_TABLE_C * OBSCURA_FFAO_TABLE_D;
constexpr uint64_t kTableBytes = uint64_t(OBSCURA_FFAO_TABLE_A) * kTableColumns * 4;

// One 16-byte record per line and per column, as common/ffao.glsl reads them.
struct GpuLine {
    float origin[2];
    int32_t first_step, steps;
};
static_assert(sizeof(GpuLine) == 16 && sizeof(FfaoColumn) == 16, "uvec4 records");

}  // namespace

Error FfaoPass::prepare(const PassEnv& env, const obscura_ffao_settings& settings) {
    Error error;
    if (!table_program_) {
        error = env.build("ffao_table.comp", "", &table_program_);
        if (!error) error = env.build("ffao_scan.comp", "", &scan_program_);
        if (!error) error = env.build("ffao_prefix.comp", "", &prefix_program_);
        if (error) {
            table_program_ = gl::Object();
            return error;
        }
    }
    const int mipmap = ffao_uses_mipmap(settings) ? 1 : 0, saao = ffao_uses_saao(settings) ? 1 : 0;
    const int thick = ffao_single_lines(settings) ? 1 : 0;
    for (int chunked = 0; chunked < 2; ++chunked) {  // which one runs depends on the size (ensure_layout)
        gl::Object& program = obscurance_programs_[mipmap][saao][chunked][thick];
        if (program || (mipmap && chunked)) continue;
        char defines[192];
        std::snprintf(defines, sizeof defines,
                      "OBSCURA_FFAO_MIPMAP %d\nOBSCURA_FFAO_SAAO %d\nOBSCURA_FFAO_BUFFER_TEXTURES %d\n"
                      "OBSCURA_FFAO_CHUNKED %d\nOBSCURA_FFAO_FINITE_THICKNESS %d\n",
                      mipmap, saao, env.cpu_renderer ? 1 : 0, chunked, thick);
        error = env.build("ffao_obscurance.comp", defines, &program);
        if (error) return error;
    }
    if (saao && !box_program_) {
        error = env.build("ffao_box_average.comp", "", &box_program_);
        if (!error) error = env.build("ffao_gather.comp", "", &gather_program_);
        if (!error) error = env.build("ffao_saao_blur.comp", "", &blur_program_);
        if (error) {
            box_program_ = gl::Object();
            return error;
        }
    }
    if (!table_) {
        env.gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_FFAO_TABLE));  // a unit the StateGuard restores
        table_ = gl::create_texture_3d(env.gl, GL_R32F, OBSCURA_FFAO_TABLE_A, OBSCURA_FFAO_TABLE_B,
                                       OBSCURA_FFAO_TABLE_C * OBSCURA_FFAO_TABLE_D);
        table_sampler_ = gl::create_sampler_linear_clamp(env.gl);
        table_valid_ = false;
        if (!table_ || !table_sampler_) {
            table_ = gl::Object();
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating FFAO's estimator table failed");
        }
    }
    return Error();
}

Error FfaoPass::ensure_layout(const PassEnv& env, const obscura_ffao_settings& settings, int width, int height,
                              uint32_t frame_index, const Region& obscurance) {
    const LayoutKey key{width, height, settings.sectors, settings.base_interval, !ffao_uses_mipmap(settings),
                        ffao_uses_saao(settings), storage_block_limit_};
    const int phase = layout_phase(frame_index);
    // A refusal for the size is the same every time: answered again without building the layout (at 16384^2 that
    // took about a second on llvmpipe, every frame of a host that keeps asking). For every layout phase: a host that
    // advances frame_index asks for another phase each frame (the phases differ by a line per orientation, so a size
    // refused in one is refused in all but at the very edge of the limit, where answering one way every frame beats
    // AO on one frame in eight).
    if (key == refused_key_) return refused_;
    if (!(key == key_)) {
        release();
        if (key.saao) {
            env.gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE));  // a unit the StateGuard restores
            box_ = gl::Texture2D::create(env.gl, GL_RGBA32F, width, height);
            terms_ = gl::Texture2D::create(env.gl, GL_RG32F, width, height);
            if (!box_ || !terms_) {
                release();
                return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating FFAO's %dx%d SAAO textures failed",
                                   width, height);
            }
        }
        key_ = key;
    }
    if (grids_[phase].layout.width == 0) {
        Error error;
        try {
            error = build_grid(env, settings, phase);
        } catch (const std::bad_alloc&) {
            // The layout's memory (HostAllocator throws when the host's allocator fails). A grid whose layout was
            // assigned before the throw would pass for built: release() below drops it with the rest.
            error = Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "building FFAO's %dx%d layout: the host allocator returned NULL",
                                width, height);
        }
        if (error) {
            if (error.status() == OBSCURA_STATUS_INVALID_SIZE) {
                refused_key_ = key;
                refused_ = error;
            }
            release();
            return error;
        }
    }
    current_ = phase;
    // The running total, chunk to chunk (SAAO carries its sums in its terms): as large as the pixels the obscurance
    // computes, not the guard band around them (FFAO at 4K: 31.6 MiB instead of 45.6).
    // Unchunked (or SAAO, which carries its sums in its terms): no running total needed. One that a chunked phase of
    // this size made is kept: the phases differ by a line per orientation, so at a size on the storage block's edge
    // they alternate between one block and chunks, and the texture was freed and made again every other frame (the
    // memory report moving with it). release() frees it with the size.
    if (!chunked() || key_.saao) return Error();
    int running_width = obscurance.width, running_height = obscurance.height;
    if (running_width <= 0 || running_height <= 0) {
        running_width = running_ ? running_.width() : width;
        running_height = running_ ? running_.height() : height;
    }
    if (!running_ || running_.width() != running_width || running_.height() != running_height) {
        running_ = gl::Texture2D();
        env.gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE));  // a unit the StateGuard restores
        running_ = gl::Texture2D::create(env.gl, GL_R32F, running_width, running_height);
        if (!running_) {
            release();
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating FFAO's %dx%d running sums failed",
                               running_width, running_height);
        }
    }
    return Error();
}

Error FfaoPass::build_grid(const PassEnv& env, const obscura_ffao_settings& settings, int phase) {
    ++layouts_built_;
    const int width = key_.width, height = key_.height;
    Grid& grid = grids_[phase];
    grid.layout =
        make_ffao_layout(settings.sectors, settings.base_interval, width, height, layout_phase_fraction(phase), env.alloc);
    const FfaoLayout& layout = grid.layout;
    const int orientations = int(layout.orientations.size());
    if (!key_.buffers) {  // the mipmap baseline: one chunk of every orientation, no peaks
        grid.chunks[0] = Chunk{0, orientations, 0, 0};
        grid.chunk_count = 1;
        return Error();
    }
    // The columns' offsets are global entry indices, 32-bit in the records and the shaders (a chunk's buffer starts at
    // its first entry, but the indices into it do not): the whole layout must fit them, whatever the blocks allow.
    if (layout.entries > int64_t(INT32_MAX)) {
        return Error::make(OBSCURA_STATUS_INVALID_SIZE,
                           "FFAO at %dx%d needs %lld interval entries, more than 32-bit indices reach (2^31 - 1): use "
                           "fewer sectors, a larger base_interval or a reduced resolution",
                           width, height, static_cast<long long>(layout.entries));
    }
    const gl::Table& gl = env.gl;
    GLint64 max_block_bytes = 0;
    gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
    if (storage_block_limit_ > 0) max_block_bytes = std::min<GLint64>(max_block_bytes, storage_block_limit_);
    // CPU rasterisers' obscurance pass reads the peaks buffer as a buffer texture, which GL bounds in texels.
    GLint max_texels = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    int64_t most_entries = int64_t(max_block_bytes) / 16;
    if (env.cpu_renderer) most_entries = std::min<int64_t>(most_entries, max_texels);
    most_entries = std::min<int64_t>(most_entries, (int64_t(1) << 31) - 1);  // int indices in the shaders
    auto orientation_begin = [&](int k) {
        return int64_t(layout.columns[size_t(layout.column_base[size_t(k) * kFfaoMaxLevels])].offset);
    };
    auto orientation_end = [&](int k) { return k + 1 < orientations ? orientation_begin(k + 1) : layout.entries; };
    // Runs of whole orientations of at most `limit` entries each, greedily; false if one orientation alone is over.
    auto split = [&](int64_t limit) {
        grid.chunk_count = 0;
        for (int k = 0; k < orientations; ++k) {
            const int64_t begin = orientation_begin(k), end = orientation_end(k);
            if (end - begin > limit) return false;
            if (grid.chunk_count == 0 || end - grid.chunks[grid.chunk_count - 1].first > limit) {
                if (grid.chunk_count == OBSCURA_FFAO_PEAK_CHUNKS) return false;
                grid.chunks[grid.chunk_count++] = Chunk{k, 0, begin, begin};
            }
            grid.chunks[grid.chunk_count - 1].orientations += 1;
            grid.chunks[grid.chunk_count - 1].end = end;
        }
        return true;
    };
    // All of them in one chunk when they fit one storage block of at most OBSCURA_FFAO_MAX_BLOCK_BYTES (one obscurance
    // dispatch, as fast as it gets); otherwise chunks of OBSCURA_FFAO_CHUNK_BYTES, for memory (FFAO at 4K: 8 chunks
    // of 37 MiB instead of 296 MiB), doubled until they are at most OBSCURA_FFAO_PEAK_CHUNKS, up to the driver's
    // block (sizes past 8 x 128 MiB still render where the driver allows larger blocks).
    const int64_t one_block = std::min<int64_t>(most_entries, OBSCURA_FFAO_MAX_BLOCK_BYTES / 16);
    bool fits = layout.entries <= one_block && split(one_block);
    if (!fits) {
        int64_t limit = std::min<int64_t>(most_entries, OBSCURA_FFAO_CHUNK_BYTES / 16);
        while (!(fits = split(limit)) && limit < most_entries) limit = std::min(most_entries, 2 * limit);
    }
    const long long peak_bytes = static_cast<long long>(layout.entries) * 16;
    if (!fits) {
        return Error::make(OBSCURA_STATUS_INVALID_SIZE,
                           "FFAO at %dx%d needs %lld interval entries (%lld bytes), more than %d chunks of whole "
                           "orientations within %s (%lld): use fewer sectors, a larger base_interval or a reduced "
                           "resolution",
                           width, height, static_cast<long long>(layout.entries), peak_bytes, OBSCURA_FFAO_PEAK_CHUNKS,
                           env.cpu_renderer ? "GL_MAX_SHADER_STORAGE_BLOCK_SIZE / 16 and GL_MAX_TEXTURE_BUFFER_SIZE entries"
                                            : "GL_MAX_SHADER_STORAGE_BLOCK_SIZE / 16 entries",
                           static_cast<long long>(most_entries));
    }
    int64_t buffer_entries = 1;
    for (int c = 0; c < grid.chunk_count; ++c) {
        buffer_entries = std::max(buffer_entries, grid.chunks[c].end - grid.chunks[c].first);
    }
    HostVector<GpuLine> lines(layout.lines.size(), GpuLine{}, HostAllocator<GpuLine>(&env.alloc));
    for (size_t i = 0; i < lines.size(); ++i) {
        const FfaoLine& l = layout.lines[i];
        lines[i] = GpuLine{{l.origin[0], l.origin[1]}, l.first_step, l.steps};
    }
    grid.lines = gl::Buffer::create(gl, GL_SHADER_STORAGE_BUFFER, std::max<size_t>(lines.size(), 1) * sizeof(GpuLine));
    grid.columns = gl::Buffer::create(gl, GL_SHADER_STORAGE_BUFFER,
                                      std::max<size_t>(layout.columns.size(), 1) * sizeof(FfaoColumn));
    // The phases share the peaks buffer: it grows to the largest chunk of any phase (they differ by a few lines).
    if (peaks_.bytes() < uint64_t(buffer_entries) * 16) {
        peaks_texture_ = gl::Object();
        peaks_ = gl::Buffer::create(gl, GL_SHADER_STORAGE_BUFFER, uint64_t(buffer_entries) * 16);
    }
    if (env.cpu_renderer && grid.columns.name() && peaks_.name()) {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_FFAO_PEAKS));  // a unit the StateGuard restores
        if (!peaks_texture_) peaks_texture_ = gl::create_buffer_texture(gl, GL_RGBA32F, peaks_.name());
        grid.columns_texture = gl::create_buffer_texture(gl, GL_RGBA32UI, grid.columns.name());
    }
    const bool textures_ok = !env.cpu_renderer || (peaks_texture_ && grid.columns_texture);
    if (!grid.lines.name() || !grid.columns.name() || !peaks_.name() || !textures_ok) {
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating FFAO's scan buffers (%lld bytes) failed",
                           static_cast<long long>(buffer_entries) * 16);
    }
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, grid.lines.name());
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(lines.size() * sizeof(GpuLine)), lines.data());
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, grid.columns.name());
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(layout.columns.size() * sizeof(FfaoColumn)),
                     layout.columns.data());
    return Error();
}

void FfaoPass::release() {
    for (Grid& grid : grids_) grid = Grid();
    current_ = 0;
    peaks_texture_ = gl::Object();
    peaks_ = gl::Buffer();
    box_ = gl::Texture2D();
    terms_ = gl::Texture2D();
    running_ = gl::Texture2D();
    key_ = LayoutKey();
}

void FfaoPass::release_table() {
    table_ = gl::Object();
    table_sampler_ = gl::Object();
    table_valid_ = false;
}

uint64_t FfaoPass::bytes() const {
    uint64_t total = peaks_.bytes() + box_.bytes() + terms_.bytes() + running_.bytes() + (table_ ? kTableBytes : 0);
    for (const Grid& grid : grids_) total += grid.lines.bytes() + grid.columns.bytes();
    return total;
}

FfaoTableConstants FfaoPass::table_constants(const obscura_ffao_settings& settings) {
    const FfaoFalloffShape shape = ffao_falloff_shape(settings);
    FfaoTableConstants c = {};
    c.falloff[0] = float(shape.r);
    c.falloff[1] = float(shape.c);
    c.falloff[2] = float(shape.radius);
    c.config[0] = shape.kind;
    for (int i = 0; i < OBSCURA_FALLOFF_TABLE_SIZE; ++i) c.table[i / 4][i % 4] = shape.table[i];
    return c;
}

FfaoConstants FfaoPass::constants(const obscura_ffao_settings& settings, const FrameInput& input,
                                  int mipmap_levels, int frame_split) const {
    const Grid& grid = grids_[current_];
    FfaoConstants c = {};
    c.shape[0] = float(ffao_falloff_scale(settings) * input.meters_to_view_units);
    c.shape[1] = settings.intensity;
    c.shape[2] = settings.power;
    c.shape[3] = settings.thickness * input.meters_to_view_units;
    c.options[0] = settings.jitter == OBSCURA_TOGGLE_ON ? 1 : 0;
    c.options[1] = std::max(frame_split, 1);
    c.options[2] = mipmap_levels - 1;
    c.options[3] = int(input.frame_index % uint32_t(c.options[1]));
    // View-space displacement per texel at depth 1 (its direction is what the passes use).
    c.view[0] = float(2.0 / (double(input.projection.m[0]) * input.width));
    c.view[1] = float(2.0 / (double(input.projection.m[5]) * input.height));
    c.config[0] = grid.layout.sectors;
    c.config[1] = settings.segments;
    c.config[2] = grid.layout.base_interval;
    c.config[3] = grid.layout.levels;
    for (size_t k = 0; k < grid.layout.orientations.size() && k < OBSCURA_FFAO_MAX_ORIENTATIONS; ++k) {
        const FfaoOrientation& o = grid.layout.orientations[k];
        c.orientation[k][0] = float(o.dir[0]);
        c.orientation[k][1] = float(o.dir[1]);
        c.orientation[k][2] = float(o.u_min);
        c.orientation[k][3] = float(o.v_min);
        c.lines[k][0] = o.first_line;
        c.lines[k][1] = o.line_count;
        c.lines[k][2] = o.steps;
        const double ax = o.dir[0] * c.view[0], ay = o.dir[1] * c.view[1];
        const double length = std::hypot(ax, ay);
        c.axes[k][0] = float(ax / length);
        c.axes[k][1] = float(ay / length);
        for (int n = 0; n < grid.layout.levels; ++n) {
            const size_t index = k * kFfaoMaxLevels + size_t(n);
            c.column_base[index / 4][index % 4] = grid.layout.column_base[index];
            c.column_count[index / 4][index % 4] = grid.layout.column_count[index];
        }
    }
    return c;
}

void FfaoPass::run_table(const PassEnv& env, const obscura_ffao_settings& settings, const UniformRange& pass) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(table_program_.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, table_.name(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    gl.DispatchCompute(GLuint((kTableColumns + OBSCURA_FFAO_TABLE_GROUP - 1) / OBSCURA_FFAO_TABLE_GROUP), 1, 1);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    shape_ = ffao_falloff_shape(settings);
    table_valid_ = true;
}

void FfaoPass::run_scan(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                        const FrameResources& resources, int c) {
    const Grid& grid = grids_[current_];
    const gl::Table& gl = env.gl;
    gl.UseProgram(scan_program_.name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_FFAO_COLUMNS, grid.columns.name());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_FFAO_LINES, grid.lines.name());
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    const Chunk& chunk = grid.chunks[c];
    int most_lines = 1;
    for (int k = chunk.first_orientation; k < chunk.first_orientation + chunk.orientations; ++k) {
        most_lines = std::max(most_lines, grid.layout.orientations[size_t(k)].line_count);
    }
    bind_chunk(gl, c);
    env.bind_uniforms(OBSCURA_UBO_DISPATCH, chunk_uniforms_[c]);
    gl.DispatchCompute(GLuint((most_lines + OBSCURA_FFAO_SCAN_GROUP - 1) / OBSCURA_FFAO_SCAN_GROUP), 1,
                       GLuint(chunk.orientations));
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void FfaoPass::run_prefix(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, int c) {
    const Grid& grid = grids_[current_];
    const gl::Table& gl = env.gl;
    gl.UseProgram(prefix_program_.name());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_FFAO_COLUMNS, grid.columns.name());
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    const Chunk& chunk = grid.chunks[c];
    int most_columns = 1;
    for (int k = chunk.first_orientation; k < chunk.first_orientation + chunk.orientations; ++k) {
        for (int n = 0; n < grid.layout.levels; ++n) {
            most_columns = std::max(most_columns, int(grid.layout.column_count[size_t(k) * kFfaoMaxLevels + size_t(n)]));
        }
    }
    bind_chunk(gl, c);
    env.bind_uniforms(OBSCURA_UBO_DISPATCH, chunk_uniforms_[c]);
    gl.DispatchCompute(GLuint((most_columns + OBSCURA_FFAO_PREFIX_GROUP - 1) / OBSCURA_FFAO_PREFIX_GROUP), 1,
                       GLuint(chunk.orientations * grid.layout.levels));
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void FfaoPass::bind_chunk(const gl::Table& gl, int c) const {
    const Grid& grid = grids_[current_];
    const Chunk& chunk = grid.chunks[c];
    gl.BindBufferRange(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_FFAO_PEAKS, peaks_.name(), 0,
                       GLsizeiptr(std::max<int64_t>(chunk.end - chunk.first, 1) * 16));
}

// The per-pixel passes' common end: their constants, one invocation per pixel of `region`, and a barrier
// for the next pass's texel fetches.
void FfaoPass::dispatch_pixels(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                               const Region& region) {
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    env.dispatch(region.width, region.height, OBSCURA_FFAO_GROUP_X, OBSCURA_FFAO_GROUP_Y);
    env.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void FfaoPass::run_obscurance(const PassEnv& env, const obscura_ffao_settings& settings, const UniformRange& frame,
                              const UniformRange& pass, const Region& region, FrameResources& resources, int c) {
    const Grid& grid = grids_[current_];
    const gl::Table& gl = env.gl;
    const bool mipmap = ffao_uses_mipmap(settings), saao = ffao_uses_saao(settings);
    const int thick = ffao_single_lines(settings) ? 1 : 0;
    gl.UseProgram(obscurance_programs_[mipmap ? 1 : 0][saao ? 1 : 0][chunked() ? 1 : 0][thick].name());
    if (mipmap) {
        env.bind_texture_mipmapped(OBSCURA_UNIT_LINEAR_DEPTH, resources.linear_depth.name());
    } else {
        env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    }
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_FFAO_TABLE));
    gl.BindTexture(GL_TEXTURE_3D, table_.name());
    gl.BindSampler(OBSCURA_UNIT_FFAO_TABLE, table_sampler_.name());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, OBSCURA_SSBO_FFAO_COLUMNS, grid.columns.name());
    if (peaks_texture_) {  // CPU rasterisers: the chunk's peaks and the column records as buffer textures
        env.bind_texture(OBSCURA_UNIT_FFAO_PEAKS, GL_TEXTURE_BUFFER, peaks_texture_.name());
        env.bind_texture(OBSCURA_UNIT_FFAO_COLUMNS, GL_TEXTURE_BUFFER, grid.columns_texture.name());
    } else if (peaks_.name()) {  // GPUs: as one storage block (ensure_layout checked its size)
        bind_chunk(gl, c);
    }
    env.bind_uniforms(OBSCURA_UBO_DISPATCH, chunk_uniforms_[c]);
    const GLenum access = chunked() ? GL_READ_WRITE : GL_WRITE_ONLY;  // chunks resume the running sums
    if (saao) {
        env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, box_.name());
        gl.BindImageTexture(OBSCURA_IMAGE_OUT0, terms_.name(), 0, GL_FALSE, 0, access, GL_RG32F);
    } else {
        gl.BindImageTexture(OBSCURA_IMAGE_OUT0, resources.ao.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
        if (chunked()) gl.BindImageTexture(OBSCURA_IMAGE_OUT1, running_.name(), 0, GL_FALSE, 0, access, GL_R32F);
    }
    dispatch_pixels(env, frame, pass, region);
    // The next chunk's scan overwrites the peaks this pass read, and its obscurance reads the sums it wrote.
    if (chunked()) gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void FfaoPass::run_box_average(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                               const Region& region, const FrameResources& resources) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(box_program_.name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, box_.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    dispatch_pixels(env, frame, pass, region);
}

void FfaoPass::run_gather(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
                          FrameResources& resources) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(gather_program_.name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, box_.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, terms_.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, resources.ao.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    dispatch_pixels(env, frame, pass, region);
}

void FfaoPass::run_saao_blur(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                             const Region& region, FrameResources& resources) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(blur_program_.name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, resources.ao.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, resources.ao_blurred.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    dispatch_pixels(env, frame, pass, region);
}

}  // namespace obscura
