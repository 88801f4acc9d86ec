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
    // The target formats the composite writes (image_format_qualifier's table; output_writer.cpp checks the count).
    static constexpr int kFormats = 14;

private:
    struct Program {
        CompositeVariant variant;
        gl::Object program;
    };
    Program* find(const CompositeVariant& variant);
    // Room for every variant: each format, with and without debug views, overwriting and multiplying (it held 32
    // once, and an editor cycling blend modes and debug views over 9 formats got INTERNAL_ERROR).
    static constexpr int kMaxVariants = kFormats * 2 * 2;
    Program programs_[kMaxVariants];
};

}  // namespace obscura

#endif  // OBSCURA_COMPOSITE_H
