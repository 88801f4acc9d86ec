// Move-only owners of host GL object names (created and deleted through the host loader).
#ifndef OBSCURA_SAMPLES_HOST_GL_OBJECTS_H
#define OBSCURA_SAMPLES_HOST_GL_OBJECTS_H

#include <utility>

#include "host_gl.h"

namespace obscura::samples {

template <typename Traits>
class UniqueGLName {
public:
    UniqueGLName() = default;
    explicit UniqueGLName(GLuint name) : name_(name) {}
    ~UniqueGLName() { reset(); }
    UniqueGLName(UniqueGLName&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
    UniqueGLName& operator=(UniqueGLName&& other) noexcept {
        if (this != &other) {
            reset();
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    UniqueGLName(const UniqueGLName&) = delete;
    UniqueGLName& operator=(const UniqueGLName&) = delete;

    // Generates a new name (glGen* / glCreateProgram).
    static UniqueGLName create() { return UniqueGLName(Traits::create()); }

    GLuint get() const { return name_; }
    // Gives up ownership without deleting.
    GLuint release() { return std::exchange(name_, 0); }
    void reset() {
        if (name_ != 0) Traits::destroy(name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

namespace gl_traits {
struct Texture {
    static GLuint create() { GLuint name = 0; glGenTextures(1, &name); return name; }
    static void destroy(GLuint name) { glDeleteTextures(1, &name); }
};
struct Framebuffer {
    static GLuint create() { GLuint name = 0; glGenFramebuffers(1, &name); return name; }
    static void destroy(GLuint name) { glDeleteFramebuffers(1, &name); }
};
struct Renderbuffer {
    static GLuint create() { GLuint name = 0; glGenRenderbuffers(1, &name); return name; }
    static void destroy(GLuint name) { glDeleteRenderbuffers(1, &name); }
};
struct Buffer {
    static GLuint create() { GLuint name = 0; glGenBuffers(1, &name); return name; }
    static void destroy(GLuint name) { glDeleteBuffers(1, &name); }
};
struct VertexArray {
    static GLuint create() { GLuint name = 0; glGenVertexArrays(1, &name); return name; }
    static void destroy(GLuint name) { glDeleteVertexArrays(1, &name); }
};
struct Program {
    static GLuint create() { return glCreateProgram(); }
    static void destroy(GLuint name) { glDeleteProgram(name); }
};
}  // namespace gl_traits

using HostTexture = UniqueGLName<gl_traits::Texture>;
using HostFramebuffer = UniqueGLName<gl_traits::Framebuffer>;
using HostRenderbuffer = UniqueGLName<gl_traits::Renderbuffer>;
using HostBuffer = UniqueGLName<gl_traits::Buffer>;
using HostVertexArray = UniqueGLName<gl_traits::VertexArray>;
using HostProgram = UniqueGLName<gl_traits::Program>;

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_HOST_GL_OBJECTS_H
