#include "output_writer.h"

#include <cstdio>
#include <optional>

#include "gl/state_guard.h"
#include "gl/texture_probe.h"
#include "host_enum.h"

namespace obscura {
namespace {

using gl::ScopedTextureProbe;
using gl::texture_base_level;
using gl::texture_has_target;

// The target of an attached texture (GL_NONE if none binds), probed in the order hosts most often use.
GLenum attached_texture_target(const gl::TextureTargets& targets, GLuint texture, GLenum cube_face) {
    // Mesa reports a face for a cube-map-array layer too: only a cube map proper is attached by face.
    if (cube_face != GL_NONE && ScopedTextureProbe(targets, texture, GL_TEXTURE_CUBE_MAP).bound()) return GL_TEXTURE_CUBE_MAP;
    for (GLenum target : {GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP_ARRAY,
                          GL_TEXTURE_RECTANGLE, GL_TEXTURE_1D, GL_TEXTURE_1D_ARRAY, GL_TEXTURE_2D_MULTISAMPLE,
                          GL_TEXTURE_2D_MULTISAMPLE_ARRAY}) {
        if (ScopedTextureProbe(targets, texture, target).bound()) return target;
    }
    return GL_NONE;
}

// Whether an image of a texture of `target` is attached by layer (glFramebufferTextureLayer).
bool is_layered_target(GLenum target) {
    return target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_3D || target == GL_TEXTURE_CUBE_MAP_ARRAY ||
           target == GL_TEXTURE_1D_ARRAY || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
}

// Blit targets compose into a staging texture: RGBA16F for float attachments (MULTIPLY keeps HDR).
GLenum staging_format(const OutputTarget& target) { return target.attachment_float ? GL_RGBA16F : GL_RGBA8; }
}  // namespace

const char* image_format_qualifier(GLenum internal_format, int* channels) {
    struct Entry { GLenum format; const char* qualifier; int channels; };
    static constexpr Entry kFormats[] = {
        {GL_R8, "r8", 1}, {GL_R16, "r16", 1}, {GL_R16F, "r16f", 1}, {GL_R32F, "r32f", 1},
        {GL_RG8, "rg8", 2}, {GL_RG16, "rg16", 2}, {GL_RG16F, "rg16f", 2}, {GL_RG32F, "rg32f", 2},
        {GL_RGBA8, "rgba8", 4}, {GL_RGBA16, "rgba16", 4}, {GL_RGBA16F, "rgba16f", 4}, {GL_RGBA32F, "rgba32f", 4},
        {GL_RGB10_A2, "rgb10_a2", 4}, {GL_R11F_G11F_B10F, "r11f_g11f_b10f", 3},
    };
    static_assert(sizeof kFormats / sizeof kFormats[0] == CompositePass::kFormats,
                  "the composite's program table is sized by the number of target formats");
    for (const Entry& entry : kFormats) {
        if (entry.format == internal_format) {
            if (channels) *channels = entry.channels;
            return entry.qualifier;
        }
    }
    return nullptr;
}

Error check_output_fields(const obscura_output& output, OutputTarget* out) {
    OutputTarget target;
    const int32_t blend = stored_enum(output.blend);
    const int32_t debug_view = stored_enum(output.debug_view);
    if (blend != OBSCURA_BLEND_OVERWRITE && blend != OBSCURA_BLEND_MULTIPLY) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "output.blend = %d is not an obscura_blend_mode", int(blend));
    }
    if (debug_view < OBSCURA_DEBUG_NONE || debug_view > OBSCURA_DEBUG_TAP_COUNT) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "output.debug_view = %d is not an obscura_debug_view",
                           int(debug_view));
    }
    if (output.x < 0 || output.y < 0) {
        return Error::make(OBSCURA_STATUS_INVALID_RECT, "output position (%d, %d) must not be negative", output.x,
                           output.y);
    }
    target.x = output.x;
    target.y = output.y;
    target.blend = output.blend;
    target.debug_view = output.debug_view;
    *out = target;
    return Error();
}

