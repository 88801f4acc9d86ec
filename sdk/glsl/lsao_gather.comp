// LSAO's gather (Timonen, "Line-Sweep Ambient Obscurance", sec. 5.1, eq. 1): for every output pixel and
// each of the K directions, the nearest sample of each of the two lines around it (within about
// sqrt((D_S/2)^2 + (D_L/2)^2) texels); values whose depth (and optionally normal) differ from the
// receiver's are rejected, the rest are averaged weighted by their direction's azimuthal coverage.
// Deviation: the paper takes the nearest sample of the two alone. Here both count, inversely to their squared
// distance, so a direction's value moves smoothly from one line to the next instead of jumping where the nearer
// line changes: that jump stippled every crease, each texel taking a sample from the wall or from the floor.
// Against the geometry truth on 16 views: lower error on all 16 (atrium -3 %), for 1.15-1.2x the gather's time on
// llvmpipe (two value loads a direction); docs/quality.md.
// A sweep value is Algorithm 1's sin t + max(0, sin h - sin t) rho; the receiver's own tangent sine in that
// direction is subtracted here, which leaves eq. 1 unchanged when every direction is kept (the tangents of
// opposite directions cancel) and keeps the mean unbiased when an edge rejects some of them. With the sample's own
// tangent (strategy 1, the default) the sweep has already subtracted that sample's tangent: its value is the
// sample's obscurance, max(0, sin h - sin t) rho. Subtracting the pixel's tangent from a sample on the other side
// of a crease or an edge (the depth test keeps it there) added the difference of two surfaces' tangents, which
// left the texels along every box edge dotted; the pixel's tangent is not needed at all then (measured on 16 views
// with the nearest sample alone, docs/quality.md: lower error on 12, more texels within 5 % on all 16, the gather
// 17 % faster on llvmpipe). With the fixed tangent in the hull (strategies 2 and 3) the pixel's is still
// subtracted: the sample's own measured slightly worse for strategy 2.
#define OBSCURA_LSAO_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/lsao.glsl"

