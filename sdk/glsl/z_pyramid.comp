// SAO's hierarchical z (McGuire et al., "Scalable Ambient Obscurance", sec. 2.2 and Table 1): MIP levels of
// the linear view depth, so spiral taps far from a pixel read a small, cached footprint. Level 0 is the
// shared depth preparation's output (eq. 2 evaluated once per texel). One dispatch writes up to six
// levels below `source level`: each 16x16 group builds a 32x32 tile of the first of them from the
// texture, then halves it in shared memory for the next ones (a level-(m+1) texel depends only on texels of
// its own tile at level m, since tiles are aligned to their size).
// Filters: the paper's rotated-grid subsample z(2x + ((y & 1) ^ 1), 2y + ((x & 1) ^ 1)), which always
// keeps a depth that exists in the scene, and for comparison the mean, harmonic mean, min and max of 2x2.
#define OBSCURA_Z_PYRAMID_PASS 1
#include "common/shader_interface.h"

layout(local_size_x = OBSCURA_Z_PYRAMID_GROUP, local_size_y = OBSCURA_Z_PYRAMID_GROUP) in;

layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_depth;  // read at the source level
layout(binding = OBSCURA_IMAGE_OUT0, r32f) writeonly uniform image2D u_level1;
layout(binding = OBSCURA_IMAGE_OUT1, r32f) writeonly uniform image2D u_level2;
layout(binding = OBSCURA_IMAGE_OUT2, r32f) writeonly uniform image2D u_level3;
layout(binding = OBSCURA_IMAGE_OUT3, r32f) writeonly uniform image2D u_level4;
layout(binding = OBSCURA_IMAGE_OUT4, r32f) writeonly uniform image2D u_level5;
layout(binding = OBSCURA_IMAGE_OUT5, r32f) writeonly uniform image2D u_level6;

const int kTile = OBSCURA_Z_PYRAMID_TILE;
const int kThreads = OBSCURA_Z_PYRAMID_GROUP;
shared float s_tile[kTile * kTile];

// Level i (1-based below the source) of this dispatch.
void store_level(int i, ivec2 p, float z) {
    switch (i) {
        case 1: if (all(lessThan(p, imageSize(u_level1)))) imageStore(u_level1, p, vec4(z)); break;
        case 2: if (all(lessThan(p, imageSize(u_level2)))) imageStore(u_level2, p, vec4(z)); break;
        case 3: if (all(lessThan(p, imageSize(u_level3)))) imageStore(u_level3, p, vec4(z)); break;
        case 4: if (all(lessThan(p, imageSize(u_level4)))) imageStore(u_level4, p, vec4(z)); break;
        case 5: if (all(lessThan(p, imageSize(u_level5)))) imageStore(u_level5, p, vec4(z)); break;
        default: if (all(lessThan(p, imageSize(u_level6)))) imageStore(u_level6, p, vec4(z)); break;
    }
}

// The 2x2 filters of Table 1 over the four children a (2x, 2y), b (2x+1, 2y), c (2x, 2y+1), d (2x+1, 2y+1).
float reduce4(float a, float b, float c, float d) {
    int filter_kind = z_pyramid.config.z;
    if (filter_kind == OBSCURA_MIP_FILTER_MEAN) return 0.25 * (a + b + c + d);
    if (filter_kind == OBSCURA_MIP_FILTER_MEAN_OF_GEOMETRY) {
        vec4 z = vec4(a, b, c, d);
        vec4 geometry = vec4(lessThan(z, vec4(OBSCURA_SKY_THRESHOLD)));
        float count = dot(geometry, vec4(1.0));
        return count > 0.0 ? dot(z * geometry, vec4(1.0)) / count : OBSCURA_SKY_DEPTH;
    }
    if (filter_kind == OBSCURA_MIP_FILTER_HARMONIC_MEAN_OF_GEOMETRY) {
        vec4 z = vec4(a, b, c, d);
        vec4 geometry = vec4(lessThan(z, vec4(OBSCURA_SKY_THRESHOLD)));
        float count = dot(geometry, vec4(1.0));
        return count > 0.0 ? count / dot(geometry / z, vec4(1.0)) : OBSCURA_SKY_DEPTH;
    }
    if (filter_kind == OBSCURA_MIP_FILTER_HARMONIC_MEAN) return 4.0 / (1.0 / a + 1.0 / b + 1.0 / c + 1.0 / d);
    if (filter_kind == OBSCURA_MIP_FILTER_MIN) return min(min(a, b), min(c, d));
    return max(max(a, b), max(c, d));
}

