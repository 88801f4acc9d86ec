// LSAO's line sweeps (Timonen, "Line-Sweep Ambient Obscurance", EGSR 2013, sec. 4, Algorithm 1): one
// invocation walks one segment of one line of the layout (lines D_L apart in K directions across the whole
// depth texture, steps D_S long). At every step it samples the depth, places the point in the line's slice,
// pops the obscure hull until its top casts the largest obscurance on the point (or the hull's horizon is
// reached), writes that obscurance and pushes the point. Each step costs amortised O(1): the work is the
// number of steps, whatever the falloff's reach. The hull is a ring of at most `hull capacity` points in
// shared memory on GPUs (a per-invocation array would live in local memory, which a GPU reaches through its
// caches at hundreds of cycles per access) and in a private array on CPU rasterisers; when full, the oldest
// (farthest, least weighted) is dropped.
//
// Parallelism: a GPU runs ~100x more threads than there are lines (K x ~1400 at 1080p), so lines can be cut
// into segments of `segment steps` steps, one invocation each. A segment first sweeps a warm-up run before
// its start, long enough that any occluder before it lies farther than the warm-up distance from every
// receiver of the segment, where the falloff bounds what it could cast (LsaoConstants.warmup; the distance
// from a receiver at depth z to the ray of a texel m steps away is about z times their angle). The warm-up's
// values are not written. OBSCURA_LSAO_EXACT_SWEEP 1 (another program) replaces the hull with the
// brute-force largest occluder over every earlier sample of the whole line (O(M^2), for validation).
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
        // Relative to the quad's 1/w (perspective) or the tolerance distance (orthographic: the depths' own size
        // would depend on where the eye plane sits).
        float scale = perspective ? max(max(k.x, k.y), max(k.z, k.w)) : obscura_orthographic_distance();
        if (abs(k.x + k.w - k.y - k.z) <= kPlanarity * scale) {
            float kk = mix(mix(k.x, k.y, t.x), mix(k.z, k.w, t.x), t.y);
            return perspective ? 1.0 / kk : kk;
        }
    }
    ivec2 nearest = clamp(ivec2(floor(point)), ivec2(0), hi);
    point = vec2(nearest) + 0.5;
    return texelFetch(u_depth, nearest, 0).r;
}

// The program is built per hull capacity (OBSCURA_LSAO_HULL_CAPACITY points): the shared memory a group
// takes decides how many groups an SM holds, and a small hull (the default) leaves room for many.
#ifndef OBSCURA_LSAO_HULL_CAPACITY
#error "OBSCURA_LSAO_HULL_CAPACITY must be defined"
#endif
const int kCapacity = OBSCURA_LSAO_HULL_CAPACITY;
// The tangent strategy (1-3) is compiled in too: strategy 3 never reads the normals.
#ifndef OBSCURA_LSAO_TANGENT_STRATEGY
#error "OBSCURA_LSAO_TANGENT_STRATEGY must be defined"
#endif
// Whether lines are cut into segments with warm-ups (compiled in: whole lines, the default on CPU
// rasterisers, carry none of the warm-up code, whose loops a CPU rasteriser would still step through).
#ifndef OBSCURA_LSAO_SEGMENTS
#error "OBSCURA_LSAO_SEGMENTS must be defined"
#endif

// Where the hull lives (compiled in). CPU rasterisers (OBSCURA_CPU_RASTERISER 1) reach shared memory one
// invocation at a time and a private array with vector gathers (llvmpipe, 1280x720, r = 10 m: sweep 61 ms
// with the shared hull, 52 ms with the private one). GPUs keep it in shared memory, slot-major: the
// invocations of a warp reading the same slot touch consecutive words, each invocation's slots fall in its
// own banks.
#if OBSCURA_CPU_RASTERISER
vec2 g_hull[kCapacity];
vec2 hull_load(int slot) { return g_hull[slot]; }
void hull_store(int slot, vec2 p) { g_hull[slot] = p; }
#else
shared vec2 s_hull[kCapacity * OBSCURA_LSAO_SWEEP_GROUP];

int hull_slot(int i) { return i * OBSCURA_LSAO_SWEEP_GROUP + int(gl_LocalInvocationID.x); }
vec2 hull_load(int slot) { return s_hull[hull_slot(slot)]; }
void hull_store(int slot, vec2 p) { s_hull[hull_slot(slot)] = p; }
#endif

// Ring index of start + i (i < capacity): a compare instead of an integer division, which CPU rasterisers
// cannot vectorise.
int ring(int start_plus_i) { return start_plus_i >= kCapacity ? start_plus_i - kCapacity : start_plus_i; }

