// GTAO's spatial denoise (the paper's 4x4 bilateral filter over its 4x4 noise pattern, centred), separable: run
// along x, then along y. The weights (1/2, 1, 1, 1, 1/2) cover each of the 4 pattern columns (rows) with the same
// total weight, so on a plane the two passes average the 16 rotations exactly. A neighbour counts less the farther
// it lies from the pixel's tangent plane (relative to the pixel's distance): occlusion does not bleed across depth
// edges, and slanted surfaces keep their whole window. With bent normals (OBSCURA_GTAO_BENT_NORMALS) the values
// are rgba16f (visibility, bent xyz) and the final pass (OBSCURA_GTAO_DENOISE_FINAL) writes the visibility (r16f)
// and the same rgba16f with the bent normal renormalised.
// With OBSCURA_GTAO_DENOISE_TARGET (the final pass as the frame's last: full resolution, no accumulation, no debug
// view) the visibility goes into the host's target (OUTPUT_FORMAT, OUTPUT_MULTIPLY: composite.comp's write) at the
// target's own precision, in the composite's place; the bent normals still go to OUT1.
// Each invocation filters a run of OBSCURA_GTAO_DENOISE_RUN pixels along the pass's axis (4 on GPUs, 16 on CPU
// rasterisers: shader_interface.h): the run's windows overlap, so it reads RUN + 4 values and depths instead of 5 per
// pixel (the pass is bound by its reads: texel fetches on CPU rasterisers, memory transactions on GPUs).
#define OBSCURA_GTAO_DENOISE_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"

layout(local_size_x = OBSCURA_GTAO_DENOISE_GROUP_X, local_size_y = OBSCURA_GTAO_DENOISE_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_linear_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_source;
#ifndef OBSCURA_GTAO_DENOISE_TARGET
#error "OBSCURA_GTAO_DENOISE_TARGET must be defined"
#endif
#if OBSCURA_GTAO_DENOISE_TARGET
#include "common/output_target.glsl"
#elif OBSCURA_GTAO_BENT_NORMALS && !OBSCURA_GTAO_DENOISE_FINAL
layout(binding = OBSCURA_IMAGE_OUT0, rgba16f) writeonly uniform image2D u_destination;
#else
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_destination;
#endif
#if OBSCURA_GTAO_BENT_NORMALS && OBSCURA_GTAO_DENOISE_FINAL
layout(binding = OBSCURA_IMAGE_OUT1, rgba16f) writeonly uniform image2D u_bent;
#endif

// The filtered value: visibility, or visibility and bent normal (scalar math where only the visibility is filtered).
#if OBSCURA_GTAO_BENT_NORMALS
#define Value vec4
Value read_value(ivec2 q) { return texelFetch(u_source, q, 0); }
#else
#define Value float
Value read_value(ivec2 q) { return texelFetch(u_source, q, 0).r; }
#endif

// The final pass's visibility: into the host's target, or the result texture.
void store_visibility(ivec2 p, float visibility) {
#if OBSCURA_GTAO_DENOISE_TARGET
    obscura_write_final_output(p, visibility);
#else
    imageStore(u_destination, p, vec4(visibility));
#endif
}

void store(ivec2 p, Value value, vec3 normal) {
#if OBSCURA_GTAO_BENT_NORMALS && OBSCURA_GTAO_DENOISE_FINAL
    store_visibility(p, value.r);
    float bent_length = length(value.gba);
    imageStore(u_bent, p, vec4(value.r, bent_length > 0.0 ? value.gba / bent_length : normal));
#elif OBSCURA_GTAO_DENOISE_FINAL
    store_visibility(p, value);
#else
    imageStore(u_destination, p, vec4(value));
#endif
}

#ifndef OBSCURA_GTAO_DENOISE_RUN
#error "OBSCURA_GTAO_DENOISE_RUN must be defined"
#endif
const int kRun = OBSCURA_GTAO_DENOISE_RUN;
const int kTaps = kRun + 4;  // the run and 2 neighbours on each side

void main() {
    ivec2 axis = gtao_denoise.config.xy;
    // The invocation's run starts at `first` and covers first + axis * i, i < kRun, clipped to the work rectangle.
    ivec2 run_step = ivec2(1) + (kRun - 1) * axis;
    ivec2 offset = ivec2(gl_GlobalInvocationID.xy) * run_step;
    if (any(greaterThanEqual(offset, work_rect.zw))) return;
    ivec2 first = work_rect.xy + offset;
    ivec2 remaining = work_rect.zw - offset;
    int run_length = min(kRun, axis.x != 0 ? remaining.x : remaining.y);

    // The window's values and positions, read once for the whole run; a tap outside the texture or on sky has
    // weight 0 (`valid`).
    Value value[kTaps];
    vec3 position[kTaps];
    float valid[kTaps];
    for (int k = 0; k < kTaps; ++k) {
        ivec2 q = first + axis * (k - 2);
        bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, depth_size.xy));
        ivec2 clamped = clamp(q, ivec2(0), depth_size.xy - 1);
        float depth = texelFetch(u_linear_depth, clamped, 0).r;
        value[k] = read_value(clamped);
        valid[k] = inside && !obscura_is_sky(depth) ? 1.0 : 0.0;
        position[k] = obscura_view_position(clamped, depth);
    }

    for (int i = 0; i < kRun; ++i) {
        if (i >= run_length) break;
        ivec2 p = first + axis * i;
        Value center = value[i + 2];
        vec3 normal = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);
        if (valid[i + 2] == 0.0) {  // sky (inside the texture by construction): passed through
            store(p, center, vec3(0.0, 0.0, 1.0));
            continue;
        }
        vec3 origin = position[i + 2];
        // Bounded: a point at (almost) the eye would make it infinite, and 0 * inf a NaN weight.
        float sharpness = gtao_denoise.params.x * (obscura_is_perspective() ? inversesqrt(max(dot(origin, origin), 1e-38))
                                                                           : 1.0 / obscura_orthographic_distance());
        // Neighbour j's weight is c_j / d_j with d_j = 1 + (its plane distance)^2 (c_j: 1/2 at the ends, 0 where
        // invalid). The mean is taken as the centre plus the weighted mean of the differences, so a uniform window
        // returns its value exactly (see bilateral_blur.comp: r16f truncates a sum that lands a rounding step below
        // it), over the common denominator d_1 d_2 d_3 d_4: one division per pixel instead of five (a CPU divides
        // at a fraction of its multiply rate). d is capped at 1e6 (a weight of 1e-6 or less) so that the product
        // stays finite.
        vec4 d, c;
        Value differences[4];
        for (int j = 0; j < 4; ++j) {
            int k = i + (j < 2 ? j : j + 1);  // window taps -2, -1, +1, +2
            float plane_distance = dot(position[k] - origin, normal) * sharpness;
            float squared = plane_distance * plane_distance;
            d[j] = squared < 1e6 ? 1.0 + squared : 1e6;  // also where it is NaN (inf * 0 near the float range)
            c[j] = valid[k] * (j == 0 || j == 3 ? 0.5 : 1.0);
            differences[j] = value[k] - center;
        }
        float d01 = d.x * d.y, d23 = d.z * d.w;
        // n_j = c_j times the product of the other three d: w_j = n_j / (d_1 d_2 d_3 d_4).
        vec4 n = c * vec4(d.y * d23, d.x * d23, d.w * d01, d.z * d01);
        Value delta_sum = n.x * differences[0] + n.y * differences[1] + n.z * differences[2] + n.w * differences[3];
        store(p, center + delta_sum / (d01 * d23 + n.x + n.y + n.z + n.w), normal);
    }
}
