// obscura render: renders the demo scene, computes AO for its visible rectangle and writes it as PNG
// (and PFM for exact values).
#include <chrono>
#include <cstdio>

#include "ao_render.h"
#include "cli_errors.h"
#include "commands.h"
#include "method_spec.h"
#include "obscura_session.h"
#include "scene_options.h"

namespace obscura::cli {
namespace {

obscura_debug_view parse_debug_view(const std::string& name) {
    if (name == "none") return OBSCURA_DEBUG_NONE;
    if (name == "depth") return OBSCURA_DEBUG_LINEAR_DEPTH;
    if (name == "normals") return OBSCURA_DEBUG_NORMALS;
    if (name == "ao-before-blur") return OBSCURA_DEBUG_AO_BEFORE_BLUR;
    throw UsageError("unknown --debug-view '" + name + "' (valid: none, depth, normals, ao-before-blur)");
}

// Frames timed after the first one, whose time includes allocating the per-size resources.
constexpr int kTimedFrames = 5;

}  // namespace

int run_render(ArgumentList& arguments) {
    const MethodSpec method = parse_method_spec(arguments.take_value("--method").value_or("hbao"));
    const ImageSize size = parse_size(arguments.take_value("--size").value_or("640x360"));
    samples::SceneRenderOptions scene_options = take_scene_options(arguments);
    scene_options.width = size.width;
    scene_options.height = size.height;
    const bool use_normals = arguments.take_flag("--normals");
    const bool sync_timing = arguments.take_flag("--sync-timing");
    const obscura_debug_view debug_view = parse_debug_view(arguments.take_value("--debug-view").value_or("none"));
    const std::optional<std::string> png_path = arguments.take_value("--out");
    const std::optional<std::string> pfm_path = arguments.take_value("--pfm");
    arguments.require_all_taken();
    if (!png_path && !pfm_path) throw UsageError("render needs --out FILE.png (and/or --pfm FILE.pfm)");

    samples::HeadlessGL gl;
    std::printf("GL: %s\n", gl.describe().c_str());
    ObscuraSession session(timing_flags(gl, sync_timing));
    samples::RenderedScene scene = samples::render_demo_scene(scene_options);
    std::printf("scene: %dx%d visible, %s\n", size.width, size.height, describe_scene(scene_options, scene.frame()).c_str());
    std::printf("method: %s\n", method.text.c_str());
    print_effective_settings(stdout, session, method.settings);

    // Normals need colour channels; every other view is one value per pixel, kept exact in R32F.
    const AoTarget target(size.width, size.height, debug_view == OBSCURA_DEBUG_NORMALS ? GL_RGBA16F : GL_R32F);
    AoRenderRequest request;
    request.scene = &scene.frame();
    request.settings = &method.settings;
    request.target = &target;
    request.use_normals = use_normals;
    request.debug_view = debug_view;

    const auto start = std::chrono::steady_clock::now();
    render_ao(session, request);
    glFinish();
    const double first_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    samples::FloatImage image = target.read();
    if (png_path) {
        samples::write_png(*png_path, image);
        std::printf("wrote %s (%dx%d)\n", png_path->c_str(), image.width, image.height);
    }
    if (pfm_path) {
        samples::write_pfm(*pfm_path, image);
        std::printf("wrote %s\n", pfm_path->c_str());
    }

    const TimingSummary timing = time_frames(session, request, 0, kTimedFrames);
    std::printf("time: first frame %.2f ms (allocation included); next %d frames median %.2f ms wall (render + glFinish)",
                first_ms, kTimedFrames, timing.wall.median_ms);
    for (const TimingRow& row : timing.passes) {
        if (row.label == "total") std::printf(", SDK total %.2f ms", row.median_ms);
    }
    std::printf("%s\n", session.flags() & OBSCURA_CONTEXT_FLAG_SYNC_TIMING ? " [sync timing]" : "");
    return 0;
}

}  // namespace obscura::cli
