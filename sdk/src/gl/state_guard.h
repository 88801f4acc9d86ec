// StateGuard saves, on construction, every piece of GL state an SDK call may touch and restores it
// on destruction: program, active texture, texture and sampler bindings on the SDK's units, image
// units, uniform-buffer bindings (generic and indexed), read/draw framebuffers, and the scissor test
// and rasterizer discard (blits obey them). The set mirrors shader_interface.h's unit counts; a pass that uses more must grow it.
#ifndef OBSCURA_STATE_GUARD_H
#define OBSCURA_STATE_GUARD_H

#include "gl/gl_objects.h"
#include "common/shader_interface.h"

namespace obscura::gl {

class StateGuard {
public:
    explicit StateGuard(const Table& gl);
    ~StateGuard();
    StateGuard(const StateGuard&) = delete;
    StateGuard& operator=(const StateGuard&) = delete;

private:
    struct ImageUnit {
        GLint name, level, layered, layer, access, format;
    };
    struct IndexedBuffer {
        GLint name;
        GLint64 start, size;
    };
    const Table& gl_;
    GLint program_ = 0;
    GLint active_texture_ = 0;
    GLint texture_2d_[OBSCURA_TEXTURE_UNIT_COUNT] = {};
    GLint texture_2d_ms_[OBSCURA_TEXTURE_UNIT_COUNT] = {};
    GLint sampler_[OBSCURA_TEXTURE_UNIT_COUNT] = {};
    ImageUnit image_[OBSCURA_IMAGE_UNIT_COUNT] = {};
    GLint uniform_buffer_ = 0;
    IndexedBuffer uniform_indexed_[OBSCURA_UBO_COUNT] = {};
    GLint read_framebuffer_ = 0;
    GLint draw_framebuffer_ = 0;
    GLboolean scissor_test_ = GL_FALSE;
    GLboolean rasterizer_discard_ = GL_FALSE;
};

}  // namespace obscura::gl

#endif  // OBSCURA_STATE_GUARD_H