namespace {

struct NamedTexture {
    GLuint texture;
    const char* field;
};

// INVALID_TEXTURE where a texture in `written` is one of `read` named by another field.
Error refuse_aliases(const NamedTexture* written, size_t written_count, const obscura_input& input,
                     const obscura_output& output) {
    const NamedTexture read[] = {{input.depth_texture, "input.depth_texture"},
                                 {input.normal_texture, "input.normal_texture"},
                                 {input.motion_vector_texture, "input.motion_vector_texture"},
                                 {output.bent_normal_texture, "output.bent_normal_texture"}};
    for (size_t i = 0; i < written_count; ++i) {
        const NamedTexture& w = written[i];
        if (w.texture == 0) continue;
        for (const NamedTexture& r : read) {
            if (r.texture == w.texture && r.field != w.field) {
                return Error::make(OBSCURA_STATUS_INVALID_TEXTURE,
                                   "%s and %s are the same texture (%u): the frame would write a texture it reads or "
                                   "writes otherwise", w.field, r.field, w.texture);
            }
        }
    }
    return Error();
}

}  // namespace

Error check_output_aliasing(const obscura_input& input, const obscura_output& output) {
    const NamedTexture written[] = {{output.texture, "output.texture"},
                                    {output.bent_normal_texture, "output.bent_normal_texture"}};
    return refuse_aliases(written, sizeof written / sizeof written[0], input, output);
}

Error check_attachment_aliasing(const obscura_input& input, const obscura_output& output, const OutputTarget& target) {
    if (output.texture != 0 || output.framebuffer == 0) return Error();
    const GLuint attached = target.kind == TargetKind::Image ? target.texture
                            : target.attachment_type == GL_TEXTURE ? target.attachment_name
                                                                   : 0;
    const NamedTexture written[] = {{attached, "output.framebuffer's colour attachment 0"}};
    return refuse_aliases(written, 1, input, output);
}

namespace {

// GL has no blit into a multisampled framebuffer (INVALID_OPERATION; GL 4.3, 18.3.1): such a target is refused
// before anything is rendered, with its sample count. Queries the framebuffer bound to GL_DRAW_FRAMEBUFFER.
Error refuse_multisampled_draw_framebuffer(const gl::Table& gl, const char* what) {
    GLint sample_buffers = 0, samples = 0;
    gl.GetIntegerv(GL_SAMPLE_BUFFERS, &sample_buffers);
    if (sample_buffers == 0) return Error();
    gl.GetIntegerv(GL_SAMPLES, &samples);
    return Error::make(OBSCURA_STATUS_INVALID_FRAMEBUFFER,
                       "%s is multisampled (%d samples): GL cannot blit the result into it; resolve it first, or "
                       "write the AO into a single-sample texture and composite that",
                       what, int(samples));
}

// The passes write level 0 of an output texture through an image unit, which is invalid below the texture's base
// level (GL 4.3, 8.26: its stores are dropped, without an error): a base level moved from 0 is refused.
Error refuse_moved_base_level(GLint base, const char* what, GLuint texture) {
    if (base == 0) return Error();
    return Error::make(OBSCURA_STATUS_INVALID_TEXTURE,
                       "%s %u has GL_TEXTURE_BASE_LEVEL %d: the AO is written to level 0, which must be its base level",
                       what, texture, int(base));
}

}  // namespace

