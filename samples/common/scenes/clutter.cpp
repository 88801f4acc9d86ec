// The "clutter" scene: a furnished room, 7 x 6 x 2.8 m with a ceiling, full of thin features: chairs
// with 14 mm legs and 7 mm spindles, a table on a 8 mm rug, shelves of books, a raised platform with a
// railing and steps, a radiator of fins hung 5 cm off the wall, a stool with splayed legs, lamps, cartons.
#include <cmath>
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "mesh_builder.h"
#include "scenes/procedural_scenes.h"

namespace obscura::samples::scenes {
namespace {

constexpr float kLeft = -3.5f, kRight = 3.5f, kBack = -3.0f, kFront = 3.0f, kHeight = 2.8f;

// A small deterministic generator for book sizes (linear congruential, top bits only).
class Sequence {
public:
    float next(float lo, float hi) {
        state_ = state_ * 1664525u + 1013904223u;
        return lo + (hi - lo) * float(state_ >> 8) * (1.0f / 16777216.0f);
    }

private:
    uint32_t state_ = 12345u;
};

void room(MeshBuilder& b) {
    // Every surface faces into the room.
    b.quad({kLeft, 0, kFront}, {kRight, 0, kFront}, {kRight, 0, kBack}, {kLeft, 0, kBack}, {0, 1, 0});
    b.quad({kLeft, kHeight, kBack}, {kRight, kHeight, kBack}, {kRight, kHeight, kFront}, {kLeft, kHeight, kFront},
           {0, -1, 0});
    b.quad({kLeft, 0, kBack}, {kRight, 0, kBack}, {kRight, kHeight, kBack}, {kLeft, kHeight, kBack}, {0, 0, 1});
    b.quad({kRight, 0, kFront}, {kLeft, 0, kFront}, {kLeft, kHeight, kFront}, {kRight, kHeight, kFront}, {0, 0, -1});
    b.quad({kLeft, 0, kFront}, {kLeft, 0, kBack}, {kLeft, kHeight, kBack}, {kLeft, kHeight, kFront}, {1, 0, 0});
    b.quad({kRight, 0, kBack}, {kRight, 0, kFront}, {kRight, kHeight, kFront}, {kRight, kHeight, kBack}, {-1, 0, 0});
    // Skirting boards: 15 mm steps along the floor.
    b.box({kLeft, 0.0f, kBack}, {kRight, 0.08f, kBack + 0.015f}, kBoxNoBottom & ~kBoxNegZ);
    b.box({kLeft, 0.0f, kBack + 0.015f}, {kLeft + 0.015f, 0.08f, kFront}, kBoxNoBottom & ~kBoxNegX);
    // A rug, 8 mm thick.
    b.box({-1.0f, 0.0f, -0.6f}, {1.4f, 0.008f, 1.0f}, kBoxNoBottom);
}

void table(MeshBuilder& b, const glm::vec3& centre) {
    b.set_placement(centre, 0.0f);
    b.box({-0.8f, 0.72f, -0.45f}, {0.8f, 0.76f, 0.45f});
    for (float x : {-0.72f, 0.72f}) {
        for (float z : {-0.37f, 0.37f}) b.cylinder({x, 0.0f, z}, 0.022f, 0.72f, 16, kCapNone);
    }
    for (float z : {-0.37f, 0.37f}) b.cylinder_between({-0.72f, 0.12f, z}, {0.72f, 0.12f, z}, 0.012f, 10, kCapNone);
    b.reset_placement();
}

// A chair in its own frame: the sitter faces +z, the back is at -z.
void chair(MeshBuilder& b, const glm::vec3& position, float yaw_degrees) {
    b.set_placement(position, yaw_degrees);
    b.box({-0.21f, 0.43f, -0.2f}, {0.21f, 0.46f, 0.2f});
    for (float x : {-0.18f, 0.18f}) {
        b.cylinder({x, 0.0f, 0.17f}, 0.014f, 0.43f, 12, kCapNone);   // front leg
        b.cylinder({x, 0.0f, -0.17f}, 0.014f, 0.95f, 12, kCapTop);   // back leg and post
        b.cylinder_between({x, 0.15f, -0.17f}, {x, 0.15f, 0.17f}, 0.008f, 8, kCapNone);
    }
    b.box({-0.2f, 0.86f, -0.185f}, {0.2f, 0.93f, -0.155f});
    for (int i = 0; i < 5; ++i) {
        const float x = -0.12f + 0.06f * float(i);
        b.cylinder({x, 0.46f, -0.17f}, 0.007f, 0.4f, 8, kCapNone);
    }
    b.reset_placement();
}

void shelves(MeshBuilder& b, const glm::vec3& front_centre) {
    // Local frame: x across, the back panel at z = -0.32 against the wall, the open front at z = 0.
    b.set_placement(front_centre, 0.0f);
    b.box({-0.7f, 0.0f, -0.32f}, {-0.68f, 2.0f, 0.0f}, kBoxNoBottom);
    b.box({0.68f, 0.0f, -0.32f}, {0.7f, 2.0f, 0.0f}, kBoxNoBottom);
    b.box({-0.68f, 0.0f, -0.32f}, {0.68f, 2.0f, -0.31f}, kBoxNoBottom & ~kBoxNegZ);
    const float boards[] = {0.04f, 0.44f, 0.84f, 1.24f, 1.64f, 1.98f};
    for (float y : boards) b.box({-0.68f, y, -0.31f}, {0.68f, y + 0.02f, 0.0f});
    Sequence random;
    for (int shelf = 0; shelf < 4; ++shelf) {
        const float floor_y = boards[shelf] + 0.02f;
        float x = -0.66f;
        const float end = 0.2f + 0.25f * random.next(0.0f, 1.0f);
        while (x < end) {
            const float width = random.next(0.02f, 0.05f), height = random.next(0.16f, 0.3f);
            const float depth = random.next(0.17f, 0.24f);
            b.box({x, floor_y, -0.3f}, {x + width, floor_y + height, -0.3f + depth});
            x += width + (random.next(0.0f, 1.0f) < 0.2f ? 0.01f : 0.0f);
        }
        // The last book leans towards the others, turned about its bottom right edge.
        const glm::vec3 pivot = front_centre + glm::vec3(x + 0.115f, floor_y, 0.0f);
        b.set_placement(glm::rotate(glm::translate(glm::mat4(1.0f), pivot), glm::radians(18.0f),
                                    glm::vec3(0.0f, 0.0f, 1.0f)));
        b.box({-0.035f, 0.0f, -0.3f}, {0.0f, 0.26f, -0.08f});
        b.set_placement(front_centre, 0.0f);
    }
    b.reset_placement();
}

void platform_with_railing(MeshBuilder& b) {
    constexpr float kEdge = 2.2f, kEnd = 1.0f, kTop = 0.36f;
    b.box({kEdge, 0.0f, kBack}, {kRight, kTop, kEnd}, kBoxNoBottom & ~kBoxPosX & ~kBoxNegZ);
    b.stairs({0.5f * (kEdge + kRight), 0.0f, kEnd + 0.75f}, {0.0f, 0.0f, -1.0f}, kRight - kEdge, 3, 0.12f, 0.25f);
    // Railing along the platform's open side: posts every 12 cm, a handrail and a middle rail.
    const float x = kEdge + 0.05f, first = kBack + 0.1f, last = kEnd - 0.05f;
    const int posts = int((last - first) / 0.12f) + 1;
    for (int i = 0; i < posts; ++i) {
        const float z = first + (last - first) * float(i) / float(posts - 1);
        b.cylinder({x, kTop, z}, 0.012f, 0.9f, 10, kCapNone);
    }
    b.cylinder_between({x, kTop + 0.9f, first - 0.05f}, {x, kTop + 0.9f, last + 0.05f}, 0.025f, 16);
    b.cylinder_between({x, kTop + 0.45f, first}, {x, kTop + 0.45f, last}, 0.01f, 8);
    // Crates on the platform, one on another.
    b.box({3.0f, kTop, -2.4f}, {0.6f, 0.45f, 0.5f}, 10.0f, kBoxNoBottom);
    b.box({3.0f, kTop + 0.45f, -2.4f}, {0.45f, 0.35f, 0.4f}, -15.0f, kBoxNoBottom);
}

void radiator(MeshBuilder& b) {
    // Fins 3 cm wide with 3 cm gaps, 5 cm off the left wall, joined by two pipes.
    const float x0 = kLeft + 0.05f, x1 = kLeft + 0.12f;
    for (int i = 0; i < 14; ++i) {
        const float z = -0.5f + 0.06f * float(i);
        b.box({x0, 0.15f, z}, {x1, 0.75f, z + 0.03f});
    }
    const float xm = 0.5f * (x0 + x1);
    for (float y : {0.22f, 0.68f}) b.cylinder_between({xm, y, -0.56f}, {xm, y, 0.37f}, 0.015f, 12);
}

void stool_and_lamp(MeshBuilder& b) {
    const glm::vec3 stool(-1.7f, 0.0f, 1.9f);
    b.cylinder(stool + glm::vec3(0.0f, 0.6f, 0.0f), 0.17f, 0.04f, 32);
    for (int i = 0; i < 3; ++i) {
        const float angle = glm::radians(30.0f + 120.0f * float(i));
        const glm::vec3 out(std::cos(angle), 0.0f, std::sin(angle));
        b.cylinder_between(stool + 0.22f * out, stool + 0.11f * out + glm::vec3(0.0f, 0.6f, 0.0f), 0.012f, 10);
    }
    // A waste bin, a stack of cartons in the front corner, and a pendant lamp on a 4 mm cable.
    b.cylinder({-2.2f, 0.0f, -2.55f}, 0.14f, 0.32f, 24, kCapTop);
    b.box({2.6f, 0.0f, 2.45f}, {0.7f, 0.5f, 0.6f}, 5.0f, kBoxNoBottom);
    b.box({2.55f, 0.5f, 2.4f}, {0.5f, 0.4f, 0.45f}, -12.0f, kBoxNoBottom);
    b.box({1.75f, 0.0f, 2.55f}, {0.6f, 0.35f, 0.5f}, 20.0f, kBoxNoBottom);
    b.cylinder_between({0.2f, kHeight, 0.2f}, {0.2f, 1.95f, 0.2f}, 0.004f, 6, kCapNone);
    b.cylinder({0.2f, 1.88f, 0.2f}, 0.03f, 0.07f, 16);
    b.torus({0.2f, 1.85f, 0.2f}, {0.0f, 1.0f, 0.0f}, 0.2f, 0.02f, 48, 8);
    const glm::vec3 lamp(-3.0f, 0.0f, -2.4f);
    b.cylinder(lamp, 0.15f, 0.03f, 32, kCapTop);
    b.cylinder(lamp + glm::vec3(0.0f, 0.03f, 0.0f), 0.01f, 1.55f, 10, kCapNone);
    b.sphere(lamp + glm::vec3(0.0f, 1.7f, 0.0f), 0.16f, 32, 16);
}

}  // namespace

Scene build_clutter() {
    MeshBuilder builder;
    room(builder);
    const glm::vec3 table_centre(0.2f, 0.0f, 0.2f);
    table(builder, table_centre);
    chair(builder, table_centre + glm::vec3(-0.4f, 0.0f, -0.62f), 0.0f);
    chair(builder, table_centre + glm::vec3(0.4f, 0.0f, -0.6f), 8.0f);
    chair(builder, table_centre + glm::vec3(-0.4f, 0.0f, 0.64f), 180.0f);
    chair(builder, table_centre + glm::vec3(0.55f, 0.0f, 0.95f), 155.0f);  // pulled out
    chair(builder, {-0.2f, 0.0f, kBack + 0.26f}, 0.0f);                   // against the back wall
    shelves(builder, {-1.6f, 0.0f, kBack + 0.32f});
    platform_with_railing(builder);
    radiator(builder);
    stool_and_lamp(builder);

    Scene scene;
    scene.mesh = builder.take();
    scene.viewpoints = {
        viewpoint("default", {-3.1f, 1.9f, 2.6f}, {0.3f, 0.55f, -0.6f}, 0.05f, 20.0f),
        viewpoint("table", {-1.0f, 1.25f, 1.5f}, {0.2f, 0.5f, 0.1f}, 0.05f, 20.0f),
        viewpoint("shelves", {-0.6f, 1.4f, 0.6f}, {-1.6f, 1.0f, -2.9f}, 0.05f, 20.0f),
        viewpoint("railing", {-0.8f, 1.6f, -1.6f}, {2.6f, 0.6f, 0.6f}, 0.05f, 20.0f),
    };
    return scene;
}

}  // namespace obscura::samples::scenes
