#include "frame_input.h"

#include <cmath>
#include <cstring>

#include "common/shader_interface.h"
#include "host_enum.h"

namespace obscura {
namespace {


// Binds `texture` to `target` on the current unit and reports whether GL accepted it: the only way in
// GL 4.3 to learn a texture's target (binding a name to the wrong target raises INVALID_OPERATION).
bool texture_has_target(const gl::Table& gl, GLuint texture, GLenum target) {
    gl.BindTexture(target, texture);
    bool ok = gl.GetError() == GL_NO_ERROR;
    if (!ok) gl.BindTexture(target, 0);
    return ok;
}

GLenum binding_query(GLenum target) {
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
    ScopedTextureProbe(const gl::Table& gl, GLuint texture, GLenum target) : gl_(gl), target_(target) {
        gl.GetIntegerv(binding_query(target), &previous_);
        gl.BindTexture(target, texture);
        bound_ = gl.GetError() == GL_NO_ERROR;
    }
    ~ScopedTextureProbe() { gl_.BindTexture(target_, GLuint(previous_)); }
    ScopedTextureProbe(const ScopedTextureProbe&) = delete;
    ScopedTextureProbe& operator=(const ScopedTextureProbe&) = delete;
    bool bound() const { return bound_; }

private:
    const gl::Table& gl_;
    GLenum target_;
    GLint previous_ = 0;
    bool bound_ = false;
};

// The target of an attached texture (GL_NONE if none binds), probed in the order hosts most often use.
GLenum attached_texture_target(const gl::Table& gl, GLuint texture, GLenum cube_face) {
    // Mesa reports a face for a cube-map-array layer too: only a cube map proper is attached by face.
    if (cube_face != GL_NONE && ScopedTextureProbe(gl, texture, GL_TEXTURE_CUBE_MAP).bound()) return GL_TEXTURE_CUBE_MAP;
    for (GLenum target : {GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP_ARRAY,
                          GL_TEXTURE_RECTANGLE, GL_TEXTURE_1D, GL_TEXTURE_1D_ARRAY, GL_TEXTURE_2D_MULTISAMPLE,
                          GL_TEXTURE_2D_MULTISAMPLE_ARRAY}) {
        if (ScopedTextureProbe(gl, texture, target).bound()) return target;
    }
    return GL_NONE;
}

// Whether an image of a texture of `target` is attached by layer (glFramebufferTextureLayer).
bool is_layered_target(GLenum target) {
    return target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_3D || target == GL_TEXTURE_CUBE_MAP_ARRAY ||
           target == GL_TEXTURE_1D_ARRAY || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
}

bool is_hardware_depth_format(GLenum format) {
    switch (format) {
        case GL_DEPTH_COMPONENT16: case GL_DEPTH_COMPONENT24: case GL_DEPTH_COMPONENT32:
        case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_DEPTH32F_STENCIL8:
        // Unsized requests are reported as such by some drivers.
        case GL_DEPTH_COMPONENT: case GL_DEPTH_STENCIL:
            return true;
        default: return false;
    }
}

bool is_depth_stencil_format(GLenum format) {
    return format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8 || format == GL_DEPTH_STENCIL;
}

int normal_mode_for_format(GLenum format) {
    switch (format) {
        case GL_RGB16F: case GL_RGBA16F: case GL_RGB32F: case GL_RGBA32F: case GL_RGB8_SNORM:
        case GL_RGBA8_SNORM: case GL_RGB16_SNORM: case GL_RGBA16_SNORM:
            return OBSCURA_NORMALS_SIGNED;
        // R11F_G11F_B10F has no sign bit: it can only hold normals encoded as n * 0.5 + 0.5.
        case GL_RGB8: case GL_RGBA8: case GL_RGB10_A2: case GL_RGB16: case GL_RGBA16: case GL_R11F_G11F_B10F:
            return OBSCURA_NORMALS_UNSIGNED;
        default: return -1;
    }
}

}  // namespace

const char* image_format_qualifier(GLenum internal_format, int* channels) {
    struct Entry { GLenum format; const char* qualifier; int channels; };
    static const Entry kFormats[] = {
        {GL_R8, "r8", 1}, {GL_R16, "r16", 1}, {GL_R16F, "r16f", 1}, {GL_R32F, "r32f", 1},
        {GL_RG8, "rg8", 2}, {GL_RG16, "rg16", 2}, {GL_RG16F, "rg16f", 2}, {GL_RG32F, "rg32f", 2},
        {GL_RGBA8, "rgba8", 4}, {GL_RGBA16, "rgba16", 4}, {GL_RGBA16F, "rgba16f", 4}, {GL_RGBA32F, "rgba32f", 4},
        {GL_RGB10_A2, "rgb10_a2", 4}, {GL_R11F_G11F_B10F, "r11f_g11f_b10f", 3},
    };
    for (const Entry& entry : kFormats) {
        if (entry.format == internal_format) {
            if (channels) *channels = entry.channels;
            return entry.qualifier;
        }
    }
    return nullptr;
}

Error validate_input(const gl::Table& gl, const obscura_input& input, GLint max_texture_size, FrameInput* out) {
    FrameInput frame;
    const GLint max_size = max_texture_size;
    if (input.depth_width <= 0 || input.depth_height <= 0 || input.depth_width > max_size ||
        input.depth_height > max_size) {
        return Error::make(OBSCURA_STATUS_INVALID_SIZE, "depth size %dx%d must be within 1..%d", input.depth_width,
                           input.depth_height, max_size);
    }
    frame.width = input.depth_width;
    frame.height = input.depth_height;

    obscura_rect rect = input.output_rect;
    if (rect.x == 0 && rect.y == 0 && rect.width == 0 && rect.height == 0) rect = {0, 0, frame.width, frame.height};
    if (rect.width <= 0 || rect.height <= 0 || rect.x < 0 || rect.y < 0 || rect.width > frame.width - rect.x ||
        rect.height > frame.height - rect.y) {
        return Error::make(OBSCURA_STATUS_INVALID_RECT,
                           "output_rect (%d, %d, %dx%d) must be non-empty and inside the %dx%d depth texture", rect.x,
                           rect.y, rect.width, rect.height, frame.width, frame.height);
    }
    frame.output_rect = rect;

    const int32_t depth_kind = stored_enum(input.depth_kind);
    if (depth_kind != OBSCURA_DEPTH_HARDWARE && depth_kind != OBSCURA_DEPTH_LINEAR_VIEW) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "depth_kind = %d is not an obscura_depth_kind", int(depth_kind));
    }
    frame.depth_linear = depth_kind == OBSCURA_DEPTH_LINEAR_VIEW;

    float m2v = input.meters_to_view_units == 0.0f ? 1.0f : input.meters_to_view_units;
    if (!std::isfinite(m2v) || m2v <= 0.0f || m2v > 1e6f) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "meters_to_view_units = %g must be in (0, 1e6]",
                           double(input.meters_to_view_units));
    }
    frame.meters_to_view_units = m2v;

    const int32_t layout = stored_enum(input.projection_layout);
    const int32_t clip_depth = stored_enum(input.clip_depth);
    if (layout != OBSCURA_MATRIX_COLUMN_MAJOR && layout != OBSCURA_MATRIX_ROW_MAJOR) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "projection_layout = %d is not an obscura_matrix_layout",
                           int(layout));
    }
    if (clip_depth != OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE && clip_depth != OBSCURA_CLIP_DEPTH_ZERO_TO_ONE) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "clip_depth = %d is not an obscura_clip_depth", int(clip_depth));
    }
    Error error = decode_projection(input.projection, obscura_matrix_layout(layout), obscura_clip_depth(clip_depth),
                                    &frame.projection);
    if (error) return error;

    // Depth texture: a 2D or 2D multisample texture of the stated size and a readable format.
    if (input.depth_texture == 0 || !gl.IsTexture(input.depth_texture)) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "depth_texture %u is not a texture name",
                           input.depth_texture);
    }
    gl.ActiveTexture(GL_TEXTURE0 + OBSCURA_UNIT_DEPTH);
    GLenum target = GL_TEXTURE_2D;
    if (!texture_has_target(gl, input.depth_texture, GL_TEXTURE_2D)) {
        target = GL_TEXTURE_2D_MULTISAMPLE;
        if (!texture_has_target(gl, input.depth_texture, GL_TEXTURE_2D_MULTISAMPLE)) {
            return Error::make(OBSCURA_STATUS_INVALID_TEXTURE,
                               "depth_texture %u is neither GL_TEXTURE_2D nor GL_TEXTURE_2D_MULTISAMPLE",
                               input.depth_texture);
        }
    }
    frame.depth_texture = input.depth_texture;
    frame.depth_multisample = target == GL_TEXTURE_2D_MULTISAMPLE;
    GLint width = 0, height = 0, format = 0;
    gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_WIDTH, &width);
    gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_HEIGHT, &height);
    gl.GetTexLevelParameteriv(target, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (width != frame.width || height != frame.height) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "depth_texture %u is %dx%d but depth size says %dx%d",
                           input.depth_texture, width, height, frame.width, frame.height);
    }
    frame.depth_format = GLenum(format);
    if (frame.depth_linear) {
        if (format != GL_R32F && format != GL_R16F) {
            return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                               "linear view depth must be GL_R32F or GL_R16F (texture %u has format 0x%04X)",
                               input.depth_texture, unsigned(format));
        }
    } else if (!is_hardware_depth_format(GLenum(format))) {
        return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                           "hardware depth must be a GL_DEPTH_COMPONENT* or depth-stencil format (texture %u has "
                           "format 0x%04X); linear depth needs depth_kind = OBSCURA_DEPTH_LINEAR_VIEW",
                           input.depth_texture, unsigned(format));
    }
    if (is_depth_stencil_format(GLenum(format))) {
        GLint mode = GL_DEPTH_COMPONENT;
        gl.GetTexParameteriv(target, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
        if (mode != GL_DEPTH_COMPONENT) {
            gl.TexParameteri(target, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
            frame.restore_depth_stencil_mode = mode;
        }
    }
    gl.BindTexture(target, 0);

    // Optional normals: a 2D texture of the same size with a signed or unsigned-normalised RGB(A) format.
    if (input.normal_texture != 0) {
        gl.ActiveTexture(GL_TEXTURE0 + OBSCURA_UNIT_NORMALS);
        if (!gl.IsTexture(input.normal_texture) || !texture_has_target(gl, input.normal_texture, GL_TEXTURE_2D)) {
            restore_input_state(gl, frame);
            return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "normal_texture %u is not a GL_TEXTURE_2D",
                               input.normal_texture);
        }
        gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
        gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &height);
        gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
        gl.BindTexture(GL_TEXTURE_2D, 0);
        if (width != frame.width || height != frame.height) {
            restore_input_state(gl, frame);
            return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "normal_texture %u is %dx%d; the depth is %dx%d",
                               input.normal_texture, width, height, frame.width, frame.height);
        }
        frame.normal_mode = normal_mode_for_format(GLenum(format));
        if (frame.normal_mode < 0) {
            restore_input_state(gl, frame);
            return Error::make(OBSCURA_STATUS_UNSUPPORTED_FORMAT,
                               "normal_texture %u has format 0x%04X; use a float, snorm or unorm RGB(A) format",
                               input.normal_texture, unsigned(format));
        }
        frame.normal_texture = input.normal_texture;
    } else {
        frame.normal_mode = OBSCURA_NORMALS_RECONSTRUCT;
    }
    *out = frame;
    return Error();
}

