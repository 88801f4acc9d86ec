// FFAO's obscurance kernel (Timonen, "Screen-Space Far-Field Ambient Obscurance", HPG 2013, sec. 4 and 9,
// Algorithm 2). For every pixel and each of the K sectors (two per scanned orientation, one on each side):
//   - the receiver's azimuthal plane is the plane through the eye that holds the scan direction's view-space
//     vector A and the receiver p; in it, a point at x = q . A and view z maps to (x, z * zscale), exactly
//     for points of the pixel's own screen line (zscale = 1 orthographically);
//   - a near-field search reads the depth texels of the pixel's screen line up to the first far-field interval
//     (B0 to 2 B0 texels, sec. 9), each a slab;
//   - the far field walks the intervals outwards, one level up whenever the interval is aligned and no longer
//     than its distance (about one virtual point per octave of distance), and for each of the sector's
//     segments averages the peaks over the lines inside the segment at that distance (prefix sums, sec. 7),
//     reconstructs the virtual point where the receiver angles through m0 and m1 meet (sec. 6) and adds it as a
//     slab if it rises above every point before it;
//   - a slab adds |n_k| (L(a_i, b_i, c_i, d) - L(a_{i-1}, b_i, c_i, d)) (eq. 3), L from the table.
// The segments' shares are their azimuthal widths around the receiver's zenith (the w_k of eq. 2), so
// perspective's uneven mapping of screen angles around off-centre pixels is accounted for.
#define OBSCURA_FFAO_PASS 1
#define OBSCURA_FFAO_CHUNK_PASS 1
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/ffao.glsl"
#include "common/hash.glsl"

