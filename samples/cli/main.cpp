// obscura: command-line front end of the Obscura SDK on a built-in demo scene, without a window.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "cli_errors.h"
#include "commands.h"
#include "headless_gl.h"

namespace {

const char* const kUsage = R"(usage:
  obscura --list-settings [METHOD]
  obscura render --method METHOD[:key=value,...] --out AO.png [--pfm AO.pfm] [--size 640x360]
                 [--guard-band 0.1] [--projection perspective|reversed|infinite|reversed-infinite|ortho]
                 [--depth-format d32f|d24|d24s8] [--msaa N] [--normals] [--no-clip-control]
                 [--debug-view none|depth|normals|ao-before-blur] [--sync-timing]
  obscura bench [--method METHOD[:...]]... [--size WxH]... [--frames 50] [--warmup 5] [--csv FILE]
                [--sync-timing] [--normals] [scene options of render]
  obscura demo [--out-dir demo-output] [--frames 10] [--sync-timing]

Settings keys come from the SDK's metadata (see --list-settings); toggles take on/off.
--normals passes the scene's view-space normals (otherwise the SDK reconstructs them from depth).
--sync-timing times passes with glFinish (automatic on llvmpipe/softpipe, whose timer queries read 0).
Environment: OBSCURA_GL_BACKEND=auto|egl-device|egl-surfaceless|osmesa picks the headless GL backend.
)";

}  // namespace

int main(int argc, char** argv) {
    using namespace obscura::cli;
    std::vector<std::string> arguments(argv + 1, argv + argc);
    if (arguments.empty() || arguments[0] == "--help" || arguments[0] == "-h" || arguments[0] == "help") {
        std::fputs(kUsage, arguments.empty() ? stderr : stdout);
        return arguments.empty() ? 2 : 0;
    }
    const std::string command = arguments[0];
    ArgumentList rest(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
    try {
        if (command == "--list-settings" || command == "list-settings") return run_list_settings(rest);
        if (command == "render") return run_render(rest);
        if (command == "bench") return run_bench(rest);
        if (command == "demo") return run_demo(rest);
        throw UsageError("unknown command '" + command + "'");
    } catch (const UsageError& error) {
        std::fprintf(stderr, "obscura: %s\n(run 'obscura --help' for usage)\n", error.what());
        return 2;
    } catch (const ApiError& error) {
        std::fprintf(stderr, "obscura: error: %s\n", error.what());
        return 1;
    } catch (const obscura::samples::HeadlessGLError& error) {
        std::fprintf(stderr, "obscura: no OpenGL: %s\n", error.what());
        return 1;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "obscura: error: %s\n", error.what());
        return 1;
    }
}
