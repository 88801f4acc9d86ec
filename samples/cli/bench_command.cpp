// obscura bench: times obscura_render on the demo scene for every --method x --size, per pass
// (obscura_get_timings) and as wall-clock time around render + glFinish.
#include <cstdio>
#include <fstream>
#include <memory>

#include "ao_render.h"
#include "cli_errors.h"
#include "commands.h"
#include "method_spec.h"
#include "obscura_session.h"
#include "scene_options.h"

namespace obscura::cli {
namespace {

struct BenchConfig {
    std::vector<MethodSpec> methods;
    std::vector<ImageSize> sizes;
    samples::SceneRenderOptions scene;
    int frames = 50;
    int warmup = 5;
    bool use_normals = false;
    bool sync_timing = false;
    std::optional<std::string> csv_path;
};

BenchConfig take_bench_config(ArgumentList& arguments) {
    BenchConfig config;
    for (const std::string& text : arguments.take_values("--method")) config.methods.push_back(parse_method_spec(text));
    if (config.methods.empty()) config.methods.push_back(parse_method_spec("hbao"));
    for (const std::string& text : arguments.take_values("--size")) config.sizes.push_back(parse_size(text));
    if (config.sizes.empty()) config.sizes.push_back(ImageSize{1280, 720});
    config.scene = take_scene_options(arguments);
    if (auto frames = arguments.take_value("--frames")) config.frames = parse_int("--frames", *frames, 1, 100000);
    if (auto warmup = arguments.take_value("--warmup")) config.warmup = parse_int("--warmup", *warmup, 0, 100000);
    config.use_normals = arguments.take_flag("--normals");
    config.sync_timing = arguments.take_flag("--sync-timing");
    config.csv_path = arguments.take_value("--csv");
    arguments.require_all_taken();
    return config;
}

// One CSV line per timed quantity; the header names the columns.
class CsvWriter {
public:
    explicit CsvWriter(const std::string& path) : file_(path) {
        if (!file_) throw std::runtime_error("cannot open '" + path + "' for writing");
        file_ << "method,spec,width,height,depth_width,depth_height,pass,median_ms,min_ms,samples,timing,"
                 "memory_bytes,renderer\n";
    }
    void row(const MethodSpec& method, const samples::SceneFrame& frame, const TimingRow& timing,
             const std::string& timing_kind, uint64_t memory, const std::string& renderer) {
        file_ << method.name() << ',' << quote(method.text) << ',' << frame.output_rect.width << ','
              << frame.output_rect.height << ',' << frame.depth_width << ',' << frame.depth_height << ','
              << quote(timing.label) << ',' << timing.median_ms << ',' << timing.min_ms << ',' << timing.samples << ','
              << timing_kind << ',' << memory << ',' << quote(renderer) << '\n';
    }

private:
    static std::string quote(const std::string& text) {
        std::string quoted = "\"";
        for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
        return quoted + "\"";
    }
    std::ofstream file_;
};

void print_summary(const TimingSummary& summary) {
    std::printf("  %-28s %10s %10s\n", "pass", "median ms", "min ms");
    if (summary.passes.empty()) std::printf("  (the SDK reported no pass timings)\n");
    for (const TimingRow& row : summary.passes) {
        std::printf("  %-28s %10.3f %10.3f\n", row.label.c_str(), row.median_ms, row.min_ms);
    }
    std::printf("  %-28s %10.3f %10.3f\n", summary.wall.label.c_str(), summary.wall.median_ms, summary.wall.min_ms);
    std::printf("  GPU memory: %.2f MiB (%llu bytes)\n", double(summary.memory_bytes) / (1024.0 * 1024.0),
                static_cast<unsigned long long>(summary.memory_bytes));
}

}  // namespace

int run_bench(ArgumentList& arguments) {
    const BenchConfig config = take_bench_config(arguments);
    samples::HeadlessGL gl;
    std::printf("GL: %s\n", gl.describe().c_str());
    ObscuraSession session(timing_flags(gl, config.sync_timing));
    const bool sync = session.flags() & OBSCURA_CONTEXT_FLAG_SYNC_TIMING;
    const std::string timing_kind = sync ? "sync" : "gpu-queries";
    std::printf("timing: %s\n", sync ? "glFinish + CPU clock per pass (OBSCURA_CONTEXT_FLAG_SYNC_TIMING)"
                                     : "GL timer queries");
    std::unique_ptr<CsvWriter> csv;
    if (config.csv_path) csv = std::make_unique<CsvWriter>(*config.csv_path);

    for (const ImageSize& size : config.sizes) {
        samples::SceneRenderOptions scene_options = config.scene;
        scene_options.width = size.width;
        scene_options.height = size.height;
        const samples::RenderedScene scene = samples::render_demo_scene(scene_options);
        const AoTarget target(size.width, size.height, GL_R8);
        for (const MethodSpec& method : config.methods) {
            std::printf("\n%s @ %dx%d (%s), %d frames after %d warm-up\n", method.text.c_str(), size.width,
                        size.height, describe_scene(scene_options, scene.frame()).c_str(), config.frames, config.warmup);
            if (!obscura_method_available(method.method())) {
                std::printf("  not available yet\n");
                continue;
            }
            AoRenderRequest request;
            request.scene = &scene.frame();
            request.settings = &method.settings;
            request.target = &target;
            request.use_normals = config.use_normals;
            const TimingSummary summary = time_frames(session, request, config.warmup, config.frames);
            print_summary(summary);
            if (csv) {
                for (const TimingRow& row : summary.passes) {
                    csv->row(method, scene.frame(), row, timing_kind, summary.memory_bytes, gl.renderer());
                }
                csv->row(method, scene.frame(), summary.wall, "wall", summary.memory_bytes, gl.renderer());
            }
        }
    }
    if (config.csv_path) std::printf("\nwrote %s\n", config.csv_path->c_str());
    return 0;
}

}  // namespace obscura::cli
