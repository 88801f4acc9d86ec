// Geometry of the demo scene. Sizes are metres; the room is 8 m wide, 3 m high, open at the front
// and the top so the default camera (demo_scene.h) looks in from inside its front part.
#include <cmath>
#include <utility>

#include <glm/gtc/constants.hpp>

#include "demo_scene.h"

namespace obscura::samples {
namespace {

class MeshBuilder {
public:
    void vertex(const glm::vec3& position, const glm::vec3& normal) {
        mesh_.vertices.insert(mesh_.vertices.end(),
                              {position.x, position.y, position.z, normal.x, normal.y, normal.z});
    }

    // Corners in order around the quad; both triangles share `normal`.
    void quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
              const glm::vec3& normal) {
        for (const glm::vec3& corner : {a, b, c, a, c, d}) vertex(corner, normal);
    }

    // A box standing on y = base.y, centred on base.x/z, turned by `yaw_degrees` about +y.
    void box(const glm::vec3& base, const glm::vec3& size, float yaw_degrees) {
        const float yaw = glm::radians(yaw_degrees);
        const glm::mat3 rotation(glm::vec3(std::cos(yaw), 0.0f, -std::sin(yaw)), glm::vec3(0.0f, 1.0f, 0.0f),
                                 glm::vec3(std::sin(yaw), 0.0f, std::cos(yaw)));
        const glm::vec3 half = size * 0.5f;
        const glm::vec3 centre = base + glm::vec3(0.0f, half.y, 0.0f);
        for (int axis = 0; axis < 3; ++axis) {
            for (float side : {-1.0f, 1.0f}) {
                // Face `axis` on `side`, spanned by the two other axes.
                glm::vec3 normal(0.0f), u(0.0f), v(0.0f);
                normal[axis] = side;
                u[(axis + 1) % 3] = half[(axis + 1) % 3];
                v[(axis + 2) % 3] = half[(axis + 2) % 3];
                const glm::vec3 face = normal * half[axis];
                auto corner = [&](float su, float sv) { return centre + rotation * (face + su * u + sv * v); };
                quad(corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1), rotation * normal);
            }
        }
    }

    void sphere(const glm::vec3& centre, float radius, int slices, int stacks) {
        auto point = [&](int slice, int stack) {
            const float theta = glm::pi<float>() * float(stack) / float(stacks);  // from +y down
            const float phi = 2.0f * glm::pi<float>() * float(slice) / float(slices);
            return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
        };
        for (int stack = 0; stack < stacks; ++stack) {
            for (int slice = 0; slice < slices; ++slice) {
                const glm::vec3 n[4] = {point(slice, stack), point(slice + 1, stack), point(slice + 1, stack + 1),
                                        point(slice, stack + 1)};
                for (int index : {0, 1, 2, 0, 2, 3}) vertex(centre + radius * n[index], n[index]);
            }
        }
    }

    SceneMesh take() { return std::move(mesh_); }

private:
    SceneMesh mesh_;
};

}  // namespace

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
