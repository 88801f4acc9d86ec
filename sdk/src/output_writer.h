// OutputWriter: the last step of a frame, the output rectangle's AO (or a debug view) into the host's target.
// Texture targets (and framebuffer attachments a compute shader can write) are written by the composite pass
// directly; renderbuffers and the default framebuffer get the composite in a staging texture, blitted there.
#ifndef OBSCURA_OUTPUT_WRITER_H
#define OBSCURA_OUTPUT_WRITER_H

#include "frame_input.h"
#include "passes/composite.h"
#include "passes/pass_common.h"

namespace obscura {

class OutputWriter {
public:
    // Builds the composite variant for the target's format and, for a blit target, the staging texture of the
    // output rectangle's size (freed again when the target is a texture).
    Error prepare(const PassEnv& env, const OutputTarget& target, const obscura_rect& rect);
    // The target as the composite writes it: blit targets compose into the staging texture at (0, 0).
    static OutputTarget composite_target(const OutputTarget& target);
    // Writes `source` (or the target's debug view) for the output rectangle into the target. `frame`: the
    // frame's constants for the output rectangle (with composite_target's offset).
    void write(const PassEnv& env, const UniformRange& frame, const FrameInput& input, const gl::Texture2D& source,
               const FrameResources& resources, const OutputTarget& target);
    uint64_t bytes() const { return staging_.bytes(); }
    void release();

private:
    // The framebuffer a blit reaches the host's target through: 0 (default) or ours with the host's colour
    // attachment 0 attached, so only that attachment is read and written.
    GLuint blit_framebuffer(const gl::Table& gl, const OutputTarget& target);
    CompositePass composite_;
    gl::Texture2D staging_;  // RGBA8 or RGBA16F, output-rect sized: blit targets only
    gl::Object staging_framebuffer_;
    gl::Object target_framebuffer_;  // see blit_framebuffer()
};

}  // namespace obscura

#endif  // OBSCURA_OUTPUT_WRITER_H