void restore_input_state(const gl::Table& gl, const FrameInput& input) {
    if (input.restore_depth_stencil_mode == 0) return;
    GLenum target = input.depth_multisample ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    gl.ActiveTexture(GL_TEXTURE0 + OBSCURA_UNIT_DEPTH);
    gl.BindTexture(target, input.depth_texture);
    gl.TexParameteri(target, GL_DEPTH_STENCIL_TEXTURE_MODE, input.restore_depth_stencil_mode);
    gl.BindTexture(target, 0);
}

Error validate_output(const gl::Table& gl, const obscura_output& output, const obscura_rect& rect, OutputTarget* out) {
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
        if (type == GL_TEXTURE && level == 0 && !layered && texture_has_target(gl, GLuint(name), GL_TEXTURE_2D)) {
            gl.BindTexture(GL_TEXTURE_2D, 0);
            GLint format = 0;
            gl.BindTexture(GL_TEXTURE_2D, GLuint(name));
            gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
            gl.BindTexture(GL_TEXTURE_2D, 0);
            if (image_format_qualifier(GLenum(format), nullptr)) texture = GLuint(name);
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
                texture_target = attached_texture_target(gl, GLuint(name), GLenum(cube_face));
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
                const ScopedTextureProbe bound(gl, GLuint(name), texture_target);
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
    if (!gl.IsTexture(texture) || !texture_has_target(gl, texture, GL_TEXTURE_2D)) {
        return Error::make(OBSCURA_STATUS_INVALID_TEXTURE, "output texture %u is not a GL_TEXTURE_2D", texture);
    }
    GLint width = 0, height = 0, format = 0;
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &height);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    gl.BindTexture(GL_TEXTURE_2D, 0);
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

}  // namespace obscura
