// Compiles the glad2-generated loader (third_party/glad, --mx) into this translation unit only.
// GLAD_API_CALL makes every glad entry point static, so nothing but the obscura_gl_* functions leaves it.
#define GLAD_API_CALL static
// glad's functions are all static here; renaming them as well keeps even the local symbols that `nm` lists
// (unoptimised builds keep the entry points, optimised ones emit clones such as "...constprop.0") free of
// the glad prefix a host's loader uses. The two entry points are renamed before glad's header declares them.
#define gladLoadGLContext obscura_loader_load_context
#define gladLoadGLContextUserPtr obscura_loader_load_context_user_ptr
#define glad_gl_find_core_gl obscura_loader_find_core_gl
#define glad_gl_find_extensions_gl obscura_loader_find_extensions_gl
#define glad_gl_free_extensions obscura_loader_free_extensions
#define glad_gl_get_extensions obscura_loader_get_extensions
#define glad_gl_get_proc_from_userptr obscura_loader_get_proc_from_userptr
#define glad_gl_has_extension obscura_loader_has_extension
#define glad_gl_load_GL_VERSION_1_0 obscura_loader_load_GL_VERSION_1_0
#define glad_gl_load_GL_VERSION_1_1 obscura_loader_load_GL_VERSION_1_1
#define glad_gl_load_GL_VERSION_1_2 obscura_loader_load_GL_VERSION_1_2
#define glad_gl_load_GL_VERSION_1_3 obscura_loader_load_GL_VERSION_1_3
#define glad_gl_load_GL_VERSION_1_4 obscura_loader_load_GL_VERSION_1_4
#define glad_gl_load_GL_VERSION_1_5 obscura_loader_load_GL_VERSION_1_5
#define glad_gl_load_GL_VERSION_2_0 obscura_loader_load_GL_VERSION_2_0
#define glad_gl_load_GL_VERSION_2_1 obscura_loader_load_GL_VERSION_2_1
#define glad_gl_load_GL_VERSION_3_0 obscura_loader_load_GL_VERSION_3_0
#define glad_gl_load_GL_VERSION_3_1 obscura_loader_load_GL_VERSION_3_1
#define glad_gl_load_GL_VERSION_3_2 obscura_loader_load_GL_VERSION_3_2
#define glad_gl_load_GL_VERSION_3_3 obscura_loader_load_GL_VERSION_3_3
#define glad_gl_load_GL_VERSION_4_0 obscura_loader_load_GL_VERSION_4_0
#define glad_gl_load_GL_VERSION_4_1 obscura_loader_load_GL_VERSION_4_1
#define glad_gl_load_GL_VERSION_4_2 obscura_loader_load_GL_VERSION_4_2
#define glad_gl_load_GL_VERSION_4_3 obscura_loader_load_GL_VERSION_4_3
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
