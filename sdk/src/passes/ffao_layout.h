// FFAO's scan geometry (Timonen, "Screen-Space Far-Field Ambient Obscurance", HPG 2013, sec. 6-7): K/2 line
// orientations, each a grid of parallel lines one texel apart across the whole depth texture walked one texel
// per step, the 1D pyramid of intervals B_n = B0 2^n along them, and where each (line, interval) entry lives in
// the peaks buffer (column by column, so the prefix sums across lines run over consecutive entries). Pure CPU
// code: built when the size, K or B0 changes, uploaded for the passes, and used by the tests directly.
#ifndef OBSCURA_FFAO_LAYOUT_H
#define OBSCURA_FFAO_LAYOUT_H

#include <cstdint>

#include "host_allocator.h"

namespace obscura {

constexpr int kFfaoMaxLevels = 16;  // OBSCURA_FFAO_MAX_LEVELS

struct FfaoOrientation {
    double dir[2];         // unit scan direction in texels, at angle 2 pi k / K
    double u_min, v_min;   // the grid's origin along dir and along perp = (-dir.y, dir.x)
    int32_t steps;         // U: grid steps along dir (every line's step j sits at u = u_min + j + 0.5)
    int32_t first_line;    // this orientation's lines are lines[first_line ... + line_count - 1]
    int32_t line_count;    // line l sits at v = v_min + l + 0.5
};

// The steps a line's scan walks: [first_step, first_step + steps). They cover every texel of the line inside
// the texture, plus the out-of-texture steps that make each column's lines a contiguous run (read as sky).
struct FfaoLine {
    float origin[2];       // position of step 0, texels (the scan reads texel floor(origin + j dir))
    int32_t first_step;
    int32_t steps;
};

// One interval column: the entries of lines first_line ... first_line + lines - 1 at level n, interval i.
struct FfaoColumn {
    int32_t offset;        // index of first_line's entry in the peaks buffer
    int32_t first_line;
    int32_t lines;         // 0: no line reaches the interval
    int32_t block_shift;   // the prefix sums restart every 2^block_shift entries
};

// Held by the pass for every layout phase it ran (megabytes at 4K): in the host allocator's memory.
struct FfaoLayout {
    FfaoLayout() = default;
    explicit FfaoLayout(const AllocatorCallbacks& alloc)
        : orientations(HostAllocator<FfaoOrientation>(&alloc)), lines(HostAllocator<FfaoLine>(&alloc)),
          columns(HostAllocator<FfaoColumn>(&alloc)), column_base(HostAllocator<int32_t>(&alloc)),
          column_count(HostAllocator<int32_t>(&alloc)) {}
    int width = 0, height = 0, sectors = 0, base_interval = 0, levels = 0;
    HostVector<FfaoOrientation> orientations;  // K / 2
    HostVector<FfaoLine> lines;
    HostVector<FfaoColumn> columns;
    HostVector<int32_t> column_base;   // [k * kFfaoMaxLevels + n]: index of column 0 of (k, n) in columns
    HostVector<int32_t> column_count;  // [k * kFfaoMaxLevels + n]
    int64_t entries = 0;               // peaks-buffer length (vec4 each)
};

// The layout for `sectors` (even, >= 4) sectors and base interval B0 over a width x height texture. A layout phase
// (layout_phase.h) moves every line across by `line_shift` in [0, 1) of a texel (the orientations stay: turned
// ones made the accumulated AO darker than the truth, docs/algorithms.md). Everything, the layout and the scratch
// of building it, is allocated through `alloc` (which throws std::bad_alloc when the host's allocator fails).
FfaoLayout make_ffao_layout(int sectors, int base_interval, int width, int height, double line_shift = 0.0,
                            const AllocatorCallbacks& alloc = AllocatorCallbacks::system());

// Widest run of lines a sector segment averages at level n (see ffao_obscurance.comp): the prefix sums restart
// every power of two at least this wide; the top level never restarts.
int ffao_block_shift(int level, int levels, int base_interval, int sectors);

// Step j of line `line` in texels, computed in float as the scan computes it.
void ffao_step_position(const FfaoLine& line, const FfaoOrientation& o, int j, float out[2]);

}  // namespace obscura

#endif  // OBSCURA_FFAO_LAYOUT_H
