#include "gl/state_guard.h"

namespace obscura::gl {

void StateGuard::save_indexed(const Table& gl, GLenum binding_pname, GLenum start_pname, GLenum size_pname,
                              IndexedBuffer* bindings, int count) {
    for (int index = 0; index < count; ++index) {
        gl.GetIntegeri_v(binding_pname, GLuint(index), &bindings[index].name);
        gl.GetInteger64i_v(start_pname, GLuint(index), &bindings[index].start);
        gl.GetInteger64i_v(size_pname, GLuint(index), &bindings[index].size);
    }
}

void StateGuard::restore_indexed(const Table& gl, GLenum target, const IndexedBuffer* bindings, int count) {
    for (int index = 0; index < count; ++index) {
        const IndexedBuffer& binding = bindings[index];
        if (binding.name != 0 && binding.size > 0) {
            gl.BindBufferRange(target, GLuint(index), GLuint(binding.name), GLintptr(binding.start),
                               GLsizeiptr(binding.size));
        } else {
            gl.BindBufferBase(target, GLuint(index), GLuint(binding.name));
        }
    }
}

StateGuard::StateGuard(const Table& gl) : gl_(gl) {
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &program_);
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
    for (int unit = 0; unit < OBSCURA_TEXTURE_UNIT_COUNT; ++unit) {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &texture_2d_[unit]);
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE, &texture_2d_ms_[unit]);
        gl.GetIntegerv(GL_TEXTURE_BINDING_BUFFER, &texture_buffer_[unit]);
        gl.GetIntegerv(GL_TEXTURE_BINDING_3D, &texture_3d_[unit]);
        gl.GetIntegerv(GL_SAMPLER_BINDING, &sampler_[unit]);
    }
    gl.ActiveTexture(GLenum(active_texture_));
    for (int unit = 0; unit < OBSCURA_IMAGE_UNIT_COUNT; ++unit) {
        ImageUnit& image = image_[unit];
        gl.GetIntegeri_v(GL_IMAGE_BINDING_NAME, GLuint(unit), &image.name);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_LEVEL, GLuint(unit), &image.level);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYERED, GLuint(unit), &image.layered);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYER, GLuint(unit), &image.layer);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_ACCESS, GLuint(unit), &image.access);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_FORMAT, GLuint(unit), &image.format);
    }
    gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniform_buffer_);
    save_indexed(gl, GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE, uniform_indexed_,
                 OBSCURA_UBO_COUNT);
    gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &storage_buffer_);
    save_indexed(gl, GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START, GL_SHADER_STORAGE_BUFFER_SIZE,
                 storage_indexed_, OBSCURA_SSBO_COUNT);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
}

StateGuard::~StateGuard() {
    const Table& gl = gl_;
    // A host program deleted while current lives only while it is bound: once the SDK bound its own, GL deleted it.
    // It cannot come back (UseProgram would raise INVALID_VALUE and leave the SDK's program bound): 0 instead.
    gl.UseProgram(program_ != 0 && !gl.IsProgram(GLuint(program_)) ? 0u : GLuint(program_));
    for (int unit = 0; unit < OBSCURA_TEXTURE_UNIT_COUNT; ++unit) {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        gl.BindTexture(GL_TEXTURE_2D, GLuint(texture_2d_[unit]));
        gl.BindTexture(GL_TEXTURE_2D_MULTISAMPLE, GLuint(texture_2d_ms_[unit]));
        gl.BindTexture(GL_TEXTURE_BUFFER, GLuint(texture_buffer_[unit]));
        gl.BindTexture(GL_TEXTURE_3D, GLuint(texture_3d_[unit]));
        gl.BindSampler(GLuint(unit), GLuint(sampler_[unit]));
    }
    gl.ActiveTexture(GLenum(active_texture_));
    for (int unit = 0; unit < OBSCURA_IMAGE_UNIT_COUNT; ++unit) {
        const ImageUnit& image = image_[unit];
        // An unbound unit reports format 0 on some drivers; GL_R8 is the spec's initial value.
        GLenum format = image.format != 0 ? GLenum(image.format) : GL_R8;
        GLenum access = image.access != 0 ? GLenum(image.access) : GL_READ_ONLY;
        gl.BindImageTexture(GLuint(unit), GLuint(image.name), image.level, GLboolean(image.layered), image.layer,
                            access, format);
    }
    // Indexed binds also change the generic binding, so the generic one is restored last.
    restore_indexed(gl, GL_UNIFORM_BUFFER, uniform_indexed_, OBSCURA_UBO_COUNT);
    gl.BindBuffer(GL_UNIFORM_BUFFER, GLuint(uniform_buffer_));
    restore_indexed(gl, GL_SHADER_STORAGE_BUFFER, storage_indexed_, OBSCURA_SSBO_COUNT);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, GLuint(storage_buffer_));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_framebuffer_));
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_framebuffer_));
}

