// obscura truth: the geometry truth of one scene view (rays against its triangles), written with the view's
// linear depth as a capture a studio can keep for CI: the depth as `--depth` reads it (positive view depth
// in metres, the whole depth buffer with its guard band, sky +inf) and the truth over the visible rectangle.
// `obscura render --depth DEPTH.pfm --guard-band G --fovy F --pfm AO.pfm` then `obscura diff AO.pfm TRUTH.pfm`
// measures a method against it without the scene.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "cli_errors.h"
#include "commands.h"
#include "headless_gl.h"
#include "method_spec.h"
#include "reference_render.h"
#include "scene_source.h"
#include "truth_render.h"

namespace obscura::cli {
namespace {

struct TruthConfig {
    SceneSourceOptions scene;
    MethodSpec falloff;
    int rays = kDefaultTruthRays;
    uint32_t seed = kDefaultTruthSeed;
    std::string out_path;
    std::optional<std::string> depth_path, png_path;
};

TruthConfig take_truth_config(ArgumentList& arguments) {
    TruthConfig config;
    const std::vector<MethodSpec> falloff =
        parse_method_specs("--falloff", arguments.take_value("--falloff").value_or("reference"), {});
    if (falloff.size() != 1) throw UsageError("--falloff takes one method spec, whose falloff the truth uses");
    config.falloff = falloff.front();
    if (auto rays = arguments.take_value("--rays")) config.rays = parse_int("--rays", *rays, 1, 65536);
    if (auto seed = arguments.take_value("--seed")) config.seed = uint32_t(parse_int("--seed", *seed, 0, 1 << 30));
    const std::optional<std::string> out = arguments.take_value("--out");
    config.depth_path = arguments.take_value("--depth-out");
    config.png_path = arguments.take_value("--png");
    if (arguments.contains("--depth")) throw UsageError("truth needs a scene's triangles (--scene), not a depth file");
    config.scene = take_scene_source_options(
        arguments, /*takes_size=*/true, "does not apply to truth (it traces a scene's triangles, not a depth file)");
    arguments.require_all_taken();
    if (!out) throw UsageError("truth needs --out TRUTH.pfm (and optionally --depth-out DEPTH.pfm, --png TRUTH.png)");
    if (config.depth_path) {
        // What --depth reads back: one perspective, single-sample depth buffer (any scene guard band is one it
        // accepts: both take [0, 1)).
        const samples::SceneRenderOptions& raster = config.scene.raster;
        if (raster.samples > 1) throw UsageError("--depth-out needs a single-sample depth buffer (no --msaa)");
        if (raster.projection == samples::ProjectionKind::Orthographic) {
            throw UsageError("--depth-out needs a perspective projection: --depth reads perspective captures only");
        }
    }
    config.out_path = check_image_path("--out", *out, ImageFormat::Pfm, "--png");
    if (config.png_path) check_image_path("--png", *config.png_path, ImageFormat::Png, "--out");
    if (config.depth_path) check_image_path("--depth-out", *config.depth_path, ImageFormat::Pfm);
    // Before the tracing, not after it: a capture is its files together (a truth without its depth is none).
    std::vector<OutputFile> outputs = {{"--out", config.out_path}};
    if (config.depth_path) outputs.push_back({"--depth-out", *config.depth_path});
    if (config.png_path) outputs.push_back({"--png", *config.png_path});
    check_output_files(outputs);
    return config;
}

}  // namespace

int run_truth(ArgumentList& arguments) {
    const TruthConfig config = take_truth_config(arguments);
    const SceneSource source(config.scene);
    samples::HeadlessGL gl;
    const samples::RenderedScene frame = source.render();
    std::printf("scene: %s\n", source.describe(frame.frame()).c_str());

    const TruthTracer tracer(*source.scene());
    obscura_settings reference = reference_settings_for(config.falloff.settings, 0);
    // The geometry truth takes the falloff only: the scene's real thickness, not the one a screen-space method
    // assumes (FFAO's 0.4 m was printed as the truth's), as compare and tune describe it.
    reference.reference.thickness = 0.0f;
    std::printf("geometry truth: %d triangles (built in %.2f s), %d rays per pixel, seed %u, falloff %s\n",
                tracer.triangle_count(), tracer.build_seconds(), config.rays, config.seed,
                describe_reference(reference).c_str());
    const TruthImages truth = tracer.trace(frame.frame(), {config.falloff.settings}, config.rays, config.seed,
                                           "geometry truth");
    std::printf("traced %llu rays in %.1f s (%.2f Mrays/s)\n", static_cast<unsigned long long>(truth.rays_cast),
                truth.seconds, double(truth.rays_cast) / truth.seconds * 1e-6);

    samples::write_pfm(config.out_path, truth.visibility.front());
    std::printf("wrote %s\n", config.out_path.c_str());
    if (config.png_path) {
        samples::write_png(*config.png_path, truth.visibility.front());
        std::printf("wrote %s\n", config.png_path->c_str());
    }
    if (config.depth_path) {
        const samples::SceneFrame& scene_frame = frame.frame();
        samples::write_pfm(*config.depth_path,
                           samples::read_view_depth(scene_frame, {0, 0, scene_frame.depth_width, scene_frame.depth_height}));
        std::printf("wrote %s: read it with --depth %s --guard-band %g --fovy %g\n", config.depth_path->c_str(),
                    config.depth_path->c_str(), double(source.guard_band()), double(source.camera().fov_y_degrees));
    }
    return 0;
}

}  // namespace obscura::cli
