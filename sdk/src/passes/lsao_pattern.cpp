#include "passes/lsao_pattern.h"

#include "common/shader_interface.h"

#include <algorithm>
#include <cmath>

#include "math_constants.h"

namespace obscura {
namespace {

double angle_of(const double v[2]) {
    double a = std::atan2(v[1], v[0]);
    return a < 0.0 ? a + kTwoPi : a;
}

// Azimuthal coverage: half the angular gap to each neighbour, over 2 pi.
void assign_coverage_weights(LsaoDirections* directions) {
    const size_t k = directions->size();
    if (k == 1) {
        (*directions)[0].weight = 1.0;
        return;
    }
    for (size_t i = 0; i < k; ++i) {
        double prev = angle_of((*directions)[(i + k - 1) % k].dir);
        double here = angle_of((*directions)[i].dir);
        double next = angle_of((*directions)[(i + 1) % k].dir);
        double before = here - prev, after = next - here;
        if (before <= 0.0) before += kTwoPi;
        if (after <= 0.0) after += kTwoPi;
        (*directions)[i].weight = 0.5 * (before + after) / kTwoPi;
    }
}

}  // namespace

double aligned_template_step(int n) {
    double sum = 0.0;
    int count = 0;
    for (int j = -n; j <= n; ++j)
        for (int i = -n; i <= n; ++i) {
            if (std::max(std::abs(i), std::abs(j)) != n || i == 0 || j == 0) continue;  // the ring, less the axes
            sum += std::hypot(double(i), double(j));
            ++count;
        }
    return count > 0 ? sum / double(count) : 0.0;
}

int aligned_step_multiple(int n, double step_length) {
    const double template_step = aligned_template_step(n);
    if (!(template_step > 0.0)) return 1;
    return std::max(1, int(std::lround(step_length / template_step)));
}

LsaoDirections aligned_directions(int n, int step_multiple, const AllocatorCallbacks& alloc) {
    LsaoDirections out{HostAllocator<LsaoDirection>(&alloc)};
    if (n < 1) return out;
    const int m = std::max(1, step_multiple);
    double sum = 0.0;
    int non_axis = 0;
    for (int j = -n; j <= n; ++j)
        for (int i = -n; i <= n; ++i) {
            if (std::max(std::abs(i), std::abs(j)) != n) continue;  // the template's outer ring
            LsaoDirection d = {};
            d.axis = i == 0 || j == 0;
            const double length = std::hypot(double(i), double(j));
            d.dir[0] = i / length;
            d.dir[1] = j / length;
            d.step[0] = m * i;
            d.step[1] = m * j;
            d.step_length = m * length;
            if (!d.axis) {
                sum += length;
                ++non_axis;
            }
            out.push_back(d);
        }
    // Axis directions may use any step length and take the average of the others (walked as many rings at a time).
    const double average = m * sum / double(non_axis);
    for (LsaoDirection& d : out) {
        if (!d.axis) continue;
        d.step[0] = d.dir[0] * average;
        d.step[1] = d.dir[1] * average;
        d.step_length = average;
    }
    std::sort(out.begin(), out.end(),
              [](const LsaoDirection& a, const LsaoDirection& b) { return angle_of(a.dir) < angle_of(b.dir); });
    assign_coverage_weights(&out);
    return out;
}

LsaoDirections free_directions(int k, double step_length, double rotation, const AllocatorCallbacks& alloc) {
    LsaoDirections out{HostAllocator<LsaoDirection>(&alloc)};
    for (int i = 0; i < k; ++i) {
        const double angle = kTwoPi * (i + rotation) / k;
        LsaoDirection d = {};
        d.dir[0] = std::cos(angle);
        d.dir[1] = std::sin(angle);
        // Axis directions exactly: cos(pi / 2) is 6e-17, and a line on an edge row's texel centre then drifted off it
        // step by step, so half of it failed the inside test (as FFAO's layout does, ffao_layout.cpp).
        if (std::fabs(d.dir[0]) < 1e-12) d.dir[0] = 0.0;
        if (std::fabs(d.dir[1]) < 1e-12) d.dir[1] = 0.0;
        d.step[0] = d.dir[0] * step_length;
        d.step[1] = d.dir[1] * step_length;
        d.step_length = step_length;
        d.axis = false;
        out.push_back(d);
    }
    assign_coverage_weights(&out);
    return out;
}

double average_step_length(const LsaoDirections& directions) {
    double sum = 0.0;
    for (const LsaoDirection& d : directions) sum += d.step_length;
    return directions.empty() ? 0.0 : sum / double(directions.size());
}

namespace {

// Range of j with floor(origin + j * step) inside [0, size) on one axis, intersected into [lo, hi].
void clip_axis(double origin, double step, int size, double* lo, double* hi) {
    if (step == 0.0) {
        if (origin < 0.0 || origin >= double(size)) {
            *lo = 1.0;
            *hi = 0.0;
        }
        return;
    }
    double a = (0.0 - origin) / step, b = (double(size) - origin) / step;
    if (a > b) std::swap(a, b);
    *lo = std::max(*lo, a);
    *hi = std::min(*hi, b);
}

// Aligned samples read the texel containing them; free ones interpolate the four texel centres around them,
// which must all exist.
bool inside(const double p[2], int width, int height, bool aligned) {
    if (!aligned) return p[0] >= 0.5 && p[1] >= 0.5 && p[0] <= width - 0.5 && p[1] <= height - 0.5;
    return p[0] >= 0.0 && p[1] >= 0.0 && std::floor(p[0]) < double(width) && std::floor(p[1]) < double(height);
}

}  // namespace

void lsao_sample_position(const LsaoLayout& layout, const LsaoLine& line, int j, bool aligned, double out[2]) {
    const LsaoDirection& d = layout.directions[size_t(line.direction)];
    out[0] = double(line.origin[0]) + j * d.step[0];
    out[1] = double(line.origin[1]) + j * d.step[1];
    if (aligned) {
        out[0] = std::floor(out[0]) + 0.5;
        out[1] = std::floor(out[1]) + 0.5;
    }
}

namespace {

// The lines of direction `d` across a width x height texture, D_L apart (first_line left 0).
LsaoDirectionLines lines_across(const LsaoDirection& d, double line_spacing, int width, int height, double line_shift) {
    const double corners[4][2] = {{0.0, 0.0}, {double(width), 0.0}, {0.0, double(height)},
                                  {double(width), double(height)}};
    const double perp[2] = {-d.dir[1], d.dir[0]};
    double v_min = 1e300, v_max = -1e300;
    for (const auto& c : corners) {
        const double v = c[0] * perp[0] + c[1] * perp[1];
        v_min = std::min(v_min, v);
        v_max = std::max(v_max, v);
    }
    LsaoDirectionLines summary = {};
    summary.line_count = std::max(1, int(std::ceil((v_max - v_min) / line_spacing)));
    summary.line_origin_v = v_min + 0.5 * line_spacing;
    if (line_shift > 0.0) {  // a shifted grid starts one line earlier, so the band below line 0 stays as narrow
        summary.line_origin_v += (line_shift - 1.0) * line_spacing;
        summary.line_count += 1;
    }
    return summary;
}

}  // namespace

LsaoLayout make_lsao_layout(const LsaoDirections& directions, double line_spacing, int width, int height,
                            bool aligned, double line_shift, const AllocatorCallbacks& alloc) {
    LsaoLayout layout(alloc);
    layout.width = width;
    layout.height = height;
    layout.line_spacing = line_spacing;
    layout.directions.assign(directions.begin(), directions.end());  // in `alloc`'s memory, whatever theirs is
    const double center[2] = {0.5 * width, 0.5 * height};
    // Every container is sized once (each growth is an allocation from the host's allocator).
    size_t line_total = 0;
    for (const LsaoDirection& d : directions) {
        line_total += size_t(lines_across(d, line_spacing, width, height, line_shift).line_count);
    }
    layout.lines.reserve(line_total);
    layout.direction_lines.reserve(directions.size());
    int64_t offset = 0;
    for (size_t k = 0; k < directions.size(); ++k) {
        const LsaoDirection& d = directions[k];
        const double perp[2] = {-d.dir[1], d.dir[0]};
        LsaoDirectionLines summary = lines_across(d, line_spacing, width, height, line_shift);
        summary.first_line = int32_t(layout.lines.size());
        const double center_v = center[0] * perp[0] + center[1] * perp[1];
        for (int l = 0; l < summary.line_count; ++l) {
            const double v = summary.line_origin_v + l * line_spacing;
            double ideal[2] = {center[0] + (v - center_v) * perp[0], center[1] + (v - center_v) * perp[1]};
            double origin[2] = {ideal[0], ideal[1]};
            if (aligned) {
                // The texel centre of the 2x2 around the ideal point that lies closest to the ideal line: its
                // lattice line (texel centres along the step) is then the nearest one.
                const double bx = std::floor(ideal[0] - 0.5) + 0.5, by = std::floor(ideal[1] - 0.5) + 0.5;
                double best = 1e300;
                for (int c = 0; c < 4; ++c) {
                    const double cx = bx + (c & 1), cy = by + (c >> 1);
                    const double off = std::fabs(cx * perp[0] + cy * perp[1] - v);
                    if (off < best - 1e-12) {
                        best = off;
                        origin[0] = cx;
                        origin[1] = cy;
                    }
                }
            }
            double lo = -1e300, hi = 1e300;
            clip_axis(origin[0], d.step[0], width, &lo, &hi);
            clip_axis(origin[1], d.step[1], height, &lo, &hi);
            LsaoLine line = {};
            line.origin[0] = float(origin[0]);
            line.origin[1] = float(origin[1]);
            line.direction = int32_t(k);
            if (lo <= hi) {
                // Rounding at the ends is settled by testing the samples themselves.
                int first = int(std::ceil(lo)) - 1, last = int(std::floor(hi)) + 1;
                double p[2];
                auto sample_inside = [&](int j) {
                    lsao_sample_position(layout, line, j, aligned, p);
                    return inside(p, width, height, aligned);
                };
                while (first <= last && !sample_inside(first)) ++first;
                while (last >= first && !sample_inside(last)) --last;
                line.first_step = first;
                line.steps = last >= first ? last - first + 1 : 0;
            }
            line.offset = int32_t(offset);
            // The sweep stores OBSCURA_LSAO_VALUE_ALIGNMENT values at a time from the line's start.
            const int64_t alignment = OBSCURA_LSAO_VALUE_ALIGNMENT;
            offset += (int64_t(line.steps) + alignment - 1) / alignment * alignment;
            layout.lines.push_back(line);
        }
        layout.direction_lines.push_back(summary);
    }
    layout.values = offset;
    for (const LsaoLine& line : layout.lines) layout.longest_line = std::max(layout.longest_line, line.steps);
    return layout;
}

bool lsao_nearest_sample(const LsaoLayout& layout, int k, int x, int y, bool aligned, int* line_index, int* step,
                         double* distance) {
    const LsaoDirection& d = layout.directions[size_t(k)];
    const LsaoDirectionLines& summary = layout.direction_lines[size_t(k)];
    const double p[2] = {x + 0.5, y + 0.5};
    const double perp[2] = {-d.dir[1], d.dir[0]};
    const double v = p[0] * perp[0] + p[1] * perp[1];
    // The two lines whose ideal positions bracket the texel (as lsao_gather.comp).
    const int below = int(std::floor((v - summary.line_origin_v) / layout.line_spacing));
    const double step_sq = d.step[0] * d.step[0] + d.step[1] * d.step[1];
    bool found = false;
    double best = 1e300;
    for (int l = below; l <= below + 1; ++l) {
        if (l < 0 || l >= summary.line_count) continue;
        const LsaoLine& line = layout.lines[size_t(summary.first_line + l)];
        if (line.steps == 0) continue;
        const double rel[2] = {p[0] - line.origin[0], p[1] - line.origin[1]};
        int j = int(std::lround((rel[0] * d.step[0] + rel[1] * d.step[1]) / step_sq));
        j = std::clamp(j, line.first_step, line.first_step + line.steps - 1);
        double q[2];
        lsao_sample_position(layout, line, j, aligned, q);
        const double dist = std::hypot(q[0] - p[0], q[1] - p[1]);
        if (dist < best) {
            best = dist;
            found = true;
            *line_index = summary.first_line + l;
            *step = j;
            *distance = dist;
        }
    }
    return found;
}

}  // namespace obscura
