// obscura compare: renders each method and its truths with the same falloff (the geometry truth, rays
// against the scene's triangles; the screen-space reference, REFERENCE through the depth buffer; or both),
// measures the error (FFAO paper sec. 8: mean absolute error, fraction within 5 %; plus the signed mean, PSNR
// and the largest error) over the geometry pixels of the output rectangle; with --frames the flicker along a camera
// path (--orbit) or through an animated scene, and with --converged each frame's many-sample image: the flicker of the
// sampling noise alone and, on an animated scene seen still, the temporal accumulation's ghosting.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
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
#include "truth_render.h"

#include <glm/gtc/type_ptr.hpp>

namespace obscura::cli {
namespace {

constexpr int kDefaultReferenceRays = 256;
constexpr int kDefaultConvergedFrames = 16;  // an animated scene's --converged

struct CompareConfig {
    std::vector<MethodSpec> methods;
    SceneSourceOptions scene;
    std::vector<TruthKind> truths;
    int reference_rays = kDefaultReferenceRays;
    int truth_rays = kDefaultTruthRays;
    uint32_t truth_seed = kDefaultTruthSeed;
    bool all_pixels = false;
    std::filesystem::path out_dir = "compare-output";
    std::optional<std::string> json_path;
    std::optional<std::string> strip_path;
    std::optional<double> orbit_degrees;
    int frames = 1;
    // Unset: what the scene asks for (resolve_scene_defaults): an animated scene hands its motion vectors over (the
    // moving object is what they are for) and renders the converged images of the ghosting measure.
    std::optional<bool> motion_vectors;  // rasterised and handed to the SDK
    std::optional<int> converged_frames;  // 0: no many-sample images
    bool sync_timing = false;
    bool gpu_code_paths = false;
    std::optional<PixelClasses> classes;  // --classes: radius and thickness
};

std::string default_method_list() {
    std::string list;
    for (obscura_method method : comparable_methods()) {
        list += std::string(list.empty() ? "" : ",") + obscura_method_name(method);
    }
    if (list.empty()) throw ApiError("this build of libobscura has no method to compare with the reference");
    return list;
}

// --classes [RADIUS_M[,THICKNESS_M]].
PixelClasses parse_classes(const std::string& text) {
    PixelClasses classes;
    if (text.empty()) return classes;
    const std::vector<std::string> values = split_list("--classes", text);
    if (values.size() > 2) throw UsageError("--classes '" + text + "' is not RADIUS_M[,THICKNESS_M] (e.g. 1,0.3)");
    classes.radius_m = parse_double_in("--classes (radius in metres)", values[0], 0.001, 1000.0);
    if (values.size() == 2) classes.thickness_m = parse_double_in("--classes (thickness in metres)", values[1], 0.0, 1000.0);
    return classes;
}

CompareConfig take_compare_config(ArgumentList& arguments) {
    if (arguments.contains("--method")) throw UsageError("compare takes --methods SPEC,SPEC,... (not --method)");
    CompareConfig config;
    // First: its value is optional, so it must see the argument after it before another option takes that.
    if (auto classes = arguments.take_optional_value("--classes")) config.classes = parse_classes(*classes);
    const std::optional<std::string> methods = arguments.take_value("--methods");
    std::vector<std::string> sets = arguments.take_values("--set");
    // --temporal on|off: every method's temporal accumulation (the setting `temporal.enabled`; a spec's own key wins).
    if (auto temporal = arguments.take_value("--temporal")) {
        if (*temporal != "on" && *temporal != "off") throw UsageError("--temporal takes on or off, not '" + *temporal + "'");
        // Both set every method's temporal.enabled: one of them would win silently.
        for (const std::string& set : sets) {
            if (set.compare(0, set.find('='), "temporal.enabled") == 0) {
                throw UsageError("--temporal " + *temporal + " and --set " + set +
                                 " both set temporal.enabled: give one");
            }
        }
        sets.insert(sets.begin(), "temporal.enabled=" + *temporal);
    }
    config.methods = parse_method_specs("--methods", methods ? *methods : default_method_list(), sets);
    config.scene = take_scene_source_options(arguments, /*takes_size=*/true);
    if (config.classes && !config.scene.depth_file && config.scene.raster.projection == samples::ProjectionKind::Orthographic) {
        throw UsageError("--classes needs a perspective projection (the radius's size on screen shrinks with depth); "
                         "--projection ortho has none");
    }
    const std::optional<std::string> reference_rays = arguments.take_value("--reference-rays");
    const std::optional<std::string> truth_rays = arguments.take_value("--truth-rays");
    const std::optional<std::string> truth_seed = arguments.take_value("--truth-seed");
    // A depth file has no triangles: its only truth is the screen-space reference.
    const std::string truth = arguments.take_value("--truth").value_or(config.scene.depth_file ? "screen" : "geometry");
    if (truth == "geometry") {
        config.truths = {TruthKind::Geometry};
    } else if (truth == "screen") {
        config.truths = {TruthKind::Screen};
    } else if (truth == "both") {
        config.truths = {TruthKind::Geometry, TruthKind::Screen};
    } else {
        throw UsageError("unknown --truth '" + truth + "' (valid: geometry, screen, both)");
    }
    if (config.scene.depth_file && config.truths.front() == TruthKind::Geometry) {
        throw UsageError("--truth " + truth + " needs a scene's triangles: a depth file has only the screen-space reference");
    }
    // Each truth's own options: given without that truth they would do nothing, so they are refused (as --converged
    // is without --frames).
    const auto compared = [&](TruthKind kind) {
        return std::find(config.truths.begin(), config.truths.end(), kind) != config.truths.end();
    };
    if (!compared(TruthKind::Geometry) && (truth_rays || truth_seed)) {
        throw UsageError(std::string(truth_rays ? "--truth-rays" : "--truth-seed") + " sets the geometry truth, which --truth " +
                         truth + " does not trace (give --truth geometry or both)");
    }
    if (!compared(TruthKind::Screen) && reference_rays) {
        throw UsageError("--reference-rays sets the screen-space reference, which --truth " + truth +
                         " does not render (give --truth screen or both)");
    }
    if (reference_rays) config.reference_rays = parse_int("--reference-rays", *reference_rays, 1, 65536);
    if (truth_rays) config.truth_rays = parse_int("--truth-rays", *truth_rays, 1, 65536);
    if (truth_seed) config.truth_seed = uint32_t(parse_int("--truth-seed", *truth_seed, 0, 1 << 30));
    const std::string pixels = arguments.take_value("--metrics-pixels").value_or("geometry");
    if (pixels != "geometry" && pixels != "all") {
        throw UsageError("unknown --metrics-pixels '" + pixels + "' (valid: geometry, all)");
    }
    config.all_pixels = pixels == "all";
    if (auto dir = arguments.take_value("--out-dir")) config.out_dir = *dir;
    config.json_path = arguments.take_value("--json");
    config.strip_path = arguments.take_value("--strip");
    if (config.strip_path) check_image_path("--strip", *config.strip_path, ImageFormat::Png);
    const std::optional<std::string> orbit = arguments.take_value("--orbit");
    const std::optional<std::string> frames = arguments.take_value("--frames");
    const std::optional<std::string> motion_vectors = arguments.take_value("--motion-vectors");
    const std::optional<std::string> converged = arguments.take_value("--converged");
    config.sync_timing = arguments.take_flag("--sync-timing");
    config.gpu_code_paths = arguments.take_flag("--gpu-code-paths");
    arguments.require_all_taken();
    if (orbit && !frames) throw UsageError("--orbit DEG needs --frames N (the frames along the orbit)");
    if (frames) {
        if (config.scene.depth_file) throw UsageError("--frames needs a scene (a depth file has one frame)");
        config.frames = parse_int("--frames", *frames, 2, 1000);
    }
    if (orbit) config.orbit_degrees = parse_double_in("--orbit", *orbit, -360.0, 360.0);
    if (motion_vectors && *motion_vectors != "on" && *motion_vectors != "off") {
        throw UsageError("--motion-vectors takes on or off, not '" + *motion_vectors + "'");
    }
    if (motion_vectors) {
        if (config.frames < 2) throw UsageError("--motion-vectors needs --frames N (a single frame has no motion)");
        config.motion_vectors = *motion_vectors == "on";
    }
    if (converged) {
        if (config.frames < 2) throw UsageError("--converged needs --frames N");
        config.converged_frames = *converged == "off" ? 0 : parse_int("--converged", *converged, 2, 64);
    }
    return config;
}

// Before any GL: a UsageError for what the scene's defaults do not go with.
void resolve_scene_defaults(CompareConfig& config, const SceneSource& source) {
    const bool animated = source.scene() && source.scene()->animated();
    if (!config.motion_vectors) config.motion_vectors = animated;
    if (!config.converged_frames) config.converged_frames = animated && config.frames > 1 ? kDefaultConvergedFrames : 0;
    // samples::render_scene rasterises motion vectors into a single-sample target only.
    if (*config.motion_vectors && config.frames > 1 && config.scene.raster.samples > 1) {
        throw UsageError("motion vectors (--motion-vectors on, the default on an animated scene) need a single-sample "
                         "depth buffer: drop --msaa " + std::to_string(config.scene.raster.samples) +
                         " or give --motion-vectors off");
    }
    // The geometry truth traces each pixel's centre, the SDK reads an MSAA depth buffer's sample 0, which lies off it:
    // at silhouettes the two can see different surfaces. Said, not refused: --msaa checks the SDK's MSAA input path.
    if (config.scene.raster.samples > 1 &&
        std::find(config.truths.begin(), config.truths.end(), TruthKind::Geometry) != config.truths.end()) {
        std::fprintf(stderr, "obscura: note: with --msaa %d the geometry truth traces pixel centres and the SDK reads "
                             "the depth's sample 0: silhouette pixels compare different points (not for error figures)\n",
                     config.scene.raster.samples);
    }
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

// One truth image per distinct falloff; methods[i].reference says which. Every truth shares the plan.
std::vector<obscura_settings> plan_falloffs(CompareResult& result, const std::vector<MethodSpec>& methods, int rays) {
    std::vector<obscura_settings> falloffs;
    for (const MethodSpec& spec : methods) {
        ComparedMethod method;
        method.spec = spec;
        const obscura_settings reference = reference_settings_for(spec.settings, rays);
        method.reference = falloffs.size();
        for (size_t k = 0; k < falloffs.size(); ++k) {
            if (same_reference(falloffs[k], reference)) method.reference = k;
        }
        if (method.reference == falloffs.size()) falloffs.push_back(reference);
        result.methods.push_back(method);
    }
    return falloffs;
}

void render_screen_references(const ObscuraSession& session, const std::vector<samples::RenderedScene>& frames,
                              bool use_normals, ComparedTruth& truth) {
    for (size_t k = 0; k < truth.references.size(); ++k) {
        ComparedReference& reference = truth.references[k];
        const auto start = std::chrono::steady_clock::now();
        for (size_t f = 0; f < frames.size(); ++f) {
            std::string label = "screen-space reference " + reference.description;
            if (frames.size() > 1) label += ", frame " + std::to_string(f + 1) + "/" + std::to_string(frames.size());
            reference.frames.push_back(render_reference(session, frames[f].frame(), use_normals, reference.settings, label));
        }
        reference.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        truth.seconds += reference.seconds;
        std::printf("screen-space reference %zu: %s, %d rays x %zu frame(s): %.1f s\n", k + 1,
                    reference.description.c_str(), truth.rays, frames.size(), reference.seconds);
    }
}

// The scene's ray-tracing structures: one, or one per frame of an animated scene.
class FrameTracers {
public:
    FrameTracers(const samples::Scene& scene, int frames) {
        for (int f = 0; f < (scene.animated() ? frames : 1); ++f) {
            tracers_.push_back(std::make_unique<TruthTracer>(scene.animated() ? scene.mesh_at(f) : scene.mesh));
        }
    }
    const TruthTracer& operator[](size_t frame) const { return *tracers_[std::min(frame, tracers_.size() - 1)]; }

private:
    std::vector<std::unique_ptr<TruthTracer>> tracers_;
};

void trace_geometry_truth(const FrameTracers& tracers, const std::vector<samples::RenderedScene>& frames,
                          ComparedTruth& truth, std::vector<std::vector<uint8_t>>& masks,
                          std::vector<samples::FloatImage>& view_depths,
                          std::vector<std::vector<uint32_t>>& primary_triangles) {
    // References that differ only in what the geometry truth ignores (the thickness: GTAO's horizon and bitmask
    // modes) are the same falloff here: weighed once, shared.
    std::vector<obscura_settings> falloffs;
    std::vector<size_t> falloff_of(truth.references.size());
    for (size_t k = 0; k < truth.references.size(); ++k) {
        falloff_of[k] = falloffs.size();
        for (size_t j = 0; j < falloffs.size(); ++j) {
            if (same_reference(falloffs[j], truth.references[k].settings)) falloff_of[k] = j;
        }
        if (falloff_of[k] == falloffs.size()) falloffs.push_back(truth.references[k].settings);
    }
    for (size_t f = 0; f < frames.size(); ++f) {
        std::string label = "geometry truth";
        if (frames.size() > 1) label += ", frame " + std::to_string(f + 1) + "/" + std::to_string(frames.size());
        TruthImages images = tracers[f].trace(frames[f].frame(), falloffs, truth.rays, truth.seed, label);
        for (size_t k = 0; k < truth.references.size(); ++k) {
            truth.references[k].frames.push_back(images.visibility[falloff_of[k]]);
            truth.references[k].bent_frames.push_back(images.bent_normal[falloff_of[k]]);
        }
        masks[f] = std::move(images.geometry_mask);
        view_depths[f] = std::move(images.view_depth);
        primary_triangles[f] = std::move(images.primary_triangles);
        truth.seconds += images.seconds;
        truth.rays_cast += images.rays_cast;
    }
    std::printf("geometry truth: %d triangles, %zu falloff(s), %d rays x %zu frame(s): %.1f s (%.2f Mrays/s)\n",
                truth.triangles, falloffs.size(), truth.rays, frames.size(), truth.seconds,
                truth.seconds > 0.0 ? double(truth.rays_cast) / truth.seconds * 1e-6 : 0.0);
}

// A method's error against one reference in each class, every frame's pixels pooled.
std::vector<ClassErrors> measure_classes(const ComparedMethod& method, const ComparedReference& reference,
                                         const PixelClasses& classes) {
    std::vector<ClassErrors> measured;
    for (samples::ThicknessClass value : kMeasuredClasses) {
        ClassErrors errors;
        double sum_abs = 0.0, sum_signed = 0.0, sum_within = 0.0;
        size_t signed_pixels = 0;  // mean_signed leaves non-finite pixels out: pooled over its own count
        for (size_t f = 0; f < classes.frames.size(); ++f) {
            std::vector<uint8_t> mask(classes.frames[f].size());
            for (size_t i = 0; i < mask.size(); ++i) mask[i] = classes.frames[f][i] == uint8_t(value);
            const samples::ErrorMetrics metrics = samples::compare_images(method.frames[f], reference.frames[f], &mask);
            errors.pixels += metrics.pixels;
            sum_abs += metrics.mean_abs * double(metrics.pixels);
            sum_signed += metrics.mean_signed * double(metrics.signed_pixels);
            signed_pixels += metrics.signed_pixels;
            sum_within += metrics.within_5pct * double(metrics.pixels);
        }
        if (errors.pixels > 0) {
            errors.mean_abs = sum_abs / double(errors.pixels);
            errors.mean_signed = signed_pixels > 0 ? sum_signed / double(signed_pixels) : 0.0;
            errors.within_5pct = sum_within / double(errors.pixels);
        }
        // Flicker within the class (pixels of the class in both frames of a pair): the rest class holds what
        // sampling noise does, apart from the moving edges whose error changes as they move. None such: unmeasured
        // (samples::flicker's 0 would read as perfectly steady).
        if (classes.frames.size() > 1) {
            std::vector<std::vector<uint8_t>> masks(classes.frames.size());
            for (size_t f = 0; f < classes.frames.size(); ++f) {
                masks[f].resize(classes.frames[f].size());
                for (size_t i = 0; i < masks[f].size(); ++i) masks[f][i] = classes.frames[f][i] == uint8_t(value);
            }
            size_t paired_pixels = 0;
            for (size_t f = 0; f + 1 < masks.size(); ++f) {
                for (size_t i = 0; i < masks[f].size(); ++i) paired_pixels += masks[f][i] && masks[f + 1][i];
            }
            if (paired_pixels == 0) {
                measured.push_back(errors);
                continue;
            }
            errors.flicker = samples::flicker(method.frames, reference.frames, &masks);
            if (!method.converged_frames.empty()) {
                errors.noise_flicker = samples::flicker(method.frames, method.converged_frames, &masks);
            }
        }
        measured.push_back(errors);
    }
    return measured;
}

// Each frame's many-sample image: the frame held still for `count` frames with the method's noise moving and every
// frame weighed alike (temporal accumulation over `count` frames, no clamp), in a view of its own. What the method
// converges to where nothing moves: the flicker against it is the sampling noise's alone, and the ghosting compares
// with it.
std::vector<samples::FloatImage> render_converged(const ObscuraSession& session,
                                                  const std::vector<samples::RenderedScene>& frames,
                                                  const AoRenderRequest& base, int count) {
    obscura_settings many = *base.settings;
    many.temporal.enabled = OBSCURA_TOGGLE_ON;
    many.temporal.max_frames = count;
    many.temporal.clamp = 64.0f;  // the largest: a clamp would hold the mean to one frame's neighbourhood
    const ObscuraView view(session);
    AoRenderRequest request = base;
    request.settings = &many;
    request.bent_target = nullptr;
    request.view = view.get();
    request.previous_scene = nullptr;
    request.use_motion_vectors = false;
    std::vector<samples::FloatImage> converged;
    for (const samples::RenderedScene& frame : frames) {
        request.scene = &frame.frame();
        for (int k = 0; k < count; ++k) {
            request.reset_history = k == 0;
            request.frame_index = uint32_t(k);
            render_ao(session, request);
        }
        converged.push_back(request.target->read());
    }
    return converged;
}

// The ghosting of an animated scene seen still: each pixel's frames since the moving object uncovered it, and since
// the method's converged image there last changed (or the object uncovered it), and the method's error by those ages.
GhostErrors measure_ghosting(const CompareResult& result, const ComparedMethod& method,
                             const ComparedReference& reference) {
    const std::vector<std::vector<uint8_t>>& uncovered = result.uncovered;
    std::vector<std::vector<uint8_t>> changed(uncovered.size());
    for (size_t f = 0; f < uncovered.size(); ++f) {
        changed[f] = uncovered[f];
        if (f == 0) continue;
        const std::vector<float>& now = method.converged_frames[f].pixels;
        const std::vector<float>& before = method.converged_frames[f - 1].pixels;
        for (size_t i = 0; i < changed[f].size(); ++i) {
            changed[f][i] |= uint8_t(std::fabs(double(now[i]) - double(before[i])) > kGhostChangedThreshold);
        }
    }
    GhostErrors ghosting;
    ghosting.curves.push_back(GhostCurve{"uncovered", samples::error_by_age(method.frames, method.converged_frames,
                                                                           reference.frames,
                                                                           samples::frames_since_event(uncovered, result.still_geometry),
                                                                           kGhostMaxAge)});
    ghosting.curves.push_back(GhostCurve{"changed", samples::error_by_age(method.frames, method.converged_frames,
                                                                         reference.frames,
                                                                         samples::frames_since_event(changed, result.still_geometry),
                                                                         kGhostMaxAge)});
    return ghosting;
}

// The ghosting of a moving camera: the method's error by the frames since each pixel's surface point came into view.
GhostErrors measure_orbit_ghosting(const CompareResult& result, const ComparedMethod& method,
                                   const ComparedReference& reference) {
    GhostErrors ghosting;
    ghosting.curves.push_back(GhostCurve{"disoccluded", samples::error_by_age(method.frames, method.converged_frames,
                                                                             reference.frames, result.disocclusion_ages,
                                                                             kGhostMaxAge)});
    return ghosting;
}

void measure_method(const ObscuraSession& session, const std::vector<samples::RenderedScene>& frames,
                    bool use_normals, const CompareResult& result, ComparedMethod& method) {
    const obscura_rect& rect = frames.front()->output_rect;
    const AoTarget target(rect.width, rect.height, GL_R32F);
    const bool bent = obscura_method_writes_bent_normals(method.spec.method()) != 0;
    const AoTarget bent_target(bent ? rect.width : 1, bent ? rect.height : 1, GL_RGBA32F);
    AoRenderRequest request;
    request.settings = &method.spec.settings;
    request.target = &target;
    request.bent_target = bent ? &bent_target : nullptr;
    request.use_normals = use_normals;
    for (size_t f = 0; f < frames.size(); ++f) {
        request.scene = &frames[f].frame();
        if (f == 0) {
            // Timed on the first camera; the target then holds its image.
            warm_up(session, request);
            const FramePlan plan = quick_frame_plan(method.spec.method());
            method.timing = time_frames(session, request, plan.warmup, plan.frames);
            // With temporal accumulation the sequence starts here: a history of its own, the first frame's noise.
            if (method.spec.settings.temporal.enabled == OBSCURA_TOGGLE_ON) {
                request.reset_history = true;
                render_ao(session, request);
                request.reset_history = false;
            }
        } else {
            // The frames follow each other: the previous camera for the reprojection and, when the frames
            // accumulate, the next noise pattern (without accumulation the pattern stays, as a host would keep it:
            // a pattern that moves every frame only adds flicker).
            request.previous_scene = &frames[f - 1].frame();
            request.frame_index = method.spec.settings.temporal.enabled == OBSCURA_TOGGLE_ON ? uint32_t(f) : 0u;
            render_ao(session, request);
        }
        method.frames.push_back(target.read());
        if (bent) {
            method.bent_frames.push_back(bent_target.read());
            // The surface normals the method used (the normals debug view, n * 0.5 + 0.5), decoded: what a host
            // without bent normals would shade with, the baseline of the bent normals' error.
            AoRenderRequest normals = request;
            normals.target = &bent_target;
            normals.bent_target = nullptr;
            normals.debug_view = OBSCURA_DEBUG_NORMALS;
            render_ao(session, normals);
            samples::FloatImage decoded = bent_target.read();
            for (float& value : decoded.pixels) value = value * 2.0f - 1.0f;
            method.normal_frames.push_back(std::move(decoded));
        }
    }
    if (result.converged_frames > 0) {
        method.converged_frames = render_converged(session, frames, request, result.converged_frames);
    }

    for (const ComparedTruth& truth : result.truths) {
        const ComparedReference& reference = truth.references[method.reference];
        MethodErrors errors;
        samples::ErrorMetrics& mean = errors.metrics;
        mean.within_5pct = 0.0;
        const double weight = 1.0 / double(frames.size());
        // Means over the frames, but the largest error is the largest of any frame, and the PSNR is that of the
        // frames' mean squared error (a mean of dB would make one error-free frame +infinity for the whole run).
        double mean_squared_error = 0.0;
        for (size_t f = 0; f < frames.size(); ++f) {
            const samples::ErrorMetrics metrics = samples::compare_images(
                method.frames[f], reference.frames[f], result.all_pixels ? nullptr : &result.masks[f]);
            mean.mean_abs += weight * metrics.mean_abs;
            mean.mean_signed += weight * metrics.mean_signed;
            mean.within_5pct += weight * metrics.within_5pct;
            mean.over_threshold += weight * metrics.over_threshold;
            mean_squared_error += weight * (std::isfinite(metrics.psnr) ? std::pow(10.0, -metrics.psnr / 10.0) : 0.0);
            mean.max_abs = std::max(mean.max_abs, metrics.max_abs);
            // The counts are the first frame's, as the table's header says (an orbit's frames see different pixels).
            if (f == 0) {
                mean.pixels = metrics.pixels;
                mean.pixels_total = metrics.pixels_total;
            }
        }
        mean.psnr = mean_squared_error > 0.0 ? 10.0 * std::log10(1.0 / mean_squared_error)
                                             : std::numeric_limits<double>::infinity();
        if (!method.bent_frames.empty() && !reference.bent_frames.empty()) {
            double degrees = 0.0;
            for (size_t f = 0; f < frames.size(); ++f) {
                degrees += weight * samples::mean_angle_degrees(method.bent_frames[f], reference.bent_frames[f],
                                                                result.all_pixels ? nullptr : &result.masks[f]);
            }
            errors.bent_degrees = degrees;
            double normal_degrees = 0.0;
            for (size_t f = 0; f < frames.size(); ++f) {
                normal_degrees += weight * samples::mean_angle_degrees(method.normal_frames[f], reference.bent_frames[f],
                                                                       result.all_pixels ? nullptr : &result.masks[f]);
            }
            errors.normal_degrees = normal_degrees;
        }
        if (frames.size() > 1) {
            errors.flicker =
                samples::flicker(method.frames, reference.frames, result.all_pixels ? nullptr : &result.masks);
            errors.last_mean_abs = samples::compare_images(method.frames.back(), reference.frames.back(),
                                                           result.all_pixels ? nullptr : &result.masks.back())
                                       .mean_abs;
        }
        if (!method.converged_frames.empty()) {
            errors.noise_flicker =
                samples::flicker(method.frames, method.converged_frames, result.all_pixels ? nullptr : &result.masks);
            errors.converged_mean_abs = 0.0;
            for (size_t f = 0; f < frames.size(); ++f) {
                *errors.converged_mean_abs += weight * samples::compare_images(method.converged_frames[f], reference.frames[f],
                                                                               result.all_pixels ? nullptr : &result.masks[f])
                                                           .mean_abs;
            }
        }
        if (!result.geometry.empty()) {
            errors.surface_flicker = samples::surface_flicker(method.frames, result.geometry);
            if (!method.converged_frames.empty()) {
                errors.converged_surface_flicker = samples::surface_flicker(method.converged_frames, result.geometry);
            }
        }
        if (!result.still_geometry.empty() && !method.converged_frames.empty()) {
            errors.ghosting = measure_ghosting(result, method, reference);
        } else if (!result.disocclusion_ages.empty() && !method.converged_frames.empty()) {
            errors.ghosting = measure_orbit_ghosting(result, method, reference);
        }
        if (result.classes) errors.classes = measure_classes(method, reference, *result.classes);
        method.errors.push_back(errors);
    }
}

// Classifies every frame's geometry pixels (samples::thickness_classes) from its view depth and mask, and counts
// the classes.
void split_into_classes(const std::vector<samples::RenderedScene>& frames,
                        const std::vector<samples::FloatImage>& view_depths, CompareResult& result) {
    PixelClasses& classes = *result.classes;
    for (size_t f = 0; f < frames.size(); ++f) {
        const samples::SceneFrame& frame = frames[f].frame();
        if (frame.orthographic) throw UsageError("--classes needs a perspective projection");
        // Pixels per metre at 1 m: half the image's height in pixels times the projection's y scale (P[1][1]).
        const double pixels_per_metre = 0.5 * double(frame.depth_height) * std::fabs(double(frame.projection[5]));
        classes.frames.push_back(samples::thickness_classes(view_depths[f], result.masks[f], classes.radius_m,
                                                            classes.thickness_m, pixels_per_metre,
                                                            classes.max_radius_px));
        for (uint8_t value : classes.frames.back()) {
            for (size_t c = 0; c < kMeasuredClassCount; ++c) classes.pixels[c] += value == uint8_t(kMeasuredClasses[c]);
            classes.geometry_pixels += value != uint8_t(samples::ThicknessClass::Sky);
        }
    }
}

// Per frame and pixel: whether the camera sees the still part of the scene there, and whether the moving part was
// there the frame before (it has just uncovered the pixel).
// Whether a primary ray's triangle belongs to an animated scene's moving part (Scene::first_moving_triangle on).
// Each pixel's surface normal in world space: the geometric normal of the triangle its primary ray hit (a zero vector
// on sky), so that surface_flicker can tell a crease's two faces apart.
std::vector<glm::vec3> primary_normals(const samples::SceneMesh& mesh, const std::vector<uint32_t>& triangles) {
    std::vector<glm::vec3> normals(triangles.size(), glm::vec3(0.0f));
    const auto vertex = [&](size_t v) {
        return glm::vec3(mesh.vertices[v * 6], mesh.vertices[v * 6 + 1], mesh.vertices[v * 6 + 2]);
    };
    for (size_t i = 0; i < triangles.size(); ++i) {
        const uint32_t t = triangles[i];
        if (t == samples::GeometryTruth::kSky || int64_t(t) >= int64_t(mesh.triangle_count())) continue;
        const glm::vec3 a = vertex(size_t(t) * 3), b = vertex(size_t(t) * 3 + 1), c = vertex(size_t(t) * 3 + 2);
        const glm::vec3 n = glm::cross(b - a, c - a);
        const float length = glm::length(n);
        if (length > 0.0f) normals[i] = n / length;
    }
    return normals;
}

bool on_moving_part(uint32_t triangle, int first_moving_triangle) {
    return triangle != samples::GeometryTruth::kSky && triangle >= uint32_t(first_moving_triangle);
}

void mark_still_geometry(const std::vector<std::vector<uint32_t>>& primary_triangles, int first_moving_triangle,
                         CompareResult& result) {
    const auto moving = [&](uint32_t triangle) { return on_moving_part(triangle, first_moving_triangle); };
    for (size_t f = 0; f < primary_triangles.size(); ++f) {
        const std::vector<uint32_t>& now = primary_triangles[f];
        std::vector<uint8_t> still(now.size()), uncovered(now.size(), 0);
        for (size_t i = 0; i < now.size(); ++i) {
            still[i] = uint8_t(now[i] != samples::GeometryTruth::kSky && !moving(now[i]));
            if (f > 0) uncovered[i] = uint8_t(still[i] && moving(primary_triangles[f - 1][i]));
        }
        result.still_geometry.push_back(std::move(still));
        result.uncovered.push_back(std::move(uncovered));
    }
}

// The outputs, checked before the truths are traced (minutes) rather than when they are written at the end. The
// directory first: --json and --strip may name files in it.
void check_outputs(const CompareConfig& config) {
    check_output_directory("--out-dir", config.out_dir.string());
    std::vector<OutputFile> files;
    if (config.json_path) files.push_back({"--json", *config.json_path});
    if (config.strip_path) files.push_back({"--strip", *config.strip_path});
    check_output_files(files);
}

}  // namespace

int run_compare(ArgumentList& arguments) {
    CompareConfig config = take_compare_config(arguments);
    const SceneSource source(config.scene);
    resolve_scene_defaults(config, source);
    check_outputs(config);

    samples::HeadlessGL gl;
    std::printf("GL: %s\n", gl.describe().c_str());
    ObscuraSession session(timing_flags(gl, config.sync_timing) | code_path_flags(config.gpu_code_paths));
    std::vector<samples::RenderedScene> frames;
    const std::vector<samples::Camera> cameras = frame_cameras(source, config);
    for (size_t f = 0; f < cameras.size(); ++f) {
        const samples::Camera* previous = f > 0 && *config.motion_vectors ? &cameras[f - 1] : nullptr;
        frames.push_back(source.render_frame(int(f), cameras[f], source.size(), previous));
    }
    const bool animated = source.scene() && source.scene()->animated();
    std::printf("scene: %s", source.describe(frames.front().frame()).c_str());
    if (config.orbit_degrees) {
        std::printf(", orbit of %g degrees in %d frames", *config.orbit_degrees, config.frames);
    } else if (config.frames > 1) {
        std::printf(", %d frames of a still camera", config.frames);
    }
    if (animated && config.frames > 1) std::printf(", the scene moving");
    if (*config.motion_vectors && config.frames > 1) std::printf(", motion vectors handed over");
    std::printf("\n");

    CompareResult result;
    result.device = gl.renderer();
    result.scene = source.name();
    result.width = frames.front()->output_rect.width;
    result.height = frames.front()->output_rect.height;
    result.frames = config.frames;
    result.orbit_degrees = config.orbit_degrees;
    result.motion_vectors = *config.motion_vectors && config.frames > 1;
    result.converged_frames = *config.converged_frames;
    result.all_pixels = config.all_pixels;
    // Resolved through the session first: obscura_reference_settings_for has no context to tell why it
    // refuses settings, and this call's log and last error do. (The spec parser already refused the settings
    // it could tell were wrong, an all-zero falloff table say, as usage errors.)
    for (const MethodSpec& spec : config.methods) {
        obscura_settings resolved{};
        session.check(obscura_resolve_settings(session.get(), &spec.settings, &resolved),
                      "obscura_resolve_settings(" + spec.text + ")");
    }
    const std::vector<obscura_settings> falloffs = plan_falloffs(result, config.methods, config.reference_rays);

    // The geometry pixels: where the camera sees the scene (the truth's primary rays, which the tests hold to
    // the rasteriser's pixels), or a depth file's non-sky texels.
    result.masks.resize(frames.size());
    std::vector<samples::FloatImage> view_depths(frames.size());  // with a scene: the primary hits'
    std::vector<std::vector<uint32_t>> primary_triangles(frames.size());  // with a scene
    std::optional<FrameTracers> tracer;
    if (const samples::Scene* scene = source.scene()) tracer.emplace(*scene, config.frames);
    for (TruthKind kind : config.truths) {
        ComparedTruth truth;
        truth.kind = kind;
        truth.rays = kind == TruthKind::Geometry ? config.truth_rays : config.reference_rays;
        for (const obscura_settings& falloff : falloffs) {
            ComparedReference reference;
            reference.settings = falloff;
            if (kind == TruthKind::Geometry) {
                // The geometry truth takes the falloff only: its own rays, and the scene's real thickness.
                reference.settings.reference.rays = truth.rays;
                reference.settings.reference.first_ray = 0;  // no screen-space rays: its own (--truth-seed)
                reference.settings.reference.thickness = 0.0f;
            }
            reference.description = describe_reference(reference.settings);
            truth.references.push_back(reference);
        }
        if (kind == TruthKind::Geometry) {
            truth.seed = config.truth_seed;
            truth.triangles = (*tracer)[0].triangle_count();
            trace_geometry_truth(*tracer, frames, truth, result.masks, view_depths, primary_triangles);
        } else {
            render_screen_references(session, frames, source.use_normals(), truth);
        }
        result.truths.push_back(std::move(truth));
    }
    for (size_t f = 0; f < frames.size(); ++f) {
        if (!result.masks[f].empty()) continue;
        if (tracer) {
            TruthImages primary = (*tracer)[f].trace(frames[f].frame(), falloffs, 0, config.truth_seed, "primary rays");
            result.masks[f] = std::move(primary.geometry_mask);
            view_depths[f] = std::move(primary.view_depth);
            primary_triangles[f] = std::move(primary.primary_triangles);
        } else {
            result.masks[f] = samples::read_geometry_mask(frames[f].frame());
            if (config.classes) view_depths[f] = samples::read_view_depth(frames[f].frame(), frames[f]->output_rect);
        }
    }
    for (size_t f = 0; f < frames.size() && !result.all_pixels; ++f) {
        if (std::count(result.masks[f].begin(), result.masks[f].end(), uint8_t(1)) == 0) {
            throw std::runtime_error("frame " + std::to_string(f + 1) + " shows no geometry (every pixel is sky): "
                                     "nothing to measure; aim the camera at the scene, or count every pixel with "
                                     "--metrics-pixels all");
        }
    }
    if (config.classes) {
        result.classes = config.classes;
        split_into_classes(frames, view_depths, result);
    }
    if (source.scene() && config.frames > 1) {
        for (size_t f = 0; f < frames.size(); ++f) {
            const samples::SceneFrame& frame = frames[f].frame();
            samples::FrameGeometry geometry;
            geometry.view_depth = view_depths[f];
            geometry.view = glm::dmat4(frame.view);
            geometry.projection = glm::dmat4(glm::make_mat4(frame.projection));
            geometry.depth_width = frame.depth_width;
            geometry.depth_height = frame.depth_height;
            geometry.rect_x = frame.output_rect.x;
            geometry.rect_y = frame.output_rect.y;
            if (primary_triangles[f].size() == size_t(geometry.view_depth.width) * size_t(geometry.view_depth.height)) {
                geometry.normal = primary_normals(animated ? source.scene()->mesh_at(int(f)) : source.scene()->mesh,
                                                  primary_triangles[f]);
            }
            if (animated && f > 0) {
                // The moving part's pixels (their primary rays' triangles), one frame's motion since the last.
                geometry.moving.resize(primary_triangles[f].size());
                for (size_t i = 0; i < geometry.moving.size(); ++i) {
                    geometry.moving[i] = on_moving_part(primary_triangles[f][i], source.scene()->first_moving_triangle());
                }
                geometry.motion = glm::dvec3(source.scene()->motion.velocity);
            }
            result.geometry.push_back(std::move(geometry));
        }
        for (const ComparedTruth& truth : result.truths) {
            result.truth_surface_flicker.push_back(samples::surface_flicker(truth.references.front().frames, result.geometry));
        }
    }
    // An orbit's ghosting follows the surface points (and the moving part) from frame to frame.
    if (config.orbit_degrees && !result.geometry.empty() && result.converged_frames > 0) {
        result.disocclusion_ages = samples::frames_since_disocclusion(result.geometry);
    }
    // The ghosting of the moving object needs the pixels to stay where they are: an animated scene, a still camera.
    if (animated && !config.orbit_degrees && config.frames > 1 && result.converged_frames > 0) {
        mark_still_geometry(primary_triangles, source.scene()->first_moving_triangle(), result);
    }
    for (ComparedMethod& method : result.methods) measure_method(session, frames, source.use_normals(), result, method);

    const bool sync = session.flags() & OBSCURA_CONTEXT_FLAG_SYNC_TIMING;
    std::printf("\ntimes: median of warm frames, gpu = SDK total (%s)\n",
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
        write_compare_json(result, *config.json_path, session.get());
        std::printf("wrote %s\n", config.json_path->c_str());
    }
    return 0;
}

}  // namespace obscura::cli
