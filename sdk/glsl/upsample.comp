// Reduced resolution's upsample: the method's result on the reduced grid (texel t is the host's texel t << k) to
// every pixel of the output rectangle, in the host frame's constants. Per pixel p:
//   1. its own surface point P from the host's depth (one fetch: the reduced grid does not hold it);
//   2. the 2x2 reduced texels around p / 2^k, each weighed by its bilinear weight times exp(-(d / (tolerance z))^2),
//      d the distance of P from the texel's tangent plane (its point and its normal on the reduced grid), z the
//      pixel's distance: a texel across a depth edge or a crease is off the plane and drops out, so AO does not
//      bleed across them (no dark or white rims), while on one surface the weights stay bilinear;
//   3. where every texel is off the plane (a thin feature the reduced grid did not sample), the texel whose plane
//      is nearest, alone; a pixel whose four texels are all sky is left unoccluded.
// Sky pixels get visibility 1. With bent normals (OBSCURA_UPSAMPLE_BENT_NORMALS) the RGBA16F bent normals
// (visibility, unit view-space bent normal) are weighed alike and the normal renormalised. One invocation does a
// 2x2 quad of pixels, which share their four texels.
// With OBSCURA_UPSAMPLE_TARGET the visibility goes straight into the host's target (OUTPUT_FORMAT, OUTPUT_MULTIPLY:
// composite.comp's write without a debug view) instead of a full-size R16F texture the composite would copy: at
// reduced resolution the upsample and the composite were the frame's only full-size passes.
#define OBSCURA_UPSAMPLE_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/host_depth.glsl"
#include "common/normal_encoding.glsl"

