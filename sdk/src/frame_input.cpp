#include "frame_input.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "common/shader_interface.h"
#include "gl/texture_probe.h"
#include "host_enum.h"

namespace obscura {
namespace {

using gl::texture_has_target;

bool is_hardware_depth_format(GLenum format) {
    switch (format) {
        case GL_DEPTH_COMPONENT16: case GL_DEPTH_COMPONENT24: case GL_DEPTH_COMPONENT32:
        case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_DEPTH32F_STENCIL8:
        // Unsized requests are reported as such by some drivers.
        case GL_DEPTH_COMPONENT: case GL_DEPTH_STENCIL:
            return true;
        default: return false;
    }
}

bool is_depth_stencil_format(GLenum format) {
    return format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8 || format == GL_DEPTH_STENCIL;
}

int normal_mode_for_format(GLenum format) {
    switch (format) {
        case GL_RGB16F: case GL_RGBA16F: case GL_RGB32F: case GL_RGBA32F: case GL_RGB8_SNORM:
        case GL_RGBA8_SNORM: case GL_RGB16_SNORM: case GL_RGBA16_SNORM:
            return OBSCURA_NORMALS_SIGNED;
        // R11F_G11F_B10F has no sign bit: it can only hold normals encoded as n * 0.5 + 0.5.
        case GL_RGB8: case GL_RGBA8: case GL_RGB10_A2: case GL_RGB16: case GL_RGBA16: case GL_R11F_G11F_B10F:
            return OBSCURA_NORMALS_UNSIGNED;
        default: return -1;
    }
}

// A texture that goes with the depth (normals, motion vectors): a GL_TEXTURE_2D of the depth's size, probed on
// `unit` (the state guard restores it); its internal format in *format.
Error check_companion_texture(const gl::TextureTargets& targets, GLuint texture, const char* field, int unit,
                              const FrameInput& frame, GLenum* format) {
    const gl::Table& gl = targets.gl;
    gl.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
    if (!gl.IsTexture(texture) || !texture_has_target(targets, texture, GL_TEXTURE_2D)) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "%s %u is not a GL_TEXTURE_2D", field, texture);
    }
    GLint width = 0, height = 0, internal_format = 0;
    const GLint level = gl::texture_base_level(gl, GL_TEXTURE_2D);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, level, GL_TEXTURE_WIDTH, &width);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, level, GL_TEXTURE_HEIGHT, &height);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, level, GL_TEXTURE_INTERNAL_FORMAT, &internal_format);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    if (width != frame.width || height != frame.height) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "%s %u is %dx%d; the depth is %dx%d", field, texture, width,
                           height, frame.width, frame.height);
    }
    *format = GLenum(internal_format);
    return Error();
}

bool all_zero(const float (&m)[16]) {
    for (float v : m) {
        if (v != 0.0f) return false;
    }
    return true;
}

// A host matrix (in `layout`) as a double column-major glm matrix.
glm::dmat4 host_matrix(const float (&m)[16], int32_t layout) {
    glm::dmat4 r;
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            r[column][row] = layout == OBSCURA_MATRIX_ROW_MAJOR ? m[row * 4 + column] : m[column * 4 + row];
        }
    }
    return r;
}

void store_matrix(const glm::dmat4& m, float (&out)[16]) {
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) out[column * 4 + row] = float(m[column][row]);
    }
}

