#include "host_gl_program.h"

#include <stdexcept>
#include <string>

namespace obscura::samples {
namespace {

GLuint compile_shader(GLenum stage, const char* source, const char* what) {
    const GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint compiled = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw std::runtime_error(std::string(what) + (stage == GL_VERTEX_SHADER ? " vertex" : " fragment") +
                                 " shader failed to compile: " + log);
    }
    return shader;
}

}  // namespace

HostProgram link_host_program(const char* vertex_source, const char* fragment_source, const char* what) {
    HostProgram program = HostProgram::create();
    const GLuint vertex = compile_shader(GL_VERTEX_SHADER, vertex_source, what);
    GLuint fragment = 0;
    try {
        fragment = compile_shader(GL_FRAGMENT_SHADER, fragment_source, what);
    } catch (...) {
        glDeleteShader(vertex);
        throw;
    }
    glAttachShader(program.get(), vertex);
    glAttachShader(program.get(), fragment);
    glLinkProgram(program.get());
    // Attached shaders are deleted with the program; flag them now.
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint linked = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &linked);
    if (!linked) {
        char log[2048] = {};
        glGetProgramInfoLog(program.get(), sizeof log, nullptr, log);
        throw std::runtime_error(std::string(what) + " program failed to link: " + log);
    }
    return program;
}

}  // namespace obscura::samples
