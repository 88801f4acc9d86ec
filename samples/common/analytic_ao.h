// Exact ambient obscurance of the "analytic" scene (scene_library.h), on the CPU in double precision.
// No GL: this file is also compiled into the unit tests.
//
// THE SCENE (metres, y up; analytic_scene_primitives() returns it, and the scene's mesh is built from
// those primitives, so the rasterised geometry and cast_ray() agree exactly):
//   - floor: the rectangle y = 0, x in [-10, 10], z in [-4, 12], facing +y;
//   - wall:  the rectangle z = -4, x in [-10, 10], y in [0, 4], facing +z (the default camera); it
//            stands on the floor's back edge and makes a concave 90-degree corner with it;
//   - box:   [-0.5, 0.5] x [0, 1] x [-0.5, 0.5] on the floor, 3.5 m in front of the wall.
// The default camera (eye (1.5, 4.5, 6.5), target (0, 0.5, -1)) looks down about 28 degrees and sees the
// wall's face, the corner, the box's front (+z), right (+x) and top faces, and open floor all around.
//
// THE QUANTITY (FFAO, eq. 1): A(p, n) = (1/pi) * integral over the hemisphere of n of
// rho(d(p, w)) * max(0, n.w) dw, where d(p, w) is the distance to the nearest hit along w and misses
// contribute 0. rho is the caller's falloff (rho = 1 gives plain cosine-weighted occlusion).
//
// WHERE A SCREEN-SPACE METHOD CAN MATCH IT: a screen-space tracer only knows the surfaces the camera
// sees. With a falloff of compact support R (rho(d) = 0 for d >= R), the exact value is reachable at
// receivers whose occluders within R are all camera-visible from the default camera:
//   - floor points in front of the wall (wall face and corner are visible) that are farther than R
//     from the box (whose back face is hidden);
//   - floor points in front of the box's front face (z > 0.5) within its x-range [-0.5, 0.5]: they can
//     see the box's front face (visible) but neither side face, and the wall face;
//   - wall points near the floor, for R <= 1.5 m: they see only the floor in front of the wall (the
//     floor the box hides from the camera lies between z = -2.5 and -0.5, 1.5 m from the wall);
//   - floor points farther than R from the wall and the box: exact obscurance 0.
// Elsewhere (floor behind or beside the box, the box's faces themselves) the exact value also depends
// on surfaces the camera does not see.
#ifndef OBSCURA_SAMPLES_ANALYTIC_AO_H
#define OBSCURA_SAMPLES_ANALYTIC_AO_H

#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "obscura/obscura.h"

namespace obscura::samples {

// Layout of the analytic scene (the numbers above), for tests and tools that pick receivers.
namespace analytic_layout {
constexpr double kFloorMinX = -10.0, kFloorMaxX = 10.0;
constexpr double kFloorMinZ = -4.0, kFloorMaxZ = 12.0;
constexpr double kWallZ = -4.0, kWallHeight = 4.0;
constexpr double kBoxMinX = -0.5, kBoxMaxX = 0.5, kBoxHeight = 1.0, kBoxMinZ = -0.5, kBoxMaxZ = 0.5;
}  // namespace analytic_layout

// An axis-aligned box, or a bounded axis-aligned rectangle (a piece of plane). Rectangles are thin
// plates: rays hit them from both sides; `side` only says which face the mesh shows.
struct AnalyticPrimitive {
    enum class Kind { Box, Rectangle };
    Kind kind = Kind::Box;
    glm::dvec3 lo{0.0}, hi{0.0};  // box: its corners; rectangle: its extent, with lo[axis] == hi[axis]
    int axis = 1;                 // rectangle: the axis of its normal (0 = x, 1 = y, 2 = z)
    double side = 1.0;            // rectangle: the mesh's normal is side * e_axis (+1 or -1)

    static AnalyticPrimitive box(const glm::dvec3& lo, const glm::dvec3& hi);
    // The rectangle at `position` on `axis`, spanning [lo, hi] on the two other axes (lo[axis] and
    // hi[axis] are ignored), whose mesh faces side * e_axis.
    static AnalyticPrimitive rectangle(int axis, double position, double side, const glm::dvec3& lo,
                                       const glm::dvec3& hi);
};

// The analytic scene's geometry: floor, wall, box (in that order).
const std::vector<AnalyticPrimitive>& analytic_scene_primitives();

// Nearest hit of the ray origin + t * direction, t > 0 (direction need not be unit length; t is in
// its units). On a hit returns true and writes t and the unit normal of the surface on the side the
// ray arrived from (boxes: the outward normal, or the inward one for an origin inside the box).
// Either output pointer may be null.
bool cast_ray(const std::vector<AnalyticPrimitive>& scene, const glm::dvec3& origin, const glm::dvec3& direction,
              double* t, glm::dvec3* normal);

// A(p, n) of the header comment by deterministic quadrature: cosine-weighted directions on a stratified
// midpoint grid in (u = sin^2 theta, phi) of `resolution` x 4 * `resolution` equal-weight cells, one ray
// per cell from p + n * 1e-6. n is normalised here. rho receives the hit distance (> 0) and is not
// called for misses. resolution < 1 is treated as 1.
double exact_obscurance(const std::vector<AnalyticPrimitive>& scene, const glm::dvec3& p, const glm::dvec3& n,
                        const std::function<double(double)>& rho, int resolution = 256);

// The same with the falloff of `falloff` (any method's settings), as the SDK defines it
// (obscura_evaluate_falloff), all hits weighed in one call. std::invalid_argument for refused settings.
double exact_obscurance(const std::vector<AnalyticPrimitive>& scene, const glm::dvec3& p, const glm::dvec3& n,
                        const obscura_settings& falloff, int resolution = 256);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_ANALYTIC_AO_H
