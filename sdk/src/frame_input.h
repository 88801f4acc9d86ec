// Validation of the per-frame input and output against the GL objects they name, producing the
// decoded facts the passes need. Runs under a StateGuard (it probes texture targets by binding).
#ifndef OBSCURA_FRAME_INPUT_H
#define OBSCURA_FRAME_INPUT_H

#include "error.h"
#include "gl/gl_objects.h"
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
    // Depth-stencil textures sample stencil when the host set GL_DEPTH_STENCIL_TEXTURE_MODE to it; the
    // mode is switched to depth for the frame and this value restored afterwards (0: untouched).
    GLint restore_depth_stencil_mode = 0;
};

enum class TargetKind {
    Image, // compute writes the host texture (or the FBO's texture attachment) directly
    Blit   // renderbuffer or default framebuffer: compose into a staging texture, blit into the FBO
};

struct OutputTarget {
    TargetKind kind = TargetKind::Image;
    GLuint texture = 0;        // Image: the host texture
    GLenum format = 0;         // Image: its internal format
    GLuint framebuffer = 0;    // Blit: the host framebuffer (0 = default)
    // Blit into a host framebuffer object: its colour attachment 0, which the SDK attaches to a framebuffer
    // of its own so the blit reaches that attachment alone (not every draw buffer of the host's FBO).
    GLenum attachment_type = GL_NONE;  // GL_RENDERBUFFER or GL_TEXTURE (0 for the default framebuffer)
    GLuint attachment_name = 0;
    GLint attachment_level = 0;
    // Which image of that texture level the host attached: a cube map face (GL_TEXTURE_CUBE_MAP_POSITIVE_X...),
    // or a layer of an array / 3D / cube-map-array texture (attachment_by_layer: the blit then goes to the
    // host's framebuffer itself, since drivers do not all report the layer).
    GLenum attachment_face = GL_NONE;
    bool attachment_by_layer = false;
    bool attachment_float = false;     // float attachment: stage in RGBA16F so MULTIPLY keeps HDR values
    int x = 0, y = 0;
    obscura_blend_mode blend = OBSCURA_BLEND_OVERWRITE;
    obscura_debug_view debug_view = OBSCURA_DEBUG_NONE;
};

// Checks every field of `input` and the textures it names. Errors: INVALID_SIZE, INVALID_RECT,
// INVALID_TEXTURE, UNSUPPORTED_FORMAT, INVALID_PROJECTION, PROJECTION_TRANSPOSED, INVALID_ENUM, INVALID_SETTING.
Error validate_input(const gl::Table& gl, const obscura_input& input, GLint max_texture_size, FrameInput* out);

// Undoes the temporary texture-parameter changes validate_input made (depth-stencil texture mode).
void restore_input_state(const gl::Table& gl, const FrameInput& input);

// Checks `output` (texture, or framebuffer and its attachment) for a render of `rect` size.
// Errors: INVALID_TEXTURE, UNSUPPORTED_FORMAT, INVALID_RECT, INVALID_FRAMEBUFFER, INVALID_ENUM.
Error validate_output(const gl::Table& gl, const obscura_output& output, const obscura_rect& rect, OutputTarget* out);

// GLSL image format qualifier for a texture internal format the composite pass can write, or nullptr.
const char* image_format_qualifier(GLenum internal_format, int* channels);

}  // namespace obscura

#endif  // OBSCURA_FRAME_INPUT_H
