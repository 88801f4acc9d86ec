#include "passes/composite.h"

#include "output_writer.h"  // image_format_qualifier

namespace obscura {

CompositePass::Variant* CompositePass::find(GLenum format) {
    for (Variant& variant : variants_)
        if (variant.format == format) return &variant;
    return nullptr;
}

Error CompositePass::prepare(const PassEnv& env, GLenum format) {
    if (find(format)) return Error();
    int channels = 0;
    const char* qualifier = image_format_qualifier(format, &channels);
    Variant* slot = find(0);
    if (!qualifier || !slot) {
        return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "no composite variant for format 0x%04X", unsigned(format));
    }
    char defines[96];
    std::snprintf(defines, sizeof defines, "OUTPUT_FORMAT %s\nOUTPUT_CHANNELS %d\n", qualifier, channels);
    Error error = env.build("composite.comp", defines, &slot->program);
    if (error) return error;
    slot->format = format;
    return Error();
}

void CompositePass::run(const PassEnv& env, const UniformRange& frame, const obscura_rect& rect,
                        const gl::Texture2D& source, const FrameResources& resources, GLuint target_texture,
                        GLenum format) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(find(format)->program.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, target_texture, 0, GL_FALSE, 0, GL_READ_WRITE, format);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.dispatch(rect.width, rect.height, OBSCURA_COMPOSITE_GROUP_X, OBSCURA_COMPOSITE_GROUP_Y);
}

}  // namespace obscura