layout(local_size_x = OBSCURA_FFAO_GROUP_X, local_size_y = OBSCURA_FFAO_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;
layout(binding = OBSCURA_UNIT_FFAO_TABLE) uniform sampler3D u_table;
#ifndef OBSCURA_FFAO_SAAO
#error "OBSCURA_FFAO_SAAO must be defined"
#endif
#if OBSCURA_FFAO_SAAO
// SAAO: the box-average pass's receiver (depth, octahedral normal, accepted-neighbour mask) in, the near and far
// sums out.
layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_box;
#if OBSCURA_FFAO_CHUNKED
layout(binding = OBSCURA_IMAGE_OUT0, rg32f) uniform image2D u_terms;
#else
layout(binding = OBSCURA_IMAGE_OUT0, rg32f) uniform writeonly image2D u_terms;
#endif
#else
layout(binding = OBSCURA_IMAGE_OUT0, r16f) uniform writeonly image2D u_ao;
#if OBSCURA_FFAO_CHUNKED
layout(binding = OBSCURA_IMAGE_OUT1, r32f) uniform image2D u_running;  // the total so far
#endif
#endif
#ifndef OBSCURA_FFAO_BUFFER_TEXTURES
#error "OBSCURA_FFAO_BUFFER_TEXTURES must be defined"
#endif
// `index` is global (the column records'); the buffer holds the current chunk, from entry ffao_chunk.range.z.
#if OBSCURA_FFAO_BUFFER_TEXTURES
layout(binding = OBSCURA_UNIT_FFAO_PEAKS) uniform samplerBuffer u_ffao_peaks;
vec4 ffao_peak(int index) { return texelFetch(u_ffao_peaks, index - ffao_chunk.range.z); }
#else
layout(std430, binding = OBSCURA_SSBO_FFAO_PEAKS) readonly buffer FfaoPeaks { vec4 ffao_peaks[]; };
vec4 ffao_peak(int index) { return ffao_peaks[index - ffao_chunk.range.z]; }
#endif
// Chunked (OBSCURA_FFAO_CHUNKED, compiled in): this dispatch covers the chunk's orientations only and carries the
// running sums from chunk to chunk, through the SAAO terms themselves (rg32f) or, without SAAO, a r32f texture of
// the running total; the last chunk writes the result. The sums continue in the same order as in one dispatch, so
// the AO is the same to the bit.
#ifndef OBSCURA_FFAO_CHUNKED
#error "OBSCURA_FFAO_CHUNKED must be defined"
#endif
// The far field's source (compiled in): the scanned peaks (0) or the depth MIP pyramid (1, sec. 5).
#ifndef OBSCURA_FFAO_MIPMAP
#error "OBSCURA_FFAO_MIPMAP must be defined"
#endif
// A finite thickness (compiled in: CPU rasterisers run every lane through both sides of a branch, and the thickness
// selects between column sums, line points and slab bottoms): the scan then keeps single lines (no prefix sums).
#ifndef OBSCURA_FFAO_FINITE_THICKNESS
#error "OBSCURA_FFAO_FINITE_THICKNESS must be defined"
#endif
const bool kFiniteThickness = OBSCURA_FFAO_FINITE_THICKNESS != 0;

// ---- The receiver's plane for the current sector ----------------------------------------------------------
vec2 g_p;        // the receiver in the plane
vec2 g_zenith;   // unit, towards the eye
vec2 g_out;      // unit, perpendicular to the zenith, towards the sector
float g_zscale;  // view z -> the plane's second coordinate
float g_d;       // angle of the projected normal from the zenith towards the sector
bool g_perspective;

// Angle of v from the zenith towards the sector, in [0, pi] for points on the sector's side.
float zenith_angle(vec2 v) { return atan(dot(v, g_out), dot(v, g_zenith)); }

// L(a, b, c, d) from the table (its a axis is a - d, see ffao_table.comp): a, c in radians, beta = b / s.
float table_l(float a, float beta, float c) {
    float ta = clamp((a - g_d) / OBSCURA_PI + 0.5, 0.0, 1.0);
    float tb = beta / (1.0 + beta);
    float tc = clamp(c / (0.5 * OBSCURA_PI) - 1.0, 0.0, 1.0);
    float td = clamp(g_d / OBSCURA_PI + 0.5, 0.0, 1.0);
    float dz = floor(td * float(OBSCURA_FFAO_TABLE_D - 1) + 0.5);
    vec3 coord = vec3((ta * float(OBSCURA_FFAO_TABLE_A - 1) + 0.5) / float(OBSCURA_FFAO_TABLE_A),
                      (tb * float(OBSCURA_FFAO_TABLE_B - 1) + 0.5) / float(OBSCURA_FFAO_TABLE_B),
                      (dz * float(OBSCURA_FFAO_TABLE_C) + tc * float(OBSCURA_FFAO_TABLE_C - 1) + 0.5) /
                          float(OBSCURA_FFAO_TABLE_C * OBSCURA_FFAO_TABLE_D));
    return textureLod(u_table, coord, 0.0).r;
}

// Eq. 3 for the slab topped by h (plane coordinates): adds its share to `ao` if h rises above the horizon so
// far and lowers the horizon to it. `horizon` holds that angle (from the zenith towards the sector) and its
// cosine: most points stay below it, and for those the test is a dot product instead of an arctangent (the
// cosine falls as the angle grows on [0, pi]; points behind the zenith count as angle 0). A finite thickness
// t (sec. 11) ends the slab t deeper than h, as the reference's field ends: rays below its bottom pass under
// it, so a_{i-1} becomes the bottom's angle where that is the smaller angle from the zenith (the slab hides the
// arc from its top down to its bottom only; sec. 11's max(), taken literally in these angles, would hide the whole
// arc down to a_{i-1}, as infinite thickness does).
// slab_cosine is the test, raise_horizon the slab's share for a point known to rise.
float slab_cosine(vec2 h) {
    vec2 v = h - g_p;
    float length_sq = dot(v, v);
    if (!(length_sq > 0.0)) return -2.0;  // h = p: below every horizon
    return dot(v, g_out) < 0.0 ? 1.0 : dot(v, g_zenith) * inversesqrt(length_sq);
}

void raise_horizon(vec2 h, float cosine, inout float ao, inout vec2 horizon) {
    vec2 v = h - g_p;
    bool behind = dot(v, g_out) < 0.0;
    float a = behind ? 0.0 : max(zenith_angle(v), 0.0);
    // The slab continues h along its view ray: away from the eye (the plane's origin), or straight down.
    vec2 u = g_perspective ? normalize(h) : vec2(0.0, -1.0);
    float b = g_perspective ? abs(g_p.x * u.y - g_p.y * u.x) : abs(dot(v, g_out));
    // |angle|: a slab whose ray leans past the zenith's other side (h just behind p) mirrors, and atan(-0, -1)
    // would read -pi for the orthographic pi.
    float c = g_perspective ? abs(zenith_angle(u)) : OBSCURA_PI;
    float beta = b / ffao.shape.x;
    float lowest = horizon.x;
    float thickness = ffao.shape.w;
    if (kFiniteThickness) {
        float depth = -h.y / g_zscale;
        vec2 bottom = g_perspective ? h * ((depth + thickness) / depth) : h - vec2(0.0, thickness);
        lowest = min(horizon.x, max(zenith_angle(bottom - g_p), a));
    }
    ao += table_l(a, beta, c) - table_l(lowest, beta, c);
    horizon = vec2(a, cosine);
}

void add_slab(vec2 h, inout float ao, inout vec2 horizon) {
    float cosine = slab_cosine(h);
    if (cosine > horizon.y) raise_horizon(h, cosine, ao, horizon);
}

// No horizon yet: straight down (angle pi, cosine -1).
const vec2 kNoHorizon = vec2(OBSCURA_PI, -1.0);

// Azimuth of screen direction `sd` around the zenith z3 of view point p3: its view-space vector made
// perpendicular to z3, normalised.
vec3 azimuth_vector(vec2 sd, vec3 z3) {
    vec3 a = normalize(vec3(sd * ffao.view.xy, 0.0));
    return normalize(a - z3 * dot(a, z3));
}

// Sum over the lines [la, lb] of column's entries (prefix sums restarting every block): (m0, m1 back,
// m1 forward, valid lines). Single lines (no prefix sums) read the entry of line la.
vec4 column_sum(FfaoColumn column, int la, int lb) {
    if (kFiniteThickness) {  // single lines
        int e = la - column.first_line;
        return e >= 0 && e < column.lines ? ffao_peak(column.offset + e) : vec4(0.0);
    }
    int ea = max(la - column.first_line, 0);
    int eb = min(lb - column.first_line, column.lines - 1);
    int block = 1 << column.block_shift;
    eb = min(eb, ea + block - 1);  // a run spans at most two blocks
    if (eb < ea) return vec4(0.0);
    vec4 sum = ffao_peak(column.offset + eb);
    int block_a = ea >> column.block_shift;
    if ((ea & (block - 1)) != 0) sum -= ffao_peak(column.offset + ea - 1);
    if ((eb >> column.block_shift) != block_a) sum += ffao_peak(column.offset + block_a * block + block - 1);
    return sum;
}

// A quad whose four texels lie on one plane: |k00 + k11 - k10 - k01| within this fraction of the quad's 1/w
// (orthographic: of the tolerance distance), as LSAO's free pattern tests it (line_sweep.comp).
const float kPlanarity = 1e-3;
// ... and whose texels differ by at most this fraction (a depth edge along a row or column of texels is planar in that
// sense: its quad does not twist).
const float kContinuity = 0.1;

// The scene point on the pixel's screen line at q (texel units). A continuous field (infinite thickness)
// interpolates the four texels around q bilinearly in 1/w (orthographic: in depth), which reproduces planes
// exactly: the texel under q, taken at its own centre, lies off the line and so off the receiver's plane, and
// a floor's texels then rose above its tangent (2 % of false occlusion on the analytic scene's open floor).
// With a finite thickness each point is a slab, which must not be interpolated across a depth edge (it would make
// a slab of nothing between the two surfaces): there the quad must lie on one plane (kPlanarity) to be
// interpolated, and a quad across an edge or a crease takes the texel under q at its centre (the paper's
// snapping). Snapping everywhere left open floors 4 % too dark on average (up to 8 %) with thickness 0.3 m. Any
// quad touching sky snaps as well. False for sky.
bool line_point(vec2 q, out vec3 position) {
    // One gather fetches the quad, clamped at the edges like the sampler. It is addressed at the quad's shared
    // corner, half a texel from any rounding boundary, so it cannot pick a neighbouring quad. Its components are
    // the texels (0,1), (1,1), (1,0), (0,0); reordered to (0,0), (1,0), (0,1), (1,1).
    vec2 f = q - 0.5;
    vec2 base = floor(f);
    vec2 t = f - base;
    vec4 d = textureGather(u_depth, (base + 1.0) / vec2(depth_size.xy), 0).wzxy;
    if (all(lessThan(d, vec4(OBSCURA_SKY_THRESHOLD)))) {
        bool perspective = obscura_is_perspective();
        vec4 k = perspective ? 1.0 / d : d;
        float scale = perspective ? max(max(k.x, k.y), max(k.z, k.w)) : obscura_orthographic_distance();
        // Planar (no twist) and continuous: a depth step along a texel row or column has no twist, and interpolating
        // it would put points in the gap between the two surfaces.
        float spread = max(max(k.x, k.y), max(k.z, k.w)) - min(min(k.x, k.y), min(k.z, k.w));
        bool one_plane = abs(k.x + k.w - k.y - k.z) <= kPlanarity * scale && spread <= kContinuity * scale;
        if (!kFiniteThickness || one_plane) {
            float kk = mix(mix(k.x, k.y, t.x), mix(k.z, k.w, t.x), t.y);
            position = obscura_view_position_at(q, perspective ? 1.0 / kk : kk);
            return true;
        }
    }
    // The texel under q is one of the quad's, at floor(q) - base (0 or 1 per axis; the gather clamps at the edges
    // as `texel` is clamped): no second read.
    ivec2 texel = clamp(ivec2(floor(q)), ivec2(0), depth_size.xy - 1);
    bvec2 upper = greaterThanEqual(q - base, vec2(1.0));
    float depth = upper.y ? (upper.x ? d.w : d.z) : (upper.x ? d.y : d.x);
    if (obscura_is_sky(depth)) return false;
    position = obscura_view_position(texel, depth);
    return true;
}

#if OBSCURA_FFAO_MIPMAP
// ---- The paper's baseline (sec. 5): far-field points from the depth MIP pyramid ---------------------------
// Sky-aware bilinear depth of level `lod` at screen position q: (sum of weighted depths, weight).
vec2 bilinear_geometry(vec2 q, int lod) {
    ivec2 size = textureSize(u_depth, lod);
    vec2 pos = q / float(1 << lod) - 0.5;
    ivec2 base = ivec2(floor(pos));
    vec2 f = pos - vec2(base);
    vec2 sum = vec2(0.0);
    for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        float z = texelFetch(u_depth, clamp(base + o, ivec2(0), size - 1), lod).r;
        if (!obscura_is_sky(z)) sum += vec2(z * w, w);
    }
    return sum;
}

