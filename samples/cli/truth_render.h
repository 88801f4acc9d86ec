// The geometry truth of `compare` and `truth`: the scene's triangles ray-traced for a rasterised frame
// (samples/common/geometry_truth.h), every falloff asked for from one set of rays, traced in batches so that a
// progress line can be printed after each one.
#ifndef OBSCURA_CLI_TRUTH_RENDER_H
#define OBSCURA_CLI_TRUTH_RENDER_H

#include <memory>
#include <string>
#include <vector>

#include "demo_scene.h"
#include "geometry_truth.h"
#include "image_io.h"
#include "obscura/obscura.h"
#include "scene_library.h"

namespace obscura::cli {

constexpr int kTruthBatchRays = 32;
constexpr int kDefaultTruthRays = 1024;  // compare --truth-rays, truth --rays: within 0.002 of converged
constexpr uint32_t kDefaultTruthSeed = 1;

struct TruthImages {
    std::vector<samples::FloatImage> visibility;  // one per falloff
    std::vector<samples::FloatImage> bent_normal; // one per falloff: view-space unit bent normals (3 channels)
    std::vector<uint8_t> geometry_mask;           // 1 where the camera sees the scene
    std::vector<uint32_t> primary_triangles;      // the triangle each pixel sees, GeometryTruth::kSky on sky
    samples::FloatImage view_depth;               // of the primary hits, 0 on sky
    double seconds = 0.0;                         // the whole trace, primary rays included
    uint64_t rays_cast = 0;                       // hemisphere rays
};

class TruthTracer {
public:
    // Builds the scene's ray-tracing structure (Embree) once for every frame traced.
    explicit TruthTracer(const samples::Scene& scene);
    // The same for one mesh (an animated scene's in one frame: Scene::mesh_at).
    explicit TruthTracer(const samples::SceneMesh& mesh);

    int triangle_count() const { return scene_->triangle_count(); }
    double build_seconds() const { return build_seconds_; }

    // `rays` rays per pixel over the output rectangle of `frame` (0: the primary rays only: the mask and
    // depth), weighed with each of `falloffs` (any method's settings). After each batch prints
    // "<progress_label>: 96/256 rays, 12.4 s" on stderr. std::invalid_argument for refused settings.
    TruthImages trace(const samples::SceneFrame& frame, const std::vector<obscura_settings>& falloffs, int rays,
                      uint32_t seed, const std::string& progress_label) const;

private:
    std::unique_ptr<samples::TruthScene> scene_;
    double build_seconds_ = 0.0;
};

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_TRUTH_RENDER_H
