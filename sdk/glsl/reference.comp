// REFERENCE, the screen-space reference: ambient obscurance ray-traced through the depth buffer, which the
// screen-space methods converge to (Timonen, "Screen-Space Far-Field Ambient Obscurance", HPG 2013,
// eq. 1 and sec. 8):
//   AO(p, n) = 1/pi * integral over the hemisphere of rho(d(p, w)) max(0, n.w) dw,
// estimated with cosine-weighted rays, so AO = mean of rho(hit distance) (misses count 0). Each ray is
// stepped texel by texel through the whole depth buffer (guard band included) until it passes behind
// the depth field (infinitely thick, `thickness` 0, the default) or into its slab of a given thickness.
//
// What it is: the ceiling of what a screen-space method can compute from a depth buffer, not what a viewer
// sees. The depth buffer holds only the surfaces the camera sees; the geometry truth (rays against the scene's
// triangles, samples/common/geometry_truth.h; the SDK only sees depth) is the measure of that. Against it the
// infinitely thick field is too dark wherever a ray passes behind a silhouette and counts as blocked: the
// sides of convex objects, the insides of arches, the floor behind thin objects (atrium, 320x180: 0.085 mean
// abs, signed -0.073). `thickness` is the way to bring it near the geometry: metres of solid assumed behind
// every depth texel, so a ray more than that behind the field goes on; 0.3 m took the atrium to 0.026 mean
// abs (signed -0.006).
//
// Stepping: the ray is clipped in view space to the depth buffer's frustum, projected, and sampled where
// it crosses texel centres along its major screen axis (every column or row it passes, so no texel-wide
// occluder is skipped). Along the minor axis the depth field is interpolated between the two nearest
// texels in clip-w reciprocal (1/w is affine in screen space for a plane, so planes are reproduced
// exactly and a ray grazing its own surface never hits it); next to sky the surface's last texels are
// extrapolated up to the midpoint. The hit distance comes from the
// secant of (ray key - field key) between the last sample in front and the first behind, again exact
// for planes.
//
// One dispatch traces `u_batch.y` rays per pixel and accumulates the falloff sum in an R32F image; the
// last dispatch of the frame turns the sum into visibility 1 - sum / rays.
#define OBSCURA_REFERENCE_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/hash.glsl"
#include "common/falloff.glsl"

layout(local_size_x = OBSCURA_REFERENCE_GROUP_X, local_size_y = OBSCURA_REFERENCE_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_linear_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_IMAGE_OUT0, r32f) uniform image2D u_accumulator;

// Per dispatch (a program uniform, not host state): first ray index of this batch, rays in it,
// 1 if it is the frame's first batch, 1 if it is the frame's last.
layout(location = 0) uniform ivec4 u_batch;
// The dispatch's tile of the work rectangle: its offset in it (ReferencePass dispatches the rectangle in tiles).
layout(location = 1) uniform ivec2 u_tile;

const float kMiss = -1.0;

// ---- Falloff ---------------------------------------------------------------------------------------
float reference_falloff(float d) {
    vec4 table[4] = reference.table;
    return obscura_falloff(reference.config.x, d, reference.falloff, table);
}

// ---- Projection ------------------------------------------------------------------------------------
// Clip x, y, w of a view-space point (the projection's m3 = m7 = 0, as depth.glsl assumes).
vec3 reference_clip(vec3 v) {
    return vec3(proj_scale.x * v.x + proj_scale.z * v.z + proj_offset.x,
                proj_scale.y * v.y + proj_scale.w * v.z + proj_offset.y, proj_depth.z * v.z + proj_depth.w);
}

