// The scene registry, OBJ files (through tinyobjloader), the bunny, and the camera helpers.
#include "scene_library.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

#include <tiny_obj_loader.h>

#include <glm/gtc/matrix_transform.hpp>

#include "mesh_builder.h"
#include "scenes/procedural_scenes.h"

namespace obscura::samples {
namespace {

struct BuiltInScene {
    const char* name;
    const char* description;
    Scene (*build)();
};

const BuiltInScene kBuiltInScenes[] = {
    {"atrium", "arcaded courtyard: two storeys of columns and arches, gallery, balustrade, stairs, drapes",
     &scenes::build_atrium},
    {"terrain", "terraced value-noise hills and ridges with boulders, grazing view", &scenes::build_terrain},
    {"objects", "spheres, boxes, tori and a cylinder on a floor, touching each other", &scenes::build_objects},
    {"clutter", "furnished room: thin chair legs and spindles, table, shelves, railing, radiator",
     &scenes::build_clutter},
    {"analytic", "floor, wall and box with exactly known obscurance (analytic_ao.h)", &scenes::build_analytic},
    {"room", "the demo room: walls, boxes and a sphere (build_demo_scene_mesh)", &scenes::build_room},
    {"sliding", "the objects scene with a box sliding across the floor, 5 cm a frame (animated)",
     &scenes::build_sliding},
};
constexpr const char* kBunnyName = "bunny";
constexpr const char* kBunnyDescription = "Stanford bunny (glmark2-data, ~70k triangles) on a floor";

bool file_exists(const std::string& path) {
    return std::ifstream(path).good();
}

bool ends_with_obj(const std::string& path) {
    if (path.size() < 4) return false;
    std::string extension = path.substr(path.size() - 4);
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".obj";
}

std::string valid_scene_names() {
    std::string names;
    for (const BuiltInScene& scene : kBuiltInScenes) names += std::string(scene.name) + ", ";
    return names + kBunnyName + ", or a path ending in .obj";
}

void compute_bounds(Scene& scene) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    const std::vector<float>& v = scene.mesh.vertices;
    for (size_t i = 0; i + 5 < v.size(); i += 6) {
        const glm::vec3 p(v[i], v[i + 1], v[i + 2]);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    scene.bounds_min = lo;
    scene.bounds_max = hi;
}

std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    return line;
}

// Triangles of an OBJ file, in the file's units and axes.
SceneMesh load_obj_mesh(const std::string& path) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        const std::string reason = first_line(reader.Error());
        throw std::runtime_error("cannot read OBJ file '" + path + "'" + (reason.empty() ? "" : ": " + reason));
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    auto position = [&](int index) {
        const size_t i = size_t(index) * 3;
        return glm::vec3(float(attrib.vertices[i]), float(attrib.vertices[i + 1]), float(attrib.vertices[i + 2]));
    };
    auto file_normal = [&](int index, glm::vec3* normal) {
        if (index < 0 || size_t(index) * 3 + 2 >= attrib.normals.size()) return false;
        const size_t i = size_t(index) * 3;
        const glm::vec3 n(float(attrib.normals[i]), float(attrib.normals[i + 1]), float(attrib.normals[i + 2]));
        const float length = glm::length(n);
        if (!(length > 0.0f) || !std::isfinite(length)) return false;
        *normal = n / length;
        return true;
    };

