// An analytic scene (tests/gl/analytic_scene.h) uploaded as the SDK's depth input, with helpers to
// render visibility and select texels by what they hit. Shared by the per-method GL tests.
#ifndef OBSCURA_TESTS_AO_TEST_SCENE_H
#define OBSCURA_TESTS_AO_TEST_SCENE_H

#include <string>
#include <vector>

#include "analytic_scene.h"
#include "gl_test_support.h"

namespace obscura_test {

struct AoScene {
    Camera camera;
    std::vector<Hit> hits;
    HostTexture depth;
    obscura_input input;
};

// Ray casts `primitives` through `projection` and uploads the depth (D32F, or R32F linear depth).
AoScene make_ao_scene(Projection projection, const glm::dmat4& view, const std::vector<Primitive>& primitives,
                      const Lens& lens = Lens(), int width = 320, int height = 180);

// Renders into an R32F texture of the output rect's size and reads it back.
std::vector<float> render_visibility(obscura_context* context, const obscura_input& input,
                                     const obscura_settings& settings, obscura_debug_view view = OBSCURA_DEBUG_NONE);

// Mask of texels whose hit satisfies `predicate`, at least `border` texels from the image edge.
template <class Predicate>
std::vector<bool> select(const std::vector<Hit>& hits, int width, int height, int border, Predicate predicate) {
    std::vector<bool> mask(hits.size(), false);
    for (int y = border; y < height - border; ++y)
        for (int x = border; x < width - border; ++x) {
            const Hit& h = hits[size_t(y) * width + x];
            mask[size_t(y) * width + x] = h.hit && predicate(h);
        }
    return mask;
}

// A plane through (0, 0, -5) with normal (0.3, 0.5, 1) filling the image, seen from the origin.
AoScene tilted_plane_scene(Projection projection);
// A floor seen 35 degrees from grazing, covering the whole image (no horizon in view).
AoScene steep_floor_scene(Projection projection);
// Statistics of `visibility` over the texels that hit geometry.
Stats geometry_stats(const AoScene& scene, const std::vector<float>& visibility);
// The six projection variants of the flat-plane tests, and the test-name generator for them.
::testing::internal::ParamGenerator<Projection> all_projections();
std::string projection_test_name(const ::testing::TestParamInfo<Projection>& param_info);

// A concave corner: floor (y = 0) and a wall (z = 0, facing +z), seen from (0.3, 1.3, 2.8).
AoScene corner_scene(Projection projection = Projection::Perspective);
// World distance of a hit on the corner's floor or wall from the crease (the line y = 0, z = 0).
double crease_distance(const Hit& h);

// A box (id 2: 1 m square, kBoxHeight tall, centred on the origin) on a floor (id 1: y = 0), seen from above.
constexpr double kBoxHalf = 0.5;
constexpr double kBoxHeight = 0.7;
AoScene box_scene();
// Horizontal distance of a floor point from the box's footprint (0 inside).
double footprint_distance(const Hit& h);

// "N texels, min a mean b max c" for failure messages.
std::string describe(const Stats& s);

}  // namespace obscura_test

#endif  // OBSCURA_TESTS_AO_TEST_SCENE_H
