// The viewer's scenes and renderer with a headless GL context (no window, no ImGui):
//   - a depth file is read, checked and uploaded when it is opened (load_viewer_scene), so a missing or bad .pfm
//     throws there, where the viewer says "cannot open" and keeps the scene it shows; it used to be read on the
//     first frame after the scene had been replaced, and the exception closed the viewer;
//   - the split view's second method renders with its own Obscura context: the method's context (the panel's
//     timings and memory) sees only the method's renders;
//   - without temporal accumulation the frame index holds still, so a still view renders the same image every frame
//     (the one its error was measured on);
//   - the screen-space reference traces exactly the rays asked for, its last chunk what is left;
//   - the panel's derive box takes the renderer's value of a field that depends on it (LSAO's segment_steps).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "headless_gl.h"
#include "image_io.h"
#include "method_spec_parser.h"
#include "scene_library.h"
#include "settings_document.h"
#include "viewer_renderer.h"

namespace {

using obscura::samples::FloatImage;
using obscura::samples::HeadlessGL;
using obscura::viewer::load_viewer_scene;
using obscura::viewer::ReferenceJob;
using obscura::viewer::ViewerRenderer;
using obscura::viewer::ViewerScene;

std::string temp_path(const char* name) { return ::testing::TempDir() + "obscura_viewer_scene_" + name; }

FloatImage image(int width, int height, int channels, float value) {
    FloatImage out;
    out.width = width;
    out.height = height;
    out.channels = channels;
    out.pixels.assign(size_t(width) * size_t(height) * size_t(channels), value);
    return out;
}

void expect_refused(const std::string& path, const std::string& fragment) {
    SCOPED_TRACE(path);
    try {
        const ViewerScene scene = load_viewer_scene(path);
        ADD_FAILURE() << "opened";
    } catch (const std::exception& error) {
        EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    }
}

obscura_settings defaults(obscura_method method) {
    obscura_settings settings{};
    obscura_default_settings(method, &settings);
    return settings;
}

TEST(ViewerScene, BadDepthFilesAreRefusedWhenOpened) {
    HeadlessGL gl;
    expect_refused(temp_path("missing.pfm"), "missing.pfm");
    const std::string rgb = temp_path("rgb.pfm");
    obscura::samples::write_pfm(rgb, image(8, 4, 3, 2.0f));
    expect_refused(rgb, "channels");
    const std::string negative = temp_path("negative.pfm");
    obscura::samples::write_pfm(negative, image(8, 4, 1, -1.0f));
    expect_refused(negative, "negative linear depth");
}

TEST(ViewerScene, DepthFileIsDrawnFromItsOpenedScene) {
    HeadlessGL gl;
    ViewerScene scene = load_viewer_scene(OBSCURA_TEST_PFM);
    ASSERT_TRUE(scene.depth_file);
    EXPECT_FALSE(scene.mesh);
    ViewerRenderer renderer(&HeadlessGL::get_proc_address, true);
    renderer.render_scene(scene, obscura::samples::Camera(), 300, 200, &HeadlessGL::get_proc_address);
    EXPECT_EQ(renderer.width(), 64);  // the file's own size, whatever the window's
    EXPECT_EQ(renderer.height(), 36);
    EXPECT_TRUE(renderer.render_ao(0, defaults(OBSCURA_METHOD_HBAO), false)) << renderer.last_error();
    scene = ViewerScene();
    renderer.render_scene(load_viewer_scene(OBSCURA_TEST_PFM), obscura::samples::Camera(), 300, 200,
                          &HeadlessGL::get_proc_address);
    EXPECT_TRUE(renderer.render_ao(0, defaults(OBSCURA_METHOD_HBAO), false)) << renderer.last_error();
}

TEST(ViewerScene, SecondMethodDoesNotTouchTheMethodsContext) {
    HeadlessGL gl;
    const ViewerScene scene = load_viewer_scene(OBSCURA_TEST_PFM);
    ViewerRenderer renderer(&HeadlessGL::get_proc_address, true);
    renderer.render_scene(scene, obscura::samples::Camera(), 64, 36, &HeadlessGL::get_proc_address);
    ASSERT_TRUE(renderer.render_ao(0, defaults(OBSCURA_METHOD_HBAO), false)) << renderer.last_error();
    uint64_t memory = 0, frame = 0;
    obscura_timing rows[32];
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_memory_usage(renderer.context(), &memory), OBSCURA_STATUS_OK);
    ASSERT_EQ(obscura_get_timings(renderer.context(), rows, 32, &count, &frame), OBSCURA_STATUS_OK);
    for (obscura_method other : {OBSCURA_METHOD_FFAO, OBSCURA_METHOD_SAO}) {
        SCOPED_TRACE(obscura_method_name(other));
        ASSERT_TRUE(renderer.render_ao(1, defaults(other), false)) << renderer.last_error();
        uint64_t memory_after = 0, frame_after = 0;
        ASSERT_EQ(obscura_get_memory_usage(renderer.context(), &memory_after), OBSCURA_STATUS_OK);
        ASSERT_EQ(obscura_get_timings(renderer.context(), rows, 32, &count, &frame_after), OBSCURA_STATUS_OK);
        EXPECT_EQ(memory_after, memory);  // the method's resources, not freed for the other's
        EXPECT_EQ(frame_after, frame);    // its timings are still the method's frame
    }
}

