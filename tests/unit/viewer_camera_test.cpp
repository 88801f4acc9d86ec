// The viewer's camera (samples/viewer/viewer_camera.h): a viewpoint that looks straight down or up, as the scene
// library's "top" (up = -z), must leave a camera with a basis. Reset used to force world up onto it, so lookAt
// divided by a zero cross product and fly mode's move() turned the eye into NaN for good. No GL.
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "viewer_camera.h"

namespace {

using obscura::samples::Camera;
using obscura::viewer::ViewerCamera;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// What the renderer makes of the camera (samples::Camera::view()).
glm::mat4 view_of(const Camera& camera) { return glm::lookAt(camera.eye, camera.target, camera.up); }

// As scene_library.cpp's framed_viewpoints() makes "top": above the target, the picture's top towards -z.
Camera vertical_camera(float sign) {
    Camera camera;
    camera.target = glm::vec3(0.5f, 0.2f, -1.0f);
    camera.eye = camera.target + glm::vec3(0.0f, sign * 4.0f, 0.0f);
    camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
    return camera;
}

void expect_valid(const ViewerCamera& camera) {
    const Camera c = camera.camera();
    EXPECT_TRUE(finite(c.eye));
    EXPECT_TRUE(finite(c.target));
    EXPECT_TRUE(finite(view_of(c)));
}

TEST(ViewerCamera, TopViewpointKeepsABasisInEveryMode) {
    for (float sign : {1.0f, -1.0f}) {  // looking straight down, then straight up
        SCOPED_TRACE(sign > 0.0f ? "down" : "up");
        const Camera top = vertical_camera(sign);
        ViewerCamera camera;
        camera.reset(top);
        expect_valid(camera);
        // The orbit centre and the distance stay; the view still looks (almost) straight down / up.
        const Camera c = camera.camera();
        EXPECT_EQ(c.target, top.target);
        EXPECT_NEAR(camera.distance(), 4.0f, 1e-4f);
        EXPECT_GT(-sign * glm::normalize(c.target - c.eye).y, 0.999f);
        if (sign > 0.0f) {
            // Looking down, the picture's top leans where the viewpoint's up points (-z): the eye sits on +z.
            EXPECT_GT(c.eye.z, top.target.z);
        }

        camera.mode = ViewerCamera::Mode::Fly;
        camera.move(0.5f, 0.25f, 0.1f);
        expect_valid(camera);
        camera.rotate(10.0f, -5.0f);
        expect_valid(camera);
        camera.move(-0.3f, -0.2f, 0.0f);
        expect_valid(camera);

        camera.reset(top);
        camera.mode = ViewerCamera::Mode::Orbit;
        camera.rotate(30.0f, 20.0f);
        camera.dolly(2.0f);
        expect_valid(camera);
    }
}

TEST(ViewerCamera, OrdinaryViewpointIsKept) {
    Camera view;  // the default: eye above and in front of the target
    ViewerCamera camera;
    camera.reset(view);
    EXPECT_EQ(camera.camera().eye, view.eye);
    EXPECT_EQ(camera.camera().target, view.target);
    EXPECT_EQ(camera.camera().up, glm::vec3(0.0f, 1.0f, 0.0f));
}

}  // namespace
