// LSAO's line sweeps (Timonen, "Line-Sweep Ambient Obscurance", EGSR 2013, sec. 4, Algorithm 1): one
// invocation walks one segment of one line of the layout (lines D_L apart in K directions across the whole
// depth texture, steps D_S long). At every step it samples the depth, places the point in the line's slice,
// pops the obscure hull until its top casts the largest obscurance on the point (or the hull's horizon is
// reached), writes that obscurance and pushes the point. Each step costs amortised O(1): the work is the
// number of steps, whatever the falloff's reach. The hull is a ring of at most `hull capacity` points in
// shared memory (a per-invocation array would live in local memory, which a GPU reaches through its caches
// at hundreds of cycles per access); when full, the oldest (farthest, least weighted) is dropped.
//
// Parallelism: a GPU runs ~100x more threads than there are lines (K x ~1400 at 1080p), so lines can be cut
// into segments of `segment steps` steps, one invocation each. A segment first sweeps a warm-up run before
// its start, long enough that any occluder before it lies farther than the warm-up distance from every
// receiver of the segment, where the falloff bounds what it could cast (LsaoConstants.warmup; the distance
// from a receiver at depth z to the ray of a texel m steps away is about z times their angle). The warm-up's
// values are not written. FLAG_EXACT replaces the hull with the brute-force largest occluder over every
// earlier sample of the whole line (O(M^2), for validation).
#define OBSCURA_LSAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/lsao.glsl"

layout(local_size_x = OBSCURA_LSAO_SWEEP_GROUP) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
// Eight halves per uvec4: each line's values start on a multiple of OBSCURA_LSAO_VALUE_ALIGNMENT.
layout(std430, binding = OBSCURA_SSBO_LSAO_VALUES) writeonly buffer LsaoValues { uvec4 lsao_values[]; };
layout(std430, binding = OBSCURA_SSBO_LSAO_STATS) buffer LsaoStats { uint lsao_stats[]; };

// Depth at a sample: aligned patterns read their texel. Free ones interpolate bilinearly in 1/w (affine in
// the screen on planes, so interpolated points stay on them) unless the four texels are not planar, which
// marks a depth edge or a crease: then the nearest texel is read and its centre becomes the sample's position.
const float kPlanarity = 1e-3;  // |k00 + k11 - k10 - k01| / k that still counts as one plane

float sample_depth(inout vec2 point) {
    if (lsao_aligned()) return texelFetch(u_depth, ivec2(point), 0).r;
    vec2 f = point - 0.5;
    ivec2 hi = depth_size.xy - 1;
    ivec2 base = min(ivec2(floor(f)), hi - 1);  // the layout keeps the four texels inside the texture
    vec2 t = f - vec2(base);
    float d00 = texelFetch(u_depth, clamp(base, ivec2(0), hi), 0).r;
    float d10 = texelFetch(u_depth, clamp(base + ivec2(1, 0), ivec2(0), hi), 0).r;
    float d01 = texelFetch(u_depth, clamp(base + ivec2(0, 1), ivec2(0), hi), 0).r;
    float d11 = texelFetch(u_depth, clamp(base + ivec2(1, 1), ivec2(0), hi), 0).r;
    bool sky = obscura_is_sky(d00) || obscura_is_sky(d10) || obscura_is_sky(d01) || obscura_is_sky(d11);
    if (!sky) {
        // Interpolate 1/w (perspective) or the depth itself (orthographic, where w = 1).
        bool perspective = obscura_is_perspective();
        vec4 k = perspective ? 1.0 / vec4(d00, d10, d01, d11) : vec4(d00, d10, d01, d11);
        if (abs(k.x + k.w - k.y - k.z) <= kPlanarity * max(max(k.x, k.y), max(k.z, k.w))) {
            float kk = mix(mix(k.x, k.y, t.x), mix(k.z, k.w, t.x), t.y);
            return perspective ? 1.0 / kk : kk;
        }
    }
    ivec2 nearest = clamp(ivec2(floor(point)), ivec2(0), hi);
    point = vec2(nearest) + 0.5;
    return texelFetch(u_depth, nearest, 0).r;
}

// The hulls of the group's invocations, slot-major: the invocations of a warp reading the same slot touch
// consecutive words, and each invocation's slots fall in its own banks.
shared vec2 s_hull[OBSCURA_LSAO_MAX_HULL * OBSCURA_LSAO_SWEEP_GROUP];

int hull_slot(int i) { return i * OBSCURA_LSAO_SWEEP_GROUP + int(gl_LocalInvocationID.x); }

// Ring index of start + i (i < capacity): a compare instead of an integer division, which CPU rasterisers
// cannot vectorise.
int ring(int start_plus_i, int capacity) { return start_plus_i >= capacity ? start_plus_i - capacity : start_plus_i; }

// Steps of the warm-up before the segment [begin, end) of `line`: enough that the warm-up distance separates
// the segment's nearest receiver from anything before the warm-up; all of the line before it if the
// distance is unbounded (negative).
int warmup_steps(LsaoLine line, int begin, int end) {
    float distance = lsao.warmup.x;
    if (distance < 0.0 || begin == 0) return begin;
    if (distance == 0.0) return 0;
    float nearest = OBSCURA_SKY_DEPTH;
    for (int i = begin; i < end; ++i) {
        vec2 point = lsao_sample_point(line, line.first_step + i);
        nearest = min(nearest, texelFetch(u_depth, ivec2(point), 0).r);
    }
    if (obscura_is_sky(nearest)) return 0;  // no receiver
    vec2 first = lsao_sample_point(line, line.first_step + begin);
    vec2 step = lsao.directions[line.direction].zw;
    // View-space length of one step at distance 1 (perspective) or at any distance (orthographic).
    float step_angle = length(obscura_view_position_at(first + step, 1.0) - obscura_view_position_at(first, 1.0));
    float scale = obscura_is_perspective() ? nearest : 1.0;
    return min(begin, int(ceil(distance / max(step_angle * scale, 1e-20))));
}