// Trilinear depth at a fractional level (the hardware's filter, done by hand so sky texels drop out).
float trilinear_geometry(vec2 q, float level) {
    int l0 = int(floor(level));
    vec2 a = bilinear_geometry(q, l0);
    vec2 b = l0 < ffao.options.z ? bilinear_geometry(q, l0 + 1) : a;
    float t = level - float(l0);
    if (a.y <= 0.0 && b.y <= 0.0) return OBSCURA_SKY_DEPTH;
    if (a.y <= 0.0) return b.x / b.y;
    if (b.y <= 0.0) return a.x / a.y;
    return mix(a.x / a.y, b.x / b.y, t);
}

// Samples along the sector's centre line from the near field's end, each step 1.5 times the last, at the level
// whose texels match the sector's width there, and once more at the depth texture's edge.
void mipmap_far_field(vec2 centre, vec2 d, float start, float tan_half, vec3 axis, inout float ao,
                      inout vec2 horizon) {
    vec2 size = vec2(depth_size.xy);
    float edge = 1e30;
    for (int i = 0; i < 2; ++i) {
        if (d[i] > 1e-6) edge = min(edge, (size[i] - 0.5 - centre[i]) / d[i]);
        if (d[i] < -1e-6) edge = min(edge, (0.5 - centre[i]) / d[i]);
    }
    float distance = start, step = 1.0;
    for (int guard = 0; guard < 64; ++guard) {
        distance += step;
        step *= 1.5;
        bool last = distance >= edge;
        distance = min(distance, edge);
        if (distance <= start) break;
        vec2 q = centre + distance * d;
        float level = clamp(log2(max(2.0 * distance * tan_half, 1.0)), 0.0, float(ffao.options.z));
        float depth = trilinear_geometry(q, level);
        if (!obscura_is_sky(depth)) {
            vec3 v = obscura_view_position_at(q, depth);
            add_slab(vec2(dot(v, axis), v.z * g_zscale), ao, horizon);
        }
        if (last) break;
    }
}
#endif

