// A fixture for tests that drive SDK passes directly through the private headers (obscura_pass_tests):
// the process's GL context, the SDK's function table loaded from it, and a PassEnv with the SDK's samplers
// and a uniform buffer.
#ifndef OBSCURA_TESTS_PASS_TEST_SUPPORT_H
#define OBSCURA_TESTS_PASS_TEST_SUPPORT_H

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "gl/gl_api.h"
#include "gl/gl_objects.h"
#include "headless_gl.h"
#include "host_allocator.h"
#include "passes/pass_common.h"

namespace obscura_pass_test {

inline obscura::samples::HeadlessGL& shared_gl() {
    // Leaked on purpose, as in gl_test_support.cpp: Mesa's own exit handlers must not race its destruction.
    static obscura::samples::HeadlessGL* context = new obscura::samples::HeadlessGL();
    return *context;
}

// A GL perspective of 60 degrees vertically over a whole width x height texture, near 0.1, far 100, into
// `matrix` (column-major), and the frame constants of a linear-depth input of that size under it.
inline FrameConstants perspective_linear_depth_frame(int width, int height, float matrix[16]) {
    const float f = 1.0f / std::tan(0.5f * 1.0471976f), n = 0.1f, far_plane = 100.0f;
    for (int i = 0; i < 16; ++i) matrix[i] = 0.0f;
    matrix[0] = f * float(height) / float(width);
    matrix[5] = f;
    matrix[10] = (far_plane + n) / (n - far_plane);
    matrix[11] = -1.0f;
    matrix[14] = 2.0f * far_plane * n / (n - far_plane);
    FrameConstants frame = {};
    frame.proj_scale[0] = matrix[0];
    frame.proj_scale[1] = matrix[5];
    frame.proj_depth[0] = matrix[10];
    frame.proj_depth[1] = matrix[14];
    frame.proj_depth[2] = matrix[11];
    frame.proj_offset[2] = 2.0f;
    frame.proj_offset[3] = -1.0f;
    frame.depth_params[0] = 1.0f;
    frame.depth_params[1] = 1.0f;
    frame.depth_params[2] = 1.0f / float(width);
    frame.depth_params[3] = 1.0f / float(height);
    frame.depth_size[0] = width;
    frame.depth_size[1] = height;
    frame.depth_size[2] = OBSCURA_DEPTH_SOURCE_LINEAR;
    frame.work_rect[2] = width;
    frame.work_rect[3] = height;
    return frame;
}

// The frame resources a pass reads, for a width x height linear-depth image: R32F depth uploaded from
// `depth` (row-major, bottom row first) and RG16_SNORM normals all (0, 0), which decode to +z.
inline void upload_linear_depth(const obscura::gl::Table& gl, const std::vector<float>& depth, int width, int height,
                                obscura::FrameResources* resources) {
    resources->width = width;
    resources->height = height;
    resources->linear_depth = obscura::gl::Texture2D::create(gl, GL_R32F, width, height);
    resources->normals = obscura::gl::Texture2D::create(gl, GL_RG16_SNORM, width, height);
    gl.BindTexture(GL_TEXTURE_2D, resources->linear_depth.name());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RED, GL_FLOAT, depth.data());
    const std::vector<int16_t> normals(size_t(width) * size_t(height) * 2, 0);
    gl.BindTexture(GL_TEXTURE_2D, resources->normals.name());
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RG, GL_SHORT, normals.data());
    gl.BindTexture(GL_TEXTURE_2D, 0);
}

class PassTest : public ::testing::Test {
protected:
    void SetUp() override {
        shared_gl().make_current();
        loader_.plain = &obscura::samples::HeadlessGL::get_proc_address;
        ASSERT_GE(obscura_gl_load_table(&gl_, &loader_), 40003);
        sampler_ = obscura::gl::create_sampler_nearest_clamp(gl_);
        sampler_mipmap_ = obscura::gl::create_sampler_nearest_mipmap_clamp(gl_);
        uniforms_ = obscura::gl::Buffer::create(gl_, GL_UNIFORM_BUFFER, obscura::UniformArena::kCapacity);
        GLint alignment = 256;
        gl_.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
        arena_.reset(alignment);
    }
    void TearDown() override { EXPECT_EQ(gl_.GetError(), GLenum(GL_NO_ERROR)); }

    obscura::PassEnv env() const {
        return obscura::PassEnv{gl_,        alloc_, nullptr, nullptr, sampler_.name(), sampler_mipmap_.name(),
                                uniforms_.name(), cpu_renderer_};
    }

    // As on llvmpipe, where these tests run (LSAO: whole lines, a private hull); false selects what a GPU
    // runs.
    bool cpu_renderer_ = true;

    ObscuraGlLoader loader_ = {};
    obscura::gl::Table gl_ = {};
    obscura::AllocatorCallbacks alloc_ = obscura::AllocatorCallbacks::from(obscura_allocator{});
    obscura::gl::Object sampler_, sampler_mipmap_;
    obscura::gl::Buffer uniforms_;
    obscura::UniformArena arena_;
};

}  // namespace obscura_pass_test

#endif  // OBSCURA_TESTS_PASS_TEST_SUPPORT_H
