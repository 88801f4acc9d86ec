// Building the embedded compute shaders (sdk/src/gl/program.cpp) when the driver refuses one: the status, what the
// returned error says, and what reaches the host's log callback (the whole driver log once, as a warning: the error
// itself reaches the callback from the API call that returns it, Context::report).
#include <string>
#include <vector>

#include "gl/program.h"
#include "pass_test_support.h"

namespace {

struct LogLine {
    obscura_log_level level;
    obscura_status status;
    std::string message;
};

void record(obscura_log_level level, obscura_status status, const char* message, void* user_data) {
    static_cast<std::vector<LogLine>*>(user_data)->push_back({level, status, message});
}

class ProgramBuild : public obscura_pass_test::PassTest {};

// gtao_denoise.comp stops with #error when a define it needs is missing: the driver refuses to compile it.
constexpr char kMissingDefine[] = "OBSCURA_GTAO_BENT_NORMALS 0\nOBSCURA_GTAO_DENOISE_FINAL 0\nOBSCURA_GTAO_DENOISE_RUN 4\n";

TEST_F(ProgramBuild, RefusedCompileLogsTheDriversLogOnceAndTheErrorNamesItsFirstErrorLine) {
    std::vector<LogLine> lines;
    obscura::gl::Object program;
    const obscura::Error error = obscura::gl::build_compute_program(gl_, "gtao_denoise.comp", kMissingDefine, alloc_,
                                                                    record, &lines, &program);
    EXPECT_EQ(error.status(), OBSCURA_STATUS_SHADER_COMPILE_FAILED);
    EXPECT_FALSE(program);
    const std::string message = error.message();
    EXPECT_NE(message.find("compiling gtao_denoise.comp failed"), std::string::npos) << message;
    EXPECT_NE(message.find("OBSCURA_GTAO_DENOISE_TARGET must be defined"), std::string::npos) << message;
    EXPECT_NE(message.find("went to the log callback"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    // One callback: the driver's whole log, as a warning (the error is the caller's to report).
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(lines[0].level, OBSCURA_LOG_WARNING);
    EXPECT_EQ(lines[0].status, OBSCURA_STATUS_SHADER_COMPILE_FAILED);
    EXPECT_NE(lines[0].message.find("gtao_denoise.comp"), std::string::npos);
    EXPECT_NE(lines[0].message.find("OBSCURA_GTAO_DENOISE_TARGET must be defined"), std::string::npos)
        << lines[0].message;
}

TEST_F(ProgramBuild, RefusedCompileWithoutALogCallbackKeepsTheFirstErrorLineInTheError) {
    obscura::gl::Object program;
    const obscura::Error error = obscura::gl::build_compute_program(gl_, "gtao_denoise.comp", kMissingDefine, alloc_,
                                                                    nullptr, nullptr, &program);
    EXPECT_EQ(error.status(), OBSCURA_STATUS_SHADER_COMPILE_FAILED);
    const std::string message = error.message();
    EXPECT_NE(message.find("OBSCURA_GTAO_DENOISE_TARGET must be defined"), std::string::npos) << message;
    EXPECT_EQ(message.find("log callback"), std::string::npos) << message;
}

}  // namespace
