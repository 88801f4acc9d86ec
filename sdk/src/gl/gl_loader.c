// Compiles the glad2-generated loader (third_party/glad, --mx) into this translation unit only.
// GLAD_API_CALL makes every glad entry point static, so nothing but the obscura_gl_* functions leaves it.
#define GLAD_API_CALL static
#include "gl/gl_api.h"

#include "../../../third_party/glad/src/gl.c"

GLADapiproc obscura_gl_lookup(const ObscuraGlLoader* loader, const char* name) {
    if (loader->plain) return (GLADapiproc)loader->plain(name);
    return (GLADapiproc)loader->with_user_data(loader->user_data, name);
}

static GLADapiproc obscura_forward_proc(void* user, const char* name) {
    return obscura_gl_lookup((const ObscuraGlLoader*)user, name);
}

int obscura_gl_load_table(ObscuraGladGLContext* table, const ObscuraGlLoader* loader) {
    int version = gladLoadGLContextUserPtr(table, obscura_forward_proc, (void*)loader);
    if (version == 0) return 0;
    return GLAD_VERSION_MAJOR(version) * 10000 + GLAD_VERSION_MINOR(version);
}