BlitStateGuard::BlitStateGuard(const Table& gl) : gl_(gl) {
    GLint viewports = 1;
    gl.GetIntegerv(GL_MAX_VIEWPORTS, &viewports);
    viewports_ = viewports < 1 ? 1 : (viewports > kMaxViewports ? kMaxViewports : viewports);
    // glDisable(GL_SCISSOR_TEST) clears every index, so each index is saved on its own.
    for (int i = 0; i < viewports_; ++i) scissor_[i] = gl.IsEnabledi(GL_SCISSOR_TEST, GLuint(i));
    rasterizer_discard_ = gl.IsEnabled(GL_RASTERIZER_DISCARD);
    gl.Disable(GL_SCISSOR_TEST);
    gl.Disable(GL_RASTERIZER_DISCARD);  // NVIDIA drops blits while it is on
}

BlitStateGuard::~BlitStateGuard() {
    for (int i = 0; i < viewports_; ++i) {
        if (scissor_[i]) gl_.Enablei(GL_SCISSOR_TEST, GLuint(i));
    }
    if (rasterizer_discard_) gl_.Enable(GL_RASTERIZER_DISCARD);
}

AttachmentZeroScope::AttachmentZeroScope(const Table& gl, GLuint framebuffer) : gl_(gl), framebuffer_(framebuffer) {
    GLint max_draw_buffers = 1;
    gl.GetIntegerv(GL_MAX_DRAW_BUFFERS, &max_draw_buffers);
    draw_buffer_count_ = max_draw_buffers < 1 ? 1 : (max_draw_buffers > kMaxDrawBuffers ? kMaxDrawBuffers : max_draw_buffers);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    for (int i = 0; i < draw_buffer_count_; ++i) {
        GLint buffer = GL_NONE;
        gl.GetIntegerv(GLenum(GL_DRAW_BUFFER0 + i), &buffer);
        draw_buffers_[i] = GLenum(buffer);
    }
    gl.GetIntegerv(GL_READ_BUFFER, &read_buffer_);
    if (framebuffer == 0) {
        // ReadBuffer takes no FRONT_AND_BACK: both are written there, read the front (every default framebuffer
        // has one). NONE draws nothing: the read buffer stays.
        const GLenum drawn = draw_buffers_[0] == GL_FRONT_AND_BACK ? GLenum(GL_FRONT) : draw_buffers_[0];
        if (drawn != GL_NONE) gl.ReadBuffer(drawn);
        return;
    }
    const GLenum attachment_zero = GL_COLOR_ATTACHMENT0;
    gl.DrawBuffers(1, &attachment_zero);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
}

AttachmentZeroScope::~AttachmentZeroScope() {
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    if (framebuffer_ != 0) gl_.DrawBuffers(draw_buffer_count_, draw_buffers_);
    gl_.ReadBuffer(GLenum(read_buffer_));
}

}  // namespace obscura::gl