// One line orientation (both its sectors) for the receiver at p (view space, texel `pixel`, distance `depth`)
// with normal n: adds the near field's share to `near_sum` and, if `far_field`, what the far field adds
// beyond it to `far_sum` (sums of width |n_k| integral, over segments).
void evaluate_orientation(int k, ivec2 pixel, vec3 p, vec3 n, float depth, bool far_field, inout float near_sum,
                          inout float far_sum) {
    vec3 zenith3 = obscura_towards_eye(p);
    vec2 centre = vec2(pixel) + 0.5;
    ivec2 size = depth_size.xy;
    int sectors = ffao.config.x, segments = ffao.config.y, b0 = ffao.config.z, levels = ffao.config.w;
    float half_sector = OBSCURA_PI / float(sectors);
    // Jitter (sec. 11.1): every sector's lines move by the same fraction of the segment's width at each
    // distance, per pixel.
    float jitter = ffao.options.x != 0 ? obscura_pixel_noise(pixel).x - 0.5 : 0.0;
    const bool single_lines = kFiniteThickness;
    vec2 dir = ffao.orientation[k].xy;
    vec2 perp = vec2(-dir.y, dir.x);
    vec3 axis = vec3(ffao.axes[k].xy, 0.0);
    float x_p = dot(p, axis);
    g_zscale = g_perspective ? length(p - x_p * axis) / depth : 1.0;
    g_p = vec2(x_p, p.z * g_zscale);
    g_zenith = g_perspective ? normalize(-g_p) : vec2(0.0, 1.0);
    // The normal in the plane: along A and along the plane's second axis (towards the eye side).
    vec3 second = g_perspective ? -normalize(p - x_p * axis) : vec3(0.0, 0.0, 1.0);
    vec2 nk = vec2(dot(n, axis), dot(n, second));
    float n_length = length(nk);
    float u_p = dot(centre, dir) - ffao.orientation[k].z;
    float v_p = dot(centre, perp) - ffao.orientation[k].w - 0.5;  // in line indices
    int i_p = int(floor(u_p / float(b0)));
    int grid_steps = ffao.lines[k].z;
    for (int side = -1; side <= 1; side += 2) {
        // Outwards: the perpendicular of the zenith on the sector's side of the receiver.
        vec2 o = vec2(g_zenith.y, -g_zenith.x);
        g_out = dot(o, vec2(float(side), 0.0)) >= 0.0 ? o : -o;
        g_d = atan(dot(nk, g_out), dot(nk, g_zenith));
        // Near field: the pixel's own screen line up to the first far interval's near edge.
        int far_start = side < 0 ? (i_p - 1) * b0 : (i_p + 2) * b0;
        float near_length = abs(float(far_start) - u_p);
        // It runs in batches of 32 steps: a light loop marks the steps whose points rise above the horizon so
        // far, a second evaluates only those slabs (a few per batch). SIMD hardware then pays the table
        // lookups once per rising point of its slowest lane instead of once per step: CPU rasterisers execute
        // every branch under a mask, and a GPU's warp diverges on the rises.
        float near_ao = 0.0;
        vec2 near_horizon = kNoHorizon;
        int near_steps = int(ceil(near_length)) - 1;  // t = 1 ... near_steps have t < near_length
        for (int first = 1; first <= near_steps; first += 32) {
            int batch = min(32, near_steps + 1 - first);
            uint rising = 0u;
            float top = near_horizon.y;
            for (int j = 0; j < batch; ++j) {
                vec2 q_screen = centre + float(side * (first + j)) * dir;
                vec3 q;
                if (all(greaterThanEqual(q_screen, vec2(0.0))) && all(lessThan(q_screen, vec2(size))) &&
                    line_point(q_screen, q)) {
                    float cosine = slab_cosine(vec2(dot(q, axis), q.z * g_zscale));
                    if (cosine > top) {
                        top = cosine;
                        rising |= 1u << uint(j);
                    }
                }
            }
            while (rising != 0u) {
                int j = findLSB(rising);
                rising &= rising - 1u;
                vec3 q;
                line_point(centre + float(side * (first + j)) * dir, q);
                vec2 h = vec2(dot(q, axis), q.z * g_zscale);
                raise_horizon(h, slab_cosine(h), near_ao, near_horizon);
            }
        }
        float sector_width = acos(clamp(dot(azimuth_vector(float(side) * dir - tan(half_sector) * perp, zenith3),
                                            azimuth_vector(float(side) * dir + tan(half_sector) * perp, zenith3)),
                                        -1.0, 1.0));
        near_sum += sector_width * n_length * near_ao;
        if (!far_field) continue;
#if OBSCURA_FFAO_MIPMAP
        float ao = near_ao;
        vec2 horizon = near_horizon;
        mipmap_far_field(centre, float(side) * dir, near_length, tan(half_sector), axis, ao, horizon);
        far_sum += sector_width * n_length * (ao - near_ao);
#else
        // Far field, per segment.
        vec3 previous_boundary = azimuth_vector(float(side) * dir - tan(half_sector) * perp, zenith3);
        for (int s = 0; s < segments; ++s) {
            float alpha_lo = -half_sector + 2.0 * half_sector * float(s) / float(segments);
            float alpha_hi = -half_sector + 2.0 * half_sector * float(s + 1) / float(segments);
            float tan_lo = tan(alpha_lo), tan_hi = tan(alpha_hi);
            vec3 boundary = azimuth_vector(float(side) * dir + tan_hi * perp, zenith3);
            float width = acos(clamp(dot(previous_boundary, boundary), -1.0, 1.0));
            previous_boundary = boundary;
            float ao = near_ao;
            vec2 horizon = near_horizon;
            int cursor = far_start;
            for (int guard = 0; guard < 64; ++guard) {
                if (side < 0 ? cursor <= 0 : cursor >= grid_steps) break;
                float gap = abs(float(cursor) - u_p);
                int n_level = 0;
                while (n_level + 1 < levels && cursor % (b0 << (n_level + 1)) == 0 &&
                       float(b0 << (n_level + 1)) <= gap) {
                    ++n_level;
                }
                int length_n = b0 << n_level;
                int i = side < 0 ? cursor / length_n - 1 : cursor / length_n;
                float distance = gap + 0.5 * float(length_n);
                cursor += side * length_n;
                FfaoColumn column = ffao_column(k, n_level, i);
                if (column.lines == 0) continue;
                // The segment's lines at this distance (its boundaries run along side * dir + tan(alpha) perp),
                // or the one through its middle.
                float shift = v_p + jitter * distance * (tan_hi - tan_lo);
                int la = int(floor(shift + distance * (single_lines ? 0.5 * (tan_lo + tan_hi) : tan_lo) + 0.5));
                int lb = single_lines ? la : int(floor(shift + distance * tan_hi + 0.5));
                vec4 sum = column_sum(column, la, lb);
                if (sum.w < 0.5) continue;
                vec3 peaks = sum.xyz / sum.w;
                float x_h = side < 0 ? peaks.x - peaks.y : peaks.z - peaks.x;
                add_slab(vec2(x_h, peaks.x * g_zscale), ao, horizon);
            }
            far_sum += width * n_length * (ao - near_ao);
        }
#endif
    }
}

