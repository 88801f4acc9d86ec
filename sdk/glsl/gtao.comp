// GTAO: ground-truth-based ambient occlusion (Jimenez, Wu, Pesce, Jarabo, "Practical Realtime Strategies for
// Accurate Indirect Occlusion", 2016), with the visibility bitmask of Therrien, Levesque, Gilet, "Screen Space
// Indirect Lighting with Visibility Bitmask" (2023) as the finite-thickness mode.
//
// Per pixel, S slices: the planes through the eye that contain a screen direction phi (rotated per pixel). In a
// slice, angles h are measured from the direction towards the eye V, positive towards the screen direction;
// the normal projected into the slice sits at angle n, and a direction h is weighted by cos(h - n) |sin h| (the
// cosine, times the measure of the sphere in slice coordinates). N steps to each side, at radius * ((j + jitter)
// / N)^power on screen, reconstruct occluders; where the steps are far apart they read the z pyramid (harmonic
// means of the geometry below, reconstructed at the block's centre: exact on planes).
//   horizon (OBSCURA_GTAO_MODE == 1): each side keeps its highest horizon cos h (the paper's eq. 3-4); the arc a
//     sample adds to it is occluded with the sample's falloff weight (HBAO's horizon split, cosine-weighted: an
//     occluder counts as the rays that would hit it at its distance do), every arc integrated in closed form
//     (eq. 10): G(h) = (cos n + 2 h sin n - cos(2h - n)) / 4 is the weight from 0 to |h| on either side.
//   bitmask (OBSCURA_GTAO_MODE == 2): a sample occupies the sectors between the angles of its front and of the
//     point `thickness` behind it, in `sectors` equal angles over the normal's half-circle [n - pi/2, n + pi/2];
//     the unoccupied runs of sectors are integrated with the same weight (W(b) - W(a), W the signed G). A sector
//     of a slab is occupied where the ray through it meets the slab at a falloff weight above a threshold drawn
//     per slice (each ray weighed by its own hit distance).
// Visibility is the sum of the slices' visible integrals (each times |projected normal| and the slice's angular
// density around V) over the sum of their unoccluded integrals (cos n + n sin n): the paper's estimator normalised
// by its own value for an unoccluded pixel, so a plane is exactly 1 at any slice count (the paper's per-slice sum
// is 1 only on average over slices).
// Bent normals (OBSCURA_GTAO_BENT_NORMALS): the cosine-weighted mean visible direction, integrated over the
// same arcs or runs in closed form (signed_direction), as the normal plus the visible minus the unoccluded arcs'
// integrals (exact on planes); the output is then rgba16f: visibility, bent normal xyz.
#define OBSCURA_GTAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/z_pyramid.glsl"

#ifndef OBSCURA_CPU_RASTERISER
#error "OBSCURA_CPU_RASTERISER must be defined"
#endif
#ifndef OBSCURA_GTAO_STEP_DISTRIBUTION
#error "OBSCURA_GTAO_STEP_DISTRIBUTION must be defined"
#endif

