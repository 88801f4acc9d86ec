#include "image_io.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "host_gl_objects.h"

namespace obscura::samples {
namespace {

// Saves the state read_texture_region changes and restores it on destruction.
class ReadbackStateGuard {
public:
    ReadbackStateGuard() {
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
        glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer_);
        for (size_t i = 0; i < kPackParameters.size(); ++i) glGetIntegerv(kPackParameters[i], &pack_values_[i]);
    }
    ~ReadbackStateGuard() {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_framebuffer_));
        glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(pack_buffer_));
        for (size_t i = 0; i < kPackParameters.size(); ++i) glPixelStorei(kPackParameters[i], pack_values_[i]);
    }
    ReadbackStateGuard(const ReadbackStateGuard&) = delete;
    ReadbackStateGuard& operator=(const ReadbackStateGuard&) = delete;

private:
    static constexpr std::array<GLenum, 4> kPackParameters = {GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH,
                                                              GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_ROWS};
    GLint read_framebuffer_ = 0;
    GLint pack_buffer_ = 0;
    std::array<GLint, kPackParameters.size()> pack_values_{};
};

std::string gl_error_text(const char* during, GLenum error) {
    char text[160];
    std::snprintf(text, sizeof text, "GL error 0x%04x while %s", error, during);
    return text;
}

bool little_endian_host() {
    const uint32_t probe = 1;
    unsigned char first = 0;
    std::memcpy(&first, &probe, 1);
    return first == 1;
}

void swap_bytes(std::vector<float>& values) {
    for (float& value : values) {
        unsigned char bytes[4];
        std::memcpy(bytes, &value, 4);
        std::reverse(bytes, bytes + 4);
        std::memcpy(&value, bytes, 4);
    }
}

// The 1 or 3 channels a file format keeps of `image`, rows unchanged.
std::vector<float> file_channels(const FloatImage& image, int& channels_out) {
    if (image.channels != 1 && image.channels != 3 && image.channels != 4) {
        throw std::runtime_error("images of " + std::to_string(image.channels) + " channels cannot be written");
    }
    if (image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels) ||
        image.width <= 0 || image.height <= 0) {
        throw std::runtime_error("image size and pixel count do not match");
    }
    channels_out = image.channels == 1 ? 1 : 3;
    if (image.channels != 4) return image.pixels;
    std::vector<float> rgb;
    rgb.reserve(size_t(image.width) * image.height * 3);
    for (size_t i = 0; i < image.pixels.size(); i += 4) rgb.insert(rgb.end(), {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]});
    return rgb;
}

}  // namespace

FloatImage read_texture_region(GLuint texture, int x, int y, int width, int height, TextureReadFormat format) {
    if (width <= 0 || height <= 0 || x < 0 || y < 0) throw std::runtime_error("invalid read-back region");
    FloatImage image;
    image.width = width;
    image.height = height;
    image.channels = format == TextureReadFormat::Rgba ? 4 : 1;
    image.pixels.resize(size_t(width) * size_t(height) * size_t(image.channels));

    ReadbackStateGuard state;
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer.get());
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    // A depth-stencil texture may be attached to the depth attachment alone; that is all we read.
    const bool depth = format == TextureReadFormat::Depth;
    glFramebufferTexture(GL_READ_FRAMEBUFFER, depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0, texture, 0);
    glReadBuffer(depth ? GL_NONE : GL_COLOR_ATTACHMENT0);
    const GLenum status = glCheckFramebufferStatus(GL_READ_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        while (glGetError() != GL_NO_ERROR) {
        }
        char text[128];
        std::snprintf(text, sizeof text, "texture %u cannot be read back (framebuffer status 0x%04x)", texture, status);
        throw std::runtime_error(text);
    }
    const GLenum pixel_format = depth ? GL_DEPTH_COMPONENT : format == TextureReadFormat::Rgba ? GL_RGBA : GL_RED;
    glReadPixels(x, y, width, height, pixel_format, GL_FLOAT, image.pixels.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
        while (glGetError() != GL_NO_ERROR) {
        }
        throw std::runtime_error(gl_error_text("reading a texture back", error));
    }
    return image;
}

