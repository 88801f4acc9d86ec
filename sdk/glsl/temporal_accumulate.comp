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
// The history texel packs visibility, age (frames, 0: none) and the linear depth it was computed at (rgba16f);
// with bent normals (OBSCURA_TEMPORAL_BENT_NORMALS) a second history holds visibility and the bent normal, rotated
// from the previous view into this one.
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
layout(binding = OBSCURA_IMAGE_OUT0, rgba16f) writeonly uniform image2D u_next;
#if OBSCURA_TEMPORAL_BENT_NORMALS
layout(binding = OBSCURA_UNIT_BENT_SOURCE) uniform sampler2D u_bent_source;
layout(binding = OBSCURA_UNIT_BENT_HISTORY) uniform sampler2D u_bent_history;
layout(binding = OBSCURA_IMAGE_OUT1, rgba16f) writeonly uniform image2D u_bent_next;
#endif

mat4 columns(vec4 c[4]) { return mat4(c[0], c[1], c[2], c[3]); }

// Gathers return the 2x2 block at floor(uv * size - 0.5) as (i0, j1), (i1, j1), (i1, j0), (i0, j0) in x, y, z, w:
// the block's texel (o.x, o.y), o in {0, 1}^2.
float block_texel(vec4 gathered, ivec2 o) {
    return o.y == 0 ? (o.x == 0 ? gathered.w : gathered.z) : (o.x == 0 ? gathered.x : gathered.y);
}

// The history's visibility through a Catmull-Rom filter at fraction `f` past texel `base`: the 4x4 kernel less its
// corners (renormalised), from the 2x2 block at base (`centre`, gathered already) and the four blocks beside it, one
// gather each (instead of five bilinear reads of all four channels: the filter's taps are the same). A bilinear read
// of a moving history blurs it a little every frame: at 8 frames about a texel, which smeared contact shadows; the
// cubic keeps them.
float catmull_rom_history(ivec2 base, vec2 f, vec4 centre) {
    vec2 texel = 1.0 / vec2(depth_size.xy);
    vec2 corner = vec2(base);  // the centre block's gather position is corner + 1
    vec4 left = textureGather(u_history, (corner + vec2(0.0, 1.0)) * texel, 0);   // x in [base - 1, base]
    vec4 right = textureGather(u_history, (corner + vec2(2.0, 1.0)) * texel, 0);  // x in [base + 1, base + 2]
    vec4 below = textureGather(u_history, (corner + vec2(1.0, 0.0)) * texel, 0);  // y in [base - 1, base]
    vec4 above = textureGather(u_history, (corner + vec2(1.0, 2.0)) * texel, 0);  // y in [base + 1, base + 2]
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    vec2 w3 = f * f * (-0.5 + 0.5 * f);
    // Rows base and base + 1: all four columns; rows base - 1 and base + 2: the middle two.
    float row0 = w0.x * left.w + w1.x * centre.w + w2.x * centre.z + w3.x * right.z;
    float row1 = w0.x * left.x + w1.x * centre.x + w2.x * centre.y + w3.x * right.y;
    float sum = w1.y * row0 + w2.y * row1 + w0.y * (w1.x * below.w + w2.x * below.z) +
                w3.y * (w1.x * above.x + w2.x * above.y);
    float weight = (w0.y + w3.y) * (w1.x + w2.x) + (w1.y + w2.y) * (w0.x + w1.x + w2.x + w3.x);
    return sum / weight;
}

void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    float depth = texelFetch(u_linear_depth, p, 0).r;
    float current = texelFetch(u_source, p, 0).r;
#if OBSCURA_TEMPORAL_BENT_NORMALS
    vec3 current_bent = texelFetch(u_bent_source, p, 0).gba;
