// The falloff rho(d) of the obscurance integral (FFAO paper eq. 1) on the CPU: the one C++ definition of every
// obscura_falloff kind, mirrored on the GPU by sdk/glsl/common/falloff.glsl. FFAO's estimator table, the
// public obscura_evaluate_falloff() (which the samples' geometry truth integrates), LSAO's obscure hull and the
// passes' lengths derived from rho0 all call it.
#ifndef OBSCURA_FALLOFF_H
#define OBSCURA_FALLOFF_H

#include <algorithm>
#include <cmath>

#include <obscura/obscura.h>

namespace obscura {

// rho0(d) = max(0, r(1+C)/(r+d^2) - C) (LSAO paper eq. 3) of d^2, as HBAO's and LSAO's CPU mirrors have it;
// C = 0 gives LSAO eq. 2, r / (r + d^2). r in the units of d^2.
inline double rho0(double r, double c, double distance_sq) {
    return std::max(0.0, r * (1.0 + c) / (r + distance_sq) - c);
}

// The d^2 at which rho0 falls to `value` (its inverse on (0, 1]): lengths past which the falloff leaves less
// than a tolerance.
inline double rho0_distance_sq(double r, double c, double value) { return r * (1.0 + c) / (value + c) - r; }

// Where rho0 reaches 0 and stays there, sqrt(r / C): rho0_distance_sq at 0, but as r / C and in the caller's
// precision, because the reference ends its rays there in float and its images must not move by a rounding.
template <typename Real>
Real rho0_reach(Real r, Real c) {
    return std::sqrt(r / c);
}

// The decay rate a derived `decay_rate` takes, C * radius^2: rho0 then reaches 0 exactly at the radius (and the
// other falloffs share the scale). In float, as the settings hold it.
inline float derived_decay_rate(float c, float radius) { return c * radius * radius; }

// r (the decay rate), C and the radius in the units of d; `table` holds OBSCURA_FALLOFF_TABLE_SIZE values of
// rho over [0, radius] (TABLE only).
struct FalloffParameters {
    int kind = OBSCURA_FALLOFF_RHO0;
    double r = 1.0;
    double c = 0.3;
    double radius = 1.0;
    const float* table = nullptr;
};

// d in the units of the parameters. A negative d is taken as 0 (an occluder on the surface), a NaN one as a miss
// (rho 0, as +infinity gives), so no input reads outside the table.
inline double falloff_value(const FalloffParameters& f, double d) {
    if (!(d >= 0.0)) d = std::isnan(d) ? HUGE_VAL : 0.0;
    switch (f.kind) {
        case OBSCURA_FALLOFF_RHO0: return rho0(f.r, f.c, d * d);
        case OBSCURA_FALLOFF_INVERSE_QUADRATIC: return f.r / (f.r + d * d);
        case OBSCURA_FALLOFF_EXPONENTIAL: return std::exp(-d / std::sqrt(f.r));
        default: {
            // TABLE: linear between the samples, 0 from the radius on.
            const double t = d / f.radius * (OBSCURA_FALLOFF_TABLE_SIZE - 1);
            if (!(t < OBSCURA_FALLOFF_TABLE_SIZE - 1)) return 0.0;
            const int i = int(std::floor(t));
            return f.table[i] + (f.table[i + 1] - f.table[i]) * (t - i);
        }
    }
}

// The falloff of resolved REFERENCE settings, in metres.
inline FalloffParameters falloff_parameters(const obscura_reference_settings& reference) {
    FalloffParameters f;
    f.kind = reference.falloff;
    f.r = reference.decay_rate;
    f.c = reference.falloff_c;
    f.radius = reference.radius;
    f.table = reference.falloff_table;
    return f;
}

}  // namespace obscura

#endif  // OBSCURA_FALLOFF_H
