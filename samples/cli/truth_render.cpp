#include "truth_render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace obscura::cli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TruthTracer::TruthTracer(const samples::Scene& scene) : TruthTracer(scene.mesh) {}

TruthTracer::TruthTracer(const samples::SceneMesh& mesh) {
    const auto start = std::chrono::steady_clock::now();
    scene_ = std::make_unique<samples::TruthScene>(mesh);
    build_seconds_ = seconds_since(start);
}

TruthImages TruthTracer::trace(const samples::SceneFrame& frame, const std::vector<obscura_settings>& falloffs,
                               int rays, uint32_t seed, const std::string& progress_label) const {
    const auto start = std::chrono::steady_clock::now();
    samples::GeometryTruthOptions options;
    options.seed = seed;
    samples::GeometryTruth truth(*scene_, samples::TruthView::of(frame), falloffs, options);
    while (truth.rays_traced() < rays) {
        truth.trace(std::min(kTruthBatchRays, rays - truth.rays_traced()));
        std::fprintf(stderr, "%s: %d/%d rays, %.1f s\n", progress_label.c_str(), truth.rays_traced(), rays,
                     seconds_since(start));
    }
    TruthImages images;
    for (size_t k = 0; k < falloffs.size(); ++k) {
        images.visibility.push_back(truth.visibility(k));
        images.bent_normal.push_back(truth.bent_normal(k));
    }
    images.geometry_mask = truth.geometry_mask();
    images.primary_triangles = truth.primary_triangles();
    images.view_depth = truth.view_depth();
    images.rays_cast = truth.rays_cast();
    images.seconds = seconds_since(start);
    return images;
}

}  // namespace obscura::cli
