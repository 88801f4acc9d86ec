// Octahedral normal encoding into two signed components (stored as rg16_snorm): about 1e-4 rad
// precision, so planes stay free of the self-occlusion that 8-bit normals would cause.

vec2 obscura_encode_normal(vec3 n) {
    n /= (abs(n.x) + abs(n.y) + abs(n.z));
    vec2 e = n.xy;
    if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return e;
}

// The same for four normals at once (lanes: the encodings' x and y, e.g. two textureGathers): unit x, y, z.
void obscura_decode_normal4(vec4 ex, vec4 ey, out vec4 nx, out vec4 ny, out vec4 nz) {
    nz = 1.0 - abs(ex) - abs(ey);
    bvec4 folded = lessThan(nz, vec4(0.0));
    vec4 sign_x = mix(vec4(-1.0), vec4(1.0), greaterThanEqual(ex, vec4(0.0)));
    vec4 sign_y = mix(vec4(-1.0), vec4(1.0), greaterThanEqual(ey, vec4(0.0)));
    nx = mix(ex, (1.0 - abs(ey)) * sign_x, folded);
    ny = mix(ey, (1.0 - abs(ex)) * sign_y, folded);
    vec4 inverse_length = inversesqrt(nx * nx + ny * ny + nz * nz);
    nx *= inverse_length;
    ny *= inverse_length;
    nz *= inverse_length;
}

// The normal's direction, not normalised (its length lies in [1/sqrt(3), 1]): for comparisons that scale with it.
vec3 obscura_decode_normal_direction(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return n;
}

vec3 obscura_decode_normal(vec2 e) { return normalize(obscura_decode_normal_direction(e)); }