layout(local_size_x = OBSCURA_GTAO_GROUP_X, local_size_y = OBSCURA_GTAO_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_z;  // the z pyramid (mipmapped sampler)
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
#if OBSCURA_GTAO_BENT_NORMALS
layout(binding = OBSCURA_IMAGE_OUT0, rgba16f) writeonly uniform image2D u_ao;
#else
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_ao;
#endif

const float kHalfPi = 0.5 * OBSCURA_PI;

// acos to about 1e-4 rad (a polynomial in |x| times sqrt(1 - |x|), Abramowitz & Stegun 4.4.45's form): the
// library acos is a long polynomial on CPU rasterisers, and a slice needs three.
float fast_acos(float x) {
    float a = abs(x);
    float r = (((-0.0187293 * a + 0.0742610) * a - 0.2121144) * a + 1.5707288) * sqrt(max(0.0, 1.0 - a));
    return x < 0.0 ? OBSCURA_PI - r : r;
}

// The cosine-and-measure weight of the slice from angle 0 to angle h, G(h) = (cos n + 2 h sin n - cos(2h - n)) / 4,
// signed (negative for h < 0) so that the weight of [a, b] is signed_weight(b) - signed_weight(a).
float signed_weight(float h, float sin_n, float cos_n) {
    float g = 0.25 * (cos_n + 2.0 * h * sin_n - cos(2.0 * h) * cos_n - sin(2.0 * h) * sin_n);
    return h < 0.0 ? -g : g;
}

// acos c - c sqrt(1 - c^2), twice the area of the unit circle's segment beyond c (pi at c = -1, 0 at c = 1), to 6e-6:
// (1 - |c|)^1.5 times a cubic fitted to it (one square root, where acos and sin h took two), and pi minus that for
// c < 0.
float segment_area(float c) {
    // |c| is held to 1: a cosine from sqrt or inversesqrt may exceed it by an ulp on GPUs (2.5 ulp allowed), and
    // t sqrt(t) is NaN below 0.
    float a = min(abs(c), 1.0), t = 1.0 - a;
    float r = t * sqrt(t) * (((0.0112192 * a - 0.0518837) * a + 0.3558693) * a + 1.5708017);
    return c < 0.0 ? OBSCURA_PI - r : r;
}

// G(h) for the angle whose cosine is `c` on side `side_sign` (+1: h = acos c, -1: h = -acos c): the weight
// between 0 and h. With cos 2h = 2c^2 - 1 and sin 2h = 2 c sin h, G = (cos n (1 - c^2) +- sin n (h - c sin h)) / 2.
float side_weight(float c, float side_sign, float sin_n, float cos_n) {
    return 0.5 * (cos_n * (1.0 - c * c) + side_sign * sin_n * segment_area(c));
}

// The weighted direction integral from 0 to the angle h (given by its sine and cosine) in slice coordinates (along
// the screen direction, towards the eye), signed like signed_weight: d/dh = (sin h, cos h) cos(h - n) |sin h|.
vec2 signed_direction(float sin_h, float cos_h, float sin_n, float cos_n) {
    float s3 = sin_h * sin_h * sin_h, c3 = cos_h * cos_h * cos_h;
    vec2 f = vec2(cos_n * s3 + sin_n * (2.0 - 3.0 * cos_h + c3), cos_n * (1.0 - c3) + sin_n * s3) * (1.0 / 3.0);
    return sin_h < 0.0 ? -f : f;
}

// The per-pixel noise: a 4x4 ordered pattern (every 4x4 window holds each of its 16 values once, so the 5x5
// denoise averages 16 rotations), and a permutation of it for the step jitter, at the strata's centres, moved by the
// frame's offsets (mod 1: GtaoPass::constants says how). z: the base of the bitmask's occupancy draws, 7 times the
// jitter's stratum centre plus the frame's offset.
vec3 pixel_noise(ivec2 p) {
    ivec2 q = p & 3;
    int low = ((q.x & 1) ^ (q.y & 1)) << 1 | (q.y & 1);
    int high = (((q.x >> 1) ^ (q.y >> 1)) << 1) | (q.y >> 1);
    int index = (low << 2) | high;
    int jitter = (index * 5 + 3) & 15;
    vec2 strata = (vec2(float(index), float(jitter)) + 0.5) * (1.0 / 16.0);
    return vec3(fract(strata + gtao.noise.xy), strata.y * 7.0 + gtao.noise.z);
}

// The mask of sectors [0, n) for n in [0, 32], per lane: 32 is every sector (1u << 32 is undefined; clamping the
// shift to 31 once marked the top sector for every side + sample, and tilted planes came out 0.004 dark).
uvec2 sectors_below(uvec2 n) {
    return uvec2(n.x >= 32u ? 0xffffffffu : (1u << n.x) - 1u, n.y >= 32u ? 0xffffffffu : (1u << n.y) - 1u);
}

void store(ivec2 p, float visibility, vec3 bent) {
#if OBSCURA_GTAO_BENT_NORMALS
    imageStore(u_ao, p, vec4(visibility, bent));
#else
    imageStore(u_ao, p, vec4(visibility));
#endif
}

// The paper's multi-bounce fit (its eq. 12 fitted per albedo): visibility -> visibility with interreflections.
float multi_bounce(float v, float albedo) {
    float a = 2.0404 * albedo - 0.3324;
    float b = -4.7951 * albedo + 0.6417;
    float c = 2.7552 * albedo + 0.6903;
    return max(v, ((v * a + b) * v + c) * v);
}

void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;

    float depth = texelFetch(u_z, p, 0).r;
    bool count_taps = target_params.w == OBSCURA_DEBUG_VIEW_TAP_COUNT;
    // Sky, and a radius under a texel, get visibility 1 (and the normal; +z for sky). GPUs store it and leave; CPU
    // rasterisers, which run every lane through both sides of a branch, choose it at the pass's one store (a store
    // is among a pass's dearest steps there: the pass took 1-2 ms less of its 61 at 720p on llvmpipe).
    bool sky = obscura_is_sky(depth);
#if !OBSCURA_CPU_RASTERISER
    if (sky) {
        store(p, count_taps ? 0.0 : 1.0, vec3(0.0, 0.0, 1.0));
        return;
    }
#endif
    vec3 position = obscura_view_position(p, depth);
    vec3 normal = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);
    vec3 towards_eye = obscura_towards_eye(position);

    float radius_px = min(gtao.falloff.x * obscura_pixels_per_view_unit(depth), gtao.falloff.w);
    bool fully_visible = sky || radius_px < 1.0;  // the radius covers less than a texel: nothing to search