// The orientations this dispatch covers: all of them, or the chunk's.
#if OBSCURA_FFAO_CHUNKED
int first_orientation() { return ffao_chunk.range.x; }
int end_orientation() { return ffao_chunk.range.x + ffao_chunk.range.y; }
bool first_chunk() { return (ffao_chunk.range.w & OBSCURA_FFAO_CHUNK_FIRST) != 0; }
bool last_chunk() { return (ffao_chunk.range.w & OBSCURA_FFAO_CHUNK_LAST) != 0; }
#else
int first_orientation() { return 0; }
int end_orientation() { return ffao.config.x / 2; }
bool first_chunk() { return true; }
bool last_chunk() { return true; }
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + work_rect.xy;
    if (any(greaterThanEqual(gl_GlobalInvocationID.xy, uvec2(work_rect.zw)))) return;
    float depth = texelFetch(u_depth, pixel, 0).r;
    g_perspective = obscura_is_perspective();
    int k_begin = first_orientation(), k_end = end_orientation();
#if OBSCURA_FFAO_SAAO
    // SAAO (sec. 10): the full near field at the pixel itself; the far field of every ninth orientation only
    // (the pixel's place in its 3x3 group), at the group-averaged receiver of the box-average pass. The
    // gather pass adds the accepted neighbours' far fields.
    if (obscura_is_sky(depth)) {
        imageStore(u_terms, pixel, vec4(0.0));
        return;
    }
    vec3 p = obscura_view_position(pixel, depth);
    vec3 n = obscura_decode_normal(texelFetch(u_normals, pixel, 0).xy);
    float near_sum = 0.0, far_sum = 0.0, unused = 0.0;
