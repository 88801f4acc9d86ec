// Separable depth-aware (bilateral) blur of the AO: Gaussian weights in the image, multiplied by a
// weight that falls off with the relative depth difference so occlusion does not bleed across edges.
// Run twice (x then y); the C++ side sets the axis and the region.
// Each invocation filters a run of OBSCURA_BLUR_RUN pixels along the pass's axis (1 on GPUs, 16 on CPU rasterisers:
// shader_interface.h): the run's windows overlap, so it reads RUN + 2 radius values and depths instead of
// 2 radius + 1 per pixel. The radius is compiled in (OBSCURA_BLUR_RADIUS): the window is an array with constant
// indices once the loops unroll.
// With OBSCURA_BLUR_TARGET (the y pass as the frame's last: full resolution, no accumulation, no debug view) it
// writes the visibility into the host's target (OUTPUT_FORMAT, OUTPUT_MULTIPLY: composite.comp's write) at the
// target's own precision, in the composite's place: the composite would only copy it there.
#define OBSCURA_BLUR_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"

layout(local_size_x = OBSCURA_BLUR_GROUP_X, local_size_y = OBSCURA_BLUR_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_linear_depth;
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_source;
#if !defined(OBSCURA_BLUR_RADIUS) || !defined(OBSCURA_BLUR_RUN) || !defined(OBSCURA_BLUR_TARGET)
#error "OBSCURA_BLUR_RADIUS, OBSCURA_BLUR_RUN and OBSCURA_BLUR_TARGET must be defined"
#endif
#if OBSCURA_BLUR_TARGET
#include "common/output_target.glsl"
#else
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_destination;
#endif

void store(ivec2 p, float visibility) {
#if OBSCURA_BLUR_TARGET
    obscura_write_final_output(p, visibility);
#else
    imageStore(u_destination, p, vec4(visibility));
#endif
}
const int kRadius = OBSCURA_BLUR_RADIUS;
const int kRun = OBSCURA_BLUR_RUN;
const int kTaps = kRun + 2 * kRadius;  // the run and `radius` neighbours on each side

void main() {
    ivec2 axis = blur.config.yz;
    // The invocation's run starts at `first` and covers first + axis * i, i < kRun, clipped to the work rectangle.
    ivec2 offset = ivec2(gl_GlobalInvocationID.xy) * (ivec2(1) + (kRun - 1) * axis);
    if (any(greaterThanEqual(offset, work_rect.zw))) return;
    ivec2 first = work_rect.xy + offset;
    ivec2 remaining = work_rect.zw - offset;
    int run_length = min(kRun, axis.x != 0 ? remaining.x : remaining.y);

    // The window, read once for the whole run; a tap outside the texture or on sky has no weight (`valid`), and its
    // value is chosen away rather than multiplied by 0 (sky outside the AO region was never written: any value).
    float value[kTaps], depth[kTaps];
    bool valid[kTaps];
    for (int k = 0; k < kTaps; ++k) {
        ivec2 q = first + axis * (k - kRadius);
        bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, depth_size.xy));
        ivec2 clamped = clamp(q, ivec2(0), depth_size.xy - 1);
        depth[k] = texelFetch(u_linear_depth, clamped, 0).r;
        value[k] = texelFetch(u_source, clamped, 0).r;
        valid[k] = inside && !obscura_is_sky(depth[k]);
    }

    for (int i = 0; i < kRun; ++i) {
        if (i >= run_length) break;
        ivec2 p = first + axis * i;
        float center_ao = value[i + kRadius], center_depth = depth[i + kRadius];
        // Bounded (a depth near 1e-37 overflowed it): GLSL does not promise NaN semantics, so the w >= 0 test below
        // is a second line only.
        float sharpness = blur.params.x / max(obscura_tolerance_distance(center_depth), 1e-30);
        // The weighted mean is taken as the centre plus the weighted mean of the differences, so a uniform
        // neighbourhood returns its value exactly: sum / weight_sum lands a rounding step below it, which a
        // truncating conversion to r16f keeps (NVIDIA: unoccluded 1.0 came out 0.99902 after x and y).
        float delta_sum = 0.0, weight_sum = 1.0;
        for (int j = -kRadius; j <= kRadius; ++j) {
            if (j == 0) continue;
            int k = i + kRadius + j;
            float dz = (depth[k] - center_depth) * sharpness;
            float w = exp(-float(j * j) * blur.params.y - dz * dz);
            // A depth near 0 makes the sharpness infinite and 0 * inf a NaN: w >= 0 fails for it.
            bool counts = valid[k] && w >= 0.0;
            delta_sum += counts ? w * (value[k] - center_ao) : 0.0;
            weight_sum += counts ? w : 0.0;
        }
        // Sky is passed through.
        store(p, obscura_is_sky(center_depth) ? center_ao : center_ao + delta_sum / weight_sum);
    }
}
