// TruthJob (samples/viewer/viewer_truth.h): the viewer's geometry truth on a worker thread. No GL, no window:
// the view is built by hand the way a rasterised frame describes itself (TruthView).
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "geometry_truth.h"
#include "scene_library.h"
#include "viewer_truth.h"

namespace {

using obscura::viewer::TruthJob;
using obscura::viewer::TruthProgress;
using obscura::viewer::TruthRequest;
using obscura::viewer::TruthSnapshot;
namespace samples = obscura::samples;

const samples::Scene& atrium() {
    static const samples::Scene scene = samples::load_scene("atrium");
    return scene;
}

samples::TruthView small_view(int width = 48, int height = 32) {
    const samples::Camera camera = samples::find_viewpoint(atrium(), "default").camera;
    samples::TruthView view;
    view.view = glm::lookAt(camera.eye, camera.target, camera.up);
    view.projection = glm::perspective(glm::radians(60.0f), float(width) / float(height), 0.1f, 50.0f);
    view.depth_width = width;
    view.depth_height = height;
    view.output_rect = {0, 0, width, height};
    view.near_plane = 0.1f;
    view.far_plane = 50.0f;
    return view;
}

TruthRequest request(const std::string& key, int rays, int batch) {
    TruthRequest r;
    r.key = key;
    r.scene_name = "atrium";
    r.view = small_view();
    obscura_default_settings(OBSCURA_METHOD_HBAO, &r.falloff);
    r.rays = rays;
    r.batch_rays = batch;
    r.threads = 2;
    return r;
}

// The key the viewer keeps its truth under: a scene reopened under the same name (an OBJ edited on disk) is another
// scene, so the old scene's truth must not match it; the falloff and the rays are in it, other settings are not.
TEST(ViewerTruthJob, KeyTellsReopenedScenesAndFalloffsApart) {
    using obscura::viewer::truth_view_key;
    obscura_settings hbao{};
    obscura_default_settings(OBSCURA_METHOD_HBAO, &hbao);
    const std::string key = truth_view_key("room.obj", 1, small_view(), 64, hbao);
    EXPECT_EQ(truth_view_key("room.obj", 1, small_view(), 64, hbao), key);
    EXPECT_NE(truth_view_key("room.obj", 2, small_view(), 64, hbao), key);  // reopened
    EXPECT_NE(truth_view_key("other.obj", 1, small_view(), 64, hbao), key);
    EXPECT_NE(truth_view_key("room.obj", 1, small_view(50, 32), 64, hbao), key);
    EXPECT_NE(truth_view_key("room.obj", 1, small_view(), 128, hbao), key);
    obscura_settings moved = hbao;
    ASSERT_EQ(obscura_set_setting(&moved, "radius", 2.0), OBSCURA_OK);
    EXPECT_NE(truth_view_key("room.obj", 1, small_view(), 64, moved), key);
    obscura_settings steps = hbao;  // leaves the falloff alone: the truth stays
    ASSERT_EQ(obscura_set_setting(&steps, "steps", 20.0), OBSCURA_OK);
    EXPECT_EQ(truth_view_key("room.obj", 1, small_view(), 64, steps), key);
}

TEST(ViewerTruthJob, CompletesInBatchesAndEqualsOneTrace) {
    TruthJob job;
    job.start(request("a", 12, 4), atrium().mesh);
    EXPECT_EQ(job.key(), "a");
    job.wait();
    const TruthProgress progress = job.progress();
    EXPECT_TRUE(progress.done) << progress.phase << " " << progress.error;
    EXPECT_EQ(progress.rays_done, 12);
    EXPECT_EQ(progress.rays_total, 12);
    EXPECT_GT(progress.triangles, 0);
    TruthSnapshot snapshot;
    ASSERT_TRUE(job.latest(0, &snapshot));
    EXPECT_FALSE(job.latest(snapshot.generation, &snapshot)) << "nothing newer than what was taken";
    EXPECT_EQ(snapshot.key, "a");
    EXPECT_EQ(snapshot.rays, 12);
    ASSERT_EQ(snapshot.visibility.width, 48);
    ASSERT_EQ(snapshot.visibility.height, 32);
    ASSERT_TRUE(snapshot.mask);
    ASSERT_EQ(snapshot.mask->size(), size_t(48 * 32));
    EXPECT_GT(snapshot.geometry_pixels, 0u);

    // Batches of 4 on the worker give exactly what one trace of 12 rays gives (the estimator is deterministic).
    const TruthRequest r = request("a", 12, 4);
    samples::TruthScene scene(atrium().mesh);
    samples::GeometryTruth truth(scene, r.view, {r.falloff});
    truth.trace(12);
    const samples::FloatImage direct = truth.visibility(0);
    ASSERT_EQ(direct.pixels.size(), snapshot.visibility.pixels.size());
    bool occluded = false;
    for (size_t i = 0; i < direct.pixels.size(); ++i) {
        EXPECT_EQ(direct.pixels[i], snapshot.visibility.pixels[i]) << "pixel " << i;
        occluded |= snapshot.visibility.pixels[i] < 0.99f;
    }
    EXPECT_TRUE(occluded);
}

TEST(ViewerTruthJob, CancelDropsTheEstimateAndARestartReusesTheScene) {
    TruthJob job;
    job.start(request("long", 100000, 8), atrium().mesh);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    job.cancel();
    EXPECT_TRUE(job.key().empty());
    TruthSnapshot snapshot;
    EXPECT_FALSE(job.latest(0, &snapshot));
    // The worker stops early: once joined, it traced fewer than its rays (a cancel that let the 1.5e8 rays finish
    // would pass a time limit on a fast machine, not this).
    job.wait();
    EXPECT_FALSE(job.busy());
    const TruthProgress cancelled = job.progress();
    EXPECT_EQ(cancelled.phase, "cancelled");
    EXPECT_FALSE(cancelled.done);
    EXPECT_LT(cancelled.rays_done, cancelled.rays_total);
    const auto before = std::chrono::steady_clock::now();
    job.start(request("short", 8, 8), atrium().mesh);  // joins the cancelled worker first
    job.wait();
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count(), 30.0);
    EXPECT_TRUE(job.progress().done);
    ASSERT_TRUE(job.latest(0, &snapshot));
    EXPECT_EQ(snapshot.key, "short");
    EXPECT_EQ(snapshot.rays, 8);
}

TEST(ViewerTruthJob, DestructorJoinsARunningWorker) {
    const auto before = std::chrono::steady_clock::now();
    {
        TruthJob job;
        job.start(request("long", 100000, 8), atrium().mesh);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count(), 30.0);
}

TEST(ViewerTruthJob, RefusedSettingsFailWithAMessage) {
    TruthJob job;
    TruthRequest r = request("bad", 8, 8);
    r.falloff.struct_size = 3;  // not an obscura_settings
    job.start(r, atrium().mesh);
    job.wait();
    const TruthProgress progress = job.progress();
    EXPECT_FALSE(progress.done);
    EXPECT_EQ(progress.phase, "failed");
    EXPECT_NE(progress.error.find("refused"), std::string::npos) << progress.error;
    TruthSnapshot snapshot;
    EXPECT_FALSE(job.latest(0, &snapshot));
}

}  // namespace
