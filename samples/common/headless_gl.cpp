#include "headless_gl.h"

#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "gl_context_backend.h"
#include "host_gl.h"

namespace obscura::samples {
namespace {

// The lookup behind HeadlessGL::get_proc_address. obscura_get_proc_address_fn carries no user
// data, so the active backend is kept here: per thread, because "current" is per thread in GL,
// and process-wide as a fallback for threads that never made a HeadlessGL current themselves.
struct ActiveLoader {
    detail::ProcAddressFn lookup = nullptr;
    bool library_fallback = false;
};
thread_local ActiveLoader t_active_loader;
std::mutex g_last_loader_mutex;
ActiveLoader g_last_loader;

// The host loader's pointers are process-global; they are refilled only when a context with a
// different lookup or version becomes current (glad loads only the versions the context reports).
struct HostLoaderKey {
    detail::ProcAddressFn lookup = nullptr;
    int major = 0;
    int minor = 0;
    bool operator==(const HostLoaderKey& other) const {
        return lookup == other.lookup && major == other.major && minor == other.minor;
    }
};
std::mutex g_host_loader_mutex;
HostLoaderKey g_host_loader_key;

// libOpenGL (glvnd) or libGL, opened once for the process lifetime: only for entry points an EGL
// driver's eglGetProcAddress does not return (EGL < 1.5 drivers may omit core functions).
void* gl_library() {
    static void* const handle = [] {
        for (const char* name : {"libOpenGL.so.0", "libGL.so.1"}) {
            if (void* library = dlopen(name, RTLD_LAZY | RTLD_LOCAL)) return library;
        }
        return static_cast<void*>(nullptr);
    }();
    return handle;
}

GLADapiproc glad_lookup(const char* name) {
    return reinterpret_cast<GLADapiproc>(HeadlessGL::get_proc_address(name));
}

std::string gl_string(GLenum name) {
    const GLubyte* value = glGetString(name);
    return value ? reinterpret_cast<const char*>(value) : "";
}

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

std::vector<HeadlessGL::Backend> backends_to_try(HeadlessGL::Backend requested) {
    using Backend = HeadlessGL::Backend;
    if (requested != Backend::Auto) return {requested};
    std::vector<Backend> order = {Backend::EglDevice, Backend::EglSurfaceless};
    if (detail::osmesa_available()) order.push_back(Backend::OSMesa);
    return order;
}

std::unique_ptr<detail::ContextBackend> create_backend(HeadlessGL::Backend backend,
                                                       const detail::ContextRequest& request) {
    switch (backend) {
    case HeadlessGL::Backend::EglDevice: return detail::create_egl_device_context(request);
    case HeadlessGL::Backend::EglSurfaceless: return detail::create_egl_surfaceless_context(request);
    case HeadlessGL::Backend::OSMesa: return detail::create_osmesa_context(request);
    case HeadlessGL::Backend::Auto: break;
    }
    throw HeadlessGLError("Backend::Auto is not a backend");
}

}  // namespace

#ifndef OBSCURA_SAMPLES_HAVE_OSMESA
namespace detail {
bool osmesa_available() { return false; }
std::unique_ptr<ContextBackend> create_osmesa_context(const ContextRequest&) {
    throw HeadlessGLError("built without OSMesa (pkg-config osmesa not found, or OBSCURA_SAMPLES_WITH_OSMESA=OFF)");
}
}  // namespace detail
#endif

HeadlessGL::HeadlessGL() : HeadlessGL(Options{}) {}

HeadlessGL::HeadlessGL(const Options& options) {
    Backend requested = options.backend;
    if (options.honor_environment) {
        const char* from_environment = std::getenv("OBSCURA_GL_BACKEND");
        if (from_environment && *from_environment) requested = parse_backend(from_environment);
    }
    const detail::ContextRequest request{options.major, options.minor, options.core_profile};
    const std::string version = std::to_string(options.major) + "." + std::to_string(options.minor) +
                                (options.core_profile ? " core" : " compatibility");

    std::string failures;
    for (Backend candidate : backends_to_try(requested)) {
        try {
            context_ = create_backend(candidate, request);
            backend_ = candidate;
            make_current();
            if (gl_major_ * 100 + gl_minor_ < options.major * 100 + options.minor) {
                throw HeadlessGLError("got GL " + std::to_string(gl_major_) + "." + std::to_string(gl_minor_));
            }
            return;
        } catch (const std::exception& error) {
            failures += std::string("\n  ") + backend_name(candidate) + ": " + error.what();
            if (context_) release();
            context_.reset();
        }
    }
    throw HeadlessGLError("could not create an OpenGL " + version + " context without a window:" + failures);
}

HeadlessGL::~HeadlessGL() {
    if (context_) release();
}

void HeadlessGL::make_current() {
    context_->make_current();
    t_active_loader = ActiveLoader{context_->proc_address(), context_->allows_library_fallback()};
    {
        std::lock_guard<std::mutex> lock(g_last_loader_mutex);
        g_last_loader = t_active_loader;
    }
    load_host_functions();
}

void HeadlessGL::release() {
    context_->release();
}

bool HeadlessGL::is_current() const {
    return context_->is_current();
}

void HeadlessGL::load_host_functions() {
    std::lock_guard<std::mutex> lock(g_host_loader_mutex);
    const HostLoaderKey key{context_->proc_address(), gl_major_, gl_minor_};
    if (gl_major_ != 0 && key == g_host_loader_key) return;

    const int loaded = gladLoadGL(&glad_lookup);
    if (loaded == 0) {
        g_host_loader_key = HostLoaderKey{};
        throw HeadlessGLError("gladLoadGL failed: the context returned no usable glGetString");
    }
    gl_major_ = GLAD_VERSION_MAJOR(loaded);
    gl_minor_ = GLAD_VERSION_MINOR(loaded);
    g_host_loader_key = HostLoaderKey{context_->proc_address(), gl_major_, gl_minor_};
    gl_version_ = gl_string(GL_VERSION);
    renderer_ = gl_string(GL_RENDERER);
    vendor_ = gl_string(GL_VENDOR);
}

HeadlessGL::GLFunction HeadlessGL::get_proc_address(const char* name) {
    if (!name) return nullptr;
    ActiveLoader loader = t_active_loader;
    if (!loader.lookup) {
        std::lock_guard<std::mutex> lock(g_last_loader_mutex);
        loader = g_last_loader;
    }
    if (!loader.lookup) return nullptr;
    void* function = loader.lookup(name);
    if (!function && loader.library_fallback) {
        if (void* library = gl_library()) function = dlsym(library, name);
    }
    return reinterpret_cast<GLFunction>(function);
}

bool HeadlessGL::is_software() const {
    const std::string name = lowercase(renderer_);
    for (const char* software : {"llvmpipe", "softpipe", "swrast", "software rasterizer"}) {
        if (name.find(software) != std::string::npos) return true;
    }
    return false;
}

std::string HeadlessGL::describe() const {
    return context_->platform_description() + " / GL " + gl_version_ + ", renderer " + renderer_;
}

const char* HeadlessGL::backend_name(Backend backend) {
    switch (backend) {
    case Backend::Auto: return "auto";
    case Backend::EglDevice: return "egl-device";
    case Backend::EglSurfaceless: return "egl-surfaceless";
    case Backend::OSMesa: return "osmesa";
    }
    return "unknown";
}

HeadlessGL::Backend HeadlessGL::parse_backend(const std::string& name) {
    for (Backend backend : {Backend::Auto, Backend::EglDevice, Backend::EglSurfaceless, Backend::OSMesa}) {
        if (lowercase(name) == backend_name(backend)) return backend;
    }
    throw HeadlessGLError("unknown GL backend '" + name + "' (OBSCURA_GL_BACKEND): use auto, egl-device, "
                          "egl-surfaceless or osmesa");
}

}  // namespace obscura::samples
