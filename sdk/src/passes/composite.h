// Composite: the output rectangle's AO (or a debug view) into the host's target, overwriting or
// multiplying (sdk/glsl/composite.comp, one program per target format, debug views and blend, built on first use).
#ifndef OBSCURA_COMPOSITE_H
#define OBSCURA_COMPOSITE_H

#include "frame_input.h"
#include "passes/pass_common.h"

namespace obscura {

// A composite program: the target's format, whether a debug view can show, whether it multiplies.
struct CompositeVariant {
    GLenum format = 0;
    bool debug_views = false;
    bool multiply = false;
    bool operator==(const CompositeVariant& o) const {
        return format == o.format && debug_views == o.debug_views && multiply == o.multiply;
    }
};

class CompositePass {
public:
    Error prepare(const PassEnv& env, const CompositeVariant& variant);
    // Writes `rect` of `source` (plus the debug sources) into `target_texture` at frame.target_params.xy.
    void run(const PassEnv& env, const UniformRange& frame, const obscura_rect& rect, const gl::Texture2D& source,
             const FrameResources& resources, GLuint target_texture, const CompositeVariant& variant);

private:
    struct Program {
        CompositeVariant variant;
        gl::Object program;
    };
    Program* find(const CompositeVariant& variant);
    static constexpr int kMaxVariants = 32;
    Program programs_[kMaxVariants];
};

}  // namespace obscura

#endif  // OBSCURA_COMPOSITE_H
