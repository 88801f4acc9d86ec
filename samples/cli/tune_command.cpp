// obscura tune: searches a method's settings for the lowest error against the geometry truth on a set of scene
// views and captures (a depth buffer and its geometry truth, as `obscura truth --depth-out` writes them), under a
// time budget measured in the same run.
//
// The searched settings are the method's metadata rows (obscura_get_setting_infos): by default every number,
// enum and toggle that is neither derived nor only a scheduling or noise choice, and that leaves the falloff
// alone (radius, C, the falloff kind, GTAO's falloff_range: they define what the truth weighs occluders with, so
// changing them changes the target rather than the match); --keys names the ones to search instead. The
// objective is the mean over the scenes of mean_abs against the geometry truth weighed with the candidate's own
// falloff (obscura_reference_settings_for), over the geometry pixels; one truth is traced per distinct falloff
// and kept. A capture's truth is its file, traced with the start's falloff: on captures no key that changes the
// falloff is searched. The cost is the sum over the scenes of the SDK's total time (obscura_get_timings: GL timer queries,
// or glFinish + CPU clock per pass on software renderers, as bench measures), median of warm frames; with
// --budget RATIOx:SPEC a candidate whose cost exceeds RATIO times SPEC's cost on the same scenes is rejected, and
// the best is timed again against SPEC before it is reported. Settings of the best that leave its pictures bit for
// bit unchanged are put back to the start's. The search is samples/common/settings_search.h's seeded compass
// search over normalised coordinates, the search space tune_space.h's.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "ao_render.h"
#include "cli_errors.h"
#include "commands.h"
#include "demo_scene.h"
#include "depth_file.h"
#include "headless_gl.h"
#include "image_io.h"
#include "json_writer.h"
#include "method_spec.h"
#include "method_spec_parser.h"
#include "metrics.h"
#include "obscura_session.h"
#include "reference_render.h"
#include "report.h"
#include "scene_source.h"
#include "settings_document.h"
#include "settings_search.h"
#include "truth_render.h"
#include "tune_space.h"

