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

typedef void* (*obscura_gl_proc_fn)(const char* name);

// Loads `table` through `get_proc_address`; returns the GL version as major*10000+minor, 0 on failure.
int obscura_gl_load_table(ObscuraGladGLContext* table, obscura_gl_proc_fn get_proc_address);

#ifdef __cplusplus
}
#endif

#endif  // OBSCURA_GL_API_H