void main() {
    int index = int(gl_GlobalInvocationID.x);
    if (index >= lsao.config.y) return;
    LsaoLine line = lsao_lines[index];
    int segment_steps = lsao.sweep.y;
    int begin = segment_steps > 0 ? int(gl_GlobalInvocationID.y) * segment_steps : 0;
    if (begin >= line.steps) return;
    int end = segment_steps > 0 ? min(line.steps, begin + segment_steps) : line.steps;
    int warm_begin = begin - warmup_steps(line, begin, end);

    vec2 dir = lsao.directions[line.direction].xy;
    vec3 b0, a, b;
    lsao_slice_frame(lsao_sample_point(line, line.first_step), dir, b0, a, b);
    bool exact = (lsao.config.w & OBSCURA_LSAO_FLAG_EXACT) != 0;
    int capacity = lsao.config.z;
    int strategy = lsao.sweep.x;
    float fixed_sin_t = lsao.falloff.z;

    int start = 0, count = 0;  // the hull: s_hull[hull_slot(ring(start + i))], i < count, top last
    vec2 top_point = vec2(0.0);  // the top, also kept in a register: most steps pop nothing
    uint pops = 0u, dropped = 0u;
    uvec4 pending = uvec4(0u);  // packed values of the current group of 8, shifted in from .w
    float half_value = 0.0;
    for (int i = warm_begin; i < end; ++i) {
        int j = line.first_step + i;
        vec2 point = lsao_sample_point(line, j);
        float depth = sample_depth(point);
        float value = OBSCURA_LSAO_NO_OCCLUDER;
        if (!obscura_is_sky(depth)) {
            vec3 p = obscura_view_position_at(point, depth);
            vec2 pk = lsao_in_slice(p, b0, a, b);
            vec2 u = lsao_zenith(p, a, b);
            // Strategy 3 fixes the tangent for both uses; 1 uses the receiver's for both, 2 only for the occlusion.
            float real_sin_t = fixed_sin_t;
            if (strategy != 3) {
                vec3 n = obscura_decode_normal(texelFetch(u_normals, ivec2(point), 0).xy);
                real_sin_t = lsao_receiver_sin_t_3d(n, obscura_towards_eye(p), a);
            }
            float hull_sin_t = strategy == 1 ? real_sin_t : fixed_sin_t;
            float occlusion_sin_t = strategy == 3 ? fixed_sin_t : real_sin_t;
            if (exact) {
                // Every earlier sample of the line, read again.
                bool any = false;
                float best = occlusion_sin_t;
                for (int e = 0; e < i; ++e) {
                    vec2 q = lsao_sample_point(line, line.first_step + e);
                    float qd = sample_depth(q);
                    if (obscura_is_sky(qd)) continue;
                    vec2 qk = lsao_in_slice(obscura_view_position_at(q, qd), b0, a, b);
                    best = max(best, lsao_occlusion(qk - pk, u, occlusion_sin_t));
                    any = true;
                }
                if (any) value = best;
            } else {
                // The top's (occlusion, sin h) carries over when the one below becomes the top.
                vec2 top = count > 0 ? lsao_occlusion_and_sin_h(top_point - pk, u, hull_sin_t) : vec2(0.0);
                while (count >= 2) {
                    vec2 below_point = s_hull[hull_slot(ring(start + count - 2, capacity))];
                    vec2 below = lsao_occlusion_and_sin_h(below_point - pk, u, hull_sin_t);
                    if (!(top.x < below.x && top.y < below.y)) break;
                    top = below;
                    top_point = below_point;
                    --count;
                    ++pops;
                }
                if (count > 0) value = strategy == 2 ? lsao_occlusion(top_point - pk, u, occlusion_sin_t) : top.x;
                if (count == capacity) {
                    start = ring(start + 1, capacity);
                    --count;
                    ++dropped;
                }
                s_hull[hull_slot(ring(start + count, capacity))] = pk;
                top_point = pk;
                ++count;
            }
        }
        if (i < begin) continue;  // warm-up
        // Pairs of halves shift into `pending`; a full group of 8 (or the segment's last) is stored at once.
        if ((i & 1) == 0) {
            half_value = value;
        } else {
            pending = uvec4(pending.yzw, packHalf2x16(vec2(half_value, value)));
        }
        bool last = i == end - 1;
        if ((i & 7) == 7 || last) {
            if ((i & 1) == 0) pending = uvec4(pending.yzw, packHalf2x16(vec2(half_value, 0.0)));
            // Shift the partial group's pairs down to its start.
            int missing = 3 - ((i & 7) >> 1);
            for (int s = 0; s < missing; ++s) pending = uvec4(pending.yzw, 0u);
            lsao_values[(line.offset + i) >> 3] = pending;
        }
    }
    atomicAdd(lsao_stats[0], uint(end - warm_begin));
    atomicAdd(lsao_stats[1], pops);
    atomicAdd(lsao_stats[2], dropped);
}
