// Upsample: a reduced-resolution frame's result back to the host's texels over the output rectangle, weighed by
// each reduced texel's tangent plane (sdk/glsl/upsample.comp). It writes the visibility into the host's target
// itself (the composite's write, fused: without a debug view the composite would only copy it there), or into a
// full-size R16F result it owns for the composite's debug views; and RGBA16F bent normals when the frame has them.
#ifndef OBSCURA_UPSAMPLE_H
#define OBSCURA_UPSAMPLE_H

#include "frame_input.h"
#include "gl/program_cache.h"
#include "output_writer.h"
#include "passes/pass_common.h"

namespace obscura {

class UpsamplePass {
public:
    // Builds the variant for the host's depth kind, the outputs and the destination (the host's target image, or with
    // format 0 the pass's own R16F result), and (re)creates the results for the host's size (the R16F result for
    // destination format 0; once made, it is kept while the size stays).
    Error prepare(const PassEnv& env, const FrameInput& host, bool bent_normals, const TargetWrite& destination);
    // The results alone, for a host texture of width x height (obscura_prepare, which knows no depth kind and no
    // target): the R16F result if `own_result` (or if it exists already).
    Error allocate(const PassEnv& env, int width, int height, bool bent_normals, bool own_result);
    // `reduced`: the frame the method ran on (reduced_frame_input).
    static UpsampleConstants constants(const obscura_resolution_settings& settings, const FrameInput& reduced);
    // `frame`: the host frame's constants over its output rectangle (target_params: where the rectangle lands in the
    // target). Reads the reduced `resources` (depth level 0, normals), `source` (R16F) and `bent_source` (RGBA16F,
    // with bent normals); writes `target_texture` with the prepared destination's format, or its own result (0).
    void run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const FrameInput& host,
             const FrameResources& resources, const gl::Texture2D& source, const gl::Texture2D* bent_source,
             GLuint target_texture = 0);
    bool has_result() const { return static_cast<bool>(ao_); }
    const gl::Texture2D* bent() const { return bent_ ? &bent_ : nullptr; }
    uint64_t bytes() const { return ao_.bytes() + bent_.bytes(); }
    void release();

private:
    gl::ProgramCache<gl::DefineLines> programs_;
    GLuint program_ = 0;  // prepare's variant
    TargetWrite destination_;
    gl::Texture2D ao_, bent_;
};

// The upsample as the output writer's image write: the frame's run, into the image the writer names (the host's
// texture, or a blit's staging texture). Holds references: it lives for the frame's output write.
class UpsampleImageWrite final : public OutputImageWrite {
public:
    UpsampleImageWrite(UpsamplePass& pass, const UniformRange& frame, const UniformRange& constants,
                       const FrameInput& host, const FrameResources& resources, const gl::Texture2D* source,
                       const gl::Texture2D* bent_source)
        : pass_(pass), frame_(frame), constants_(constants), host_(host), resources_(resources), source_(source),
          bent_source_(bent_source) {}
    void write_image(const PassEnv& env, GLuint texture, GLenum) const override {
        pass_.run(env, frame_, constants_, host_, resources_, *source_, bent_source_, texture);
    }

private:
    UpsamplePass& pass_;
    const UniformRange& frame_;
    const UniformRange& constants_;
    const FrameInput& host_;
    const FrameResources& resources_;
    const gl::Texture2D* source_;
    const gl::Texture2D* bent_source_;
};

}  // namespace obscura

#endif  // OBSCURA_UPSAMPLE_H
