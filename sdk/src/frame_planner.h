// FramePlanner: turns a technique's plan into the regions of the frame's passes, and collects the frame's
// uniform blocks (the shared FrameConstants per region, then the technique's) for one upload per frame.
#ifndef OBSCURA_FRAME_PLANNER_H
#define OBSCURA_FRAME_PLANNER_H

#include "frame_input.h"
#include "output_writer.h"
#include "technique.h"

namespace obscura {

class FramePlanner final : public UniformWriter {
public:
    // The uniform buffer every frame's blocks go to. `alignment`: GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT.
    void create(const gl::Table& gl, GLint alignment);
    GLuint uniform_buffer() const { return buffer_.name(); }
    uint64_t bytes() const { return buffer_.bytes(); }

    // AO is computed where the reconstruction will read it: the output rectangle and the plan's apron on both
    // axes (on whole 2x2 quads if the plan asks); the horizontal pass covers the rows the vertical one reads.
    static FrameRegions regions(const FrameInput& input, const TechniquePlan& plan);
    // Starts a frame's blocks with the shared constants of each region. `target`: as the composite writes it.
    FrameUniforms begin(const FrameInput& input, const OutputTarget& target, const FrameRegions& regions,
                        const TechniquePlan& plan);
    UniformRange frame_constants(const Region& work) override;
    // After a reduced-resolution frame: the host frame's constants over its output rectangle, for the passes that
    // work on the host's texels (the upsample, the composite). `ao_reduced`: the composite reads a working-size AO
    // (the raw debug views) rather than the upsampled one.
    UniformRange host_constants(const FrameInput& host, const OutputTarget& target, const TechniquePlan& plan,
                                int shift, bool ao_reduced);
    // Uploads the frame's blocks (after the technique wrote its own).
    void upload(const gl::Table& gl) { arena_.upload(gl, buffer_.name()); }

protected:
    UniformArena& arena() override { return arena_; }

private:
    gl::Buffer buffer_;
    GLint alignment_ = 256;
    UniformArena arena_;
    FrameConstants base_ = {};  // the frame's constants without the work rectangle
};

}  // namespace obscura

#endif  // OBSCURA_FRAME_PLANNER_H
