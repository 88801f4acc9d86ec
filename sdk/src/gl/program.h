// Builds compute programs from the embedded GLSL: prepends #version and the variant's #defines,
// resolves #include "path" (once per file, with #line markers so driver logs name the right file),
// compiles and links, and reports failures with the driver's log.
#ifndef OBSCURA_PROGRAM_H
#define OBSCURA_PROGRAM_H

#include "error.h"
#include "gl/gl_objects.h"
#include "host_allocator.h"

namespace obscura::gl {

// Returns the fully expanded source of `entry` with `defines` ("NAME VALUE" lines, may be empty).
// Errors: INTERNAL_ERROR when a file or include is missing or includes nest too deep.
Error assemble_shader_source(const char* entry, const char* defines, HostString* out_source);

// Compiles and links a compute program. On failure the error carries the (truncated) driver log;
// the whole log is also passed to `log` when set.
Error build_compute_program(const Table& gl, const char* entry, const char* defines, const AllocatorCallbacks& alloc,
                            obscura_log_fn log, void* log_user_data, Object* out_program);

}  // namespace obscura::gl

#endif  // OBSCURA_PROGRAM_H