namespace obscura::cli {
namespace {

constexpr int kDefaultEvaluations = 60;
constexpr int kDefaultTuneTruthRays = 256;  // within about 0.002 of converged (docs/quality.md)
constexpr ImageSize kDefaultTuneSize{320, 180};
// With a budget, the best candidates are timed again against the budget's configuration, alternately, this many
// times each, before one is reported: a software renderer's times move with the machine's load by more than the
// differences a budget decides on. The first of at most kVerifiedCandidates (lowest error first; then the start)
// whose median ratio stays within the budget is the result.
constexpr int kVerifyRounds = 3;
constexpr int kVerifiedCandidates = 4;
// A candidate replaces the best only when its mean_abs is lower by more than this: smaller differences are a few
// pixels' worth at small sizes, and taking them would fill the best spec with settings that do nothing.
constexpr double kMinImprovement = 1e-5;

struct SceneChoice {
    std::string name;
    std::optional<std::string> viewpoint;
    std::string label() const { return viewpoint ? name + "@" + *viewpoint : name; }
};

struct Budget {
    std::string text;  // "1.0x:hbao"
    double ratio = 1.0;
    MethodSpec spec;
};

// A studio's capture: its depth buffer (render --depth reads it with the config's depth options) and the geometry
// truth of the visible image, traced with the tuned method's falloff (obscura truth --falloff).
struct Capture {
    std::string depth_path;
    std::string truth_path;
};

struct TuneConfig {
    MethodSpec start;
    std::vector<SceneChoice> scenes;
    std::vector<Capture> captures;
    samples::DepthFileOptions capture_depth;  // the captures' depth options (each its own path)
    SceneSourceOptions scene;  // everything but the scene and its camera
    std::optional<Budget> budget;
    std::optional<std::vector<std::string>> keys;
    int evaluations = kDefaultEvaluations;
    int truth_rays = kDefaultTuneTruthRays;
    uint32_t seed = kDefaultTruthSeed;
    std::optional<std::string> json_path;
    bool sync_timing = false;
};

// "1.0x:hbao", "0.5x:gtao:preset=low": a positive ratio, 'x', ':', then a method spec.
Budget parse_budget(const std::string& text) {
    const size_t x = text.find("x:");
    if (x == std::string::npos || x == 0 || x + 2 >= text.size()) {
        throw UsageError("--budget: '" + text + "' is not RATIOx:SPEC (e.g. 1.0x:hbao, 0.5x:gtao:preset=low)");
    }
    Budget budget;
    budget.text = text;
    budget.ratio = parse_double("--budget (ratio)", text.substr(0, x));
    if (!(budget.ratio > 0.0)) throw UsageError("--budget: the ratio in '" + text + "' must be greater than 0");
    budget.spec = parse_method_spec(text.substr(x + 2));
    return budget;
}

SceneChoice parse_scene_choice(const std::string& text) {
    SceneChoice choice;
    const size_t at = text.rfind('@');
    choice.name = text.substr(0, at);
    if (at != std::string::npos) choice.viewpoint = text.substr(at + 1);
    if (choice.name.empty() || (choice.viewpoint && choice.viewpoint->empty())) {
        throw UsageError("--scenes: '" + text + "' is not NAME or NAME@VIEWPOINT");
    }
    return choice;
}

TuneConfig take_tune_config(ArgumentList& arguments) {
    if (arguments.contains("--methods")) {
        throw UsageError("tune takes one --method SPEC, its starting point (not --methods)");
    }
    if (arguments.contains("--scene")) throw UsageError("tune takes --scenes NAME[@VIEWPOINT],... (not --scene)");
    for (const char* option : {"--viewpoint", "--eye", "--target"}) {
        if (arguments.contains(option)) {
            throw UsageError(std::string(option) +
                             " does not apply to tune: give each view as --scenes NAME@VIEWPOINT");
        }
    }
    if (arguments.contains("--depth")) {
        throw UsageError("tune takes depth buffers as --captures DEPTH.pfm,... with --truths TRUTH.pfm,... (not --depth)");
    }
    TuneConfig config;
    const std::optional<std::string> method = arguments.take_value("--method");
    if (!method) throw UsageError("tune needs --method SPEC, the settings the search starts from");
    config.start = parse_method_spec(*method);
    normalise_start(&config.start.settings);
    // Each candidate is weighed by one frame per scene, rendered through one view: accumulation would carry one
    // scene's history into the next (the error then depended on the scenes' order) and add cost without its quality.
    if (config.start.settings.temporal.enabled == OBSCURA_TOGGLE_ON) {
        throw UsageError("--method " + *method + ": tune weighs one frame per scene; tune the method without "
                         "temporal.enabled (its presets with accumulation are measured by compare --frames N)");
    }
    const std::optional<std::string> scenes = arguments.take_value("--scenes");
    const std::optional<std::string> captures = arguments.take_value("--captures");
    const std::optional<std::string> truths = arguments.take_value("--truths");
    if (!scenes && !captures) {
        throw UsageError("tune needs --scenes NAME[@VIEWPOINT],... (e.g. --scenes atrium,objects) or --captures");
    }
    if (scenes && captures) throw UsageError("--scenes and --captures are alternatives: give one");
    if (scenes) {
        for (const std::string& text : split_list("--scenes", *scenes)) {
            const SceneChoice choice = parse_scene_choice(text);
            // A view given twice would weigh twice in the mean error and the cost, silently. NAME and NAME@default
            // are one view.
            const std::string viewpoint = choice.viewpoint.value_or("default");
            for (const SceneChoice& earlier : config.scenes) {
                if (earlier.name == choice.name && earlier.viewpoint.value_or("default") == viewpoint) {
                    throw UsageError("--scenes names the view " + choice.label() + " twice (as " + earlier.label() +
                                     " before)");
                }
            }
            config.scenes.push_back(choice);
        }
    }
    if (captures.has_value() != truths.has_value()) {
        throw UsageError("--captures DEPTH.pfm,... and --truths TRUTH.pfm,... go together (one truth per capture)");
    }
    const std::optional<std::string> size = arguments.take_value("--size");
    if (captures) {
        const std::vector<std::string> depths = split_list("--captures", *captures);
        const std::vector<std::string> truth_files = split_list("--truths", *truths);
        if (depths.size() != truth_files.size()) {
            throw UsageError("--captures names " + std::to_string(depths.size()) + " depth files and --truths " +
                             std::to_string(truth_files.size()) + " truths: one truth per capture");
        }
        for (size_t i = 0; i < depths.size(); ++i) {
            for (const Capture& earlier : config.captures) {
                if (earlier.depth_path == depths[i]) throw UsageError("--captures names " + depths[i] + " twice");
            }
            config.captures.push_back(Capture{depths[i], truth_files[i]});
        }
        // The depth options as render --depth takes them (--depth-kind, --near, --far, --reversed-z, --fovy,
        // --guard-band), one set for every capture.
        if (size) throw UsageError("--size does not apply to --captures (a capture's size is its file's)");
        for (const char* option : {"--projection", "--depth-format", "--msaa", "--no-clip-control", "--normals"}) {
            if (arguments.contains(option)) {
                throw UsageError(std::string(option) + " does not apply to --captures (they are depth files)");
            }
        }
        if (arguments.contains("--truth-rays")) {
            throw UsageError("--truth-rays does not apply to --captures (each truth is its file)");
        }
        std::vector<std::string> rest = arguments.take_rest();
        rest.insert(rest.end(), {"--depth", depths.front()});
        ArgumentList depth_arguments(std::move(rest));
        config.capture_depth = *take_scene_source_options(depth_arguments, /*takes_size=*/false).depth_file;
        arguments = ArgumentList(depth_arguments.take_rest());
    }
    config.scene = take_scene_source_options(arguments, /*takes_size=*/false,
                                             "is a depth option of --captures (tune renders --scenes' depth itself)");
    const ImageSize visible = size ? parse_size("--size", *size) : kDefaultTuneSize;
    config.scene.raster.width = visible.width;
    config.scene.raster.height = visible.height;
    if (auto budget = arguments.take_value("--budget")) config.budget = parse_budget(*budget);
    if (auto keys = arguments.take_value("--keys")) {
        config.keys = split_list("--keys", *keys);
        std::vector<std::string> sorted = *config.keys;
        std::sort(sorted.begin(), sorted.end());
        const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
        if (twice != sorted.end()) throw UsageError("--keys names '" + *twice + "' twice");
    }
    if (auto evaluations = arguments.take_value("--evaluations")) {
        config.evaluations = parse_int("--evaluations", *evaluations, 1, 100000);
    }
    if (auto rays = arguments.take_value("--truth-rays")) {
        config.truth_rays = parse_int("--truth-rays", *rays, 1, 65536);
    }
    if (auto seed = arguments.take_value("--seed")) config.seed = uint32_t(parse_int("--seed", *seed, 0, 1 << 30));
    config.json_path = arguments.take_value("--json");
    // Found before the search, not after it (the report is written at the end).
    if (config.json_path) check_output_files({{"--json", *config.json_path}});
    config.sync_timing = arguments.take_flag("--sync-timing");
    arguments.require_all_taken();
    return config;
}

// ---- Measuring ------------------------------------------------------------------------------------------

enum class Status { Measured, OverBudget, Refused };

// Whether two settings are the same configuration once resolved (derived values filled in): the same frames, so the
// same cost. A candidate that is the budget's own configuration costs the budget exactly: timed against itself it
// read 1.01-1.35x here on llvmpipe, and `--budget 1.0x:M` then refused the start it was measured from.
bool same_configuration(const obscura_settings& a, const obscura_settings& b) {
    obscura_settings resolved_a{}, resolved_b{};
    if (obscura_resolve_settings(nullptr, &a, &resolved_a) != OBSCURA_OK ||
        obscura_resolve_settings(nullptr, &b, &resolved_b) != OBSCURA_OK) {
        return false;
    }
    return std::memcmp(&resolved_a, &resolved_b, sizeof resolved_a) == 0;
}

const char* status_name(Status status) {
    switch (status) {
    case Status::Measured: return "measured";
    case Status::OverBudget: return "over_budget";
    case Status::Refused: return "refused";
    }
    return "";
}

struct Candidate {
    int index = 0;
    obscura_settings settings{};
    std::string spec;    // the whole spec (every setting that differs from the defaults)
    std::string change;  // the searched settings that differ from the start: "power=1.8 preset=ultra", or "start"
    Status status = Status::Refused;
    std::string reason;  // refused: why
    double error = std::numeric_limits<double>::quiet_NaN();  // mean over the scenes of mean_abs
    std::vector<double> scene_errors;
    double cost_ms = std::numeric_limits<double>::quiet_NaN();  // sum over the scenes
    std::vector<double> scene_cost_ms;
    std::string falloff;  // the truth's falloff, described
};

// One scene view or capture as the search measures it: its depth, its geometry pixels, the AO target; a scene's
// tracer, or a capture's truth.
struct TuneScene {
    SceneChoice choice;  // a capture: its depth file as the name
    std::unique_ptr<SceneSource> source;
    std::optional<samples::RenderedScene> rendered;
    std::unique_ptr<TruthTracer> tracer;
    std::optional<samples::FloatImage> capture_truth;
    std::string capture_truth_path;
    std::vector<uint8_t> mask;
    std::unique_ptr<AoTarget> target;
};

// The geometry truth of every scene for one falloff.
struct TruthSet {
    obscura_settings falloff{};
    std::string description;
    std::vector<samples::FloatImage> images;  // per scene
};

struct CostMeasurement {
    double total_ms = 0.0;
    std::vector<double> scene_ms;
    std::vector<samples::FloatImage> images;  // the last timed frame of each scene
};

// A candidate timed again against the budget's configuration (kVerifyRounds each, alternately).
struct Verification {
    size_t candidate = 0;    // the evaluation it re-measures (index)
    std::string spec;        // what it timed
    double cost_ms = 0.0;    // median of the rounds
    double budget_ms = 0.0;  // the budget's configuration, median of the rounds
    double ratio = 0.0;      // cost_ms / budget_ms
    bool within = false;     // ratio <= the budget's ratio
};

class Tuner {
public:
    Tuner(const TuneConfig& config, const ObscuraSession& session, std::vector<TuneScene>& scenes,
          const SearchSpace& space)
        : config_(config), session_(session), scenes_(scenes), space_(space) {}