// The temporal fields: view, frame index, flags, matrices, motion vectors (their texture is checked in stage 2).
Error check_temporal_fields(const obscura_input& input, int32_t layout, FrameInput* frame) {
    if ((input.flags & ~uint32_t(OBSCURA_INPUT_FLAG_RESET_HISTORY)) != 0) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "obscura_input.flags = 0x%x has unknown bits",
                           unsigned(input.flags));
    }
    const int32_t units = stored_enum(input.motion_vector_units);
    if (units != OBSCURA_MOTION_PIXELS && units != OBSCURA_MOTION_NDC) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "motion_vector_units = %d is not an obscura_motion_units",
                           int(units));
    }
    frame->view = input.view;
    frame->frame_index = input.frame_index;
    frame->reset_history = (input.flags & OBSCURA_INPUT_FLAG_RESET_HISTORY) != 0;
    frame->motion_vector_texture = input.motion_vector_texture;
    frame->motion_units = units;
    // Each matrix given is checked on its own, the other one all zero or not: a first frame (no previous matrix) with
    // a broken view_projection was accepted, and the host heard of it a frame later, as previous_view_projection.
    const bool has_current = !all_zero(input.view_projection), has_previous = !all_zero(input.previous_view_projection);
    for (int i = 0; i < 16; ++i) {
        if ((has_current && !std::isfinite(input.view_projection[i])) ||
            (has_previous && !std::isfinite(input.previous_view_projection[i]))) {
            const bool previous_bad = has_previous && !std::isfinite(input.previous_view_projection[i]);
            const bool current_bad = has_current && !std::isfinite(input.view_projection[i]);
            return Error::make(OBSCURA_STATUS_INVALID_PROJECTION, "%sview_projection[%d] is not finite",
                               previous_bad && !current_bad ? "previous_" : "", i);
        }
    }
    const glm::dmat4 view_projection = host_matrix(input.view_projection, layout);
    const glm::dmat4 previous = host_matrix(input.previous_view_projection, layout);
    const double det = glm::determinant(view_projection);
    if (has_current && (!std::isfinite(det) || std::fabs(det) < 1e-30)) {
        return Error::make(OBSCURA_STATUS_INVALID_PROJECTION, "view_projection is singular (determinant %g)", det);
    }
    if (!has_current || !has_previous) return Error();  // no reprojection from matrices (motion vectors may still give one)
    frame->has_matrices = true;
    double previous_columns[16];
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            frame->view_projection[column * 4 + row] = view_projection[column][row];
            previous_columns[column * 4 + row] = previous[column][row];
        }
    }
    set_reprojection(previous_columns, frame);
    return Error();
}

}  // namespace

void set_reprojection(const double* previous, FrameInput* frame) {
    // The SDK's view space maps to this frame's clip space through the decoded projection (normalised, an
    // orthographic near plane shifted: same clip coordinates up to scale); world space is one inverse away.
    glm::dmat4 projection, view_projection, previous_matrix;
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            projection[column][row] = frame->projection.m[column * 4 + row];
            view_projection[column][row] = frame->view_projection[column * 4 + row];
            previous_matrix[column][row] = previous[column * 4 + row];
        }
    }
    // Equal matrices (a static camera): the identity, read by its own program variant (exact: both are the host's
    // floats converted).
    frame->identity_reprojection = std::memcmp(previous, frame->view_projection, sizeof frame->view_projection) == 0;
    glm::dmat4 reprojection;
    bool through_shared_rows = false;
    if (frame->projection.perspective) {
        // Under perspective the previous view point comes from the previous clip coordinates through the rows this
        // frame's projection shares with the last one (x, y and w = -z), not its depth row: a near or far plane that
        // changed between the frames then still finds the history's depths (through the inverse projection the
        // points moved by up to 19 % of their distance for a near plane of 0.10 -> 0.12, and every texel failed the
        // plane test). Clip coordinates are homogeneous, so the previous matrix is first brought to this one's scale
        // by their w rows (-z times the world-to-view scale times the matrix's own factor): the point then has w = 1.
        const double current_w = glm::length(glm::dvec3(view_projection[0][3], view_projection[1][3], view_projection[2][3]));
        const double previous_w = glm::length(glm::dvec3(previous_matrix[0][3], previous_matrix[1][3], previous_matrix[2][3]));
        if (current_w > 0.0 && previous_w > 0.0 && std::isfinite(current_w / previous_w)) {
            const double m0 = projection[0][0], m5 = projection[1][1], m8 = projection[2][0], m9 = projection[2][1];
            const double m12 = projection[3][0], m13 = projection[3][1];
            // Clip (x, y, z, w) -> view: z = -w, x = (x_c - m8 z - m12) / m0, y = (y_c - m9 z - m13) / m5.
            glm::dmat4 unproject(0.0);
            unproject[0][0] = 1.0 / m0;
            unproject[3][0] = m8 / m0;
            unproject[1][1] = 1.0 / m5;
            unproject[3][1] = m9 / m5;
            unproject[3][2] = -1.0;
            glm::dmat4 rows = unproject * (current_w / previous_w) * previous_matrix * glm::inverse(view_projection) *
                              projection;
            // The constant terms (the view point has w = 1) and the homogeneous row.
            rows[3][0] -= m12 / m0;
            rows[3][1] -= m13 / m5;
            rows[0][3] = rows[1][3] = rows[2][3] = 0.0;
            rows[3][3] = 1.0;
            reprojection = rows;
            through_shared_rows = true;
        }
    }
    if (!through_shared_rows) {  // orthographic (or a degenerate w row): this frame's projection inverted
        reprojection = glm::inverse(projection) * previous_matrix * glm::inverse(view_projection) * projection;
    }
    store_matrix(frame->identity_reprojection ? glm::dmat4(1.0) : reprojection, frame->reprojection);
}