#if !OBSCURA_CPU_RASTERISER
    if (fully_visible) {
        store(p, count_taps ? 0.0 : 1.0, normal);
        return;
    }
#endif
    // Slices and steps are compiled in (GtaoPass::prepare): constant trip counts let compilers unroll the loops.
    const int slices = OBSCURA_GTAO_SLICES, steps = OBSCURA_GTAO_STEPS;
    int deepest = gtao.config.w;
    vec3 noise = pixel_noise(p);
    vec2 pixel_center = vec2(p) + 0.5;
    // Screen directions map to view-space directions through the projection's x/y scales.
    vec2 view_per_pixel = vec2(1.0) / (proj_scale.xy * vec2(depth_size.xy));
    // Slice s is the first one's direction turned by s pi / S: one rotation per slice instead of cos and sin.
    float phi = noise.x * (OBSCURA_PI / float(slices));
    vec2 dir = vec2(cos(phi), sin(phi));
    vec2 turn = gtao.rotation.xy;
#if OBSCURA_GTAO_MODE == OBSCURA_GTAO_MODE_BITMASK
    int sectors = gtao.config.z;
    uint all_sectors = sectors == 32 ? 0xffffffffu : (1u << uint(sectors)) - 1u;
    float sector_angle = OBSCURA_PI / float(sectors);
    // A slab lies along the eye ray of its sample. Every point of a slice sees the eye inside the slice, at
    // (0, eye_distance) from the receiver in the slice's (along, V) coordinates under perspective; an orthographic
    // eye ray is -V everywhere (eye_rays = 0). Arithmetic rather than a select per sample: the select measured 6 ms
    // slower at 720p on llvmpipe.
    bool perspective = obscura_is_perspective();
    float eye_distance = perspective ? length(position) : 0.0;
    float eye_rays = perspective ? gtao.thickness.x : 0.0;
    vec2 orthographic_back = vec2(0.0, perspective ? 0.0 : gtao.thickness.x);
