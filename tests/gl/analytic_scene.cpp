#include "analytic_scene.h"

#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace obscura_test {

const char* projection_name(Projection projection) {
    switch (projection) {
        case Projection::Perspective: return "Perspective";
        case Projection::ReversedZ: return "ReversedZ";
        case Projection::Infinite: return "Infinite";
        case Projection::ReversedInfinite: return "ReversedInfinite";
        case Projection::Orthographic: return "Orthographic";
        case Projection::LinearView: return "LinearView";
    }
    return "Unknown";
}

Camera::Camera(Projection projection, int width, int height, const Lens& lens, const glm::dmat4& view)
    : projection_(projection), width_(width), height_(height), view_(view) {
    const double n = lens.near_plane, f = lens.far_plane;
    const double aspect = double(width) / double(height);
    double m[16] = {};
    if (projection == Projection::Orthographic) {
        const double half_h = lens.ortho_half_height, half_w = half_h * aspect;
        m[0] = 1.0 / half_w;
        m[5] = 1.0 / half_h;
        m[10] = -2.0 / (f - n);
        m[12] = lens.shift_x;
        m[13] = lens.shift_y;
        m[14] = -(f + n) / (f - n);
        m[15] = 1.0;
    } else {
        const double t = std::tan(0.5 * lens.fov_y_degrees * M_PI / 180.0);
        m[0] = 1.0 / (t * aspect);
        m[5] = 1.0 / t;
        m[8] = -lens.shift_x;  // ndc_x = m0 x / -z - m8: a positive shift moves the image right
        m[9] = -lens.shift_y;
        m[11] = -1.0;
        switch (projection) {
            case Projection::Perspective:
            case Projection::LinearView:
                m[10] = -(f + n) / (f - n);
                m[14] = -2.0 * f * n / (f - n);
                break;
            case Projection::ReversedZ:  // [0,1]: z_ndc = n/(f-n) * (-1) ... near -> 1, far -> 0
                m[10] = n / (f - n);
                m[14] = f * n / (f - n);
                break;
            case Projection::Infinite:  // z_ndc = 1 + 2n/z
                m[10] = -1.0;
                m[14] = -2.0 * n;
                break;
            case Projection::ReversedInfinite:  // z_ndc = -n/z
                m[10] = 0.0;
                m[14] = n;
                break;
            case Projection::Orthographic: break;
        }
    }
    for (int i = 0; i < 16; ++i) matrix_[i] = float(m[i]);
    clip_depth_ = reversed() ? OBSCURA_CLIP_DEPTH_ZERO_TO_ONE : OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
}

void Camera::ray(int x, int y, glm::dvec3* origin, glm::dvec3* direction) const {
    double m[16];
    for (int i = 0; i < 16; ++i) m[i] = matrix_[i];
    const double ndc_x = (x + 0.5) / width_ * 2.0 - 1.0;
    const double ndc_y = (y + 0.5) / height_ * 2.0 - 1.0;
    // The view point with NDC (ndc_x, ndc_y) at view z: x = (ndc_x * w - m8 z - m12) / m0, w = m11 z + m15.
    auto point_at = [&](double z) {
        double w = m[11] * z + m[15];
        return glm::dvec3((ndc_x * w - m[8] * z - m[12]) / m[0], (ndc_y * w - m[9] * z - m[13]) / m[5], z);
    };
    // Perspective rays start at the eye. Orthographic ones start on the near plane, which may lie behind
    // the eye (glOrtho with a negative near): GL rasterises that geometry, so the tracer must see it too.
    double z0 = 0.0;
    if (m[11] == 0.0) {
        const bool reversed = projection_ == Projection::ReversedZ || projection_ == Projection::ReversedInfinite;
        const double near_window = reversed ? 1.0 : 0.0;
        const double near_ndc = clip_depth_ == OBSCURA_CLIP_DEPTH_ZERO_TO_ONE ? near_window : near_window * 2.0 - 1.0;
        z0 = std::max(0.0, (near_ndc * m[15] - m[14]) / m[10]);  // only ever behind the eye: z0 >= 0
    }
    glm::dvec3 p0 = point_at(z0), p1 = point_at(z0 - 1.0);
    *origin = p0;
    *direction = glm::normalize(p1 - p0);
}

