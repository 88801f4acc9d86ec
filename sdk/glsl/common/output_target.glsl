// The host's output image and its write, shared by the passes that write it (composite.comp; upsample.comp at
// reduced resolution): OUTPUT_FORMAT is the image's format qualifier, OUTPUT_MULTIPLY the blend (compiled in: one
// program per target format and blend). Multiply scales the target's colour by the value's first channel and keeps
// its alpha; overwrite stores the value.
layout(binding = OBSCURA_IMAGE_OUT0, OUTPUT_FORMAT) uniform image2D u_target;

void obscura_write_output(ivec2 destination, vec4 value) {
#if OUTPUT_MULTIPLY
    vec4 previous = imageLoad(u_target, destination);
    value = vec4(previous.rgb * value.r, previous.a);
#endif
    imageStore(u_target, destination, value);
}
