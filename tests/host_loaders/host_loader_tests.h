// Tests shared by the GLEW and the epoxy host executables. Included after the loader's header (which
// declares the gl* entry points); every GL call below therefore goes through that loader, never
// through glad. HeadlessGL (samples/common) only creates the context; HOST_LOADER_INIT() is the
// loader's own initialisation, run once the context is current.
#ifndef OBSCURA_TESTS_HOST_LOADER_TESTS_H
#define OBSCURA_TESTS_HOST_LOADER_TESTS_H

#include <algorithm>
#include <iostream>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analytic_scene.h"
#include "headless_gl.h"
#include "obscura/obscura.h"

namespace host_loader_test {

using obscura::samples::HeadlessGL;
using namespace obscura_test;

constexpr int kWidth = 128;
constexpr int kHeight = 72;

class HostLoader : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        gl_ = new HeadlessGL();
        init_message_ = HOST_LOADER_INIT();
    }
    static void TearDownTestSuite() {
        delete gl_;
        gl_ = nullptr;
    }
    void SetUp() override {
        ASSERT_NE(gl_, nullptr);
        gl_->make_current();
        ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
        obscura_context_desc desc{};
        desc.struct_size = sizeof desc;
        desc.header_version = OBSCURA_VERSION;
        desc.get_proc_address = &HeadlessGL::get_proc_address;
        obscura_context* context = nullptr;
        ASSERT_EQ(obscura_create_context(&desc, &context), OBSCURA_OK);
        context_ = context;
    }
    void TearDown() override {
        obscura_destroy_context(context_);
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    }

    // Texture helpers written against the host loader.
    static GLuint depth_texture(const std::vector<float>& depth) {
        GLuint texture = 0;
        glGenTextures(1, &texture);
        glBindTexture(GL_TEXTURE_2D, texture);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, kWidth, kHeight, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                     depth.data());
        glBindTexture(GL_TEXTURE_2D, 0);
        return texture;
    }
    static GLuint r32f_texture() {
        GLuint texture = 0;
        glGenTextures(1, &texture);
        glBindTexture(GL_TEXTURE_2D, texture);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_R32F, kWidth, kHeight);
        glBindTexture(GL_TEXTURE_2D, 0);
        return texture;
    }
    static std::vector<float> read_r32f(GLuint texture) {
        std::vector<float> values(size_t(kWidth) * kHeight);
        glBindTexture(GL_TEXTURE_2D, texture);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, values.data());
        glBindTexture(GL_TEXTURE_2D, 0);
        return values;
    }

    // Renders `hits` seen by `camera` and returns the R32F result (empty on failure).
    std::vector<float> render(const Camera& camera, const std::vector<Hit>& hits, float radius,
                              obscura_debug_view view) {
        GLuint depth = depth_texture(depth_values(camera, hits));
        GLuint target = r32f_texture();
        obscura_input input{};
        input.struct_size = sizeof input;
        input.depth_texture = depth;
        input.depth_width = kWidth;
        input.depth_height = kHeight;
        std::copy(camera.matrix(), camera.matrix() + 16, input.projection);
        input.clip_depth = camera.clip_depth();
        obscura_output output{};
        output.struct_size = sizeof output;
        output.texture = target;
        output.debug_view = view;
        obscura_settings settings{};
        obscura_default_settings(OBSCURA_METHOD_HBAO, &settings);
        settings.hbao.radius = radius;
        settings.hbao.decay_rate = 0.0f;
        obscura_status status = obscura_render(context_, &input, &settings, &output);
        EXPECT_EQ(status, OBSCURA_OK) << obscura_get_last_error(context_);
        std::vector<float> result;
        if (status == OBSCURA_OK) result = read_r32f(target);
        glDeleteTextures(1, &depth);
        glDeleteTextures(1, &target);
        return result;
    }

    static HeadlessGL* gl_;
    static std::string init_message_;
    obscura_context* context_ = nullptr;
};

HeadlessGL* HostLoader::gl_ = nullptr;
std::string HostLoader::init_message_;

TEST_F(HostLoader, LoaderProvidesGl43) {
    RecordProperty("loader_init", init_message_);
    std::cout << "host loader: " << init_message_ << "; context: " << gl_->describe() << "\n";
    EXPECT_EQ(init_message_.rfind("FAILED", 0), std::string::npos) << init_message_;
    EXPECT_TRUE(HOST_LOADER_HAS_GL43()) << init_message_;
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    EXPECT_GE(major * 10 + minor, 43);
}

TEST_F(HostLoader, LinearDepthMatchesAnalytic) {
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), glm::dmat4(1.0));
    std::vector<Hit> hits = trace(camera, {plane(1, glm::dvec3(0.0, 0.0, -6.0), glm::dvec3(0.3, 0.5, 1.0)),
                                           sphere(2, glm::dvec3(0.8, -0.3, -4.5), 1.2)});
    std::vector<float> got = render(camera, hits, 5.0f, OBSCURA_DEBUG_LINEAR_DEPTH);
    ASSERT_EQ(got.size(), hits.size());
    int bad = 0;
    for (size_t i = 0; i < got.size(); ++i) {
        double expected = hits[i].hit ? hits[i].view_depth() / 20.0 : 1.0;
        bad += std::fabs(got[i] - expected) > 1e-4 * std::max(expected, 0.1);
    }
    EXPECT_EQ(bad, 0);
}

TEST_F(HostLoader, CornerAmbientOcclusion) {
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(),
                  look_at(glm::dvec3(0.3, 1.3, 2.8), glm::dvec3(0.0, 0.45, 0.0)));
    std::vector<Hit> hits = trace(camera, {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                                           plane(2, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0))});
    std::vector<float> v = render(camera, hits, 1.0f, OBSCURA_DEBUG_NONE);
    ASSERT_EQ(v.size(), hits.size());
    double near_sum = 0, far_min = 1;
    int near_count = 0, far_count = 0;
    for (int y = 6; y < kHeight - 6; ++y)
        for (int x = 6; x < kWidth - 6; ++x) {
            size_t i = size_t(y) * kWidth + x;
            double crease = std::hypot(std::max(hits[i].world.y, 0.0), std::max(hits[i].world.z, 0.0));
            if (crease < 0.06) {
                near_sum += v[i];
                ++near_count;
            } else if (crease > 1.4) {
                far_min = std::min(far_min, double(v[i]));
                ++far_count;
            }
        }
    ASSERT_GT(near_count, 20);
    ASSERT_GT(far_count, 100);
    EXPECT_LT(near_sum / near_count, 0.8);
    EXPECT_GT(far_min, 0.99);
}

TEST_F(HostLoader, HostBindingsSurvive) {
    GLuint texture = r32f_texture();
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, texture);
    glActiveTexture(GL_TEXTURE0);
    Camera camera(Projection::Perspective, kWidth, kHeight, Lens(), glm::dmat4(1.0));
    std::vector<Hit> hits = trace(camera, {plane(1, glm::dvec3(0.0, 0.0, -5.0), glm::dvec3(0.0, 0.0, 1.0))});
    std::vector<float> v = render(camera, hits, 1.0f, OBSCURA_DEBUG_NONE);
    ASSERT_FALSE(v.empty());
    GLint bound = 0, active = 0;
    glActiveTexture(GL_TEXTURE2);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    EXPECT_EQ(GLuint(bound), texture);
    EXPECT_EQ(active, GL_TEXTURE0);
    glDeleteTextures(1, &texture);
}

}  // namespace host_loader_test

#endif  // OBSCURA_TESTS_HOST_LOADER_TESTS_H