    MeshBuilder builder;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const tinyobj::mesh_t& mesh = shape.mesh;
        size_t offset = 0;
        for (const auto face_size : mesh.num_face_vertices) {
            const size_t count = size_t(face_size);
            if (count == 3 && offset + 3 <= mesh.indices.size()) {
                const tinyobj::index_t* index = &mesh.indices[offset];
                for (int k = 0; k < 3; ++k) {
                    if (index[k].vertex_index < 0 || size_t(index[k].vertex_index) * 3 + 2 >= attrib.vertices.size()) {
                        throw std::runtime_error("OBJ file '" + path + "' has a face with a bad vertex index");
                    }
                }
                const glm::vec3 a = position(index[0].vertex_index), b = position(index[1].vertex_index),
                                c = position(index[2].vertex_index);
                // A vertex beyond the float range (1e400) or NaN would give infinite bounds, a NaN camera and NaN
                // rays (Embree asserts on them): such faces are left out, with or without file normals.
                auto finite = [](const glm::vec3& v) { return !glm::any(glm::isnan(v)) && !glm::any(glm::isinf(v)); };
                if (!finite(a) || !finite(b) || !finite(c)) {
                    offset += count;
                    continue;
                }
                glm::vec3 na, nb, nc;
                if (file_normal(index[0].normal_index, &na) && file_normal(index[1].normal_index, &nb) &&
                    file_normal(index[2].normal_index, &nc)) {
                    builder.triangle(a, na, b, nb, c, nc);
                } else {
                    // Per face, from the winding (counter-clockwise is the front, as OBJ has it).
                    const glm::vec3 cross = glm::cross(b - a, c - a);
                    const float length = glm::length(cross);
                    if (length > 0.0f && std::isfinite(length)) builder.triangle(a, b, c, cross / length);
                }
            }
            offset += count;
        }
    }
    if (builder.triangle_count() == 0) throw std::runtime_error("OBJ file '" + path + "' has no triangles");
    return builder.take();
}

// default, left, right (orbits of the framing camera) and top.
std::vector<NamedCamera> framed_viewpoints(const glm::vec3& lo, const glm::vec3& hi) {
    const Camera framed = frame_bounds(lo, hi, 60.0f);
    Camera top = framed;
    const float distance = glm::length(framed.eye - framed.target);
    top.eye = framed.target + glm::vec3(0.0f, distance, 0.0f);
    top.up = glm::vec3(0.0f, 0.0f, -1.0f);
    return {{"default", framed},
            {"left", orbit_camera(framed, -70.0f)},
            {"right", orbit_camera(framed, 70.0f)},
            {"top", top}};
}

Scene load_obj_scene(const std::string& path) {
    Scene scene;
    scene.name = path;
    scene.mesh = load_obj_mesh(path);
    scene.description = "OBJ file, " + std::to_string(scene.mesh.triangle_count()) + " triangles";
    compute_bounds(scene);
    scene.viewpoints = framed_viewpoints(scene.bounds_min, scene.bounds_max);
    return scene;
}

Scene load_bunny_scene() {
    const std::string path = bunny_obj_path();
    if (!file_exists(path)) {
        throw std::runtime_error("scene 'bunny' needs " + path + " (install the package glmark2-data)");
    }
    SceneMesh bunny = load_obj_mesh(path);
    // Stand it on y = 0, centred over the origin.
    Scene framing;
    framing.mesh = bunny;
    compute_bounds(framing);
    const glm::vec3 shift(-0.5f * (framing.bounds_min.x + framing.bounds_max.x), -framing.bounds_min.y,
                          -0.5f * (framing.bounds_min.z + framing.bounds_max.z));
    for (size_t i = 0; i + 5 < bunny.vertices.size(); i += 6) {
        bunny.vertices[i] += shift.x;
        bunny.vertices[i + 1] += shift.y;
        bunny.vertices[i + 2] += shift.z;
    }
    const glm::vec3 lo = framing.bounds_min + shift, hi = framing.bounds_max + shift;

    MeshBuilder builder(std::move(bunny));
    const float half = 2.5f * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    builder.quad({-half, 0.0f, half}, {half, 0.0f, half}, {half, 0.0f, -half}, {-half, 0.0f, -half}, {0, 1, 0});

    Scene scene;
    scene.name = kBunnyName;
    scene.description = kBunnyDescription;
    scene.mesh = builder.take();
    compute_bounds(scene);
    scene.viewpoints = framed_viewpoints(lo, hi);
    for (NamedCamera& named : scene.viewpoints) {
        // The floor reaches beyond the framed box: keep all of it inside the far plane.
        const float floor_reach = glm::length(named.camera.eye) + half * std::sqrt(2.0f);
        named.camera.far_plane = std::max(named.camera.far_plane, 1.1f * floor_reach);
    }
    return scene;
}

}  // namespace