// Steps of the warm-up before the segment [begin, end) of `line`: enough that the warm-up distance separates
// the segment's nearest receiver from anything before the warm-up; all of the line before it if the
// distance is unbounded (infinite: the quotient below, held to `begin`).
int warmup_steps(LsaoLine line, int begin, int end) {
    float distance = lsao.warmup.x;
    if (distance < 0.0 || begin == 0) return begin;
    if (distance == 0.0) return 0;
    // Eight fetches in flight at a time (the segment's last sample repeats past its end): a loop that used
    // each fetch before issuing the next waited a full memory latency per sample.
    float nearest = OBSCURA_SKY_DEPTH;
    for (int i = begin; i < end; i += 8) {
        float d[8];
        for (int u = 0; u < 8; ++u) {
            vec2 point = lsao_sample_point(line, line.first_step + min(i + u, end - 1));
            // Clamped: a free pattern's point is unclamped (lsao_sample_point) and a float step can round onto the
            // texture's far edge, where texelFetch's result is undefined.
            d[u] = texelFetch(u_depth, clamp(ivec2(point), ivec2(0), depth_size.xy - 1), 0).r;
        }
        for (int u = 0; u < 8; ++u) nearest = min(nearest, d[u]);
    }
    if (obscura_is_sky(nearest)) return 0;  // no receiver
    vec2 first = lsao_sample_point(line, line.first_step + begin);
    vec2 step = line.step;
    // View-space length of one step at distance 1 (perspective) or at any distance (orthographic).
    float step_angle = length(obscura_view_position_at(first + step, 1.0) - obscura_view_position_at(first, 1.0));
    float scale = obscura_is_perspective() ? nearest : 1.0;
    // Compared in float before converting: a quotient past the int range (a large radius, a tiny warm-up tolerance,
    // a receiver near the eye) converts to an undefined value (INT_MIN on x86).
    return int(min(float(begin), ceil(distance / max(step_angle * scale, 1e-20))));
}

// The invocation's line (of direction g_direction, one per workgroup layer), its first value's index, its
// slice frame and the part of it that it writes.
LsaoLine g_line;
int g_direction, g_offset;
vec3 g_b0, g_a, g_b;
int g_begin, g_end;

// View positions are affine in the depth and, at a fixed depth, in the texel position; so are their slice
// coordinates: pk = at0 + depth (at1 - at0), at_w = g_at[w] + g_slope[w] (point - g_origin). Ten FMAs per
// step instead of a deprojection and two projections.
vec2 g_origin;
vec2 g_at[2];
mat2 g_slope[2];
vec2 g_eye;            // perspective: the eye in slice coordinates
vec2 g_ortho_zenith;   // orthographic: the direction towards the eye in the slice

void setup_slice(vec2 origin) {
    lsao_slice_frame(origin, lsao.directions[g_direction].xy, g_b0, g_a, g_b);
    g_origin = origin;
    for (int w = 0; w < 2; ++w) {
        float depth = float(w);
        vec2 at = lsao_in_slice(obscura_view_position_at(origin, depth), g_b0, g_a, g_b);
        vec2 x = lsao_in_slice(obscura_view_position_at(origin + vec2(1.0, 0.0), depth), g_b0, g_a, g_b);
        vec2 y = lsao_in_slice(obscura_view_position_at(origin + vec2(0.0, 1.0), depth), g_b0, g_a, g_b);
        g_at[w] = at;
        g_slope[w] = mat2(x - at, y - at);
    }
    g_eye = lsao_in_slice(vec3(0.0), g_b0, g_a, g_b);
    g_ortho_zenith = normalize(vec2(g_a.z, g_b.z));
}

vec2 slice_point(vec2 point, float depth) {
    vec2 q = point - g_origin;
    vec2 at0 = g_at[0] + g_slope[0] * q;
    vec2 at1 = g_at[1] + g_slope[1] * q;
    return at0 + depth * (at1 - at0);
}

// Unit vector towards the eye from the slice point pk.
vec2 slice_zenith(vec2 pk) { return obscura_is_perspective() ? normalize(g_eye - pk) : g_ortho_zenith; }
// The hull: hull_load(ring(g_start + i)), i < g_count, top last; the top and the point below it also in
// registers (most steps pop nothing).
int g_start = 0, g_count = 0;
vec2 g_top_point = vec2(0.0), g_below_point = vec2(0.0);
uint g_pops = 0u, g_dropped = 0u;

