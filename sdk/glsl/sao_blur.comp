// SAO's bilateral reconstruction (McGuire et al., "Scalable Ambient Obscurance", sec. 2.4): one 1D pass per
// axis, 2R+1 taps `stride` pixels apart (the paper: 7 taps, stride 3, after the 2x2 step), Gaussian weights
// times max(0, 1 - sharpness * |key difference|) on the 16-bit z key packed beside the AO, so one RGBA8
// fetch gives both. Sky texels (alpha 0) are neither read nor changed. FINAL_OUTPUT 0: RGBA8 with the key
// kept (the horizontal pass); 1: plain visibility into R16F (the vertical pass, read by the composite), or with
// OBSCURA_SAO_BLUR_TARGET (the frame's last pass: full resolution, no accumulation, no debug view) into the host's
// target (OUTPUT_FORMAT, OUTPUT_MULTIPLY: composite.comp's write) at its own precision, in the composite's place.
// Each invocation filters a run of OBSCURA_SAO_BLUR_RUN pixels `stride` apart along the pass's axis (1 on GPUs, 16 on
// CPU rasterisers: shader_interface.h), whose taps are then every `stride`-th texel of one window: it reads RUN + 2R
// texels instead of 2R + 1 per pixel. R is compiled in (OBSCURA_SAO_BLUR_RADIUS): the window is an array with
// constant indices once the loops unroll; the stride is not (a run's taps are window entries whatever it is).
#define OBSCURA_SAO_BLUR_PASS 1
#include "common/shader_interface.h"

layout(local_size_x = OBSCURA_BLUR_GROUP_X, local_size_y = OBSCURA_BLUR_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_source;  // RGBA8: A, key high, key low, geometry
#ifndef OBSCURA_SAO_BLUR_TARGET
#error "OBSCURA_SAO_BLUR_TARGET must be defined"
#endif
#if OBSCURA_SAO_BLUR_TARGET
#include "common/output_target.glsl"
#elif FINAL_OUTPUT
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_destination;
#else
layout(binding = OBSCURA_IMAGE_OUT0, rgba8) writeonly uniform image2D u_destination;
#endif

#if !defined(OBSCURA_SAO_BLUR_RADIUS) || !defined(OBSCURA_SAO_BLUR_RUN)
#error "OBSCURA_SAO_BLUR_RADIUS and OBSCURA_SAO_BLUR_RUN must be defined"
#endif
const int kRadius = OBSCURA_SAO_BLUR_RADIUS;
const int kRun = OBSCURA_SAO_BLUR_RUN;
const int kTaps = kRun + 2 * kRadius;  // the run and R taps on each side

float unpack_key(vec4 texel) {
    vec2 bytes = round(texel.yz * 255.0);
    return (bytes.x * 256.0 + bytes.y) * (1.0 / 65535.0);
}

void main() {
    ivec2 axis = sao_blur.config.zw;
    int stride = sao_blur.config.y;
    bool along_x = axis.x != 0;
    // Invocation n along the axis takes residue n % stride of the block of kRun * stride pixels n / stride.
    int n = int(along_x ? gl_GlobalInvocationID.x : gl_GlobalInvocationID.y);
    int across = int(along_x ? gl_GlobalInvocationID.y : gl_GlobalInvocationID.x);
    int along = (n / stride) * kRun * stride + n % stride;
    int extent = along_x ? work_rect.z : work_rect.w;
    if (along >= extent || across >= (along_x ? work_rect.w : work_rect.z)) return;
    ivec2 first = work_rect.xy + (along_x ? ivec2(along, across) : ivec2(across, along));
    ivec2 step = axis * stride;
    int run_length = min(kRun, (extent - along + stride - 1) / stride);

    // The window, read once for the run: taps, their keys, and whether they count (inside the texture, not sky).
    vec4 tap[kTaps];
    float tap_key[kTaps];
    bool counts[kTaps];
    for (int k = 0; k < kTaps; ++k) {
        ivec2 q = first + step * (k - kRadius);
        bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, depth_size.xy));
        tap[k] = texelFetch(u_source, clamp(q, ivec2(0), depth_size.xy - 1), 0);
        tap_key[k] = unpack_key(tap[k]);
        counts[k] = inside && tap[k].w != 0.0;
    }
    float spatial[2 * kRadius + 1];  // the Gaussian's weight of each tap
    for (int j = -kRadius; j <= kRadius; ++j) spatial[j + kRadius] = exp(-float(j * j) * sao_blur.params.y);

    for (int i = 0; i < kRun; ++i) {
        if (i >= run_length) break;
        ivec2 p = first + step * i;
        vec4 center = tap[i + kRadius];
        float key = tap_key[i + kRadius];
        // The centre plus the weighted mean of the differences: a uniform neighbourhood keeps its value exactly
        // (sum / weight_sum may land a rounding step below it, which the conversion to r16f truncates).
        float delta_sum = 0.0, weight_sum = 1.0;
        // No branch on the taps (CPU rasterisers run every lane through every branch): a tap outside the texture or
        // on sky counts for nothing, chosen by selection.
        for (int j = -kRadius; j <= kRadius; ++j) {
            if (j == 0) continue;
            int k = i + kRadius + j;
            float w = spatial[j + kRadius] * max(0.0, 1.0 - sao_blur.params.x * abs(tap_key[k] - key));
            delta_sum += counts[k] ? w * (tap[k].x - center.x) : 0.0;
            weight_sum += counts[k] ? w : 0.0;
        }
        // Sky (alpha 0) is neither read nor changed.
        vec4 blurred = center.w == 0.0 ? center : vec4(center.x + delta_sum / weight_sum, center.yzw);
#if OBSCURA_SAO_BLUR_TARGET
        obscura_write_final_output(p, blurred.x);
#else
        imageStore(u_destination, p, blurred);
#endif
    }
}
