// Compile-time checks that common/shader_interface.h, which the shaders read instead of the public header,
// carries the API's values: a shader compares FrameConstants and pass constants against these #defines, so a
// value the API renumbers without them fails the build here rather than rendering the wrong branch.
#include <obscura/obscura.h>

#include "common/shader_interface.h"

static_assert(OBSCURA_DEBUG_VIEW_LINEAR_DEPTH == OBSCURA_DEBUG_LINEAR_DEPTH, "shader_interface.h mirrors the API");
static_assert(OBSCURA_DEBUG_VIEW_NORMALS == OBSCURA_DEBUG_NORMALS, "shader_interface.h mirrors the API");
static_assert(OBSCURA_DEBUG_VIEW_TAP_COUNT == OBSCURA_DEBUG_TAP_COUNT, "shader_interface.h mirrors the API");

static_assert(OBSCURA_BLEND_MODE_OVERWRITE == OBSCURA_BLEND_OVERWRITE, "shader_interface.h mirrors the API");
static_assert(OBSCURA_BLEND_MODE_MULTIPLY == OBSCURA_BLEND_MULTIPLY, "shader_interface.h mirrors the API");

static_assert(OBSCURA_FALLOFF_KIND_RHO0 == OBSCURA_FALLOFF_RHO0, "shader_interface.h mirrors the API");
static_assert(OBSCURA_FALLOFF_KIND_INVERSE_QUADRATIC == OBSCURA_FALLOFF_INVERSE_QUADRATIC,
              "shader_interface.h mirrors the API");
static_assert(OBSCURA_FALLOFF_KIND_EXPONENTIAL == OBSCURA_FALLOFF_EXPONENTIAL, "shader_interface.h mirrors the API");
static_assert(OBSCURA_FALLOFF_KIND_TABLE == OBSCURA_FALLOFF_TABLE, "shader_interface.h mirrors the API");
// common/falloff.glsl interpolates 16 values, which the pass blocks hold as vec4 table[4].
static_assert(OBSCURA_FALLOFF_TABLE_SIZE == 16, "falloff.glsl's table has 16 entries");
