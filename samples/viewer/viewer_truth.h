// TruthJob: the viewer's geometry truth (samples/common/geometry_truth.h: ambient visibility ray-traced against
// the scene's triangles on the CPU with Embree), traced progressively on a worker thread.
//
// THREADING. One worker std::thread at a time. The GL thread starts a job with a copy of everything the worker
// needs (the frame's TruthView is plain CPU data, the mesh is copied when the cached BVH is of another scene),
// so the worker never touches GL or the app's state. The worker alone owns the TruthScene (the BVH, kept across
// jobs of one scene) and the GeometryTruth; after each batch it publishes a copy of the running estimate into a
// mutex-protected snapshot and bumps a generation counter. The GL thread only polls: a snapshot newer than the
// one it uploaded is copied out (latest()) and uploaded into a texture. cancel() sets the flag that
// GeometryTruth::trace() polls at row boundaries (non-blocking); stop() cancels and joins; start() stops the
// previous job first, and the destructor stops, so closing the window joins the worker cleanly.
#ifndef OBSCURA_VIEWER_TRUTH_H
#define OBSCURA_VIEWER_TRUTH_H

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <obscura/obscura.h>

#include "geometry_truth.h"
#include "image_io.h"
#include "scene_library.h"

namespace obscura::viewer {

// What one job traces: everything is copied, the worker keeps no reference into the caller.
struct TruthRequest {
    std::string key;              // what the estimate belongs to (the caller compares it with its current view)
    std::string scene_name;       // the BVH is rebuilt when this changes
    samples::TruthView view;      // TruthView::of(frame): plain CPU data
    obscura_settings falloff{};   // the method's settings: its falloff weighs the hits
    int rays = 256;               // rays per pixel in all
    int batch_rays = 8;           // rays per pixel per published batch
    int threads = 0;              // tracing threads of the worker; 0: every hardware thread but one
    uint32_t seed = 1;
};

// The worker's progress, a cheap copy for the panel.
struct TruthProgress {
    bool active = false;          // a job was started (and not cancelled)
    bool done = false;            // every ray traced
    std::string phase;            // "building the BVH", "primary rays", "tracing", "done", "failed", "cancelled"
    int rays_done = 0;
    int rays_total = 0;
    double seconds = 0.0;         // since the job started (frozen when it ends)
    int triangles = 0;
    std::string error;            // why it failed (then done is false)
};

// One published estimate.
struct TruthSnapshot {
    std::string key;
    uint64_t generation = 0;      // increases with every publication, across jobs
    samples::FloatImage visibility;                      // rows bottom-up, 1 on sky
    std::shared_ptr<const std::vector<uint8_t>> mask;    // GeometryTruth::geometry_mask(): 1 where a triangle was hit
    size_t geometry_pixels = 0;
    int rays = 0;                 // rays per pixel in this estimate
    int rays_total = 0;
};

// The key of the geometry truth of `view` (TruthRequest::key): the scene opened (its name and `scene_generation`, which
// counts the scenes opened, so that an OBJ reopened after an edit on disk is another scene), the view's exact
// matrices, sizes and planes, the rays, and the falloff `method_settings` weigh occluders with (the falloff fields of
// obscura_reference_settings_for, as the CLI tells falloffs apart; not the rays or the thickness: the truth has its
// own rays and the scene's real thickness). Changes exactly when the truth must be traced again.
std::string truth_view_key(const std::string& scene_name, int scene_generation, const samples::TruthView& view,
                           int rays, const obscura_settings& method_settings);

class TruthJob {
public:
    TruthJob() = default;
    ~TruthJob() { stop(); }
    TruthJob(const TruthJob&) = delete;
    TruthJob& operator=(const TruthJob&) = delete;

    // Stops the running job (cancel + join) and starts `request` for `mesh` (copied when the cached BVH is of
    // another scene; the caller's mesh may then change or go away).
    void start(TruthRequest request, const samples::SceneMesh& mesh);
    // Asks the worker to stop at the next row (returns at once); the estimate published so far is dropped.
    void cancel();
    // cancel() and join: no worker runs afterwards.
    void stop();
    // Waits until the worker ends by itself (its job complete or failed) and joins it. For the screenshot mode.
    void wait();

    // Whether a worker is still running (a cancelled one until it has returned): starting a job then would
    // wait for it in join().
    bool busy() const;
    // The key of the job last started (empty after cancel()/stop() or before any start).
    const std::string& key() const { return key_; }
    TruthProgress progress() const;
    // Copies the latest published estimate into *out when its generation differs from `generation`; false
    // when there is nothing newer (or nothing yet).
    bool latest(uint64_t generation, TruthSnapshot* out) const;

private:
    void run(TruthRequest request, std::shared_ptr<const samples::SceneMesh> mesh);

    std::thread worker_;
    std::atomic<bool> cancel_{false};
    std::string key_;  // GL thread only

    // Worker only while it runs; the GL thread reads them only after join.
    std::unique_ptr<samples::TruthScene> bvh_;
    std::string bvh_scene_;

    mutable std::mutex mutex_;  // guards everything below
    TruthSnapshot snapshot_;
    TruthProgress progress_;
    uint64_t generation_ = 0;
    std::chrono::steady_clock::time_point started_{};
    bool running_ = false;
};

}  // namespace obscura::viewer

#endif  // OBSCURA_VIEWER_TRUTH_H