#if OBSCURA_FFAO_CHUNKED
    if (!first_chunk()) {
        vec2 running = imageLoad(u_terms, pixel).xy;
        near_sum = running.x;
        far_sum = running.y;
    }
#endif
    for (int k = k_begin; k < k_end; ++k) evaluate_orientation(k, pixel, p, n, depth, false, near_sum, unused);
    vec4 box = texelFetch(u_box, pixel, 0);
    vec3 box_p = obscura_view_position(pixel, box.x);
    vec3 box_n = obscura_decode_normal(box.yz);
    int place = (pixel.x % 3) + 3 * (pixel.y % 3);
    // The first k >= k_begin with k = place (mod 9).
    for (int k = k_begin + (place - k_begin % 9 + 9) % 9; k < k_end; k += 9) {
        evaluate_orientation(k, pixel, box_p, box_n, box.x, true, unused, far_sum);
    }
    imageStore(u_terms, pixel, vec4(near_sum, far_sum, 0.0, 0.0));
#else
    // The tap-count debug view counts depth texels per pixel; FFAO's cost is per line and interval: 0.
    bool count_taps = target_params.w == OBSCURA_DEBUG_VIEW_TAP_COUNT;
    if (obscura_is_sky(depth) || count_taps) {
        imageStore(u_ao, pixel, vec4(count_taps ? 0.0 : 1.0));
        return;
    }
    vec3 p = obscura_view_position(pixel, depth);
    vec3 n = obscura_decode_normal(texelFetch(u_normals, pixel, 0).xy);
    // One running total, near and far field together, added orientation by orientation: a chunk resumes it where
    // the previous one stopped.
    float total = 0.0;