// Largest s in [0, s_max] with origin + s * direction inside the depth buffer's frustum (|x|, |y| <= w)
// and in front of the eye (w above a small fraction of the origin's).
float reference_clip_ray(vec3 origin, vec3 direction, float s_max) {
    vec3 c0 = reference_clip(origin);
    vec3 c1 = reference_clip(origin + direction) - c0;  // the linear part
    float s = s_max;
    // Each constraint a + b s >= 0 bounds s when b < 0.
    vec4 a = vec4(c0.z - c0.x, c0.z + c0.x, c0.z - c0.y, c0.z + c0.y);
    vec4 b = vec4(c1.z - c1.x, c1.z + c1.x, c1.z - c1.y, c1.z + c1.y);
    for (int i = 0; i < 4; ++i) {
        if (b[i] < 0.0) s = min(s, max(a[i], 0.0) / -b[i]);
    }
    // Between the near and far planes (|z_clip| <= w; a superset of [0, w] for [0, 1] clip depth), which
    // also bounds orthographic rays along the view axis.
    float z0 = proj_depth.x * origin.z + proj_depth.y, z1 = proj_depth.x * direction.z;
    vec2 az = vec2(c0.z - z0, c0.z + z0), bz = vec2(c1.z - z1, c1.z + z1);
    for (int i = 0; i < 2; ++i) {
        if (bz[i] < 0.0) s = min(s, max(az[i], 0.0) / -bz[i]);
    }
    if (obscura_is_perspective() && c1.z < 0.0) s = min(s, 0.999 * c0.z / -c1.z);
    return s;
}

// ---- Depth field -----------------------------------------------------------------------------------
// Key of a view depth: 1/w, affine in screen space for planes (perspective), or the depth (orthographic).
float reference_key(float view_depth) {
    return obscura_is_perspective() ? 1.0 / obscura_clip_w(view_depth) : view_depth;
}

struct FieldSample {
    float depth;  // view depth of the depth field at the sample (OBSCURA_SKY_DEPTH: nothing there)
    float key;
};

// Whether two neighbouring texels are joined by the depth field: neither is sky. (A finite thickness does
// not break it: a step between a foreground and a background texel becomes a one-texel skirt whose slab
// is as thin as any other, while rays pass behind the foreground beyond it. Splitting steps larger than
// the thickness instead would break every steep or distant surface into texel-sized plates, not
// planes, and rays grazing them would hit them.)
bool reference_continuous(float a, float b) { return !obscura_is_sky(a) && !obscura_is_sky(b); }

FieldSample reference_field_between(float z0, float z1, float f) {
    FieldSample s;
    s.key = mix(reference_key(z0), reference_key(z1), f);
    s.depth = obscura_is_perspective() ? (proj_depth.w - 1.0 / s.key) / proj_depth.z : s.key;
    return s;
}

// The depth field at screen position (major centre `column`, continuous `minor`): interpolated between
// the two texels around it; next to sky, the surface of the nearer texel continued (extrapolated from it
// and its other neighbour) up to the midpoint, so a surface's edge texels are as exact as its interior
// ones; a lone texel is taken as it is.
FieldSample reference_field(int column, float minor, bool x_major) {
    float m = minor - 0.5;
    int lo = int(floor(m));
    float f = m - float(lo);
    int limit = x_major ? depth_size.y : depth_size.x;
    // Within half a texel of the buffer's edge the outermost pair is extrapolated (f outside [0, 1]).
    int shift = clamp(lo, 0, max(limit - 2, 0)) - lo;
    lo += shift;
    f -= float(shift);
    int i0 = lo, i1 = min(lo + 1, limit - 1);
    ivec2 axis = x_major ? ivec2(0, 1) : ivec2(1, 0);
    ivec2 base = x_major ? ivec2(column, 0) : ivec2(0, column);
    float z0 = texelFetch(u_linear_depth, base + axis * i0, 0).r;
    float z1 = texelFetch(u_linear_depth, base + axis * i1, 0).r;
    if (reference_continuous(z0, z1)) return reference_field_between(z0, z1, f);

    bool near_first = f < 0.5;
    float near = near_first ? z0 : z1;
    FieldSample s;
    s.depth = near;
    s.key = obscura_is_sky(near) ? 0.0 : reference_key(near);
    if (obscura_is_sky(near)) return s;
    int outer = near_first ? i0 - 1 : i1 + 1;
    if (outer < 0 || outer >= limit) return s;
    float z_outer = texelFetch(u_linear_depth, base + axis * outer, 0).r;
    if (!reference_continuous(near, z_outer)) return s;
    // Parameter along (outer -> near) reaching past near by the sample's offset from it.
    return near_first ? reference_field_between(z_outer, near, 1.0 + f) : reference_field_between(z_outer, near, 2.0 - f);
}

