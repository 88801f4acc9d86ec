// Shared helpers of the headless-GL tests: the process-wide HeadlessGL, a fixture that gives each test
// a fresh obscura context and checks that no GL error is left behind, host-side texture creation and
// read-back through the host loader (samples/common/host_gl.h), and input/output/settings builders.
#ifndef OBSCURA_TESTS_GL_TEST_SUPPORT_H
#define OBSCURA_TESTS_GL_TEST_SUPPORT_H

#include <cstring>
#include <memory>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "headless_gl.h"
#include "host_gl.h"
#include "host_gl_objects.h"
#include "obscura/obscura.h"

namespace obscura_test {

using obscura::samples::HeadlessGL;
using obscura::samples::HostBuffer;
using obscura::samples::HostFramebuffer;
using obscura::samples::HostProgram;
using obscura::samples::HostRenderbuffer;
using obscura::samples::HostTexture;
using obscura::samples::HostVertexArray;

// The GL 4.3 core context every test of the process shares (created on first use, never destroyed
// before exit). Tests that release it or make another context current call make_current() again.
HeadlessGL& shared_gl();

struct ContextDeleter {
    void operator()(obscura_context* context) const { obscura_destroy_context(context); }
};
using ContextPtr = std::unique_ptr<obscura_context, ContextDeleter>;

// A desc for HeadlessGL::get_proc_address with the given flags.
obscura_context_desc make_desc(uint32_t flags = 0);
// Creates a context on the current GL context; fails the test (and returns null) on error.
ContextPtr create_context(uint32_t flags = 0);

const char* gl_error_name(GLenum error);
// Drains the GL error queue and returns the first error.
GLenum take_gl_error();

// What a context's log callback received.
struct LogEntry {
    obscura_log_level level;
    obscura_status status;
    std::string message;
};
struct LogCapture {
    std::vector<LogEntry> entries;
    static void callback(obscura_log_level level, obscura_status status, const char* message, void* user_data);
    // Sets desc.log / log_user_data to record into this capture.
    void attach(obscura_context_desc* desc);
};

// Every GL test: the shared context current, no pending error before, none left after; ctx() is a
// fresh obscura context whose log goes to log_.
class GLTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    obscura_context* ctx() const { return context_.get(); }
    ContextPtr context_;
    LogCapture log_;
    uint32_t context_flags_ = 0;  // set in a derived constructor to create the context with flags
};

// ---- Host textures ----------------------------------------------------------------------------------
// Immutable storage, nearest filtering, clamp to edge.
HostTexture make_texture(GLenum internal_format, int width, int height);
// Hardware depth from window depths in [0, 1]: D16, D24, D32, D32F (float upload), DEPTH24_STENCIL8
// (packed 24_8 upload, stencil = `stencil`), DEPTH32F_STENCIL8.
HostTexture make_depth_texture(GLenum internal_format, int width, int height, const std::vector<float>& depth,
                               uint8_t stencil = 0x5A);
// GL_R32F / GL_R16F single-channel texture from floats (linear depth input).
HostTexture make_red_texture(GLenum internal_format, int width, int height, const std::vector<float>& values);
// A GL_TEXTURE_2D_MULTISAMPLE depth texture (GL_DEPTH_COMPONENT32F) whose sample 0 holds `depth` and
// every other sample holds `other_samples`, written by a per-sample fragment shader.
HostTexture make_multisample_depth_texture(int width, int height, int samples, const std::vector<float>& depth,
                                           float other_samples);
// Fills level 0 of a colour texture with one RGBA value (converted to the texture's format by GL).
void fill_texture(GLuint texture, int width, int height, float r, float g, float b, float a);
// Level 0 as floats: channels = 1 (GL_RED) or 4 (GL_RGBA); rows bottom-up.
std::vector<float> read_texture(GLuint texture, int width, int height, int channels);
// RGBA8 level 0 as bytes.
std::vector<uint8_t> read_texture_rgba8(GLuint texture, int width, int height);

// Stores any int into an enum field of an API struct, as a C host may, without forming an
// out-of-range value of the C++ enum type (which would be undefined behaviour in the test itself).
template <class Enum>
void store_raw(Enum* field, int32_t value) {
    static_assert(sizeof(Enum) == sizeof(int32_t), "int-sized C enum");
    std::memcpy(field, &value, sizeof value);
}

// A renderbuffer of `format` (multisampled with `samples` > 0) as colour attachment 0 of a framebuffer: a blit target.
struct RenderbufferTarget {
    HostRenderbuffer renderbuffer;
    HostFramebuffer framebuffer;
};
RenderbufferTarget make_renderbuffer_target(GLenum format, int width, int height, int samples = 0);

// ---- API structs ------------------------------------------------------------------------------------
obscura_input make_input(GLuint depth_texture, int width, int height, const float projection[16],
                         obscura_clip_depth clip_depth = OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
obscura_output make_output(GLuint texture, obscura_debug_view debug_view = OBSCURA_DEBUG_NONE);
obscura_settings make_settings(float radius = 1.0f);

// A standard [-1,1] perspective, 60 degrees vertical, near 0.1, far 100, for the given aspect.
void standard_projection(float aspect, float out[16]);

// Renders into a new texture of `format` the size of the output rect and reads it back (channels 1 or
// 4). Fails the test on a non-OK status.
std::vector<float> render_to_new_texture(obscura_context* context, const obscura_input& input,
                                         const obscura_settings& settings, GLenum format, int channels,
                                         obscura_debug_view debug_view = OBSCURA_DEBUG_NONE);

// Live GL objects of the current context per type ("texture", "buffer", "program", ...), found by asking glIs*
// for every name up to 65536 (see the .cpp), and a one-line description of such counts.
std::map<std::string, int> count_gl_objects();
std::string describe(const std::map<std::string, int>& counts);

// Statistics over a float image with a mask; min, max and mean are NaN where the mask selects nothing.
struct Stats {
    int count = 0;
    double min = 0, max = 0, mean = 0;
};
Stats stats(const std::vector<float>& values, const std::vector<bool>& mask);

}  // namespace obscura_test

#endif  // OBSCURA_TESTS_GL_TEST_SUPPORT_H
