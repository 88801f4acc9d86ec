#include "viewer_truth.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <utility>

namespace obscura::viewer {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A string that changes exactly when the falloff that `settings` weigh occluders with changes: the bytes of the
// falloff fields of the matching REFERENCE settings (kind, radius, C, decay rate, table).
std::string falloff_signature(const obscura_settings& settings) {
    obscura_settings reference{};
    if (obscura_reference_settings_for(&settings, &reference) != OBSCURA_STATUS_OK) return "refused";
    const obscura_reference_settings& r = reference.reference;
    std::string text;
    auto append = [&text](const void* bytes, size_t size) { text.append(static_cast<const char*>(bytes), size); };
    append(&r.falloff, sizeof r.falloff);
    append(&r.radius, sizeof r.radius);
    append(&r.falloff_c, sizeof r.falloff_c);
    append(&r.decay_rate, sizeof r.decay_rate);
    append(r.falloff_table, sizeof r.falloff_table);
    return text;
}

}  // namespace

std::string truth_view_key(const std::string& scene_name, int scene_generation, const samples::TruthView& view,
                           int rays, const obscura_settings& method_settings) {
    std::string key = scene_name + "#" + std::to_string(scene_generation) + "|";
    char number[48];
    auto add = [&](double value) {  // exact (%a): a small move far from the origin is another view
        std::snprintf(number, sizeof number, "%a,", value);
        key += number;
    };
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) add(view.view[c][r]);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) add(view.projection[c][r]);
    add(view.depth_width);
    add(view.depth_height);
    add(view.output_rect.x);
    add(view.output_rect.y);
    add(view.output_rect.width);
    add(view.output_rect.height);
    add(view.near_plane);
    add(view.far_plane);
    add(rays);
    return key + "|" + falloff_signature(method_settings);
}

void TruthJob::start(TruthRequest request, const samples::SceneMesh& mesh) {
    stop();
    // The worker is joined: bvh_ and bvh_scene_ are safe to read here.
    std::shared_ptr<const samples::SceneMesh> copy;
    if (!bvh_ || bvh_scene_ != request.scene_name) copy = std::make_shared<const samples::SceneMesh>(mesh);
    if (request.threads <= 0) request.threads = int(std::max(2u, std::thread::hardware_concurrency()) - 1u);
    request.rays = std::max(request.rays, 1);
    request.batch_rays = std::clamp(request.batch_rays, 1, request.rays);
    key_ = request.key;
    cancel_.store(false);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        snapshot_ = TruthSnapshot();
        progress_ = TruthProgress();
        progress_.active = true;
        progress_.rays_total = request.rays;
        progress_.phase = copy ? "building the BVH" : "primary rays";
        started_ = std::chrono::steady_clock::now();
        running_ = true;
    }
    worker_ = std::thread(&TruthJob::run, this, std::move(request), std::move(copy));
}

void TruthJob::cancel() {
    cancel_.store(true);
    key_.clear();
    std::lock_guard<std::mutex> lock(mutex_);
    snapshot_ = TruthSnapshot();
    if (progress_.active && !progress_.done && progress_.error.empty()) progress_.phase = "cancelled";
    progress_.active = false;
}

void TruthJob::stop() {
    cancel();
    if (worker_.joinable()) worker_.join();
}

void TruthJob::wait() {
    if (worker_.joinable()) worker_.join();
}

bool TruthJob::busy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return running_;
}

TruthProgress TruthJob::progress() const {
    std::lock_guard<std::mutex> lock(mutex_);
    TruthProgress out = progress_;
    if (running_ && out.active) out.seconds = seconds_since(started_);
    return out;
}

bool TruthJob::latest(uint64_t generation, TruthSnapshot* out) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (snapshot_.generation == 0 || snapshot_.generation == generation) return false;
    *out = snapshot_;
    return true;
}

void TruthJob::run(TruthRequest request, std::shared_ptr<const samples::SceneMesh> mesh) {
    const auto start = std::chrono::steady_clock::now();
    auto set_phase = [&](const char* phase) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!cancel_.load()) progress_.phase = phase;
    };
    auto finish = [&](const char* phase, const std::string& error) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!cancel_.load()) {
            progress_.phase = phase;
            progress_.error = error;
            progress_.seconds = seconds_since(start);
        }
        running_ = false;
    };
    try {
        if (mesh) {
            bvh_.reset();
            bvh_scene_.clear();
            bvh_ = std::make_unique<samples::TruthScene>(*mesh);
            bvh_scene_ = request.scene_name;
            mesh.reset();
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            progress_.triangles = bvh_->triangle_count();
        }
        if (cancel_.load()) return finish("cancelled", "");
        set_phase("primary rays");
        samples::GeometryTruthOptions options;
        options.seed = request.seed;
        options.threads = request.threads;
        options.cancel = &cancel_;  // a restart need not wait for the primary rays
        samples::GeometryTruth truth(*bvh_, request.view, {request.falloff}, options);
        if (truth.cancelled()) return finish("cancelled", "");
        const auto mask = std::make_shared<const std::vector<uint8_t>>(truth.geometry_mask());
        set_phase("tracing");
        while (truth.rays_traced() < request.rays) {
            if (!truth.trace(std::min(request.batch_rays, request.rays - truth.rays_traced()), &cancel_)) {
                return finish("cancelled", "");
            }
            samples::FloatImage visibility = truth.visibility(0);  // a copy: the worker keeps tracing into truth
            std::lock_guard<std::mutex> lock(mutex_);
            if (cancel_.load()) break;
            snapshot_.key = request.key;
            snapshot_.generation = ++generation_;
            snapshot_.visibility = std::move(visibility);
            snapshot_.mask = mask;
            snapshot_.geometry_pixels = truth.geometry_pixels();
            snapshot_.rays = truth.rays_traced();
            snapshot_.rays_total = request.rays;
            progress_.rays_done = truth.rays_traced();
            progress_.done = truth.rays_traced() >= request.rays;
        }
        finish(cancel_.load() ? "cancelled" : "done", "");
    } catch (const std::exception& error) {
        finish("failed", error.what());
    }
}

}  // namespace obscura::viewer
