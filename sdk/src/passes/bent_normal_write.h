// BentNormalWrite: the technique's bent normals for the output rectangle into the host's bent-normal texture
// (sdk/glsl/bent_normal_write.comp, one program per target format, built on first use).
#ifndef OBSCURA_BENT_NORMAL_WRITE_H
#define OBSCURA_BENT_NORMAL_WRITE_H

#include "passes/pass_common.h"

namespace obscura {

// The formats a host's bent-normal texture may have (RGBA8, RGBA16F, RGBA32F).
bool is_bent_normal_format(GLenum format);

class BentNormalWritePass {
public:
    Error prepare(const PassEnv& env, GLenum format);
    static BentNormalWriteConstants constants(int x, int y);
    // Writes `rect` of `source` (RGBA16F: visibility, bent normal) into `target` (of `format`) at the pass's offset.
    void run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const obscura_rect& rect,
             const gl::Texture2D& source, GLuint target, GLenum format);

private:
    gl::Object programs_[3];  // RGBA8, RGBA16F, RGBA32F
};

}  // namespace obscura

#endif  // OBSCURA_BENT_NORMAL_WRITE_H
