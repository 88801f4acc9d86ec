#include "obscura_session.h"

#include <cstdio>

#include "cli_errors.h"
#include "headless_gl.h"

namespace obscura::cli {

ObscuraSession::ObscuraSession(uint32_t flags) : flags_(flags) {
    obscura_context_desc desc{};
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = &samples::HeadlessGL::get_proc_address;
    desc.log = &log_to_stderr;
    desc.flags = flags;
    const obscura_status status = obscura_create_context(&desc, &context_);
    if (status != OBSCURA_OK) {
        // No context exists to ask for the detail; the log callback has already printed it.
        context_ = nullptr;
        throw ApiError(api_error_message(status, "obscura_create_context", nullptr));
    }
}

ObscuraSession::~ObscuraSession() {
    obscura_destroy_context(context_);
}

void ObscuraSession::check(obscura_status status, const std::string& call) const {
    if (status != OBSCURA_OK) throw ApiError(api_error_message(status, call, context_));
}

ObscuraView::ObscuraView(const ObscuraSession& session) : context_(session.get()) {
    session.check(obscura_create_view(context_, &view_), "obscura_create_view");
}

ObscuraView::~ObscuraView() {
    if (view_) obscura_destroy_view(context_, view_);
}

std::string api_error_message(obscura_status status, const std::string& call, const obscura_context* context) {
    std::string message = call + " failed: " + obscura_status_string(status);
    const char* detail = context ? obscura_get_last_error(context) : "";
    if (detail && *detail) message += std::string(": ") + detail;
    return message;
}

void log_to_stderr(obscura_log_level level, obscura_status status, const char* message, void*) {
    const char* level_name = level == OBSCURA_LOG_ERROR ? "error" : level == OBSCURA_LOG_WARNING ? "warning" : "info";
    if (status != OBSCURA_OK) {
        std::fprintf(stderr, "[obscura %s] %s: %s\n", level_name, obscura_status_string(status), message ? message : "");
    } else {
        std::fprintf(stderr, "[obscura %s] %s\n", level_name, message ? message : "");
    }
}

uint32_t timing_flags(const samples::HeadlessGL& gl, bool sync_timing_requested) {
    return sync_timing_requested || gl.is_software() ? uint32_t(OBSCURA_CONTEXT_FLAG_SYNC_TIMING) : 0u;
}

uint32_t code_path_flags(bool gpu_code_paths) {
    return gpu_code_paths ? uint32_t(OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS | OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES) : 0u;
}

}  // namespace obscura::cli
