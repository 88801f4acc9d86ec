// Compiles the glad2-generated loader (third_party/glad, --mx) into this translation unit only.
// gl_api.h makes every glad entry point static, so nothing but obscura_gl_load_table leaves it.
#define GLAD_API_CALL static
#include "gl/gl_api.h"

#include "../../../third_party/glad/src/gl.c"

typedef struct LoaderForward {
    obscura_gl_proc_fn get_proc_address;
} LoaderForward;

static GLADapiproc obscura_forward_proc(void* user, const char* name) {
    const LoaderForward* forward = (const LoaderForward*)user;
    return (GLADapiproc)forward->get_proc_address(name);
}

int obscura_gl_load_table(ObscuraGladGLContext* table, obscura_gl_proc_fn get_proc_address) {
    LoaderForward forward;
    forward.get_proc_address = get_proc_address;
    int version = gladLoadGLContextUserPtr(table, obscura_forward_proc, &forward);
    if (version == 0) return 0;
    return GLAD_VERSION_MAJOR(version) * 10000 + GLAD_VERSION_MINOR(version);
}