// The AO of slot 0, read back.
FloatImage ao_of(const ViewerRenderer& renderer) {
    return obscura::samples::read_texture_region(renderer.ao_texture(0), 0, 0, renderer.width(), renderer.height());
}

TEST(ViewerScene, FrameIndexHoldsWithoutTemporalAccumulation) {
    HeadlessGL gl;
    const ViewerScene scene = load_viewer_scene("objects");
    ASSERT_TRUE(scene.mesh);
    const obscura::samples::Camera camera = obscura::samples::find_viewpoint(*scene.mesh, "default").camera;
    ViewerRenderer renderer(&HeadlessGL::get_proc_address, true);
    renderer.render_scene(scene, camera, 96, 64, &HeadlessGL::get_proc_address);
    // GTAO's per-pixel noise moves with the frame index: with it held, frame after frame is the same image.
    const obscura_settings gtao = defaults(OBSCURA_METHOD_GTAO);
    ASSERT_TRUE(renderer.render_ao(0, gtao, false)) << renderer.last_error();
    const FloatImage first = ao_of(renderer);
    for (int frame = 1; frame < 3; ++frame) {
        ASSERT_TRUE(renderer.render_ao(0, gtao, false)) << renderer.last_error();
        EXPECT_EQ(ao_of(renderer).pixels, first.pixels) << "frame " << frame;
    }
    // With accumulation the index advances: the next frame's noise differs, so the history changes the image.
    obscura_settings accumulating = gtao;
    accumulating.temporal.enabled = OBSCURA_TOGGLE_ON;
    ASSERT_TRUE(renderer.render_ao(0, accumulating, false)) << renderer.last_error();
    const FloatImage accumulated = ao_of(renderer);
    ASSERT_TRUE(renderer.render_ao(0, accumulating, false)) << renderer.last_error();
    EXPECT_NE(ao_of(renderer).pixels, accumulated.pixels);
}

TEST(ViewerScene, ReferenceTracesExactlyTheRaysAsked) {
    HeadlessGL gl;
    const ViewerScene scene = load_viewer_scene(OBSCURA_TEST_PFM);
    ViewerRenderer renderer(&HeadlessGL::get_proc_address, true);
    renderer.render_scene(scene, obscura::samples::Camera(), 64, 36, &HeadlessGL::get_proc_address);
    ASSERT_TRUE(renderer.render_ao(0, defaults(OBSCURA_METHOD_HBAO), false)) << renderer.last_error();
    for (int rays : {20, 3, 16}) {
        SCOPED_TRACE(rays);
        ReferenceJob job;
        job.start("view", defaults(OBSCURA_METHOD_HBAO), rays);
        int steps = 0;
        while (!job.done() && steps < 100) {
            ASSERT_TRUE(renderer.step_reference(job, false)) << renderer.last_error();
            ++steps;
        }
        EXPECT_EQ(job.traced_rays(), rays);  // 20: 8 + 8 + 4, not 24
        EXPECT_EQ(steps, (rays + ReferenceJob::kChunkRays - 1) / ReferenceJob::kChunkRays);
        EXPECT_TRUE(job.metrics);
    }
}

TEST(ViewerScene, DeriveBoxTakesTheRenderersValue) {
    HeadlessGL gl;
    ViewerRenderer renderer(&HeadlessGL::get_proc_address, true);
    obscura_settings lsao = defaults(OBSCURA_METHOD_LSAO);
    const std::vector<obscura_setting_info> infos = obscura::samples::setting_infos(OBSCURA_METHOD_LSAO);
    const obscura_setting_info* steps = obscura::samples::find_setting(infos, "segment_steps");
    ASSERT_TRUE(steps);
    // What the context's renders use: -1 (whole lines) on a CPU renderer, 128 on a GPU; 0 only without a context.
    obscura_settings resolved = lsao;
    ASSERT_EQ(obscura_resolve_settings(renderer.context(), &lsao, &resolved), OBSCURA_OK);
    ASSERT_NE(resolved.lsao.segment_steps, 0);
    EXPECT_EQ(obscura::viewer::effective_setting_value(renderer.context(), lsao, *steps),
              double(resolved.lsao.segment_steps));
    // Unticked, the field holds that value (0 would be "derive" again, and the box would tick itself).
    ASSERT_TRUE(obscura::viewer::set_derive(renderer.context(), lsao, *steps, false));
    EXPECT_FALSE(obscura::samples::derives(lsao, *steps));
    EXPECT_EQ(lsao.lsao.segment_steps, resolved.lsao.segment_steps);
    ASSERT_TRUE(obscura::viewer::set_derive(renderer.context(), lsao, *steps, true));
    EXPECT_TRUE(obscura::samples::derives(lsao, *steps));
}

}  // namespace
