#include "passes/composite.h"

#include "output_writer.h"  // image_format_qualifier

namespace obscura {

CompositePass::Program* CompositePass::find(const CompositeVariant& variant) {
    for (Program& program : programs_)
        if (program.variant == variant) return &program;
    return nullptr;
}

Error CompositePass::prepare(const PassEnv& env, const CompositeVariant& variant) {
    if (find(variant)) return Error();
    int channels = 0;
    const char* qualifier = image_format_qualifier(variant.format, &channels);
    Program* slot = find(CompositeVariant());
    if (!qualifier || !slot) {
        return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "no composite variant for format 0x%04X",
                           unsigned(variant.format));
    }
    char defines[160];
    std::snprintf(defines, sizeof defines, "OUTPUT_FORMAT %s\nOUTPUT_CHANNELS %d\nOUTPUT_DEBUG_VIEWS %d\nOUTPUT_MULTIPLY %d\n",
                  qualifier, channels, variant.debug_views ? 1 : 0, variant.multiply ? 1 : 0);
    Error error = env.build("composite.comp", defines, &slot->program);
    if (error) return error;
    slot->variant = variant;
    return Error();
}

void CompositePass::run(const PassEnv& env, const UniformRange& frame, const obscura_rect& rect,
                        const gl::Texture2D& source, const FrameResources& resources, GLuint target_texture,
                        const CompositeVariant& variant) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(find(variant)->program.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, target_texture, 0, GL_FALSE, 0, GL_READ_WRITE, variant.format);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.dispatch(rect.width, rect.height, OBSCURA_COMPOSITE_GROUP_X, OBSCURA_COMPOSITE_GROUP_Y);
}

}  // namespace obscura
