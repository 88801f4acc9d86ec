#include "scene_options.h"

#include <cstdio>
#include <stdexcept>

#include "cli_errors.h"

namespace obscura::cli {

samples::SceneRenderOptions take_scene_options(ArgumentList& arguments) {
    samples::SceneRenderOptions options;
    try {
        if (auto guard = arguments.take_value("--guard-band")) {
            const double fraction = parse_double("--guard-band", *guard);
            if (fraction < 0.0 || fraction > 1.0) throw UsageError("--guard-band must be in [0, 1]");
            options.guard_band = float(fraction);
        }
        if (auto projection = arguments.take_value("--projection")) {
            options.projection = samples::parse_projection_kind(*projection);
        }
        if (auto format = arguments.take_value("--depth-format")) {
            options.depth_format = samples::parse_depth_format(*format);
        }
    } catch (const std::invalid_argument& error) {
        throw UsageError(error.what());
    }
    if (auto msaa = arguments.take_value("--msaa")) options.samples = parse_int("--msaa", *msaa, 1, 32);
    options.use_clip_control = !arguments.take_flag("--no-clip-control");
    return options;
}

std::string describe_scene(const samples::SceneRenderOptions& options, const samples::SceneFrame& frame) {
    char text[256];
    std::snprintf(text, sizeof text, "%dx%d depth (guard band %.2f), %s, %s%s, clip depth %s", frame.depth_width,
                  frame.depth_height, double(options.guard_band), samples::projection_kind_name(options.projection),
                  samples::depth_format_name(options.depth_format),
                  frame.samples > 1 ? (" x" + std::to_string(frame.samples) + " MSAA").c_str() : "",
                  frame.clip_depth == OBSCURA_CLIP_DEPTH_ZERO_TO_ONE ? "[0,1]" : "[-1,1]");
    return text;
}

uint32_t timing_flags(const samples::HeadlessGL& gl, bool sync_timing_requested) {
    return sync_timing_requested || gl.is_software() ? uint32_t(OBSCURA_CONTEXT_FLAG_SYNC_TIMING) : 0u;
}

}  // namespace obscura::cli
