#include "passes/ffao_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "common/shader_interface.h"
#include "falloff.h"
#include "math_constants.h"

namespace obscura {
namespace {

double adaptive_simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
                        double whole, double tolerance, int depth) {
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    if (depth <= 0 || std::fabs(left + right - whole) <= 15.0 * tolerance) return left + right + (left + right - whole) / 15.0;
    return adaptive_simpson(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
           adaptive_simpson(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

}  // namespace

double FfaoFalloffShape::falloff(double x) const {
    FalloffParameters parameters;
    parameters.kind = kind;
    parameters.r = r;
    parameters.c = c;
    parameters.radius = radius;
    parameters.table = table;
    return falloff_value(parameters, x);
}

bool FfaoFalloffShape::operator==(const FfaoFalloffShape& o) const {
    return kind == o.kind && r == o.r && c == o.c && radius == o.radius &&
           std::memcmp(table, o.table, sizeof table) == 0;
}

double ffao_falloff_scale(const obscura_ffao_settings& settings) {
    const double r = settings.decay_rate, c = settings.falloff_c;
    switch (settings.falloff) {
        case OBSCURA_FALLOFF_RHO0: return std::sqrt(r * (1.0 + c) / c);  // sqrt(1 + C) times rho0_reach()
        case OBSCURA_FALLOFF_TABLE: return settings.radius;
        default: return std::sqrt(r);
    }
}

FfaoFalloffShape ffao_falloff_shape(const obscura_ffao_settings& settings) {
    FfaoFalloffShape shape;
    shape.kind = settings.falloff;
    if (shape.kind == OBSCURA_FALLOFF_RHO0) {
        // r / s^2 with s^2 = r (1 + C) / C.
        shape.c = settings.falloff_c;
        shape.r = shape.c / (1.0 + shape.c);
    }
    if (shape.kind == OBSCURA_FALLOFF_TABLE) std::memcpy(shape.table, settings.falloff_table, sizeof shape.table);
    return shape;
}

double ffao_slab_integral(const FfaoFalloffShape& shape, double a, double beta, double c, double d) {
    // Nothing past the slab's direction (c) or the receiver's tangent (d + pi/2); below the zenith is the other
    // sector's. Equal pieces first, so a narrow lobe cannot hide between the first few samples.
    const double lo = std::max(a, 0.0), hi = std::min(c, d + 0.5 * kPi);
    if (!(lo < hi)) return 0.0;
    auto f = [&](double theta) {
        const double s = std::max(std::sin(c - theta), 1e-300);
        return shape.falloff(beta / s) * std::max(0.0, std::cos(theta - d)) * std::sin(theta);
    };
    constexpr int kPieces = 32;
    double sum = 0.0;
    for (int i = 0; i < kPieces; ++i) {
        const double x0 = lo + (hi - lo) * i / kPieces, x1 = lo + (hi - lo) * (i + 1) / kPieces;
        const double f0 = f(x0), fm = f(0.5 * (x0 + x1)), f1 = f(x1);
        sum += adaptive_simpson(f, x0, x1, f0, fm, f1, (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1), 1e-12, 30);
    }
    return sum;
}

}  // namespace obscura