Error check_output_target(const gl::TextureTargets& targets, const obscura_output& output, const obscura_rect& rect,
                          OutputTarget* out) {
    const gl::Table& gl = targets.gl;
    OutputTarget target = *out;
    GLuint texture = output.texture;
    if (texture == 0 && output.framebuffer != 0) {
        // A framebuffer object: write its colour attachment 0 directly when that is a 2D texture level 0.
        if (!gl.IsFramebuffer(output.framebuffer)) {
            return Error::make(OBSCURA_STATUS_INVALID_FRAMEBUFFER, "output.framebuffer %u is not a framebuffer",
                               output.framebuffer);
        }
        gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, output.framebuffer);
        GLenum status = gl.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
        GLint type = GL_NONE, name = 0, level = 0, layered = GL_FALSE;
        gl.GetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                               GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
        if (type == GL_TEXTURE) {
            gl.GetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                                   GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
            gl.GetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                                   GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, &level);
            gl.GetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                                   GL_FRAMEBUFFER_ATTACHMENT_LAYERED, &layered);
        }
        if (status != GL_FRAMEBUFFER_COMPLETE || type == GL_NONE) {
            return Error::make(OBSCURA_STATUS_INVALID_FRAMEBUFFER,
                               "output.framebuffer %u is incomplete (status 0x%04X) or has no colour attachment 0",
                               output.framebuffer, unsigned(status));
        }
        gl.ActiveTexture(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE);
        if (type == GL_TEXTURE && level == 0 && !layered && texture_has_target(targets, GLuint(name), GL_TEXTURE_2D)) {
            gl.BindTexture(GL_TEXTURE_2D, 0);
            GLint format = 0;
            gl.BindTexture(GL_TEXTURE_2D, GLuint(name));
            gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
            const GLint base = texture_base_level(gl, GL_TEXTURE_2D);
            gl.BindTexture(GL_TEXTURE_2D, 0);
            // Written directly only where level 0 is the base level (an image unit below it is invalid: its stores
            // are dropped); otherwise the blit reaches the level the host attached.
            if (image_format_qualifier(GLenum(format), nullptr) && base == 0) texture = GLuint(name);
        }
        if (texture == 0) {
            // Blit path: the attachment must accept a blit from the RGBA8 staging texture, and the result
            // must fit it (checked where the attachment size can be queried: renderbuffers, 2D textures).
            GLint component_type = GL_NONE;
            gl.GetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                                   GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &component_type);
            if (component_type == GL_INT || component_type == GL_UNSIGNED_INT) {
                return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                                   "output.framebuffer %u has an integer colour attachment 0, which a blit of "
                                   "normalised visibility cannot write",
                                   output.framebuffer);
            }
            GLint width = -1, height = -1;
            GLenum texture_target = GL_NONE;
            GLint cube_face = GL_NONE;
            if (type == GL_TEXTURE) {
                gl.GetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                                       GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE, &cube_face);
                texture_target = attached_texture_target(targets, GLuint(name), GLenum(cube_face));
            }
            if (type == GL_RENDERBUFFER) {
                GLint renderbuffer = 0, previous = 0;
                gl.GetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                                       GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &renderbuffer);
                gl.GetIntegerv(GL_RENDERBUFFER_BINDING, &previous);
                gl.BindRenderbuffer(GL_RENDERBUFFER, GLuint(renderbuffer));
                gl.GetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_WIDTH, &width);
                gl.GetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_HEIGHT, &height);
                gl.BindRenderbuffer(GL_RENDERBUFFER, GLuint(previous));
            } else if (type == GL_TEXTURE && !layered && texture_target != GL_NONE) {
                // The attached image's size: a cube map's per face, a 1D array layer's is one row.
                const ScopedTextureProbe bound(targets, GLuint(name), texture_target);
                const GLenum level_target = texture_target == GL_TEXTURE_CUBE_MAP ? GLenum(cube_face) : texture_target;
                gl.GetTexLevelParameteriv(level_target, level, GL_TEXTURE_WIDTH, &width);
                gl.GetTexLevelParameteriv(level_target, level, GL_TEXTURE_HEIGHT, &height);
                if (texture_target == GL_TEXTURE_1D_ARRAY) height = 1;
            }
            if (layered) {
                return Error::make(OBSCURA_STATUS_INVALID_FRAMEBUFFER,
                                   "output.framebuffer %u has a layered colour attachment 0; attach one layer",
                                   output.framebuffer);
            }
            if (width >= 0 && (rect.width > width - target.x || rect.height > height - target.y)) {
                return Error::make(OBSCURA_STATUS_INVALID_RECT,
                                   "a %dx%d result at (%d, %d) does not fit the %dx%d colour attachment of "
                                   "output.framebuffer %u",
                                   rect.width, rect.height, target.x, target.y, width, height, output.framebuffer);
            }
            char what[64];
            std::snprintf(what, sizeof what, "output.framebuffer %u", output.framebuffer);
            if (Error error = refuse_multisampled_draw_framebuffer(gl, what)) return error;
            target.kind = TargetKind::Blit;
            target.framebuffer = output.framebuffer;
            target.attachment_type = GLenum(type);
            target.attachment_name = GLuint(name != 0 ? name : 0);
            if (type == GL_RENDERBUFFER) {
                GLint renderbuffer = 0;
                gl.GetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                                       GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &renderbuffer);
                target.attachment_name = GLuint(renderbuffer);
            }
            target.attachment_level = level;
            target.attachment_face = texture_target == GL_TEXTURE_CUBE_MAP ? GLenum(cube_face) : GL_NONE;
            target.attachment_by_layer = is_layered_target(texture_target);

            target.attachment_float = component_type == GL_FLOAT;
            *out = target;
            return Error();
        }
    } else if (texture == 0) {
        // The default framebuffer can only be reached by a blit, and a surfaceless context has none.
        gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        GLenum status = gl.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            return Error::make(OBSCURA_STATUS_INVALID_FRAMEBUFFER,
                               "the default framebuffer is not complete (status 0x%04X); a context without a "
                               "surface has none: name an output texture or framebuffer object",
                               unsigned(status));
        }
        if (Error error = refuse_multisampled_draw_framebuffer(gl, "the default framebuffer")) return error;
        // GL cannot report the window's size; at least keep the blit's end coordinates representable.
        if (target.x > INT32_MAX - rect.width || target.y > INT32_MAX - rect.height) {
            return Error::make(OBSCURA_STATUS_INVALID_RECT, "output position (%d, %d) overflows with a %dx%d result",
                               target.x, target.y, rect.width, rect.height);
        }
        target.kind = TargetKind::Blit;
        target.framebuffer = 0;
        *out = target;
        return Error();
    }

    gl.ActiveTexture(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE);
    if (!gl.IsTexture(texture) || !texture_has_target(targets, texture, GL_TEXTURE_2D)) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "output texture %u is not a GL_TEXTURE_2D", texture);
    }
    GLint width = 0, height = 0, format = 0;
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &height);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    const GLint base = texture_base_level(gl, GL_TEXTURE_2D);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    if (Error error = refuse_moved_base_level(base, "output texture", texture)) return error;
    if (!image_format_qualifier(GLenum(format), nullptr)) {
        return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                           "output texture %u has format 0x%04X; use R8, R16F, R32F, RG8/16F/32F, RGBA8/16F/32F, "
                           "RGB10_A2 or R11F_G11F_B10F",
                           texture, unsigned(format));
    }
    if (rect.width > width - target.x || rect.height > height - target.y) {
        return Error::make(OBSCURA_STATUS_INVALID_RECT, "a %dx%d result at (%d, %d) does not fit the %dx%d output texture",
                           rect.width, rect.height, target.x, target.y, width, height);
    }
    target.kind = TargetKind::Image;
    target.texture = texture;
    target.format = GLenum(format);
    *out = target;
    return Error();
}