// Algorithm 1's body for step i at `point` with `depth`: returns the value for the receiver there (pops,
// then the top's obscurance), then pushes the point.
float sweep_step(int i, vec2 point, float depth) {
    float value = OBSCURA_LSAO_NO_OCCLUDER;
    if (!obscura_is_sky(depth)) {
        const int strategy = OBSCURA_LSAO_TANGENT_STRATEGY;
        float fixed_sin_t = lsao.falloff.z;
        vec2 pk = slice_point(point, depth);
        vec2 u = slice_zenith(pk);
        // Strategy 3 fixes the tangent for both uses; 1 uses the receiver's for both, 2 only for the occlusion.
        float real_sin_t = fixed_sin_t;
        if (strategy != 3) {
            vec3 n = obscura_decode_normal(texelFetch(u_normals, clamp(ivec2(point), ivec2(0), depth_size.xy - 1), 0).xy);
            real_sin_t = lsao_receiver_sin_t_3d(n, obscura_towards_eye(obscura_view_position_at(point, depth)), g_a);
        }
        float hull_sin_t = strategy == 1 ? real_sin_t : fixed_sin_t;
        float occlusion_sin_t = strategy == 3 ? fixed_sin_t : real_sin_t;
#if OBSCURA_LSAO_EXACT_SWEEP
        // Validation: every earlier sample of the whole line, read again.
        bool any = false;
        float best = occlusion_sin_t;
        for (int e = 0; e < i; ++e) {
            vec2 q = lsao_sample_point(g_line, g_line.first_step + e);
            float qd = sample_depth(q);
            if (obscura_is_sky(qd)) continue;
            vec2 qk = slice_point(q, qd);
            best = max(best, lsao_occlusion(qk - pk, u, occlusion_sin_t));
            any = true;
        }
        if (any) value = best;
#else
        // The top's (occlusion, sin h) carries over when the one below becomes the top.
        vec2 top = g_count > 0 ? lsao_occlusion_and_sin_h(g_top_point - pk, u, hull_sin_t) : vec2(0.0);
#if OBSCURA_CPU_RASTERISER
        // CPU rasterisers run a loop's body for all lanes while any lane pops: the shortest loop is the
        // fastest (llvmpipe: the GPU form below takes 10 % longer).
        while (g_count >= 2) {
            g_below_point = hull_load(ring(g_start + g_count - 2));
            vec2 below = lsao_occlusion_and_sin_h(g_below_point - pk, u, hull_sin_t);
            if (!(top.x < below.x && top.y < below.y)) break;
            top = below;
            g_top_point = g_below_point;
            --g_count;
            ++g_pops;
        }
#else
        // GPUs keep the point below the top in a register too, so a step that pops nothing (most) reads no
        // hull memory (the H100: 6 % off the sweep).
        if (g_count >= 2) {
            vec2 below = lsao_occlusion_and_sin_h(g_below_point - pk, u, hull_sin_t);
            while (top.x < below.x && top.y < below.y) {
                top = below;
                g_top_point = g_below_point;
                --g_count;
                ++g_pops;
                if (g_count < 2) break;
                g_below_point = hull_load(ring(g_start + g_count - 2));
                below = lsao_occlusion_and_sin_h(g_below_point - pk, u, hull_sin_t);
            }
        }
#endif
        if (g_count > 0) value = strategy == 2 ? lsao_occlusion(g_top_point - pk, u, occlusion_sin_t) : top.x;
        if (g_count == kCapacity) {
            g_start = ring(g_start + 1);
            --g_count;
            ++g_dropped;
        }
        hull_store(ring(g_start + g_count), pk);
        g_below_point = g_top_point;
        g_top_point = pk;
        ++g_count;
#endif
        // With the receiver's own tangent for both uses (strategy 1) the value stored is the obscurance above that
        // tangent, sin h - sin t clamped and weighted, rather than the horizon: the gather takes a nearby sample's
        // value for its pixel, and across a crease or an edge that sample's tangent is another surface's (see
        // lsao_gather.comp).
        if (strategy == 1 && value < 0.5 * OBSCURA_LSAO_NO_OCCLUDER) value -= occlusion_sin_t;
    }
    return value;
}

// The warm-up's last steps, swept at full resolution whatever its stride.
const int kDenseWarmup = 16;

// Sample i of the line, clamped to the segment's last (blocks may run past it).
vec2 block_point(int i) { return lsao_sample_point(g_line, g_line.first_step + min(i, g_end - 1)); }

