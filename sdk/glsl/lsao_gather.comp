// LSAO's gather (Timonen, "Line-Sweep Ambient Obscurance", sec. 5.1, eq. 1): for every output pixel and
// each of the K directions, the nearest sample of the lines around it (within about
// sqrt((D_S/2)^2 + (D_L/2)^2) texels); values whose depth (and optionally normal) differ from the
// receiver's are rejected, the rest are averaged weighted by their direction's azimuthal coverage.
// A sweep value is Algorithm 1's sin t + max(0, sin h - sin t) rho; the receiver's own tangent sine in that
// direction is subtracted here, which leaves eq. 1 unchanged when every direction is kept (the tangents of
// opposite directions cancel) and keeps the mean unbiased when an edge rejects some of them.
#define OBSCURA_LSAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/lsao.glsl"

layout(local_size_x = OBSCURA_LSAO_GATHER_GROUP_X, local_size_y = OBSCURA_LSAO_GATHER_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_ao;
// The sweeps' values (R16F texels over the sweep's storage buffer).
layout(binding = OBSCURA_UNIT_LSAO_VALUES) uniform samplerBuffer u_values;

void main() {
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    float depth = texelFetch(u_depth, p, 0).r;
    bool count_taps = target_params.w == OBSCURA_DEBUG_VIEW_TAP_COUNT;
    if (obscura_is_sky(depth) || count_taps) {
        imageStore(u_ao, p, vec4(count_taps ? 0.0 : 1.0));
        return;
    }
    vec2 center = vec2(p) + 0.5;
    vec3 position = obscura_view_position(p, depth);
    vec3 normal = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);
    bool normal_test = (lsao.config.w & OBSCURA_LSAO_FLAG_NORMAL_TEST) != 0;
    vec3 towards_eye = obscura_towards_eye(position);  // every slice through the receiver contains it
    float line_spacing = lsao.falloff.w;

    float sum = 0.0, weight_sum = 0.0;
    for (int k = 0; k < lsao.config.x; ++k) {
        vec4 direction = lsao.directions[k];
        vec4 coverage = lsao.coverage[k];
        vec2 perp = vec2(-direction.y, direction.x);
        int line_count = int(coverage.w);
        int below = int(floor((dot(center, perp) - coverage.y) / line_spacing));
        float inv_step_sq = lsao.axes[k].w;
        // The nearest sample of the two lines whose ideal positions bracket the pixel (snapped origins move a
        // line by at most half a lattice step, less than half of D_L).
        float best = 1e30;
        int best_index = -1;
        vec2 best_point = vec2(0.0);
        for (int l = below; l <= below + 1; ++l) {
            if (l < 0 || l >= line_count) continue;
            LsaoLine line = lsao_line(k, l);
            if (line.steps <= 0) continue;
            int j = int(round(dot(center - line.origin, direction.zw) * inv_step_sq));
            j = clamp(j, line.first_step, line.first_step + line.steps - 1);
            vec2 q = lsao_sample_point(line, j);
            float d = dot(q - center, q - center);
            if (d < best) {
                best = d;
                best_index = line.value_base + j;
                best_point = q;
            }
        }
        if (best_index < 0) continue;
        ivec2 q_texel = clamp(ivec2(floor(best_point)), ivec2(0), depth_size.xy - 1);
        float q_depth = texelFetch(u_depth, q_texel, 0).r;
        if (obscura_is_sky(q_depth) || abs(q_depth - depth) > lsao.gather.x * depth) continue;
        if (normal_test) {
            vec3 q_normal = obscura_decode_normal(texelFetch(u_normals, q_texel, 0).xy);
            if (dot(q_normal, normal) < lsao.gather.y) continue;
        }
        float value = texelFetch(u_values, best_index).r;
        float obscurance = 0.0;  // no earlier sample: the horizon is the receiver's tangent
        if (value < 0.5 * OBSCURA_LSAO_NO_OCCLUDER) {
            obscurance = value - lsao_receiver_sin_t_3d(normal, towards_eye, lsao.axes[k].xyz);
        }
        sum += coverage.x * obscurance;
        weight_sum += coverage.x;
    }
    float ao = weight_sum > 0.0 ? sum / weight_sum : 0.0;
    float visibility = pow(clamp(1.0 - lsao.gather.z * ao, 0.0, 1.0), lsao.gather.w);
    imageStore(u_ao, p, vec4(visibility));
}
