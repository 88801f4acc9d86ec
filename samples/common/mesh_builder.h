// Small helpers that append shapes to a SceneMesh: quads, boxes, cylinders, spheres, tori, round
// arches, solid stairs, flat quad grids and smooth parametric surfaces (thin or with a thickness).
//
// Conventions every helper keeps (tests check them on every built-in scene):
//   - triangles wind counter-clockwise seen from the side their normals point to;
//   - normals are unit length: flat faces get the face normal, curved ones the exact surface normal;
//   - solids are closed, except for faces a caller leaves out on purpose because they lie on a
//     supporting surface (box bottoms on a floor, column caps under a capital), where they would only
//     add triangles that nobody sees.
// A rigid placement (rotation + translation) set with set_placement() applies to everything appended
// after it, so furniture can be modelled in its own frame and then turned and moved.
#ifndef OBSCURA_SAMPLES_MESH_BUILDER_H
#define OBSCURA_SAMPLES_MESH_BUILDER_H

#include <functional>

#include <glm/glm.hpp>

#include "demo_scene.h"

namespace obscura::samples {

// Faces of an axis-aligned box, as bits.
enum BoxFaces : unsigned {
    kBoxNegX = 1u << 0,
    kBoxPosX = 1u << 1,
    kBoxNegY = 1u << 2,
    kBoxPosY = 1u << 3,
    kBoxNegZ = 1u << 4,
    kBoxPosZ = 1u << 5,
    kBoxAll = 63u,
    kBoxNoBottom = kBoxAll & ~kBoxNegY,
};

// Caps of a cylinder, as bits.
enum CylinderCaps : unsigned { kCapNone = 0u, kCapBottom = 1u, kCapTop = 2u, kCapBoth = 3u };

// A round arch: a block of `thickness` spanning [-half_span, half_span] along `along` and [0, height]
// above `springing` (the centre of the opening at the height where the curve starts), with a
// semicircular opening of `radius` (<= half_span, < height) cut from below. The flat bottom strips
// beside the opening rest on the supports.
struct ArchShape {
    glm::vec3 springing{0.0f};
    glm::vec3 along{0.0f, 0.0f, 1.0f};  // horizontal unit vector of the span
    float half_span = 1.5f;
    float radius = 1.2f;
    float height = 1.5f;
    float thickness = 0.5f;
    int segments = 24;  // along the half circle
    bool end_faces = true;  // the two vertical ends (leave out where they abut a wall or another arch)
};

class MeshBuilder {
public:
    MeshBuilder() = default;
    // Appends to an existing mesh.
    explicit MeshBuilder(SceneMesh mesh) : mesh_(std::move(mesh)) {}

    // Rigid placement applied to everything appended from now on (identity by default).
    void set_placement(const glm::mat4& rigid) { placement_ = rigid; }
    // Turn by `yaw_degrees` about +y, then move by `offset`.
    void set_placement(const glm::vec3& offset, float yaw_degrees);
    void reset_placement() { placement_ = glm::mat4(1.0f); }

    void vertex(const glm::vec3& position, const glm::vec3& normal);
    void triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& normal);
    void triangle(const glm::vec3& a, const glm::vec3& na, const glm::vec3& b, const glm::vec3& nb,
                  const glm::vec3& c, const glm::vec3& nc);
    // Corners in counter-clockwise order seen from `normal`'s side; both triangles share `normal`.
    void quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
              const glm::vec3& normal);
    // A flat rectangle corner + s * edge_u + t * edge_v (s, t in [0, 1]) split into nu x nv cells;
    // its normal is normalize(cross(edge_u, edge_v)).
    void quad_grid(const glm::vec3& corner, const glm::vec3& edge_u, const glm::vec3& edge_v, int nu, int nv);

    // Axis-aligned box [lo, hi] with the chosen faces.
    void box(const glm::vec3& lo, const glm::vec3& hi, unsigned faces = kBoxAll);
    // A box standing on y = base.y, centred on base.x/z, turned by `yaw_degrees` about +y.
    void box(const glm::vec3& base, const glm::vec3& size, float yaw_degrees, unsigned faces = kBoxAll);

    // Vertical cylinder standing on `base` (centre of its bottom), smooth sides.
    void cylinder(const glm::vec3& base, float radius, float height, int segments, unsigned caps = kCapBoth);
    // Cylinder from a to b (any direction).
    void cylinder_between(const glm::vec3& a, const glm::vec3& b, float radius, int segments,
                          unsigned caps = kCapBoth);
    void sphere(const glm::vec3& centre, float radius, int slices, int stacks);
    // Torus around an axis through `centre`: `major` from the axis to the tube's centre line, tube radius `minor`.
    void torus(const glm::vec3& centre, const glm::vec3& axis, float major, float minor, int segments, int sides);
    void arch(const ArchShape& shape);
    // Solid stairs: the front of the first riser is centred on `foot` (at floor level), steps climb
    // along the horizontal unit vector `climb`; `steps` steps of `rise` x `run`, `width` wide. The
    // last tread ends in a vertical back face; no bottom face.
    void stairs(const glm::vec3& foot, const glm::vec3& climb, float width, int steps, float rise, float run);

    // A smooth surface position(s, t), s and t in [0, 1], split into nu x nv cells. Normals are
    // normalize(dP/ds x dP/dt) (central differences), so orient the parameters accordingly.
    using SurfaceFunction = std::function<glm::vec3(float s, float t)>;
    void surface(int nu, int nv, const SurfaceFunction& position);
    // The same surface as a closed sheet of `thickness` (front and back offset by half of it along the
    // normal, joined by a rim): thin cloth that looks right from both sides.
    void thick_surface(int nu, int nv, const SurfaceFunction& position, float thickness);

    int triangle_count() const { return mesh_.vertex_count() / 3; }
    SceneMesh take() { return std::move(mesh_); }

private:
    glm::mat4 placement_{1.0f};
    SceneMesh mesh_;
};

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_MESH_BUILDER_H
