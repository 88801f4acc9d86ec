// Texture read-back and image files (PNG for looking at, PFM for exact float data).
//
// Every image here keeps GL's row order: row 0 is the bottom row. PFM stores rows bottom-up too, so
// PFM files are written as is; PNG rows are top-down, so write_png flips.
#ifndef OBSCURA_SAMPLES_IMAGE_IO_H
#define OBSCURA_SAMPLES_IMAGE_IO_H

#include <string>
#include <vector>

#include "host_gl.h"

namespace obscura::samples {

struct FloatImage {
    int width = 0;
    int height = 0;
    int channels = 1;
    std::vector<float> pixels;  // width * height * channels, rows bottom-up

    float at(int x, int y, int channel = 0) const { return pixels[(size_t(y) * width + x) * channels + channel]; }
};

enum class TextureReadFormat {
    Red,   // 1 float per pixel (GL_RED)
    Rgba,  // 4 floats per pixel (GL_RGBA)
    Depth  // 1 float per pixel, window-space depth (GL_DEPTH_COMPONENT) of a depth or depth-stencil texture
};

// Reads level 0 of a GL_TEXTURE_2D over [x, x+width) x [y, y+height) through a temporary framebuffer.
// Restores the read-framebuffer binding and the pack state it changes. Throws std::runtime_error if
// the texture cannot be read that way (multisampled, or a colour format GL cannot read as float).
FloatImage read_texture_region(GLuint texture, int x, int y, int width, int height,
                               TextureReadFormat format = TextureReadFormat::Red);

// 8-bit PNG: 1 channel -> gray, 3 -> RGB, 4 -> RGB (alpha dropped). Values are clamped to [0, 1];
// NaN becomes 0. Throws std::runtime_error when the file cannot be written.
void write_png(const std::string& path, const FloatImage& image);
// Reads an 8- or 16-bit PNG into [0, 1] values, rows bottom-up: gray (and gray + alpha) -> 1 channel,
// RGB and RGBA -> 3 channels (alpha dropped). Throws std::runtime_error naming the path when the file
// cannot be opened or is not a PNG it can decode.
FloatImage read_png(const std::string& path);

// PFM, float32, little-endian (negative scale): 1 channel -> "Pf", 3 -> "PF", 4 -> "PF" (alpha dropped).
void write_pfm(const std::string& path, const FloatImage& image);
// Reads "Pf" (1 channel) or "PF" (3 channels), either byte order. Throws std::runtime_error.
FloatImage read_pfm(const std::string& path);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_IMAGE_IO_H