    // Times `settings` on every scene (ApiError when the SDK refuses them).
    CostMeasurement measure_cost(const obscura_settings& settings) const {
        CostMeasurement cost;
        const FramePlan plan = quick_frame_plan(settings.method);
        for (TuneScene& scene : scenes_) {
            AoRenderRequest request;
            request.scene = &scene.rendered->frame();
            request.settings = &settings;
            request.target = scene.target.get();
            request.use_normals = scene.source->use_normals();
            warm_up(session_, request);
            const TimingSummary timing = time_frames(session_, request, plan.warmup, plan.frames);
            const TimingRow total = timing.sdk_total();
            const double ms = total.samples > 0 ? total.median_ms : timing.wall.median_ms;
            cost.scene_ms.push_back(ms);
            cost.total_ms += ms;
            cost.images.push_back(scene.target->read());
        }
        return cost;
    }

    // One untimed frame of `settings` on every scene (ApiError when the SDK refuses them).
    std::vector<samples::FloatImage> render_images(const obscura_settings& settings) const {
        std::vector<samples::FloatImage> images;
        for (TuneScene& scene : scenes_) {
            AoRenderRequest request;
            request.scene = &scene.rendered->frame();
            request.settings = &settings;
            request.target = scene.target.get();
            request.use_normals = scene.source->use_normals();
            render_ao(session_, request);
            images.push_back(scene.target->read());
        }
        return images;
    }

    // Times the candidate and the budget's configuration alternately, kVerifyRounds times each.
    Verification verify(const Candidate& candidate, const Budget& budget) const {
        if (same_configuration(candidate.settings, budget.spec.settings)) {
            Verification verification;
            verification.candidate = size_t(candidate.index);
            verification.spec = candidate.spec;
            verification.cost_ms = verification.budget_ms = budget_cost_ms_;
            verification.ratio = 1.0;
            verification.within = 1.0 <= budget.ratio;
            return verification;
        }
        std::vector<double> costs, budget_costs;
        for (int round = 0; round < kVerifyRounds; ++round) {
            budget_costs.push_back(measure_cost(budget.spec.settings).total_ms);
            costs.push_back(measure_cost(candidate.settings).total_ms);
        }
        Verification verification;
        verification.candidate = size_t(candidate.index);
        verification.spec = candidate.spec;
        verification.cost_ms = median(costs);
        verification.budget_ms = median(budget_costs);
        verification.ratio = verification.cost_ms / verification.budget_ms;
        verification.within = verification.ratio <= budget.ratio;
        return verification;
    }

    // The budget: its configuration's measured cost and the limit (its ratio times that cost).
    void set_budget(const Budget& budget, double cost_ms) {
        budget_ = &budget;
        budget_cost_ms_ = cost_ms;
        limit_ms_ = budget.ratio * cost_ms;
    }
    const std::vector<Candidate>& candidates() const { return candidates_; }
    const std::vector<TruthSet>& truths() const { return truths_; }
    double truth_seconds() const { return truth_seconds_; }

