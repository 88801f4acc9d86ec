// The SDK's private OpenGL function table (glad2, multi-context mode).
//
// gl_loader.c compiles glad's implementation with every entry point `static`, and the context type is
// renamed, so the library exports no glad* or gl* symbol and links beside a host that uses its own
// glad, GLEW or epoxy.
// Include this header instead of <glad/gl.h> anywhere in the SDK.
#ifndef OBSCURA_GL_API_H
#define OBSCURA_GL_API_H

#define GladGLContext ObscuraGladGLContext
#include <glad/gl.h>

#ifdef __cplusplus
extern "C" {
#endif

// The host's loader as given in obscura_context_desc: `plain` if set, else `with_user_data(user_data, name)`.
typedef struct ObscuraGlLoader {
    void (*(*plain)(const char* name))(void);
    void (*(*with_user_data)(void* user_data, const char* name))(void);
    void* user_data;
} ObscuraGlLoader;

// Looks up one function through `loader`.
GLADapiproc obscura_gl_lookup(const ObscuraGlLoader* loader, const char* name);

// Loads `table` through `loader`; returns the GL version as major*10000+minor, 0 on failure.
int obscura_gl_load_table(ObscuraGladGLContext* table, const ObscuraGlLoader* loader);

#ifdef __cplusplus
}
#endif

#endif  // OBSCURA_GL_API_H
