// Depth preparation, shared by every method: linear view depth for the whole depth texture (every
// texel can occlude) and view-space normals where the method reads them, from the host's normals or reconstructed
// from depth (SAO paper eq. 4, with the one-sided difference of the side that continues the centre's surface).
// At reduced resolution (resolution.x = k > 0) texel p is the host's texel p << k, read alone: its depth at its
// own position (the reduced frame's projection puts p's centre there), so planes stay exact planes; the normals
// are reconstructed on the reduced grid (or read from the host's at that texel).
// Variants: DEPTH_LINEAR (host gives linear view depth), DEPTH_MULTISAMPLE (sample 0 is used),
// OBSCURA_DEPTH_PREPARE_NORMALS (1: linear depth and normals; 0: linear depth alone).
// A dispatch covers work_rect (DepthPreparePass: the normals where the method reads them, the linear depth alone
// in the guard band around them, which only occludes); reconstructions still read the depths beyond it.
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

// Compiled in (DepthPreparePass::prepare): where the normals come from (OBSCURA_NORMAL_SOURCE, one of
// OBSCURA_NORMALS_*), and how the depths a reconstruction reads are shared. Reconstructing a normal reads the depths
// up to 2 texels away on each axis: 9 texel fetches and linearisations per texel. GPUs share them through a tile in
// shared memory (a texture unit takes one texel a clock); on CPU rasterisers, which reach shared memory one
// invocation at a time, an invocation reconstructs a 4x4 block from the 48 texels of its cross-shaped footprint
// (3 per texel), kept in registers.
#ifndef OBSCURA_CPU_RASTERISER
#error "OBSCURA_CPU_RASTERISER must be defined"
#endif
#ifndef OBSCURA_NORMAL_SOURCE
#error "OBSCURA_NORMAL_SOURCE must be defined"
#endif
#ifndef OBSCURA_DEPTH_PREPARE_NORMALS
#error "OBSCURA_DEPTH_PREPARE_NORMALS must be defined"
#endif
const bool kReconstruct = OBSCURA_NORMAL_SOURCE == OBSCURA_NORMALS_RECONSTRUCT;
// The end of the dispatch's rectangle: texels from there on are another dispatch's.
ivec2 rect_end() { return work_rect.xy + work_rect.zw; }
#if !OBSCURA_CPU_RASTERISER
const int kMargin = 2;
const ivec2 kGroup = ivec2(OBSCURA_DEPTH_PREPARE_GROUP_X, OBSCURA_DEPTH_PREPARE_GROUP_Y);
const ivec2 kTile = kGroup + 2 * kMargin;
shared float s_depth[kTile.x * kTile.y];
ivec2 g_tile_origin;

