// The GLSL files of sdk/glsl/, embedded at build time by cmake/EmbedShaders.cmake.
#ifndef OBSCURA_SHADER_SOURCES_H
#define OBSCURA_SHADER_SOURCES_H

#include <cstddef>

namespace obscura {

struct EmbeddedShader {
    const char* path;  // relative to sdk/glsl/, e.g. "hbao.comp", "common/depth.glsl"
    const char* source;
    size_t length;
};

extern const EmbeddedShader kEmbeddedShaders[];
extern const size_t kEmbeddedShaderCount;

}  // namespace obscura

#endif  // OBSCURA_SHADER_SOURCES_H
