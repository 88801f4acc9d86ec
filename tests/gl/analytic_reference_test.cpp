// The ray-traced REFERENCE against the exact obscurance of the built-in "analytic" scene (floor, wall,
// box; samples/common/analytic_ao.h), computed on the CPU by quadrature over the true geometry.
//
// The scene is rasterised by the samples' renderer exactly as the CLI does (D32F, 10 % guard band), and
// the reference sees only that depth buffer. It can match the world-space value only where every
// occluder within the falloff radius is visible to the camera; analytic_ao.h lists those receivers, and
// each class is checked: floor in front of the wall, floor in front of the box's face, wall near the
// floor, and open floor (exact value 1). Criterion (issue: "matches the analytic scenes' exact AO within
// 1 %"): the mean absolute difference of each class is below 0.01 of visibility. Measured at 320x180,
// 512 rays, normals reconstructed from depth: 0.0010 (floor by the wall), 0.0024 (floor by the box),
// 0.0010 (wall by the floor), 0.0000 (open floor); the largest single texel is 0.026 off, at the box.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "analytic_ao.h"
#include "gl_test_support.h"
#include "scene_library.h"

namespace obscura_test {
namespace {

namespace layout = obscura::samples::analytic_layout;

constexpr int kWidth = 320;
constexpr int kHeight = 180;
constexpr double kRadius = 1.0;
constexpr double kC = 0.3;

// rho0 with radius 1 m and C = 0.3 (decay rate C * radius^2), evaluated as the SDK defines it
// (exact_obscurance hands the hits to obscura_evaluate_falloff).
obscura_settings rho0_settings() {
    obscura_settings settings{};
    settings.struct_size = sizeof settings;
    settings.method = OBSCURA_METHOD_REFERENCE;
    settings.reference.falloff = OBSCURA_FALLOFF_RHO0;
    settings.reference.radius = float(kRadius);
    settings.reference.falloff_c = float(kC);
    return settings;
}

struct Receiver {
    int index = 0;  // into the output image
    glm::dvec3 position{0.0}, normal{0.0};
};

// World-space hits of the output rectangle's texel centres, cast through the frame's own matrices.
std::vector<Receiver> cast_receivers(const obscura::samples::SceneFrame& frame) {
    const glm::dmat4 projection = glm::dmat4(glm::make_mat4(frame.projection));
    const glm::dmat4 inverse = glm::inverse(projection * glm::dmat4(frame.view));
    const auto& scene = obscura::samples::analytic_scene_primitives();
    std::vector<Receiver> receivers;
    for (int j = 0; j < frame.output_rect.height; ++j) {
        for (int i = 0; i < frame.output_rect.width; ++i) {
            const double nx = (frame.output_rect.x + i + 0.5) / frame.depth_width * 2.0 - 1.0;
            const double ny = (frame.output_rect.y + j + 0.5) / frame.depth_height * 2.0 - 1.0;
            glm::dvec4 near = inverse * glm::dvec4(nx, ny, -1.0, 1.0);
            glm::dvec4 far = inverse * glm::dvec4(nx, ny, 1.0, 1.0);
            const glm::dvec3 origin = glm::dvec3(near) / near.w;
            const glm::dvec3 direction = glm::dvec3(far) / far.w - origin;
            double t = 0.0;
            glm::dvec3 normal(0.0);
            if (!obscura::samples::cast_ray(scene, origin, direction, &t, &normal)) continue;
            receivers.push_back({j * frame.output_rect.width + i, origin + direction * t, normal});
        }
    }
    return receivers;
}

// Renders the analytic scene with `settings` (rho0, radius 1 m, C = 0.3) and checks each receiver class's mean
// |visibility - exact| against `limit`.
void expect_matches_exact(obscura_context* context, const obscura_settings& settings, double limit) {
    obscura::samples::Scene scene = obscura::samples::load_scene("analytic");
    obscura::samples::SceneRenderOptions options;
    options.width = kWidth;
    options.height = kHeight;
    options.camera = scene.viewpoints[0].camera;
    obscura::samples::RenderedScene rendered = obscura::samples::render_scene(scene.mesh, options);
    const obscura::samples::SceneFrame& frame = rendered.frame();

    std::vector<float> visibility =
        render_to_new_texture(context, frame.make_input(false), settings, GL_R32F, 1, OBSCURA_DEBUG_NONE);
    ASSERT_EQ(visibility.size(), size_t(kWidth) * kHeight);

    struct Class {
        const char* name;
        std::function<bool(const Receiver&)> member;
        std::vector<double> errors;
    };
    auto on_floor = [](const Receiver& r) { return r.normal.y > 0.99 && std::fabs(r.position.y) < 1e-6; };
    auto on_wall = [](const Receiver& r) { return r.normal.z > 0.99 && std::fabs(r.position.z - layout::kWallZ) < 1e-6; };
    auto inside_x = [](const Receiver& r, double lo, double hi) { return r.position.x > lo && r.position.x < hi; };
    std::vector<Class> classes = {
        {"floor in front of the wall",
         [&](const Receiver& r) {
             return on_floor(r) && r.position.z < layout::kWallZ + kRadius && inside_x(r, -3.0, 3.0);
         },
         {}},
        {"floor in front of the box",
         [&](const Receiver& r) {
             return on_floor(r) && r.position.z > layout::kBoxMaxZ && r.position.z < layout::kBoxMaxZ + kRadius &&
                    inside_x(r, layout::kBoxMinX + 0.05, layout::kBoxMaxX - 0.05);
         },
         {}},
        {"wall near the floor",
         [&](const Receiver& r) { return on_wall(r) && r.position.y < kRadius && inside_x(r, -3.0, 3.0); }, {}},
        {"open floor",
         [&](const Receiver& r) {
             return on_floor(r) && r.position.z > layout::kBoxMaxZ + kRadius + 0.05 && inside_x(r, -3.0, 3.0);
         },
         {}},
    };
    // Each class is sampled evenly down to about 60 receivers, which keeps the CPU quadrature short.
    const std::vector<Receiver> receivers = cast_receivers(frame);
    std::vector<std::vector<const Receiver*>> members(classes.size());
    for (const Receiver& receiver : receivers) {
        for (size_t k = 0; k < classes.size(); ++k) {
            if (!classes[k].member(receiver)) continue;
            members[k].push_back(&receiver);
            break;
        }
    }
    const auto& primitives = obscura::samples::analytic_scene_primitives();
    for (size_t k = 0; k < classes.size(); ++k) {
        const size_t stride = std::max<size_t>(1, members[k].size() / 60);
        for (size_t m = 0; m < members[k].size(); m += stride) {
            const Receiver& receiver = *members[k][m];
            const double exact =
                1.0 - obscura::samples::exact_obscurance(primitives, receiver.position, receiver.normal, rho0_settings(), 192);
            classes[k].errors.push_back(double(visibility[size_t(receiver.index)]) - exact);

        }
    }
    for (const Class& c : classes) {
        double mean_abs = 0.0, mean = 0.0, worst = 0.0;
        for (double e : c.errors) {
            mean_abs += std::fabs(e);
            mean += e;
            worst = std::max(worst, std::fabs(e));
        }
        const double n = double(c.errors.size());
        std::printf("%-6s %-28s %4zu receivers: mean |method - exact| %.4f, mean (method - exact) %+.4f, max %.4f\n",
                    obscura_method_name(settings.method), c.name, c.errors.size(), mean_abs / n, mean / n, worst);
        ASSERT_GT(c.errors.size(), 20u) << c.name;
        EXPECT_LT(mean_abs / n, limit) << obscura_method_name(settings.method) << ", " << c.name;
    }
}

class AnalyticReference : public GLTest {};

TEST_F(AnalyticReference, MatchesTheExactObscuranceWithinOnePercent) {
    obscura_settings settings{};
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_REFERENCE, &settings), OBSCURA_OK);
    settings.reference.radius = float(kRadius);
    settings.reference.falloff_c = float(kC);
    settings.reference.rays = 512;
    expect_matches_exact(ctx(), settings, 0.01);
}

// FFAO (issue: "analytic scenes within 2 % of their exact AO"), with the same falloff. Measured at 320x180,
// default K = 16x2, B0 = 10: see the printed table (docs/quality.md).
TEST_F(AnalyticReference, FfaoMatchesTheExactObscuranceWithinTwoPercent) {
    obscura_settings settings{};
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_FFAO, &settings), OBSCURA_OK);
    settings.ffao.falloff = OBSCURA_FALLOFF_RHO0;
    settings.ffao.radius = float(kRadius);
    settings.ffao.falloff_c = float(kC);
    settings.ffao.decay_rate = 0.0f;
    expect_matches_exact(ctx(), settings, 0.02);
}

}  // namespace
}  // namespace obscura_test
