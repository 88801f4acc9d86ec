// Compiling and linking the samples' own (host) GL programs through the host loader.
#ifndef OBSCURA_SAMPLES_HOST_GL_PROGRAM_H
#define OBSCURA_SAMPLES_HOST_GL_PROGRAM_H

#include "host_gl_objects.h"

namespace obscura::samples {

// A program of a vertex and a fragment shader. Throws std::runtime_error("<what> ... failed to compile:
// <log>") when a stage does not compile or the program does not link; leaves no shader object behind.
HostProgram link_host_program(const char* vertex_source, const char* fragment_source, const char* what);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_HOST_GL_PROGRAM_H
