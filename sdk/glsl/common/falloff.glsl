// The falloff rho(d) of the obscurance integral (FFAO paper eq. 1): the GPU's one definition of each kind, as
// sdk/src/falloff.h is the CPU's.

// rho0(d) = max(0, r(1+C)/(r+d^2) - C) (LSAO paper eq. 3), taking d^2: HBAO and LSAO have the squared length
// and no reason to take its root. C = 0 gives LSAO eq. 2, r / (r + d^2). r in the units of d^2.
float obscura_rho0(float r, float c, float distance_sq) {
    return max(0.0, r * (1.0 + c) / (r + distance_sq) - c);
}

// Every obscura_falloff kind, shared by the reference and FFAO's table. `params`: r (decay rate), C, radius, in
// the same units as d.
float obscura_falloff(int kind, float d, vec4 params, vec4 table[4]) {
    float r = params.x;
    if (kind == OBSCURA_FALLOFF_KIND_RHO0) return obscura_rho0(r, params.y, d * d);
    if (kind == OBSCURA_FALLOFF_KIND_INVERSE_QUADRATIC) return r / (r + d * d);
    if (kind == OBSCURA_FALLOFF_KIND_EXPONENTIAL) return exp(-d * inversesqrt(r));
    // Table: 16 values over [0, radius], linear in between, 0 beyond.
    float x = d / params.z * 15.0;
    if (!(x < 15.0)) return 0.0;
    int i = int(floor(x));
    float a = table[i >> 2][i & 3];
    float b = table[(i + 1) >> 2][(i + 1) & 3];
    return mix(a, b, x - float(i));
}