#if OBSCURA_CPU_RASTERISER
#define GATHER_GROUP_X OBSCURA_LSAO_GATHER_GROUP_X
#define GATHER_GROUP_Y OBSCURA_LSAO_GATHER_GROUP_Y
#else
#define GATHER_GROUP_X OBSCURA_LSAO_GPU_GATHER_GROUP
#define GATHER_GROUP_Y OBSCURA_LSAO_GPU_GATHER_GROUP
#endif
layout(local_size_x = GATHER_GROUP_X, local_size_y = GATHER_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
// With OBSCURA_LSAO_GATHER_TARGET (full resolution, no accumulation, no debug view: the gather is the frame's last
// pass) the visibility goes into the host's target (OUTPUT_FORMAT, OUTPUT_MULTIPLY: composite.comp's write) at its
// own precision, in the composite's place.
#ifndef OBSCURA_LSAO_GATHER_TARGET
#error "OBSCURA_LSAO_GATHER_TARGET must be defined"
#endif
#if OBSCURA_LSAO_GATHER_TARGET
#include "common/output_target.glsl"
#else
layout(binding = OBSCURA_IMAGE_OUT0, r16f) writeonly uniform image2D u_ao;
#endif

void store(ivec2 p, float visibility) {
#if OBSCURA_LSAO_GATHER_TARGET
    obscura_write_final_output(p, visibility);
#else
    imageStore(u_ao, p, vec4(visibility));
#endif
}

// K compiled in (LsaoPass::prepare), so the loop over directions unrolls and every direction's line record
// loads can be in flight together.
#ifndef OBSCURA_LSAO_DIRECTIONS
#error "OBSCURA_LSAO_DIRECTIONS must be defined"
#endif

#if OBSCURA_CPU_RASTERISER
// The sweeps' values as R16F texels over the sweep's storage buffer.
layout(binding = OBSCURA_UNIT_LSAO_VALUES) uniform samplerBuffer u_values;
float sweep_value(int index) { return texelFetch(u_values, index).r; }

void load_depth_tile(ivec2 group_origin) {}
float candidate_depth(ivec2 texel) { return texelFetch(u_depth, texel, 0).r; }
#else
layout(std430, binding = OBSCURA_SSBO_LSAO_VALUES) readonly buffer LsaoValues { uint lsao_value_pairs[]; };
float sweep_value(int index) {
    vec2 pair = unpackHalf2x16(lsao_value_pairs[index >> 1]);
    return (index & 1) == 0 ? pair.x : pair.y;
}

// The group's depths and a margin around them in shared memory: every direction's nearest sample lies within
// about sqrt((D_S/2)^2 + (D_L/2)^2) texels of its receiver, so 16 depth reads per pixel through the texture
// unit become ~2 per pixel and 16 from shared memory. Samples outside it (clamped at a line's end) fall back
// to a texel fetch. OBSCURA_LSAO_GATHER_MARGIN is compiled in from the pattern's longest step.
#ifndef OBSCURA_LSAO_GATHER_MARGIN
#error "OBSCURA_LSAO_GATHER_MARGIN must be defined"
#endif
const int kMargin = OBSCURA_LSAO_GATHER_MARGIN;
const ivec2 kTile = ivec2(GATHER_GROUP_X, GATHER_GROUP_Y) + 2 * kMargin;
shared float s_depth[kTile.x * kTile.y];
ivec2 g_tile_origin;

void load_depth_tile(ivec2 group_origin) {
    g_tile_origin = group_origin - kMargin;
    ivec2 hi = depth_size.xy - 1;
    for (int i = int(gl_LocalInvocationIndex); i < kTile.x * kTile.y; i += GATHER_GROUP_X * GATHER_GROUP_Y) {
        ivec2 texel = clamp(g_tile_origin + ivec2(i % kTile.x, i / kTile.x), ivec2(0), hi);
        s_depth[i] = texelFetch(u_depth, texel, 0).r;
    }
    barrier();
}

float candidate_depth(ivec2 texel) {
    ivec2 t = texel - g_tile_origin;
    if (all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, kTile))) return s_depth[t.y * kTile.x + t.x];
    return texelFetch(u_depth, texel, 0).r;
}
#endif

// Directions per batch of value loads, compiled in: min(K, 16) on GPUs (the H100 at 1080p: K = 16 took
// 0.59 ms in batches of 4, 0.27 in batches of 8 and 0.24 in one of 16; K = 32 0.89 in batches of 8, 0.46
// of 16), 1 on CPU rasterisers (llvmpipe keeps a batch's arrays in memory: its gather took twice as long).
#ifndef OBSCURA_LSAO_GATHER_BATCH
#error "OBSCURA_LSAO_GATHER_BATCH must be defined"
#endif
const int kBatch = OBSCURA_LSAO_GATHER_BATCH;

