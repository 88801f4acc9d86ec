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

    float obscurance = 0.0;
    for (int k = 0; k < directions; ++k) {
        float angle = (float(k) + noise.x) * (2.0 * OBSCURA_PI / float(directions));
        vec2 dir = vec2(cos(angle), sin(angle));
        // The slice's horizontal axis: the screen direction in view space, made orthogonal to the zenith.
        vec3 line = vec3(normalize(dir * view_per_pixel), 0.0);
        vec3 horizontal = normalize(line - zenith * dot(line, zenith));
        // Tangent of the receiver along +horizontal inside the slice: sin(t) from the normal's in-slice part.
        float n_h = dot(normal, horizontal), n_z = dot(normal, zenith);
        float n_len_sq = n_h * n_h + n_z * n_z;
        float sin_t = n_len_sq > 0.0 ? -n_h * inversesqrt(n_len_sq) : 0.0;
        // Off-slice correction: a step c along the slice normal moves the tangent plane by c * slope
        // along the zenith. The slope is limited where the receiver is seen edge-on.
        vec3 slice_normal = cross(horizontal, zenith);
        float slope = dot(normal, slice_normal) / max(n_z, 0.1);

        float horizon = sin_t + bias;  // running max of sin(h) (horizon-split estimator)
        float direction_obscurance = 0.0;
        for (int j = 0; j < steps; ++j) {
            float t = (float(j) + noise.y) * step_px + 1.0;
            ivec2 s = ivec2(floor(pixel_center + dir * t));
            if (any(lessThan(s, ivec2(0))) || any(greaterThanEqual(s, depth_size.xy))) break;
            if (s == p) continue;
            float sample_depth = texelFetch(u_linear_depth, s, 0).r;
            ++taps_read;
            if (obscura_is_sky(sample_depth)) continue;
            vec3 h = obscura_view_position(s, sample_depth) - position;
            float off_slice = dot(h, slice_normal);
            h += (zenith * slope - slice_normal) * off_slice;
            float distance_sq = dot(h, h);
            if (distance_sq <= 0.0) continue;
            float sin_h = dot(h, zenith) * inversesqrt(distance_sq);
            float rho = obscura_rho0(hbao.falloff.x, hbao.falloff.y, distance_sq);  // d^2 in view units^2
            if (OBSCURA_HBAO_ESTIMATOR == 1) {  // compiled in
                if (sin_h > horizon) {
                    direction_obscurance += rho * (sin_h - horizon);
                    horizon = sin_h;
                }
            } else {
                direction_obscurance = max(direction_obscurance, rho * (sin_h - sin_t - bias));
            }
        }
        obscurance += direction_obscurance;
    }
    obscurance *= hbao.shaping.y / float(directions);
    float visibility = pow(clamp(1.0 - obscurance, 0.0, 1.0), hbao.shaping.z);
    imageStore(u_ao, p, vec4(count_taps ? float(taps_read) / 256.0 : visibility));
}
