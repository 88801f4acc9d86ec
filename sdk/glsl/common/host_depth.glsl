// The host's depth texture (OBSCURA_UNIT_DEPTH) read as linear view depth, for the passes that read it: the depth
// preparation and the reduced-resolution upsample. Variants: DEPTH_LINEAR (the host gives linear view depth),
// DEPTH_MULTISAMPLE (sample 0 is used). Needs FrameConstants (shader_interface.h) and depth.glsl.
#if DEPTH_MULTISAMPLE
layout(binding = OBSCURA_UNIT_DEPTH) uniform sampler2DMS u_host_depth;
#else
layout(binding = OBSCURA_UNIT_DEPTH) uniform sampler2D u_host_depth;
#endif

// Linear view depth (or OBSCURA_SKY_DEPTH) of the host's texel `host_texel`.
float obscura_host_linear_depth(ivec2 host_texel) {
    float raw = texelFetch(u_host_depth, host_texel, 0).r;
#if DEPTH_LINEAR
    return obscura_sanitize_linear_depth(raw);
#else
    return obscura_linearize_window_depth(raw);
#endif
}
