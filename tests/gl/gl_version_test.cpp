// A real GL 3.3 core context must be rejected with GL_VERSION_UNSUPPORTED. Mesa hands out its highest
// core version whatever is asked, so CTest runs this executable with MESA_GL_VERSION_OVERRIDE=3.3 (which
// caps every context of the process: that is why it is not part of obscura_gl_tests). With
// OBSCURA_TEST_REQUIRE_GL33=1 a driver that still gives a newer version fails instead of skipping.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "headless_gl.h"
#include "obscura/obscura.h"

namespace {

void capture_log(obscura_log_level, obscura_status, const char* message, void* user_data) {
    *static_cast<std::string*>(user_data) = message;
}

TEST(GlVersion, Core33ContextIsRejected) {
    obscura::samples::HeadlessGL::Options options;
    options.major = 3;
    options.minor = 3;
    obscura::samples::HeadlessGL gl(options);
    const bool required = std::getenv("OBSCURA_TEST_REQUIRE_GL33") != nullptr;
    if (gl.gl_major() * 100 + gl.gl_minor() >= 403) {
        if (required) FAIL() << "asked for GL 3.3 core, got " << gl.gl_version();
        GTEST_SKIP() << "the driver gave " << gl.gl_version() << " for a 3.3 request";
    }
    obscura_context_desc desc = {};
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = &obscura::samples::HeadlessGL::get_proc_address;
    std::string message;
    desc.log = &capture_log;
    desc.log_user_data = &message;
    obscura_context* context = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_GL_VERSION_UNSUPPORTED);
    EXPECT_EQ(context, nullptr);
    EXPECT_NE(message.find("3.3"), std::string::npos) << message;
}

}  // namespace
