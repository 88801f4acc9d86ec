// Composite: the output rectangle's AO (or a debug view) into the host's target, overwriting or
// multiplying (sdk/glsl/composite.comp, one program per target format, built on first use).
#ifndef OBSCURA_COMPOSITE_H
#define OBSCURA_COMPOSITE_H

#include "frame_input.h"
#include "passes/pass_common.h"

namespace obscura {

class CompositePass {
public:
    Error prepare(const PassEnv& env, GLenum format);
    // Writes `rect` of `source` (plus the debug sources) into `target_texture` at frame.target_params.xy.
    void run(const PassEnv& env, const UniformRange& frame, const obscura_rect& rect, const gl::Texture2D& source,
             const FrameResources& resources, GLuint target_texture, GLenum format);

private:
    struct Variant {
        GLenum format = 0;
        gl::Object program;
    };
    Variant* find(GLenum format);
    static constexpr int kMaxVariants = 16;
    Variant variants_[kMaxVariants];
};

}  // namespace obscura

#endif  // OBSCURA_COMPOSITE_H
