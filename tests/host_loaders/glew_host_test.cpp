// A host that loads OpenGL with GLEW. Debian's GLEW 2.2 is built for GLX: under an EGL context
// glewInit() first loads every GL entry point (glewContextInit, through libGL's dispatch stubs, which
// route to whichever context libglvnd has current, EGL included) and then fails in glxewInit with
// GLEW_ERROR_NO_GLX_DISPLAY because there is no X display. The GL functions are loaded at that point,
// so that status is accepted and the loaded pointers are checked instead.
#include <GL/glew.h>

#include <iostream>
#include <string>

namespace {
std::string glew_init() {
    glewExperimental = GL_TRUE;
    GLenum status = glewInit();
    std::string text = "glewInit() = " + std::to_string(status) + " (" +
                       reinterpret_cast<const char*>(glewGetErrorString(status)) + ")";
    if (status != GLEW_OK && status != GLEW_ERROR_NO_GLX_DISPLAY) text = "FAILED: " + text;
    return text;
}
bool glew_has_gl43() {
    // GLEW_VERSION_4_3 is set by glewContextInit from GL_VERSION; the pointers prove the loading.
    return GLEW_VERSION_4_3 && glDispatchCompute != nullptr && glTexStorage2D != nullptr &&
           glBindImageTexture != nullptr;
}
}  // namespace

#define HOST_LOADER_INIT glew_init
#define HOST_LOADER_HAS_GL43 glew_has_gl43
#include "host_loader_tests.h"
