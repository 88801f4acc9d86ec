// obscura bench: times warm frames of every --methods spec at every --sizes size, in total and per pass.
//
// The clock: on a GPU the SDK's GL timer queries (obscura_get_timings; "gpu-timer"). On software
// renderers (llvmpipe, softpipe), whose timer queries read 0, the CPU clock around obscura_render +
// glFinish ("wall"), with per-pass times from the SDK's sync timing (glFinish + CPU clock per pass), whose
// glFinish after every pass the total includes (`--clock wall` on a GPU reads above the unsynchronised frame).
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>

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

enum class Clock { Auto, GpuTimer, Wall };

const char* clock_name(Clock clock) {
    return clock == Clock::GpuTimer ? "gpu-timer" : clock == Clock::Wall ? "wall" : "auto";
}

Clock parse_clock(const std::string& text) {
    for (Clock clock : {Clock::Auto, Clock::GpuTimer, Clock::Wall}) {
        if (text == clock_name(clock)) return clock;
    }
    throw UsageError("--clock: '" + text + "' is not auto, gpu-timer or wall");
}

struct BenchConfig {
    std::vector<MethodSpec> methods;
    std::vector<ImageSize> sizes;
    SceneSourceOptions scene;
    int frames = 50;
    int warmup = 5;
    Clock clock = Clock::Auto;
    std::optional<std::string> json_path;
    std::optional<std::string> csv_path;
    double motion_degrees = 0.0;  // --motion: the previous frame's camera, turned back along the orbit by this much
};

BenchConfig take_bench_config(ArgumentList& arguments) {
    if (arguments.contains("--method")) throw UsageError("bench takes --methods SPEC,SPEC,... (not --method)");
    if (arguments.contains("--size")) throw UsageError("bench takes --sizes WxH,WxH,... (not --size)");
    BenchConfig config;
    const std::vector<std::string> sets = arguments.take_values("--set");
    config.methods = parse_method_specs("--methods", arguments.take_value("--methods").value_or("hbao"), sets);
    const std::optional<std::string> sizes = arguments.take_value("--sizes");
    config.scene = take_scene_source_options(arguments, /*takes_size=*/false);
    if (sizes && config.scene.depth_file) throw UsageError("--sizes does not apply to --depth (the size is the file's)");
    for (const std::string& text : split_list("--sizes", sizes.value_or("1280x720"))) {
        config.sizes.push_back(parse_size("--sizes", text));
    }
    if (config.scene.depth_file) config.sizes.resize(1);  // the file's size; this entry is ignored
    if (auto frames = arguments.take_value("--frames")) config.frames = parse_int("--frames", *frames, 1, 100000);
    if (auto warmup = arguments.take_value("--warmup")) config.warmup = parse_int("--warmup", *warmup, 0, 100000);
    if (auto clock = arguments.take_value("--clock")) config.clock = parse_clock(*clock);
    config.json_path = arguments.take_value("--json");
    config.csv_path = arguments.take_value("--csv");
    std::vector<OutputFile> outputs;
    if (config.json_path) outputs.push_back({"--json", *config.json_path});
    if (config.csv_path) outputs.push_back({"--csv", *config.csv_path});
    if (auto motion = arguments.take_value("--motion")) {
        if (config.scene.depth_file) throw UsageError("--motion needs a scene (a depth file has one camera)");
        config.motion_degrees = parse_double_in("--motion", *motion, -45.0, 45.0);
    }
    arguments.require_all_taken();
    check_output_files(outputs);  // before the run: its numbers are what the files are for
    return config;
}

struct BenchResult {
    std::string scene;
    int width = 0;
    int height = 0;
    const MethodSpec* method = nullptr;
    TimingRow total;
    std::vector<TimingRow> passes;  // "total" excluded
    uint64_t memory_bytes = 0;
    std::string error;  // non-empty: this configuration failed (status and message); no timings
};

BenchResult make_result(const SceneSource& source, const samples::SceneFrame& frame, const MethodSpec& method,
                        const TimingSummary& summary, Clock clock) {
    BenchResult result;
    result.scene = source.name();
    result.width = frame.output_rect.width;
    result.height = frame.output_rect.height;
    result.method = &method;
    result.total = clock == Clock::Wall ? summary.wall : summary.sdk_total();
    result.total.label = "total";
    for (const TimingRow& row : summary.passes) {
        if (row.label != "total") result.passes.push_back(row);
    }
    result.memory_bytes = summary.memory_bytes;
    return result;
}