#if OBSCURA_FFAO_CHUNKED
    // The running total covers the dispatch's region only (FfaoPass::ensure_layout): indexed from its corner.
    ivec2 running_texel = ivec2(gl_GlobalInvocationID.xy);
    if (!first_chunk()) total = imageLoad(u_running, running_texel).x;
#endif
    // Frame split N (ffao.options.y): every Nth orientation from the pixel's share s, weighted N times, so that the
    // mean over N frames is the sum over all of them. s follows a 2x2 pattern (a checkerboard for N = 2) turned by
    // the frame: each 2x2 block, and the 7 texels the temporal pass's clamp reads around a pixel, hold every share.
    // The loop's stride is per pixel rather than a test per orientation: CPU rasterisers run every lane through
    // both sides of a branch, and would pay for every orientation.
    int split = ffao.options.y;
    int pattern = ((pixel.x ^ pixel.y) & 1) | ((pixel.y & 1) << 1);
    int share = (pattern + ffao.options.w) % split;
    float weight = float(split);
    for (int k = k_begin + (share - k_begin % split + split) % split; k < k_end; k += split) {
        float near_sum = 0.0, far_sum = 0.0;
        evaluate_orientation(k, pixel, p, n, depth, true, near_sum, far_sum);
        total += weight * (near_sum + far_sum);
    }
#if OBSCURA_FFAO_CHUNKED
    if (!last_chunk()) {
        imageStore(u_running, running_texel, vec4(total));
        return;
    }
#endif
    float obscurance = clamp(total / OBSCURA_PI * ffao.shape.y, 0.0, 1.0);
    imageStore(u_ao, pixel, vec4(pow(1.0 - obscurance, ffao.shape.z)));
#endif
}
