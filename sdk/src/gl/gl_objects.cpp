#include "gl/gl_objects.h"

namespace obscura::gl {

void Object::reset() {
    if (name_ == 0 || gl_ == nullptr) {
        name_ = 0;
        return;
    }
    switch (kind_) {
        case ObjectKind::Texture: gl_->DeleteTextures(1, &name_); break;
        case ObjectKind::Buffer: gl_->DeleteBuffers(1, &name_); break;
        case ObjectKind::Program: gl_->DeleteProgram(name_); break;
        case ObjectKind::Shader: gl_->DeleteShader(name_); break;
        case ObjectKind::Sampler: gl_->DeleteSamplers(1, &name_); break;
        case ObjectKind::Query: gl_->DeleteQueries(1, &name_); break;
        case ObjectKind::Framebuffer: gl_->DeleteFramebuffers(1, &name_); break;
    }
    name_ = 0;
}

GLenum take_errors(const Table& gl) {
    GLenum chosen = gl.GetError();
    if (chosen == GL_NO_ERROR) return chosen;
    for (int i = 0; i < 16; ++i) {
        const GLenum next = gl.GetError();
        if (next == GL_NO_ERROR) break;
        if (next == kGlContextLostError || (next == GL_OUT_OF_MEMORY && chosen != kGlContextLostError)) chosen = next;
    }
    return chosen;
}

uint32_t bytes_per_texel(GLenum internal_format) {
    switch (internal_format) {
        case GL_R8: return 1;
        case GL_R16F: case GL_RG8: case GL_R16: return 2;
        case GL_R32F: case GL_RG16F: case GL_RG16_SNORM: case GL_RGBA8: case GL_RGBA8_SNORM: return 4;
        case GL_RG32F: case GL_RGBA16F: return 8;
        case GL_RGBA32F: return 16;
        default: return 0;
    }
}

Texture2D Texture2D::create(const Table& gl, GLenum internal_format, int width, int height, int levels) {
    // The caller holds a StateGuard, so binding on the active unit is restored afterwards.
    GLuint name = 0;
    gl.GenTextures(1, &name);
    gl.BindTexture(GL_TEXTURE_2D, name);
    gl.TexStorage2D(GL_TEXTURE_2D, levels, internal_format, width, height);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    Texture2D texture;
    texture.object_ = Object(&gl, ObjectKind::Texture, name);
    if (take_errors(gl) != GL_NO_ERROR) return Texture2D();
    texture.width_ = width;
    texture.height_ = height;
    texture.format_ = internal_format;
    texture.levels_ = levels;
    for (int level = 0; level < levels; ++level) {
        uint64_t w = uint64_t(width >> level > 0 ? width >> level : 1);
        uint64_t h = uint64_t(height >> level > 0 ? height >> level : 1);
        texture.bytes_ += w * h * bytes_per_texel(internal_format);
    }
    return texture;
}

Buffer Buffer::create(const Table& gl, GLenum target, uint64_t size) {
    GLuint name = 0;
    gl.GenBuffers(1, &name);
    gl.BindBuffer(target, name);
    gl.BufferData(target, GLsizeiptr(size), nullptr, GL_DYNAMIC_DRAW);
    gl.BindBuffer(target, 0);
    Buffer buffer;
    buffer.object_ = Object(&gl, ObjectKind::Buffer, name);
    if (take_errors(gl) != GL_NO_ERROR) return Buffer();
    buffer.bytes_ = size;
    return buffer;
}

Object create_buffer_texture(const Table& gl, GLenum internal_format, GLuint buffer) {
    GLuint name = 0;
    gl.GenTextures(1, &name);
    gl.BindTexture(GL_TEXTURE_BUFFER, name);
    gl.TexBuffer(GL_TEXTURE_BUFFER, internal_format, buffer);
    gl.BindTexture(GL_TEXTURE_BUFFER, 0);
    Object texture(&gl, ObjectKind::Texture, name);
    if (take_errors(gl) != GL_NO_ERROR) return Object();
    return texture;
}

Object create_sampler_nearest_clamp(const Table& gl) {
    GLuint name = 0;
    gl.GenSamplers(1, &name);
    gl.SamplerParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.SamplerParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.SamplerParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.SamplerParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    // A host shadow-map texture may have compare mode on; the sampler object overrides it.
    gl.SamplerParameteri(name, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    return Object(&gl, ObjectKind::Sampler, name);
}

Object create_texture_3d(const Table& gl, GLenum internal_format, int width, int height, int depth) {
    GLuint name = 0;
    gl.GenTextures(1, &name);
    gl.BindTexture(GL_TEXTURE_3D, name);
    gl.TexStorage3D(GL_TEXTURE_3D, 1, internal_format, width, height, depth);
    gl.BindTexture(GL_TEXTURE_3D, 0);
    Object texture(&gl, ObjectKind::Texture, name);
    if (take_errors(gl) != GL_NO_ERROR) return Object();
    return texture;
}

Object create_sampler_linear_clamp(const Table& gl) {
    Object sampler = create_sampler_nearest_clamp(gl);
    gl.SamplerParameteri(sampler.name(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.SamplerParameteri(sampler.name(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.SamplerParameteri(sampler.name(), GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return sampler;
}

Object create_sampler_nearest_mipmap_clamp(const Table& gl) {
    Object sampler = create_sampler_nearest_clamp(gl);
    gl.SamplerParameteri(sampler.name(), GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    return sampler;
}

Object create_query(const Table& gl) {
    GLuint name = 0;
    gl.GenQueries(1, &name);
    return Object(&gl, ObjectKind::Query, name);
}

Object create_framebuffer(const Table& gl) {
    GLuint name = 0;
    gl.GenFramebuffers(1, &name);
    return Object(&gl, ObjectKind::Framebuffer, name);
}

}  // namespace obscura::gl
