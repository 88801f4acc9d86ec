#include "ao_test_scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace obscura_test {

AoScene make_ao_scene(Projection projection, const glm::dmat4& view, const std::vector<Primitive>& primitives,
                      const Lens& lens, int width, int height) {
    Camera camera(projection, width, height, lens, view);
    std::vector<Hit> hits = trace(camera, primitives);
    std::vector<float> depth = depth_values(camera, hits);
    HostTexture texture = projection == Projection::LinearView
                              ? make_red_texture(GL_R32F, width, height, depth)
                              : make_depth_texture(GL_DEPTH_COMPONENT32F, width, height, depth);
    obscura_input input = make_input(texture.get(), width, height, camera.matrix(), camera.clip_depth());
    if (projection == Projection::LinearView) input.depth_kind = OBSCURA_DEPTH_LINEAR_VIEW;
    return AoScene{camera, std::move(hits), std::move(texture), input};
}

std::vector<float> render_visibility(obscura_context* context, const obscura_input& input,
                                     const obscura_settings& settings, obscura_debug_view view) {
    return render_to_new_texture(context, input, settings, GL_R32F, 1, view);
}

std::string describe(const Stats& s) {
    std::ostringstream out;
    out << s.count << " texels, min " << s.min << " mean " << s.mean << " max " << s.max;
    return out.str();
}

AoScene corner_scene(Projection projection) {
    return make_ao_scene(projection, look_at(glm::dvec3(0.3, 1.3, 2.8), glm::dvec3(0.0, 0.45, 0.0)),
                         {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                          plane(2, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0))});
}

double crease_distance(const Hit& h) { return std::hypot(std::max(h.world.y, 0.0), std::max(h.world.z, 0.0)); }

AoScene box_scene() {
    return make_ao_scene(Projection::Perspective, look_at(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0)),
                         {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                          box(2, glm::dvec3(-kBoxHalf, 0.0, -kBoxHalf), glm::dvec3(kBoxHalf, kBoxHeight, kBoxHalf))});
}

double footprint_distance(const Hit& h) {
    const double dx = std::max(std::fabs(h.world.x) - kBoxHalf, 0.0);
    const double dz = std::max(std::fabs(h.world.z) - kBoxHalf, 0.0);
    return std::hypot(dx, dz);
}

AoScene tilted_plane_scene(Projection projection) {
    return make_ao_scene(projection, glm::dmat4(1.0), {plane(1, glm::dvec3(0.0, 0.0, -5.0), glm::dvec3(0.3, 0.5, 1.0))});
}

AoScene steep_floor_scene(Projection projection) {
    return make_ao_scene(projection, look_at(glm::dvec3(0.0, 3.0, 0.0), glm::dvec3(0.0, 0.0, -2.5)),
                         {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0))});
}

Stats geometry_stats(const AoScene& scene, const std::vector<float>& visibility) {
    std::vector<bool> geometry(visibility.size(), false);
    for (size_t i = 0; i < geometry.size() && i < scene.hits.size(); ++i) geometry[i] = scene.hits[i].hit;
    return stats(visibility, geometry);
}

::testing::internal::ParamGenerator<Projection> all_projections() {
    return ::testing::Values(Projection::Perspective, Projection::ReversedZ, Projection::Infinite,
                             Projection::ReversedInfinite, Projection::Orthographic, Projection::LinearView);
}

std::string projection_test_name(const ::testing::TestParamInfo<Projection>& param_info) {
    return projection_name(param_info.param);
}

}  // namespace obscura_test
