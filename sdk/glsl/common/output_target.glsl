// The host's output image and its write, shared by the passes that write it (composite.comp; upsample.comp at
// reduced resolution; temporal_accumulate.comp at full resolution; a method's last reconstruction pass without
// either: bilateral_blur.comp, gtao_denoise.comp, sao_blur.comp, lsao_gather.comp): OUTPUT_FORMAT is the image's format qualifier,
// OUTPUT_MULTIPLY the blend (compiled in: one program per target format and blend), OBSCURA_OUTPUT_IMAGE its image
// unit (OBSCURA_IMAGE_OUT0 unless the pass defines another). Multiply scales the target's colour by the value's first
// channel and keeps its alpha; overwrite stores the value.
#ifndef OBSCURA_OUTPUT_IMAGE
#define OBSCURA_OUTPUT_IMAGE OBSCURA_IMAGE_OUT0
#endif
layout(binding = OBSCURA_OUTPUT_IMAGE, OUTPUT_FORMAT) uniform image2D u_target;

void obscura_write_output(ivec2 destination, vec4 value) {
#if OUTPUT_MULTIPLY
    vec4 previous = imageLoad(u_target, destination);
    value = vec4(previous.rgb * value.r, previous.a);
#endif
    imageStore(u_target, destination, value);
}

// A pass over the output rectangle's texel p writes its visibility where the composite would (target_params places
// the rectangle), at the target's own precision, held to [0, 1]: a weighted mean of values up to 1 can round an ulp
// above it.
void obscura_write_final_output(ivec2 p, float visibility) {
    float v = clamp(visibility, 0.0, 1.0);
    obscura_write_output(target_params.xy + (p - output_rect.xy), vec4(v, v, v, 1.0));
}