#endif
    if (obscura_is_sky(depth)) {  // sky keeps no history
        imageStore(u_next, p, vec4(current, 0.0, depth, 0.0));
#if OBSCURA_TEMPORAL_BENT_NORMALS
        imageStore(u_bent_next, p, vec4(current, current_bent));
#endif
        return;
    }

    // 3. The neighbourhood's mean and deviation (this frame): two gathers, at p + 0.25 and p + 1.25 texels, whose
    // 2x2 footprints [p-1, p]^2 and [p, p+1]^2 make the 3x3 window less its corners (+1, -1) and (-1, +1), centre
    // once. Gathers halve the texture reads of the 3x3's nine fetches.
    // Only the output rectangle holds this frame's AO: at its edges the window moves inwards to stay inside it.
    ivec2 rect_last = output_rect.xy + output_rect.zw - 1;
    ivec2 window = clamp(p, min(output_rect.xy + 1, rect_last), max(rect_last - 1, output_rect.xy));
    vec2 texel = 1.0 / vec2(depth_size.xy);
    vec4 g00 = textureGather(u_source, (vec2(window) + 0.25) * texel, 0);
    vec4 g11 = textureGather(u_source, (vec2(window) + 1.25) * texel, 0);
    // A rectangle under 3 texels on an axis leaves texels of the footprints outside it (never written: any value,
    // NaN included): those count as the pixel's own value, chosen by selection so that nothing of theirs is left.
    ivec2 rect_end = output_rect.xy + output_rect.zw;
    ivec2 before = window - 1, after = window + 1;
    bvec4 inside00 = bvec4(all(greaterThanEqual(ivec2(before.x, window.y), output_rect.xy)),  // x: (-1, 0)
                           true,                                                                 // y: (0, 0)
                           all(greaterThanEqual(ivec2(window.x, before.y), output_rect.xy)),  // z: (0, -1)
                           all(greaterThanEqual(before, output_rect.xy)));                      // w: (-1, -1)
    bvec4 inside11 = bvec4(all(lessThan(ivec2(window.x, after.y), rect_end)),                   // x: (0, 1)
                           all(lessThan(after, rect_end)),                                      // y: (1, 1)
                           all(lessThan(ivec2(after.x, window.y), rect_end)),                   // z: (1, 0)
                           true);                                                                // w: (0, 0)
    g00 = mix(vec4(current), g00, inside00);
    g11 = mix(vec4(current), g11, inside11);
    vec3 c = vec3(g11.z, g11.x, g11.y);  // (1, 0), (0, 1), (1, 1); g11.w is the centre, g00.y again
    float sum = dot(g00, vec4(1.0)) + dot(c, vec3(1.0));
    float sum_sq = dot(g00, g00) + dot(c, c);
    float mean = sum * (1.0 / 7.0);
    float deviation = sqrt(max(0.0, sum_sq * (1.0 / 7.0) - mean * mean));

    // 1. Where the pixel's point was.
    vec3 position = obscura_view_position(p, depth);
    vec3 normal = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_IDENTITY
    // A static camera (the same view-projection: its own variant, since CPU rasterisers run every lane through
    // every branch) reads its own texel: no matrix work, one history texel, no cubic.
    vec3 previous_position = position, previous_normal = normal;
    vec2 previous_pixel = vec2(p) + 0.5;
    const int kTaps = 1;
#else
    mat4 reprojection = columns(temporal.reprojection);
    mat3 rotation = mat3(reprojection);  // rigid up to the projections' jitter
    vec4 previous_h = reprojection * vec4(position, 1.0);
    vec3 previous_position = previous_h.xyz / previous_h.w;
    vec3 previous_normal = normalize(rotation * normal);
    vec2 previous_pixel;
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_MOTION
    // At reduced resolution the host's vector is read at the host's texel (p << k) and scaled to reduced texels.
    previous_pixel = vec2(p) + 0.5 + texelFetch(u_motion, p << resolution.x, 0).xy * temporal.motion.xy;
#else
    vec4 clip = columns(temporal.previous_clip) * vec4(position, 1.0);
    previous_pixel = (clip.xy / clip.w * 0.5 + 0.5) * vec2(depth_size.xy);
#endif
    const int kTaps = 4;
#endif

    // 2. The history's texels that lie on the point's plane, bilinearly weighted: the 2x2 block at base, gathered
    // (visibility, age, depth).
    vec2 f = previous_pixel - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    vec2 cubic_fraction = t;
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_IDENTITY
    vec4 own_texel = texelFetch(u_history, base, 0);  // the one tap: a fetch reads its three channels at once
