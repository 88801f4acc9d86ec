// Geometry of the demo scene. Sizes are metres; the room is 8 m wide, 3 m high, open at the front
// and the top so the default camera (demo_scene.h) looks in from inside its front part.
#include "demo_scene.h"
#include "mesh_builder.h"

namespace obscura::samples {

SceneMesh build_demo_scene_mesh(bool with_ceiling) {
    constexpr float kLeft = -4.0f, kRight = 4.0f, kBack = -5.0f, kFront = 8.0f, kHeight = 3.0f;
    MeshBuilder builder;
    // Room: every surface faces into the room.
    builder.quad({kLeft, 0, kFront}, {kRight, 0, kFront}, {kRight, 0, kBack}, {kLeft, 0, kBack}, {0, 1, 0});
    builder.quad({kLeft, 0, kBack}, {kRight, 0, kBack}, {kRight, kHeight, kBack}, {kLeft, kHeight, kBack}, {0, 0, 1});
    builder.quad({kLeft, 0, kFront}, {kLeft, 0, kBack}, {kLeft, kHeight, kBack}, {kLeft, kHeight, kFront}, {1, 0, 0});
    builder.quad({kRight, 0, kBack}, {kRight, 0, kFront}, {kRight, kHeight, kFront}, {kRight, kHeight, kBack},
                 {-1, 0, 0});
    if (with_ceiling) {
        builder.quad({kLeft, kHeight, kBack}, {kRight, kHeight, kBack}, {kRight, kHeight, kFront},
                     {kLeft, kHeight, kFront}, {0, -1, 0});
    }
    // Free-standing boxes, turned so their edges are not aligned with the pixel grid.
    builder.box({-1.9f, 0.0f, -1.8f}, {1.2f, 1.0f, 1.2f}, 25.0f);
    builder.box({2.0f, 0.0f, -0.4f}, {0.9f, 0.7f, 0.9f}, -20.0f);
    // Against the back wall: its back face lies in the wall plane, a sharp concave corner for AO.
    builder.box({0.9f, 0.0f, kBack + 0.45f}, {1.6f, 1.3f, 0.9f}, 0.0f);
    // A tall box against the left wall.
    builder.box({kLeft + 0.4f, 0.0f, -3.2f}, {0.8f, 2.0f, 0.8f}, 0.0f);
    // A sphere resting on the floor: a smooth occluder with a point contact.
    builder.sphere({-0.2f, 0.7f, 1.9f}, 0.7f, 48, 24);
    return builder.take();
}

}  // namespace obscura::samples
