// FFAO's SAAO box-average kernel (Timonen, "Screen-Space Far-Field Ambient Obscurance", HPG 2013, sec. 10):
// an edge-aware 3x3 average of depth and normal. A neighbour is accepted when its normal's dot with the pixel's
// exceeds 0.5 and its depth differs by less than 3 %; the obscurance pass evaluates the pixel's share of the
// far field at the averaged receiver, and the gather pass adds the far fields of exactly the accepted
// neighbours (the mask, bit 3 (dy + 1) + (dx + 1)).
#define OBSCURA_FFAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"

layout(local_size_x = OBSCURA_FFAO_GROUP_X, local_size_y = OBSCURA_FFAO_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_IMAGE_OUT0, rgba32f) uniform writeonly image2D u_box;

const float kNormalDot = 0.5;
const float kRelativeDepth = 0.03;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + work_rect.xy;
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    float depth = texelFetch(u_depth, pixel, 0).r;
    if (obscura_is_sky(depth)) {
        imageStore(u_box, pixel, vec4(depth, 0.0, 0.0, uintBitsToFloat(0u)));
        return;
    }
    vec3 normal = obscura_decode_normal(texelFetch(u_normals, pixel, 0).xy);
    float depth_sum = 0.0;
    vec3 normal_sum = vec3(0.0);
    float count = 0.0;
    uint mask = 0u;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, depth_size.xy))) continue;
            float d = texelFetch(u_depth, q, 0).r;
            if (obscura_is_sky(d)) continue;
            vec3 m = obscura_decode_normal(texelFetch(u_normals, q, 0).xy);
            // Relative to the pixel's distance (orthographic: the tolerance distance, not the eye plane's depth).
            bool accepted = (dx == 0 && dy == 0) ||
                            (dot(m, normal) > kNormalDot && abs(d - depth) < kRelativeDepth * obscura_tolerance_distance(depth));
            if (!accepted) continue;
            depth_sum += d;
            normal_sum += m;
            count += 1.0;
            mask |= 1u << uint(3 * (dy + 1) + dx + 1);
        }
    }
    vec3 averaged = length(normal_sum) > 1e-6 ? normalize(normal_sum) : normal;
    // The mask (1..511) as a float value, exact: its bits as a float would be a denormal, which GLSL lets drivers flush
    // to 0 on the store or the fetch (and the gather would then drop the whole far field).
    imageStore(u_box, pixel, vec4(depth_sum / count, obscura_encode_normal(averaged), float(mask)));
}