namespace scenes {

Scene build_room() {
    Scene scene;
    scene.mesh = build_demo_scene_mesh(false);
    const Camera camera;  // the demo room's default camera
    Camera high = camera;
    high.eye = glm::vec3(0.0f, 4.6f, 6.8f);
    scene.viewpoints = {{"default", camera},
                        {"left", orbit_camera(camera, -25.0f)},
                        {"right", orbit_camera(camera, 25.0f)},
                        {"high", high}};
    return scene;
}

}  // namespace scenes

const char* bunny_obj_path() {
    return "/usr/share/glmark2/models/bunny.obj";
}

std::vector<SceneInfo> list_scenes() {
    std::vector<SceneInfo> list;
    for (const BuiltInScene& scene : kBuiltInScenes) list.push_back({scene.name, scene.description, true});
    list.push_back({kBunnyName, kBunnyDescription, file_exists(bunny_obj_path())});
    return list;
}

Scene load_scene(const std::string& name_or_obj_path) {
    for (const BuiltInScene& built_in : kBuiltInScenes) {
        if (name_or_obj_path == built_in.name) {
            Scene scene = built_in.build();
            scene.name = built_in.name;
            scene.description = built_in.description;
            compute_bounds(scene);
            return scene;
        }
    }
    if (name_or_obj_path == kBunnyName) return load_bunny_scene();
    if (ends_with_obj(name_or_obj_path)) return load_obj_scene(name_or_obj_path);
    throw std::invalid_argument("unknown scene '" + name_or_obj_path + "' (valid: " + valid_scene_names() + ")");
}

SceneMesh Scene::mesh_at(int frame) const {
    SceneMesh moved = mesh;
    if (!animated() || frame == 0) return moved;
    const glm::vec3 offset = float(frame) * motion.velocity;
    for (size_t i = size_t(std::max(motion.first_vertex, 0)) * 6; i + 5 < moved.vertices.size(); i += 6) {
        moved.vertices[i] += offset.x;
        moved.vertices[i + 1] += offset.y;
        moved.vertices[i + 2] += offset.z;
    }
    return moved;
}

const NamedCamera& find_viewpoint(const Scene& scene, const std::string& name) {
    std::string names;
    for (const NamedCamera& viewpoint : scene.viewpoints) {
        if (viewpoint.name == name) return viewpoint;
        names += (names.empty() ? "" : ", ") + viewpoint.name;
    }
    throw std::invalid_argument("scene '" + scene.name + "' has no viewpoint '" + name + "' (valid: " + names + ")");
}

Camera orbit_camera(const Camera& camera, float degrees) {
    const glm::vec3 axis = glm::normalize(camera.up);
    const glm::mat4 rotation = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), axis);
    Camera orbited = camera;
    orbited.eye = camera.target + glm::vec3(rotation * glm::vec4(camera.eye - camera.target, 0.0f));
    return orbited;
}

Camera frame_bounds(glm::vec3 lo, glm::vec3 hi, float fov_y_degrees) {
    const glm::vec3 centre = 0.5f * (lo + hi);
    float radius = 0.5f * glm::length(hi - lo);
    if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;
    const float half_fov = 0.5f * glm::radians(std::clamp(fov_y_degrees, 1.0f, 170.0f));
    // The bounding sphere touches the vertical field of view's edges, with 5 % to spare.
    const float distance = 1.05f * radius / std::sin(half_fov);
    const float azimuth = glm::radians(30.0f), elevation = glm::radians(25.0f);
    const glm::vec3 direction(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                              std::cos(elevation) * std::cos(azimuth));
    Camera camera;
    camera.target = centre;
    camera.eye = centre + distance * direction;
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    camera.fov_y_degrees = fov_y_degrees;
    camera.near_plane = std::max(0.5f * (distance - radius), 1e-3f * distance);
    camera.far_plane = 2.0f * (distance + radius);
    camera.ortho_half_height = 1.05f * radius;
    return camera;
}

}  // namespace obscura::samples
