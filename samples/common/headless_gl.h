// HeadlessGL: an OpenGL context with no window, for the CLI and the tests.
//
// Backends, tried in this order by Backend::Auto:
//   EglDevice       EGL_EXT_platform_device on an enumerated device, NVIDIA or hardware first
//                   (works on GPU servers without X or a DRM master);
//   EglSurfaceless  EGL_PLATFORM_SURFACELESS_MESA, then eglGetDisplay(EGL_DEFAULT_DISPLAY);
//   OSMesa          Mesa's off-screen library (when it was found at configure time).
// The environment variable OBSCURA_GL_BACKEND = auto | egl-device | egl-surfaceless | osmesa
// overrides the backend asked for in Options.
//
// The context is current on the constructing thread when the constructor returns, and the host
// loader (host_gl.h) is loaded for it. Several HeadlessGL may be alive at once; make_current() switches.
#ifndef OBSCURA_SAMPLES_HEADLESS_GL_H
#define OBSCURA_SAMPLES_HEADLESS_GL_H

#include <memory>
#include <stdexcept>
#include <string>

namespace obscura::samples {

namespace detail {
class ContextBackend;
}

// Thrown when no backend could give the requested context.
class HeadlessGLError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class HeadlessGL {
public:
    enum class Backend { Auto, EglDevice, EglSurfaceless, OSMesa };

    struct Options {
        Backend backend = Backend::Auto;
        // Requested version. Drivers may return any newer compatible version (Mesa and NVIDIA give
        // their highest core version), so check gl_major()/gl_minor() for what was actually created.
        // To really get GL 3.3 from Mesa, run the process with MESA_GL_VERSION_OVERRIDE=3.3 (read
        // once per process, before the first context); 4.3 requests then fail.
        int major = 4;
        int minor = 3;
        bool core_profile = true;
        // Let OBSCURA_GL_BACKEND override `backend`.
        bool honor_environment = true;
    };

    HeadlessGL();  // Options{}: GL 4.3 core, Backend::Auto
    explicit HeadlessGL(const Options& options);
    ~HeadlessGL();
    HeadlessGL(const HeadlessGL&) = delete;
    HeadlessGL& operator=(const HeadlessGL&) = delete;

    // Makes this context current on the calling thread and points get_proc_address() and the host
    // loader at it.
    void make_current();
    // Makes no context current on the calling thread (if this one is current there).
    void release();
    bool is_current() const;

    // Forwards to the lookup of the backend whose context this thread made current last (EGL or
    // OSMesa), so it can be given to obscura_context_desc.get_proc_address directly.
    // If the backend returns NULL for an EGL context, libOpenGL.so.0 / libGL.so.1 are asked with dlsym.
    using GLFunction = void (*)();  // the shape of obscura_gl_function
    static GLFunction get_proc_address(const char* name);

    Backend backend() const { return backend_; }
    int gl_major() const { return gl_major_; }
    int gl_minor() const { return gl_minor_; }
    const std::string& gl_version() const { return gl_version_; }
    const std::string& renderer() const { return renderer_; }
    const std::string& vendor() const { return vendor_; }
    // llvmpipe, softpipe, swrast: timer queries read 0 and everything is slow.
    bool is_software() const;
    // E.g. "EGL device 0 of 1: NVIDIA (/dev/dri/renderD128) / GL 4.6.0 NVIDIA 580.65, renderer NVIDIA H100".
    std::string describe() const;

    static const char* backend_name(Backend backend);
    // Parses "auto", "egl-device", "egl-surfaceless", "osmesa"; throws HeadlessGLError otherwise.
    static Backend parse_backend(const std::string& name);

private:
    void load_host_functions();

    std::unique_ptr<detail::ContextBackend> context_;
    Backend backend_ = Backend::Auto;
    int gl_major_ = 0;
    int gl_minor_ = 0;
    std::string gl_version_;
    std::string renderer_;
    std::string vendor_;
};

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_HEADLESS_GL_H
