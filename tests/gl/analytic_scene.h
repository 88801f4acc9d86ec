// CPU ray casting of analytic scenes (planes, boxes, spheres) through the exact projection the SDK is
// given, so tests know the true view-space position and normal of every depth texel and can write
// the window depth GL would have written, for every projection variant.
//
// Everything is computed in double from the float matrix handed to the SDK (what GL would rasterise
// with): the pixel-centre rays use its x/y rows, window depths its z/w rows.
#ifndef OBSCURA_TESTS_ANALYTIC_SCENE_H
#define OBSCURA_TESTS_ANALYTIC_SCENE_H

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "obscura/obscura.h"

namespace obscura_test {

enum class Projection {
    Perspective,       // standard, [-1,1] clip depth
    ReversedZ,         // reversed, [0,1] clip depth (glClipControl style; CPU-made depth needs no GL 4.5)
    Infinite,          // standard with the far plane at infinity, [-1,1]
    ReversedInfinite,  // reversed infinite, [0,1]
    Orthographic,      // [-1,1]
    LinearView         // a standard perspective matrix, depth given as linear view depth (R32F)
};
const char* projection_name(Projection projection);

struct Lens {
    double fov_y_degrees = 60.0;  // of the whole depth texture
    double near_plane = 0.1;
    double far_plane = 100.0;
    double ortho_half_height = 3.0;
    double shift_x = 0.0;  // off-centre: added to NDC x (m8 for perspective, -m12 for ortho)
    double shift_y = 0.0;
};

class Camera {
public:
    Camera(Projection projection, int width, int height, const Lens& lens, const glm::dmat4& view);

    Projection projection() const { return projection_; }
    int width() const { return width_; }
    int height() const { return height_; }
    const float* matrix() const { return matrix_; }   // column-major, as given to the SDK
    obscura_clip_depth clip_depth() const { return clip_depth_; }
    float sky_window_depth() const { return reversed() ? 0.0f : 1.0f; }
    bool reversed() const {
        return projection_ == Projection::ReversedZ || projection_ == Projection::ReversedInfinite;
    }
    const glm::dmat4& view() const { return view_; }

    // View-space ray through the centre of texel (x, y).
    void ray(int x, int y, glm::dvec3* origin, glm::dvec3* direction) const;
    // Window depth GL would store for a point at view z (< 0), in double.
    double window_depth(double view_z) const;
    // Texel coordinates (continuous, 0..width) of a world point.
    glm::dvec2 project(const glm::dvec3& world) const;

private:
    Projection projection_;
    int width_, height_;
    float matrix_[16];
    obscura_clip_depth clip_depth_;
    glm::dmat4 view_;
};

struct Primitive {
    enum class Kind { Plane, Box, Sphere } kind = Kind::Plane;
    // Plane: point + normal, optionally clipped to [bounds_min, bounds_max] (world AABB).
    glm::dvec3 point{0.0}, normal{0.0, 1.0, 0.0};
    bool bounded = false;
    glm::dvec3 bounds_min{0.0}, bounds_max{0.0};
    // Box: [bounds_min, bounds_max]. Sphere: centre = point, radius.
    double radius = 0.0;
    int id = 0;
};

Primitive plane(int id, glm::dvec3 point, glm::dvec3 normal);
Primitive bounded_plane(int id, glm::dvec3 point, glm::dvec3 normal, glm::dvec3 lo, glm::dvec3 hi);
Primitive box(int id, glm::dvec3 lo, glm::dvec3 hi);
Primitive sphere(int id, glm::dvec3 centre, double radius);

struct Hit {
    bool hit = false;
    int id = -1;
    glm::dvec3 world{0.0};
    glm::dvec3 view{0.0};         // view-space position (z < 0 in front)
    glm::dvec3 view_normal{0.0};  // unit, facing the ray origin
    double view_depth() const { return -view.z; }
};

// Nearest hit of every texel (row-major from the bottom row).
std::vector<Hit> trace(const Camera& camera, const std::vector<Primitive>& scene);

// Depth texture contents for the camera's projection: window depth (sky = clear value), or for
// Projection::LinearView the positive view depth (sky = 0, which the SDK treats as sky).
std::vector<float> depth_values(const Camera& camera, const std::vector<Hit>& hits);

// The view matrix of a camera at `eye` looking at `target` (y up).
glm::dmat4 look_at(glm::dvec3 eye, glm::dvec3 target);

// Pixels whose whole (2r+1)^2 neighbourhood hits the same primitive (away from silhouettes and sky).
std::vector<bool> interior_mask(const std::vector<Hit>& hits, int width, int height, int r);

}  // namespace obscura_test

#endif  // OBSCURA_TESTS_ANALYTIC_SCENE_H
