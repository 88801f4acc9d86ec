// HBAO: horizon-based ambient obscurance by ray marching K azimuthal directions x N steps per pixel
// (Bavoil et al. 2008; as specified for comparison in Timonen, "Line-Sweep Ambient Obscurance", sec. 3
// eq. 1 and sec. 6 eq. 3). Per pixel: a jittered rotation of the K directions and a jittered step
// offset; steps scaled so N of them cover the view-space radius on screen, snapped to texel centres.
// Eq. 1 is evaluated in the view slice: the plane through the eye that contains the marched screen
// line, with the zenith pointing at the eye. Every sample of the march lies in that plane, so a flat
// surface gets sin(h) = sin(t) exactly under perspective too; the paper's (direction, view z) basis is
// the orthographic special case of it. Snapping puts a sample up to half a texel beside the line; it
// is moved back into the slice along the receiver's tangent plane (exact for planes, first order
// otherwise), which removes the speckled self-occlusion snapped HBAO otherwise hides with a bias.
#define OBSCURA_HBAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/hash.glsl"
#include "common/falloff.glsl"

layout(local_size_x = OBSCURA_HBAO_GROUP_X, local_size_y = OBSCURA_HBAO_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_linear_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_ao;

void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;

    float depth = texelFetch(u_linear_depth, p, 0).r;
    bool count_taps = target_params.w == OBSCURA_DEBUG_VIEW_TAP_COUNT;
    if (obscura_is_sky(depth)) {
        imageStore(u_ao, p, vec4(count_taps ? 0.0 : 1.0));
        return;
    }
    vec3 position = obscura_view_position(p, depth);
    vec3 normal = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);

    float radius_px = min(hbao.falloff.z * obscura_pixels_per_view_unit(depth), hbao.falloff.w);
    int directions = hbao.counts.x, steps = hbao.counts.y;
    if (radius_px < 1.0) {  // the radius covers less than a texel: nothing to march
        imageStore(u_ao, p, vec4(count_taps ? 0.0 : 1.0));
        return;
    }
    int taps_read = 0;
    float step_px = radius_px / float(steps);
    vec2 noise = obscura_pixel_noise(p);
    vec2 pixel_center = vec2(p) + 0.5;
    // Screen directions map to view-space azimuths through the projection's x/y scales.
    vec2 view_per_pixel = vec2(1.0) / (proj_scale.xy * vec2(depth_size.xy));
    // Zenith: towards the eye (perspective) or along +z (orthographic).
    vec3 zenith = obscura_towards_eye(position);
    float bias = hbao.shaping.x;

    // With K even, direction k + K/2 is direction k turned by pi: the two share their slice, so they are marched
    // together as the two sides of one line (lane x: k, lane y: its opposite), one setup and one loop for both.
    // With K odd every direction is a line of its own, and the second lane is off.
    bool paired = (directions & 1) == 0;
    int lines = paired ? directions / 2 : directions;
    float obscurance = 0.0;
    for (int k = 0; k < lines; ++k) {
        float angle = (float(k) + noise.x) * (2.0 * OBSCURA_PI / float(directions));
        vec2 dir = vec2(cos(angle), sin(angle));
        vec3 line = vec3(normalize(dir * view_per_pixel), 0.0);
        vec3 horizontal = normalize(line - zenith * dot(line, zenith));
        float n_h = dot(normal, horizontal), n_z = dot(normal, zenith);
        float n_len_sq = n_h * n_h + n_z * n_z;
        float sin_t = n_len_sq > 0.0 ? -n_h * inversesqrt(n_len_sq) : 0.0;
        vec3 slice_normal = cross(horizontal, zenith);
        float slope = dot(normal, slice_normal) / max(n_z, 0.1);
        // A sample's offset h from the pixel is moved into the slice along the tangent plane, h + (zenith slope -
        // slice_normal) (h . slice_normal), exact for planes: its coordinates there are h . horizontal and
        // h . (zenith + slope slice_normal), taken straight from the sample's pixel and depth (axis forms). The
        // opposite side's horizontal axis and slice normal are these negated: its tangent is -sin_t, its distance
        // and sin h come out of the same two coordinates.
        vec4 horizontal_form = obscura_axis_form(horizontal, position);
        vec4 zenith_form = obscura_axis_form(zenith + slope * slice_normal, position);
        vec2 tangent = vec2(sin_t, -sin_t);

        vec2 horizon = tangent + bias;  // running max of sin(h) per side (horizon-split estimator)
        vec2 line_obscurance = vec2(0.0);
        // No branch in the steps (CPU rasterisers run every lane through every branch): a step outside the texture
        // (every later one is too), on the pixel itself or on sky counts for nothing.
        for (int j = 0; j < steps; ++j) {
            float t = (float(j) + noise.y) * step_px + 1.0;
            vec2 sin_h, rho;
            bvec2 valid;
            for (int side = 0; side < 2; ++side) {  // unrolled by the compilers: constant trip count
                ivec2 s = ivec2(floor(pixel_center + dir * (side == 0 ? t : -t)));
                ivec2 clamped = clamp(s, ivec2(0), depth_size.xy - 1);
                bool inside = s == clamped && s != p && (side == 0 || paired);  // the clamp moved nothing
                float sample_depth = texelFetch(u_linear_depth, clamped, 0).r;
                taps_read += inside ? 1 : 0;
                vec2 origin = vec2(s) + 0.5;
                float sample_w = obscura_clip_w(sample_depth);
                float h_x = obscura_along_axis(horizontal_form, origin, sample_depth, sample_w);
                float h_z = obscura_along_axis(zenith_form, origin, sample_depth, sample_w);
                float distance_sq = h_x * h_x + h_z * h_z;
                valid[side] = inside && !obscura_is_sky(sample_depth) && distance_sq > 0.0;
                sin_h[side] = h_z * inversesqrt(max(distance_sq, 1e-30));
                rho[side] = obscura_rho0(hbao.falloff.x, hbao.falloff.y, distance_sq);  // d^2 in view units^2
            }
            if (OBSCURA_HBAO_ESTIMATOR == 1) {  // compiled in
                bvec2 raises = bvec2(valid.x && sin_h.x > horizon.x, valid.y && sin_h.y > horizon.y);
                line_obscurance += mix(vec2(0.0), rho * (sin_h - horizon), raises);
                horizon = mix(horizon, sin_h, raises);
            } else {
                line_obscurance = mix(line_obscurance, max(line_obscurance, rho * (sin_h - tangent - bias)), valid);
            }
        }
        obscurance += line_obscurance.x + line_obscurance.y;
    }
    obscurance *= hbao.shaping.y / float(directions);
    float visibility = pow(clamp(1.0 - obscurance, 0.0, 1.0), hbao.shaping.z);
    imageStore(u_ao, p, vec4(count_taps ? float(taps_read) / 256.0 : visibility));
}
