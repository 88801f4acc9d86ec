// A host that loads OpenGL with libepoxy: entry points resolve lazily on first call, through EGL or
// GLX depending on the current context (EGL here).
#include <epoxy/gl.h>

#include <iostream>
#include <string>

namespace {
std::string epoxy_init() {
    return "epoxy GL version " + std::to_string(epoxy_gl_version()) + (epoxy_is_desktop_gl() ? " desktop" : " ES");
}
bool epoxy_has_gl43() { return epoxy_is_desktop_gl() && epoxy_gl_version() >= 43; }
}  // namespace

#define HOST_LOADER_INIT epoxy_init
#define HOST_LOADER_HAS_GL43 epoxy_has_gl43
#include "host_loader_tests.h"
