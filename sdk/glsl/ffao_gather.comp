// FFAO's SAAO gather kernel (Timonen, HPG 2013, sec. 10): every pixel's own near field plus the far field of the
// 3x3 neighbours it accepted in the box-average pass. Each pixel of a 3x3 window evaluated a different ninth of
// the orientations, so the accepted ones' mean, times nine, stands for the whole far field.
#define OBSCURA_FFAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"

layout(local_size_x = OBSCURA_FFAO_GROUP_X, local_size_y = OBSCURA_FFAO_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_box;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_terms;  // (near sum, far sum) of each pixel
layout(binding = OBSCURA_IMAGE_OUT0, r16f) uniform writeonly image2D u_ao;


void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + work_rect.xy;
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    // The tap-count debug view counts depth texels per pixel; FFAO's cost is per line and interval: 0.
    bool count_taps = target_params.w == OBSCURA_DEBUG_VIEW_TAP_COUNT;
    if (obscura_is_sky(texelFetch(u_depth, pixel, 0).r) || count_taps) {
        imageStore(u_ao, pixel, vec4(count_taps ? 0.0 : 1.0));
        return;
    }
    uint mask = uint(texelFetch(u_box, pixel, 0).w + 0.5);  // stored as float(mask) by ffao_box_average.comp
    float far_sum = 0.0, count = 0.0;
    for (int i = 0; i < 9; ++i) {
        if ((mask & (1u << uint(i))) == 0u) continue;
        far_sum += texelFetch(u_terms, pixel + ivec2(i % 3 - 1, i / 3 - 1), 0).y;
        count += 1.0;
    }
    float near_sum = texelFetch(u_terms, pixel, 0).x;
    float obscurance = clamp((near_sum + 9.0 * far_sum / max(count, 1.0)) / OBSCURA_PI * ffao.shape.y, 0.0, 1.0);
    imageStore(u_ao, pixel, vec4(pow(1.0 - obscurance, ffao.shape.z)));
}
