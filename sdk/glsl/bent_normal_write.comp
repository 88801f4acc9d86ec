// Writes the output rectangle's bent normals into the host's bent-normal texture at its offset: the technique's
// RGBA16F (visibility, unit view-space bent normal) as rgb = bent normal (unorm formats: n * 0.5 + 0.5) and
// a = visibility. One variant per target format (OUTPUT_FORMAT, OUTPUT_UNORM).
#define OBSCURA_BENT_NORMAL_WRITE_PASS 1
#include "common/shader_interface.h"

layout(local_size_x = OBSCURA_COMPOSITE_GROUP_X, local_size_y = OBSCURA_COMPOSITE_GROUP_Y) in;

layout(binding = OBSCURA_UNIT_SOURCE) uniform sampler2D u_bent;
layout(binding = OBSCURA_IMAGE_OUT0, OUTPUT_FORMAT) writeonly uniform image2D u_target;

void main() {
    ivec2 i = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(i, output_rect.zw))) return;
    vec4 value = texelFetch(u_bent, output_rect.xy + i, 0);
    vec3 bent = value.gba;
    if (OUTPUT_UNORM == 1) bent = bent * 0.5 + 0.5;
    imageStore(u_target, bent_normal_write.config.xy + i, vec4(bent, value.r));
}
