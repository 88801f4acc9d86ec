#include "scene_projection.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

namespace obscura::samples {

namespace {
constexpr ProjectionKind kAllKinds[] = {ProjectionKind::Perspective, ProjectionKind::ReversedZ,
                                        ProjectionKind::InfinitePerspective, ProjectionKind::ReversedInfinite,
                                        ProjectionKind::Orthographic};

// Right-handed perspective whose z row is replaced; GLM's matrices are indexed [column][row].
glm::mat4 perspective_with_depth_row(const Camera& camera, float aspect, float z_scale, float z_offset) {
    glm::mat4 matrix = glm::perspectiveRH_NO(glm::radians(camera.fov_y_degrees), aspect, camera.near_plane,
                                             camera.far_plane);
    matrix[2][2] = z_scale;   // clip z = z_scale * view z + z_offset, clip w = -view z
    matrix[3][2] = z_offset;
    return matrix;
}
}  // namespace

const char* projection_kind_name(ProjectionKind kind) {
    switch (kind) {
    case ProjectionKind::Perspective: return "perspective";
    case ProjectionKind::ReversedZ: return "reversed";
    case ProjectionKind::InfinitePerspective: return "infinite";
    case ProjectionKind::ReversedInfinite: return "reversed-infinite";
    case ProjectionKind::Orthographic: return "ortho";
    }
    return "unknown";
}

ProjectionKind parse_projection_kind(const std::string& name) {
    std::string valid;
    for (ProjectionKind kind : kAllKinds) {
        if (name == projection_kind_name(kind)) return kind;
        valid += std::string(valid.empty() ? "" : ", ") + projection_kind_name(kind);
    }
    throw std::invalid_argument("unknown projection '" + name + "' (valid: " + valid + ")");
}

glm::mat4 Camera::view() const {
    return glm::lookAt(eye, target, up);
}

Projection make_projection(ProjectionKind kind, const Camera& camera, float aspect, bool zero_to_one_clip_depth) {
    const float fov_y = glm::radians(camera.fov_y_degrees);
    const float n = camera.near_plane;
    const float f = camera.far_plane;
    Projection projection;
    projection.near_plane = n;
    projection.far_plane = f;
    const bool reversed = kind == ProjectionKind::ReversedZ || kind == ProjectionKind::ReversedInfinite;
    const bool zero_to_one = reversed && zero_to_one_clip_depth;
    projection.clip_depth = zero_to_one ? OBSCURA_CLIP_DEPTH_ZERO_TO_ONE : OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
    projection.reversed_z = reversed;

    switch (kind) {
    case ProjectionKind::Perspective:
        projection.matrix = glm::perspectiveRH_NO(fov_y, aspect, n, f);
        break;
    case ProjectionKind::ReversedZ:
        // Swapping near and far reverses the depth mapping of the ordinary matrices.
        projection.matrix = zero_to_one ? glm::perspectiveRH_ZO(fov_y, aspect, f, n)
                                        : glm::perspectiveRH_NO(fov_y, aspect, f, n);
        break;
    case ProjectionKind::InfinitePerspective:
        // NDC z = 1 - 2n / d for view distance d: near -> -1, infinity -> 1.
        projection.matrix = perspective_with_depth_row(camera, aspect, -1.0f, -2.0f * n);
        break;
    case ProjectionKind::ReversedInfinite:
        // [0,1]: NDC z = n / d (near -> 1, infinity -> 0); [-1,1]: NDC z = 2n / d - 1.
        projection.matrix = zero_to_one ? perspective_with_depth_row(camera, aspect, 0.0f, n)
                                        : perspective_with_depth_row(camera, aspect, 1.0f, 2.0f * n);
        break;
    case ProjectionKind::Orthographic: {
        const float half_height = camera.ortho_half_height;
        const float half_width = half_height * aspect;
        projection.matrix = glm::orthoRH_NO(-half_width, half_width, -half_height, half_height, n, f);
        projection.orthographic = true;
        break;
    }
    }
    if (kind == ProjectionKind::InfinitePerspective || kind == ProjectionKind::ReversedInfinite) {
        projection.infinite_far = true;
        projection.far_plane = std::numeric_limits<float>::infinity();
    }
    return projection;
}

GuardBandLayout guard_band_layout(int width, int height, float fraction) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("image size must be positive");
    if (!(fraction >= 0.0f && fraction <= 1.0f)) throw std::invalid_argument("guard band must be in [0, 1]");
    GuardBandLayout layout;
    layout.depth_width = int(std::lround(double(width) * (1.0 + 2.0 * double(fraction))));
    layout.depth_height = int(std::lround(double(height) * (1.0 + 2.0 * double(fraction))));
    layout.output_rect = {(layout.depth_width - width) / 2, (layout.depth_height - height) / 2, width, height};
    return layout;
}

glm::mat4 widen_for_guard_band(const glm::mat4& visible, const GuardBandLayout& layout) {
    // In the visible image's NDC the depth texture spans [lo, hi] on each axis; map that onto [-1, 1].
    // Applied to clip coordinates (x' = s x + t w), so it holds for perspective and orthographic.
    auto axis = [](int visible_size, int offset, int depth_size, float& scale, float& translate) {
        const double lo = -1.0 - 2.0 * offset / visible_size;
        const double hi = -1.0 + 2.0 * double(depth_size - offset) / visible_size;
        scale = float(2.0 / (hi - lo));
        translate = float(-(hi + lo) / (hi - lo));
    };
    glm::mat4 widen(1.0f);
    const obscura_rect& rect = layout.output_rect;
    axis(rect.width, rect.x, layout.depth_width, widen[0][0], widen[3][0]);
    axis(rect.height, rect.y, layout.depth_height, widen[1][1], widen[3][1]);
    return widen * visible;
}

}  // namespace obscura::samples