// Values at or above this are the sweep's marker for "no earlier sample" (OBSCURA_LSAO_NO_OCCLUDER, 4). A value is
// below 2 (the receiver's obscurance reaches 2 at most), which a half float may round up to 2 itself: the test sits
// between the two.
const float kNoOccluderBelow = 0.75 * OBSCURA_LSAO_NO_OCCLUDER;

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
    // Every invocation helps load the tile before any leaves.
    load_depth_tile(work_rect.xy + ivec2(gl_WorkGroupID.xy) * ivec2(GATHER_GROUP_X, GATHER_GROUP_Y));
    ivec2 p = work_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    float depth = candidate_depth(p);
    bool count_taps = target_params.w == OBSCURA_DEBUG_VIEW_TAP_COUNT;
    if (obscura_is_sky(depth) || count_taps) {
        store(p, count_taps ? 0.0 : 1.0);
        return;
    }
    vec2 center = vec2(p) + 0.5;
    vec3 position = obscura_view_position(p, depth);
    vec3 normal = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);
    const bool normal_test = OBSCURA_LSAO_NORMAL_TEST != 0;  // compiled in
    vec3 towards_eye = obscura_towards_eye(position);  // every slice through the receiver contains it
    float line_spacing = lsao.falloff.w;

    // Directions in batches: first where the two lines around the pixel have their nearest samples and whether the
    // depth test keeps them (line records, cached, and the depth tile), then the batch's value loads, independent of
    // each other and in flight together, then the sums. A loop that used each value before looking up the next
    // direction's waited a full memory latency per direction (the H100: 0.64 ms at 1080p).
    float sum = 0.0, weight_sum = 0.0;
    for (int k0 = 0; k0 < OBSCURA_LSAO_DIRECTIONS; k0 += kBatch) {
        int index[kBatch], other_index[kBatch];
        float weight[kBatch], other_share[kBatch];
        for (int u = 0; u < kBatch; ++u) {
            int k = min(k0 + u, OBSCURA_LSAO_DIRECTIONS - 1);
            vec4 direction = lsao.directions[k];
            vec4 coverage = lsao.coverage[k];
            vec2 perp = vec2(-direction.y, direction.x);
            int last_line = int(coverage.w) - 1;
            int below = int(floor((dot(center, perp) - coverage.y) / line_spacing));
            // The nearest sample of each of the two lines whose ideal positions bracket the pixel (snapped origins
            // move a line by at most half a lattice step, less than half of D_L). The layout's lines cover the
            // texture, so only clamping at its edges can make them one line.
            Candidate candidates[2] = Candidate[2](nearest_on_line(k, clamp(below, 0, last_line), center),
                                                   nearest_on_line(k, clamp(below + 1, 0, last_line), center));
            // Each sample the tests keep counts inversely to its squared distance (plus a quarter texel^2, so that a
            // sample on the pixel does not take all the weight): the value moves smoothly from one line to the next
            // instead of jumping where the nearer one changes, which stippled every crease (docs/quality.md).
            float kept[2];
            for (int c = 0; c < 2; ++c) {
                ivec2 q_texel = clamp(ivec2(floor(candidates[c].point)), ivec2(0), depth_size.xy - 1);
                float q_depth = candidate_depth(q_texel);
                bool keep = k0 + u < OBSCURA_LSAO_DIRECTIONS && candidates[c].distance_sq < 1e30 &&
                            !obscura_is_sky(q_depth) &&
                            abs(q_depth - depth) <= lsao.gather.x * obscura_tolerance_distance(depth);
                if (normal_test) {
                    vec3 q_normal = obscura_decode_normal(texelFetch(u_normals, q_texel, 0).xy);
                    keep = keep && dot(q_normal, normal) >= lsao.gather.y;
                }
                kept[c] = keep ? 1.0 / (candidates[c].distance_sq + 0.25) : 0.0;
            }
            float total = kept[0] + kept[1];
            weight[u] = total > 0.0 ? coverage.x : 0.0;
            other_share[u] = total > 0.0 ? kept[1] / total : 0.0;
            index[u] = max(candidates[0].index, 0);
            other_index[u] = max(candidates[1].index, 0);
        }
        float value[kBatch], other_value[kBatch];
        for (int u = 0; u < kBatch; ++u) {
            value[u] = sweep_value(index[u]);
            other_value[u] = sweep_value(other_index[u]);
        }
        for (int u = 0; u < kBatch; ++u) {
            int k = min(k0 + u, OBSCURA_LSAO_DIRECTIONS - 1);
            // No earlier sample: the horizon is the tangent the sweep used (obscurance 0).
            float tangent = OBSCURA_LSAO_TANGENT_STRATEGY == 1 ? 0.0
                                                               : lsao_receiver_sin_t_3d(normal, towards_eye, lsao.axes[k].xyz);
            float obscurance = value[u] < kNoOccluderBelow ? value[u] - tangent : 0.0;
            float other = other_value[u] < kNoOccluderBelow ? other_value[u] - tangent : 0.0;
            sum += weight[u] * mix(obscurance, other, other_share[u]);
            weight_sum += weight[u];
        }
    }
    float ao = weight_sum > 0.0 ? sum / weight_sum : 0.0;
    float visibility = pow(clamp(1.0 - lsao.gather.z * ao, 0.0, 1.0), lsao.gather.w);
    store(p, visibility);
}
