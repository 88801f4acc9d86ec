// Writes the result for the output rectangle into the host's target image: the AO (or a debug view)
// overwriting the target or multiplying its colour. One variant per target format (OUTPUT_FORMAT), per blend
// (OUTPUT_MULTIPLY) and for the debug views (OUTPUT_DEBUG_VIEWS): CPU rasterisers run every lane through both sides
// of a branch, so the plain AO write would otherwise pay for every debug view's reads and multiply's load.
#include "common/shader_interface.h"
#include "common/depth.glsl"
#include "common/normal_encoding.glsl"
#include "common/output_target.glsl"

layout(local_size_x = OBSCURA_COMPOSITE_GROUP_X, local_size_y = OBSCURA_COMPOSITE_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_ao;
layout(binding = OBSCURA_UNIT_LINEAR_DEPTH) uniform sampler2D u_linear_depth;
layout(binding = OBSCURA_UNIT_NORMALS) uniform sampler2D u_normals;

void main() {
    ivec2 i = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(i, output_rect.zw))) return;
    ivec2 source = output_rect.xy + i;
    // After a reduced-resolution frame the working textures (depth, normals, the raw AO of the debug views) hold
    // the host's texel t at t >> k: each covers its 2^k x 2^k pixels.
    ivec2 working = source >> resolution.x;
    ivec2 ao_source = resolution.y != 0 ? working : source;
    ivec2 destination = target_params.xy + i;
    int debug_view = target_params.w;

    vec4 value;
#if OUTPUT_DEBUG_VIEWS
    if (debug_view == OBSCURA_DEBUG_VIEW_LINEAR_DEPTH) {
        float depth = texelFetch(u_linear_depth, working, 0).r;
        float v = obscura_is_sky(depth) ? 1.0 : clamp(depth * debug_params.x, 0.0, 1.0);
        value = vec4(v, v, v, 1.0);
    } else if (debug_view == OBSCURA_DEBUG_VIEW_NORMALS) {
        vec3 n = obscura_decode_normal(texelFetch(u_normals, working, 0).xy) * 0.5 + 0.5;
        value = OUTPUT_CHANNELS == 1 ? vec4(n.z) : vec4(n, 1.0);
    } else
#endif
    {
        float v = texelFetch(u_ao, ao_source, 0).r;
        value = vec4(v, v, v, 1.0);
    }
    obscura_write_output(destination, value);
}
