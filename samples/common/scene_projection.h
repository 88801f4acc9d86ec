// Camera, projection variants and guard-band layout of the demo scene: pure math, no GL calls.
#ifndef OBSCURA_SAMPLES_SCENE_PROJECTION_H
#define OBSCURA_SAMPLES_SCENE_PROJECTION_H

#include <string>

#include <glm/glm.hpp>

#include "obscura/obscura.h"

namespace obscura::samples {

enum class ProjectionKind {
    Perspective,          // standard: near -> depth 0, far -> 1, clip depth [-1, 1]
    ReversedZ,            // near -> 1, far -> 0; [0, 1] clip depth when glClipControl is used
    InfinitePerspective,  // standard with the far plane at infinity
    ReversedInfinite,     // reversed-Z with the far plane at infinity
    Orthographic
};

// "perspective", "reversed", "infinite", "reversed-infinite", "ortho".
const char* projection_kind_name(ProjectionKind kind);
// Inverse of projection_kind_name; throws std::invalid_argument listing the valid names.
ProjectionKind parse_projection_kind(const std::string& name);

struct Camera {
    glm::vec3 eye{0.0f, 2.4f, 5.5f};
    glm::vec3 target{0.0f, 0.6f, -1.5f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 60.0f;    // of the visible image, guard band excluded
    float near_plane = 0.1f;
    float far_plane = 50.0f;        // ignored by the infinite variants
    float ortho_half_height = 2.2f; // world units, Orthographic only

    glm::mat4 view() const;
};

struct Projection {
    glm::mat4 matrix{1.0f};  // column-major, as given to GL and to obscura_input.projection
    obscura_clip_depth clip_depth = OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
    float near_plane = 0.0f;
    float far_plane = 0.0f;  // +infinity for the infinite variants
    bool reversed_z = false;
    bool infinite_far = false;
    bool orthographic = false;

    // Depth of empty pixels ("sky") and the depth test that goes with it.
    float clear_depth() const { return reversed_z ? 0.0f : 1.0f; }
};

// The projection of `camera` for an image of aspect width / height. `zero_to_one_clip_depth` says
// glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) will be active; only the reversed variants use it
// (that is where it matters for precision). Without it reversed-Z still works with [-1, 1] clip depth:
// near maps to window depth 1 and far to 0, only the float precision benefit is lost.
Projection make_projection(ProjectionKind kind, const Camera& camera, float aspect, bool zero_to_one_clip_depth);

// The depth texture covers the visible image plus `fraction` of its size on each side.
struct GuardBandLayout {
    int depth_width = 0;   // round(width * (1 + 2 fraction))
    int depth_height = 0;
    obscura_rect output_rect{};  // the visible width x height, centred (left/bottom get the odd pixel less)
};
// Throws std::invalid_argument for non-positive sizes or a fraction outside [0, 1].
GuardBandLayout guard_band_layout(int width, int height, float fraction);

// Returns the projection for the whole depth texture: `visible` widened (works for perspective and
// orthographic alike, being applied in clip space) so that layout.output_rect sees exactly what
// `visible` sees over the full viewport.
glm::mat4 widen_for_guard_band(const glm::mat4& visible, const GuardBandLayout& layout);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_SCENE_PROJECTION_H
