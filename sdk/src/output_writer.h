// The output: its validation in two stages (the fields without GL, then the texture or framebuffer they name),
// and OutputWriter, the last step of a frame: the output rectangle's AO (or a debug view) into the host's target.
// Texture targets (and framebuffer attachments a compute shader can write) are written by the composite pass
// directly; renderbuffers and the default framebuffer get the composite in a staging texture, blitted there.
#ifndef OBSCURA_OUTPUT_WRITER_H
#define OBSCURA_OUTPUT_WRITER_H

#include "frame_input.h"
#include "gl/program_cache.h"
#include "passes/bent_normal_write.h"
#include "passes/composite.h"
#include "passes/pass_common.h"

namespace obscura {

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
    GLuint bent_texture = 0;  // output.bent_normal_texture (at x, y), 0: none
    GLenum bent_format = 0;   // its internal format (RGBA8, RGBA16F, RGBA32F)
};

// Stage 1, no GL: the fields of `output` (blend, debug view, position). Errors: INVALID_ENUM, INVALID_RECT.
Error check_output_fields(const obscura_output& output, OutputTarget* out);
// Stage 2, first (after the host's GL state is checked, so that a pending host error is reported first), no GL call:
// no texture the frame writes (output.texture, output.bent_normal_texture) is one it reads (input.depth_texture,
// normal_texture, motion_vector_texture) or the other one it writes: GL leaves reading and writing one texture in a
// dispatch undefined, and two writes of one texture clobber each other. Error: INVALID_TEXTURE, naming both fields.
// A framebuffer's attachment is compared once check_output_target has found it (check_attachment_aliasing).
Error check_output_aliasing(const obscura_input& input, const obscura_output& output);
// The same for output.framebuffer's colour attachment 0 when it is a texture (written directly or blitted into),
// after check_output_target has filled `target`. Error: INVALID_TEXTURE.
Error check_attachment_aliasing(const obscura_input& input, const obscura_output& output, const OutputTarget& target);
// Stage 2: the texture, or the framebuffer and its attachment, for a result of `rect`'s size, completing `*out`
// from stage 1. Errors: INVALID_TEXTURE, UNSUPPORTED_FORMAT, INVALID_RECT, INVALID_FRAMEBUFFER.
Error check_output_target(const gl::TextureTargets& targets, const obscura_output& output, const obscura_rect& rect,
                          OutputTarget* out);

// Stage 2 for output.bent_normal_texture (when set): a GL_TEXTURE_2D of a bent-normal format the result fits at
// (x, y). Errors: INVALID_TEXTURE, UNSUPPORTED_FORMAT, INVALID_RECT.
Error check_bent_normal_target(const gl::TextureTargets& targets, const obscura_output& output, const obscura_rect& rect,
                               OutputTarget* out);

// GLSL image format qualifier for a texture internal format the composite pass can write, or nullptr.
const char* image_format_qualifier(GLenum internal_format, int* channels);

// How a pass that can write the host's target image in the composite's place is built: the image's format (one of
// image_format_qualifier's) and the blend; format 0: it writes its own result, and the composite the target.
struct TargetWrite {
    GLenum format = 0;
    bool multiply = false;
};
// The write for `target` (its image's format and blend).
TargetWrite target_write(const OutputTarget& target);
// The program of `shader` with the #define lines `pass_defines` and then the ones common/output_target.glsl reads for
// `write`, "OUTPUT_FORMAT <qualifier>\nOUTPUT_MULTIPLY <0|1>\n" (format 0, where the pass writes no target: a
// placeholder): the one kept in `cache`, or built into it. INTERNAL_ERROR for a format without a qualifier.
Error target_variant(const PassEnv& env, const char* shader, const char* pass_defines, const TargetWrite& write,
                     gl::ProgramCache<gl::DefineLines>* cache, GLuint* program);
// Binds the target image `texture` (of `write`'s format) to image `unit` for common/output_target.glsl: read and
// written for the multiply blend, written otherwise.
void bind_target_image(const gl::Table& gl, GLuint unit, GLuint texture, const TargetWrite& write);

// A pass that writes the output rectangle into the image the composite would write (the host's texture, or a blit's
// staging texture), in the composite's place: the upsample at reduced resolution, the temporal pass at full
// resolution, and without either a method's last reconstruction pass (TechniqueOutput::target_write).
class OutputImageWrite {
public:
    // Writes the image `texture` of `format` (OutputWriter::image_format's), the frame's target_params placing the
    // rectangle in it.
    virtual void write_image(const PassEnv& env, GLuint texture, GLenum format) const = 0;

protected:
    ~OutputImageWrite() = default;
};

class OutputWriter {
public:
    // Builds the composite variant for the target's format (unless another pass writes the image: `composite`
    // false) and, for a blit target, the staging texture of the output rectangle's size (freed again when the
    // target is a texture).
    Error prepare(const PassEnv& env, const OutputTarget& target, const obscura_rect& rect, bool composite = true);
    // The target as the composite writes it: blit targets compose into the staging texture at (0, 0).
    static OutputTarget composite_target(const OutputTarget& target);
    // The format of the image the composite writes: the host texture's, or a blit's staging texture's.
    static GLenum image_format(const OutputTarget& target);
    // The uniform block of the bent-normal write (push it with the frame's other blocks).
    static BentNormalWriteConstants bent_constants(const OutputTarget& target);
    // Writes `source` (or the target's debug view) for the output rectangle into the target, or has `image_write`
    // write it there (`source` then unread), and then `bent` (the technique's RGBA16F bent normals) into the
    // target's bent-normal texture when it has one. `frame`: the frame's constants for the output rectangle (with
    // composite_target's offset); `bent_pass`: bent_constants'.
    void write(const PassEnv& env, const UniformRange& frame, const FrameInput& input, const gl::Texture2D& source,
               const FrameResources& resources, const OutputTarget& target, const gl::Texture2D* bent = nullptr,
               const UniformRange& bent_pass = UniformRange(), const OutputImageWrite* image_write = nullptr);
    uint64_t bytes() const { return staging_.bytes(); }
    void release();

private:
    // The output rectangle into the target: composed in place, or into the staging texture and blitted.
    void write_image(const PassEnv& env, const UniformRange& frame, const obscura_rect& rect,
                     const gl::Texture2D& source, const FrameResources& resources, const OutputTarget& target,
                     const OutputImageWrite* image_write);
    // One image of the target's: `image_write`, or the composite of `source`.
    void compose(const PassEnv& env, const UniformRange& frame, const obscura_rect& rect, const gl::Texture2D& source,
                 const FrameResources& resources, const OutputTarget& target, const OutputImageWrite* image_write,
                 GLuint texture, GLenum format);
    // The framebuffer a blit reaches the host's target through: 0 (default) or ours with the host's colour
    // attachment 0 attached, so only that attachment is read and written.
    GLuint blit_framebuffer(const gl::Table& gl, const OutputTarget& target);
    // Attaches nothing to target_framebuffer_ again (binds it to GL_DRAW_FRAMEBUFFER: under the write's guard).
    void detach_target(const gl::Table& gl);
    CompositePass composite_;
    BentNormalWritePass bent_;
    gl::Texture2D staging_;  // RGBA8 or RGBA16F, output-rect sized: blit targets only
    gl::Object staging_framebuffer_;
    gl::Object target_framebuffer_;  // see blit_framebuffer()
};

}  // namespace obscura

#endif  // OBSCURA_OUTPUT_WRITER_H