// Linear depths of the group and its margin (sky outside the texture); only the group's own texels when
// the host gives the normals.
void load_depth_tile() {
    g_tile_origin = work_rect.xy + ivec2(gl_WorkGroupID.xy) * kGroup - kMargin;
    if (kReconstruct) {
        for (int i = int(gl_LocalInvocationIndex); i < kTile.x * kTile.y; i += kGroup.x * kGroup.y) {
            ivec2 p = g_tile_origin + ivec2(i % kTile.x, i / kTile.x);
            s_depth[i] = inside(p) ? linear_depth_at(p) : OBSCURA_SKY_DEPTH;
        }
    } else {
        ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy), t = p - g_tile_origin;
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

// A side whose continuation misses the centre by more than this (relative) shows another surface: beside a
// feature narrower than two texels (a pole, a baluster, a railing seen from afar) both sides do, and no difference
// along that axis lies on the feature. Measured on the built-in scenes (docs/quality.md, "Normals of features
// narrower than two texels"): 0.1 keeps the atrium's gains of 0.05 and more of the clutter room's.
const float kOtherSurfaceError = 0.1;

// How far the surface on one side, continued linearly from its two texels (in affine_depth, affine on planes),
// misses the centre's depth; kOneTexelError and up when only one texel is there, a huge value for none.
// k_*: affine_depth of each depth, computed once per texel read.
// Relative to the centre's affine depth under perspective; under an orthographic projection (affine depth = depth)
// to obscura_orthographic_distance(), so that where the eye plane sits changes nothing.
float continuation_error(float center, float k_center, float near, float k_near, float far, float k_far) {
    if (obscura_is_sky(near)) return 3.0e38;
    if (obscura_is_sky(far)) {  // rank by the step
        return kOneTexelError * (1.0 + abs(near - center) / obscura_tolerance_distance(center));
    }
    float scale = obscura_is_perspective() ? k_center : obscura_orthographic_distance();
    float error = abs(2.0 * k_near - k_far - k_center) / scale;
    // A feature two texels wide: the near texel continues the centre's surface (a small step) and the far one is
    // another surface. The side then ranks as one texel before the feature's end, as at sky: the tangent to the
    // neighbour is the feature's own (both sides failing the two-texel test left one column of a two-texel pole
    // 64-72 degrees off, the other 10-18).
    if (error > kOtherSurfaceError && abs(k_near - k_center) / scale < 0.5 * kOtherSurfaceError) {
        return kOneTexelError * (1.0 + abs(near - center) / obscura_tolerance_distance(center));
    }
    return error;
}

// The function of depth that is affine in screen space on planes: 1 / clip w under perspective, the depth itself
// under an orthographic projection (whose w is 1: 1 / w would call every side planar).
float affine_depth(float depth) { return obscura_is_perspective() ? 1.0 / obscura_clip_w(depth) : depth; }

// The one-sided difference along one axis on the side whose surface continues through the centre: the
// side that is planar with it (SAO paper eq. 4 takes the side with the smaller depth step, which picks
// the wrong one next to a concave crease, where the other surface's first texel is closer in depth).
// d: the depths at centre - 2, -1, 0, +1, +2 texels along the axis (index 2 the centre), k their affine_depth;
// pa, pb: the texels at +1 and -1. Zero if both neighbours are sky or outside the texture, or if neither side
// continues the centre's surface (kOtherSurfaceError).
vec3 one_sided_derivative(vec3 center, float d[5], float k[5], ivec2 pa, ivec2 pb) {
    bool a_valid = !obscura_is_sky(d[3]), b_valid = !obscura_is_sky(d[1]);
    if (!a_valid && !b_valid) return vec3(0.0);
    float error_a = continuation_error(d[2], k[2], d[3], k[3], d[4], k[4]);
    float error_b = continuation_error(d[2], k[2], d[1], k[1], d[0], k[0]);
    // Both sides another surface, and both farther (a feature in front) or both nearer (a gap): no tangent. A surface
    // that only curves fast at this size, a distant ridge of terrain, is nearer on one side and farther on the other.
    if (min(error_a, error_b) > kOtherSurfaceError && (d[3] - d[2]) * (d[1] - d[2]) > 0.0) return vec3(0.0);
    bool use_a = a_valid && (!b_valid || error_a < error_b ||
                             (error_a == error_b && abs(d[3] - d[2]) <= abs(d[2] - d[1])));
    if (use_a) return obscura_view_position(pa, d[3]) - center;
    return center - obscura_view_position(pb, d[1]);
}

// The view-space normal of texel p (depth d[2] on both axes) from the depths along x and y, facing the eye. An axis
// that gives no tangent (sky on both sides, or a feature narrower than two texels) leaves the normal free about the
// other axis' tangent t: it is taken as close to the eye direction e as t allows, e |t|^2 - t (t.e), the guess that
// is right for a pole or baluster seen from the side. That is the cross product with the missing tangent replaced
// by t x e (x missing) or e x t (y missing), so no branch is taken; with neither axis, the eye direction.
vec3 reconstruct_normal(ivec2 p, float dx[5], float kx[5], float dy[5], float ky[5]) {
    if (obscura_is_sky(dx[2])) return vec3(0.0, 0.0, 1.0);
    vec3 center = obscura_view_position(p, dx[2]);
    vec3 eye = obscura_towards_eye(center);
    vec3 tx = one_sided_derivative(center, dx, kx, p + ivec2(1, 0), p - ivec2(1, 0));
    vec3 ty = one_sided_derivative(center, dy, ky, p + ivec2(0, 1), p - ivec2(0, 1));
    vec3 c = cross(dot(tx, tx) > 0.0 ? tx : cross(ty, eye), dot(ty, ty) > 0.0 ? ty : cross(eye, tx));
    // Scaled to its largest component first: the product of two tangents grows with the depth squared, and its squared
    // length overflowed past about 1e9 view units (inf passed the test below, and normalize returned 0, then NaN).
    float largest = max(max(abs(c.x), abs(c.y)), abs(c.z));
    c *= largest > 0.0 ? 1.0 / largest : 0.0;
    if (!(dot(c, c) > 0.0)) return eye;
    // The cross product's sign depends on the projection's handedness (flipped x or y): a visible surface faces the
    // eye.
    vec3 n = normalize(c);
    return dot(n, eye) < 0.0 ? -n : n;
}

// The normal the host gives at its texel for p (depth `depth`), facing the eye, or +z where it is not a finite non-zero
// vector. A normal facing away is the other side's (a two-sided surface's back face written with its geometric
// normal): negated, as a reconstructed normal is. The methods assume a visible surface faces the eye: GTAO's slices
// came out unoccluded (visibility 1 whatever the geometry) for a normal at -V, and HBAO's tangent took the wrong sign.
vec3 host_normal(ivec2 p, float depth) {
    vec3 host = texelFetch(u_host_normals, p << resolution.x, 0).xyz;
    if (OBSCURA_NORMAL_SOURCE == OBSCURA_NORMALS_UNSIGNED) host = host * 2.0 - 1.0;
    bool finite = obscura_is_finite(host.x) && obscura_is_finite(host.y) && obscura_is_finite(host.z);
    if (!(finite && dot(host, host) > 1e-12)) return vec3(0.0, 0.0, 1.0);
    vec3 n = normalize(host);
    if (obscura_is_sky(depth)) return n;
    return dot(n, obscura_towards_eye(obscura_view_position(p, depth))) < 0.0 ? -n : n;
}

void store(ivec2 p, float depth, vec3 normal) {
    imageStore(u_linear_depth, p, vec4(depth));
    imageStore(u_normals, p, vec4(obscura_encode_normal(normal), 0.0, 0.0));
}

#if OBSCURA_CPU_RASTERISER
// The 4x4 block at 4 * invocation reads its cross-shaped footprint once: the block, and two texels beyond it on each
// side of each of its rows and columns (48 texels, 3 per texel; a 2x2 quad read 5 per texel). The arrays are indexed
// by constants once the loops unroll (their trip counts are constant), so compilers keep them in registers.
const int kBlock = OBSCURA_DEPTH_PREPARE_CPU_BLOCK;

float depth_or_sky(ivec2 p) { return inside(p) ? linear_depth_at(p) : OBSCURA_SKY_DEPTH; }

// Offset -2, -1, 4 or 5 from the block's first row or column: the beyond-the-block texel `side` (0..3).
int beyond(int side) { return side < 2 ? side - 2 : side + kBlock - 2; }

// Texel a (-2 <= a < kBlock + 2) along line `line` of the block: from the block, or from the texels beyond it
// (`outer`: four per line, at beyond(0..3)).
float along_line(float block[kBlock * kBlock], float outer[4 * kBlock], int line, int a, bool rows) {
    if (a >= 0 && a < kBlock) return rows ? block[line * kBlock + a] : block[a * kBlock + line];
    return outer[line * 4 + (a < 0 ? a + 2 : a - kBlock + 2)];
}

void main() {
    // The rectangles start on multiples of the block (DepthPreparePass), so blocks never straddle two of them.
    ivec2 origin = work_rect.xy + kBlock * ivec2(gl_GlobalInvocationID.xy), end = rect_end();
    if (any(greaterThanEqual(origin, end))) return;
#if !OBSCURA_DEPTH_PREPARE_NORMALS
    for (int i = 0; i < kBlock * kBlock; ++i) {
        ivec2 p = origin + ivec2(i % kBlock, i / kBlock);
        if (all(lessThan(p, end))) imageStore(u_linear_depth, p, vec4(linear_depth_at(p)));
    }
#else
    float d[kBlock * kBlock], k[kBlock * kBlock];
    for (int i = 0; i < kBlock * kBlock; ++i) {
        d[i] = depth_or_sky(origin + ivec2(i % kBlock, i / kBlock));
        k[i] = affine_depth(d[i]);
    }
#if OBSCURA_NORMAL_SOURCE == OBSCURA_NORMALS_RECONSTRUCT
    // Beyond the block: row r's texels at x = beyond(s), column c's at y = beyond(s).
    float row_d[4 * kBlock], row_k[4 * kBlock], column_d[4 * kBlock], column_k[4 * kBlock];
    for (int i = 0; i < 4 * kBlock; ++i) {
        int line = i / 4, offset = beyond(i % 4);
        row_d[i] = depth_or_sky(origin + ivec2(offset, line));
        row_k[i] = affine_depth(row_d[i]);
        column_d[i] = depth_or_sky(origin + ivec2(line, offset));
        column_k[i] = affine_depth(column_d[i]);
    }
#endif
    for (int i = 0; i < kBlock * kBlock; ++i) {
        ivec2 q = ivec2(i % kBlock, i / kBlock), p = origin + q;
#if OBSCURA_NORMAL_SOURCE == OBSCURA_NORMALS_RECONSTRUCT
        float dx[5], kx[5], dy[5], ky[5];
        for (int j = 0; j < 5; ++j) {
            dx[j] = along_line(d, row_d, q.y, q.x + j - 2, true);
            kx[j] = along_line(k, row_k, q.y, q.x + j - 2, true);
            dy[j] = along_line(d, column_d, q.x, q.y + j - 2, false);
            ky[j] = along_line(k, column_k, q.x, q.y + j - 2, false);
        }
        vec3 n = reconstruct_normal(p, dx, kx, dy, ky);
#else
        vec3 n = host_normal(p, d[i]);
#endif
        // Texels of the block past the rectangle's end (the texture's last row or column) are not written.
        if (all(lessThan(p, end))) store(p, d[i], n);
    }
#endif
}
#else
void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
#if !OBSCURA_DEPTH_PREPARE_NORMALS
    if (all(lessThan(p, rect_end()))) imageStore(u_linear_depth, p, vec4(linear_depth_at(p)));
#else
    load_depth_tile();  // every invocation, before any leaves
    if (any(greaterThanEqual(p, rect_end()))) return;
    vec3 n;
    if (kReconstruct) {
        float dx[5], kx[5], dy[5], ky[5];
        for (int i = 0; i < 5; ++i) {
            dx[i] = depth_or_sky(p + ivec2(i - 2, 0));
            kx[i] = affine_depth(dx[i]);
            dy[i] = depth_or_sky(p + ivec2(0, i - 2));
            ky[i] = affine_depth(dy[i]);
        }
        n = reconstruct_normal(p, dx, kx, dy, ky);
    } else {
        n = host_normal(p, depth_or_sky(p));
    }
    store(p, depth_or_sky(p), n);
#endif
}
#endif
