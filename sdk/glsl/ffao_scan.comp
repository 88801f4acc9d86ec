// FFAO's scan kernel (Timonen, "Screen-Space Far-Field Ambient Obscurance", HPG 2013, sec. 6, Algorithm 1):
// one invocation walks one line of one orientation a texel at a time. Each sample's view position q is
// placed in the orientation's frame, x = q . A (A the view-space direction of the scan) and z = q.z (towards
// the eye is up), and the interval keeps the peaks m0 = max z (seen along a horizontal receiver angle) and,
// for the two receiver angles of slope -1 (a receiver behind the interval looking back, one ahead looking
// forward), m1 = max(z - x) and max(z + x). Every B0 steps the interval is written and merged into the next
// level of the 1D pyramid (B_n = B0 2^n, the max of its two halves), so one pass writes every level. An
// interval whose samples are all sky writes (0, 0, 0, 0): the last component counts valid lines for the
// sector averages (sec. 7), which then skip it.
#define OBSCURA_FFAO_PASS 1
#define OBSCURA_FFAO_CHUNK_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/ffao.glsl"

layout(local_size_x = OBSCURA_FFAO_SCAN_GROUP) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;
layout(std430, binding = OBSCURA_SSBO_FFAO_PEAKS) writeonly buffer FfaoPeaks { vec4 ffao_peaks[]; };
layout(std430, binding = OBSCURA_SSBO_FFAO_LINES) readonly buffer FfaoLines { uvec4 ffao_lines[]; };

vec4 g_level[OBSCURA_FFAO_MAX_LEVELS];  // the open interval of every level: (m0, m1 back, m1 forward, valid)

vec4 merged(vec4 a, vec4 b) {
    if (a.w == 0.0) return b;
    if (b.w == 0.0) return a;
    return vec4(max(a.xyz, b.xyz), 1.0);
}

void write_interval(int k, int n, int i, int l, vec4 peaks) {
    FfaoColumn column = ffao_column(k, n, i);
    int entry = l - column.first_line;
    if (entry >= 0 && entry < column.lines) ffao_peaks[column.offset + entry - ffao_chunk.range.z] = peaks;
}

void main() {
    int k = ffao_chunk.range.x + int(gl_GlobalInvocationID.z);  // one dispatch per chunk of orientations
    int l = int(gl_GlobalInvocationID.x);
    if (l >= ffao.lines[k].y) return;
    uvec4 record = ffao_lines[ffao.lines[k].x + l];
    vec2 origin = uintBitsToFloat(record.xy);
    int first = int(record.z), steps = int(record.w);
    if (steps <= 0) return;
    vec2 dir = ffao.orientation[k].xy;
    vec2 axis = ffao.axes[k].xy;
    int levels = ffao_levels();
    int b0 = ffao_base_interval();
    ivec2 size = depth_size.xy;
    for (int n = 0; n < levels; ++n) g_level[n] = vec4(0.0);
    int last = first + steps - 1;
    // Interval by interval: the steps of level-0 interval i, then its writes. (A test at every step for the interval's
    // end would make CPU rasterisers, which run every lane through both sides of a branch, do the writes' work at
    // every step.)
    for (int i = first / b0; i <= last / b0; ++i) {
        int end = min(last, i * b0 + b0 - 1);
        for (int j = max(first, i * b0); j <= end; ++j) {
            // Steps outside the texture (a few, where a column's run of lines needs them) read as sky.
            ivec2 texel = ivec2(floor(origin + float(j) * dir));
            bool inside = all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, size));
            float depth = inside ? texelFetch(u_depth, texel, 0).r : OBSCURA_SKY_DEPTH;
            if (!obscura_is_sky(depth)) {
                vec3 q = obscura_view_position(texel, depth);
                float x = dot(q.xy, axis);
                g_level[0] = merged(g_level[0], vec4(q.z, q.z - x, q.z + x, 1.0));
            }
        }
        // The level-0 interval ends here (or the line does): write it and every level it completes (interval i
        // completes its parent when i is odd, so as many levels as i has trailing ones, plus one; all at the line's
        // end).
        int completed = end == last ? levels : min(levels, findLSB(~i) + 1);
        for (int n = 0; n < completed; ++n) {
            write_interval(k, n, i >> n, l, g_level[n]);
            if (n + 1 < levels) g_level[n + 1] = merged(g_level[n + 1], g_level[n]);
            g_level[n] = vec4(0.0);
        }
    }
}
