// obscura render: one method on one scene (or depth file); writes the AO as PNG (and PFM for exact
// values), and optionally a JSON report with the effective settings and the times.
#include <cstdio>

#include "ao_render.h"
#include "cli_errors.h"
#include "commands.h"
#include "headless_gl.h"
#include "json_writer.h"
#include "method_spec.h"
#include "obscura_session.h"
#include "report.h"
#include "scene_source.h"

namespace obscura::cli {
namespace {

obscura_debug_view parse_debug_view(const std::string& name) {
    if (name == "none") return OBSCURA_DEBUG_NONE;
    if (name == "depth") return OBSCURA_DEBUG_LINEAR_DEPTH;
    if (name == "normals") return OBSCURA_DEBUG_NORMALS;
    if (name == "ao-before-blur") return OBSCURA_DEBUG_AO_BEFORE_BLUR;
    if (name == "tap-count") return OBSCURA_DEBUG_TAP_COUNT;
    throw UsageError("unknown --debug-view '" + name + "' (valid: none, depth, normals, ao-before-blur, tap-count)");
}

struct RenderConfig {
    MethodSpec method;
    SceneSourceOptions scene;
    obscura_debug_view debug_view = OBSCURA_DEBUG_NONE;
    bool sync_timing = false;
    bool gpu_code_paths = false;
    std::optional<std::string> png_path, pfm_path, json_path;
};

RenderConfig take_render_config(ArgumentList& arguments) {
    if (arguments.contains("--methods")) throw UsageError("render takes one --method SPEC (compare takes --methods)");
    RenderConfig config;
    const std::string method_text = arguments.take_value("--method").value_or("hbao");
    const std::vector<std::string> sets = arguments.take_values("--set");
    const std::vector<MethodSpec> methods = parse_method_specs("--method", method_text, sets);
    if (methods.size() != 1) throw UsageError("render takes one method (compare takes a list)");
    config.method = methods.front();
    config.scene = take_scene_source_options(arguments, /*takes_size=*/true);
    config.debug_view = parse_debug_view(arguments.take_value("--debug-view").value_or("none"));
    config.sync_timing = arguments.take_flag("--sync-timing");
    config.gpu_code_paths = arguments.take_flag("--gpu-code-paths");
    config.png_path = arguments.take_value("--out");
    config.pfm_path = arguments.take_value("--pfm");
    if (config.png_path) check_image_path("--out", *config.png_path, ImageFormat::Png, "--pfm");
    if (config.pfm_path) check_image_path("--pfm", *config.pfm_path, ImageFormat::Pfm, "--out");
    config.json_path = arguments.take_value("--json");
    arguments.require_all_taken();
    if (!config.png_path && !config.pfm_path && !config.json_path) {
        throw UsageError("render needs --out FILE.png (and/or --pfm FILE.pfm, --json FILE.json)");
    }
    std::vector<OutputFile> outputs;
    if (config.png_path) outputs.push_back({"--out", *config.png_path});
    if (config.pfm_path) outputs.push_back({"--pfm", *config.pfm_path});
    if (config.json_path) outputs.push_back({"--json", *config.json_path});
    check_output_files(outputs);
    return config;
}

void write_json(const std::string& path, const SceneSource& source, const samples::SceneFrame& frame,
                const MethodSpec& method, const TimingSummary& timing, obscura_context* context) {
    samples::JsonWriter json;
    json.begin_object();
    json.field("scene", source.name());
    json.field("width", frame.output_rect.width).field("height", frame.output_rect.height);
    json.field("method", method.text);
    write_settings_json(json, method.settings, context);
    write_gpu_ms_json(json, timing);
    json.field("wall_ms", timing.wall.median_ms);
    json.end_object().write_file(path);
}

}  // namespace

int run_render(ArgumentList& arguments) {
    const RenderConfig config = take_render_config(arguments);
    const SceneSource source(config.scene);

    samples::HeadlessGL gl;
    std::printf("GL: %s\n", gl.describe().c_str());
    ObscuraSession session(timing_flags(gl, config.sync_timing) | code_path_flags(config.gpu_code_paths));
    const samples::RenderedScene scene = source.render();
    std::printf("scene: %s\n", source.describe(scene.frame()).c_str());
    std::printf("method: %s\n", config.method.text.c_str());
    print_effective_settings(stdout, config.method.settings, session.get());

    // Normals need colour channels; every other view is one value per pixel, kept exact in R32F.
    const obscura_rect& rect = scene->output_rect;
    const AoTarget target(rect.width, rect.height, config.debug_view == OBSCURA_DEBUG_NORMALS ? GL_RGBA16F : GL_R32F);
    AoRenderRequest request;
    request.scene = &scene.frame();
    request.settings = &config.method.settings;
    request.target = &target;
    request.use_normals = source.use_normals();
    request.debug_view = config.debug_view;

    // The image is the last timed frame: every frame renders the same thing.
    warm_up(session, request);
    const FramePlan plan = quick_frame_plan(config.method.method());
    const TimingSummary timing = time_frames(session, request, plan.warmup, plan.frames);
    const samples::FloatImage image = target.read();
    if (config.png_path) {
        samples::write_png(*config.png_path, image);
        std::printf("wrote %s (%dx%d)\n", config.png_path->c_str(), image.width, image.height);
    }
    if (config.pfm_path) {
        samples::write_pfm(*config.pfm_path, image);
        std::printf("wrote %s\n", config.pfm_path->c_str());
    }

    const bool sync = session.flags() & OBSCURA_CONTEXT_FLAG_SYNC_TIMING;
    std::printf("time: median of %d warm frames: %.3f ms wall (render + glFinish), SDK total %.3f ms (%s)\n",
                plan.frames, timing.wall.median_ms, timing.sdk_total().median_ms,
                sync ? "glFinish + CPU clock per pass" : "GL timer queries");
    if (config.json_path) {
        write_json(*config.json_path, source, scene.frame(), config.method, timing, session.get());
        std::printf("wrote %s\n", config.json_path->c_str());
    }
    return 0;
}

}  // namespace obscura::cli