Error check_bent_normal_target(const gl::TextureTargets& targets, const obscura_output& output, const obscura_rect& rect,
                               OutputTarget* out) {
    const gl::Table& gl = targets.gl;
    const GLuint texture = output.bent_normal_texture;
    if (texture == 0) return Error();
    gl.ActiveTexture(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE);
    if (!gl.IsTexture(texture) || !texture_has_target(targets, texture, GL_TEXTURE_2D)) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "output.bent_normal_texture %u is not a GL_TEXTURE_2D",
                           texture);
    }
    GLint width = 0, height = 0, format = 0;
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &height);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    const GLint base = texture_base_level(gl, GL_TEXTURE_2D);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    if (Error error = refuse_moved_base_level(base, "output.bent_normal_texture", texture)) return error;
    if (!is_bent_normal_format(GLenum(format))) {
        return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                           "output.bent_normal_texture %u has format 0x%04X; use RGBA8, RGBA16F or RGBA32F", texture,
                           unsigned(format));
    }
    if (rect.width > width - output.x || rect.height > height - output.y) {
        return Error::make(OBSCURA_STATUS_INVALID_RECT,
                           "a %dx%d result at (%d, %d) does not fit the %dx%d output.bent_normal_texture", rect.width,
                           rect.height, output.x, output.y, width, height);
    }
    out->bent_texture = texture;
    out->bent_format = GLenum(format);
    return Error();
}

