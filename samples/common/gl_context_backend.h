// Internal to HeadlessGL: the interface one windowless context implementation (EGL or OSMesa) offers,
// and the factory functions that create them. Each factory throws std::runtime_error with the reason
// when it cannot give a context of the requested version.
#ifndef OBSCURA_SAMPLES_GL_CONTEXT_BACKEND_H
#define OBSCURA_SAMPLES_GL_CONTEXT_BACKEND_H

#include <memory>
#include <string>

namespace obscura::samples::detail {

// Looks up a GL entry point; the shape of obscura_get_proc_address_fn.
using ProcAddressFn = void* (*)(const char* name);

struct ContextRequest {
    int major = 4;
    int minor = 3;
    bool core_profile = true;
};

class ContextBackend {
public:
    virtual ~ContextBackend() = default;
    // Makes the context current on the calling thread; throws on failure.
    virtual void make_current() = 0;
    // Makes no context current on the calling thread if this one is current there.
    virtual void release() = 0;
    virtual bool is_current() const = 0;
    // The backend's own lookup (eglGetProcAddress, OSMesaGetProcAddress).
    virtual ProcAddressFn proc_address() const = 0;
    // True when a NULL from proc_address() may be retried with dlsym on libOpenGL / libGL: right for
    // EGL through glvnd, wrong for OSMesa, whose functions only its own lookup returns.
    virtual bool allows_library_fallback() const = 0;
    // E.g. "EGL device 0 of 2: NVIDIA (/dev/dri/renderD128), EGL 1.5 NVIDIA".
    virtual std::string platform_description() const = 0;
};

std::unique_ptr<ContextBackend> create_egl_device_context(const ContextRequest& request);
// The Mesa surfaceless platform, then eglGetDisplay(EGL_DEFAULT_DISPLAY).
std::unique_ptr<ContextBackend> create_egl_surfaceless_context(const ContextRequest& request);
std::unique_ptr<ContextBackend> create_osmesa_context(const ContextRequest& request);
bool osmesa_available();

}  // namespace obscura::samples::detail

#endif  // OBSCURA_SAMPLES_GL_CONTEXT_BACKEND_H