// ---- Ray marching ----------------------------------------------------------------------------------
// The march's sample at `column`: its screen parameter t along the ray's screen segment (p0 + delta t, from major
// coordinate major0, major_step = +-|delta| along the major axis) and the depth field there.
FieldSample reference_sample(int column, vec2 p0, vec2 delta, float major0, float major_step, bool x_major, out float t) {
    t = (float(column) + 0.5 - major0) / major_step;
    vec2 q = p0 + delta * t;
    return reference_field(column, x_major ? q.y : q.x, x_major);
}

// Distance from `origin` (a receiver at a texel centre) along the unit `direction` to where the ray first
// enters the depth field, or kMiss.
float reference_trace(vec3 origin, vec3 direction) {
    float s_end = reference_clip_ray(origin, direction, reference.falloff.w);
    if (!(s_end > 0.0)) return kMiss;
    vec3 end = origin + direction * s_end;
    vec3 c0 = reference_clip(origin), c1 = reference_clip(end);
    vec2 size = vec2(depth_size.xy);
    vec2 p0 = (c0.xy / c0.z * 0.5 + 0.5) * size;
    vec2 p1 = (c1.xy / c1.z * 0.5 + 0.5) * size;
    vec2 delta = p1 - p0;
    bool x_major = abs(delta.x) >= abs(delta.y);
    float major_length = x_major ? abs(delta.x) : abs(delta.y);
    if (major_length < 1.0) return kMiss;  // the ray stays inside its own texel column: nothing to cross
    // Perspective-correct interpolation: point / w and 1 / w are affine in the screen parameter t.
    float k0 = 1.0 / c0.z, k1 = 1.0 / c1.z;
    vec3 q0 = origin * k0, q1 = end * k1;
    float thickness = reference.params.x;
    bool perspective = obscura_is_perspective();
    float major0 = x_major ? p0.x : p0.y;
    float major_sign = (x_major ? delta.x : delta.y) > 0.0 ? 1.0 : -1.0;
    int receiver_column = int(floor(major0));

    // g = ray key - field key in the key's "towards the eye" orientation: > 0 in front of the field.
    float previous_t = 0.0, previous_g = 0.0;
    // The field's key at the last two samples and where they were (key 0: sky or none), for the continuity test
    // below; the receiver, on the field at t = 0, is the first.
    float previous_key = perspective ? k0 : -origin.z, earlier_key = 0.0, earlier_t = 0.0;
    int steps = int(floor(major_length));
    int column_limit = x_major ? depth_size.x : depth_size.y;
    for (int i = 1; i <= steps; ++i) {
        int column = receiver_column + int(major_sign) * i;
        if (column < 0 || column >= column_limit) break;
        float t;
        FieldSample field = reference_sample(column, p0, delta, major0, major_sign * major_length, x_major, t);
        float k = mix(k0, k1, t);
        vec3 point = mix(q0, q1, t) / k;
        float ray_depth = -point.z;
        if (obscura_is_sky(field.depth)) {
            earlier_t = previous_t;
            earlier_key = previous_key;
            previous_t = t;
            previous_g = 1.0;
            previous_key = 0.0;
            continue;
        }
        float ray_key = perspective ? k : ray_depth;
        float g = perspective ? ray_key - field.key : field.key - ray_key;
        // Behind the surface by more than rounding (relative 1e-5 of the key).
        bool behind = g < -1e-5 * abs(ray_key);
        bool hit = behind && (thickness <= 0.0 || ray_depth <= field.depth + thickness);
        // With a thickness, a ray more than that far behind the field passes under it, unless it crossed the field's
        // front between the last sample and this one where the field is one surface. A skirt across a depth edge
        // (foreground and background texels joined) jumps in one step by far more than the steps on either side of
        // it; a plane (the key, 1/w, affine in the screen parameter), a fold (a crease) or a steep distant floor
        // changes by no more than about its neighbouring steps. Without this, continuous surfaces whose depth changes
        // by more than the thickness per texel let rays through: a floor-and-wall scene, which has no silhouette,
        // came out 0.003 too bright over its geometry at 320x180 with 0.3 m (0.03 over its occluded pixels).
        if (behind && !hit && previous_g >= 0.0 && previous_key != 0.0 && earlier_key != 0.0) {
            float rate_now = abs(field.key - previous_key) / (t - previous_t);
            float rate_before = abs(previous_key - earlier_key) / max(previous_t - earlier_t, 1e-30);
            float rate_after = 0.0;
            int next_column = column + int(major_sign);
            if (i < steps && next_column >= 0 && next_column < column_limit) {
                float next_t;
                FieldSample next =
                    reference_sample(next_column, p0, delta, major0, major_sign * major_length, x_major, next_t);
                if (!obscura_is_sky(next.depth)) rate_after = abs(next.key - field.key) / (next_t - t);
            }
            hit = rate_now <= 2.0 * max(rate_before, rate_after);
        }
        if (hit) {
            float hit_t = t;
            if (previous_g >= 0.0) hit_t = mix(previous_t, t, previous_g / (previous_g - g));
            vec3 hit_point = mix(q0, q1, hit_t) / mix(k0, k1, hit_t);
            return length(hit_point - origin);
        }
        earlier_t = previous_t;
        earlier_key = previous_key;
        previous_t = t;
        previous_g = g;
        previous_key = field.key;
    }
    return kMiss;
}

