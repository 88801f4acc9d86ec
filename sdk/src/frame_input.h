// Validation of the per-frame input, in two stages: the fields alone (no GL: testable without a context), then
// the textures they name, producing the decoded facts the passes need. The GL stage runs under a StateGuard
// (it probes texture targets by binding) and changes no host object's state. The output's validation, in the
// same two stages, is the output writer's (output_writer.h).
#ifndef OBSCURA_FRAME_INPUT_H
#define OBSCURA_FRAME_INPUT_H

#include "error.h"
#include "gl/gl_objects.h"
#include "gl/texture_probe.h"
#include "projection.h"

namespace obscura {

struct FrameInput {
    GLuint depth_texture = 0;
    bool depth_multisample = false;
    bool depth_linear = false;       // host gave linear view depth
    GLenum depth_format = 0;
    int width = 0, height = 0;       // whole depth texture
    obscura_rect output_rect = {};
    ProjectionInfo projection;
    float meters_to_view_units = 1.0f;
    GLuint normal_texture = 0;
    int normal_mode = 0;             // OBSCURA_NORMALS_* of shader_interface.h
    // Depth-stencil textures sample stencil when the host set GL_DEPTH_STENCIL_TEXTURE_MODE to it: the host's
    // mode, which the depth preparation switches to depth for its dispatches and back (0: depth already).
    GLint host_depth_stencil_mode = 0;
    // Temporal accumulation (obscura_input 0.5 fields): the view, the frame's noise index, and the reprojection.
    obscura_view* view = nullptr;
    uint32_t frame_index = 0;
    bool reset_history = false;
    // The matrices were given: `reprojection` maps this frame's view space (the SDK's: ProjectionInfo) to the
    // previous frame's (homogeneous; the projection assumed unchanged), column-major; the previous clip position is
    // the projection applied to that. `identity`: the two view-projections are equal (a static camera), the map 1.
    bool has_matrices = false;
    bool identity_reprojection = false;
    float reprojection[16] = {};
    // This frame's view-projection (column-major, the host's converted; with has_matrices): kept with the history
    // it writes, so that the next frame reprojects from the frame the history was made at (set_reprojection).
    double view_projection[16] = {};
    GLuint motion_vector_texture = 0;
    int motion_units = OBSCURA_MOTION_PIXELS;
    // Reduced resolution (reduced_resolution.h): this frame's texel t is the host's texel t << resolution_shift in a
    // host depth texture of host_width x host_height; 0 and the frame's own size at full resolution.
    int resolution_shift = 0;
    int host_width = 0, host_height = 0;
};

// Points `frame`'s reprojection (and identity_reprojection) at the view-projection `previous` (16 values,
// column-major): the
// host's previous_view_projection in stage 1, and the view's history's own frame where that differs (a debug-view
// frame or a frame the host skipped lies between them). Needs frame->has_matrices.
void set_reprojection(const double* previous, FrameInput* frame);

// Stage 1, no GL: every field of `input` (sizes against `max_texture_size`, the rectangle, the enums, the
// projection). Errors: INVALID_SIZE, INVALID_RECT, INVALID_PROJECTION, PROJECTION_TRANSPOSED, INVALID_ENUM,
// INVALID_SETTING.
Error check_input_fields(const obscura_input& input, GLint max_texture_size, FrameInput* out);
// Stage 2: the textures `input` names (targets, sizes, formats), completing `*out` from stage 1.
// Errors: INVALID_TEXTURE, UNSUPPORTED_FORMAT.
Error check_input_textures(const gl::TextureTargets& targets, const obscura_input& input, FrameInput* out);

}  // namespace obscura

#endif  // OBSCURA_FRAME_INPUT_H
