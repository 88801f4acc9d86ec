// Reading the z pyramid (z_pyramid.comp builds it): where a level's depth came from.

// Where the z of level-m texel `t` was taken from, in level-0 texel units: the rotated grid keeps one real
// texel (followed down level by level, the same rule as z_pyramid.comp); the 2x2 filters describe the
// block's centre. Reconstructing a tap there instead of at the tap's own pixel keeps it on the surface
// (at the tap's pixel, a level-m depth misses a slanted plane by up to 2^m texels of its slope).
vec2 obscura_level_texel_origin(ivec2 t, int m, int filter_kind) {
    if (filter_kind != OBSCURA_MIP_FILTER_ROTATED_GRID) return (vec2(t) + 0.5) * float(1 << m);
    for (int level = m; level > 0; --level) t = 2 * t + ivec2((t.y & 1) ^ 1, (t.x & 1) ^ 1);
    return vec2(t) + 0.5;
}
