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

// Compiled in (ZPyramidPass::prepare). GPUs: 16x16 threads, four first-level texels each, every further level through
// shared memory. CPU rasterisers, which reach shared memory one invocation at a time and pay for every barrier:
// 8x8 invocations, each building a 4x4 block of the first level, its 2x2 of the second and its texel of the third in
// registers (the block is aligned, so none needs another invocation's texels); shared memory only from the fourth
// level on (64 texels a group). The same texels either way, bit for bit.
#ifndef OBSCURA_CPU_RASTERISER
#error "OBSCURA_CPU_RASTERISER must be defined"
#endif
// The filter (OBSCURA_MIP_FILTER_*), compiled in (ZPyramidPass::prepare): CPU rasterisers would run every filter's
// arithmetic under a uniform branch.
#ifndef OBSCURA_Z_PYRAMID_FILTER
#error "OBSCURA_Z_PYRAMID_FILTER must be defined"
#endif
const int kFilter = OBSCURA_Z_PYRAMID_FILTER;
#if OBSCURA_CPU_RASTERISER
layout(local_size_x = OBSCURA_Z_PYRAMID_GROUP_CPU, local_size_y = OBSCURA_Z_PYRAMID_GROUP_CPU) in;
#else
layout(local_size_x = OBSCURA_Z_PYRAMID_GROUP, local_size_y = OBSCURA_Z_PYRAMID_GROUP) in;
#endif

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
    const int filter_kind = kFilter;
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
    if (kFilter == OBSCURA_MIP_FILTER_ROTATED_GRID) return fetch_source(rotated_grid_child(p), source_size);
    ivec2 c = 2 * p;
    return reduce4(fetch_source(c, source_size), fetch_source(c + ivec2(1, 0), source_size),
                   fetch_source(c + ivec2(0, 1), source_size), fetch_source(c + ivec2(1, 1), source_size));
}

// Texel p (local to the tile) of the next level from the tile in shared memory holding the previous level
// (row length `width`). The rotated grid's offsets follow the parity of the global coordinate `global_p`:
// the 1x1 tiles of a dispatch's sixth level do not start on even coordinates.
float from_tile(ivec2 p, ivec2 global_p, int width) {
    if (kFilter == OBSCURA_MIP_FILTER_ROTATED_GRID) {
        ivec2 c = 2 * p + ivec2((global_p.y & 1) ^ 1, (global_p.x & 1) ^ 1);
        return s_tile[c.y * width + c.x];
    }
    int i = 2 * p.y * width + 2 * p.x;
    return reduce4(s_tile[i], s_tile[i + 1], s_tile[i + width], s_tile[i + width + 1]);
}

// Levels `level` to the dispatch's last from the tile in shared memory, which holds level - 1 in rows of `width`:
// each level halves the tile in place (read the previous level, sync, then overwrite).
void halve_tile(int level, int width, ivec2 local, ivec2 tile_origin, int levels) {
    for (; level <= levels; ++level) {
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

void main() {
    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    ivec2 tile_origin = ivec2(gl_WorkGroupID.xy) * kTile;
    ivec2 source_size = textureSize(u_depth, z_pyramid.config.x);
    ivec2 first_size = max(source_size / 2, ivec2(1));
    int levels = z_pyramid.config.y;
#if OBSCURA_CPU_RASTERISER
    // The first level's 4x4 block at `block`, straight from the texture (texels past the level's edge are clamped
    // copies, never stored, as below).
    ivec2 block = tile_origin + 4 * local;
    float first[16];
    for (int j = 0; j < 16; ++j) {
        ivec2 t = block + ivec2(j & 3, j >> 2);
        first[j] = from_source(min(t, first_size - 1), source_size);
        store_level(1, t, first[j]);
    }
    // The second level's 2x2 (at block / 2, even coordinates: the rotated grid's offsets follow j's parity alone).
    float second[4];
    bool rotated = kFilter == OBSCURA_MIP_FILTER_ROTATED_GRID;
    for (int j = 0; j < 4; ++j) {
        ivec2 q = ivec2(j & 1, j >> 1), c = 2 * q;
        float reduced = reduce4(first[c.y * 4 + c.x], first[c.y * 4 + c.x + 1], first[c.y * 4 + c.x + 4],
                                first[c.y * 4 + c.x + 5]);
        ivec2 r = c + ivec2((q.y & 1) ^ 1, (q.x & 1) ^ 1);  // rotated_grid_child of an even-based parent
        second[j] = rotated ? first[r.y * 4 + r.x] : reduced;
        if (levels >= 2) store_level(2, (block >> 1) + q, second[j]);
    }
    // The third level's texel, whose coordinates' parity is the invocation's own.
    ivec2 third_p = block >> 2;
    float rotated_child = (third_p.x & 1) == 0 ? ((third_p.y & 1) == 0 ? second[3] : second[2])
                                                : ((third_p.y & 1) == 0 ? second[1] : second[0]);
    float third = rotated ? rotated_child : reduce4(second[0], second[1], second[2], second[3]);
    if (levels >= 3) store_level(3, third_p, third);
    if (levels < 4) return;  // uniform across the dispatch: no barrier is skipped by only some invocations
    s_tile[local.y * (kTile / 4) + local.x] = third;
    barrier();
    halve_tile(4, kTile / 4, local, tile_origin, levels);
#else
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
    halve_tile(2, kTile, local, tile_origin, levels);
#endif
}
