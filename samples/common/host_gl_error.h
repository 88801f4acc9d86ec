// GL error codes by name, for the samples' and the tests' messages (host side: through the host loader's header).
#ifndef OBSCURA_SAMPLES_HOST_GL_ERROR_H
#define OBSCURA_SAMPLES_HOST_GL_ERROR_H

#include "host_gl.h"

namespace obscura::samples {

// "GL_INVALID_ENUM", ..., "GL_NO_ERROR"; "unknown GL error" for other values.
const char* gl_error_name(GLenum error);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_HOST_GL_ERROR_H
