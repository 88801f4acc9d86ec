// The "objects" scene: simple solids on a large floor, many of them touching each other or the floor
// (contact creases and narrow gaps are where screen-space methods differ most).
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "mesh_builder.h"
#include "scenes/procedural_scenes.h"

namespace obscura::samples::scenes {

Scene build_objects() {
    MeshBuilder builder;
    constexpr float kFloorHalf = 20.0f;
    builder.quad({-kFloorHalf, 0.0f, kFloorHalf}, {kFloorHalf, 0.0f, kFloorHalf}, {kFloorHalf, 0.0f, -kFloorHalf},
                 {-kFloorHalf, 0.0f, -kFloorHalf}, {0.0f, 1.0f, 0.0f});

    // Two spheres touching each other and the floor.
    const glm::vec3 big(-1.6f, 0.5f, 0.0f);
    builder.sphere(big, 0.5f, 48, 24);
    const float small = 0.3f;
    const float reach = std::sqrt((0.5f + small) * (0.5f + small) - (0.5f - small) * (0.5f - small));
    builder.sphere({big.x + reach, small, 0.0f}, small, 40, 20);

    // A turned box with a sphere on top and a smaller box against one of its faces.
    const glm::vec3 box_base(1.3f, 0.0f, -0.7f);
    const float yaw = 20.0f;
    builder.box(box_base, {1.0f, 0.8f, 1.0f}, yaw, kBoxNoBottom);
    builder.sphere(box_base + glm::vec3(0.0f, 0.8f + 0.3f, 0.0f), 0.3f, 40, 20);
    const float radians = glm::radians(yaw);
    const glm::vec3 local_x(std::cos(radians), 0.0f, -std::sin(radians)), local_z(std::sin(radians), 0.0f,
                                                                                 std::cos(radians));
    builder.box(box_base + 0.75f * local_x + 0.1f * local_z, {0.5f, 0.5f, 0.5f}, yaw, kBoxNoBottom);

    // A torus lying on the floor with a sphere resting in its hole, 3 cm above the floor.
    const glm::vec3 ring(0.3f, 0.15f, 1.3f);
    const float major = 0.55f, minor = 0.15f, cradled = 0.55f;
    builder.torus(ring, {0.0f, 1.0f, 0.0f}, major, minor, 64, 24);
    const float lift = std::sqrt((cradled + minor) * (cradled + minor) - major * major);
    builder.sphere(ring + glm::vec3(0.0f, lift, 0.0f), cradled, 48, 24);

    // A torus standing on its rim.
    builder.torus({-0.4f, 0.45f + 0.12f, -1.6f}, {1.0f, 0.0f, 0.0f}, 0.45f, 0.12f, 64, 24);

    // A cylinder, and a pyramid of four small spheres.
    builder.cylinder({-2.5f, 0.0f, -1.3f}, 0.25f, 1.2f, 48, kCapTop);
    const glm::vec3 pile(2.1f, 0.2f, 1.1f);
    const float spread = 0.4f / std::sqrt(3.0f);
    for (int i = 0; i < 3; ++i) {
        const float angle = glm::radians(90.0f + 120.0f * float(i));
        builder.sphere(pile + spread * glm::vec3(std::cos(angle), 0.0f, std::sin(angle)), 0.2f, 32, 16);
    }
    builder.sphere(pile + glm::vec3(0.0f, 0.4f * std::sqrt(2.0f / 3.0f), 0.0f), 0.2f, 32, 16);

    Scene scene;
    scene.mesh = builder.take();
    scene.viewpoints = {
        viewpoint("default", {0.6f, 2.5f, 4.1f}, {0.0f, 0.3f, -0.2f}, 0.1f, 80.0f),
        viewpoint("close", {-0.3f, 1.0f, 1.6f}, {-1.1f, 0.3f, 0.0f}, 0.05f, 60.0f),
        viewpoint("low", {3.6f, 0.45f, 3.6f}, {0.0f, 0.35f, 0.0f}, 0.05f, 80.0f),
        viewpoint("top", {0.0f, 7.5f, 0.5f}, {0.0f, 0.0f, 0.0f}, 0.1f, 60.0f),
    };
    return scene;
}

// The objects scene and, last in the mesh, a box (0.6 x 0.5 x 0.4 m) that slides along +x across the floor in front
// of the torus, 0.35 m from its rim: behind it the floor it uncovers, beside it the contact shadow it drags along.
// 5 cm a frame is 3 m/s at 60 frames a second, about 5 pixels a frame at 640x360 from the default viewpoint.
Scene build_sliding() {
    Scene scene = build_objects();
    scene.motion.first_vertex = scene.mesh.vertex_count();
    MeshBuilder builder(std::move(scene.mesh));
    builder.box(glm::vec3(-1.2f, 0.0f, 2.6f), glm::vec3(0.6f, 0.5f, 0.4f), 0.0f, kBoxNoBottom);
    scene.mesh = builder.take();
    scene.motion.velocity = glm::vec3(0.05f, 0.0f, 0.0f);
    return scene;
}

}  // namespace obscura::samples::scenes
