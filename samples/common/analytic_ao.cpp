#include "analytic_ao.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

namespace obscura::samples {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

glm::dvec3 axis_normal(int axis, double sign) {
    glm::dvec3 normal(0.0);
    normal[axis] = sign;
    return normal;
}

double facing_sign(double direction_component) {
    return direction_component > 0.0 ? -1.0 : 1.0;
}

// Slab test. Either the entry (origin outside) or, from inside, the exit; t > 0 only.
bool hit_box(const AnalyticPrimitive& box, const glm::dvec3& origin, const glm::dvec3& direction, double* t_out,
             glm::dvec3* normal_out) {
    double t_near = -kInfinity, t_far = kInfinity;
    int near_axis = -1, far_axis = -1;
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0) {
            if (origin[axis] < box.lo[axis] || origin[axis] > box.hi[axis]) return false;
            continue;
        }
        double t0 = (box.lo[axis] - origin[axis]) / direction[axis];
        double t1 = (box.hi[axis] - origin[axis]) / direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        if (t0 > t_near) {
            t_near = t0;
            near_axis = axis;
        }
        if (t1 < t_far) {
            t_far = t1;
            far_axis = axis;
        }
    }
    if (t_near > t_far || t_far <= 0.0) return false;
    const bool from_outside = t_near > 0.0;
    const int axis = from_outside ? near_axis : far_axis;
    *t_out = from_outside ? t_near : t_far;
    *normal_out = axis_normal(axis, facing_sign(direction[axis]));
    return true;
}

bool hit_rectangle(const AnalyticPrimitive& rectangle, const glm::dvec3& origin, const glm::dvec3& direction,
                   double* t_out, glm::dvec3* normal_out) {
    const int axis = rectangle.axis;
    if (direction[axis] == 0.0) return false;
    const double t = (rectangle.lo[axis] - origin[axis]) / direction[axis];
    if (!(t > 0.0)) return false;
    const glm::dvec3 hit = origin + t * direction;
    for (int other : {(axis + 1) % 3, (axis + 2) % 3}) {
        if (hit[other] < rectangle.lo[other] || hit[other] > rectangle.hi[other]) return false;
    }
    *t_out = t;
    *normal_out = axis_normal(axis, facing_sign(direction[axis]));
    return true;
}

}  // namespace

AnalyticPrimitive AnalyticPrimitive::box(const glm::dvec3& lo, const glm::dvec3& hi) {
    AnalyticPrimitive primitive;
    primitive.kind = Kind::Box;
    primitive.lo = glm::min(lo, hi);
    primitive.hi = glm::max(lo, hi);
    return primitive;
}

AnalyticPrimitive AnalyticPrimitive::rectangle(int axis, double position, double side, const glm::dvec3& lo,
                                               const glm::dvec3& hi) {
    AnalyticPrimitive primitive;
    primitive.kind = Kind::Rectangle;
    primitive.axis = axis;
    primitive.side = side < 0.0 ? -1.0 : 1.0;
    primitive.lo = glm::min(lo, hi);
    primitive.hi = glm::max(lo, hi);
    primitive.lo[axis] = position;
    primitive.hi[axis] = position;
    return primitive;
}

const std::vector<AnalyticPrimitive>& analytic_scene_primitives() {
    using namespace analytic_layout;
    static const std::vector<AnalyticPrimitive> primitives = {
        AnalyticPrimitive::rectangle(1, 0.0, 1.0, {kFloorMinX, 0.0, kFloorMinZ}, {kFloorMaxX, 0.0, kFloorMaxZ}),
        AnalyticPrimitive::rectangle(2, kWallZ, 1.0, {kFloorMinX, 0.0, 0.0}, {kFloorMaxX, kWallHeight, 0.0}),
        AnalyticPrimitive::box({kBoxMinX, 0.0, kBoxMinZ}, {kBoxMaxX, kBoxHeight, kBoxMaxZ}),
    };
    return primitives;
}