// The rotated grid's child of parent texel p: x offset from y's parity, y offset from x's (both inverted).
ivec2 rotated_grid_child(ivec2 p) { return 2 * p + ivec2((p.y & 1) ^ 1, (p.x & 1) ^ 1); }

// Children stay inside the source level for every stored parent; the clamp only guards a source level one
// texel wide and the clamped copies past the edge.
float fetch_source(ivec2 c, ivec2 source_size) {
    return texelFetch(u_depth, min(c, source_size - 1), z_pyramid.config.x).r;
}

float from_source(ivec2 p, ivec2 source_size) {
    if (z_pyramid.config.z == OBSCURA_MIP_FILTER_ROTATED_GRID) return fetch_source(rotated_grid_child(p), source_size);
    ivec2 c = 2 * p;
    return reduce4(fetch_source(c, source_size), fetch_source(c + ivec2(1, 0), source_size),
                   fetch_source(c + ivec2(0, 1), source_size), fetch_source(c + ivec2(1, 1), source_size));
}

// Texel p (local to the tile) of the next level from the tile in shared memory holding the previous level
// (row length `width`). The rotated grid's offsets follow the parity of the global coordinate `global_p`:
// the 1x1 tiles of a dispatch's sixth level do not start on even coordinates.
float from_tile(ivec2 p, ivec2 global_p, int width) {
    if (z_pyramid.config.z == OBSCURA_MIP_FILTER_ROTATED_GRID) {
        ivec2 c = 2 * p + ivec2((global_p.y & 1) ^ 1, (global_p.x & 1) ^ 1);
        return s_tile[c.y * width + c.x];
    }
    int i = 2 * p.y * width + 2 * p.x;
    return reduce4(s_tile[i], s_tile[i + 1], s_tile[i + width], s_tile[i + width + 1]);
}

void main() {
    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    ivec2 tile_origin = ivec2(gl_WorkGroupID.xy) * kTile;
    ivec2 source_size = textureSize(u_depth, z_pyramid.config.x);
    ivec2 first_size = max(source_size / 2, ivec2(1));
    int levels = z_pyramid.config.y;

    // First level: 32x32 texels, four per thread, straight from the texture. Texels past the level's edge
    // are clamped copies (never stored; they keep the shared-memory levels finite).
    float first[4];
    for (int j = 0; j < 4; ++j) {
        ivec2 t = local + ivec2(j & 1, j >> 1) * kThreads;
        ivec2 p = min(tile_origin + t, first_size - 1);
        first[j] = from_source(p, source_size);
        store_level(1, tile_origin + t, first[j]);
    }
    if (levels < 2) return;  // uniform across the dispatch: no barrier is skipped by only some threads
    for (int j = 0; j < 4; ++j) {
        ivec2 t = local + ivec2(j & 1, j >> 1) * kThreads;
        s_tile[t.y * kTile + t.x] = first[j];
    }
    barrier();

    // Each further level halves the tile in place: read the previous level, sync, then overwrite.
    int width = kTile;
    for (int level = 2; level <= levels; ++level) {
        int next = width / 2;
        bool in_level = all(lessThan(local, ivec2(next)));
        ivec2 global_p = (tile_origin >> (level - 1)) + local;
        float z = in_level ? from_tile(local, global_p, width) : 0.0;
        barrier();
        if (in_level) {
            s_tile[local.y * next + local.x] = z;
            store_level(level, global_p, z);
        }
        barrier();
        width = next;
    }
}