void main() {
    g_direction = int(gl_WorkGroupID.z);
    int index = int(gl_GlobalInvocationID.x);
    if (index >= int(lsao.coverage[g_direction].w)) return;
    g_line = lsao_line(g_direction, index);
    g_offset = g_line.value_base + g_line.first_step;
    int segment_steps = lsao.sweep.y;
    g_begin = segment_steps > 0 ? int(gl_GlobalInvocationID.y) * segment_steps : 0;
    if (g_begin >= g_line.steps) return;
    g_end = segment_steps > 0 ? min(g_line.steps, g_begin + segment_steps) : g_line.steps;
    setup_slice(lsao_sample_point(g_line, g_line.first_step));

    // Blocks of 8 samples whose depths are all fetched before the first is used: the hull's loop-carried
    // work cannot hide a fetch's latency, eight fetches in flight can.
    int dense_begin = 0, strided_steps = 0;
#if OBSCURA_LSAO_SEGMENTS
    // The warm-up's far part at a stride (the falloff leaves far occluders little weight, and a coarse hull of
    // them casts nearly the same), ending kDenseWarmup steps before the segment, which are swept densely: the
    // segment's first receivers see their nearest occluders at full resolution. Blocks of 8 strided samples,
    // aligned to end at the dense part; samples before the warm-up's start are skipped.
    // The dense part starts on a multiple of 8, like the segment, so every block of the segment is one
    // aligned store of 8 halves.
    int warm_begin = g_begin - warmup_steps(g_line, g_begin, g_end);
    dense_begin = max(warm_begin, g_begin - kDenseWarmup) & ~7;
    int stride = max(lsao.sweep.x, 1);
    for (int base = dense_begin - ((dense_begin - warm_begin + 8 * stride - 1) / (8 * stride)) * 8 * stride;
         base < dense_begin; base += 8 * stride) {
        vec2 q[8];
        float qd[8];
        for (int u = 0; u < 8; ++u) {
            q[u] = block_point(max(base + u * stride, 0));
            qd[u] = sample_depth(q[u]);
        }
        for (int u = 0; u < 8; ++u) {
            if (base + u * stride < warm_begin) continue;
            sweep_step(base + u * stride, q[u], qd[u]);  // the value is not written
            ++strided_steps;
        }
    }
#endif
    // Written out rather than as loops over arrays: a compiler that does not unroll a loop around the
    // inlined step keeps the arrays in memory (llvmpipe's sweep took 23 % longer).
    for (int i = dense_begin; i < g_end; i += 8) {
        vec2 p0 = block_point(i), p1 = block_point(i + 1), p2 = block_point(i + 2), p3 = block_point(i + 3);
        vec2 p4 = block_point(i + 4), p5 = block_point(i + 5), p6 = block_point(i + 6), p7 = block_point(i + 7);
        float d0 = sample_depth(p0), d1 = sample_depth(p1), d2 = sample_depth(p2), d3 = sample_depth(p3);
        float d4 = sample_depth(p4), d5 = sample_depth(p5), d6 = sample_depth(p6), d7 = sample_depth(p7);
        // Past the segment's end (its last block) the padding is 0.
        float v0 = sweep_step(i, p0, d0);
        float v1 = i + 1 < g_end ? sweep_step(i + 1, p1, d1) : 0.0;
        float v2 = i + 2 < g_end ? sweep_step(i + 2, p2, d2) : 0.0;
        float v3 = i + 3 < g_end ? sweep_step(i + 3, p3, d3) : 0.0;
        float v4 = i + 4 < g_end ? sweep_step(i + 4, p4, d4) : 0.0;
        float v5 = i + 5 < g_end ? sweep_step(i + 5, p5, d5) : 0.0;
        float v6 = i + 6 < g_end ? sweep_step(i + 6, p6, d6) : 0.0;
        float v7 = i + 7 < g_end ? sweep_step(i + 7, p7, d7) : 0.0;
        if (i >= g_begin) {
            lsao_values[(g_offset + i) >> 3] = uvec4(packHalf2x16(vec2(v0, v1)), packHalf2x16(vec2(v2, v3)),
                                                     packHalf2x16(vec2(v4, v5)), packHalf2x16(vec2(v6, v7)));
        }
    }
    // Counters for tests only: thousands of invocations adding to one address would serialise.
    if ((lsao.config.w & OBSCURA_LSAO_FLAG_STATS) != 0) {
        atomicAdd(lsao_stats[0], uint(g_end - dense_begin + strided_steps));
        atomicAdd(lsao_stats[1], g_pops);
        atomicAdd(lsao_stats[2], g_dropped);
    }
}