Error check_input_fields(const obscura_input& input, GLint max_texture_size, FrameInput* out) {
    FrameInput frame;
    const GLint max_size = max_texture_size;
    if (input.depth_width <= 0 || input.depth_height <= 0 || input.depth_width > max_size ||
        input.depth_height > max_size) {
        return Error::make(OBSCURA_STATUS_INVALID_SIZE, "depth size %dx%d must be within 1..%d", input.depth_width,
                           input.depth_height, max_size);
    }
    frame.width = input.depth_width;
    frame.height = input.depth_height;
    frame.host_width = frame.width;
    frame.host_height = frame.height;

    obscura_rect rect = input.output_rect;
    if (rect.x == 0 && rect.y == 0 && rect.width == 0 && rect.height == 0) rect = {0, 0, frame.width, frame.height};
    if (rect.width <= 0 || rect.height <= 0 || rect.x < 0 || rect.y < 0 || rect.width > frame.width - rect.x ||
        rect.height > frame.height - rect.y) {
        return Error::make(OBSCURA_STATUS_INVALID_RECT,
                           "output_rect (%d, %d, %dx%d) must be non-empty and inside the %dx%d depth texture", rect.x,
                           rect.y, rect.width, rect.height, frame.width, frame.height);
    }
    frame.output_rect = rect;

    const int32_t depth_kind = stored_enum(input.depth_kind);
    if (depth_kind != OBSCURA_DEPTH_HARDWARE && depth_kind != OBSCURA_DEPTH_LINEAR_VIEW) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "depth_kind = %d is not an obscura_depth_kind", int(depth_kind));
    }
    frame.depth_linear = depth_kind == OBSCURA_DEPTH_LINEAR_VIEW;

    float m2v = input.meters_to_view_units == 0.0f ? 1.0f : input.meters_to_view_units;
    if (!std::isfinite(m2v) || m2v <= 0.0f || m2v > 1e6f) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "meters_to_view_units = %g must be in (0, 1e6]",
                           double(input.meters_to_view_units));
    }
    frame.meters_to_view_units = m2v;

    const int32_t layout = stored_enum(input.projection_layout);
    const int32_t clip_depth = stored_enum(input.clip_depth);
    if (layout != OBSCURA_MATRIX_COLUMN_MAJOR && layout != OBSCURA_MATRIX_ROW_MAJOR) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "projection_layout = %d is not an obscura_matrix_layout",
                           int(layout));
    }
    if (clip_depth != OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE && clip_depth != OBSCURA_CLIP_DEPTH_ZERO_TO_ONE) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "clip_depth = %d is not an obscura_clip_depth", int(clip_depth));
    }
    Error error = decode_projection(input.projection, obscura_matrix_layout(layout), obscura_clip_depth(clip_depth),
                                    obscura_depth_kind(depth_kind), &frame.projection);
    if (error) return error;
    frame.depth_texture = input.depth_texture;
    frame.normal_texture = input.normal_texture;
    error = check_temporal_fields(input, layout, &frame);
    if (error) return error;
    *out = frame;
    return Error();
}

