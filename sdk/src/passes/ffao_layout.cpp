#include "passes/ffao_layout.h"

#include <algorithm>
#include <cmath>

#include "math_constants.h"

namespace obscura {
namespace {

bool texel_inside(const float p[2], int width, int height) {
    const float x = std::floor(p[0]), y = std::floor(p[1]);
    return x >= 0.0f && y >= 0.0f && x < float(width) && y < float(height);
}

// First and last step of the line whose texel lies inside the texture; false if none. The analytic range is
// widened and then settled by testing the steps exactly as the scan computes them.
bool inside_steps(const FfaoLine& line, const FfaoOrientation& o, int width, int height, int* first, int* last) {
    double lo = 0.0, hi = double(o.steps - 1);
    const double origin[2] = {line.origin[0], line.origin[1]};
    const int sizes[2] = {width, height};
    for (int axis = 0; axis < 2; ++axis) {
        const double d = o.dir[axis];
        if (std::fabs(d) < 1e-12) {
            if (origin[axis] < 0.0 || origin[axis] >= sizes[axis]) return false;
            continue;
        }
        double a = (0.0 - origin[axis]) / d, b = (double(sizes[axis]) - origin[axis]) / d;
        if (a > b) std::swap(a, b);
        lo = std::max(lo, a);
        hi = std::min(hi, b);
    }
    int j0 = std::max(0, int(std::floor(lo)) - 2), j1 = std::min(o.steps - 1, int(std::ceil(hi)) + 2);
    float p[2];
    while (j0 <= j1 && (ffao_step_position(line, o, j0, p), !texel_inside(p, width, height))) ++j0;
    while (j1 >= j0 && (ffao_step_position(line, o, j1, p), !texel_inside(p, width, height))) --j1;
    *first = j0;
    *last = j1;
    return j0 <= j1;
}

int ceil_div(int a, int b) { return (a + b - 1) / b; }

}  // namespace

void ffao_step_position(const FfaoLine& line, const FfaoOrientation& o, int j, float out[2]) {
    out[0] = line.origin[0] + float(j) * float(o.dir[0]);
    out[1] = line.origin[1] + float(j) * float(o.dir[1]);
}

int ffao_block_shift(int level, int levels, int base_interval, int sectors) {
    if (level >= levels - 1) return 15;
    // A level-n interval is read at most 4.5 B_n from the receiver (the walk climbs a level once an aligned
    // interval is no longer than its distance), where a segment spans at most 2 tan(pi / K) of it.
    const double widest = 2.0 * 4.5 * double(base_interval << level) * std::tan(kPi / sectors) + 2.0;
    int shift = 2;
    while (shift < 15 && double(1 << shift) < widest) ++shift;
    return shift;
}

FfaoLayout make_ffao_layout(int sectors, int base_interval, int width, int height, double line_shift,
                            const AllocatorCallbacks& alloc) {
    FfaoLayout layout(alloc);
    layout.width = width;
    layout.height = height;
    layout.sectors = sectors;
    layout.base_interval = base_interval;
    const double corners[4][2] = {{0.0, 0.0}, {double(width), 0.0}, {0.0, double(height)},
                                  {double(width), double(height)}};
    // Each line's walked steps, per orientation: [first, last] (empty: first > last).
    HostVector<int> first_steps{HostAllocator<int>(&alloc)}, last_steps{HostAllocator<int>(&alloc)};
    int longest = 1;
    layout.orientations.reserve(size_t(sectors / 2));
    for (int k = 0; k < sectors / 2; ++k) {
        FfaoOrientation o = {};
        const double angle = 2.0 * kPi * k / sectors;
        o.dir[0] = std::cos(angle);
        o.dir[1] = std::sin(angle);
        if (std::fabs(o.dir[0]) < 1e-15) o.dir[0] = 0.0;
        if (std::fabs(o.dir[1]) < 1e-15) o.dir[1] = 0.0;
        const double perp[2] = {-o.dir[1], o.dir[0]};
        double u_min = 1e300, u_max = -1e300, v_min = 1e300, v_max = -1e300;
        for (const auto& c : corners) {
            const double u = c[0] * o.dir[0] + c[1] * o.dir[1], v = c[0] * perp[0] + c[1] * perp[1];
            u_min = std::min(u_min, u);
            u_max = std::max(u_max, u);
            v_min = std::min(v_min, v);
            v_max = std::max(v_max, v);
        }
        o.u_min = u_min;
        o.v_min = v_min;
        o.steps = std::max(1, int(std::ceil(u_max - u_min - 1e-9)));
        o.line_count = std::max(1, int(std::ceil(v_max - v_min - 1e-9)));
        if (line_shift > 0.0) {  // a shifted grid starts one line earlier, so that it still covers the first texels
            o.v_min += line_shift - 1.0;
            o.line_count += 1;
        }
        o.first_line = layout.orientations.empty()
                           ? 0
                           : layout.orientations.back().first_line + layout.orientations.back().line_count;
        longest = std::max(longest, o.steps);
        layout.orientations.push_back(o);
    }
    // Every container is sized once (each growth is an allocation from the host's allocator).
    const size_t line_total =
        layout.orientations.empty()
            ? 0
            : size_t(layout.orientations.back().first_line + layout.orientations.back().line_count);
    layout.lines.reserve(line_total);
    first_steps.reserve(line_total);
    last_steps.reserve(line_total);
    for (const FfaoOrientation& o : layout.orientations) {
        const double perp[2] = {-o.dir[1], o.dir[0]};
        for (int l = 0; l < o.line_count; ++l) {
            FfaoLine line = {};
            const double u = o.u_min + 0.5, v = o.v_min + 0.5 + l;
            line.origin[0] = float(u * o.dir[0] + v * perp[0]);
            line.origin[1] = float(u * o.dir[1] + v * perp[1]);
            int first = 0, last = -1;
            if (!inside_steps(line, o, width, height, &first, &last)) {
                first = 0;
                last = -1;
            }
            first_steps.push_back(first);
            last_steps.push_back(last);
            layout.lines.push_back(line);
        }
    }
    int levels = 1;
    while (levels < kFfaoMaxLevels && (base_interval << (levels - 1)) * 2 < longest) ++levels;
    layout.levels = levels;

    // Columns: the run of lines reaching each interval. A line inside a column's run that has no step in the
    // interval (possible next to the texture's corners) gets out-of-texture steps there, so each column's
    // entries are written by a contiguous run of lines; repeat until no run changes.
    layout.column_base.assign(size_t(sectors / 2) * kFfaoMaxLevels, 0);
    layout.column_count.assign(size_t(sectors / 2) * kFfaoMaxLevels, 0);
    int32_t column_total = 0;
    for (int k = 0; k < sectors / 2; ++k) {
        const FfaoOrientation& o = layout.orientations[size_t(k)];
        for (int n = 0; n < levels; ++n) {
            const size_t index = size_t(k) * kFfaoMaxLevels + size_t(n);
            layout.column_base[index] = column_total;
            layout.column_count[index] = ceil_div(o.steps, base_interval << n);
            column_total += layout.column_count[index];
        }
    }
    // Per column: the run of lines.
    HostVector<int> lo(size_t(column_total), 0, HostAllocator<int>(&alloc));
    HostVector<int> hi(size_t(column_total), 0, HostAllocator<int>(&alloc));
    for (int pass = 0; pass < 8; ++pass) {
        std::fill(lo.begin(), lo.end(), 1 << 30);
        std::fill(hi.begin(), hi.end(), -1);
        for (int k = 0; k < sectors / 2; ++k) {
            const FfaoOrientation& o = layout.orientations[size_t(k)];
            for (int l = 0; l < o.line_count; ++l) {
                const size_t line = size_t(o.first_line + l);
                if (first_steps[line] > last_steps[line]) continue;
                for (int n = 0; n < levels; ++n) {
                    const int length = base_interval << n;
                    const int base = layout.column_base[size_t(k) * kFfaoMaxLevels + size_t(n)];
                    for (int i = first_steps[line] / length; i <= last_steps[line] / length; ++i) {
                        lo[size_t(base + i)] = std::min(lo[size_t(base + i)], l);
                        hi[size_t(base + i)] = std::max(hi[size_t(base + i)], l);
                    }
                }
            }
        }
        bool changed = false;
        for (int k = 0; k < sectors / 2; ++k) {
            const FfaoOrientation& o = layout.orientations[size_t(k)];
            for (int n = 0; n < levels; ++n) {
                const int length = base_interval << n;
                const size_t index = size_t(k) * kFfaoMaxLevels + size_t(n);
                for (int i = 0; i < layout.column_count[index]; ++i) {
                    const int c = layout.column_base[index] + i;
                    for (int l = lo[size_t(c)]; l <= hi[size_t(c)]; ++l) {
                        const size_t line = size_t(o.first_line + l);
                        int& first = first_steps[line];
                        int& last = last_steps[line];
                        const int begin = i * length, end = std::min((i + 1) * length, o.steps) - 1;
                        if (first > last) {  // a line with no texel inside: give it this interval's first step
                            first = last = begin;
                            changed = true;
                        } else if (last < begin) {
                            last = begin;
                            changed = true;
                        } else if (first > end) {
                            first = end;
                            changed = true;
                        }
                    }
                }
            }
        }
        if (!changed) break;
    }
    int64_t offset = 0;
    layout.columns.reserve(size_t(column_total));
    for (int k = 0; k < sectors / 2; ++k) {
        for (int n = 0; n < levels; ++n) {
            const size_t index = size_t(k) * kFfaoMaxLevels + size_t(n);
            const int shift = ffao_block_shift(n, levels, base_interval, sectors);
            for (int i = 0; i < layout.column_count[index]; ++i) {
                const int c = layout.column_base[index] + i;
                FfaoColumn column = {};
                column.offset = int32_t(offset);
                column.block_shift = shift;
                if (hi[size_t(c)] >= lo[size_t(c)]) {
                    column.first_line = lo[size_t(c)];
                    column.lines = hi[size_t(c)] - lo[size_t(c)] + 1;
                }
                offset += column.lines;
                layout.columns.push_back(column);
            }
        }
    }
    layout.entries = offset;
    for (size_t i = 0; i < layout.lines.size(); ++i) {
        layout.lines[i].first_step = first_steps[i];
        layout.lines[i].steps = last_steps[i] >= first_steps[i] ? last_steps[i] - first_steps[i] + 1 : 0;
    }
    return layout;
}

}  // namespace obscura