bool cast_ray(const std::vector<AnalyticPrimitive>& scene, const glm::dvec3& origin, const glm::dvec3& direction,
              double* t, glm::dvec3* normal) {
    double best_t = kInfinity;
    glm::dvec3 best_normal(0.0);
    for (const AnalyticPrimitive& primitive : scene) {
        double hit_t = 0.0;
        glm::dvec3 hit_normal(0.0);
        const bool hit = primitive.kind == AnalyticPrimitive::Kind::Box
                             ? hit_box(primitive, origin, direction, &hit_t, &hit_normal)
                             : hit_rectangle(primitive, origin, direction, &hit_t, &hit_normal);
        if (hit && hit_t < best_t) {
            best_t = hit_t;
            best_normal = hit_normal;
        }
    }
    if (best_t == kInfinity) return false;
    if (t) *t = best_t;
    if (normal) *normal = best_normal;
    return true;
}

double exact_obscurance(const std::vector<AnalyticPrimitive>& scene, const glm::dvec3& p, const glm::dvec3& n_in,
                        const std::function<double(double)>& rho, int resolution) {
    const int u_cells = std::max(resolution, 1);
    const int phi_cells = 4 * u_cells;
    const glm::dvec3 n = glm::normalize(n_in);
    const glm::dvec3 helper = std::fabs(n.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    const glm::dvec3 t1 = glm::normalize(glm::cross(helper, n));
    const glm::dvec3 t2 = glm::cross(n, t1);
    const glm::dvec3 origin = p + n * 1e-6;

    std::vector<double> cos_phi(static_cast<size_t>(phi_cells)), sin_phi(static_cast<size_t>(phi_cells));
    for (int j = 0; j < phi_cells; ++j) {
        const double phi = 2.0 * glm::pi<double>() * (double(j) + 0.5) / double(phi_cells);
        cos_phi[size_t(j)] = std::cos(phi);
        sin_phi[size_t(j)] = std::sin(phi);
    }
    // Cosine weighting: with u = sin^2 theta, cos theta dw = du dphi / 2, so equal cells in (u, phi)
    // carry equal weight and (1/pi) * (1/2) * (1 * 2 pi) = 1 is the total.
    double sum = 0.0;
    for (int i = 0; i < u_cells; ++i) {
        const double u = (double(i) + 0.5) / double(u_cells);
        const double sin_theta = std::sqrt(u), cos_theta = std::sqrt(1.0 - u);
        double ring = 0.0;
        for (int j = 0; j < phi_cells; ++j) {
            const glm::dvec3 w =
                sin_theta * (cos_phi[size_t(j)] * t1 + sin_phi[size_t(j)] * t2) + cos_theta * n;
            double t = 0.0;
            if (cast_ray(scene, origin, w, &t, nullptr)) ring += rho(t);
        }
        sum += ring;
    }
    return sum / (double(u_cells) * double(phi_cells));
}

double exact_obscurance(const std::vector<AnalyticPrimitive>& scene, const glm::dvec3& p, const glm::dvec3& n,
                        const obscura_settings& falloff, int resolution) {
    // The same quadrature, its hit distances weighed in one call (obscura_evaluate_falloff resolves the settings
    // once per call).
    std::vector<float> distances;
    exact_obscurance(scene, p, n, [&](double t) { distances.push_back(float(t)); return 0.0; }, resolution);
    std::vector<float> rho(distances.size());
    const obscura_status status =
        obscura_evaluate_falloff(&falloff, distances.data(), rho.data(), uint32_t(distances.size()));
    if (status != OBSCURA_OK) {
        throw std::invalid_argument(std::string("exact_obscurance: the falloff's settings are refused (") +
                                    obscura_status_string(status) + ")");
    }
    double sum = 0.0;
    for (float value : rho) sum += double(value);
    const double cells = double(std::max(resolution, 1)) * double(4 * std::max(resolution, 1));
    return sum / cells;
}

}  // namespace obscura::samples
