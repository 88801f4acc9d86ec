// SAO's distributed AO sample pass (McGuire, Mara, Luebke, "Scalable Ambient Obscurance", HPG 2012,
// sec. 2.3): s taps on a spiral around each pixel (eq. 6-7; the unrotated taps come from the CPU, which
// also chose tau), rotated per pixel by the AlchemyAO XOR hash (eq. 8), each read from the z-MIP level its
// screen radius calls for (eq. 9-10), reconstructed to camera space (eq. 3, here obscura_view_position,
// which covers every projection the SDK accepts) and fed to the AlchemyAO estimator (SAO eq. 1). The pass
// ends with the 2x2 bilateral step, done through shared memory instead of quad derivatives, and packs
// (A, 16-bit z key, coverage) into RGBA8 for the blur (sec. 2.3, last paragraph).
#define OBSCURA_SAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/z_pyramid.glsl"

layout(local_size_x = OBSCURA_SAO_GROUP_X, local_size_y = OBSCURA_SAO_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_z;  // the z pyramid (mipmapped sampler)
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_IMAGE_OUT0, rgba8) writeonly uniform image2D u_packed;

const int kGroupSize = OBSCURA_SAO_GROUP_X * OBSCURA_SAO_GROUP_Y;
shared float s_visibility[kGroupSize];
// The z pyramid's filter, compiled in (SaoPass::prepare): CPU rasterisers, which run every lane through both sides
// of a branch, then do not walk the rotated grid's texel origin for the other filters (the pass at 0.9x of its time
// on llvmpipe; compiling the sample count in as well gained nothing more).
#ifndef OBSCURA_SAO_MIP_FILTER
#error "OBSCURA_SAO_MIP_FILTER must be defined"
#endif
shared float s_depth[kGroupSize];

// Eq. 8: phi = 30 x' ^ y' + 10 x' y' (radians), reduced to [0, 2 pi) before the one sin/cos per pixel. The
// integer is exact; it is reduced in double precision (SaoPass's spiral_rotation does the same), because a
// float's reduction (a spacing of 4 at 10 x' y' = 4e7) left GPUs and llvmpipe with unrelated angles for
// the same pixel, and so with other images.
vec2 rotation(ivec2 p) {
    uvec2 u = uvec2(p);
    double n = double((30u * u.x) ^ u.y) + double(10u * u.x * u.y);
    double turns = n * (1.0LF / 6.283185307179586LF);
    float phi = float((turns - floor(turns)) * 6.283185307179586LF) + noise_offset.x * (2.0 * OBSCURA_PI);
    return vec2(cos(phi), sin(phi));
}

// Visibility of the receiver at p (SAO eq. 1) and the number of depth texels read.
float sample_visibility(ivec2 p, float depth, out int taps_read) {
    taps_read = 0;
    vec3 c = obscura_view_position(p, depth);
    vec3 n = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);
    // Eq. 5: the ball's screen radius, capped.
    float radius_px = min(sao.ball.x * obscura_pixels_per_view_unit(depth), sao.shaping.z);
    vec2 rot = rotation(p);
    vec2 center = vec2(p) + 0.5;
    int log_q = sao.config.y, deepest = sao.config.z;
    // z_C beta (z_C < 0: it raises the bar v.n must clear); orthographic: the tolerance distance instead of the depth,
    // so that the AO does not change where the eye plane sits (1000 units back, -z_C beta was -1 and cleared nothing).
    float bias = -obscura_tolerance_distance(depth) * sao.shaping.x;
    float sum = 0.0;
    for (int i = 0; i < sao.config.x; ++i) {
        vec4 tap = sao.taps[i];
        vec2 u = vec2(tap.x * rot.x - tap.y * rot.y, tap.x * rot.y + tap.y * rot.x);
        float h = radius_px * tap.z;
        ivec2 q = ivec2(floor(center + h * u));
        // No branch (CPU rasterisers run every lane through every branch): a tap outside the texture, on sky or
        // outside the ball of radius r (where the estimator's points lie) counts for nothing, chosen by selection
        // (its term may be NaN).
        bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, depth_size.xy));
        // Eq. 9-10: one level down per doubling of the tap's screen radius past q'.
        int m = clamp(findMSB(int(h)) - log_q, 0, deepest);
        ivec2 level_size = max(depth_size.xy >> m, ivec2(1));
        ivec2 t = clamp(q >> m, ivec2(0), level_size - 1);
        float z = texelFetch(u_z, t, m).r;
        taps_read += inside ? 1 : 0;
        vec3 v = obscura_view_position_at(obscura_level_texel_origin(t, m, OBSCURA_SAO_MIP_FILTER), z) - c;
        float vv = dot(v, v);
        float term = max(0.0, dot(v, n) + bias) / (vv + sao.ball.w);
        sum += inside && !obscura_is_sky(z) && vv < sao.ball.y ? term : 0.0;
    }
    return pow(max(0.0, 1.0 - sao.ball.z * sum), sao.shaping.y);
}

// 16-bit z key over [0, blur depth range] past the key's origin (0: the eye; orthographic: the near plane, so that the
// blur's edges do not depend on where the eye plane sits) in G (high byte) and B (low byte), exact through RGBA8.
vec2 pack_key(float depth) {
    uint key = uint(round(clamp((depth - sao.packing.y) * sao.packing.x, 0.0, 1.0) * 65535.0));
    return vec2(float(key >> 8u), float(key & 255u)) * (1.0 / 255.0);
}

void main() {
    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    int index = local.y * OBSCURA_SAO_GROUP_X + local.x;
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    bool in_work = all(lessThan(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)));
    float depth = in_work ? texelFetch(u_z, p, 0).r : OBSCURA_SKY_DEPTH;
    bool sky = obscura_is_sky(depth);

    int taps_read = 0;
    float visibility = sky ? 1.0 : sample_visibility(p, depth, taps_read);
    bool count_taps = target_params.w == OBSCURA_DEBUG_VIEW_TAP_COUNT;
    if (count_taps) visibility = float(taps_read) / 256.0;

    // The 2x2 bilateral step: average with the x partner of the quad, then with the y partner, where the
    // two are on the same surface (the blur's edge test). Work regions start on even coordinates, so
    // quads never straddle groups. Barriers are reached by every invocation (no early returns above).
    if (sao.config.w != 0 && !count_taps) {
        s_visibility[index] = visibility;
        s_depth[index] = depth;
        barrier();
        int partner_x = index ^ 1;
        float depth_x = s_depth[partner_x];
        if (!sky && !obscura_is_sky(depth_x) && abs(depth_x - depth) * sao.shaping.w < 1.0) {
            visibility = 0.5 * (visibility + s_visibility[partner_x]);
        }
        barrier();
        s_visibility[index] = visibility;
        barrier();
        int partner_y = index ^ OBSCURA_SAO_GROUP_X;
        float depth_y = s_depth[partner_y];
        if (!sky && !obscura_is_sky(depth_y) && abs(depth_y - depth) * sao.shaping.w < 1.0) {
            visibility = 0.5 * (visibility + s_visibility[partner_y]);
        }
    }
    if (!in_work) return;
    // Alpha marks geometry: the blur neither reads sky texels nor changes them.
    imageStore(u_packed, p, vec4(visibility, pack_key(depth), sky ? 0.0 : 1.0));
}
