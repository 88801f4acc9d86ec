// Separable depth-aware (bilateral) blur of the AO: Gaussian weights in the image, multiplied by a
// weight that falls off with the relative depth difference so occlusion does not bleed across edges.
// Run twice (x then y); the C++ side sets the axis and the region.
#define OBSCURA_BLUR_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"

layout(local_size_x = OBSCURA_BLUR_GROUP_X, local_size_y = OBSCURA_BLUR_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_linear_depth;
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_source;
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_destination;


void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    float center_ao = texelFetch(u_source, p, 0).r;
    float depth = texelFetch(u_linear_depth, p, 0).r;
    if (obscura_is_sky(depth)) {
        imageStore(u_destination, p, vec4(center_ao));
        return;
    }
    ivec2 axis = blur.config.yz;
    float sharpness = blur.params.x / depth;
    // The weighted mean is taken as the centre plus the weighted mean of the differences, so a uniform
    // neighbourhood returns its value exactly: sum / weight_sum lands a rounding step below it, which a
    // truncating conversion to r16f keeps (NVIDIA: unoccluded 1.0 came out 0.99902 after x and y).
    float delta_sum = 0.0, weight_sum = 1.0;
    for (int i = -blur.config.x; i <= blur.config.x; ++i) {
        if (i == 0) continue;
        ivec2 q = p + axis * i;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, depth_size.xy))) continue;
        float q_depth = texelFetch(u_linear_depth, q, 0).r;
        if (obscura_is_sky(q_depth)) continue;
        float dz = (q_depth - depth) * sharpness;
        float w = exp(-float(i * i) * blur.params.y - dz * dz);
        w = w >= 0.0 ? w : 0.0;  // a depth near 0 makes the sharpness infinite and 0 * inf a NaN
        delta_sum += w * (texelFetch(u_source, q, 0).r - center_ao);
        weight_sum += w;
    }
    imageStore(u_destination, p, vec4(center_ao + delta_sum / weight_sum));
}
