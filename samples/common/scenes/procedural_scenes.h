// Builders of the built-in procedural scenes (one file each) and what they share. Internal to
// samples/common: the public interface is scene_library.h.
#ifndef OBSCURA_SAMPLES_SCENES_PROCEDURAL_SCENES_H
#define OBSCURA_SAMPLES_SCENES_PROCEDURAL_SCENES_H

#include <string>

#include "scene_library.h"

namespace obscura::samples::scenes {

// Each returns the mesh and the viewpoints; load_scene() fills in name, description and bounds.
Scene build_atrium();
Scene build_terrain();
Scene build_objects();
Scene build_clutter();
Scene build_analytic();
Scene build_room();
Scene build_sliding();

inline NamedCamera viewpoint(const std::string& name, const glm::vec3& eye, const glm::vec3& target,
                             float near_plane, float far_plane) {
    NamedCamera named;
    named.name = name;
    named.camera.eye = eye;
    named.camera.target = target;
    named.camera.near_plane = near_plane;
    named.camera.far_plane = far_plane;
    return named;
}

}  // namespace obscura::samples::scenes

#endif  // OBSCURA_SAMPLES_SCENES_PROCEDURAL_SCENES_H
