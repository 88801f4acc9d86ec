// Exact obscurance of analytic scenes (samples/common/analytic_ao.h), no GL: the ray caster, closed
// forms (an open plane, the foot of a wall, a wall at a distance with a step falloff) and an
// independent Monte Carlo estimate in the analytic scene itself.
#include "analytic_ao.h"

#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

namespace {

using obscura::samples::AnalyticPrimitive;
using obscura::samples::cast_ray;
using obscura::samples::exact_obscurance;

constexpr double kPi = glm::pi<double>();
const glm::dvec3 kUp(0.0, 1.0, 0.0);

double no_falloff(double) {
    return 1.0;
}

// A floor y = 0 and a wall z = 0 facing +z, both `size` metres across.
std::vector<AnalyticPrimitive> floor_and_wall(double size) {
    return {AnalyticPrimitive::rectangle(1, 0.0, 1.0, {-size, 0.0, 0.0}, {size, 0.0, size}),
            AnalyticPrimitive::rectangle(2, 0.0, 1.0, {-size, 0.0, 0.0}, {size, size, 0.0})};
}

TEST(AnalyticAo, CastRayFindsTheNearestSurface) {
    const std::vector<AnalyticPrimitive>& scene = obscura::samples::analytic_scene_primitives();
    double t = 0.0;
    glm::dvec3 normal(0.0);
    // Straight down onto the floor.
    ASSERT_TRUE(cast_ray(scene, {3.0, 2.0, 3.0}, {0.0, -2.0, 0.0}, &t, &normal));
    EXPECT_DOUBLE_EQ(t, 1.0);  // in units of the (unnormalised) direction
    EXPECT_EQ(normal, kUp);
    // Towards the wall through the box: the box's front face comes first.
    ASSERT_TRUE(cast_ray(scene, {0.0, 0.5, 5.0}, {0.0, 0.0, -1.0}, &t, &normal));
    EXPECT_DOUBLE_EQ(t, 4.5);
    EXPECT_EQ(normal, glm::dvec3(0.0, 0.0, 1.0));
    // Beside the box: the wall.
    ASSERT_TRUE(cast_ray(scene, {2.0, 0.5, 5.0}, {0.0, 0.0, -1.0}, &t, &normal));
    EXPECT_DOUBLE_EQ(t, 9.0);
    // From inside the box: its far face, facing back at the origin.
    ASSERT_TRUE(cast_ray(scene, {0.0, 0.5, 0.0}, {1.0, 0.0, 0.0}, &t, &normal));
    EXPECT_DOUBLE_EQ(t, 0.5);
    EXPECT_EQ(normal, glm::dvec3(-1.0, 0.0, 0.0));
    // Rectangles are thin plates: hit from behind too, with the normal facing the ray.
    ASSERT_TRUE(cast_ray(scene, {0.0, 1.0, -6.0}, {0.0, 0.0, 1.0}, &t, &normal));
    EXPECT_DOUBLE_EQ(t, 2.0);
    EXPECT_EQ(normal, glm::dvec3(0.0, 0.0, -1.0));
    // Misses: over the wall, and out beside the floor; null outputs are allowed.
    EXPECT_FALSE(cast_ray(scene, {0.0, 5.0, 0.0}, {0.0, 0.0, -1.0}, nullptr, nullptr));
    EXPECT_FALSE(cast_ray(scene, {20.0, 1.0, 0.0}, {1.0, -0.01, 0.0}, nullptr, nullptr));
}

TEST(AnalyticAo, OpenPlaneIsUnoccluded) {
    const std::vector<AnalyticPrimitive> plane = {
        AnalyticPrimitive::rectangle(1, 0.0, 1.0, {-1e4, 0.0, -1e4}, {1e4, 0.0, 1e4})};
    EXPECT_EQ(exact_obscurance(plane, {0.0, 0.0, 0.0}, kUp, no_falloff, 64), 0.0);
    // In the analytic scene, farther than the falloff's reach from the wall and the box.
    auto within_one_metre = [](double d) { return d < 1.0 ? 1.0 : 0.0; };
    EXPECT_EQ(exact_obscurance(obscura::samples::analytic_scene_primitives(), {4.0, 0.0, 6.0}, kUp, within_one_metre,
                               64),
              0.0);
}

TEST(AnalyticAo, FootOfALargeWallIsHalfOccluded) {
    // Every direction towards the wall hits it: half of the cosine-weighted hemisphere.
    const double obscurance = exact_obscurance(floor_and_wall(1e4), {0.0, 0.0, 1e-4}, kUp, no_falloff);
    EXPECT_NEAR(obscurance, 0.5, 1e-3);
}

TEST(AnalyticAo, WallAtADistanceMatchesTheClosedForm) {
    // Receiver on the floor at distance x from a tall, wide wall; rho = 1 closer than R, 0 beyond.
    // Directions with -w.z > a = x / R hit within R; projected onto the floor's unit disk they form a
    // circular segment of area acos(a) - a sqrt(1 - a^2), and cosine-weighted measure is area / pi.
    const double radius = 2.0;
    auto step = [radius](double d) { return d < radius ? 1.0 : 0.0; };
    for (double a : {0.1, 0.35, 0.6, 0.9}) {
        SCOPED_TRACE(a);
        const double expected = (std::acos(a) - a * std::sqrt(1.0 - a * a)) / kPi;
        const double obscurance = exact_obscurance(floor_and_wall(1e3), {0.3, 0.0, a * radius}, kUp, step);
        EXPECT_NEAR(obscurance, expected, 1e-3);  // measured: 1.5e-4 at most
    }
}

TEST(AnalyticAo, MatchesAnIndependentMonteCarloEstimate) {
    // Uniform hemisphere sampling (pdf 1 / 2 pi) instead of the cosine-weighted grid:
    // A = (1/pi) E[rho cos] * 2 pi. 200k samples: standard error about 1e-3.
    const std::vector<AnalyticPrimitive>& scene = obscura::samples::analytic_scene_primitives();
    auto linear = [](double d) { return std::fmax(0.0, 1.0 - d / 1.5); };
    struct Receiver {
        glm::dvec3 p, n;
    };
    const Receiver receivers[] = {
        {{0.2, 0.0, 0.8}, kUp},                       // floor in front of the box
        {{0.6, 0.0, 0.1}, kUp},                       // floor beside the box
        {{0.3, 0.25, -4.0}, {0.0, 0.0, 1.0}},         // the wall near the floor
        {{0.0, 0.3, 0.5}, {0.0, 0.0, 1.0}},           // the box's front face
    };
    std::mt19937_64 generator(20240611u);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (const Receiver& receiver : receivers) {
        SCOPED_TRACE(receiver.p.x + 10.0 * receiver.p.z);
        const glm::dvec3 n = receiver.n;
        const glm::dvec3 helper = std::fabs(n.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
        const glm::dvec3 t1 = glm::normalize(glm::cross(helper, n)), t2 = glm::cross(n, t1);
        constexpr int kSamples = 200000;
        double sum = 0.0;
        for (int i = 0; i < kSamples; ++i) {
            const double cos_theta = uniform(generator), phi = 2.0 * kPi * uniform(generator);
            const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
            const glm::dvec3 w = sin_theta * (std::cos(phi) * t1 + std::sin(phi) * t2) + cos_theta * n;
            double t = 0.0;
            if (cast_ray(scene, receiver.p + n * 1e-6, w, &t, nullptr)) sum += linear(t) * cos_theta;
        }
        const double monte_carlo = 2.0 * sum / kSamples;
        const double exact = exact_obscurance(scene, receiver.p, receiver.n, linear);
        EXPECT_GT(exact, 0.01);
        EXPECT_NEAR(exact, monte_carlo, 5e-3);
    }
}

TEST(AnalyticAo, QuadratureConvergesAndStaysInRange) {
    const std::vector<AnalyticPrimitive>& scene = obscura::samples::analytic_scene_primitives();
    auto linear = [](double d) { return std::fmax(0.0, 1.0 - d / 2.0); };
    // Measured: 0.27619 at 96, 0.27565 at 512 (and 1024).
    const double coarse = exact_obscurance(scene, {0.0, 0.0, 0.7}, kUp, linear, 96);
    const double fine = exact_obscurance(scene, {0.0, 0.0, 0.7}, kUp, linear, 512);
    EXPECT_NEAR(coarse, fine, 2e-3);
    EXPECT_GT(fine, 0.0);
    EXPECT_LT(fine, 0.5);
    // A non-unit normal is normalised; resolution below 1 is treated as 1.
    EXPECT_DOUBLE_EQ(exact_obscurance(scene, {0.0, 0.0, 0.7}, {0.0, 3.0, 0.0}, linear, 96), coarse);
    const double single = exact_obscurance(scene, {0.0, 0.0, 0.7}, kUp, linear, 0);
    EXPECT_GE(single, 0.0);
    EXPECT_LE(single, 1.0);
}

}  // namespace
