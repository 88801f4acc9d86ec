// Upsample: a reduced-resolution frame's result back to the host's texels over the output rectangle, weighed by
// each reduced texel's tangent plane (sdk/glsl/upsample.comp). Owns the full-size result it writes: R16F
// visibility, and RGBA16F bent normals when the frame has them.
#ifndef OBSCURA_UPSAMPLE_H
#define OBSCURA_UPSAMPLE_H

#include "frame_input.h"
#include "passes/pass_common.h"

namespace obscura {

class UpsamplePass {
public:
    // Builds the variant for the host's depth kind and the outputs, and (re)creates the results for the host's size.
    Error prepare(const PassEnv& env, const FrameInput& host, bool bent_normals);
    // The results alone, for a host texture of width x height (obscura_prepare, which knows no depth kind).
    Error allocate(const PassEnv& env, int width, int height, bool bent_normals);
    // `reduced`: the frame the method ran on (reduced_frame_input).
    static UpsampleConstants constants(const obscura_resolution_settings& settings, const FrameInput& reduced);
    // `frame`: the host frame's constants over its output rectangle. Reads the reduced `resources` (depth level 0,
    // normals), `source` (R16F) and `bent_source` (RGBA16F, with bent normals).
    void run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const FrameInput& host,
             const FrameResources& resources, const gl::Texture2D& source, const gl::Texture2D* bent_source);
    const gl::Texture2D& result() const { return ao_; }
    const gl::Texture2D* bent() const { return bent_ ? &bent_ : nullptr; }
    uint64_t bytes() const { return ao_.bytes() + bent_.bytes(); }
    void release();

private:
    gl::Object programs_[4][2];  // [host depth variant][bent normals]
    gl::Texture2D ao_, bent_;
};

}  // namespace obscura

#endif  // OBSCURA_UPSAMPLE_H
