// Shared by line_sweep.comp and lsao_gather.comp: the line layout's data, where a line's sample j lies,
// and the 2D frame of a line's slice (the plane through the eye that contains the screen line).
// Needs FrameConstants, LsaoConstants and depth.glsl.
#include "common/falloff.glsl"

// Compiled in (LsaoPass::prepare): which memory paths the program takes. CPU rasterisers (1) fetch texels
// with vector gathers but load storage buffers and shared memory one invocation at a time; GPUs (0) load
// buffers through their caches in a few transactions per warp where a texture unit takes one texel a clock.
#ifndef OBSCURA_CPU_RASTERISER
#error "OBSCURA_CPU_RASTERISER must be defined"
#endif

// Line records (LsaoLayout, 16 bytes each): origin xy (float bits), the first step j inside the texture in
// the low 16 bits and the step count in the high 16, and the value index of j = 0.
#if OBSCURA_CPU_RASTERISER
layout(binding = OBSCURA_UNIT_LSAO_LINES) uniform usamplerBuffer u_lsao_lines;
uvec4 lsao_line_record(int index) { return texelFetch(u_lsao_lines, index); }
#else
layout(std430, binding = OBSCURA_SSBO_LSAO_LINES) readonly buffer LsaoLines { uvec4 lsao_line_records[]; };
uvec4 lsao_line_record(int index) { return lsao_line_records[index]; }
#endif

struct LsaoLine {
    vec2 origin;      // texel units
    vec2 step;        // the direction's step vector (texels)
    int first_step;   // j of the first sample inside the texture
    int steps;        // samples inside the texture
    int value_base;   // values buffer index of sample j is value_base + j (first_step's is a multiple of 8)
};

// Line l of direction k.
LsaoLine lsao_line(int k, int l) {
    uvec4 record = lsao_line_record(int(lsao.coverage[k].z) + l);
    LsaoLine line;
    line.origin = uintBitsToFloat(record.xy);
    line.step = lsao.directions[k].zw;
    line.first_step = bitfieldExtract(int(record.z), 0, 16);
    line.steps = int(record.z >> 16u);
    line.value_base = int(record.w);
    return line;
}

// Compiled in (LsaoPass::prepare): an aligned 8n pattern (1) or free directions (0).
#ifndef OBSCURA_LSAO_ALIGNED
#error "OBSCURA_LSAO_ALIGNED must be defined"
#endif
bool lsao_aligned() { return OBSCURA_LSAO_ALIGNED != 0; }

// Sample j of a line: aligned patterns read the texel containing origin + j * step (its centre is returned),
// free ones the point itself.
vec2 lsao_sample_point(LsaoLine line, int j) {
    vec2 p = line.origin + float(j) * line.step;
    // The layout keeps every step inside the texture in double precision; in float a last step just inside the edge
    // (x = 3361.99993 at width 3362, K = 8's step sqrt 2) can round onto it, and a fetch there is undefined.
    return lsao_aligned() ? min(floor(p), vec2(depth_size.xy - 1)) + 0.5 : p;
}

// An orthonormal 2D frame in the slice through `pixel` along screen direction `dir`: origin b0, axes a (along
// the line) and b. For a perspective projection the slice contains the eye, so every point of the line and
// the vector towards the eye lie in it exactly (the paper's (p.xy . D, p.z) is the orthographic case).
void lsao_slice_frame(vec2 pixel, vec2 dir, out vec3 b0, out vec3 a, out vec3 b) {
    b0 = obscura_view_position_at(pixel, 1.0);
    a = normalize(obscura_view_position_at(pixel + dir, 1.0) - b0);
    vec3 deeper = obscura_view_position_at(pixel, 2.0) - b0;
    b = normalize(deeper - a * dot(deeper, a));
}

vec2 lsao_in_slice(vec3 p, vec3 b0, vec3 a, vec3 b) { return vec2(dot(p - b0, a), dot(p - b0, b)); }

// Unit vector from p towards the eye, in the slice.
vec2 lsao_zenith(vec3 p, vec3 a, vec3 b) {
    vec3 t = obscura_towards_eye(p);
    return normalize(vec2(dot(t, a), dot(t, b)));
}

// sin of the receiver's own tangent towards -a (where the earlier samples of a sweep along +a lie), from its
// normal n, the unit vector towards the eye z and the slice's screen axis a (the slice holds z and a). In the
// frame (h, z), h = a made orthogonal to z, the normal is (n.h, n.z) and the tangent towards -h has sine
// n.h / |(n.h, n.z)| (for a normal facing the eye).
float lsao_receiver_sin_t_3d(vec3 n, vec3 z, vec3 a) {
    float az = dot(a, z), nz = dot(n, z);
    float nh = (dot(n, a) - nz * az) * inversesqrt(max(1.0 - az * az, 1e-12));
    float len_sq = nh * nh + nz * nz;
    if (len_sq <= 0.0) return 0.0;
    return (nz >= 0.0 ? nh : -nh) * inversesqrt(len_sq);
}

// rho(d) from d^2 (view units): rho0, or with C = 0 LSAO eq. 2.
float lsao_falloff(float distance_sq) { return obscura_rho0(lsao.falloff.x, lsao.falloff.y, distance_sq); }

// Algorithm 1's occlusion(): sin t + max(0, sin h - sin t) rho(|h|).
float lsao_occlusion(vec2 h, vec2 u, float sin_t) {
    float length_sq = dot(h, h);
    if (length_sq <= 0.0) return sin_t;
    float sin_h = dot(h, u) * inversesqrt(length_sq);
    return sin_t + max(0.0, sin_h - sin_t) * lsao_falloff(length_sq);
}

// Both of Algorithm 1's tests for one hull point in one go: (occlusion, sin h).
vec2 lsao_occlusion_and_sin_h(vec2 h, vec2 u, float sin_t) {
    float length_sq = dot(h, h);
    if (length_sq <= 0.0) return vec2(sin_t, -1.0);
    float sin_h = dot(h, u) * inversesqrt(length_sq);
    return vec2(sin_t + max(0.0, sin_h - sin_t) * lsao_falloff(length_sq), sin_h);
}

