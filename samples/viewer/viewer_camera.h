// ViewerCamera: the viewer's orbit and fly camera, as pure math over samples::Camera (no GL, no window).
//
// Orbit turns the eye around the target (yaw about world up, pitch clamped short of the poles) and dollies
// towards it; fly turns the view direction around the eye and moves eye and target together. Both keep the
// scene camera's field of view and clip planes, so depth precision stays what the scene chose.
#ifndef OBSCURA_VIEWER_CAMERA_H
#define OBSCURA_VIEWER_CAMERA_H

#include <glm/glm.hpp>

#include "scene_projection.h"

namespace obscura::viewer {

class ViewerCamera {
public:
    enum class Mode { Orbit, Fly };

    // Starts from a scene viewpoint, with world up (y); one looking straight down or up is tilted to the pitch
    // limit, leaning towards the viewpoint's own up, so that the camera always has a basis.
    void reset(const samples::Camera& camera);
    // Mouse drag in degrees: orbit turns around the target, fly looks around the eye. Positive yaw turns
    // right, positive pitch up.
    void rotate(float yaw_degrees, float pitch_degrees);
    // Orbit: moves the eye towards the target by the fraction `steps` * 10 % of the distance (negative: away),
    // never closer than the near plane allows.
    void dolly(float steps);
    // Fly: moves eye and target by `metres` along the view direction (forward), right and world up.
    void move(float forward, float right, float up);

    Mode mode = Mode::Orbit;
    // The camera to render with.
    samples::Camera camera() const { return camera_; }
    // How far the eye is from the target (the orbit radius).
    float distance() const;

private:
    samples::Camera camera_;
};

}  // namespace obscura::viewer

#endif  // OBSCURA_VIEWER_CAMERA_H