layout(local_size_x = OBSCURA_UPSAMPLE_GROUP_X, local_size_y = OBSCURA_UPSAMPLE_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_reduced_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_reduced_normals;
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_reduced_ao;
#if OBSCURA_UPSAMPLE_TARGET
#include "common/output_target.glsl"
#else
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_ao;
#endif
#if OBSCURA_UPSAMPLE_BENT_NORMALS
layout(binding = OBSCURA_UNIT_BENT_SOURCE) uniform sampler2D u_reduced_bent;
layout(binding = OBSCURA_IMAGE_OUT1, rgba16f) writeonly uniform image2D u_bent;
#endif

// Below this sum of weights no texel lies on the pixel's plane: every one is more than 3 tolerances off it.
const float kNoneOnPlane = 1e-4;

void store(ivec2 p, float visibility, vec3 bent) {
#if OBSCURA_UPSAMPLE_TARGET
    // At the target's own precision (the composite's copy went through R16F, which drivers round or truncate).
    obscura_write_final_output(p, visibility);
#else
    imageStore(u_ao, p, vec4(visibility));
#endif
#if OBSCURA_UPSAMPLE_BENT_NORMALS
    imageStore(u_bent, p, vec4(visibility, bent));
#endif
}

// The four reduced texels around a pixel are the lanes of a vec4, in textureGather's order: (0, 1), (1, 1), (1, 0),
// (0, 0) from the lower-left one. Four gathers read what twelve fetches would (CPU rasterisers pay per read).
const vec4 kCornerX = vec4(0.0, 1.0, 1.0, 0.0), kCornerY = vec4(1.0, 1.0, 0.0, 0.0);

// One invocation upsamples a 2x2 quad of pixels (in absolute coordinates, so at half and quarter resolution its
// four pixels lie between the same four reduced texels): their gathers, points and normals are read and computed
// once for the four.
void main() {
    ivec2 quad = (work_rect.xy & ~1) + 2 * ivec2(gl_GlobalInvocationID.xy);
    ivec2 rect_end = work_rect.xy + work_rect.zw;
    if (any(greaterThanEqual(quad, rect_end))) return;
    int k = upsample.config.z;
    ivec2 base = quad >> k;

    // The 2x2 texels from `base` (clamped to the grid's edge, as the sampler clamps the gathers).
    vec2 gather_at = vec2(base + 1) * upsample.params.zw;
    vec4 z = textureGather(u_reduced_depth, gather_at, 0);
    vec4 ex = textureGather(u_reduced_normals, gather_at, 0);
    vec4 ey = textureGather(u_reduced_normals, gather_at, 1);
    vec4 tx = min(vec4(base.x) + kCornerX, vec4(upsample.config.x));
    vec4 ty = min(vec4(base.y) + kCornerY, vec4(upsample.config.y));
    bvec4 valid = lessThan(z, vec4(OBSCURA_SKY_THRESHOLD));

    // Each texel's point at its host texel's centre, where the depth preparation read it; sky lanes get a finite
    // stand-in and weight 0 below. Their unit normals.
    float host_texel = float(1 << k);
    vec4 view_z = -mix(vec4(1.0), z, valid);
    vec4 x, y, nx, ny, nz;
    obscura_view_position_at4(tx * host_texel + 0.5, ty * host_texel + 0.5, -view_z, x, y);
    obscura_decode_normal4(ex, ey, nx, ny, nz);
    vec4 plane_offset = x * nx + y * ny + view_z * nz;  // each texel's plane: dot(n, point) = offset
#if OBSCURA_UPSAMPLE_BENT_NORMALS
    vec4 bent[4] = vec4[4](texelFetch(u_reduced_bent, ivec2(tx.x, ty.x), 0), texelFetch(u_reduced_bent, ivec2(tx.y, ty.y), 0),
                           texelFetch(u_reduced_bent, ivec2(tx.z, ty.z), 0), texelFetch(u_reduced_bent, ivec2(tx.w, ty.w), 0));
#else
    vec4 ao = textureGather(u_reduced_ao, gather_at, 0);
#endif

    for (int i = 0; i < 4; ++i) {  // constant trip count: unrolled
        ivec2 p = quad + ivec2(i & 1, i >> 1);
        if (any(greaterThanEqual(p, rect_end)) || any(lessThan(p, work_rect.xy))) continue;
        float depth = obscura_host_linear_depth(p);
        vec3 position = obscura_view_position(p, obscura_is_sky(depth) ? 1.0 : depth);
        vec2 f = vec2(p - (base << k)) * upsample.params.y;  // where p lies between the reduced texels, in [0, 1)
        vec4 d = abs(position.x * nx + position.y * ny + position.z * nz - plane_offset) * (upsample.params.x / obscura_tolerance_distance(depth));
        d = mix(vec4(3.0e19), d, valid);
        vec4 bilinear = mix(vec4(1.0 - f.x), vec4(f.x), kCornerX) * mix(vec4(1.0 - f.y), vec4(f.y), kCornerY);
        vec4 w = bilinear * exp(-d * d);
        float weight_sum = dot(w, vec4(1.0));
        // Where no texel lies on the plane: the nearest plane's texel alone (ties: their mean; none if all are sky).
        float nearest = min(min(d.x, d.y), min(d.z, d.w));
        vec4 only_nearest = vec4(equal(d, vec4(nearest))) * (nearest < 1.0e19 ? 1.0 : 0.0);
        only_nearest *= 1.0 / max(dot(only_nearest, vec4(1.0)), 1.0);
        w = weight_sum > kNoneOnPlane ? w / weight_sum : only_nearest;
        bool unoccluded = obscura_is_sky(depth) || dot(w, vec4(1.0)) == 0.0;
#if OBSCURA_UPSAMPLE_BENT_NORMALS
        vec4 value = w.x * bent[0] + w.y * bent[1] + w.z * bent[2] + w.w * bent[3];
        float bent_length = length(value.yzw);
        if (unoccluded) value = vec4(1.0, 0.0, 0.0, 1.0);
        else value.yzw = bent_length > 0.0 ? value.yzw / bent_length : vec3(0.0, 0.0, 1.0);
        store(p, value.x, value.yzw);
#else
        store(p, unoccluded ? 1.0 : dot(w, ao), vec3(0.0));
#endif
    }
}
