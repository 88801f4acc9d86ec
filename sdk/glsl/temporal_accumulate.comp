// Temporal accumulation, after every method's reconstruction: this frame's AO blended into the view's history.
// Per pixel of the output rectangle:
//   1. reproject: the pixel's surface point in the previous frame, from the two view-projections (through the
//      depth) or the host's motion vectors; a static camera reads the same texel (compiled in: OBSCURA_TEMPORAL_REPROJECT);
//   2. read the history bilinearly, each of the 4 texels only if it lies on the pixel's tangent plane as the
//      previous frame saw it (its stored depth within plane_tolerance of the plane, relative to the distance):
//      disocclusions and moving edges fall out; a reprojection within 1/256 texel of a centre reads that texel
//      alone, so a static camera does not blur its history frame after frame;
//   3. clamp the history to this frame's neighbourhood (7 texels), mean +- clamp * standard deviation, which bounds
//      ghosting where the AO changed under a surface that did not (a moving object's contact shadow);
//   4. blend with weight 1 / age, age = min(history age + 1, max frames): a static pixel is the mean of its last
//      frames, exponential once it reaches max_frames.
// The history texel (rg32f) holds the visibility and the linear depth it was computed at, with the age (frames) in
// the depth's 6 lowest mantissa bits: one gather reads age and depth for the 2x2 block, and 32-bit floats need no
// conversion on CPU rasterisers. With bent normals (OBSCURA_TEMPORAL_BENT_NORMALS) a second history (rgba32f) holds
// visibility and the bent normal, rotated from the previous view into this one.
// With OBSCURA_TEMPORAL_TARGET (full resolution, no debug view) the pass also writes the visibility into the host's
// target (OUTPUT_FORMAT, OUTPUT_MULTIPLY: composite.comp's write) at image unit OUT2, in the composite's place: the
// composite would only copy the history's visibility there.
#define OBSCURA_TEMPORAL_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"

