// Texture probes: how validation learns a texture's target. GL 4.5 (and ARB_direct_state_access) answers it
// directly, through glGetTextureParameteriv(GL_TEXTURE_TARGET); GL 4.3 can only be told it, by binding the name to a
// target and seeing whether GL accepts it, which raises GL_INVALID_OPERATION for a wrong guess: consumed here, but a
// host with debug output on sees an error every frame. Shared by the input's and the output's validation
// (frame_input.cpp, output_writer.cpp).
#ifndef OBSCURA_GL_TEXTURE_PROBE_H
#define OBSCURA_GL_TEXTURE_PROBE_H

#include <algorithm>

#include "gl/gl_objects.h"

namespace obscura::gl {

// The GL table and, where the context has it (GlDevice), glGetTextureParameteriv (GL 4.5 or
// ARB_direct_state_access; not in the SDK's 4.3 table).
struct TextureTargets {
    using GetTextureParameterivFn = void(GLAD_API_PTR*)(GLuint texture, GLenum name, GLint* value);
    static constexpr GLenum kTextureTarget = 0x1006;  // GL_TEXTURE_TARGET (GL 4.5)

    const Table& gl;
    GetTextureParameterivFn get_texture_parameteriv = nullptr;

    // Whether `texture` is known not to be a texture of `target`, asked without a GL error where the query exists (a
    // name that is no texture object is asked nothing: the query would raise INVALID_OPERATION for it); false where
    // it cannot be asked, and the caller's bind tells.
    bool known_not(GLuint texture, GLenum target) const {
        if (!get_texture_parameteriv) return false;
        if (!gl.IsTexture(texture)) return true;
        GLint actual = GL_NONE;
        get_texture_parameteriv(texture, kTextureTarget, &actual);
        return GLenum(actual) != target;
    }
};

// Binds `texture` to `target` on the current unit and reports whether it is a texture of that target (asked first
// where the context can be asked; else GL's refusal of the bind, INVALID_OPERATION, tells it).
inline bool texture_has_target(const TextureTargets& targets, GLuint texture, GLenum target) {
    if (targets.known_not(texture, target)) return false;
    targets.gl.BindTexture(target, texture);
    bool ok = targets.gl.GetError() == GL_NO_ERROR;
    if (!ok) targets.gl.BindTexture(target, 0);
    return ok;
}

// The level texelFetch's and an image unit's level 0 name of the texture bound to `target` on the active unit: its
// GL_TEXTURE_BASE_LEVEL (a host building a pyramid in place may have moved it), clamped to an immutable texture's
// levels (GL 4.3, 8.17). Multisample textures have one level.
inline GLint texture_base_level(const Table& gl, GLenum target) {
    if (target != GL_TEXTURE_2D) return 0;
    GLint level = 0, immutable = GL_FALSE, levels = 0;
    gl.GetTexParameteriv(target, GL_TEXTURE_BASE_LEVEL, &level);
    gl.GetTexParameteriv(target, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    if (immutable) {
        gl.GetTexParameteriv(target, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
        level = std::clamp(level, 0, std::max(levels - 1, 0));
    }
    return level;
}

inline GLenum binding_query(GLenum target) {
    switch (target) {
        case GL_TEXTURE_2D: return GL_TEXTURE_BINDING_2D;
        case GL_TEXTURE_2D_ARRAY: return GL_TEXTURE_BINDING_2D_ARRAY;
        case GL_TEXTURE_3D: return GL_TEXTURE_BINDING_3D;
        case GL_TEXTURE_CUBE_MAP: return GL_TEXTURE_BINDING_CUBE_MAP;
        case GL_TEXTURE_CUBE_MAP_ARRAY: return GL_TEXTURE_BINDING_CUBE_MAP_ARRAY;
        case GL_TEXTURE_RECTANGLE: return GL_TEXTURE_BINDING_RECTANGLE;
        case GL_TEXTURE_1D: return GL_TEXTURE_BINDING_1D;
        case GL_TEXTURE_1D_ARRAY: return GL_TEXTURE_BINDING_1D_ARRAY;
        case GL_TEXTURE_2D_MULTISAMPLE: return GL_TEXTURE_BINDING_2D_MULTISAMPLE;
        default: return GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY;
    }
}

// Binds `texture` to `target` on the active unit for the probe's lifetime and then puts back the host's
// binding: the state guard restores only the targets the passes use, and a probe may touch any.
class ScopedTextureProbe {
public:
    ScopedTextureProbe(const TextureTargets& targets, GLuint texture, GLenum target) : gl_(targets.gl), target_(target) {
        gl_.GetIntegerv(binding_query(target), &previous_);
        if (targets.known_not(texture, target)) return;
        gl_.BindTexture(target, texture);
        bound_ = gl_.GetError() == GL_NO_ERROR;
    }
    ~ScopedTextureProbe() { gl_.BindTexture(target_, GLuint(previous_)); }
    ScopedTextureProbe(const ScopedTextureProbe&) = delete;
    ScopedTextureProbe& operator=(const ScopedTextureProbe&) = delete;
    bool bound() const { return bound_; }

private:
    const Table& gl_;
    GLenum target_;
    GLint previous_ = 0;
    bool bound_ = false;
};

}  // namespace obscura::gl

#endif  // OBSCURA_GL_TEXTURE_PROBE_H