#endif

    int taps_read = 0;
    float visible = 0.0, unoccluded = 0.0;
    vec3 bent = vec3(0.0);
    for (int s = 0; s < slices; ++s, dir = vec2(dir.x * turn.x - dir.y * turn.y, dir.x * turn.y + dir.y * turn.x)) {
        // The slice's axes: `along` is the screen direction in view space made orthogonal to V.
        vec3 line = vec3(normalize(dir * view_per_pixel), 0.0);
        vec3 across = line - towards_eye * dot(line, towards_eye);
        float across_length = length(across);
        // A point (almost) on the eye plane sees the screen direction along V: there is no slice plane (normalize
        // would return NaN).
        if (!(across_length > 1e-6)) continue;
        vec3 along = across / across_length;
        // The slices are spaced evenly on screen, but the estimator integrates over angles around V: off the
        // screen's centre the screen's directions crowd around V's tilt (up to 1.5x apart at 60 degrees' field of
        // view). Each slice is weighted by d(angle around V) / d(screen angle): |V.z| / |across|^2 for the
        // projection of the image plane onto the plane normal to V, times the pixel aspect's own stretch.
        vec2 view_dir = dir * view_per_pixel;
        // The pixel's area |a b| is unsigned: a mirrored projection (y flipped for render-to-texture, m5 < 0) made
        // every slice's weight negative, and the pass returned 1 everywhere with bent normals towards the occluders.
        float slice_density = abs(towards_eye.z) / (across_length * across_length) *
                              (abs(view_per_pixel.x * view_per_pixel.y) / dot(view_dir, view_dir));
        vec3 slice_normal = cross(along, towards_eye);
        // The normal projected into the slice: its length weighs the slice, its angle n from V.
        float n_along = dot(normal, along), n_view = dot(normal, towards_eye);
        float projected_length = sqrt(n_along * n_along + n_view * n_view);
        if (projected_length < 1e-4) continue;  // the slice is (almost) the receiver's tangent plane
        float cos_n = n_view / projected_length, sin_n = n_along / projected_length;
        float n = sin_n < 0.0 ? -fast_acos(cos_n) : fast_acos(cos_n);
        // Off-slice correction (as in hbao.comp): a texel beside the slice is moved back into it along the
        // receiver's tangent plane, exact for planes, so planes do not occlude themselves. The moved offset
        // delta + (V slope - slice_normal) dot(delta, slice_normal) lies in the slice: its coordinates are
        // dot(delta, along) and dot(delta, eye_axis), with eye_axis = V + slope slice_normal.
        float slope = dot(normal, slice_normal) / max(n_view, 0.1);
        vec3 eye_axis = towards_eye + slope * slice_normal;
        vec4 along_form = obscura_axis_form(along, position), eye_form = obscura_axis_form(eye_axis, position);
        // Per side, the tangent plane's cos h: cos(n + pi/2) = -sin n (side +), cos(n - pi/2) = sin n (side -).
        vec2 low_cos = vec2(-sin_n, sin_n);
#if OBSCURA_GTAO_MODE == OBSCURA_GTAO_MODE_BITMASK
        uint occupied = 0u;
        float lowest = n - kHalfPi;  // the angle of sector 0's lower edge
        // A sector is occupied when the ray through it meets a slab at a falloff weight above one threshold drawn
        // per slice: with the probability of its nearest hit's weight, as the REFERENCE weighs a ray (the denoise
        // averages the draws).
        float chance = fract(noise.z + float(s) * 0.6180339887);
        // The distance at which the falloff weight equals the chance: a ray is blocked by a sample's slab when it
        // hits the slab nearer than that.
        float reach = (chance - gtao.falloff.z) / gtao.falloff.y;
#else
        // Per side: the highest horizon so far (as cos h), G at it, and the weight of the occluded arc: each sample
        // that raises the horizon occludes the arc it adds with its falloff weight (the horizon-split estimator of
        // HBAO, here cosine-weighted), so an occluder counts as rays that hit it at its distance would.
        vec2 horizon_cos = low_cos;
        vec2 unoccluded_weight = vec2(side_weight(low_cos.x, 1.0, sin_n, cos_n), side_weight(low_cos.y, -1.0, sin_n, cos_n));
        vec2 horizon_weight = unoccluded_weight;
        vec2 occluded = vec2(0.0);
        // Bent normals: the occluded arcs' direction integrals (along, towards eye), side + in xy, side - in zw.
        vec4 occluded_bent = vec4(0.0);
#endif
        // Both sides in one step: the two samples share their distance and level (vec2 lanes: side +, side -).
        // No branch in the steps (CPU rasterisers run every lane through every branch): a sample outside the
        // texture, on the pixel itself or on sky gets weight 0.
        for (int j = 0; j < steps; ++j) {
            float u = (float(j) + noise.y) / float(steps);
#if OBSCURA_GTAO_STEP_DISTRIBUTION == 2
            float t = u * u * radius_px + 1.0;  // XeGTAO's distribution, without pow's exp2 and log2
#elif OBSCURA_GTAO_STEP_DISTRIBUTION == 1
            float t = u * sqrt(u) * radius_px + 1.0;  // the default, u^1.5
#else
            float t = pow(u, gtao.thickness.z) * radius_px + 1.0;
#endif
            // One level down per doubling of the step's distance past 2^mip_offset pixels.
            int m = clamp(findMSB(int(t * gtao.rotation.z)), 0, deepest);
            ivec2 level_last = max(depth_size.xy >> m, ivec2(1)) - 1;
            vec2 cos_h, weight, back_cos, lateral;
            bvec2 usable;
            for (int side = 0; side < 2; ++side) {  // unrolled by the compilers: constant trip count
                ivec2 unclamped = ivec2(floor(pixel_center + dir * (side == 0 ? t : -t)));
                ivec2 q = clamp(unclamped, ivec2(0), depth_size.xy - 1);
                ivec2 texel = min(q >> m, level_last);
                float z = texelFetch(u_z, texel, m).r;
                bool inside = unclamped == q && q != p;
                bool valid = inside && !obscura_is_sky(z);
                taps_read += inside ? 1 : 0;
                // The pyramid holds harmonic means (perspective) or plain means (orthographic) of the geometry below,
                // exact at the block's centre on planes.
                vec2 origin = obscura_level_texel_origin(texel, m, OBSCURA_MIP_FILTER_HARMONIC_MEAN_OF_GEOMETRY);
                float sample_depth = valid ? z : depth, sample_w = obscura_clip_w(sample_depth);
                // The sample relative to the pixel, moved into the slice.
                float slice_x = obscura_along_axis(along_form, origin, sample_depth, sample_w);
                float slice_y = obscura_along_axis(eye_form, origin, sample_depth, sample_w);
                float distance_sq = max(slice_x * slice_x + slice_y * slice_y, 1e-30);
                float inverse_distance = inversesqrt(distance_sq);
                // The falloff: full weight up to radius (1 - range), fading to 0 at the radius.
                float w = clamp(distance_sq * inverse_distance * gtao.falloff.y + gtao.falloff.z, 0.0, 1.0);
                weight[side] = valid ? w : 0.0;
                usable[side] = valid;
                lateral[side] = abs(slice_x);
                cos_h[side] = slice_y * inverse_distance;
#if OBSCURA_GTAO_MODE == OBSCURA_GTAO_MODE_BITMASK
                // The point `thickness` behind the sample (as moved into the slice), away from the eye: in slice
                // coordinates, without the 3D eye ray's normalisation.
                vec2 from_eye = vec2(slice_x, slice_y - eye_distance);
                vec2 back = vec2(slice_x, slice_y) - orthographic_back +
                            from_eye * (eye_rays * inversesqrt(max(dot(from_eye, from_eye), 1e-30)));
                back_cos[side] = back.y * inversesqrt(max(dot(back, back), 1e-30));
#endif
            }
#if OBSCURA_GTAO_MODE == OBSCURA_GTAO_MODE_BITMASK
            vec2 front_h = vec2(fast_acos(cos_h.x), -fast_acos(cos_h.y));
            vec2 back_h = vec2(fast_acos(back_cos.x), -fast_acos(back_cos.y));
            // A ray at angle h between the slab's front and back meets it at its lateral distance: at the
            // distance lateral / |sin h|, nearer than `reach` for |h| within acos(lateral / reach) of pi/2. Only
            // those sectors are marked, so every ray is weighed by its own hit distance, as the REFERENCE weighs
            // it (weighing the whole slab by its front's distance left the bitmask 0.01 too bright on the atrium).
            vec2 spread = vec2(fast_acos(min(lateral.x / reach, 1.0)), fast_acos(min(lateral.y / reach, 1.0)));
            vec2 centre = vec2(kHalfPi, -kHalfPi);
            vec2 lo = clamp((max(min(front_h, back_h), centre - spread) - lowest) / sector_angle, 0.0, float(sectors));
            vec2 hi = clamp((min(max(front_h, back_h), centre + spread) - lowest) / sector_angle, 0.0, float(sectors));
            uvec2 first = uvec2(lo + 0.5), last = uvec2(hi + 0.5);  // sectors [first, last)
            uvec2 marked = sectors_below(last) & ~sectors_below(first);
            occupied |= (usable.x ? marked.x : 0u) | (usable.y ? marked.y : 0u);
#else
            vec2 sample_cos = max(mix(low_cos, cos_h, greaterThan(weight, vec2(0.0))), low_cos);
            vec2 sample_weight = vec2(side_weight(sample_cos.x, 1.0, sin_n, cos_n), side_weight(sample_cos.y, -1.0, sin_n, cos_n));
            bvec2 raises = greaterThan(sample_cos, horizon_cos);
            occluded += mix(vec2(0.0), weight * (horizon_weight - sample_weight), raises);
#if OBSCURA_GTAO_BENT_NORMALS
            // The same arcs' direction integrals, for the bent normal.
            vec2 sin_horizon = vec2(1.0, -1.0) * sqrt(max(vec2(0.0), 1.0 - horizon_cos * horizon_cos));
            vec2 sin_sample = vec2(1.0, -1.0) * sqrt(max(vec2(0.0), 1.0 - sample_cos * sample_cos));
            for (int side = 0; side < 2; ++side) {
                vec2 arc = signed_direction(sin_horizon[side], horizon_cos[side], sin_n, cos_n) -
                           signed_direction(sin_sample[side], sample_cos[side], sin_n, cos_n);
                // Side -'s arcs run from the sample up to the horizon (negative angles): the signed integral flips.
                vec2 added = raises[side] ? weight[side] * (side == 0 ? arc : -arc) : vec2(0.0);
                occluded_bent += side == 0 ? vec4(added, 0.0, 0.0) : vec4(0.0, 0.0, added);
            }
#endif
#if OBSCURA_GTAO_THICKNESS_BLEND
            // The thickness heuristic: a lower sample pulls the horizon down by the blend fraction (of the arc's
            // weight), so a thin occluder stops hiding what lies beyond it. The occlusion is accumulated arc by arc,
            // so the arc the horizon gives up is refunded: the occluded part of [horizon, tangent plane] shrinks
            // with its span (its mean occlusion kept). Without the refund the heuristic could only add occlusion.
            vec2 blend = gtao.thickness.y * step(vec2(1e-30), weight) * vec2(not(raises));
            vec2 lowered_weight = mix(horizon_weight, sample_weight, blend);
            vec2 span = unoccluded_weight - horizon_weight;
            vec2 kept = mix(vec2(1.0), (unoccluded_weight - lowered_weight) / max(span, vec2(1e-20)),
                            greaterThan(span, vec2(1e-12)));
            occluded *= kept;
#if OBSCURA_GTAO_BENT_NORMALS
            occluded_bent *= kept.xxyy;
#endif
            horizon_weight = mix(lowered_weight, sample_weight, raises);
            horizon_cos = mix(mix(horizon_cos, sample_cos, blend), sample_cos, raises);
#else
            // Without it (thickness_blend = 0, the default: compiled out), the horizon only rises.
            horizon_weight = mix(horizon_weight, sample_weight, raises);
            horizon_cos = mix(horizon_cos, sample_cos, raises);
#endif
#endif
        }

        // The unoccluded slice, G(n + pi/2) + G(n - pi/2) = cos n + n sin n.
        float slice_unoccluded = cos_n + n * sin_n;
        float slice_visible;
        vec2 slice_bent = vec2(0.0);
#if OBSCURA_GTAO_MODE == OBSCURA_GTAO_MODE_BITMASK
        slice_visible = 0.0;
        uint free_sectors = ~occupied & all_sectors;
        while (free_sectors != 0u) {
            int first = findLSB(free_sectors);
            uint above = ~free_sectors & ~((1u << uint(first)) - 1u) & all_sectors;  // occupied above `first`
            int last = above == 0u ? sectors : findLSB(above);
            float a = lowest + float(first) * sector_angle, b = lowest + float(last) * sector_angle;
            slice_visible += signed_weight(b, sin_n, cos_n) - signed_weight(a, sin_n, cos_n);
#if OBSCURA_GTAO_BENT_NORMALS
            slice_bent += signed_direction(sin(b), cos(b), sin_n, cos_n) - signed_direction(sin(a), cos(a), sin_n, cos_n);
#endif
            free_sectors &= last >= 32 ? 0u : ~((1u << uint(last)) - 1u);
        }
#else
        // The visible arc [h0, h1]: h1 = acos of side +'s horizon, h0 = -acos of side -'s.
        slice_visible = max(0.0, unoccluded_weight.x + unoccluded_weight.y - occluded.x - occluded.y);
        slice_unoccluded = unoccluded_weight.x + unoccluded_weight.y;
#if OBSCURA_GTAO_BENT_NORMALS
        // The full arc's integral minus the occluded arcs' (added back below as the normal's share).
        slice_bent = signed_direction(cos_n, -sin_n, sin_n, cos_n) - signed_direction(-cos_n, sin_n, sin_n, cos_n) -
                     occluded_bent.xy - occluded_bent.zw;
#endif
#endif
        float slice_share = slice_density * projected_length;
        visible += slice_share * slice_visible;
        unoccluded += slice_share * slice_unoccluded;
#if OBSCURA_GTAO_BENT_NORMALS
        // Minus the unoccluded slice's, the full arc [n - pi/2, n + pi/2] (sin, cos of n + pi/2: cos n, -sin n).
        slice_bent -= signed_direction(cos_n, -sin_n, sin_n, cos_n) - signed_direction(-cos_n, sin_n, sin_n, cos_n);
        bent += slice_share * (along * slice_bent.x + towards_eye * slice_bent.y);
#endif
    }

    float visibility = unoccluded > 0.0 ? clamp(visible / unoccluded, 0.0, 1.0) : 1.0;
    visibility = pow(clamp(1.0 - gtao.shaping.x * (1.0 - visibility), 0.0, 1.0), gtao.shaping.y);
    if (gtao.shaping.z > 0.0) visibility = multi_bounce(visibility, gtao.shaping.z);
    // The slices' unoccluded integrals average (2/3) n each over the slice directions: the normal times 2S/3 plus the
    // occluded arcs' difference estimates the bent normal, exactly the normal where nothing occludes (a control
    // variate, as the visibility's ratio: the sum of the visible arcs alone strays by degrees at 3 slices).
    bent += (2.0 / 3.0) * float(slices) * normal;
    float bent_length = length(bent);
    vec3 bent_normal = bent_length > 0.0 ? bent / bent_length : normal;
    if (fully_visible) {
        visibility = 1.0;
        taps_read = 0;
        bent_normal = sky ? vec3(0.0, 0.0, 1.0) : normal;
    }
    store(p, count_taps ? float(taps_read) / 256.0 : visibility, bent_normal);
}
