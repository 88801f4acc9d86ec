// The "atrium" scene: an arcaded courtyard in the manner of Sponza or the Sibenik cathedral, built to
// be rich in what ambient obscurance is about: columns meeting plinths and floors, arches and their
// soffits, a gallery slab with an overhang, a balustrade of thin balusters, stairs up to a dais,
// drapes hanging a hand's width in front of the arcades, benches with narrow gaps, a fountain.
//
// Layout (metres): the court is 16 m wide (x in [-8, 8]) and 24 m long (z in [-12, 12]), walls 11 m
// high, open to the sky over the nave (|x| < 5). Along both long sides an arcade of 8 bays (3 m) on
// two storeys: ground columns at x = +-5 with arches springing at 3.2 m, the gallery slab at 4.7-5.0 m,
// upper columns and arches, and a roof slab over the gallery at 9.4-9.7 m. The aisles behind the
// ground arcade are raised by 12 cm. Stairs climb to a dais at the far end (z = -12).
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "mesh_builder.h"
#include "scenes/procedural_scenes.h"

namespace obscura::samples::scenes {
namespace {

constexpr float kHalfWidth = 8.0f;    // outer walls at x = +-8
constexpr float kArcadeX = 5.0f;      // column axes at x = +-5
constexpr float kHalfLength = 12.0f;  // end walls at z = +-12
constexpr float kWallHeight = 11.0f;
constexpr float kWallThickness = 0.4f;
constexpr float kBay = 3.0f;
constexpr int kBays = 8;
constexpr float kAisleStep = 0.12f;

// Storey geometry: column on a plinth, a capital, and the arches that spring from it.
struct Storey {
    float floor_y;
    float plinth_half, plinth_height;
    float shaft_radius, shaft_top;
    float capital_half, capital_height;
    float arch_thickness, arch_height;
};

constexpr Storey kGround{0.0f, 0.35f, 0.3f, 0.25f, 2.9f, 0.35f, 0.3f, 0.6f, 1.5f};
constexpr Storey kUpper{5.0f, 0.25f, 0.2f, 0.17f, 7.6f, 0.25f, 0.25f, 0.45f, 1.55f};

float bay_centre(int bay) {
    return -kHalfLength + kBay * (float(bay) + 0.5f);
}

void walls_and_floors(MeshBuilder& b) {
    const float hw = kHalfWidth, hl = kHalfLength, t = kWallThickness;
    b.quad({-hw, 0.0f, hl}, {hw, 0.0f, hl}, {hw, 0.0f, -hl}, {-hw, 0.0f, -hl}, {0.0f, 1.0f, 0.0f});
    b.box({hw, 0.0f, -hl - t}, {hw + t, kWallHeight, hl + t}, kBoxNoBottom);
    b.box({-hw - t, 0.0f, -hl - t}, {-hw, kWallHeight, hl + t}, kBoxNoBottom);
    b.box({-hw, 0.0f, hl}, {hw, kWallHeight, hl + t}, kBoxNoBottom & ~kBoxNegX & ~kBoxPosX);
    b.box({-hw, 0.0f, -hl - t}, {hw, kWallHeight, -hl}, kBoxNoBottom & ~kBoxNegX & ~kBoxPosX);
    for (float side : {-1.0f, 1.0f}) {
        // Raised aisle floor behind the ground arcade: a 12 cm step along the plinths.
        const float inner = side * (kArcadeX + kGround.plinth_half), outer = side * hw;
        b.box({std::fmin(inner, outer), 0.0f, -hl}, {std::fmax(inner, outer), kAisleStep, hl},
              side > 0 ? kBoxNegX | kBoxPosY : kBoxPosX | kBoxPosY);
        // Gallery floor and roof slabs, 10 cm proud of the arcade faces, and a parapet on the roof.
        const float edge = side * (kArcadeX - 0.4f);
        const unsigned slab_faces = kBoxPosY | kBoxNegY | (side > 0 ? kBoxNegX : kBoxPosX);
        b.box({std::fmin(edge, outer), 4.7f, -hl}, {std::fmax(edge, outer), 5.0f, hl}, slab_faces);
        b.box({std::fmin(edge, outer), 9.4f, -hl}, {std::fmax(edge, outer), 9.7f, hl}, slab_faces);
        const float parapet = side * (kArcadeX - 0.1f);
        b.box({std::fmin(edge, parapet), 9.7f, -hl}, {std::fmax(edge, parapet), 10.3f, hl},
              kBoxPosY | kBoxNegX | kBoxPosX);
    }
}

void storey(MeshBuilder& b, const Storey& s, float side) {
    const float x = side * kArcadeX;
    const float capital_y = s.shaft_top;
    const float springing_y = capital_y + s.capital_height;
    for (int column = 1; column < kBays; ++column) {
        const float z = -kHalfLength + kBay * float(column);
        const float y0 = s.floor_y;
        b.box({x - s.plinth_half, y0, z - s.plinth_half}, {x + s.plinth_half, y0 + s.plinth_height, z + s.plinth_half},
              kBoxNoBottom);
        const float shaft_base = y0 + s.plinth_height;
        // A torus moulding where the shaft meets the plinth, and a neck ring under the capital.
        b.torus({x, shaft_base + 0.24f * s.shaft_radius, z}, {0.0f, 1.0f, 0.0f}, 1.08f * s.shaft_radius,
                0.24f * s.shaft_radius, 40, 12);
        b.cylinder({x, shaft_base, z}, s.shaft_radius, capital_y - shaft_base, 32, kCapNone);
        b.box({x - 0.8f * s.capital_half, capital_y - 0.1f, z - 0.8f * s.capital_half},
              {x + 0.8f * s.capital_half, capital_y, z + 0.8f * s.capital_half}, kBoxAll & ~kBoxPosY);
        b.box({x - s.capital_half, capital_y, z - s.capital_half},
              {x + s.capital_half, springing_y, z + s.capital_half});
    }
    // Pilasters against the end walls carry the outer halves of the end arches.
    for (float end : {-1.0f, 1.0f}) {
        const float wall = end * kHalfLength, inner = wall - end * s.capital_half;
        b.box({x - s.capital_half, s.floor_y, std::fmin(wall, inner)},
              {x + s.capital_half, springing_y, std::fmax(wall, inner)},
              kBoxPosX | kBoxNegX | (end > 0 ? kBoxNegZ : kBoxPosZ));
    }
    for (int bay = 0; bay < kBays; ++bay) {
        ArchShape arch;
        arch.springing = {x, springing_y, bay_centre(bay)};
        arch.along = {0.0f, 0.0f, 1.0f};
        arch.half_span = 0.5f * kBay;
        arch.radius = 0.5f * kBay - s.capital_half;
        arch.height = s.arch_height;
        arch.thickness = s.arch_thickness;
        arch.segments = 24;
        arch.end_faces = false;  // neighbours and the end walls cover them
        b.arch(arch);
    }
}

// The gallery balustrade: bottom rail, handrail, and square balusters about 20 cm apart.
void balustrade(MeshBuilder& b, float side) {
    const float x = side * kArcadeX, y0 = kUpper.floor_y;
    for (int bay = 0; bay < kBays; ++bay) {
        const float z0 = bay_centre(bay) - 0.5f * kBay + kUpper.plinth_half;
        const float z1 = bay_centre(bay) + 0.5f * kBay - kUpper.plinth_half;
        b.box({x - 0.08f, y0, z0}, {x + 0.08f, y0 + 0.1f, z1}, kBoxNoBottom & ~kBoxNegZ & ~kBoxPosZ);
        b.box({x - 0.1f, y0 + 0.95f, z0}, {x + 0.1f, y0 + 1.05f, z1}, kBoxAll & ~kBoxNegZ & ~kBoxPosZ);
        const int count = int((z1 - z0) / 0.2f);
        for (int i = 0; i < count; ++i) {
            const float z = z0 + (z1 - z0) * (float(i) + 0.5f) / float(count);
            b.box({x - 0.025f, y0 + 0.1f, z - 0.025f}, {x + 0.025f, y0 + 0.95f, z + 0.025f},
                  kBoxAll & ~kBoxNegY & ~kBoxPosY);
        }
    }
}

// A drape hanging from a rod in front of the arcade of `side`, centred on bay `bay`: gathered at the
// top, five vertical folds that deepen downwards, billowing into the nave. 2 cm thick.
void drape(MeshBuilder& b, float side, int bay) {
    const float zc = bay_centre(bay);
    const float rod_x = side * (kArcadeX - 0.55f), top = 9.1f, bottom = 2.6f;
    b.cylinder_between({rod_x, top + 0.04f, zc - 1.25f}, {rod_x, top + 0.04f, zc + 1.25f}, 0.025f, 12);
    const float phase = 0.7f * float(bay);
    auto position = [=](float s, float t) {
        // s across (along z), t from the bottom (0) to the rod (1); the sign keeps the normal facing
        // the nave on both sides.
        const float hang = 1.0f - t;
        const float width = 1.8f + 0.45f * hang;
        const float fold = (0.04f + 0.08f * hang) * std::sin(2.0f * glm::pi<float>() * 5.0f * s + phase);
        const float billow = 0.2f * std::sin(0.5f * glm::pi<float>() * hang);
        const float x = rod_x - side * (billow + fold);
        const float z = zc + side * (s - 0.5f) * width;
        return glm::vec3(x, bottom + t * (top - bottom), z);
    };
    b.thick_surface(60, 18, position, 0.02f);
}

void stairs_and_dais(MeshBuilder& b) {
    const float back = -kHalfLength, front = back + 2.0f, height = 1.2f;
    b.box({-3.0f, 0.0f, back}, {3.0f, height, front}, kBoxNoBottom & ~kBoxNegZ);
    b.stairs({0.0f, 0.0f, front + 6 * 0.3f}, {0.0f, 0.0f, -1.0f}, 4.0f, 6, 0.2f, 0.3f);
    // A pedestal with a sphere, and two urns at the front corners.
    b.box({0.0f, height, back + 0.9f}, {0.9f, 1.1f, 0.9f}, 0.0f, kBoxNoBottom);
    b.sphere({0.0f, height + 1.1f + 0.45f, back + 0.9f}, 0.45f, 48, 24);
    for (float x : {-2.5f, 2.5f}) {
        b.cylinder({x, height, front - 0.5f}, 0.25f, 0.5f, 32, kCapNone);
        b.sphere({x, height + 0.5f + 0.22f, front - 0.5f}, 0.3f, 32, 16);
    }
}

void fountain(MeshBuilder& b) {
    const glm::vec3 centre(0.0f, 0.0f, 2.0f);
    b.cylinder(centre, 1.6f, 0.4f, 64, kCapTop);
    b.torus(centre + glm::vec3(0.0f, 0.4f, 0.0f), {0.0f, 1.0f, 0.0f}, 1.52f, 0.1f, 96, 16);
    b.cylinder(centre + glm::vec3(0.0f, 0.4f, 0.0f), 0.14f, 1.0f, 24, kCapNone);
    b.torus(centre + glm::vec3(0.0f, 1.4f, 0.0f), {0.0f, 1.0f, 0.0f}, 0.42f, 0.08f, 48, 12);
    b.cylinder(centre + glm::vec3(0.0f, 1.36f, 0.0f), 0.42f, 0.04f, 48, kCapBoth);
    b.sphere(centre + glm::vec3(0.0f, 1.56f, 0.0f), 0.18f, 32, 16);
}

// Benches in alternate aisle bays, 35 cm off the outer walls.
void benches(MeshBuilder& b) {
    for (float side : {-1.0f, 1.0f}) {
        for (int bay = side > 0 ? 1 : 0; bay < kBays; bay += 2) {
            const float x = side * (kHalfWidth - 0.55f), z = bay_centre(bay), y = kAisleStep;
            b.box({x - 0.2f, y + 0.4f, z - 0.8f}, {x + 0.2f, y + 0.46f, z + 0.8f});
            for (float leg : {-0.6f, 0.6f}) {
                b.box({x - 0.17f, y, z + leg - 0.03f}, {x + 0.17f, y + 0.4f, z + leg + 0.03f},
                      kBoxAll & ~kBoxNegY & ~kBoxPosY);
            }
        }
    }
}

}  // namespace

Scene build_atrium() {
    MeshBuilder builder;
    walls_and_floors(builder);
    for (float side : {-1.0f, 1.0f}) {
        storey(builder, kGround, side);
        storey(builder, kUpper, side);
        balustrade(builder, side);
        for (int bay = side > 0 ? 2 : 1; bay < kBays - 1; bay += 2) drape(builder, side, bay);
    }
    stairs_and_dais(builder);
    fountain(builder);
    benches(builder);

    Scene scene;
    scene.mesh = builder.take();
    scene.viewpoints = {
        // Down the nave from near the entrance: floor, fountain, both arcades, gallery, drapes, stairs.
        viewpoint("default", {1.5f, 3.5f, 11.0f}, {0.0f, 1.2f, -3.0f}, 0.1f, 60.0f),
        viewpoint("gallery", {-6.5f, 6.7f, 10.5f}, {-5.3f, 5.8f, -3.0f}, 0.1f, 60.0f),
        viewpoint("aisle", {6.6f, 1.85f, 10.8f}, {5.4f, 1.3f, -2.0f}, 0.1f, 60.0f),
        viewpoint("stairs", {2.8f, 2.6f, -2.0f}, {0.0f, 0.9f, -10.0f}, 0.1f, 60.0f),
        viewpoint("overview", {0.0f, 24.0f, 10.0f}, {0.0f, 0.0f, -1.5f}, 0.5f, 80.0f),
    };
    return scene;
}

}  // namespace obscura::samples::scenes