void write_png(const std::string& path, const FloatImage& image) {
    int channels = 0;
    const std::vector<float> values = file_channels(image, channels);
    std::vector<unsigned char> bytes(values.size());
    const size_t row = size_t(image.width) * size_t(channels);
    for (int y = 0; y < image.height; ++y) {
        // PNG rows go top-down.
        const float* source = values.data() + size_t(image.height - 1 - y) * row;
        unsigned char* target = bytes.data() + size_t(y) * row;
        for (size_t i = 0; i < row; ++i) {
            const float value = std::isnan(source[i]) ? 0.0f : std::clamp(source[i], 0.0f, 1.0f);
            target[i] = static_cast<unsigned char>(std::lround(value * 255.0f));
        }
    }
    if (!stbi_write_png(path.c_str(), image.width, image.height, channels, bytes.data(), int(row))) {
        throw std::runtime_error("cannot write PNG '" + path + "'");
    }
}

FloatImage read_png(const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) throw std::runtime_error("cannot open '" + path + "': " + std::strerror(errno));
    // 1 or 2 channels in the file -> gray; 3 or 4 -> RGB.
    int width = 0, height = 0, file_channels_count = 0;
    const bool info = stbi_info_from_file(file, &width, &height, &file_channels_count) != 0;
    const bool sixteen_bit = info && stbi_is_16_bit_from_file(file) != 0;
    const int channels = file_channels_count <= 2 ? 1 : 3;
    void* data = nullptr;
    if (info && sixteen_bit) {
        data = stbi_load_from_file_16(file, &width, &height, &file_channels_count, channels);
    } else if (info) {
        data = stbi_load_from_file(file, &width, &height, &file_channels_count, channels);
    }
    std::fclose(file);
    if (!data) {
        const char* reason = stbi_failure_reason();
        throw std::runtime_error("cannot read PNG '" + path + "': " + (reason ? reason : "unknown error"));
    }
    FloatImage image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.pixels.resize(size_t(width) * size_t(height) * size_t(channels));
    const size_t row = size_t(width) * size_t(channels);
    for (int y = 0; y < height; ++y) {
        // PNG rows go top-down.
        const size_t source_row = size_t(height - 1 - y) * row;
        float* target = image.pixels.data() + size_t(y) * row;
        for (size_t i = 0; i < row; ++i) {
            // k / 255.0f: the same float write_png's rounding of that level came from.
            target[i] = sixteen_bit ? float(static_cast<const stbi_us*>(data)[source_row + i]) / 65535.0f
                                    : float(static_cast<const stbi_uc*>(data)[source_row + i]) / 255.0f;
        }
    }
    stbi_image_free(data);
    return image;
}

void write_pfm(const std::string& path, const FloatImage& image) {
    int channels = 0;
    std::vector<float> values = file_channels(image, channels);
    if (!little_endian_host()) swap_bytes(values);
    std::ofstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot open '" + path + "' for writing");
    // Negative scale: little-endian samples.
    file << (channels == 1 ? "Pf" : "PF") << '\n' << image.width << ' ' << image.height << "\n-1.0\n";
    file.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
    if (!file) throw std::runtime_error("cannot write PFM '" + path + "'");
}

FloatImage read_pfm(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot open '" + path + "'");
    std::string type;
    FloatImage image;
    double scale = 0.0;
    file >> type >> image.width >> image.height >> scale;
    if (!file || (type != "Pf" && type != "PF") || image.width <= 0 || image.height <= 0 || scale == 0.0) {
        throw std::runtime_error("'" + path + "' is not a PFM file");
    }
    file.get();  // the single whitespace character that ends the header
    image.channels = type == "Pf" ? 1 : 3;
    // The header's size against the file's before anything is allocated: a header claiming 100000x100000 would
    // otherwise zero-fill 40 GB and only then find the file short.
    const std::streampos data_start = file.tellg();
    file.seekg(0, std::ios::end);
    const std::streamoff available = file.tellg() - data_start;
    file.seekg(data_start);
    const double wanted = double(image.width) * double(image.height) * double(image.channels) * sizeof(float);
    if (!file || double(available) < wanted) {
        throw std::runtime_error("'" + path + "' is truncated: its header says " + std::to_string(image.width) + "x" +
                                 std::to_string(image.height) + " x " + std::to_string(image.channels) +
                                 " floats, the file holds " + std::to_string(static_cast<long long>(available)) + " bytes after it");
    }
    image.pixels.resize(size_t(image.width) * size_t(image.height) * size_t(image.channels));
    file.read(reinterpret_cast<char*>(image.pixels.data()), std::streamsize(image.pixels.size() * sizeof(float)));
    if (!file) throw std::runtime_error("'" + path + "' is truncated");
    if ((scale < 0.0) != little_endian_host()) swap_bytes(image.pixels);
    return image;
}

}  // namespace obscura::samples