namespace {

// The composite program a target needs: the format it writes (the staging texture's for a blit), the depth and
// normal views (the raw views read the AO source like the plain output), the blend.
CompositeVariant composite_variant(const OutputTarget& target, GLenum format) {
    CompositeVariant variant;
    variant.format = format;
    variant.debug_views = target.debug_view == OBSCURA_DEBUG_LINEAR_DEPTH || target.debug_view == OBSCURA_DEBUG_NORMALS;
    variant.multiply = target.blend == OBSCURA_BLEND_MULTIPLY;
    return variant;
}

}  // namespace

Error OutputWriter::prepare(const PassEnv& env, const OutputTarget& target, const obscura_rect& rect, bool composite) {
    const gl::Table& gl = env.gl;
    const GLenum format = staging_format(target);
    Error error = composite ? composite_.prepare(env, composite_variant(target, image_format(target))) : Error();
    if (!error && target.bent_texture) error = bent_.prepare(env, target.bent_format);
    if (error) return error;
    if (target.kind != TargetKind::Blit) {
        // A texture target again: the blit's staging is not needed. Its framebuffer goes too: a texture deleted
        // while attached to a framebuffer that is not bound lives on until it is detached.
        staging_ = gl::Texture2D();
        staging_framebuffer_ = gl::Object();
        return Error();
    }
    if (staging_ && staging_.width() == rect.width && staging_.height() == rect.height &&
        staging_.internal_format() == format) {
        return Error();
    }
    staging_ = env.create_texture(format, rect.width, rect.height);
    if (!staging_) {
        staging_framebuffer_ = gl::Object();  // which still held the old staging texture
        return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the staging texture failed");
    }
    if (!staging_framebuffer_) staging_framebuffer_ = gl::create_framebuffer(gl);
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

GLenum OutputWriter::image_format(const OutputTarget& target) {
    return target.kind == TargetKind::Image ? target.format : staging_format(target);
}

TargetWrite target_write(const OutputTarget& target) {
    TargetWrite write;
    write.format = OutputWriter::image_format(target);
    write.multiply = target.blend == OBSCURA_BLEND_MULTIPLY;
    return write;
}

namespace {

// common/output_target.glsl's #define lines for `write` (target_variant).
Error output_target_defines(const TargetWrite& write, const char* pass, char (&out)[64]) {
    int channels = 0;
    const char* qualifier = write.format != 0 ? image_format_qualifier(write.format, &channels) : "r8";
    if (!qualifier) {
        return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "no %s variant for target format 0x%04X", pass,
                           unsigned(write.format));
    }
    std::snprintf(out, sizeof out, "OUTPUT_FORMAT %s\nOUTPUT_MULTIPLY %d\n", qualifier, write.multiply ? 1 : 0);
    return Error();
}

}  // namespace

Error target_variant(const PassEnv& env, const char* shader, const char* pass_defines, const TargetWrite& write,
                     gl::ProgramCache<gl::DefineLines>* cache, GLuint* program) {
    char target_defines[64];
    Error error = output_target_defines(write, shader, target_defines);
    if (error) return error;
    gl::DefineLines defines;
    const int length = std::snprintf(defines.text, sizeof defines.text, "%s%s", pass_defines, target_defines);
    if (length < 0 || size_t(length) >= sizeof defines.text) {
        return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "%s: the variant's #define lines do not fit", shader);
    }
    return cache->get(defines, [&](gl::Object* built) { return env.build(shader, defines.text, built); }, program);
}