layout(local_size_x = OBSCURA_TEMPORAL_GROUP_X, local_size_y = OBSCURA_TEMPORAL_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_linear_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_source;
layout(binding = OBSCURA_UNIT_HISTORY) uniform sampler2D u_history;
layout(binding = OBSCURA_UNIT_MOTION) uniform sampler2D u_motion;
layout(binding = OBSCURA_IMAGE_OUT0, rg32f) writeonly uniform image2D u_next;
#if OBSCURA_TEMPORAL_TARGET
#define OBSCURA_OUTPUT_IMAGE OBSCURA_IMAGE_OUT2
#include "common/output_target.glsl"
#endif
#if OBSCURA_TEMPORAL_BENT_NORMALS
layout(binding = OBSCURA_UNIT_BENT_SOURCE) uniform sampler2D u_bent_source;
layout(binding = OBSCURA_UNIT_BENT_HISTORY) uniform sampler2D u_bent_history;
layout(binding = OBSCURA_IMAGE_OUT1, rgba32f) writeonly uniform image2D u_bent_next;
#endif

mat4 columns(vec4 c[4]) { return mat4(c[0], c[1], c[2], c[3]); }

// The frame's visibility into the host's target, where the composite would have copied the history's (held to [0, 1]).
void write_target(ivec2 p, float visibility) {
#if OBSCURA_TEMPORAL_TARGET
    obscura_write_final_output(p, visibility);
#endif
}

// The history's second channel: the linear depth with its 6 lowest mantissa bits replaced by age - 1 (ages 1 to 64
// frames; the depth keeps a relative precision of 8e-6). Sky keeps its depth as it is (and no age: it is sky).
float pack_depth_age(float depth, float age) {
    return uintBitsToFloat((floatBitsToUint(depth) & ~63u) | uint(age - 1.0));
}
vec4 unpacked_depth(vec4 stored) { return uintBitsToFloat(floatBitsToUint(stored) & ~uvec4(63u)); }
vec4 unpacked_age(vec4 stored) { return vec4(floatBitsToUint(stored) & uvec4(63u)) + 1.0; }

// Lane-wise a && b (GLSL has no && on bvecs).
bvec4 both(bvec4 a, bvec4 b) { return bvec4(uvec4(a) & uvec4(b)); }

// The history's visibility through a Catmull-Rom filter at fraction `f` past texel `base`: the 4x4 kernel less its
// corners (renormalised), from the four 2x2 blocks of the 4x4 around base (quadrants[i]: the block whose lower-left
// texel is base - 1 + 2 (i & 1, i >> 1)), gathered already for the bilinear read. A bilinear read of a moving history
// blurs it a little every frame: at 8 frames about a texel, which smeared contact shadows; the cubic keeps them.
float catmull_rom_history(vec2 f, vec4 quadrants[4]) {
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    vec2 w3 = f * f * (-0.5 + 0.5 * f);
    // Rows base and base + 1: all four columns; rows base - 1 and base + 2: the middle two. Gather order per block:
    // x (0, 1), y (1, 1), z (1, 0), w (0, 0).
    float row0 = w0.x * quadrants[0].x + w1.x * quadrants[0].y + w2.x * quadrants[1].x + w3.x * quadrants[1].y;
    float row1 = w0.x * quadrants[2].w + w1.x * quadrants[2].z + w2.x * quadrants[3].w + w3.x * quadrants[3].z;
    float sum = w1.y * row0 + w2.y * row1 + w0.y * (w1.x * quadrants[0].z + w2.x * quadrants[1].w) +
                w3.y * (w1.x * quadrants[2].y + w2.x * quadrants[3].x);
    float weight = (w0.y + w3.y) * (w1.x + w2.x) + (w1.y + w2.y) * (w0.x + w1.x + w2.x + w3.x);
    return sum / weight;
}

void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    float depth = texelFetch(u_linear_depth, p, 0).r;
    // 3. (first, since it reads this frame's value too) The neighbourhood's mean and deviation (this frame): two
    // gathers, at p + 0.25 and p + 1.25 texels, whose 2x2 footprints [p-1, p]^2 and [p, p+1]^2 make the 3x3 window
    // less its corners (+1, -1) and (-1, +1), the pixel itself in both. Gathers halve the texture reads of the 3x3's
    // nine fetches, and the pixel's own value comes with them.
    vec2 texel = 1.0 / vec2(depth_size.xy);
    vec4 g00 = textureGather(u_source, (vec2(p) + 0.25) * texel, 0);
    vec4 g11 = textureGather(u_source, (vec2(p) + 1.25) * texel, 0);
    float current = g11.w;
#if OBSCURA_TEMPORAL_BENT_NORMALS
    vec3 current_bent = texelFetch(u_bent_source, p, 0).gba;
#endif
    // Sky keeps no history. GPUs store it and leave; CPU rasterisers, which run every lane through both sides, choose
    // it at the one store at the end (a store is among the pass's dearest steps there: 1.3 ms of 24 at 720p).
    bool sky = obscura_is_sky(depth);
#if !OBSCURA_CPU_RASTERISER
    if (sky) {
        imageStore(u_next, p, vec4(current, depth, 0.0, 0.0));
        write_target(p, current);
#if OBSCURA_TEMPORAL_BENT_NORMALS
        imageStore(u_bent_next, p, vec4(current, current_bent));
#endif
        return;
    }
#endif
    // Only the output rectangle holds this frame's AO: the footprints' texels outside it (never written: any value,
    // NaN included) count as the pixel's own value, chosen by selection so that nothing of theirs is left.
    ivec2 rect_end = output_rect.xy + output_rect.zw;
    ivec2 before = p - 1, after = p + 1;
    bvec4 inside00 = bvec4(before.x >= output_rect.x,                                     // x: (-1, 0)
                           true,                                                         // y: (0, 0)
                           before.y >= output_rect.y,                                     // z: (0, -1)
                           all(greaterThanEqual(before, output_rect.xy)));              // w: (-1, -1)
    bvec4 inside11 = bvec4(after.y < rect_end.y,                                          // x: (0, 1)
                           all(lessThan(after, rect_end)),                              // y: (1, 1)
                           after.x < rect_end.x,                                          // z: (1, 0)
                           true);                                                        // w: (0, 0)
    g00 = mix(vec4(current), g00, inside00);
    g11 = mix(vec4(current), g11, inside11);
    vec3 c = vec3(g11.z, g11.x, g11.y);  // (1, 0), (0, 1), (1, 1); g11.w is the centre, g00.y again
    // The moments of the differences from the pixel's own value: E[v^2] - E[v]^2 of the values themselves cancels
    // in 32-bit floats near 1 (a deviation of 3e-4 is 1e-7 of variance, one ulp of 1), and the clamp then pinned
    // unoccluded surfaces' histories to the current frame.
    vec4 d00 = g00 - current;
    vec3 dc = c - current;
    float offset = (dot(d00, vec4(1.0)) + dot(dc, vec3(1.0))) * (1.0 / 7.0);
    float mean = current + offset;
    float deviation = sqrt(max(0.0, (dot(d00, d00) + dot(dc, dc)) * (1.0 / 7.0) - offset * offset));

    // 1. Where the pixel's point was.
    vec3 position = obscura_view_position(p, depth);
    // The plane test compares squares (below), so the normal needs no normalising.
    vec3 normal = obscura_decode_normal_direction(texelFetch(u_normals, p, 0).xy);
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_IDENTITY
    // A static camera (the same view-projection: its own variant, since CPU rasterisers run every lane through
    // every branch) reads its own texel: no matrix work, one history texel, no cubic.
    vec3 previous_position = position, previous_normal = normal;
    vec2 previous_pixel = vec2(p) + 0.5;
#else
    mat4 reprojection = columns(temporal.reprojection);
    mat3 rotation = mat3(reprojection);  // rigid up to the projections' jitter
    vec4 previous_h = reprojection * vec4(position, 1.0);
    vec3 previous_position = previous_h.xyz * (1.0 / previous_h.w);
    vec3 previous_normal = rotation * normal;
    vec2 previous_pixel;
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_MOTION
    // At reduced resolution the host's vector is read at the host's texel (p << k) and scaled to reduced texels.
    previous_pixel = vec2(p) + 0.5 + texelFetch(u_motion, p << resolution.x, 0).xy * temporal.motion.xy;
#else
    // The previous frame's clip position: the projection (assumed unchanged between the frames, jitter aside)
    // applied to the point in the previous view, through its nonzero terms (m0, m5, m8, m9, m12, m13; w from m11,
    // m15) rather than a 4x4 product.
    vec2 clip_xy = proj_scale.xy * previous_h.xy + proj_scale.zw * previous_h.z + proj_offset.xy * previous_h.w;
    float clip_w = proj_depth.z * previous_h.z + proj_depth.w * previous_h.w;
    previous_pixel = (clip_xy * (0.5 / clip_w) + 0.5) * vec2(depth_size.xy);
    // A point behind the previous camera (or on its eye plane) was not in its image: clip_w's sign would mirror it
    // to a pixel on the opposite side. Far outside the rectangle, no tap has a history (NaN fails the test too).
    if (!(clip_w > 0.0)) previous_pixel = vec2(-1.0e9);
#endif
#endif

    // 2. The history's texels that lie on the point's plane, bilinearly weighted: the 2x2 block at base, gathered
    // (visibility, age, depth).
    vec2 f = previous_pixel - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    vec2 cubic_fraction = t;
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_IDENTITY
    vec2 own_packed = texelFetch(u_history, base, 0).xy;  // the one tap: a fetch reads both channels at once
    vec3 own_texel = vec3(own_packed.x, unpacked_age(own_packed.yyyy).x, unpacked_depth(own_packed.yyyy).x);
#else
    vec2 block_at = (vec2(base) + 1.0) * texel;
    // The visibility of the 4x4 around base in four gathers: the bilinear block in their middle, the cubic's ring.
    vec4 quadrants[4];
    for (int i = 0; i < 4; ++i) {
        quadrants[i] = textureGather(u_history, (vec2(base) + vec2(2 * (i & 1), 2 * (i >> 1))) * texel, 0);
    }
    vec4 block_visibility = vec4(quadrants[2].z, quadrants[3].w, quadrants[1].x, quadrants[0].y);
    vec4 block_packed = textureGather(u_history, block_at, 1);
    vec4 block_age = unpacked_age(block_packed), block_depth = unpacked_depth(block_packed);
#endif
    const float kSnap = 1.0 / 256.0;
    bvec2 snap_low = lessThan(t, vec2(kSnap)), snap_high = greaterThan(t, vec2(1.0 - kSnap));
    t = mix(t, vec2(0.0), snap_low);
    t = mix(t, vec2(1.0), snap_high);
    float history = 0.0, age = 0.0, weight_sum = 0.0;
    float history_low = 1.0, history_high = 0.0;  // the range of the valid texels' visibility
#if OBSCURA_TEMPORAL_BENT_NORMALS
    vec3 history_bent = vec3(0.0);
#endif
    // A texel is on the plane when |(X - P) . n| <= tolerance |P| |n|, compared squared: no square roots (|P|: the
    // orthographic tolerance distance under an orthographic projection, obscura_tolerance_distance).
    float reach_sq = obscura_is_perspective() ? dot(previous_position, previous_position)
                                              : obscura_orthographic_distance() * obscura_orthographic_distance();
    float limit_sq = temporal.params.z * temporal.params.z * reach_sq * dot(previous_normal, previous_normal);
    int valid_taps = 0;
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_IDENTITY
    // The one tap: the pixel's own texel (always inside the output rectangle).
    // Not sky (a history: age >= 1), and a finite visibility (a NaN kept would stay for good: clamp and min/max of
    // NaN are undefined in GLSL).
    if (temporal.config.x != 0 && !obscura_is_sky(own_texel.z) && obscura_is_finite(own_texel.x)) {
        float plane_distance = dot(obscura_view_position(p, own_texel.z) - previous_position, previous_normal);
        if (plane_distance * plane_distance <= limit_sq) {  // another surface (moved), or not finite, otherwise
            history = own_texel.x;
            age = own_texel.y;
            weight_sum = 1.0;
            valid_taps = 1;
            history_low = history_high = own_texel.x;
#if OBSCURA_TEMPORAL_BENT_NORMALS
            history_bent = texelFetch(u_bent_history, p, 0).gba;
#endif
        }
    }
#else
    // The four taps as the lanes of vec4s, in the gathers' order: texels (0, 1), (1, 1), (1, 0), (0, 0) of the block.
    const vec4 kTapX = vec4(0.0, 1.0, 1.0, 0.0), kTapY = vec4(1.0, 1.0, 0.0, 0.0);
    vec4 tap_weight = mix(vec4(1.0 - t.x), vec4(t.x), kTapX) * mix(vec4(1.0 - t.y), vec4(t.y), kTapY);
    // Only the output rectangle was written (a change of it starts a new history). Each tap is tested against both
    // of the rectangle's edges on each axis: a reprojection past an edge puts the whole block outside it (the
    // gathers then return the edge's texels, clamped, which are not this point's history).
    vec4 tap_column = vec4(base.x) + kTapX, tap_row = vec4(base.y) + kTapY;
    bvec4 inside = both(both(greaterThanEqual(tap_column, vec4(output_rect.x)), lessThan(tap_column, vec4(rect_end.x))),
                        both(greaterThanEqual(tap_row, vec4(output_rect.y)), lessThan(tap_row, vec4(rect_end.y))));
    // On the point's plane as the previous frame saw it: each texel's stored point within the tolerance of it.
    vec4 tap_x, tap_y;
    obscura_view_position_at4(vec4(base.x) + 0.5 + kTapX, vec4(base.y) + 0.5 + kTapY, block_depth, tap_x, tap_y);
    vec3 d = previous_normal;
    vec4 plane_distance = ((tap_x - previous_position.x) * d.x + (tap_y - previous_position.y) * d.y +
                              (-block_depth - previous_position.z) * d.z);
    // Gathers return the 2x2 block at floor(uv * size - 0.5) as (0, 1), (1, 1), (1, 0), (0, 0) in x, y, z, w. A texel
    // counts when it has a history (not sky: the age is then >= 1), lies on the plane, inside the rectangle, and has
    // bilinear weight; NaN fails every comparison.
    // A finite visibility too: a NaN kept would stay for good (clamp and min/max of NaN are undefined in GLSL).
    bvec4 finite = notEqual(floatBitsToUint(block_visibility) & uvec4(0x7f800000u), uvec4(0x7f800000u));
    bvec4 has_history = both(both(both(lessThan(block_depth, vec4(OBSCURA_SKY_THRESHOLD)), inside), finite),
                             both(lessThanEqual(plane_distance * plane_distance, vec4(limit_sq)),
                                  greaterThan(tap_weight, vec4(0.0))));
    if (temporal.config.x == 0) has_history = bvec4(false);
    // Selected, not multiplied: a texel outside the rectangle may hold anything, NaN included.
    vec4 used = mix(vec4(0.0), tap_weight, has_history);
    weight_sum = dot(used, vec4(1.0));
    history = dot(used, mix(vec4(0.0), block_visibility, has_history));
    age = dot(used, mix(vec4(0.0), block_age, has_history));
    valid_taps = int(dot(vec4(has_history), vec4(1.0)));
    vec4 low = mix(vec4(1.0), block_visibility, has_history), high = mix(vec4(0.0), block_visibility, has_history);
    history_low = min(min(low.x, low.y), min(low.z, low.w));
    history_high = max(max(high.x, high.y), max(high.z, high.w));
#if OBSCURA_TEMPORAL_BENT_NORMALS
    for (int i = 0; i < 4; ++i) {
        ivec2 q = base + ivec2(kTapX[i], kTapY[i]);
        if (has_history[i]) history_bent += used[i] * texelFetch(u_bent_history, q, 0).gba;
    }
#endif
#endif
    float result = current, new_age = 1.0;
#if OBSCURA_TEMPORAL_BENT_NORMALS
    vec3 result_bent = current_bent;
#endif
    // Less than a texel's worth of support (a quarter of the bilinear weight): start anew.
    if (weight_sum >= 0.25) {
        float inverse_weight = 1.0 / weight_sum;
        history *= inverse_weight;
        // Between texels, with all four on the pixel's surface: the cubic read instead of the bilinear one (its
        // wider footprint can reach another surface at an edge; the clamp below bounds what that brings).
        // The cubic's 4x4 texels must lie in the output rectangle, the only part of the history that was written.
#if OBSCURA_TEMPORAL_REPROJECT != OBSCURA_TEMPORAL_REPROJECT_IDENTITY
        bool cubic_inside = all(greaterThanEqual(base - 1, output_rect.xy)) &&
                            all(lessThanEqual(base + 2, output_rect.xy + output_rect.zw - 1));
        // Held within the four texels' range: the cubic's outer ring may lie on another surface (a silhouette one
        // texel away), and its negative lobes overshoot at steps.
        // The cubic's outer ring is not tested: a non-finite result keeps the bilinear read.
        float cubic = catmull_rom_history(cubic_fraction, quadrants);
        if (valid_taps == 4 && cubic_inside && obscura_is_finite(cubic)) {
            history = clamp(cubic, history_low, history_high);
        }
#endif
        // The box holds the pixel's own value too: an image equal to its history is kept as it is.
        float spread = temporal.params.y * deviation;
        float unclamped = history;
        history = clamp(history, min(mean - spread, current), max(mean + spread, current));
        new_age = min(floor(age * inverse_weight + 0.5) + 1.0, temporal.params.x);
        float alpha = 1.0 / new_age;
        result = mix(history, current, alpha);
#if OBSCURA_TEMPORAL_BENT_NORMALS
        // The previous view's bent normal in this view: the inverse rotation.
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_IDENTITY
        vec3 previous_bent = history_bent;
#else
        vec3 previous_bent = transpose(rotation) * history_bent;
#endif
        // The clamp moved the visibility's history towards this frame's value by the fraction `moved` of their
        // difference (the box holds the current value, so it lies between them): the result is then the current value
        // at weight 1 - (1 - moved)(1 - alpha). The bent normal is blended at the same weight, so that where the AO
        // changed under a surface (a moving object's contact shadow) its direction follows the visibility rather than
        // keeping (N - 1) / N of the history's.
        float moved = min(abs(unclamped - history) / max(abs(unclamped - current), 1e-6), 1.0);
        float bent_alpha = 1.0 - (1.0 - moved) * (1.0 - alpha);
        float previous_length = length(previous_bent);
        if (previous_length > 0.0) result_bent = normalize(mix(previous_bent / previous_length, current_bent, bent_alpha));
#endif
    }
    imageStore(u_next, p, sky ? vec4(current, depth, 0.0, 0.0) : vec4(result, pack_depth_age(depth, new_age), 0.0, 0.0));
    write_target(p, sky ? current : result);
#if OBSCURA_TEMPORAL_BENT_NORMALS
    imageStore(u_bent_next, p, sky ? vec4(current, current_bent) : vec4(result, result_bent));
#endif
}
