// host_gl.h - the one header samples and tests include for their own (host) GL calls.
//
// It is the glad2 global loader of third_party/glad_host, standing in for a host engine's loader.
// The SDK has its own private function table and never sees these symbols; HeadlessGL fills these
// pointers (gladLoadGL) each time a context with a different loader or version becomes current.
#ifndef OBSCURA_SAMPLES_HOST_GL_H
#define OBSCURA_SAMPLES_HOST_GL_H

#include <glad/gl.h>

// GL 4.5 / ARB_clip_control tokens: the host loader is generated for 4.3 core, so they are absent.
#ifndef GL_CLIP_ORIGIN
#define GL_CLIP_ORIGIN 0x935C
#define GL_CLIP_DEPTH_MODE 0x935D
#define GL_NEGATIVE_ONE_TO_ONE 0x935E
#define GL_ZERO_TO_ONE 0x935F
#endif

#endif  // OBSCURA_SAMPLES_HOST_GL_H
