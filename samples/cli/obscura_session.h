// ObscuraSession: one obscura_context for the GL context current on this thread, with the CLI's log
// callback, destroyed with it. check() turns a failed status into an ApiError.
#ifndef OBSCURA_CLI_OBSCURA_SESSION_H
#define OBSCURA_CLI_OBSCURA_SESSION_H

#include <cstdint>
#include <string>

#include "obscura/obscura.h"

namespace obscura::samples {
class HeadlessGL;
}

namespace obscura::cli {

class ObscuraSession {
public:
    // flags: OBSCURA_CONTEXT_FLAG_*. Throws ApiError when obscura_create_context fails.
    explicit ObscuraSession(uint32_t flags);
    ~ObscuraSession();
    ObscuraSession(const ObscuraSession&) = delete;
    ObscuraSession& operator=(const ObscuraSession&) = delete;

    obscura_context* get() const { return context_; }
    uint32_t flags() const { return flags_; }
    // Throws ApiError("<call>: <obscura_status_string>: <last error>") unless status is OK.
    void check(obscura_status status, const std::string& call) const;

private:
    obscura_context* context_ = nullptr;
    uint32_t flags_ = 0;
};

// One obscura_view of a session (a temporal history of its own), destroyed with this object (before the session).
class ObscuraView {
public:
    // Throws ApiError when obscura_create_view fails.
    explicit ObscuraView(const ObscuraSession& session);
    ~ObscuraView();
    ObscuraView(const ObscuraView&) = delete;
    ObscuraView& operator=(const ObscuraView&) = delete;
    obscura_view* get() const { return view_; }

private:
    obscura_context* context_ = nullptr;
    obscura_view* view_ = nullptr;
};

// Builds the ApiError message for a failed call; `context` may be NULL.
std::string api_error_message(obscura_status status, const std::string& call, const obscura_context* context);

// The obscura_log_fn the CLI installs: every SDK message goes to stderr.
void log_to_stderr(obscura_log_level level, obscura_status status, const char* message, void* user_data);

// OBSCURA_CONTEXT_FLAG_SYNC_TIMING when asked for, or when the renderer is a software one whose
// timer queries read 0 (llvmpipe, softpipe): per-pass times then come from glFinish + the CPU clock.
uint32_t timing_flags(const samples::HeadlessGL& gl, bool sync_timing_requested);

// --gpu-code-paths: OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS (the variants GPUs run, on a CPU rasteriser too) with
// VALIDATE_PASSES, so that a GL error on those paths names its pass; 0 otherwise.
uint32_t code_path_flags(bool gpu_code_paths);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_OBSCURA_SESSION_H
