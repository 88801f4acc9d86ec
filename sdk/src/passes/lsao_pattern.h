// LSAO's sweep geometry (Timonen, "Line-Sweep Ambient Obscurance", EGSR 2013, sec. 5): the K azimuthal
// directions with their step vectors and azimuthal-coverage weights (aligned 8n patterns of Figure 10, or
// free directions), and the layout of the parallel lines that cover a depth texture in each direction:
// where each line starts, how many steps it takes and where its results go in the intermediate buffer.
// Pure CPU code: computed when the size or the pattern changes, uploaded for the sweep and gather passes,
// and used directly by the tests.
#ifndef OBSCURA_LSAO_PATTERN_H
#define OBSCURA_LSAO_PATTERN_H

#include <cstdint>

#include "host_allocator.h"

namespace obscura {

struct LsaoDirection {
    double dir[2];       // unit sweep direction in texels (lines are walked along it)
    double step[2];      // step vector in texels; aligned non-axis patterns: integer, ending on a texel centre
    double step_length;  // D_S of this direction
    double weight;       // azimuthal coverage / (2 pi); all weights sum to 1
    bool axis;           // an axis direction (aligned patterns: it uses the average step)
};

// Every container here lives in the host allocator's memory (`alloc`, which throws std::bad_alloc when the host's
// allocator fails): the pass keeps a layout per layout phase.
using LsaoDirections = HostVector<LsaoDirection>;

// K = 8n aligned directions from the (2n+1)x(2n+1) texel template (Figure 10), ordered by angle from +x.
// Non-axis directions step to the outer ring's texel centres, `step_multiple` rings at a time (the paper's Figures
// 1 and 13 walk two: D_S 2.83 and 4.87 for K = 8 and 16); axis ones use the average of those lengths.
LsaoDirections aligned_directions(int n, int step_multiple = 1,
                                  const AllocatorCallbacks& alloc = AllocatorCallbacks::system());

// The template's own D_S for K = 8n (its non-axis steps' mean length: Table 2's 1.41, 2.43, 3.56, 4.69), and the whole
// number of template steps an aligned pattern walks for a requested D_S (at least 1): aligned samples must stay on
// texel centres, so D_S is the template's times that number.
double aligned_template_step(int n);
int aligned_step_multiple(int n, double step_length);

// K evenly spaced directions (angle 2 pi (k + rotation) / K, rotation in [0, 1): a layout phase's turn) with step
// length `step_length` and weight 1/K.
LsaoDirections free_directions(int k, double step_length, double rotation = 0.0,
                               const AllocatorCallbacks& alloc = AllocatorCallbacks::system());

// The average step length D_S of a pattern.
double average_step_length(const LsaoDirections& directions);

// One sweep line: samples at origin + j * step for j in [first_step, first_step + steps); aligned patterns
// snap each sample to the texel that contains it (floor), free ones interpolate.
struct LsaoLine {
    float origin[2];      // texel units (texel centres at .5)
    int32_t first_step;   // j of the first sample inside the texture
    int32_t steps;        // samples inside the texture (0: the line misses it)
    int32_t offset;       // index of the line's first value in the intermediate buffer (a multiple of 8)
    int32_t direction;    // index into the directions
};

// Per-direction summary for the gather: lines l of direction k are lines[first_line + l], their ideal
// offsets across the sweep direction are line_origin_v + l * line_spacing.
struct LsaoDirectionLines {
    int32_t first_line;
    int32_t line_count;
    double line_origin_v;  // perpendicular coordinate (texels, along (-dir.y, dir.x)) of line 0
};

struct LsaoLayout {
    LsaoLayout() = default;
    explicit LsaoLayout(const AllocatorCallbacks& alloc)
        : directions(HostAllocator<LsaoDirection>(&alloc)), direction_lines(HostAllocator<LsaoDirectionLines>(&alloc)),
          lines(HostAllocator<LsaoLine>(&alloc)) {}
    int width = 0, height = 0;
    double line_spacing = 0.0;  // D_L
    LsaoDirections directions;
    HostVector<LsaoDirectionLines> direction_lines;
    HostVector<LsaoLine> lines;
    int64_t values = 0;  // intermediate buffer length (each line's count rounded up to a multiple of 8)
    int32_t longest_line = 0;  // the most steps of any line
};

// Lines D_L apart across a width x height texture for every direction. `aligned`: line origins are chosen
// so that samples fall on texel centres (the snapped pattern repeats along the line). `line_shift` in [0, 1)
// moves every line across by that fraction of D_L (a layout phase; 0: the first line half a spacing in).
LsaoLayout make_lsao_layout(const LsaoDirections& directions, double line_spacing, int width, int height,
                            bool aligned, double line_shift = 0.0,
                            const AllocatorCallbacks& alloc = AllocatorCallbacks::system());

// The sample j of `line` as the texel it reads (aligned) or the point it interpolates at (free).
void lsao_sample_position(const LsaoLayout& layout, const LsaoLine& line, int j, bool aligned, double out[2]);

// The gather's choice for the texel centre (x + 0.5, y + 0.5) in direction k: the nearest sample of the two
// lines whose ideal positions bracket it. Returns false if no line of the direction has a sample near it. `line_index` is an
// index into layout.lines, `step` the sample's j, `distance` how far its position is from the texel centre.
bool lsao_nearest_sample(const LsaoLayout& layout, int k, int x, int y, bool aligned, int* line_index, int* step,
                         double* distance);

}  // namespace obscura

#endif  // OBSCURA_LSAO_PATTERN_H
