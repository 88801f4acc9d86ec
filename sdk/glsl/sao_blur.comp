// SAO's bilateral reconstruction (McGuire et al., "Scalable Ambient Obscurance", sec. 2.4): one 1D pass per
// axis, 2R+1 taps `stride` pixels apart (the paper: 7 taps, stride 3, after the 2x2 step), Gaussian weights
// times max(0, 1 - sharpness * |key difference|) on the 16-bit z key packed beside the AO, so one RGBA8
// fetch gives both. Sky texels (alpha 0) are neither read nor changed. FINAL_OUTPUT 0: RGBA8 with the key
// kept (the horizontal pass); 1: plain visibility into R16F (the vertical pass, read by the composite).
#define OBSCURA_SAO_BLUR_PASS 1
#include "common/shader_interface.h"

layout(local_size_x = OBSCURA_BLUR_GROUP_X, local_size_y = OBSCURA_BLUR_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_source;  // RGBA8: A, key high, key low, geometry
#if FINAL_OUTPUT
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_destination;
#else
layout(binding = OBSCURA_IMAGE_OUT0, rgba8) writeonly uniform image2D u_destination;
#endif

float unpack_key(vec4 texel) {
    vec2 bytes = round(texel.yz * 255.0);
    return (bytes.x * 256.0 + bytes.y) * (1.0 / 65535.0);
}

void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    vec4 center = texelFetch(u_source, p, 0);
    if (center.w == 0.0) {
        imageStore(u_destination, p, center);
        return;
    }
    float key = unpack_key(center);
    ivec2 step = sao_blur.config.zw * sao_blur.config.y;
    // The centre plus the weighted mean of the differences: a uniform neighbourhood keeps its value exactly
    // (sum / weight_sum may land a rounding step below it, which the conversion to r16f truncates).
    float delta_sum = 0.0, weight_sum = 1.0;
    // No branch on the taps (CPU rasterisers run every lane through every branch): a tap outside the texture or on
    // sky counts for nothing, chosen by selection.
    for (int i = -sao_blur.config.x; i <= sao_blur.config.x; ++i) {
        if (i == 0) continue;  // the same for every invocation
        ivec2 q = p + step * i;
        bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, depth_size.xy));
        vec4 tap = texelFetch(u_source, clamp(q, ivec2(0), depth_size.xy - 1), 0);
        float w = exp(-float(i * i) * sao_blur.params.y) *
                  max(0.0, 1.0 - sao_blur.params.x * abs(unpack_key(tap) - key));
        bool counts = inside && tap.w != 0.0;
        delta_sum += counts ? w * (tap.x - center.x) : 0.0;
        weight_sum += counts ? w : 0.0;
    }
    imageStore(u_destination, p, vec4(center.x + delta_sum / weight_sum, center.yzw));
}
