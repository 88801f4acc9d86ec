// GTAO's spatial denoise (the paper's 4x4 bilateral filter over its 4x4 noise pattern, centred), separable: run
// along x, then along y. The weights (1/2, 1, 1, 1, 1/2) cover each of the 4 pattern columns (rows) with the same
// total weight, so on a plane the two passes average the 16 rotations exactly. A neighbour counts less the farther
// it lies from the pixel's tangent plane (relative to the pixel's distance): occlusion does not bleed across depth
// edges, and slanted surfaces keep their whole window. With bent normals (OBSCURA_GTAO_BENT_NORMALS) the values
// are rgba16f (visibility, bent xyz) and the final pass (OBSCURA_GTAO_DENOISE_FINAL) writes the visibility (r16f)
// and the same rgba16f with the bent normal renormalised.
#define OBSCURA_GTAO_DENOISE_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"

layout(local_size_x = OBSCURA_GTAO_DENOISE_GROUP_X, local_size_y = OBSCURA_GTAO_DENOISE_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_linear_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_source;
#if OBSCURA_GTAO_BENT_NORMALS && !OBSCURA_GTAO_DENOISE_FINAL
layout(binding = OBSCURA_IMAGE_OUT0, rgba16f) writeonly uniform image2D u_destination;
#else
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_destination;
#endif
#if OBSCURA_GTAO_BENT_NORMALS && OBSCURA_GTAO_DENOISE_FINAL
layout(binding = OBSCURA_IMAGE_OUT1, rgba16f) writeonly uniform image2D u_bent;
#endif

void store(ivec2 p, vec4 value, vec3 normal) {
#if OBSCURA_GTAO_BENT_NORMALS && OBSCURA_GTAO_DENOISE_FINAL
    imageStore(u_destination, p, vec4(value.r));
    float bent_length = length(value.gba);
    imageStore(u_bent, p, vec4(value.r, bent_length > 0.0 ? value.gba / bent_length : normal));
#elif OBSCURA_GTAO_BENT_NORMALS
    imageStore(u_destination, p, value);
#else
    imageStore(u_destination, p, vec4(value.r));
#endif
}

void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    vec4 center = texelFetch(u_source, p, 0);
    float depth = texelFetch(u_linear_depth, p, 0).r;
    vec3 normal = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);
    if (obscura_is_sky(depth)) {
        store(p, center, vec3(0.0, 0.0, 1.0));
        return;
    }
    vec3 position = obscura_view_position(p, depth);
    float sharpness = gtao_denoise.params.x / length(position);
    ivec2 axis = gtao_denoise.config.xy;
    // The mean is the centre plus the weighted mean of the differences, so a uniform window returns its value
    // exactly (see bilateral_blur.comp: r16f truncates a sum that lands a rounding step below it).
    vec4 delta_sum = vec4(0.0);
    float weight_sum = 1.0;
    for (int i = -2; i <= 2; ++i) {
        if (i == 0) continue;
        ivec2 q = p + axis * i;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, depth_size.xy))) continue;
        float q_depth = texelFetch(u_linear_depth, q, 0).r;
        if (obscura_is_sky(q_depth)) continue;
        float plane_distance = dot(obscura_view_position(q, q_depth) - position, normal) * sharpness;
        float w = (abs(i) == 2 ? 0.5 : 1.0) / (1.0 + plane_distance * plane_distance);
        delta_sum += w * (texelFetch(u_source, q, 0) - center);
        weight_sum += w;
    }
    store(p, center + delta_sum / weight_sum, normal);
}
