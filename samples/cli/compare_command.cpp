// obscura compare: renders each method and the ray-traced reference with the same falloff, measures
// the error (FFAO paper sec. 8: mean absolute error, fraction within 5 %; plus PSNR and the largest
// error) over the output rectangle, and with --orbit the flicker along a camera path.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "ao_render.h"
#include "cli_errors.h"
#include "commands.h"
#include "compare_output.h"
#include "headless_gl.h"
#include "obscura_session.h"
#include "reference_render.h"
#include "scene_library.h"
#include "scene_source.h"

namespace obscura::cli {
namespace {

constexpr int kDefaultReferenceRays = 256;

struct CompareConfig {
    std::vector<MethodSpec> methods;
    SceneSourceOptions scene;
    int reference_rays = kDefaultReferenceRays;
    std::filesystem::path out_dir = "compare-output";
    std::optional<std::string> json_path;
    std::optional<std::string> strip_path;
    std::optional<double> orbit_degrees;
    int frames = 1;
    bool sync_timing = false;
};

std::string default_method_list() {
    std::string list;
    for (obscura_method method : comparable_methods()) {
        list += std::string(list.empty() ? "" : ",") + obscura_method_name(method);
    }
    if (list.empty()) throw ApiError("this build of libobscura has no method to compare with the reference");
    return list;
}

CompareConfig take_compare_config(ArgumentList& arguments) {
    if (arguments.contains("--method")) throw UsageError("compare takes --methods SPEC,SPEC,... (not --method)");
    CompareConfig config;
    const std::optional<std::string> methods = arguments.take_value("--methods");
    const std::vector<std::string> sets = arguments.take_values("--set");
    config.methods = parse_method_specs("--methods", methods ? *methods : default_method_list(), sets);
    config.scene = take_scene_source_options(arguments, /*takes_size=*/true);
    if (auto rays = arguments.take_value("--reference-rays")) {
        config.reference_rays = parse_int("--reference-rays", *rays, 1, 65536);
    }
    if (auto dir = arguments.take_value("--out-dir")) config.out_dir = *dir;
    config.json_path = arguments.take_value("--json");
    config.strip_path = arguments.take_value("--strip");
    const std::optional<std::string> orbit = arguments.take_value("--orbit");
    const std::optional<std::string> frames = arguments.take_value("--frames");
    config.sync_timing = arguments.take_flag("--sync-timing");
    arguments.require_all_taken();
    if (orbit.has_value() != frames.has_value()) throw UsageError("--orbit DEG and --frames N go together");
    if (orbit) {
        if (config.scene.depth_file) throw UsageError("--orbit needs a scene (a depth file has one camera)");
        config.orbit_degrees = parse_double_in("--orbit", *orbit, -360.0, 360.0);
        config.frames = parse_int("--frames", *frames, 2, 1000);
    }
    return config;
}

// The cameras of the frames: the chosen one, or N along an orbit of `degrees` in total.
std::vector<samples::Camera> frame_cameras(const SceneSource& source, const CompareConfig& config) {
    std::vector<samples::Camera> cameras;
    for (int i = 0; i < config.frames; ++i) {
        const double fraction = config.frames > 1 ? double(i) / double(config.frames - 1) : 0.0;
        cameras.push_back(samples::orbit_camera(source.camera(), float(config.orbit_degrees.value_or(0.0) * fraction)));
    }
    return cameras;
}

// One reference render per distinct falloff; methods[i].reference says which.
void plan_references(CompareResult& result, const std::vector<MethodSpec>& methods) {
    for (const MethodSpec& spec : methods) {
        ComparedMethod method;
        method.spec = spec;
        const obscura_settings reference = reference_settings_for(spec.settings, result.reference_rays);
        method.reference = result.references.size();
        for (size_t k = 0; k < result.references.size(); ++k) {
            if (same_reference(result.references[k].settings, reference)) method.reference = k;
        }
        if (method.reference == result.references.size()) {
            ComparedReference added;
            added.settings = reference;
            added.description = describe_reference(reference);
            result.references.push_back(added);
        }
        result.methods.push_back(method);
    }
}

void render_references(const ObscuraSession& session, const std::vector<samples::RenderedScene>& frames,
                       bool use_normals, CompareResult& result) {
    for (size_t k = 0; k < result.references.size(); ++k) {
        ComparedReference& reference = result.references[k];
        const auto start = std::chrono::steady_clock::now();
        for (size_t f = 0; f < frames.size(); ++f) {
            std::string label = "reference " + reference.description;
            if (frames.size() > 1) label += ", frame " + std::to_string(f + 1) + "/" + std::to_string(frames.size());
            reference.frames.push_back(render_reference(session, frames[f].frame(), use_normals, reference.settings, label));
        }
        reference.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("reference %zu: %s, %d rays x %zu frame(s): %.1f s\n", k + 1, reference.description.c_str(),
                    result.reference_rays, frames.size(), reference.seconds);
    }
}

void measure_method(const ObscuraSession& session, const std::vector<samples::RenderedScene>& frames,
                    bool use_normals, const ComparedReference& reference, ComparedMethod& method) {
    const obscura_rect& rect = frames.front()->output_rect;
    const AoTarget target(rect.width, rect.height, GL_R32F);
    AoRenderRequest request;
    request.settings = &method.spec.settings;
    request.target = &target;
    request.use_normals = use_normals;
    for (size_t f = 0; f < frames.size(); ++f) {
        request.scene = &frames[f].frame();
        if (f == 0) {
            // Timed on the first camera; the target then holds its image.
            warm_up(session, request);
            const FramePlan plan = quick_frame_plan(method.spec.method());
            method.timing = time_frames(session, request, plan.warmup, plan.frames);
        } else {
            render_ao(session, request);
        }
        method.frames.push_back(target.read());
    }

    samples::ErrorMetrics& mean = method.metrics;
    mean = samples::ErrorMetrics{};
    mean.within_5pct = 0.0;
    const double weight = 1.0 / double(frames.size());
    for (size_t f = 0; f < frames.size(); ++f) {
        const samples::ErrorMetrics metrics = samples::compare_images(method.frames[f], reference.frames[f]);
        mean.mean_abs += weight * metrics.mean_abs;
        mean.within_5pct += weight * metrics.within_5pct;
        mean.over_threshold += weight * metrics.over_threshold;
        mean.psnr += weight * metrics.psnr;
        mean.max_abs += weight * metrics.max_abs;
        mean.pixels = metrics.pixels;
    }
    if (frames.size() > 1) method.flicker = samples::flicker(method.frames, reference.frames);
}

}  // namespace

int run_compare(ArgumentList& arguments) {
    const CompareConfig config = take_compare_config(arguments);
    const SceneSource source(config.scene);

    samples::HeadlessGL gl;
    std::printf("GL: %s\n", gl.describe().c_str());
    ObscuraSession session(timing_flags(gl, config.sync_timing));
    std::vector<samples::RenderedScene> frames;
    for (const samples::Camera& camera : frame_cameras(source, config)) frames.push_back(source.render(camera, source.size()));
    std::printf("scene: %s", source.describe(frames.front().frame()).c_str());
    if (config.orbit_degrees) std::printf(", orbit of %g degrees in %d frames", *config.orbit_degrees, config.frames);
    std::printf("\n");

    CompareResult result;
    result.device = gl.renderer();
    result.scene = source.name();
    result.width = frames.front()->output_rect.width;
    result.height = frames.front()->output_rect.height;
    result.reference_rays = config.reference_rays;
    result.frames = config.frames;
    result.orbit_degrees = config.orbit_degrees;
    // Resolved through the session first: obscura_reference_settings_for has no context to tell why it
    // refuses settings (an all-zero falloff table, say), and this call's log and last error do.
    for (const MethodSpec& spec : config.methods) {
        obscura_settings resolved{};
        session.check(obscura_resolve_settings(session.get(), &spec.settings, &resolved),
                      "obscura_resolve_settings(" + spec.text + ")");
    }
    plan_references(result, config.methods);
    render_references(session, frames, source.use_normals(), result);
    for (ComparedMethod& method : result.methods) {
        measure_method(session, frames, source.use_normals(), result.references[method.reference], method);
    }

    const bool sync = session.flags() & OBSCURA_CONTEXT_FLAG_SYNC_TIMING;
    std::printf("\nerrors against the reference over the %dx%d output rectangle%s; times: median of warm frames, "
                "gpu = SDK total (%s)\n",
                result.width, result.height, config.frames > 1 ? ", averaged over the frames" : "",
                sync ? "glFinish + CPU clock per pass" : "GL timer queries");
    print_compare_table(result);
    const std::vector<std::string> written = write_compare_images(result, config.out_dir);
    std::string names;
    for (const std::string& name : written) names += (names.empty() ? "" : ", ") + name;
    std::printf("wrote %s/: %s\n", config.out_dir.string().c_str(), names.c_str());
    if (config.strip_path) {
        samples::write_png(*config.strip_path, compare_strip(result));
        std::printf("wrote %s\n", config.strip_path->c_str());
    }
    if (config.json_path) {
        write_compare_json(result, *config.json_path);
        std::printf("wrote %s\n", config.json_path->c_str());
    }
    return 0;
}

}  // namespace obscura::cli
