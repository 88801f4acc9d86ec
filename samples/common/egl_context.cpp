// EGL backends of HeadlessGL: the device platform (EGL_EXT_platform_device), Mesa's surfaceless
// platform and the default display. All three end in EglContext, which creates a desktop-GL
// context and makes it current without a surface when the display allows it.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl_context_backend.h"

namespace obscura::samples::detail {
namespace {

std::string egl_error_name(EGLint error) {
    switch (error) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: {
        char text[32];
        std::snprintf(text, sizeof text, "EGL error 0x%04x", unsigned(error));
        return text;
    }
    }
}

[[noreturn]] void throw_egl_error(const std::string& call) {
    throw std::runtime_error(call + " failed: " + egl_error_name(eglGetError()));
}

bool has_extension(const char* extensions, const char* name) {
    if (!extensions) return false;
    const size_t length = std::strlen(name);
    for (const char* at = std::strstr(extensions, name); at; at = std::strstr(at + 1, name)) {
        const bool starts = at == extensions || at[-1] == ' ';
        const bool ends = at[length] == '\0' || at[length] == ' ';
        if (starts && ends) return true;
    }
    return false;
}

std::string egl_string(EGLDisplay display, EGLint name) {
    const char* value = eglQueryString(display, name);
    return value ? value : "";
}

template <typename Function>
Function load_egl_function(const char* name) {
    return reinterpret_cast<Function>(eglGetProcAddress(name));
}

// eglInitialize/eglTerminate are not reference counted: the same native display gives the same
// EGLDisplay, and terminating it would pull the contexts from under a second HeadlessGL. Count here.
class EglDisplayReference {
public:
    explicit EglDisplayReference(EGLDisplay display) : display_(display) {
        std::lock_guard<std::mutex> lock(mutex());
        int& count = counts()[display_];
        if (count == 0) {
            EGLint major = 0, minor = 0;
            if (!eglInitialize(display_, &major, &minor)) {
                counts().erase(display_);
                throw_egl_error("eglInitialize");
            }
        }
        ++count;
    }
    ~EglDisplayReference() {
        std::lock_guard<std::mutex> lock(mutex());
        auto found = counts().find(display_);
        if (found != counts().end() && --found->second == 0) {
            counts().erase(found);
            eglTerminate(display_);
        }
    }
    EglDisplayReference(const EglDisplayReference&) = delete;
    EglDisplayReference& operator=(const EglDisplayReference&) = delete;

    EGLDisplay get() const { return display_; }

private:
    static std::mutex& mutex() {
        static std::mutex instance;
        return instance;
    }
    static std::map<EGLDisplay, int>& counts() {
        static std::map<EGLDisplay, int> instance;
        return instance;
    }
    EGLDisplay display_;
};

void* egl_proc_address(const char* name) {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
}

class EglContext final : public ContextBackend {
public:
    // `display` is obtained but not yet initialised; `label` says where it came from.
    EglContext(EGLDisplay display, const std::string& label, const ContextRequest& request)
        : display_(display) {
        const EGLDisplay egl = display_.get();
        description_ = label + ", EGL " + egl_string(egl, EGL_VERSION) + " " + egl_string(egl, EGL_VENDOR);
        if (!eglBindAPI(EGL_OPENGL_API)) throw_egl_error("eglBindAPI(EGL_OPENGL_API)");

        const char* extensions = eglQueryString(egl, EGL_EXTENSIONS);
        const bool surfaceless = has_extension(extensions, "EGL_KHR_surfaceless_context");
        const bool configless = has_extension(extensions, "EGL_KHR_no_config_context");
        // A config is only needed for a pbuffer (no surfaceless contexts) or without no_config_context.
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!surfaceless || !configless) config = choose_config(egl, !surfaceless);

        std::vector<EGLint> attributes = {EGL_CONTEXT_MAJOR_VERSION, request.major,
                                          EGL_CONTEXT_MINOR_VERSION, request.minor};
        // Profiles exist from GL 3.2 on; asking for one below that is an error.
        if (request.major * 10 + request.minor >= 32) {
            attributes.push_back(EGL_CONTEXT_OPENGL_PROFILE_MASK);
            attributes.push_back(request.core_profile ? EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT
                                                      : EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT);
        }
        attributes.push_back(EGL_NONE);
        context_ = eglCreateContext(egl, config, EGL_NO_CONTEXT, attributes.data());
        if (context_ == EGL_NO_CONTEXT) throw_egl_error("eglCreateContext(GL " + version(request) + ")");

        if (!surfaceless) {
            const EGLint size[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
            surface_ = eglCreatePbufferSurface(egl, config, size);
            if (surface_ == EGL_NO_SURFACE) {
                eglDestroyContext(egl, context_);
                throw_egl_error("eglCreatePbufferSurface");
            }
            description_ += " (pbuffer)";
        }
    }

    ~EglContext() override {
        release();
        if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_.get(), surface_);
        eglDestroyContext(display_.get(), context_);
    }

    void make_current() override {
        // The bound API is per thread: another thread may make this context current.
        if (!eglBindAPI(EGL_OPENGL_API)) throw_egl_error("eglBindAPI(EGL_OPENGL_API)");
        if (!eglMakeCurrent(display_.get(), surface_, surface_, context_)) throw_egl_error("eglMakeCurrent");
    }