double Camera::window_depth(double z) const {
    double m10 = matrix_[10], m14 = matrix_[14], m11 = matrix_[11], m15 = matrix_[15];
    double z_ndc = (m10 * z + m14) / (m11 * z + m15);
    return clip_depth_ == OBSCURA_CLIP_DEPTH_ZERO_TO_ONE ? z_ndc : z_ndc * 0.5 + 0.5;
}

glm::dvec2 Camera::project(const glm::dvec3& world) const {
    glm::dvec4 v = view_ * glm::dvec4(world, 1.0);
    double m[16];
    for (int i = 0; i < 16; ++i) m[i] = matrix_[i];
    double w = m[11] * v.z + m[15];
    double ndc_x = (m[0] * v.x + m[8] * v.z + m[12]) / w;
    double ndc_y = (m[5] * v.y + m[9] * v.z + m[13]) / w;
    return glm::dvec2((ndc_x * 0.5 + 0.5) * width_, (ndc_y * 0.5 + 0.5) * height_);
}

Primitive plane(int id, glm::dvec3 point, glm::dvec3 normal) {
    Primitive p;
    p.kind = Primitive::Kind::Plane;
    p.id = id;
    p.point = point;
    p.normal = glm::normalize(normal);
    return p;
}

Primitive bounded_plane(int id, glm::dvec3 point, glm::dvec3 normal, glm::dvec3 lo, glm::dvec3 hi) {
    Primitive p = plane(id, point, normal);
    p.bounded = true;
    p.bounds_min = lo;
    p.bounds_max = hi;
    return p;
}

Primitive box(int id, glm::dvec3 lo, glm::dvec3 hi) {
    Primitive p;
    p.kind = Primitive::Kind::Box;
    p.id = id;
    p.bounds_min = lo;
    p.bounds_max = hi;
    return p;
}

Primitive sphere(int id, glm::dvec3 centre, double radius) {
    Primitive p;
    p.kind = Primitive::Kind::Sphere;
    p.id = id;
    p.point = centre;
    p.radius = radius;
    return p;
}

namespace {

constexpr double kMiss = std::numeric_limits<double>::infinity();

bool inside(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi) {
    const double e = 1e-9;
    return p.x >= lo.x - e && p.y >= lo.y - e && p.z >= lo.z - e && p.x <= hi.x + e && p.y <= hi.y + e &&
           p.z <= hi.z + e;
}

// Distance along the (unit) ray to the primitive, and its outward normal there.
double intersect(const Primitive& p, const glm::dvec3& o, const glm::dvec3& d, glm::dvec3* normal) {
    switch (p.kind) {
        case Primitive::Kind::Plane: {
            double denom = glm::dot(p.normal, d);
            if (std::fabs(denom) < 1e-15) return kMiss;
            double t = glm::dot(p.point - o, p.normal) / denom;
            if (t <= 0.0) return kMiss;
            if (p.bounded && !inside(o + t * d, p.bounds_min, p.bounds_max)) return kMiss;
            *normal = p.normal;
            return t;
        }
        case Primitive::Kind::Box: {
            double t_near = -kMiss, t_far = kMiss;
            int axis_near = -1;
            double sign_near = 0.0;
            for (int a = 0; a < 3; ++a) {
                if (std::fabs(d[a]) < 1e-15) {
                    if (o[a] < p.bounds_min[a] || o[a] > p.bounds_max[a]) return kMiss;
                    continue;
                }
                double t0 = (p.bounds_min[a] - o[a]) / d[a];
                double t1 = (p.bounds_max[a] - o[a]) / d[a];
                double s = -1.0;  // entering through the min face: normal -axis
                if (t0 > t1) {
                    std::swap(t0, t1);
                    s = 1.0;
                }
                if (t0 > t_near) {
                    t_near = t0;
                    axis_near = a;
                    sign_near = s;
                }
                t_far = std::fmin(t_far, t1);
            }
            if (t_near > t_far || t_near <= 0.0 || axis_near < 0) return kMiss;
            *normal = glm::dvec3(0.0);
            (*normal)[axis_near] = sign_near;
            return t_near;
        }
        case Primitive::Kind::Sphere: {
            glm::dvec3 oc = o - p.point;
            double b = glm::dot(oc, d);
            double c = glm::dot(oc, oc) - p.radius * p.radius;
            double disc = b * b - c;
            if (disc < 0.0) return kMiss;
            double t = -b - std::sqrt(disc);
            if (t <= 0.0) return kMiss;
            *normal = glm::normalize(o + t * d - p.point);
            return t;
        }
    }
    return kMiss;
}

}  // namespace

