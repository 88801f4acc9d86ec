// Command-line options that describe the rasterised demo scene, shared by render and bench:
// --guard-band F, --projection P, --depth-format D, --msaa N, --no-clip-control.
#ifndef OBSCURA_CLI_SCENE_OPTIONS_H
#define OBSCURA_CLI_SCENE_OPTIONS_H

#include <cstdint>
#include <string>

#include "cli_args.h"
#include "demo_scene.h"
#include "headless_gl.h"

namespace obscura::cli {

// Takes the scene options out of `arguments`; width and height are left to the caller.
samples::SceneRenderOptions take_scene_options(ArgumentList& arguments);

// "768x432 depth (guard band 0.10), perspective, d32f" for logs.
std::string describe_scene(const samples::SceneRenderOptions& options, const samples::SceneFrame& frame);

// OBSCURA_CONTEXT_FLAG_SYNC_TIMING when asked for, or when the renderer is a software one whose
// timer queries read 0 (llvmpipe, softpipe).
uint32_t timing_flags(const samples::HeadlessGL& gl, bool sync_timing_requested);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_SCENE_OPTIONS_H
