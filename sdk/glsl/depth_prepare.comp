// Depth preparation, shared by every method: linear view depth for the whole depth texture (every
// texel can occlude) and view-space normals, from the host's normals or reconstructed from depth
// (SAO paper eq. 4, taking the smaller one-sided difference at depth edges).
// Variants: DEPTH_LINEAR (host gives linear view depth), DEPTH_MULTISAMPLE (sample 0 is used).
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"

layout(local_size_x = OBSCURA_DEPTH_PREPARE_GROUP_X, local_size_y = OBSCURA_DEPTH_PREPARE_GROUP_Y) in;

#if DEPTH_MULTISAMPLE
layout(binding = OBSCURA_UNIT_DEPTH) uniform sampler2DMS u_depth;
float fetch_raw_depth(ivec2 p) { return texelFetch(u_depth, p, 0).r; }
#else
layout(binding = OBSCURA_UNIT_DEPTH) uniform sampler2D u_depth;
float fetch_raw_depth(ivec2 p) { return texelFetch(u_depth, p, 0).r; }
#endif
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_host_normals;

layout(binding = OBSCURA_IMAGE_OUT0, r32f) writeonly uniform image2D u_linear_depth;
layout(binding = OBSCURA_IMAGE_OUT1, rg16_snorm) writeonly uniform image2D u_normals;

float linear_depth_at(ivec2 p) {
    float raw = fetch_raw_depth(p);
#if DEPTH_LINEAR
    return obscura_sanitize_linear_depth(raw);
#else
    return obscura_linearize_window_depth(raw);
#endif
}

// The one-sided difference along `axis` whose depth step is smaller (flat side of an edge); zero if
// both neighbours are sky or outside the texture.
vec3 one_sided_derivative(ivec2 p, vec3 center, float depth, ivec2 axis) {
    ivec2 size = depth_size.xy;
    ivec2 pa = p + axis, pb = p - axis;
    bool a_ok = all(lessThan(pa, size)) && all(greaterThanEqual(pa, ivec2(0)));
    bool b_ok = all(lessThan(pb, size)) && all(greaterThanEqual(pb, ivec2(0)));
    float da = a_ok ? linear_depth_at(pa) : OBSCURA_SKY_DEPTH;
    float db = b_ok ? linear_depth_at(pb) : OBSCURA_SKY_DEPTH;
    bool a_valid = !obscura_is_sky(da), b_valid = !obscura_is_sky(db);
    if (!a_valid && !b_valid) return vec3(0.0);
    if (a_valid && (!b_valid || abs(da - depth) <= abs(depth - db))) {
        return obscura_view_position(pa, da) - center;
    }
    return center - obscura_view_position(pb, db);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, depth_size.xy))) return;
    float depth = linear_depth_at(p);
    imageStore(u_linear_depth, p, vec4(depth));

    vec3 n = vec3(0.0, 0.0, 1.0);
    if (depth_size.w == OBSCURA_NORMALS_RECONSTRUCT) {
        if (!obscura_is_sky(depth)) {
            vec3 center = obscura_view_position(p, depth);
            vec3 dx = one_sided_derivative(p, center, depth, ivec2(1, 0));
            vec3 dy = one_sided_derivative(p, center, depth, ivec2(0, 1));
            vec3 c = cross(dx, dy);
            if (dot(c, c) > 0.0) {
                // The cross product's sign depends on the projection's handedness (flipped x or y):
                // a visible surface faces the eye.
                n = normalize(c);
                if (dot(n, obscura_towards_eye(center)) < 0.0) n = -n;
            }
        }
    } else {
        vec3 host = texelFetch(u_host_normals, p, 0).xyz;
        if (depth_size.w == OBSCURA_NORMALS_UNSIGNED) host = host * 2.0 - 1.0;
        bool finite = obscura_is_finite(host.x) && obscura_is_finite(host.y) && obscura_is_finite(host.z);
        if (finite && dot(host, host) > 1e-12) n = normalize(host);
    }
    imageStore(u_normals, p, vec4(obscura_encode_normal(n), 0.0, 0.0));
}