    void release() override {
        if (is_current()) eglMakeCurrent(display_.get(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }

    bool is_current() const override { return eglGetCurrentContext() == context_; }
    ProcAddressFn proc_address() const override { return &egl_proc_address; }
    bool allows_library_fallback() const override { return true; }
    std::string platform_description() const override { return description_; }

private:
    static std::string version(const ContextRequest& request) {
        return std::to_string(request.major) + "." + std::to_string(request.minor) +
               (request.core_profile ? " core" : " compatibility");
    }

    static EGLConfig choose_config(EGLDisplay display, bool need_pbuffer) {
        const EGLint attributes[] = {EGL_SURFACE_TYPE, need_pbuffer ? EGL_PBUFFER_BIT : 0,
                                     EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                     EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        if (!eglChooseConfig(display, attributes, &config, 1, &count)) throw_egl_error("eglChooseConfig");
        if (count == 0) throw std::runtime_error("eglChooseConfig found no desktop-GL config");
        return config;
    }

    EglDisplayReference display_;
    EGLContext context_ = EGL_NO_CONTEXT;
    EGLSurface surface_ = EGL_NO_SURFACE;
    std::string description_;
};

// One enumerated EGL device and how much it is preferred.
struct DeviceCandidate {
    EGLDeviceEXT device = nullptr;
    int index = 0;
    std::string label;
    int preference = 0;
};

std::vector<DeviceCandidate> enumerate_devices() {
    const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_extension(client_extensions, "EGL_EXT_platform_device") ||
        !(has_extension(client_extensions, "EGL_EXT_device_enumeration") ||
          has_extension(client_extensions, "EGL_EXT_device_base"))) {
        throw std::runtime_error("EGL_EXT_platform_device / EGL_EXT_device_enumeration not supported");
    }
    const auto query_devices = load_egl_function<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
    const auto query_device_string = load_egl_function<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
    if (!query_devices || !query_device_string) throw std::runtime_error("eglQueryDevicesEXT not found");

    EGLDeviceEXT devices[32];
    EGLint count = 0;
    if (!query_devices(32, devices, &count)) throw_egl_error("eglQueryDevicesEXT");
    if (count == 0) throw std::runtime_error("eglQueryDevicesEXT found no device");

    std::vector<DeviceCandidate> candidates;
    for (EGLint i = 0; i < count; ++i) {
        auto device_string = [&](EGLint name) {
            const char* value = query_device_string(devices[i], name);
            return std::string(value ? value : "");
        };
        const std::string extensions = device_string(EGL_EXTENSIONS);
        const char* extension_list = extensions.c_str();
        const std::string drm_file =
            has_extension(extension_list, "EGL_EXT_device_drm") ? device_string(EGL_DRM_DEVICE_FILE_EXT) : "";
        const std::string vendor =
            has_extension(extension_list, "EGL_EXT_device_query_name") ? device_string(EGL_VENDOR) : "";
        const bool nvidia = vendor.find("NVIDIA") != std::string::npos ||
                            has_extension(extension_list, "EGL_NV_device_cuda");
        const bool software = has_extension(extension_list, "EGL_MESA_device_software");

        DeviceCandidate candidate;
        candidate.device = devices[i];
        candidate.index = i;
        candidate.preference = nvidia ? 3 : software ? 0 : !drm_file.empty() ? 2 : 1;
        candidate.label = "EGL device " + std::to_string(i) + " of " + std::to_string(count) + ": " +
                          (nvidia ? "NVIDIA" : software ? "software" : vendor.empty() ? "hardware" : vendor);
        if (!drm_file.empty()) candidate.label += " (" + drm_file + ")";
        candidates.push_back(candidate);
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const DeviceCandidate& a, const DeviceCandidate& b) { return a.preference > b.preference; });
    return candidates;
}

PFNEGLGETPLATFORMDISPLAYEXTPROC platform_display_function() {
    const auto get_platform_display = load_egl_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (!get_platform_display) throw std::runtime_error("eglGetPlatformDisplayEXT not found");
    return get_platform_display;
}

}  // namespace

std::unique_ptr<ContextBackend> create_egl_device_context(const ContextRequest& request) {
    const std::vector<DeviceCandidate> candidates = enumerate_devices();
    const auto get_platform_display = platform_display_function();
    std::string failures;
    for (const DeviceCandidate& candidate : candidates) {
        try {
            EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, candidate.device, nullptr);
            if (display == EGL_NO_DISPLAY) throw_egl_error("eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT)");
            return std::make_unique<EglContext>(display, candidate.label, request);
        } catch (const std::exception& error) {
            failures += (failures.empty() ? "" : "; ") + candidate.label + ": " + error.what();
        }
    }
    throw std::runtime_error(failures);
}

std::unique_ptr<ContextBackend> create_egl_surfaceless_context(const ContextRequest& request) {
    std::string failures;
    const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (has_extension(client_extensions, "EGL_MESA_platform_surfaceless")) {
        try {
            EGLDisplay display =
                platform_display_function()(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            if (display == EGL_NO_DISPLAY) throw_egl_error("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
            return std::make_unique<EglContext>(display, "EGL surfaceless", request);
        } catch (const std::exception& error) {
            failures = std::string("surfaceless platform: ") + error.what() + "; ";
        }
    } else {
        failures = "EGL_MESA_platform_surfaceless not supported; ";
    }
    try {
        EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        if (display == EGL_NO_DISPLAY) throw_egl_error("eglGetDisplay(EGL_DEFAULT_DISPLAY)");
        return std::make_unique<EglContext>(display, "EGL default display", request);
    } catch (const std::exception& error) {
        throw std::runtime_error(failures + "default display: " + error.what());
    }
}

}  // namespace obscura::samples::detail