#else
    vec2 block_at = (vec2(base) + 1.0) / vec2(depth_size.xy);
    vec4 block_visibility = textureGather(u_history, block_at, 0);
    vec4 block_age = textureGather(u_history, block_at, 1);
    vec4 block_depth = textureGather(u_history, block_at, 2);
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
    float tolerance = temporal.params.z * length(previous_position);
    int valid_taps = 0;
    if (temporal.config.x != 0) {
        for (int i = 0; i < kTaps; ++i) {
            ivec2 o = ivec2(i & 1, i >> 1);
            float w = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y);
            ivec2 q = base + o;
            // Only the output rectangle was written (a change of it starts a new history).
            if (w <= 0.0 || any(lessThan(q, output_rect.xy)) || any(greaterThanEqual(q, output_rect.xy + output_rect.zw))) continue;
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_IDENTITY
            vec3 h = own_texel.xyz;
#else
            vec3 h = vec3(block_texel(block_visibility, o), block_texel(block_age, o), block_texel(block_depth, o));
#endif
            if (!(h.y >= 1.0) || obscura_is_sky(h.z)) continue;  // no history there
            float plane_distance = abs(dot(obscura_view_position(q, h.z) - previous_position, previous_normal));
            if (!(plane_distance <= tolerance)) continue;  // another surface (disoccluded or moved), or not finite
            history += w * h.x;
            age += w * h.y;
            weight_sum += w;
            ++valid_taps;
            history_low = min(history_low, h.x);
            history_high = max(history_high, h.x);
#if OBSCURA_TEMPORAL_BENT_NORMALS
            history_bent += w * texelFetch(u_bent_history, q, 0).gba;
#endif
        }
    }
    float result = current, new_age = 1.0;
#if OBSCURA_TEMPORAL_BENT_NORMALS
    vec3 result_bent = current_bent;
#endif
    // Less than a texel's worth of support (a quarter of the bilinear weight): start anew.
    if (weight_sum >= 0.25) {
        // Between texels, with all four on the pixel's surface: the cubic read instead of the bilinear one (its
        // wider footprint can reach another surface at an edge; the clamp below bounds what that brings).
        // The cubic's 4x4 texels must lie in the output rectangle, the only part of the history that was written.
#if OBSCURA_TEMPORAL_REPROJECT != OBSCURA_TEMPORAL_REPROJECT_IDENTITY
        bool cubic_inside = all(greaterThanEqual(base - 1, output_rect.xy)) &&
                            all(lessThanEqual(base + 2, output_rect.xy + output_rect.zw - 1));
        // Held within the four texels' range: the cubic's outer ring may lie on another surface (a silhouette one
        // texel away), and its negative lobes overshoot at steps.
        if (valid_taps == 4 && cubic_inside) {
            history = clamp(catmull_rom_history(base, cubic_fraction, block_visibility), history_low, history_high) *
                      weight_sum;
        }
#endif
        // The box holds the pixel's own value too: an image equal to its history is kept as it is.
        float spread = temporal.params.y * deviation;
        history = clamp(history / weight_sum, min(mean - spread, current), max(mean + spread, current));
        new_age = min(floor(age / weight_sum + 0.5) + 1.0, temporal.params.x);
        float alpha = 1.0 / new_age;
        result = mix(history, current, alpha);
#if OBSCURA_TEMPORAL_BENT_NORMALS
        // The previous view's bent normal in this view: the inverse rotation.
#if OBSCURA_TEMPORAL_REPROJECT == OBSCURA_TEMPORAL_REPROJECT_IDENTITY
        vec3 previous_bent = history_bent;
#else
        vec3 previous_bent = transpose(rotation) * history_bent;
#endif
        float previous_length = length(previous_bent);
        if (previous_length > 0.0) result_bent = normalize(mix(previous_bent / previous_length, current_bent, alpha));
#endif
    }
    imageStore(u_next, p, vec4(result, new_age, depth, 0.0));
#if OBSCURA_TEMPORAL_BENT_NORMALS
    imageStore(u_bent_next, p, vec4(result, result_bent));
#endif
}
