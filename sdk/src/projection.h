// Decoding of the host's projection matrix into the terms the shaders use to turn window depth into
// view-space positions. Handles perspective and orthographic, standard and reversed-Z, finite and
// infinite far planes, and both clip-depth conventions, from the matrix alone (no flags to get wrong).
#ifndef OBSCURA_PROJECTION_H
#define OBSCURA_PROJECTION_H

#include "error.h"

namespace obscura {

struct ProjectionInfo {
    float m[16];               // column-major, normalised so that m[11] = -1 (perspective) or m[15] = 1 (ortho)
    bool perspective = true;
    bool reversed_z = false;   // window depth decreases with distance
    bool infinite_far = false; // perspective with the far plane at infinity
    float clip_scale = 2.0f;   // z_ndc = window_depth * clip_scale + clip_bias
    float clip_bias = -1.0f;
    float sky_window_depth = 1.0f; // the far-plane clear value: 1, or 0 with reversed-Z
    // Orthographic cameras may put the near plane at or behind the eye (glOrtho(..., -8, 12)); the SDK
    // needs positive distances, so for hardware depth view space is translated along z by this much (folded into
    // m12..m14). AO of an orthographic view does not change under such a translation. 0 for perspective, and for
    // host linear depth, which is the host's own distance (its view space must stay the host's: the temporal
    // reprojection maps it through the host's matrices).
    float view_z_shift = 0.0f;
};

// Validates and decodes `matrix` (given in `layout`) for depth of `depth_kind`. Errors: INVALID_PROJECTION (not a projection GL can
// use: non-finite, zero scale, rotation terms, w not from z), PROJECTION_TRANSPOSED (a valid projection once
// transposed), INVALID_ENUM (bad layout / clip-depth value).
Error decode_projection(const float matrix[16], obscura_matrix_layout layout, obscura_clip_depth clip_depth,
                        obscura_depth_kind depth_kind, ProjectionInfo* out);

// View-space z (negative in front of the camera) of a window depth under `info`; used by tests and by the
// CPU mirror of the shader math.
double view_z_from_window_depth(const ProjectionInfo& info, double window_depth);

}  // namespace obscura

#endif  // OBSCURA_PROJECTION_H
