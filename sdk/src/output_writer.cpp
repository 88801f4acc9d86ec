#include "output_writer.h"

#include <optional>

#include "gl/state_guard.h"

namespace obscura {
namespace {
// Blit targets compose into a staging texture: RGBA16F for float attachments (MULTIPLY keeps HDR).
GLenum staging_format(const OutputTarget& target) { return target.attachment_float ? GL_RGBA16F : GL_RGBA8; }
}  // namespace

Error OutputWriter::prepare(const PassEnv& env, const OutputTarget& target, const obscura_rect& rect) {
    const gl::Table& gl = env.gl;
    const GLenum format = staging_format(target);
    Error error = composite_.prepare(env, target.kind == TargetKind::Image ? target.format : format);
    if (error) return error;
    if (target.kind != TargetKind::Blit) {
        staging_ = gl::Texture2D();  // a texture target again: the blit's staging is not needed
        return Error();
    }
    if (staging_ && staging_.width() == rect.width && staging_.height() == rect.height &&
        staging_.internal_format() == format) {
        return Error();
    }
    staging_ = env.create_texture(format, rect.width, rect.height);
    if (!staging_framebuffer_) staging_framebuffer_ = gl::create_framebuffer(gl);
    if (!staging_) return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the staging texture failed");
    gl.BindFramebuffer(GL_FRAMEBUFFER, staging_framebuffer_.name());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, staging_.name(), 0);
    return Error();
}

OutputTarget OutputWriter::composite_target(const OutputTarget& target) {
    OutputTarget composite = target;
    if (target.kind == TargetKind::Blit) {
        composite.x = 0;
        composite.y = 0;
    }
    return composite;
}

void OutputWriter::write(const PassEnv& env, const UniformRange& frame, const FrameInput& input,
                         const gl::Texture2D& source, const FrameResources& resources, const OutputTarget& target) {
    const gl::Table& gl = env.gl;
    const obscura_rect& rect = input.output_rect;
    if (target.kind == TargetKind::Image) {
        composite_.run(env, frame, rect, source, resources, target.texture, target.format);
        return;
    }
    gl::BlitStateGuard blit_state(gl);
    const GLuint host = blit_framebuffer(gl, target);
    std::optional<gl::AttachmentZeroScope> attachment_zero;
    if (host != 0 && host == target.framebuffer) attachment_zero.emplace(gl, host);
    // Multiply needs the framebuffer's colour first: blit it into the staging texture.
    if (target.blend == OBSCURA_BLEND_MULTIPLY) {
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, host);
        gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, staging_framebuffer_.name());
        gl.BlitFramebuffer(target.x, target.y, target.x + rect.width, target.y + rect.height, 0, 0, rect.width,
                           rect.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    composite_.run(env, frame, rect, source, resources, staging_.name(), staging_.internal_format());
    gl.MemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, staging_framebuffer_.name());
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, host);
    gl.BlitFramebuffer(0, 0, rect.width, rect.height, target.x, target.y, target.x + rect.width,
                       target.y + rect.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void OutputWriter::release() {
    staging_ = gl::Texture2D();
    staging_framebuffer_ = gl::Object();
}

GLuint OutputWriter::blit_framebuffer(const gl::Table& gl, const OutputTarget& target) {
    if (target.framebuffer == 0) return 0;  // the default framebuffer: its own draw/read buffer
    // A layer of an array, 3D or cube-map-array texture: the host's framebuffer itself (narrowed to
    // attachment 0 by the caller), because the layer cannot be read back everywhere (Mesa 22 reports
    // GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER 0 for a cube-map-array layer it renders to correctly).
    if (target.attachment_by_layer) return target.framebuffer;
    if (!target_framebuffer_) target_framebuffer_ = gl::create_framebuffer(gl);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, target_framebuffer_.name());
    if (target.attachment_type == GL_RENDERBUFFER) {
        gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        gl.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target.attachment_name);
    } else {
        // Attach the very image the host attached: glFramebufferTexture would attach a whole cube level
        // as a layered image, and a blit into that writes face 0 only.
        gl.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, 0);
        if (target.attachment_face != GL_NONE) {
            gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target.attachment_face,
                                    target.attachment_name, target.attachment_level);
        } else {
            gl.FramebufferTexture(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target.attachment_name,
                                  target.attachment_level);
        }
    }
    return target_framebuffer_.name();
}

}  // namespace obscura
