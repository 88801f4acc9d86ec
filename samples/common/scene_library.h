// The scenes of the samples: built-in procedural scenes, the Stanford bunny of glmark2-data, and any
// Wavefront OBJ file. Each comes as a world-space mesh (metres, y up) with named viewpoints, ready for
// render_scene() (demo_scene.h).
//
// Built-in scenes, in list_scenes() order (viewpoint [0] is always "default"):
//   atrium    an arcaded courtyard in the manner of Sponza / Sibenik: two storeys of columns and round
//             arches, a gallery with a floor slab and a balustrade, stairs up to a dais, hanging drapes,
//             a fountain, benches; the roof is open over the court. The headline scene of the quality
//             comparisons. Viewpoints: default, gallery, aisle, stairs, overview.
//   terrain   a 96 m height field of value noise (hills and folded ridges cut into terraces, fine bumps)
//             with half-buried boulders, seen at a grazing angle. Viewpoints: default, valley, overview.
//   objects   spheres, boxes, tori and a cylinder on a floor, several touching each other and the floor.
//             Viewpoints: default, close, low, top.
//   clutter   a furnished room with thin features: a table and chairs with thin legs and spindles,
//             shelves with books, a platform with a railing, a radiator, a stool, a floor lamp.
//             Viewpoints: default, table, shelves, railing.
//   analytic  floor, wall and box whose exact obscurance analytic_ao.h computes. Viewpoints: default,
//             corner, box, top.
//   room      the demo room of build_demo_scene_mesh(). Viewpoints: default, left, right, high.
//   sliding   the objects scene with a box sliding across the floor in front of them (+x, 5 cm a frame): the
//             moving object of the temporal accumulation's ghosting measure (compare --frames). Viewpoints:
//             those of objects.
//   bunny     /usr/share/glmark2/models/bunny.obj (package glmark2-data) standing on a floor quad,
//             auto-framed; listed as unavailable when the file is missing. Viewpoints: default, left,
//             right, top.
// An OBJ path: the file as is (triangulated; normals from the file, or per face where it has none),
// auto-framed by frame_bounds(). Viewpoints: default, left, right, top.
#ifndef OBSCURA_SAMPLES_SCENE_LIBRARY_H
#define OBSCURA_SAMPLES_SCENE_LIBRARY_H

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "demo_scene.h"
#include "scene_projection.h"

namespace obscura::samples {

struct NamedCamera {
    std::string name;
    Camera camera;
};

// A rigid part of a scene that moves from frame to frame: the mesh's vertices from `first_vertex` on, placed for
// frame 0, are moved by frame * velocity in frame `frame`.
struct SceneMotion {
    int first_vertex = 0;
    glm::vec3 velocity{0.0f};  // metres per frame
};

struct Scene {
    std::string name;         // "atrium", or the OBJ path
    std::string description;  // one line
    SceneMesh mesh;           // world space, metres, y up; an animated scene's as of frame 0
    std::vector<NamedCamera> viewpoints;  // [0] is the default camera, named "default"
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  // of the mesh (frame 0)
    SceneMotion motion;       // velocity 0: a still scene

    bool animated() const { return motion.velocity != glm::vec3(0.0f); }
    // The mesh in frame `frame` (any integer; frame 0 is `mesh`): the same vertices in the same order, the moving
    // part moved. Its triangles from first_moving_triangle() on are the moving part's.
    SceneMesh mesh_at(int frame) const;
    int first_moving_triangle() const { return animated() ? motion.first_vertex / 3 : mesh.triangle_count(); }
};

struct SceneInfo {
    std::string name;
    std::string description;
    bool available = true;  // false: a scene whose data file is missing (bunny without glmark2-data)
};

// The built-in scenes in a fixed order, then "bunny".
std::vector<SceneInfo> list_scenes();

// A built-in name, "bunny", or a path ending in ".obj" (any case). Throws std::invalid_argument for
// an unknown name (the message lists the valid ones) and std::runtime_error for a missing or
// unreadable file, or one without triangles.
Scene load_scene(const std::string& name_or_obj_path);

// Throws std::invalid_argument listing the scene's viewpoint names.
const NamedCamera& find_viewpoint(const Scene& scene, const std::string& name);

// `camera` with its eye rotated about the target by `degrees` around camera.up (counter-clockwise
// seen from above when up is +y); everything else unchanged.
Camera orbit_camera(const Camera& camera, float degrees);

// A camera that sees the whole box [lo, hi] (its bounding sphere fits the vertical field of view, so
// any aspect >= 1 shows all of it) from the front (+z), 30 degrees to the right and 25 degrees above,
// with near and far planes around the box and ortho_half_height fitted too. Used for OBJ files.
Camera frame_bounds(glm::vec3 lo, glm::vec3 hi, float fov_y_degrees);

// The path of the bunny model (glmark2-data).
const char* bunny_obj_path();

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_SCENE_LIBRARY_H
