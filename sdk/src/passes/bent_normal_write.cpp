#include "passes/bent_normal_write.h"

#include <cstdio>

namespace obscura {
namespace {

struct BentFormat {
    GLenum format;
    const char* qualifier;
    int unorm;
};
constexpr BentFormat kBentFormats[] = {{GL_RGBA8, "rgba8", 1}, {GL_RGBA16F, "rgba16f", 0}, {GL_RGBA32F, "rgba32f", 0}};

int format_index(GLenum format) {
    for (int i = 0; i < 3; ++i) {
        if (kBentFormats[i].format == format) return i;
    }
    return -1;
}

}  // namespace

bool is_bent_normal_format(GLenum format) { return format_index(format) >= 0; }

Error BentNormalWritePass::prepare(const PassEnv& env, GLenum format) {
    const int index = format_index(format);
    if (index < 0) {
        return Error::make(OBSCURA_STATUS_INTERNAL_ERROR, "no bent-normal variant for format 0x%04X", unsigned(format));
    }
    if (programs_[index]) return Error();
    char defines[96];
    std::snprintf(defines, sizeof defines, "OUTPUT_FORMAT %s\nOUTPUT_UNORM %d\n", kBentFormats[index].qualifier,
                  kBentFormats[index].unorm);
    return env.build("bent_normal_write.comp", defines, &programs_[index]);
}

BentNormalWriteConstants BentNormalWritePass::constants(int x, int y) {
    BentNormalWriteConstants c = {};
    c.config[0] = x;
    c.config[1] = y;
    return c;
}

void BentNormalWritePass::run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                              const obscura_rect& rect, const gl::Texture2D& source, GLuint target, GLenum format) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(programs_[format_index(format)].name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    env.dispatch(rect.width, rect.height, OBSCURA_COMPOSITE_GROUP_X, OBSCURA_COMPOSITE_GROUP_Y);
}

}  // namespace obscura
