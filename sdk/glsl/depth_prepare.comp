// Depth preparation, shared by every method: linear view depth for the whole depth texture (every
// texel can occlude) and view-space normals, from the host's normals or reconstructed from depth
// (SAO paper eq. 4, with the one-sided difference of the side that continues the centre's surface).
// At reduced resolution (resolution.x = k > 0) texel p is the host's texel p << k, read alone: its depth at its
// own position (the reduced frame's projection puts p's centre there), so planes stay exact planes; the normals
// are reconstructed on the reduced grid (or read from the host's at that texel).
// Variants: DEPTH_LINEAR (host gives linear view depth), DEPTH_MULTISAMPLE (sample 0 is used).
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/host_depth.glsl"
#include "common/normal_encoding.glsl"

layout(local_size_x = OBSCURA_DEPTH_PREPARE_GROUP_X, local_size_y = OBSCURA_DEPTH_PREPARE_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_host_normals;

layout(binding = OBSCURA_IMAGE_OUT0, r32f) writeonly uniform image2D u_linear_depth;
layout(binding = OBSCURA_IMAGE_OUT1, rg16_snorm) writeonly uniform image2D u_normals;

float linear_depth_at(ivec2 p) { return obscura_host_linear_depth(p << resolution.x); }

bool inside(ivec2 p) { return all(lessThan(p, depth_size.xy)) && all(greaterThanEqual(p, ivec2(0))); }

// Compiled in (DepthPreparePass::prepare). Reconstructing a normal reads the depths up to 2 texels away on
// each axis: 9 texel fetches and linearisations per texel. GPUs share them through a tile in shared memory
// (a texture unit takes one texel a clock); CPU rasterisers, which reach shared memory one invocation at a
// time, fetch them.
#ifndef OBSCURA_CPU_RASTERISER
#error "OBSCURA_CPU_RASTERISER must be defined"
#endif
#if OBSCURA_CPU_RASTERISER
void load_depth_tile(bool reconstruct) {}
float depth_or_sky(ivec2 p) { return inside(p) ? linear_depth_at(p) : OBSCURA_SKY_DEPTH; }
#else
const int kMargin = 2;
const ivec2 kGroup = ivec2(OBSCURA_DEPTH_PREPARE_GROUP_X, OBSCURA_DEPTH_PREPARE_GROUP_Y);
const ivec2 kTile = kGroup + 2 * kMargin;
shared float s_depth[kTile.x * kTile.y];
ivec2 g_tile_origin;

// Linear depths of the group and its margin (sky outside the texture); only the group's own texels when
// the host gives the normals.
void load_depth_tile(bool reconstruct) {
    g_tile_origin = ivec2(gl_WorkGroupID.xy) * kGroup - kMargin;
    if (reconstruct) {
        for (int i = int(gl_LocalInvocationIndex); i < kTile.x * kTile.y; i += kGroup.x * kGroup.y) {
            ivec2 p = g_tile_origin + ivec2(i % kTile.x, i / kTile.x);
            s_depth[i] = inside(p) ? linear_depth_at(p) : OBSCURA_SKY_DEPTH;
        }
    } else {
        ivec2 p = ivec2(gl_GlobalInvocationID.xy), t = p - g_tile_origin;
        s_depth[t.y * kTile.x + t.x] = inside(p) ? linear_depth_at(p) : OBSCURA_SKY_DEPTH;
    }
    barrier();
}

// Every texel a reconstruction reads lies in the tile.
float depth_or_sky(ivec2 p) {
    ivec2 t = p - g_tile_origin;
    return s_depth[t.y * kTile.x + t.x];
}
#endif

// A side with one texel before sky or the texture's edge cannot show that it continues the centre's surface.
// It loses to a side that is planar with the centre (continuation error below this) and wins over one that is
// not: next to a hole of sky, a floor texel keeps the floor's normal instead of taking the box's beyond it.
const float kOneTexelError = 1.0e-3;

// How far the surface on one side, continued linearly from its two texels (in 1/w, affine on planes),
// misses the centre's depth; kOneTexelError and up when only one texel is there, a huge value for none.
float continuation_error(float center, float near, float far) {
    if (obscura_is_sky(near)) return 3.0e38;
    if (obscura_is_sky(far)) return kOneTexelError * (1.0 + abs(near - center) / center);  // rank by the step
    float k_center = 1.0 / obscura_clip_w(center);
    float k_near = 1.0 / obscura_clip_w(near), k_far = 1.0 / obscura_clip_w(far);
    return abs(2.0 * k_near - k_far - k_center) / k_center;
}

// The one-sided difference along `axis` on the side whose surface continues through the centre: the
// side that is planar with it (SAO paper eq. 4 takes the side with the smaller depth step, which picks
// the wrong one next to a concave crease, where the other surface's first texel is closer in depth).
// Zero if both neighbours are sky or outside the texture.
vec3 one_sided_derivative(ivec2 p, vec3 center, float depth, ivec2 axis) {
    ivec2 pa = p + axis, pb = p - axis;
    float da = depth_or_sky(pa), db = depth_or_sky(pb);
    bool a_valid = !obscura_is_sky(da), b_valid = !obscura_is_sky(db);
    if (!a_valid && !b_valid) return vec3(0.0);
    float error_a = continuation_error(depth, da, depth_or_sky(p + 2 * axis));
    float error_b = continuation_error(depth, db, depth_or_sky(p - 2 * axis));
    bool use_a = a_valid && (!b_valid || error_a < error_b ||
                             (error_a == error_b && abs(da - depth) <= abs(depth - db)));
    if (use_a) return obscura_view_position(pa, da) - center;
    return center - obscura_view_position(pb, db);
}

void main() {
    load_depth_tile(depth_size.w == OBSCURA_NORMALS_RECONSTRUCT);  // every invocation, before any leaves
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, depth_size.xy))) return;
    float depth = depth_or_sky(p);
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
        vec3 host = texelFetch(u_host_normals, p << resolution.x, 0).xyz;
        if (depth_size.w == OBSCURA_NORMALS_UNSIGNED) host = host * 2.0 - 1.0;
        bool finite = obscura_is_finite(host.x) && obscura_is_finite(host.y) && obscura_is_finite(host.z);
        if (finite && dot(host, host) > 1e-12) n = normalize(host);
    }
    imageStore(u_normals, p, vec4(obscura_encode_normal(n), 0.0, 0.0));
}