// Branchless orthonormal basis around a unit vector (Duff et al., "Building an Orthonormal Basis,
// Revisited", JCGT 2017).
void reference_basis(vec3 n, out vec3 b1, out vec3 b2) {
    float sign_z = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sign_z + n.z);
    float b = n.x * n.y * a;
    b1 = vec3(1.0 + sign_z * n.x * n.x * a, sign_z * b, -sign_z * n.x);
    b2 = vec3(b, sign_z + n.y * n.y * a, -n.y);
}

void main() {
    ivec2 offset = u_tile + ivec2(gl_GlobalInvocationID.xy);
    ivec2 p = work_rect.xy + offset;
    if (any(greaterThanEqual(offset, work_rect.zw))) return;
    bool first_batch = u_batch.z != 0, last_batch = u_batch.w != 0;
    float sum = first_batch ? 0.0 : imageLoad(u_accumulator, p).r;

    float depth = texelFetch(u_linear_depth, p, 0).r;
    if (!obscura_is_sky(depth)) {
        vec3 origin = obscura_view_position(p, depth);
        vec3 normal = obscura_decode_normal(texelFetch(u_normals, p, 0).xy);
        vec3 tangent, bitangent;
        reference_basis(normal, tangent, bitangent);
        // A rank-1 lattice in [0,1)^2 (the R2 sequence, generator 1/phi_2 and 1/phi_2^2 in 0.32 fixed
        // point) with a per-pixel Cranley-Patterson rotation: any prefix of it is well stratified, so
        // batches and frames with consecutive first rays accumulate into one low-discrepancy set. The frame moves
        // the first ray (ReferencePass::first_ray_of_frame), not the rotation: the frames' R2 offset is this
        // lattice's own generator, so adding it to the rotation only shifted the sequence by one ray a frame.
        vec2 noise = obscura_pixel_hash_noise(p);
        uvec2 rotation = uvec2(noise * 4294967296.0);
        for (int j = 0; j < u_batch.y; ++j) {
            uint index = uint(u_batch.x) + uint(j);
            uvec2 lattice = rotation + index * uvec2(3242174889u, 2447445414u);
            vec2 u = vec2(lattice >> 8u) * (1.0 / 16777216.0);
            float r = sqrt(u.x);
            float phi = 2.0 * OBSCURA_PI * u.y;
            vec3 direction = tangent * (r * cos(phi)) + bitangent * (r * sin(phi)) + normal * sqrt(max(0.0, 1.0 - u.x));
            float d = reference_trace(origin, direction);
            if (d >= 0.0) sum += reference_falloff(d);
        }
    }
    float value = last_batch ? (obscura_is_sky(depth) ? 1.0 : clamp(1.0 - sum * reference.params.y, 0.0, 1.0)) : sum;
    // The tap-count debug view counts texel reads of the methods that take a few; rays take thousands.
    if (last_batch && target_params.w == OBSCURA_DEBUG_VIEW_TAP_COUNT) value = 0.0;
    imageStore(u_accumulator, p, vec4(value));
}