void bind_target_image(const gl::Table& gl, GLuint unit, GLuint texture, const TargetWrite& write) {
    gl.BindImageTexture(unit, texture, 0, GL_FALSE, 0, write.multiply ? GL_READ_WRITE : GL_WRITE_ONLY, write.format);
}

BentNormalWriteConstants OutputWriter::bent_constants(const OutputTarget& target) {
    return BentNormalWritePass::constants(target.x, target.y);
}

void OutputWriter::write(const PassEnv& env, const UniformRange& frame, const FrameInput& input,
                         const gl::Texture2D& source, const FrameResources& resources, const OutputTarget& target,
                         const gl::Texture2D* bent, const UniformRange& bent_pass, const OutputImageWrite* image_write) {
    const obscura_rect& rect = input.output_rect;
    // The image write first: the upsample writes the bent normals the bent-normal write reads.
    write_image(env, frame, rect, source, resources, target, image_write);
    if (target.bent_texture && bent) bent_.run(env, frame, bent_pass, rect, *bent, target.bent_texture, target.bent_format);
}

void OutputWriter::compose(const PassEnv& env, const UniformRange& frame, const obscura_rect& rect,
                           const gl::Texture2D& source, const FrameResources& resources, const OutputTarget& target,
                           const OutputImageWrite* image_write, GLuint texture, GLenum format) {
    if (image_write) image_write->write_image(env, texture, format);
    else composite_.run(env, frame, rect, source, resources, texture, composite_variant(target, format));
}

void OutputWriter::write_image(const PassEnv& env, const UniformRange& frame, const obscura_rect& rect,
                               const gl::Texture2D& source, const FrameResources& resources, const OutputTarget& target,
                               const OutputImageWrite* image_write) {
    const gl::Table& gl = env.gl;
    if (target.kind == TargetKind::Image) {
        compose(env, frame, rect, source, resources, target, image_write, target.texture, target.format);
        return;
    }
    gl::BlitStateGuard blit_state(gl);
    const GLuint host = blit_framebuffer(gl, target);
    std::optional<gl::AttachmentZeroScope> attachment_zero;
    if (host == target.framebuffer) attachment_zero.emplace(gl, host);  // the host's framebuffer, or the default one
    // Multiply needs the framebuffer's colour first: blit it into the staging texture.
    if (target.blend == OBSCURA_BLEND_MULTIPLY) {
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, host);
        gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, staging_framebuffer_.name());
        gl.BlitFramebuffer(target.x, target.y, target.x + rect.width, target.y + rect.height, 0, 0, rect.width,
                           rect.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    compose(env, frame, rect, source, resources, target, image_write, staging_.name(), staging_.internal_format());
    gl.MemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, staging_framebuffer_.name());
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, host);
    gl.BlitFramebuffer(0, 0, rect.width, rect.height, target.x, target.y, target.x + rect.width,
                       target.y + rect.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    // Hold no reference to the host's image between frames: a renderbuffer or texture the host deletes would live
    // on, attached to this framebuffer, until the next blit (the next frame attaches it again).
    // (Not the default framebuffer: with no framebuffer of the SDK's yet, both names are 0, and detaching from the
    // window-system framebuffer is GL_INVALID_OPERATION: every frame into the default framebuffer failed with it.)
    if (host != 0 && host == target_framebuffer_.name()) detach_target(gl);
}

void OutputWriter::release() {
    staging_ = gl::Texture2D();
    staging_framebuffer_ = gl::Object();
    target_framebuffer_ = gl::Object();
}

void OutputWriter::detach_target(const gl::Table& gl) {
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, target_framebuffer_.name());
    gl.FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, 0);
    gl.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
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
