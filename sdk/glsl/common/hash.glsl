// Deterministic per-pixel noise (the same in every run for a frame index): a PCG-style integer hash, moved by
// the frame's offsets (FrameConstants.noise_offset, 0 at frame 0) so that accumulated frames see other samples.

uint obscura_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Two values in [0, 1) for a pixel, the same in every frame.
vec2 obscura_pixel_hash_noise(ivec2 pixel) {
    uint h = obscura_hash(uint(pixel.x) + obscura_hash(uint(pixel.y)));
    uint g = obscura_hash(h);
    return vec2(float(h >> 8u), float(g >> 8u)) * (1.0 / 16777216.0);
}

// The same moved by the frame's offset: two values in [0, 1) for a pixel in this frame.
vec2 obscura_pixel_noise(ivec2 pixel) { return fract(obscura_pixel_hash_noise(pixel) + noise_offset.xy); }
