// The "analytic" scene: its mesh is made from analytic_scene_primitives(), so rasterised depth and
// the exact obscurance of analytic_ao.h describe the same geometry.
#include "analytic_ao.h"
#include "mesh_builder.h"
#include "scenes/procedural_scenes.h"

namespace obscura::samples::scenes {
namespace {

void add_rectangle(MeshBuilder& builder, const AnalyticPrimitive& rectangle) {
    const int a = rectangle.axis, u = (a + 1) % 3, v = (a + 2) % 3;
    auto corner = [&](bool high_u, bool high_v) {
        glm::dvec3 p = rectangle.lo;
        p[u] = high_u ? rectangle.hi[u] : rectangle.lo[u];
        p[v] = high_v ? rectangle.hi[v] : rectangle.lo[v];
        return glm::vec3(p);
    };
    glm::vec3 normal(0.0f);
    normal[a] = float(rectangle.side);
    // (e_u, e_v, e_a) is right-handed: counter-clockwise in (u, v) faces +e_a.
    if (rectangle.side > 0.0) {
        builder.quad(corner(false, false), corner(true, false), corner(true, true), corner(false, true), normal);
    } else {
        builder.quad(corner(false, false), corner(false, true), corner(true, true), corner(true, false), normal);
    }
}

}  // namespace

Scene build_analytic() {
    MeshBuilder builder;
    for (const AnalyticPrimitive& primitive : analytic_scene_primitives()) {
        if (primitive.kind == AnalyticPrimitive::Kind::Rectangle) {
            add_rectangle(builder, primitive);
        } else {
            builder.box(glm::vec3(primitive.lo), glm::vec3(primitive.hi));
        }
    }
    Scene scene;
    scene.mesh = builder.take();
    scene.viewpoints = {
        // About 28 degrees down: wall face, corner, box front / right / top and open floor all visible.
        viewpoint("default", {1.5f, 4.5f, 6.5f}, {0.0f, 0.5f, -1.0f}, 0.1f, 60.0f),
        viewpoint("corner", {2.5f, 2.2f, 0.8f}, {0.8f, 0.4f, -4.0f}, 0.1f, 60.0f),
        viewpoint("box", {2.2f, 2.0f, 3.2f}, {0.0f, 0.4f, 0.0f}, 0.1f, 60.0f),
        viewpoint("top", {0.5f, 9.0f, 3.0f}, {0.0f, 0.0f, -1.0f}, 0.1f, 60.0f),
    };
    return scene;
}

}  // namespace obscura::samples::scenes
