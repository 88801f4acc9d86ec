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

// A line's sample nearest to a texel centre (clamped to the line's samples inside the texture), as the
// index of its value, its position and its squared distance (1e30 when the line misses the texture).
struct Candidate {
    float distance_sq;
    int index;
    vec2 point;
};

Candidate nearest_on_line(int k, int l, vec2 center) {
    LsaoLine line = lsao_line(k, l);
    int j = int(round(dot(center - line.origin, line.step) * lsao.axes[k].w));
    j = clamp(j, line.first_step, line.first_step + max(line.steps, 1) - 1);
    Candidate c;
    c.point = lsao_sample_point(line, j);
    c.distance_sq = line.steps > 0 ? dot(c.point - center, c.point - center) : 1e30;
    c.index = line.value_base + j;
    return c;
}

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
    const bool normal_test = OBSCURA_LSAO_NORMAL_TEST != 0;  // compiled in
    vec3 towards_eye = obscura_towards_eye(position);  // every slice through the receiver contains it
    float line_spacing = lsao.falloff.w;

    float sum = 0.0, weight_sum = 0.0;
    for (int k = 0; k < lsao.config.x; ++k) {
        vec4 direction = lsao.directions[k];
        vec4 coverage = lsao.coverage[k];
        vec2 perp = vec2(-direction.y, direction.x);
        int last_line = int(coverage.w) - 1;
        int below = int(floor((dot(center, perp) - coverage.y) / line_spacing));
        // The nearest sample of the two lines whose ideal positions bracket the pixel (snapped origins move a
        // line by at most half a lattice step, less than half of D_L). The layout's lines cover the texture,
        // so only clamping at its edges can make them one line.
        Candidate nearest = nearest_on_line(k, clamp(below, 0, last_line), center);
        Candidate other = nearest_on_line(k, clamp(below + 1, 0, last_line), center);
        if (other.distance_sq < nearest.distance_sq) nearest = other;
        ivec2 q_texel = clamp(ivec2(floor(nearest.point)), ivec2(0), depth_size.xy - 1);
        float q_depth = texelFetch(u_depth, q_texel, 0).r;
        bool keep = nearest.distance_sq < 1e30 && !obscura_is_sky(q_depth) &&
                    abs(q_depth - depth) <= lsao.gather.x * depth;
        if (normal_test) {
            vec3 q_normal = obscura_decode_normal(texelFetch(u_normals, q_texel, 0).xy);
            keep = keep && dot(q_normal, normal) >= lsao.gather.y;
        }
        float value = texelFetch(u_values, max(nearest.index, 0)).r;
        // No earlier sample: the horizon is the receiver's tangent.
        float obscurance = value < 0.5 * OBSCURA_LSAO_NO_OCCLUDER
                               ? value - lsao_receiver_sin_t_3d(normal, towards_eye, lsao.axes[k].xyz)
                               : 0.0;
        float weight = keep ? coverage.x : 0.0;
        sum += weight * obscurance;
        weight_sum += weight;
    }
    float ao = weight_sum > 0.0 ? sum / weight_sum : 0.0;
    float visibility = pow(clamp(1.0 - lsao.gather.z * ao, 0.0, 1.0), lsao.gather.w);
    imageStore(u_ao, p, vec4(visibility));
}