std::vector<Hit> trace(const Camera& camera, const std::vector<Primitive>& scene) {
    std::vector<Hit> hits(size_t(camera.width()) * size_t(camera.height()));
    const glm::dmat4 inverse_view = glm::inverse(camera.view());
    const glm::dmat3 view_rotation(camera.view());
    for (int y = 0; y < camera.height(); ++y) {
        for (int x = 0; x < camera.width(); ++x) {
            glm::dvec3 origin_view, direction_view;
            camera.ray(x, y, &origin_view, &direction_view);
            glm::dvec3 o = glm::dvec3(inverse_view * glm::dvec4(origin_view, 1.0));
            glm::dvec3 d = glm::normalize(glm::dvec3(inverse_view * glm::dvec4(direction_view, 0.0)));
            double best = kMiss;
            Hit hit;
            for (const Primitive& p : scene) {
                glm::dvec3 n;
                double t = intersect(p, o, d, &n);
                if (t < best) {
                    best = t;
                    hit.hit = true;
                    hit.id = p.id;
                    hit.world = o + t * d;
                    if (glm::dot(n, d) > 0.0) n = -n;  // facing the viewer
                    hit.view_normal = glm::normalize(view_rotation * n);
                }
            }
            if (hit.hit) hit.view = glm::dvec3(camera.view() * glm::dvec4(hit.world, 1.0));
            hits[size_t(y) * camera.width() + x] = hit;
        }
    }
    return hits;
}

std::vector<float> depth_values(const Camera& camera, const std::vector<Hit>& hits) {
    std::vector<float> depth(hits.size());
    for (size_t i = 0; i < hits.size(); ++i) {
        if (camera.projection() == Projection::LinearView) {
            depth[i] = hits[i].hit ? float(hits[i].view_depth()) : 0.0f;
        } else {
            depth[i] = hits[i].hit ? float(camera.window_depth(hits[i].view.z)) : camera.sky_window_depth();
        }
    }
    return depth;
}

glm::dmat4 look_at(glm::dvec3 eye, glm::dvec3 target) {
    return glm::lookAt(eye, target, glm::dvec3(0.0, 1.0, 0.0));
}

std::vector<bool> interior_mask(const std::vector<Hit>& hits, int width, int height, int r) {
    std::vector<bool> mask(hits.size(), false);
    for (int y = r; y < height - r; ++y) {
        for (int x = r; x < width - r; ++x) {
            const Hit& centre = hits[size_t(y) * width + x];
            if (!centre.hit) continue;
            bool same = true;
            for (int dy = -r; dy <= r && same; ++dy)
                for (int dx = -r; dx <= r && same; ++dx) {
                    const Hit& h = hits[size_t(y + dy) * width + (x + dx)];
                    same = h.hit && h.id == centre.id;
                }
            mask[size_t(y) * width + x] = same;
        }
    }
    return mask;
}

}  // namespace obscura_test