    // The objective of the search: builds, times and measures the candidate at `point`.
    samples::Evaluation evaluate(const std::vector<double>& point) {
        Candidate candidate;
        candidate.index = int(candidates_.size());
        candidate.settings = config_.start.settings;
        for (size_t k = 0; k < point.size(); ++k) {
            const TunedKey& key = space_.keys[k];
            if (point[k] == key.start_coordinate) continue;  // keeps the start's own value (0 "derive" too)
            const double value = key.value_at(point[k]);
            candidate.change += std::string(candidate.change.empty() ? "" : " ") + key.info.name + "=" +
                                spec_value_text(key.info, value);
            const obscura_status status = obscura_set_setting(&candidate.settings, key.info.name, value);
            if (status != OBSCURA_OK) {
                candidate.reason =
                    context_free_error(status, std::string("obscura_set_setting(") + key.info.name + ")");
            }
        }
        if (candidate.change.empty()) candidate.change = "start";
        candidate.spec = settings_spec(candidate.settings);
        constexpr double kInfinity = std::numeric_limits<double>::infinity();
        samples::Evaluation evaluation{kInfinity, kInfinity};  // refused: not evaluable
        if (candidate.reason.empty()) {
            obscura_settings resolved{};
            const obscura_status status = obscura_resolve_settings(nullptr, &candidate.settings, &resolved);
            if (status != OBSCURA_OK) candidate.reason = context_free_error(status, "obscura_resolve_settings");
        }
        if (candidate.reason.empty()) {
            try {
                evaluation = measure(candidate);
            } catch (const ApiError& error) {
                candidate.reason = error.what();
            }
        }
        if (!candidate.reason.empty()) candidate.status = Status::Refused;
        candidates_.push_back(std::move(candidate));
        return evaluation;
    }

    // "power=1.8: mean_abs 0.0312 (atrium 0.0402, objects 0.0222), 21.4 ms (0.47x budget)".
    std::string describe(const Candidate& candidate) const {
        std::string text = candidate.change + ": ";
        if (candidate.status == Status::Refused) return text + "refused: " + candidate.reason;
        char number[96];
        std::snprintf(number, sizeof number, "mean_abs %.4f", candidate.error);
        text += number;
        if (scenes_.size() > 1) {
            text += " (";
            for (size_t i = 0; i < scenes_.size(); ++i) {
                std::snprintf(number, sizeof number, "%s%s %.4f", i ? ", " : "", scenes_[i].choice.label().c_str(),
                              candidate.scene_errors[i]);
                text += number;
            }
            text += ")";
        }
        std::snprintf(number, sizeof number, ", %.2f ms", candidate.cost_ms);
        text += number;
        if (limit_ms_) {
            std::snprintf(number, sizeof number, " (%.2fx budget)", candidate.cost_ms / *limit_ms_);
            text += number;
        }
        if (candidate.status == Status::OverBudget) text += ": over budget, rejected";
        return text;
    }

private:
    samples::Evaluation measure(Candidate& candidate) {
        const CostMeasurement cost = measure_cost(candidate.settings);
        candidate.cost_ms = cost.total_ms;
        candidate.scene_cost_ms = cost.scene_ms;
        const TruthSet& truth = truth_for(candidate.settings);
        candidate.falloff = truth.description;
        candidate.error = 0.0;
        for (size_t i = 0; i < scenes_.size(); ++i) {
            const double error = samples::compare_images(cost.images[i], truth.images[i], &scenes_[i].mask).mean_abs;
            candidate.scene_errors.push_back(error);
            candidate.error += error / double(scenes_.size());
        }
        double violation = 0.0;
        candidate.status = Status::Measured;
        // The budget's own configuration costs the budget: its ratio is 1 by definition, not by this frame's timing.
        if (budget_ && same_configuration(candidate.settings, budget_->spec.settings)) candidate.cost_ms = budget_cost_ms_;
        if (limit_ms_ && candidate.cost_ms > *limit_ms_) {
            candidate.status = Status::OverBudget;
            violation = candidate.cost_ms / *limit_ms_ - 1.0;
        }
        return samples::Evaluation{candidate.error, violation};
    }

    // The truth weighed with the falloff of `settings`: traced the first time that falloff is asked for; a
    // capture's is its file, which holds the start's falloff only.
    const TruthSet& truth_for(const obscura_settings& settings) {
        const std::optional<obscura_settings> falloff = geometry_falloff(settings, config_.truth_rays);
        if (!falloff) {
            throw ApiError(context_free_error(OBSCURA_STATUS_INVALID_SETTING, "obscura_reference_settings_for"));
        }
        for (const TruthSet& truth : truths_) {
            if (same_reference(truth.falloff, *falloff)) return truth;
        }
        TruthSet truth;
        truth.falloff = *falloff;
        truth.description = describe_reference(*falloff);
        if (!config_.captures.empty()) {
            // (take_tune_config refuses the keys that change the falloff on captures.)
            if (!truths_.empty()) throw ApiError("a capture's truth holds the start's falloff only, not " + truth.description);
            for (TuneScene& scene : scenes_) truth.images.push_back(*scene.capture_truth);
            truths_.push_back(std::move(truth));
            return truths_.back();
        }
        const auto start = std::chrono::steady_clock::now();
        for (TuneScene& scene : scenes_) {
            const std::string label = "geometry truth " + std::to_string(truths_.size() + 1) + " (" +
                                      truth.description + "), " + scene.choice.label();
            TruthImages images =
                scene.tracer->trace(scene.rendered->frame(), {*falloff}, config_.truth_rays, config_.seed, label);
            truth.images.push_back(std::move(images.visibility.front()));
        }
        truth_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        truths_.push_back(std::move(truth));
        return truths_.back();
    }