void print_result(const BenchResult& result) {
    if (!result.error.empty()) {
        std::printf("  failed: %s\n", result.error.c_str());
        return;
    }
    TextTable table({"  pass", "median ms", "min ms"});
    table.add_row({"  total", format_fixed(result.total.median_ms, 3), format_fixed(result.total.min_ms, 3)});
    for (const TimingRow& row : result.passes) {
        table.add_row({"  " + row.label, format_fixed(row.median_ms, 3), format_fixed(row.min_ms, 3)});
    }
    table.print(stdout);
    std::printf("  GPU memory: %.2f MiB\n", double(result.memory_bytes) / (1024.0 * 1024.0));
}

void write_json(const std::string& path, const std::string& device, Clock clock, const BenchConfig& config,
                const std::vector<BenchResult>& results, obscura_context* context) {
    samples::JsonWriter json;
    json.begin_object();
    json.field("device", device).field("clock", clock_name(clock));
    json.field("frames", config.frames).field("warmup", config.warmup);
    json.key("results").begin_array();
    for (const BenchResult& result : results) {
        json.begin_object();
        json.field("scene", result.scene).field("width", result.width).field("height", result.height);
        json.field("method", result.method->text);
        write_settings_json(json, result.method->settings, context);
        if (!result.error.empty()) {
            json.field("error", result.error).end_object();
            continue;
        }
        json.key("total_ms").begin_object();
        json.field("median", result.total.median_ms).field("min", result.total.min_ms).end_object();
        json.key("passes").begin_object();
        for (const TimingRow& row : result.passes) {
            json.key(row.label).begin_object();
            json.field("median", row.median_ms).field("min", row.min_ms).end_object();
        }
        json.end_object();
        json.field("memory_bytes", result.memory_bytes);
        json.end_object();
    }
    json.end_array();
    json.end_object().write_file(path);
}