Error check_input_textures(const gl::TextureTargets& targets, const obscura_input& input, FrameInput* out) {
    const gl::Table& gl = targets.gl;
    FrameInput frame = *out;

    // Depth texture: a 2D or 2D multisample texture of the stated size and a readable format.
    if (input.depth_texture == 0 || !gl.IsTexture(input.depth_texture)) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "depth_texture %u is not a texture name",
                           input.depth_texture);
    }
    gl.ActiveTexture(GL_TEXTURE0 + OBSCURA_UNIT_DEPTH);
    GLenum target = GL_TEXTURE_2D;
    if (!texture_has_target(targets, input.depth_texture, GL_TEXTURE_2D)) {
        target = GL_TEXTURE_2D_MULTISAMPLE;
        if (!texture_has_target(targets, input.depth_texture, GL_TEXTURE_2D_MULTISAMPLE)) {
            return Error::make(OBSCURA_STATUS_INVALID_TEXTURE,
                               "depth_texture %u is neither GL_TEXTURE_2D nor GL_TEXTURE_2D_MULTISAMPLE",
                               input.depth_texture);
        }
    }
    frame.depth_multisample = target == GL_TEXTURE_2D_MULTISAMPLE;
    GLint width = 0, height = 0, format = 0;
    const GLint level = gl::texture_base_level(gl, target);
    gl.GetTexLevelParameteriv(target, level, GL_TEXTURE_WIDTH, &width);
    gl.GetTexLevelParameteriv(target, level, GL_TEXTURE_HEIGHT, &height);
    gl.GetTexLevelParameteriv(target, level, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (width != frame.width || height != frame.height) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE,
                           "depth_texture %u is %dx%d at its base level %d but depth size says %dx%d",
                           input.depth_texture, width, height, level, frame.width, frame.height);
    }
    frame.depth_format = GLenum(format);
    if (frame.depth_linear) {
        if (format != GL_R32F && format != GL_R16F) {
            return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                               "linear view depth must be GL_R32F or GL_R16F (texture %u has format 0x%04X)",
                               input.depth_texture, unsigned(format));
        }
    } else if (!is_hardware_depth_format(GLenum(format))) {
        return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                           "hardware depth must be a GL_DEPTH_COMPONENT* or depth-stencil format (texture %u has "
                           "format 0x%04X); linear depth needs depth_kind = OBSCURA_DEPTH_LINEAR_VIEW",
                           input.depth_texture, unsigned(format));
    }
    if (is_depth_stencil_format(GLenum(format))) {
        GLint mode = GL_DEPTH_COMPONENT;
        gl.GetTexParameteriv(target, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
        if (mode != GL_DEPTH_COMPONENT) frame.host_depth_stencil_mode = mode;  // the depth preparation switches it
    }
    gl.BindTexture(target, 0);

    // Optional normals: a 2D texture of the same size with a signed or unsigned-normalised RGB(A) format.
    if (input.normal_texture != 0) {
        GLenum normal_format = 0;
        Error error = check_companion_texture(targets, input.normal_texture, "normal_texture", OBSCURA_UNIT_NORMALS, frame,
                                              &normal_format);
        if (error) return error;
        frame.normal_mode = normal_mode_for_format(normal_format);
        if (frame.normal_mode < 0) {
            return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                               "normal_texture %u has format 0x%04X; use a float, snorm or unorm RGB(A) format",
                               input.normal_texture, unsigned(normal_format));
        }
    } else {
        frame.normal_mode = OBSCURA_NORMALS_RECONSTRUCT;
    }

    // Optional motion vectors: a 2D texture of the depth's size with two float channels.
    if (input.motion_vector_texture != 0) {
        GLenum motion_format = 0;
        Error error = check_companion_texture(targets, input.motion_vector_texture, "motion_vector_texture",
                                              OBSCURA_UNIT_MOTION, frame, &motion_format);
        if (error) return error;
        if (motion_format != GL_RG16F && motion_format != GL_RG32F) {
            return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                               "motion_vector_texture %u has format 0x%04X; use GL_RG16F or GL_RG32F",
                               input.motion_vector_texture, unsigned(motion_format));
        }
    }
    *out = frame;
    return Error();
}

}  // namespace obscura