    const TuneConfig& config_;
    const ObscuraSession& session_;
    std::vector<TuneScene>& scenes_;
    const SearchSpace& space_;
    std::optional<double> limit_ms_;
    const Budget* budget_ = nullptr;
    double budget_cost_ms_ = 0.0;
    std::vector<Candidate> candidates_;
    std::vector<TruthSet> truths_;
    double truth_seconds_ = 0.0;
};

// ---- Reports ----------------------------------------------------------------------------------------------

void write_candidate_json(samples::JsonWriter& json, const Candidate& candidate, std::optional<double> limit_ms) {
    json.field("index", candidate.index).field("spec", candidate.spec).field("change", candidate.change);
    json.field("status", status_name(candidate.status));
    if (candidate.status == Status::Refused) {
        json.field("reason", candidate.reason);
        return;
    }
    json.field("mean_abs", candidate.error);
    json.key("scene_mean_abs").begin_array();
    for (double error : candidate.scene_errors) json.value(error);
    json.end_array();
    json.field("cost_ms", candidate.cost_ms);
    json.key("scene_cost_ms").begin_array();
    for (double ms : candidate.scene_cost_ms) json.value(ms);
    json.end_array();
    if (limit_ms) {
        json.field("budget_ratio", candidate.cost_ms / *limit_ms);
    } else {
        json.key("budget_ratio").null();
    }
    json.field("falloff", candidate.falloff);
}

struct TuneReport {
    std::string device;
    bool sync_timing = false;
    const TuneConfig* config = nullptr;
    const std::vector<TuneScene>* scenes = nullptr;
    const SearchSpace* space = nullptr;
    std::optional<CostMeasurement> budget_cost;
    std::optional<double> limit_ms;
    const samples::SearchResult* search = nullptr;
    const Tuner* tuner = nullptr;
    std::vector<Verification> verifications;
    std::optional<size_t> best;       // the search's best, or with a budget the first candidate verified within it
    std::optional<Candidate> result;  // that candidate with the settings that do not change its picture put back
    std::vector<std::string> restored;  // those settings
    double seconds = 0.0;
};

void write_tune_json(const TuneReport& report, const std::string& path, obscura_context* context) {
    const TuneConfig& config = *report.config;
    const std::vector<Candidate>& candidates = report.tuner->candidates();
    samples::JsonWriter json;
    json.begin_object();
    json.field("device", report.device);
    json.field("timing", report.sync_timing ? "glFinish + CPU clock per pass" : "GL timer queries");
    json.field("method", config.start.text);
    // --size's: the scenes'. Captures have each their file's size (in "scenes"), and no common one.
    if (config.captures.empty()) json.field("width", config.scene.raster.width).field("height", config.scene.raster.height);
    json.key("scenes").begin_array();
    for (const TuneScene& scene : *report.scenes) {
        json.begin_object().field("name", scene.choice.name);
        if (scene.capture_truth) json.field("truth", scene.capture_truth_path);
        else json.field("viewpoint", scene.choice.viewpoint.value_or("default"));
        const obscura_rect& rect = scene.rendered->frame().output_rect;
        json.field("width", rect.width).field("height", rect.height);
        json.field("geometry_pixels", size_t(std::count(scene.mask.begin(), scene.mask.end(), uint8_t(1))));
        json.end_object();
    }
    json.end_array();
    json.key("truth").begin_object().field("rays", config.truth_rays).field("seed", config.seed);
    json.field("from_files", !config.captures.empty());
    json.field("falloffs", report.tuner->truths().size()).field("seconds", report.tuner->truth_seconds()).end_object();
    size_t counts[3] = {0, 0, 0};
    for (const Candidate& candidate : candidates) ++counts[int(candidate.status)];
    json.key("evaluations").begin_object().field("requested", config.evaluations).field("used", candidates.size());
    json.field("measured", counts[int(Status::Measured)]).field("over_budget", counts[int(Status::OverBudget)]);
    json.field("refused", counts[int(Status::Refused)]).end_object();
    json.key("search").begin_object().field("seed", config.seed).field("restarts", report.search->restarts);
    json.field("converged", report.search->converged).field("seconds", report.seconds).end_object();
    json.key("keys").begin_array();
    for (const TunedKey& key : report.space->keys) {
        json.begin_object().field("name", key.info.name).field("scale", key.scale_name());
        json.field("range", key.describe()).field("start", key.start_value);
        json.field("changes_falloff", key.changes_falloff).end_object();
    }
    json.end_array();
    json.key("left_out").begin_array();
    for (const auto& [name, why] : report.space->left_out) {
        json.begin_object().field("name", name).field("why", why).end_object();
    }
    json.end_array();
    if (config.budget && report.budget_cost && report.limit_ms) {
        json.key("budget").begin_object().field("text", config.budget->text).field("ratio", config.budget->ratio);
        json.field("spec", config.budget->spec.text).field("cost_ms", report.budget_cost->total_ms);
        json.key("scene_cost_ms").begin_array();
        for (double ms : report.budget_cost->scene_ms) json.value(ms);
        json.end_array();
        json.field("limit_ms", *report.limit_ms).end_object();
    } else {
        json.key("budget").null();
    }
    json.key("start").begin_object();
    write_candidate_json(json, candidates.front(), report.limit_ms);
    json.end_object();
    if (report.result) {
        const Candidate& best = *report.result;
        json.key("best").begin_object();
        write_candidate_json(json, best, report.limit_ms);
        json.key("restored").begin_array();
        for (const std::string& name : report.restored) json.value(name);
        json.end_array();
        write_settings_json(json, best.settings, context);
        json.field("c_code", viewer::settings_to_c(best.settings));
        json.end_object();
    } else {
        json.key("best").null();
    }
    json.key("verifications").begin_array();
    for (const Verification& verification : report.verifications) {
        json.begin_object().field("index", verification.candidate).field("spec", verification.spec);
        json.field("cost_ms", verification.cost_ms).field("budget_ms", verification.budget_ms);
        json.field("ratio", verification.ratio).field("within", verification.within).field("rounds", kVerifyRounds);
        json.end_object();
    }
    json.end_array();
    json.key("history").begin_array();
    for (const Candidate& candidate : candidates) {
        json.begin_object();
        write_candidate_json(json, candidate, report.limit_ms);
        json.end_object();
    }
    json.end_array();
    json.end_object().write_file(path);
}

std::string format_ms(double ms) { return format_fixed(ms, 2); }

void print_summary(const TuneReport& report) {
    const std::vector<Candidate>& candidates = report.tuner->candidates();
    const std::vector<TuneScene>& scenes = *report.scenes;
    size_t counts[3] = {0, 0, 0};
    for (const Candidate& candidate : candidates) ++counts[int(candidate.status)];
    char truths[96];
    if (report.config->captures.empty()) {
        std::snprintf(truths, sizeof truths, "%zu geometry truth(s) traced in %.1f s", report.tuner->truths().size(),
                      report.tuner->truth_seconds());
    } else {
        std::snprintf(truths, sizeof truths, "the captures' truths read from their files");
    }
    std::printf("\nevaluations: %zu of %d (%zu measured within the budget, %zu over it, %zu refused), %d restart(s), "
                "%s; %s; %.1f s in all\n",
                candidates.size(), report.config->evaluations, counts[int(Status::Measured)],
                counts[int(Status::OverBudget)], counts[int(Status::Refused)], report.search->restarts,
                report.search->converged ? "converged" : "stopped at the evaluation limit", truths, report.seconds);
    std::printf("times: the SDK's total summed over the scenes, median of warm frames (%s)\n\n",
                report.sync_timing ? "glFinish + CPU clock per pass" : "GL timer queries");

    std::vector<std::string> header = {"", "mean_abs"};
    for (const TuneScene& scene : scenes) header.push_back(scene.choice.label());
    header.push_back("cost ms");
    header.push_back("vs budget");
    TextTable table(header);
    const auto add = [&](const std::string& label, const Candidate& candidate) {
        std::vector<std::string> row = {label};
        if (candidate.status == Status::Refused) {
            row.push_back("refused");
            table.add_row(row);
            return;
        }
        row.push_back(format_fixed(candidate.error, 4));
        for (double error : candidate.scene_errors) row.push_back(format_fixed(error, 4));
        row.push_back(format_ms(candidate.cost_ms));
        row.push_back(report.limit_ms ? format_fixed(candidate.cost_ms / *report.limit_ms, 2) + "x" : "-");
        table.add_row(row);
    };
    add("start", candidates.front());
    if (report.result) add("best (#" + std::to_string(*report.best + 1) + ")", *report.result);
    table.print(stdout, "  ");
    if (!report.restored.empty()) {
        std::string names;
        for (const std::string& name : report.restored) names += (names.empty() ? "" : ", ") + name;
        std::printf("  (best: %s put back to the start's value: the picture is the same without the change)\n",
                    names.c_str());
    }
    if (report.limit_ms) {
        std::printf("budget: %s: %.2f ms (%s costs %.2f ms on these scenes)\n", report.config->budget->text.c_str(),
                    *report.limit_ms, report.config->budget->spec.text.c_str(), report.budget_cost->total_ms);
        for (const Verification& verification : report.verifications) {
            std::printf("  timed again (%s, #%zu, %d times alternately with %s): %.2f ms against %.2f ms, %.3fx: %s\n",
                        verification.spec.c_str(), verification.candidate + 1, kVerifyRounds,
                        report.config->budget->spec.text.c_str(),
                        verification.cost_ms, verification.budget_ms, verification.ratio,
                        verification.within ? "within the budget" : "over the budget, passed over");
        }
    } else {
        std::printf("budget: none (--budget RATIOx:SPEC sets one)\n");
    }
    if (!report.result) return;
    const Candidate& best = *report.result;
    std::printf("\nbest spec: %s\n", best.spec.c_str());
    std::printf("best settings in C (the fields that differ from the defaults):\n");
    std::string code = viewer::settings_to_c(best.settings);
    size_t start = 0;
    while (start < code.size()) {
        const size_t end = code.find('\n', start);
        std::printf("    %s\n", code.substr(start, end - start).c_str());
        start = end == std::string::npos ? code.size() : end + 1;
    }
}

// The searched settings of `settings` that differ from the start's: "preset=ultra power=1.8", or "start".
std::string change_text(const obscura_settings& settings, const obscura_settings& start, const SearchSpace& space) {
    std::string text;
    for (const TunedKey& key : space.keys) {
        if (samples::stored_value(settings, key.info) == samples::stored_value(start, key.info)) continue;
        double value = 0.0;
        obscura_get_setting(&settings, key.info.name, &value);
        text += (text.empty() ? "" : " ") + std::string(key.info.name) + "=" + spec_value_text(key.info, value);
    }
    return text.empty() ? "start" : text;
}

// `best` with each searched setting it changed put back to the start's value, one at a time, where that leaves
// every scene's picture bit for bit the same (GTAO's sectors in horizon mode, say: the search may take such a
// change on its way): the result then names only what matters. Its cost is measured again; with a budget it is
// also timed against the budget's configuration, and `best` itself stays the result when that puts it over.
Candidate without_idle_changes(const Tuner& tuner, const TuneConfig& config, const SearchSpace& space,
                               const Candidate& best, TuneReport& report) {
    Candidate result = best;
    std::vector<std::string> restored;
    const std::vector<samples::FloatImage> images = tuner.render_images(best.settings);
    for (const TunedKey& key : space.keys) {
        const double start_value = samples::stored_value(config.start.settings, key.info);
        if (samples::stored_value(result.settings, key.info) == start_value) continue;
        obscura_settings trial = result.settings;
        copy_setting(trial, config.start.settings, key.info);
        obscura_settings resolved{};
        if (obscura_resolve_settings(nullptr, &trial, &resolved) != OBSCURA_OK) continue;
        std::vector<samples::FloatImage> trial_images;
        try {
            trial_images = tuner.render_images(trial);
        } catch (const ApiError&) {
            continue;
        }
        bool same = trial_images.size() == images.size();
        for (size_t i = 0; same && i < images.size(); ++i) same = trial_images[i].pixels == images[i].pixels;
        if (!same) continue;
        result.settings = trial;
        restored.push_back(key.info.name);
    }
    if (restored.empty()) return best;
    result.spec = settings_spec(result.settings);
    result.change = change_text(result.settings, config.start.settings, space);
    if (config.budget) {
        const Verification verification = tuner.verify(result, *config.budget);
        report.verifications.push_back(verification);
        std::fprintf(stderr,
                     "tune: %s (#%zu without %zu setting(s) that do not change its picture) timed again: %.3fx%s\n",
                     result.spec.c_str(), size_t(best.index) + 1, restored.size(), verification.ratio,
                     verification.within ? "" : ": over the budget, kept as measured");
        if (!verification.within) return best;
    }
    const CostMeasurement cost = tuner.measure_cost(result.settings);
    result.cost_ms = cost.total_ms;
    result.scene_cost_ms = cost.scene_ms;
    report.restored = restored;
    return result;
}

}  // namespace

int run_tune(ArgumentList& arguments) {
    const TuneConfig config = take_tune_config(arguments);
    const SearchSpace space = make_search_space(config.start, config.keys);
    for (const TunedKey& key : space.keys) {
        if (key.changes_falloff && !config.captures.empty()) {
            throw UsageError(std::string("--keys ") + key.info.name + ": a capture's truth was traced with one falloff, "
                             "and " + key.info.name + " changes it");
        }
    }
    // The scenes' meshes and cameras before any GL: an unknown scene or viewpoint is a usage error.
    std::vector<std::unique_ptr<SceneSource>> sources;
    std::vector<SceneChoice> choices = config.scenes;
    for (const SceneChoice& choice : config.scenes) {
        SceneSourceOptions options = config.scene;
        options.scene = choice.name;
        options.viewpoint = choice.viewpoint;
        sources.push_back(std::make_unique<SceneSource>(options));
    }
    for (const Capture& capture : config.captures) {
        SceneSourceOptions options;
        options.depth_file = config.capture_depth;
        options.depth_file->path = capture.depth_path;
        sources.push_back(std::make_unique<SceneSource>(options));
        choices.push_back(SceneChoice{capture.depth_path, std::nullopt});
    }
    const auto begin = std::chrono::steady_clock::now();

    samples::HeadlessGL gl;
    std::printf("GL: %s\n", gl.describe().c_str());
    const ObscuraSession session(timing_flags(gl, config.sync_timing));
    const bool sync = session.flags() & OBSCURA_CONTEXT_FLAG_SYNC_TIMING;
    if (config.captures.empty()) {
        std::printf("tune %s: %d evaluations, geometry truth %d rays per pixel, seed %u\n", config.start.text.c_str(),
                    config.evaluations, config.truth_rays, config.seed);
    } else {
        std::printf("tune %s: %d evaluations, %zu captures, each against its truth file (traced with %s's falloff: "
                    "obscura truth --falloff)\n",
                    config.start.text.c_str(), config.evaluations, config.captures.size(), config.start.text.c_str());
    }
    // Declared after the GL context and the session: their textures go first.
    std::vector<TuneScene> scenes(sources.size());
    for (size_t i = 0; i < scenes.size(); ++i) {
        TuneScene& scene = scenes[i];
        scene.choice = choices[i];
        scene.source = std::move(sources[i]);
        scene.rendered.emplace(scene.source->render());
        const obscura_rect& rect = scene.rendered->frame().output_rect;
        scene.target = std::make_unique<AoTarget>(rect.width, rect.height, GL_R32F);
        if (i >= config.scenes.size()) {
            // A capture: the geometry pixels are the depth's non-sky texels; the truth is read at the visible size.
            const Capture& capture = config.captures[i - config.scenes.size()];
            scene.mask = samples::read_geometry_mask(scene.rendered->frame());
            scene.capture_truth = samples::read_pfm(capture.truth_path);
            scene.capture_truth_path = capture.truth_path;
            const samples::FloatImage& truth = *scene.capture_truth;
            if (truth.channels != 1 || truth.width != rect.width || truth.height != rect.height) {
                throw std::runtime_error(capture.truth_path + ": a " + std::to_string(truth.width) + "x" +
                                         std::to_string(truth.height) + "x" + std::to_string(truth.channels) +
                                         " image, not the 1-channel truth of " + capture.depth_path + "'s visible " +
                                         std::to_string(rect.width) + "x" + std::to_string(rect.height) +
                                         " (check --guard-band)");
            }
        } else {
            scene.tracer = std::make_unique<TruthTracer>(*scene.source->scene());
            // The geometry pixels, from the truth's primary rays (the same for every falloff).
            scene.mask = scene.tracer->trace(scene.rendered->frame(), {config.start.settings}, 0, config.seed,
                                             "primary rays").geometry_mask;
        }
        const size_t pixels = size_t(std::count(scene.mask.begin(), scene.mask.end(), uint8_t(1)));
        if (pixels == 0) {
            throw std::runtime_error("scene " + scene.choice.label() + " shows no geometry (every pixel is sky): "
                                     "nothing to measure");
        }
        std::printf("scene: %s; %.1f %% geometry pixels\n", scene.source->describe(scene.rendered->frame()).c_str(),
                    100.0 * double(pixels) / double(scene.mask.size()));
    }
    std::printf("searched (%zu):", space.keys.size());
    for (const TunedKey& key : space.keys) {
        std::printf("%s %s %s", &key == &space.keys.front() ? "" : ",", key.info.name, key.describe().c_str());
    }
    std::printf("\n");
    for (const TunedKey& key : space.keys) {
        if (key.changes_falloff) {
            std::printf("note: %s changes the falloff the truth weighs with: each value is measured against the "
                        "truth of its own falloff (the target moves with it)\n", key.info.name);
        }
    }
    if (!space.left_out.empty()) {
        std::map<std::string, std::string> by_reason;
        std::vector<std::string> reasons;
        for (const auto& [name, why] : space.left_out) {
            if (!by_reason.count(why)) reasons.push_back(why);
            by_reason[why] += (by_reason[why].empty() ? "" : ", ") + name;
        }
        std::printf("left out:");
        for (const std::string& why : reasons) {
            std::printf("%s %s (%s)", why == reasons.front() ? "" : ";", by_reason[why].c_str(), why.c_str());
        }
        std::printf("\n");
    }

    Tuner tuner(config, session, scenes, space);
    TuneReport report;
    report.device = gl.renderer();
    report.sync_timing = sync;
    report.config = &config;
    report.scenes = &scenes;
    report.space = &space;
    if (config.budget) {
        report.budget_cost = tuner.measure_cost(config.budget->spec.settings);
        report.limit_ms = config.budget->ratio * report.budget_cost->total_ms;
        tuner.set_budget(*config.budget, report.budget_cost->total_ms);
        std::string scene_costs;
        for (size_t i = 0; i < scenes.size(); ++i) {
            scene_costs +=
                (i ? ", " : "") + scenes[i].choice.label() + " " + format_ms(report.budget_cost->scene_ms[i]);
        }
        std::printf("budget: %s: %.2f ms (%s: %.2f ms: %s)\n", config.budget->text.c_str(), *report.limit_ms,
                    config.budget->spec.text.c_str(), report.budget_cost->total_ms, scene_costs.c_str());
    }
    std::fflush(stdout);

    std::vector<double> start;
    std::vector<samples::SearchParameter> parameters;
    for (const TunedKey& key : space.keys) {
        start.push_back(key.start_coordinate);
        parameters.push_back(key.parameter);
    }
    samples::SearchOptions options;
    options.max_evaluations = config.evaluations;
    options.initial_step = kTuneInitialStep;
    options.min_improvement = kMinImprovement;
    options.seed = config.seed;
    options.on_evaluation = [&](const samples::EvaluatedPoint& point) {
        const Candidate& candidate = tuner.candidates().at(size_t(point.index));
        const bool best = point.best && point.evaluation.feasible();
        std::fprintf(stderr, "tune %d/%d: %s%s\n", point.index + 1, config.evaluations,
                     tuner.describe(candidate).c_str(), best ? " (best so far)" : "");
    };
    const samples::SearchResult result = samples::pattern_search(
        parameters, start, [&](const std::vector<double>& point) { return tuner.evaluate(point); }, options);
    report.search = &result;
    report.tuner = &tuner;
    if (result.best.feasible() && !config.budget) report.best = size_t(result.best_index);
    if (result.best.feasible() && config.budget) {
        // The candidates within the budget, lowest error first (earlier first among equals), timed again.
        std::vector<size_t> order;
        for (const Candidate& candidate : tuner.candidates()) {
            if (candidate.status == Status::Measured) order.push_back(size_t(candidate.index));
        }
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
            return tuner.candidates()[a].error < tuner.candidates()[b].error;
        });
        // The search's best comes first: within min_improvement of a lower error it is the one it kept. A
        // candidate of the same error as one passed over has the same picture (a setting that does nothing
        // there), so the same cost: it is skipped. The start, when it was within the budget, is the last resort.
        order.erase(std::remove(order.begin(), order.end(), size_t(result.best_index)), order.end());
        order.insert(order.begin(), size_t(result.best_index));
        std::vector<double> passed_over;
        int tried = 0;
        const auto try_candidate = [&](size_t index) {
            const Candidate& candidate = tuner.candidates()[index];
            const Verification verification = tuner.verify(candidate, *config.budget);
            std::fprintf(stderr, "tune: timed #%zu again against %s: %.3fx%s\n", index + 1,
                         config.budget->spec.text.c_str(), verification.ratio,
                         verification.within ? "" : ": over the budget, passed over");
            report.verifications.push_back(verification);
            if (verification.within) report.best = index;
            passed_over.push_back(candidate.error);
            ++tried;
        };
        for (size_t index : order) {
            if (report.best || tried >= kVerifiedCandidates) break;
            const double error = tuner.candidates()[index].error;
            if (std::find(passed_over.begin(), passed_over.end(), error) == passed_over.end()) try_candidate(index);
        }
        if (!report.best && tuner.candidates().front().status == Status::Measured &&
            std::find(passed_over.begin(), passed_over.end(), tuner.candidates().front().error) == passed_over.end()) {
            try_candidate(0);
        }
    }
    // Never a result worse than the start: when the start is at most as far from the truth as the candidate kept (or
    // none was kept, nor found within the budget by the search), the start is timed again, whatever its status in
    // the search (a noisy timing may have put it over), and kept if it is within the budget.
    if (config.budget && !tuner.candidates().empty()) {
        const Candidate& first = tuner.candidates().front();
        const bool start_no_worse = first.status != Status::Refused &&
                                    (!report.best || first.error <= tuner.candidates()[*report.best].error);
        if (start_no_worse && report.best != size_t(0)) {
            const Verification verification = tuner.verify(first, *config.budget);
            std::fprintf(stderr, "tune: timed the start again against %s: %.3fx%s\n", config.budget->spec.text.c_str(),
                         verification.ratio, verification.within ? ": kept, no candidate improved on it" : "");
            report.verifications.push_back(verification);
            if (verification.within) report.best = size_t(0);
        }
    }
    if (report.best) {
        report.result = without_idle_changes(tuner, config, space, tuner.candidates()[*report.best], report);
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();

    print_summary(report);
    const bool found = report.result.has_value();
    if (found) {
        const Candidate& best = *report.result;
        if (!spec_reads_back(best.spec, best.settings)) {
            std::fprintf(stderr, "obscura tune: warning: the spec '%s' does not read back as the settings measured\n",
                         best.spec.c_str());
        }
    }
    if (config.json_path) {
        write_tune_json(report, *config.json_path, session.get());
        std::printf("wrote %s\n", config.json_path->c_str());
    }
    if (!found) {
        std::fprintf(stderr, "obscura tune: no candidate %s (see above)\n",
                     !result.best.feasible() ? (config.budget ? "was within the budget" : "could be measured")
                                             : "stayed within the budget when timed again");
        return 1;
    }
    return 0;
}

}  // namespace obscura::cli