std::string csv_quote(const std::string& text) {
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

void write_csv(const std::string& path, const std::string& device, Clock clock, const std::vector<BenchResult>& results) {
    std::ofstream file(path);
    if (!file) throw std::runtime_error("cannot open '" + path + "' for writing");
    file << "scene,method,width,height,clock,pass,median_ms,min_ms,samples,memory_bytes,device,error\n";
    for (const BenchResult& result : results) {
        if (!result.error.empty()) {  // one row, pass "failed", no numbers
            file << csv_quote(result.scene) << ',' << csv_quote(result.method->text) << ',' << result.width << ','
                 << result.height << ',' << clock_name(clock) << ",\"failed\",,,0,0," << csv_quote(device) << ','
                 << csv_quote(result.error) << '\n';
            continue;
        }
        std::vector<const TimingRow*> rows = {&result.total};
        for (const TimingRow& row : result.passes) rows.push_back(&row);
        for (const TimingRow* row : rows) {
            file << csv_quote(result.scene) << ',' << csv_quote(result.method->text) << ',' << result.width << ','
                 << result.height << ',' << clock_name(clock) << ',' << csv_quote(row->label) << ',' << row->median_ms
                 << ',' << row->min_ms << ',' << row->samples << ',' << result.memory_bytes << ',' << csv_quote(device)
                 << ",\"\"\n";
        }
    }
    if (!file) throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace

int run_bench(ArgumentList& arguments) {
    const BenchConfig config = take_bench_config(arguments);
    const SceneSource source(config.scene);

    samples::HeadlessGL gl;
    std::printf("GL: %s\n", gl.describe().c_str());
    const Clock clock = config.clock != Clock::Auto ? config.clock : gl.is_software() ? Clock::Wall : Clock::GpuTimer;
    if (clock == Clock::GpuTimer && gl.is_software()) {
        std::fprintf(stderr, "obscura bench: warning: the timer queries of %s read 0; --clock wall measures it\n",
                     gl.renderer().c_str());
    }
    // The wall clock's per-pass times come from the SDK's sync timing, a glFinish after every pass, which the total
    // then includes: on a GPU it reads above what the frame costs unsynchronised (the gpu-timer clock measures that);
    // on a software renderer, which runs each pass to its end anyway, it adds little. Said, not hidden.
    ObscuraSession session(clock == Clock::Wall ? uint32_t(OBSCURA_CONTEXT_FLAG_SYNC_TIMING) : 0u);
    std::printf("clock: %s (%s); median and min of %d frames after %d warm-up\n", clock_name(clock),
                clock == Clock::Wall ? "CPU clock around obscura_render + glFinish, with a glFinish after every pass; "
                                       "passes by glFinish + CPU clock"
                                     : "GL timer queries of the SDK (obscura_get_timings)",
                config.frames, config.warmup);

    // A size this context cannot hold is a usage error found before the first size is timed, not after it.
    for (const ImageSize& size : config.sizes) source.check_size(size);

    std::vector<BenchResult> results;
    size_t failures = 0;
    const auto record_failure = [&](const MethodSpec& method, int width, int height, const std::string& error) {
        BenchResult failed;
        failed.scene = source.name();
        failed.width = width;
        failed.height = height;
        failed.method = &method;
        failed.error = error;
        results.push_back(failed);
        ++failures;
    };
    for (const ImageSize& size : config.sizes) {
        // A size whose depth the samples cannot rasterise (a framebuffer GL refuses, out of memory) fails each method
        // at that size, as a configuration the SDK refuses does: the other sizes still run and the files are written.
        // A usage error (--msaa past the context's limit) fails every size alike: it ends the run.
        std::optional<samples::RenderedScene> scene;
        std::optional<AoTarget> target;
        // --motion: the camera moves every frame, back and forth between the scene's camera and one turned by that
        // much along the orbit, each frame reprojecting the other's history (temporal accumulation's moving path).
        // A camera that stays put while its previous_view_projection claims motion is a still camera to the SDK,
        // which reprojects from the camera its history was made with (the bench measured the still path so from
        // 2026-12-05, a3ec05a, until this was fixed).
        std::optional<samples::RenderedScene> turned;
        try {
            scene.emplace(source.render(source.camera(), size));
            std::printf("\nscene: %s\n", source.describe(scene->frame()).c_str());
            target.emplace((*scene)->output_rect.width, (*scene)->output_rect.height, GL_R8);
            if (config.motion_degrees != 0.0) {
                const samples::Camera previous = samples::orbit_camera(source.camera(), float(-config.motion_degrees));
                turned.emplace(source.render(previous, size));
            }
        } catch (const UsageError&) {
            throw;
        } catch (const std::exception& error) {
            const ImageSize shown = source.is_depth_file() ? ImageSize{} : size;  // a depth file's size is its own
            std::printf("\nscene: %s: %s\n", source.name().c_str(), error.what());
            for (const MethodSpec& method : config.methods) {
                record_failure(method, shown.width, shown.height, error.what());
                std::printf("%s @ %dx%d, clock %s\n", method.text.c_str(), shown.width, shown.height,
                            clock_name(clock));
                print_result(results.back());
            }
            continue;
        }
        for (const MethodSpec& method : config.methods) {
            AoRenderRequest request;
            request.scene = &scene->frame();
            if (turned) request.previous_scene = &turned->frame();
            request.settings = &method.settings;
            request.target = &*target;
            request.use_normals = source.use_normals();
            // A configuration the SDK refuses (FFAO at 4K over a software renderer's storage-block limit,
            // say) is reported and the rest still run: one refusal must not lose a long run's numbers.
            try {
                warm_up(session, request);
                AoRenderRequest back = request;
                if (turned) {
                    back.scene = &turned->frame();
                    back.previous_scene = &scene->frame();
                }
                const TimingSummary summary =
                    time_frames(session, request, config.warmup, config.frames, turned ? &back : nullptr);
                results.push_back(make_result(source, scene->frame(), method, summary, clock));
            } catch (const ApiError& error) {
                record_failure(method, (*scene)->output_rect.width, (*scene)->output_rect.height, error.what());
            }
            std::printf("%s @ %dx%d, clock %s\n", method.text.c_str(), results.back().width, results.back().height,
                        clock_name(clock));
            print_result(results.back());
        }
    }
    if (config.json_path) {
        write_json(*config.json_path, gl.renderer(), clock, config, results, session.get());
        std::printf("\nwrote %s\n", config.json_path->c_str());
    }
    if (config.csv_path) {
        write_csv(*config.csv_path, gl.renderer(), clock, results);
        std::printf("wrote %s\n", config.csv_path->c_str());
    }
    if (failures > 0) {
        std::fprintf(stderr, "obscura bench: %zu of %zu configurations failed (see above)\n", failures, results.size());
        return 1;
    }
    return 0;
}

}  // namespace obscura::cli
