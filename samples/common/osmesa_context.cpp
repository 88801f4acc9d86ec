// OSMesa backend of HeadlessGL: Mesa's off-screen library renders into a client buffer and needs
// neither EGL nor a device. Compiled only when pkg-config found osmesa.
#include <GL/osmesa.h>

#include <stdexcept>
#include <vector>

#include "gl_context_backend.h"

namespace obscura::samples::detail {
namespace {

void* osmesa_proc_address(const char* name) {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
}

class OsMesaContext final : public ContextBackend {
public:
    explicit OsMesaContext(const ContextRequest& request) {
        const int attributes[] = {
            OSMESA_FORMAT, OSMESA_RGBA,
            OSMESA_DEPTH_BITS, 0,
            OSMESA_STENCIL_BITS, 0,
            OSMESA_ACCUM_BITS, 0,
            OSMESA_PROFILE, request.core_profile ? OSMESA_CORE_PROFILE : OSMESA_COMPAT_PROFILE,
            OSMESA_CONTEXT_MAJOR_VERSION, request.major,
            OSMESA_CONTEXT_MINOR_VERSION, request.minor,
            0};
        context_ = OSMesaCreateContextAttribs(attributes, nullptr);
        if (!context_) {
            throw std::runtime_error("OSMesaCreateContextAttribs(GL " + std::to_string(request.major) + "." +
                                     std::to_string(request.minor) + ") failed");
        }
    }

    ~OsMesaContext() override {
        release();
        OSMesaDestroyContext(context_);
    }

    void make_current() override {
        // OSMesa cannot be current without a colour buffer; this small one is the default
        // framebuffer, which the samples never draw to.
        if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, kBufferSize, kBufferSize)) {
            throw std::runtime_error("OSMesaMakeCurrent failed");
        }
    }

    void release() override {
        if (is_current()) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    }

    bool is_current() const override { return OSMesaGetCurrentContext() == context_; }
    ProcAddressFn proc_address() const override { return &osmesa_proc_address; }
    bool allows_library_fallback() const override { return false; }
    std::string platform_description() const override { return "OSMesa"; }

private:
    static constexpr int kBufferSize = 16;
    OSMesaContext context_ = nullptr;
    std::vector<unsigned char> buffer_ = std::vector<unsigned char>(kBufferSize * kBufferSize * 4);
};

}  // namespace

bool osmesa_available() { return true; }

std::unique_ptr<ContextBackend> create_osmesa_context(const ContextRequest& request) {
    return std::make_unique<OsMesaContext>(request);
}

}  // namespace obscura::samples::detail
