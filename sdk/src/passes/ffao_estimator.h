// FFAO's obscurance estimator on the CPU (Timonen, "Screen-Space Far-Field Ambient Obscurance", HPG 2013,
// sec. 4): the falloff split into a shape and a scale, and the slab integral L(a, b, c, d) that
// sdk/glsl/ffao_table.comp tabulates, by adaptive quadrature in double precision (the tests' ground truth).
#ifndef OBSCURA_FFAO_ESTIMATOR_H
#define OBSCURA_FFAO_ESTIMATOR_H

#include <obscura/obscura.h>

namespace obscura {

// The falloff of resolved FFAO settings as a shape and a scale: rho(d) = shape(d / s). The table depends on
// the shape only, so a radius change does not rebuild it.
struct FfaoFalloffShape {
    int kind = OBSCURA_FALLOFF_EXPONENTIAL;
    double r = 1.0, c = 0.0, radius = 1.0;  // the falloff's parameters in units of s
    float table[OBSCURA_FALLOFF_TABLE_SIZE] = {};
    double falloff(double x) const;  // rho at distance x (units of s)
    bool operator==(const FfaoFalloffShape& o) const;
};
FfaoFalloffShape ffao_falloff_shape(const obscura_ffao_settings& settings);
// s in metres.
double ffao_falloff_scale(const obscura_ffao_settings& settings);

// The estimator integral the table samples, by adaptive quadrature in double precision (tests, docs):
// integral from a to c of shape(beta / sin(c - theta)) max(0, cos(theta - d)) sin(theta) dtheta.
double ffao_slab_integral(const FfaoFalloffShape& shape, double a, double beta, double c, double d);

}  // namespace obscura

#endif  // OBSCURA_FFAO_ESTIMATOR_H
