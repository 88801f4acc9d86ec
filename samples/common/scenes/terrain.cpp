// The "terrain" scene: a 96 x 96 m height field of value noise (rolling hills and folded ridges cut
// into terraces, fine bumps) with half-buried boulders, closed by vertical skirts, seen at a grazing
// angle.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "integer_hash.h"
#include "mesh_builder.h"
#include "scenes/procedural_scenes.h"

namespace obscura::samples::scenes {
namespace {

constexpr float kHalfSize = 48.0f;  // metres, the field spans [-48, 48] in x and z
constexpr int kCells = 224;         // 0.43 m cells

// Integer hash (xorshift-multiply rounds) of a lattice point; deterministic on every platform.
uint32_t hash(int32_t x, int32_t z, uint32_t seed) {
    return hash32(uint32_t(x) * 0x8da6b343u ^ uint32_t(z) * 0xd8163841u ^ seed * 0xcb1ab31fu);
}

float lattice(int32_t x, int32_t z, uint32_t seed) { return unit_float(hash(x, z, seed)); }

// Value noise in [0, 1): lattice values blended with a quintic fade (C2 across cell borders).
float value_noise(float x, float z, uint32_t seed) {
    const float fx = std::floor(x), fz = std::floor(z);
    const int32_t ix = int32_t(fx), iz = int32_t(fz);
    auto fade = [](float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); };
    const float u = fade(x - fx), v = fade(z - fz);
    const float a = lattice(ix, iz, seed), b = lattice(ix + 1, iz, seed);
    const float c = lattice(ix, iz + 1, seed), d = lattice(ix + 1, iz + 1, seed);
    return (a + (b - a) * u) * (1.0f - v) + (c + (d - c) * u) * v;
}

// Octaves of signed value noise, each at twice the frequency and half the amplitude.
float fbm(float x, float z, int octaves, uint32_t seed) {
    float sum = 0.0f, amplitude = 0.5f, frequency = 1.0f;
    for (int octave = 0; octave < octaves; ++octave) {
        sum += amplitude * (2.0f * value_noise(x * frequency, z * frequency, seed + uint32_t(octave)) - 1.0f);
        amplitude *= 0.5f;
        frequency *= 2.0f;
    }
    return sum;
}

float smoothstep(float lo, float hi, float x) {
    const float t = std::clamp((x - lo) / (hi - lo), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

float terrain_height(float x, float z) {
    // Rolling hills plus sharp ridges (folded noise), cut into terraces: flat benches joined by steep
    // risers, each riser foot a long concave crease.
    const float hills = 12.0f * fbm(x / 45.0f, z / 45.0f, 4, 11u);
    // Folded noise; a soft absolute value rounds the crests (a kink would flip smooth normals).
    const float centred = 2.0f * value_noise(x / 23.0f, z / 23.0f, 29u) - 1.0f;
    const float fold = 1.0f - std::sqrt(centred * centred + 0.01f);
    const float ridges = 5.0f * fold * fold;
    const float level = (hills + ridges) / 1.6f;
    const float steps = std::floor(level) + smoothstep(0.55f, 1.0f, level - std::floor(level));
    const float terraced = 1.6f * (level + 0.65f * (steps - level));
    const float bumps = 0.25f * fbm(x / 2.5f, z / 2.5f, 3, 53u);
    return terraced + bumps;
}

}  // namespace

Scene build_terrain() {
    MeshBuilder builder;
    // s along +x, t along -z: dP/ds x dP/dt points up.
    auto field = [](float s, float t) {
        const float x = -kHalfSize + 2.0f * kHalfSize * s, z = kHalfSize - 2.0f * kHalfSize * t;
        return glm::vec3(x, terrain_height(x, z), z);
    };
    builder.surface(kCells, kCells, field);

    // Skirts down to below the lowest point, facing outwards, so the field is a closed solid.
    float lowest = 0.0f;
    for (int j = 0; j <= kCells; ++j) {
        for (int i = 0; i <= kCells; ++i) lowest = std::min(lowest, field(float(i) / kCells, float(j) / kCells).y);
    }
    const float bottom = lowest - 2.0f;
    auto skirt = [&](auto edge_point, const glm::vec3& outward) {
        for (int k = 0; k < kCells; ++k) {
            const glm::vec3 a = edge_point(float(k) / kCells), b = edge_point(float(k + 1) / kCells);
            const glm::vec3 a_low(a.x, bottom, a.z), b_low(b.x, bottom, b.z);
            if (glm::dot(glm::cross(b - a, a_low - a), outward) > 0.0f) {
                builder.quad(a, b, b_low, a_low, outward);
            } else {
                builder.quad(a, a_low, b_low, b, outward);
            }
        }
    };
    skirt([&](float r) { return field(r, 0.0f); }, {0.0f, 0.0f, 1.0f});
    skirt([&](float r) { return field(r, 1.0f); }, {0.0f, 0.0f, -1.0f});
    skirt([&](float r) { return field(0.0f, r); }, {-1.0f, 0.0f, 0.0f});
    skirt([&](float r) { return field(1.0f, r); }, {1.0f, 0.0f, 0.0f});

    // Boulders, half buried, scattered over the middle of the field.
    for (uint32_t i = 0; i < 28u; ++i) {
        const float x = -30.0f + 60.0f * lattice(int32_t(i), 1, 71u);
        const float z = -34.0f + 70.0f * lattice(int32_t(i), 2, 71u);
        const float radius = 0.3f + 0.7f * lattice(int32_t(i), 3, 71u);
        builder.sphere({x, terrain_height(x, z) + 0.35f * radius, z}, radius, 24, 12);
    }

    auto above_ground = [](float x, float z, float height) { return glm::vec3(x, terrain_height(x, z) + height, z); };
    const glm::vec3 eye = above_ground(2.0f, 40.0f, 3.0f);
    const glm::vec3 valley_eye = above_ground(26.0f, 40.0f, 1.8f);
    Scene scene;
    scene.mesh = builder.take();
    scene.viewpoints = {
        // About 14 degrees down: the ground fills most of the frame, the far hills meet the sky near the top.
        viewpoint("default", eye, eye + glm::vec3(-2.0f, -7.5f, -30.0f), 0.1f, 250.0f),
        viewpoint("valley", valley_eye, {0.0f, 3.0f, 4.0f}, 0.1f, 250.0f),  // up the slopes of the central hill
        viewpoint("overview", {0.0f, 40.0f, 70.0f}, {0.0f, 0.0f, 0.0f}, 1.0f, 300.0f),
    };
    return scene;
}

}  // namespace obscura::samples::scenes
