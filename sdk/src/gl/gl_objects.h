// Move-only RAII owners for the GL objects the SDK creates. Each remembers the function table it
// was created with; destruction needs the same GL context current (obscura_destroy_context's contract).
#ifndef OBSCURA_GL_OBJECTS_H
#define OBSCURA_GL_OBJECTS_H

#include <cstdint>
#include <utility>

#include "gl/gl_api.h"

namespace obscura::gl {

using Table = ObscuraGladGLContext;

enum class ObjectKind { Texture, Buffer, Program, Shader, Sampler, Query, Framebuffer };

class Object {
public:
    Object() = default;
    Object(const Table* gl, ObjectKind kind, GLuint name) : gl_(gl), kind_(kind), name_(name) {}
    ~Object() { reset(); }
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;
    Object(Object&& other) noexcept { *this = std::move(other); }
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            reset();
            gl_ = other.gl_;
            kind_ = other.kind_;
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    GLuint name() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset();

private:
    const Table* gl_ = nullptr;
    ObjectKind kind_ = ObjectKind::Texture;
    GLuint name_ = 0;
};

// Immutable-storage 2D texture with its size and byte count (for the memory report).
class Texture2D {
public:
    Texture2D() = default;
    // Allocates storage for `levels` MIP levels; returns an empty texture if GL reports an error (out of memory).
    static Texture2D create(const Table& gl, GLenum internal_format, int width, int height, int levels = 1);
    GLuint name() const { return object_.name(); }
    explicit operator bool() const { return static_cast<bool>(object_); }
    int width() const { return width_; }
    int height() const { return height_; }
    GLenum internal_format() const { return format_; }
    int levels() const { return levels_; }
    uint64_t bytes() const { return bytes_; }

private:
    Object object_;
    int width_ = 0, height_ = 0, levels_ = 0;
    GLenum format_ = 0;
    uint64_t bytes_ = 0;
};

// Immutable-storage buffer (glBufferData with DYNAMIC_DRAW; 4.3 has no glBufferStorage).
class Buffer {
public:
    Buffer() = default;
    static Buffer create(const Table& gl, GLenum target, uint64_t size);
    GLuint name() const { return object_.name(); }
    uint64_t bytes() const { return bytes_; }

private:
    Object object_;
    uint64_t bytes_ = 0;
};

// A buffer texture that reads `buffer` as texels of `internal_format` (texelFetch on a samplerBuffer): CPU
// rasterisers fetch texels with vector gathers, where they load storage buffers one invocation at a time.
// Binds on the active unit (the caller's StateGuard restores it); empty if GL reports an error.
Object create_buffer_texture(const Table& gl, GLenum internal_format, GLuint buffer);

// An immutable-storage 3D texture (one level); binds on the active unit (the caller's StateGuard restores it);
// empty if GL reports an error.
Object create_texture_3d(const Table& gl, GLenum internal_format, int width, int height, int depth);

Object create_sampler_nearest_clamp(const Table& gl);
// Linear filtering, clamped, no MIP levels (FFAO's estimator table).
Object create_sampler_linear_clamp(const Table& gl);
// The same, with nearest MIP selection: texelFetch of levels above 0 needs a mipmapped minification filter.
Object create_sampler_nearest_mipmap_clamp(const Table& gl);
Object create_query(const Table& gl);
Object create_framebuffer(const Table& gl);

// Bytes per texel of the internal formats the SDK allocates (0 for unknown).
uint32_t bytes_per_texel(GLenum internal_format);

constexpr GLenum kGlContextLostError = 0x0507;  // GL_CONTEXT_LOST (GL 4.5; the loader is generated for 4.3)
// GL 4.4 / ARB_query_buffer_object: a buffer bound here turns glGetQueryObject*'s pointer into an offset into it.
constexpr GLenum kGlQueryBuffer = 0x9192;         // GL_QUERY_BUFFER
constexpr GLenum kGlQueryBufferBinding = 0x9193;  // GL_QUERY_BUFFER_BINDING
// Drains the GL error queue (GL hands several pending errors back in no set order): GL_CONTEXT_LOST, else
// GL_OUT_OF_MEMORY if either was pending (what failed, whatever an INVALID_* from a call that went on without the
// memory says), else the first error; GL_NO_ERROR if none. The creators below use it, so that an allocation that
// failed leaves nothing pending for the host.
GLenum take_errors(const Table& gl);

}  // namespace obscura::gl

#endif  // OBSCURA_GL_OBJECTS_H
