// FFAO's SAAO blur (Timonen, HPG 2013, sec. 10): a 5x5 box filter over the visibilities within 7 % of the
// pixel's own, which smooths the small noise where far fields of different pixels meet without blurring
// across edges.
#define OBSCURA_FFAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"

layout(local_size_x = OBSCURA_FFAO_GROUP_X, local_size_y = OBSCURA_FFAO_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_source;
layout(binding = OBSCURA_IMAGE_OUT0, r16f) uniform writeonly image2D u_blurred;

const float kThreshold = 0.07;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + work_rect.xy;
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    float centre = texelFetch(u_source, pixel, 0).r;
    if (obscura_is_sky(texelFetch(u_depth, pixel, 0).r)) {
        imageStore(u_blurred, pixel, vec4(centre));
        return;
    }
    float sum = 0.0, count = 0.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), depth_size.xy - 1);
            if (obscura_is_sky(texelFetch(u_depth, q, 0).r)) continue;
            float v = texelFetch(u_source, q, 0).r;
            if (abs(v - centre) > kThreshold) continue;
            sum += v;
            count += 1.0;
        }
    }
    imageStore(u_blurred, pixel, vec4(sum / max(count, 1.0)));
}
