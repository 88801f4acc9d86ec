// StateGuard saves, on construction, every binding an SDK call may touch and restores it on
// destruction: program, active texture, texture and sampler bindings on the SDK's units, image units,
// uniform- and storage-buffer bindings (generic and indexed), and read/draw framebuffers. The set mirrors
// shader_interface.h's unit counts; a pass that uses more must grow it. Capabilities that only blits
// care about (scissor, rasterizer discard) are saved by BlitStateGuard, only when a blit happens.
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
    static void save_indexed(const Table& gl, GLenum binding_pname, GLenum start_pname, GLenum size_pname,
                             IndexedBuffer* bindings, int count);
    static void restore_indexed(const Table& gl, GLenum target, const IndexedBuffer* bindings, int count);

    const Table& gl_;
    GLint program_ = 0;
    GLint active_texture_ = 0;
    GLint texture_2d_[OBSCURA_TEXTURE_UNIT_COUNT] = {};
    GLint texture_2d_ms_[OBSCURA_TEXTURE_UNIT_COUNT] = {};
    GLint texture_buffer_[OBSCURA_TEXTURE_UNIT_COUNT] = {};
    GLint texture_3d_[OBSCURA_TEXTURE_UNIT_COUNT] = {};
    GLint sampler_[OBSCURA_TEXTURE_UNIT_COUNT] = {};
    ImageUnit image_[OBSCURA_IMAGE_UNIT_COUNT] = {};
    GLint uniform_buffer_ = 0;
    IndexedBuffer uniform_indexed_[OBSCURA_UBO_COUNT] = {};
    GLint storage_buffer_ = 0;
    IndexedBuffer storage_indexed_[OBSCURA_SSBO_COUNT] = {};
    GLint read_framebuffer_ = 0;
    GLint draw_framebuffer_ = 0;
};

// Saves and disables what would alter or drop a glBlitFramebuffer (the scissor test of every viewport
// index, rasterizer discard) and restores it. sRGB conversion is left to the host's GL_FRAMEBUFFER_SRGB.
class BlitStateGuard {
public:
    explicit BlitStateGuard(const Table& gl);
    ~BlitStateGuard();
    BlitStateGuard(const BlitStateGuard&) = delete;
    BlitStateGuard& operator=(const BlitStateGuard&) = delete;

private:
    static constexpr int kMaxViewports = 32;
    const Table& gl_;
    int viewports_ = 1;
    GLboolean scissor_[kMaxViewports] = {};
    GLboolean rasterizer_discard_ = GL_FALSE;
};

// Narrows a host framebuffer object to its colour attachment 0 for a blit (draw buffers and read
// buffer), and puts the host's buffers back. Binds the framebuffer to both targets: the StateGuard
// restores those bindings. For the default framebuffer (0) the draw buffers stay the host's and the read
// buffer becomes the first of them, so that MULTIPLY reads back the colour it then writes (a host reading
// GL_FRONT while drawing to GL_BACK got the front buffer's colour times the AO).
class AttachmentZeroScope {
public:
    AttachmentZeroScope(const Table& gl, GLuint framebuffer);
    ~AttachmentZeroScope();
    AttachmentZeroScope(const AttachmentZeroScope&) = delete;
    AttachmentZeroScope& operator=(const AttachmentZeroScope&) = delete;

private:
    static constexpr int kMaxDrawBuffers = 32;
    const Table& gl_;
    GLuint framebuffer_;
    int draw_buffer_count_ = 1;
    GLenum draw_buffers_[kMaxDrawBuffers] = {};
    GLint read_buffer_ = GL_NONE;
};

}  // namespace obscura::gl

#endif  // OBSCURA_STATE_GUARD_H
