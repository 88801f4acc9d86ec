#include "depth_file.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "host_gl_objects.h"
#include "image_io.h"
#include "scene_projection.h"

namespace obscura::samples {
namespace {

constexpr DepthFileKind kAllKinds[] = {DepthFileKind::Linear, DepthFileKind::Hardware};

void check_options(const DepthFileOptions& options) {
    if (options.path.empty()) throw std::invalid_argument("depth file: no path given");
    if (!(options.fov_y_degrees > 0.0f && options.fov_y_degrees < 180.0f)) {
        throw std::invalid_argument("depth file: fov_y_degrees must be in (0, 180)");
    }
    if (!(options.guard_band >= 0.0f && options.guard_band < 1.0f)) {
        throw std::invalid_argument("depth file: guard_band must be in [0, 1)");
    }
    if (!(options.near_plane > 0.0f) || !std::isfinite(options.near_plane)) {
        throw std::invalid_argument("depth file: near_plane must be positive and finite");
    }
    if (!(options.far_plane > options.near_plane)) {
        throw std::invalid_argument("depth file: far_plane must be greater than near_plane (or +infinity)");
    }
}

[[noreturn]] void throw_bad_value(const std::string& path, const char* what, float value, int x, int y) {
    char message[160];
    std::snprintf(message, sizeof message, "%s at pixel (%d, %d): %g", what, x, y, double(value));
    throw std::runtime_error("depth file '" + path + "': " + message);
}

// The file's values as they go into the texture: linear sky becomes +inf; anything that does not
// fit the kind throws.
void convert_values(const DepthFileOptions& options, FloatImage& image) {
    const float infinity = std::numeric_limits<float>::infinity();
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            float& value = image.pixels[size_t(y) * size_t(image.width) + size_t(x)];
            if (options.kind == DepthFileKind::Linear) {
                if (std::isnan(value) || std::isinf(value) || value == 0.0f) {
                    value = infinity;
                } else if (value < 0.0f) {
                    throw_bad_value(options.path, "negative linear depth", value, x, y);
                }
            } else if (!(value >= 0.0f && value <= 1.0f)) {
                throw_bad_value(options.path, "hardware depth outside [0, 1]", value, x, y);
            }
        }
    }
}

// Saves and restores what the upload changes: the 2D binding of the active unit and unpack state.
class UploadStateGuard {
public:
    UploadStateGuard() {
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_);
        glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer_);
        for (size_t i = 0; i < kParameters.size(); ++i) glGetIntegerv(kParameters[i], &values_[i]);
    }
    ~UploadStateGuard() {
        glBindTexture(GL_TEXTURE_2D, GLuint(texture_));
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpack_buffer_));
        for (size_t i = 0; i < kParameters.size(); ++i) glPixelStorei(kParameters[i], values_[i]);
    }
    UploadStateGuard(const UploadStateGuard&) = delete;
    UploadStateGuard& operator=(const UploadStateGuard&) = delete;

    // Tightly packed floats from client memory.
    static void set_plain_unpack() {
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        for (GLenum parameter : kParameters) glPixelStorei(parameter, parameter == GL_UNPACK_ALIGNMENT ? 4 : 0);
    }

private:
    static constexpr std::array<GLenum, 6> kParameters = {GL_UNPACK_ALIGNMENT,   GL_UNPACK_ROW_LENGTH,
                                                          GL_UNPACK_SKIP_ROWS,   GL_UNPACK_SKIP_PIXELS,
                                                          GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SWAP_BYTES};
    GLint texture_ = 0, unpack_buffer_ = 0;
    std::array<GLint, kParameters.size()> values_{};
};

HostTexture upload(const FloatImage& image, bool linear) {
    UploadStateGuard state;
    UploadStateGuard::set_plain_unpack();
    HostTexture texture = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, linear ? GL_R32F : GL_DEPTH_COMPONENT32F, image.width, image.height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, linear ? GL_RED : GL_DEPTH_COMPONENT,
                    GL_FLOAT, image.pixels.data());
    return texture;
}

}  // namespace

