#include "viewer_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace obscura::viewer {
namespace {

constexpr float kMaxPitchDegrees = 89.0f;  // short of the poles, where yaw would be undefined

// The direction of yaw / pitch (degrees) in a y-up world; yaw 0 looks along -z.
glm::vec3 direction(float yaw_degrees, float pitch_degrees) {
    const float yaw = glm::radians(yaw_degrees), pitch = glm::radians(pitch_degrees);
    return glm::vec3(std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
}

void angles_of(glm::vec3 d, float* yaw_degrees, float* pitch_degrees) {
    d = glm::normalize(d);
    *pitch_degrees = glm::degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f)));
    *yaw_degrees = glm::degrees(std::atan2(d.x, -d.z));
}

}  // namespace

void ViewerCamera::reset(const samples::Camera& camera) {
    camera_ = camera;
    camera_.up = glm::vec3(0.0f, 1.0f, 0.0f);
    // A viewpoint straight down or up (the library's "top", with its own up vector) has no basis with world up:
    // lookAt and move() would divide by a zero cross product. Such a view is tilted to the pitch limit the mouse
    // keeps to, around the same target, leaning the way the viewpoint's up points so the picture keeps its
    // orientation.
    const glm::vec3 offset = camera_.target - camera_.eye;
    const float radius = glm::length(offset);
    if (!(radius > 0.0f)) return;
    float yaw = 0.0f, pitch = 0.0f;
    angles_of(offset, &yaw, &pitch);
    if (std::abs(pitch) <= kMaxPitchDegrees) return;
    // Looking down, the top of the picture is where `up` points; looking up, the opposite way.
    glm::vec3 lean = pitch < 0.0f ? camera.up : -camera.up;
    lean.y = 0.0f;
    if (glm::length(lean) > 1e-6f) yaw = glm::degrees(std::atan2(lean.x, -lean.z));
    camera_.eye = camera_.target - radius * direction(yaw, std::clamp(pitch, -kMaxPitchDegrees, kMaxPitchDegrees));
}

float ViewerCamera::distance() const { return glm::length(camera_.target - camera_.eye); }

void ViewerCamera::rotate(float yaw_degrees, float pitch_degrees) {
    const float radius = std::max(distance(), 1e-4f);
    float yaw = 0.0f, pitch = 0.0f;
    if (mode == Mode::Orbit) {
        // The eye's direction seen from the target; turning right moves the eye left around it.
        angles_of(camera_.eye - camera_.target, &yaw, &pitch);
        yaw -= yaw_degrees;
        pitch = std::clamp(pitch - pitch_degrees, -kMaxPitchDegrees, kMaxPitchDegrees);
        camera_.eye = camera_.target + radius * direction(yaw, pitch);
    } else {
        angles_of(camera_.target - camera_.eye, &yaw, &pitch);
        yaw += yaw_degrees;
        pitch = std::clamp(pitch + pitch_degrees, -kMaxPitchDegrees, kMaxPitchDegrees);
        camera_.target = camera_.eye + radius * direction(yaw, pitch);
    }
}

void ViewerCamera::dolly(float steps) {
    const glm::vec3 offset = camera_.eye - camera_.target;
    const float radius = glm::length(offset);
    const float closest = std::max(4.0f * camera_.near_plane, 1e-3f);
    const float wanted = std::max(radius * std::pow(0.9f, steps), closest);
    if (radius > 0.0f) camera_.eye = camera_.target + offset * (wanted / radius);
}

void ViewerCamera::move(float forward, float right, float up) {
    const glm::vec3 ahead = glm::normalize(camera_.target - camera_.eye);
    const glm::vec3 across = glm::cross(ahead, glm::vec3(0.0f, 1.0f, 0.0f));
    // reset() and rotate() keep the view short of the poles; should it still be vertical, there is no "right".
    const float across_length = glm::length(across);
    const glm::vec3 side = across_length > 1e-6f ? across / across_length : glm::vec3(0.0f);
    const glm::vec3 step = forward * ahead + right * side + up * glm::vec3(0.0f, 1.0f, 0.0f);
    camera_.eye += step;
    camera_.target += step;
}

}  // namespace obscura::viewer
