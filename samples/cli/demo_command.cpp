// obscura demo: one AO image per available method of the demo scene, plus each method's time at
// 640x360 and 1280x720.
#include <cstdio>
#include <filesystem>

#include "ao_render.h"
#include "cli_errors.h"
#include "commands.h"
#include "method_spec.h"
#include "obscura_session.h"
#include "scene_options.h"

namespace obscura::cli {
namespace {

constexpr ImageSize kImageSize{640, 360};
constexpr ImageSize kTimedSizes[] = {{640, 360}, {1280, 720}};
constexpr int kWarmupFrames = 2;

samples::SceneRenderOptions scene_of_size(ImageSize size) {
    samples::SceneRenderOptions options;
    options.width = size.width;
    options.height = size.height;
    return options;
}

void write_method_image(const ObscuraSession& session, const MethodSpec& method, const std::filesystem::path& path) {
    const samples::RenderedScene scene = samples::render_demo_scene(scene_of_size(kImageSize));
    const AoTarget target(kImageSize.width, kImageSize.height, GL_R8);
    AoRenderRequest request;
    request.scene = &scene.frame();
    request.settings = &method.settings;
    request.target = &target;
    render_ao(session, request);
    samples::write_png(path.string(), target.read());
}

double median_time_ms(const ObscuraSession& session, const MethodSpec& method, ImageSize size, int frames) {
    const samples::RenderedScene scene = samples::render_demo_scene(scene_of_size(size));
    const AoTarget target(size.width, size.height, GL_R8);
    AoRenderRequest request;
    request.scene = &scene.frame();
    request.settings = &method.settings;
    request.target = &target;
    return time_frames(session, request, kWarmupFrames, frames).best_total().median_ms;
}

}  // namespace

int run_demo(ArgumentList& arguments) {
    const std::filesystem::path out_dir = arguments.take_value("--out-dir").value_or("demo-output");
    const int frames = parse_int("--frames", arguments.take_value("--frames").value_or("10"), 1, 10000);
    const bool sync_timing = arguments.take_flag("--sync-timing");
    arguments.require_all_taken();

    samples::HeadlessGL gl;
    std::printf("GL: %s\n", gl.describe().c_str());
    ObscuraSession session(timing_flags(gl, sync_timing));
    std::filesystem::create_directories(out_dir);
    std::printf("demo scene, perspective, guard band 0.10; times are medians over %d frames%s\n", frames,
                session.flags() & OBSCURA_CONTEXT_FLAG_SYNC_TIMING ? " (sync timing: software renderer)" : "");

    for (obscura_method method_id : all_methods()) {
        const MethodSpec method = parse_method_spec(obscura_method_name(method_id));
        if (!obscura_method_available(method_id)) {
            std::printf("%-10s not available yet\n", method.name());
            continue;
        }
        const std::filesystem::path image = out_dir / (std::string(method.name()) + ".png");
        write_method_image(session, method, image);
        std::printf("%-10s %s\n", method.name(), image.string().c_str());
        for (const ImageSize& size : kTimedSizes) {
            std::printf("%-10s   %dx%d: %.2f ms\n", "", size.width, size.height,
                        median_time_ms(session, method, size, frames));
        }
        std::printf("%-10s   reference: not available yet\n", "");
    }
    return 0;
}

}  // namespace obscura::cli
