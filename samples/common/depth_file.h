// Captured depth buffers from files: a 1-channel float32 PFM ("Pf", rows bottom-up as GL has them)
// uploaded as the depth input of obscura_render(), with the perspective projection it was captured with.
//
// Two kinds of content:
//   linear    positive view depth (distance from the eye plane) in metres; 0, +-inf and NaN are sky.
//             Uploaded as GL_R32F (sky stored as +inf) with depth_kind OBSCURA_DEPTH_LINEAR_VIEW.
//   hardware  window-space depth in [0, 1] written by a perspective projection with `near_plane`,
//             `far_plane` (+infinity for an infinite projection) and optionally reversed-Z; sky is the
//             clear value (1, or 0 reversed). Uploaded as GL_DEPTH_COMPONENT32F. Window depth as a
//             function of view depth is the same for [-1, 1] and [0, 1] clip depth, so either can be
//             read; the frame uses [0, 1] for reversed-Z and [-1, 1] otherwise.
// Guard band: `guard_band` is the fraction per side the file already includes around the visible
// image (as guard_band_layout() makes it): the visible width is round(file width / (1 + 2 guard_band)),
// likewise the height, centred. `fov_y_degrees` is the visible image's vertical field of view; the
// frame's projection covers the whole file (widen_for_guard_band of the visible one).
#ifndef OBSCURA_SAMPLES_DEPTH_FILE_H
#define OBSCURA_SAMPLES_DEPTH_FILE_H

#include <string>

#include "demo_scene.h"

namespace obscura::samples {

enum class DepthFileKind { Linear, Hardware };

// "linear", "hardware".
const char* depth_file_kind_name(DepthFileKind kind);
// Throws std::invalid_argument listing the valid names.
DepthFileKind parse_depth_file_kind(const std::string& name);

struct DepthFileOptions {
    std::string path;
    DepthFileKind kind = DepthFileKind::Linear;
    float fov_y_degrees = 60.0f;  // of the visible rectangle (guard band excluded), in (0, 180)
    float guard_band = 0.0f;      // per side, in [0, 1)
    // The projection: hardware files need the ones they were written with; for linear files they
    // only shape the matrix handed to obscura (its x/y scale is what matters).
    float near_plane = 0.1f;
    float far_plane = 1000.0f;    // > near_plane, or +infinity
    bool reversed_z = false;      // hardware only
};

// Reads options.path and uploads it with the current GL context (GL 4.3 core); restores the texture
// binding and unpack state it changes. The frame has no normal texture and an identity view matrix.
// Throws std::invalid_argument for bad options and std::runtime_error for an unreadable file, a
// 3-channel PFM, or values that do not fit the kind (negative linear depth, hardware depth outside
// [0, 1] or NaN), each with a one-line message naming the file.
RenderedScene load_depth_file(const DepthFileOptions& options);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_DEPTH_FILE_H
