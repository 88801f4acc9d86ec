// FFAO's obscurance estimator table (Timonen, "Screen-Space Far-Field Ambient Obscurance", HPG 2013, sec. 4,
// eq. 3). A virtual point h seen from a receiver p stands for a slab: the part of the view ray through h
// beyond h (infinitely thick depth). In the receiver's azimuthal plane, with angles measured from its zenith z
// (towards the eye) towards the sector, the rays between angle a and the slab's own angle c hit the slab at
// distance b / sin(c - theta), b being the distance from p to the slab's line. The falloff- and
// cosine-weighted visibility they lose is
//   L(a, b, c, d) = integral from a to c of rho(b / sin(c - theta)) max(0, cos(theta - d)) sin(theta) dtheta,
// d the angle of the receiver's projected normal; eq. 3 takes differences of L between consecutive horizons.
// L depends on the falloff only through its shape: b is in units of the falloff's scale s, so a radius
// change reuses the table. The a axis is measured from the normal, a' = a - d in [-pi/2, pi/2]: every ray past
// the receiver's tangent (a' >= pi/2) carries no weight, so the cosine's kink sits on the last texel whatever d
// is, and a receiver's own plane casts exactly nothing even though d is taken at the nearest of its values
// (nearest d with a measured from the zenith put a 6-degree band of the tangent into the integral). One
// invocation integrates one (b, c, d) column over every a' (Simpson's rule on each cell), from a' = pi/2
// (L = 0) downwards; rays below the zenith (theta < 0) belong to the opposite sector. Axes: a' as above;
// b / s = t / (1 - t), t in [0, 1] (t = 1: an infinitely far slab, L = 0); c in [pi/2, pi]; d in [-pi/2, pi/2].
// The texture is A x B x (D * C): c and d share the third axis, c-major inside each d segment, so a', b and c
// interpolate and d is taken nearest.
#define OBSCURA_FFAO_TABLE_PASS 1
#include "common/shader_interface.h"
#include "common/falloff.glsl"

layout(local_size_x = OBSCURA_FFAO_TABLE_GROUP) in;
layout(binding = OBSCURA_IMAGE_OUT0, r32f) uniform writeonly image3D u_table;

const int kSubintervals = 16;  // Simpson's rule per a-cell (even)

float g_beta, g_c, g_d;

float integrand(float theta) {
    float s = max(sin(g_c - theta), 1e-12);
    vec4 table[4] = ffao_table.table;
    float rho = obscura_falloff(ffao_table.config.x, g_beta / s, ffao_table.falloff, table);
    return rho * max(0.0, cos(theta - g_d)) * sin(theta);
}

void main() {
    int index = int(gl_GlobalInvocationID.x);
    const int columns = OBSCURA_FFAO_TABLE_B * OBSCURA_FFAO_TABLE_C * OBSCURA_FFAO_TABLE_D;
    if (index >= columns) return;
    int jb = index % OBSCURA_FFAO_TABLE_B;
    int kc = (index / OBSCURA_FFAO_TABLE_B) % OBSCURA_FFAO_TABLE_C;
    int md = index / (OBSCURA_FFAO_TABLE_B * OBSCURA_FFAO_TABLE_C);
    float t = float(jb) / float(OBSCURA_FFAO_TABLE_B - 1);
    g_beta = t / max(1.0 - t, 1e-30);
    g_c = 0.5 * OBSCURA_PI * (1.0 + float(kc) / float(OBSCURA_FFAO_TABLE_C - 1));
    g_d = OBSCURA_PI * (float(md) / float(OBSCURA_FFAO_TABLE_D - 1) - 0.5);
    int z = md * OBSCURA_FFAO_TABLE_C + kc;
    float sum = 0.0;
    imageStore(u_table, ivec3(OBSCURA_FFAO_TABLE_A - 1, jb, z), vec4(0.0));
    for (int i = OBSCURA_FFAO_TABLE_A - 2; i >= 0; --i) {
        float lo = max(g_d + OBSCURA_PI * (float(i) / float(OBSCURA_FFAO_TABLE_A - 1) - 0.5), 0.0);
        float hi = min(g_d + OBSCURA_PI * (float(i + 1) / float(OBSCURA_FFAO_TABLE_A - 1) - 0.5), g_c);
        if (jb < OBSCURA_FFAO_TABLE_B - 1 && hi > lo) {
            float h = (hi - lo) / float(kSubintervals);
            float cell = integrand(lo) + integrand(hi);
            for (int s = 1; s < kSubintervals; ++s) cell += float(2 + 2 * (s & 1)) * integrand(lo + h * float(s));
            sum += cell * h / 3.0;
        }
        imageStore(u_table, ivec3(i, jb, z), vec4(sum));
    }
}