const char* depth_file_kind_name(DepthFileKind kind) {
    switch (kind) {
    case DepthFileKind::Linear: return "linear";
    case DepthFileKind::Hardware: return "hardware";
    }
    return "unknown";
}

DepthFileKind parse_depth_file_kind(const std::string& name) {
    std::string valid;
    for (DepthFileKind kind : kAllKinds) {
        if (name == depth_file_kind_name(kind)) return kind;
        valid += std::string(valid.empty() ? "" : ", ") + depth_file_kind_name(kind);
    }
    throw std::invalid_argument("unknown depth file kind '" + name + "' (valid: " + valid + ")");
}

RenderedScene load_depth_file(const DepthFileOptions& options) {
    check_options(options);
    FloatImage image = read_pfm(options.path);
    if (image.channels != 1) {
        throw std::runtime_error("depth file '" + options.path + "' has " + std::to_string(image.channels) +
                                 " channels; expected a 1-channel PFM (Pf)");
    }
    convert_values(options, image);

    // The visible rectangle: the inverse of guard_band_layout(), centred the same way.
    const double scale = 1.0 + 2.0 * double(options.guard_band);
    const int visible_width = int(std::lround(double(image.width) / scale));
    const int visible_height = int(std::lround(double(image.height) / scale));
    if (visible_width < 1 || visible_height < 1) {
        throw std::runtime_error("depth file '" + options.path + "' is too small for a guard band of " +
                                 std::to_string(options.guard_band));
    }
    GuardBandLayout layout;
    layout.depth_width = image.width;
    layout.depth_height = image.height;
    layout.output_rect = {(image.width - visible_width) / 2, (image.height - visible_height) / 2, visible_width,
                          visible_height};

    const bool linear = options.kind == DepthFileKind::Linear;
    const bool reversed = !linear && options.reversed_z;
    const bool infinite = std::isinf(options.far_plane);
    const ProjectionKind kind =
        reversed ? (infinite ? ProjectionKind::ReversedInfinite : ProjectionKind::ReversedZ)
                 : (infinite ? ProjectionKind::InfinitePerspective : ProjectionKind::Perspective);
    Camera camera;
    camera.fov_y_degrees = options.fov_y_degrees;
    camera.near_plane = options.near_plane;
    camera.far_plane = infinite ? std::numeric_limits<float>::max() : options.far_plane;
    const Projection projection =
        make_projection(kind, camera, float(visible_width) / float(visible_height), /*zero_to_one=*/reversed);
    const glm::mat4 widened = widen_for_guard_band(projection.matrix, layout);

    HostTexture texture = upload(image, linear);
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        while (glGetError() != GL_NO_ERROR) {
        }
        char message[64];
        std::snprintf(message, sizeof message, "GL error 0x%04x", error);
        throw std::runtime_error("depth file '" + options.path + "': " + message + " while uploading");
    }

    SceneFrame frame;
    frame.depth_kind = linear ? OBSCURA_DEPTH_LINEAR_VIEW : OBSCURA_DEPTH_HARDWARE;
    frame.depth_internal_format = linear ? GL_R32F : GL_DEPTH_COMPONENT32F;
    frame.depth_width = image.width;
    frame.depth_height = image.height;
    frame.output_rect = layout.output_rect;
    std::memcpy(frame.projection, glm::value_ptr(widened), sizeof frame.projection);
    frame.clip_depth = projection.clip_depth;
    frame.near_plane = projection.near_plane;
    frame.far_plane = projection.far_plane;
    frame.reversed_z = projection.reversed_z;
    frame.infinite_far = projection.infinite_far;
    frame.depth_texture = texture.release();
    return RenderedScene(frame);
}

}  // namespace obscura::samples
