// obscura-viewer: tune every setting of every method on a real scene and see the cost and the error at once.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "settings_document.h"
#include "viewer_app.h"

namespace {

constexpr const char* kUsage =
    "usage: obscura-viewer [--scene NAME|FILE.obj|FILE.pfm] [--viewpoint NAME] [--method SPEC]\n"
    "                      [--settings FILE.json] [--view ao|lit|lit-no-ao|split|error]\n"
    "                      [--compare reference|truth|SPEC] [--size WxH] [--normals] [--reference-rays N]\n"
    "                      [--truth-rays N] [--spin DEG] [--screenshot OUT.png --frames N]\n"
    "SPEC is NAME[:KEY=VALUE...] as in `obscura --list-settings`, e.g. hbao:directions=16:steps=48 or\n"
    "  lsao:preset=k32 (enums by name or number; the falloff table as falloff_table=V0/.../V15 or @FILE).\n"
    "--compare: what the error heat map and the split view compare the method with: `reference`, the\n"
    "  screen-space reference (REFERENCE: the depth buffer ray-traced, infinitely thick; the default), or\n"
    "  `truth`, the geometry truth (the scene's triangles ray-traced on the CPU, --truth-rays per pixel,\n"
    "  default 256; not for .pfm depth files); a SPEC puts a second method on the split view's right.\n"
    "--spin DEG turns the orbit camera DEG degrees every frame: with --method M:temporal.enabled=on --compare M --view\n"
    "  split, temporal accumulation on (left) and off (right) side by side while the camera moves.\n"
    "--screenshot with --frames N renders N frames, saves the window (panel included) and exits; with\n"
    "  --compare truth the frame before the last waits for the geometry truth to complete.\n"
    "Mouse: drag to orbit (fly: to look), wheel to dolly; fly mode moves with W A S D Q E.\n";

int usage_error(const std::string& message) {
    std::fprintf(stderr, "obscura-viewer: %s\n%s", message.c_str(), kUsage);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    using obscura::viewer::ViewMode;
    obscura::viewer::ViewerOptions options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::printf("%s", kUsage);
            return 0;
        }
        if (arg == "--normals") {
            options.use_normals = true;
            continue;
        }
        if (i + 1 >= argc) return usage_error("missing value for " + arg);
        const std::string value = argv[++i];
        if (arg == "--scene") {
            options.scene = value;
        } else if (arg == "--viewpoint") {
            options.viewpoint = value;
        } else if (arg == "--method") {
            options.method = value;
        } else if (arg == "--settings") {
            options.settings_file = value;
        } else if (arg == "--compare") {
            options.compare = value;
            options.comparison = value == "truth" ? obscura::viewer::Comparison::GeometryTruth
                                                  : obscura::viewer::Comparison::ScreenSpaceReference;
        } else if (arg == "--screenshot") {
            options.screenshot = value;
        } else if (arg == "--frames" || arg == "--reference-rays" || arg == "--truth-rays") {
            char* rest = nullptr;
            const long n = std::strtol(value.c_str(), &rest, 10);
            if (*rest != 0 || n < 1 || n > 100000) return usage_error(arg + " needs a count in [1, 100000]");
            (arg == "--frames" ? options.frames : arg == "--truth-rays" ? options.truth_rays : options.reference_rays) =
                int(n);
        } else if (arg == "--spin") {
            char* rest = nullptr;
            const double degrees = std::strtod(value.c_str(), &rest);
            if (*rest != 0 || !(degrees >= -45.0 && degrees <= 45.0)) return usage_error("--spin needs degrees in [-45, 45]");
            options.spin = float(degrees);
        } else if (arg == "--size") {
            int w = 0, h = 0;
            char tail = 0;
            if (std::sscanf(value.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 64 || h < 64 || w > 8192 || h > 8192) {
                return usage_error("--size needs WxH, each in [64, 8192]");
            }
            options.width = w;
            options.height = h;
        } else if (arg == "--view") {
            const ViewMode modes[] = {ViewMode::AoOnly, ViewMode::LitWithAo, ViewMode::LitWithoutAo, ViewMode::Split,
                                      ViewMode::ErrorMap};
            bool found = false;
            for (ViewMode mode : modes) {
                if (value == obscura::viewer::view_mode_name(mode)) {
                    options.view = mode;
                    found = true;
                }
            }
            if (!found) return usage_error("--view takes ao, lit, lit-no-ao, split or error");
        } else {
            return usage_error("unknown argument '" + arg + "'");
        }
    }
    if (options.frames > 0 && options.screenshot.empty()) return usage_error("--frames goes with --screenshot");
    // Without --frames the window would stay open and never write the screenshot.
    if (!options.screenshot.empty() && options.frames == 0) return usage_error("--screenshot goes with --frames N");
    try {
        obscura::viewer::settings_from_spec(options.method);
        if (!options.compare.empty() && options.compare != "reference" && options.compare != "truth") {
            obscura::viewer::settings_from_spec(options.compare);
        }
    } catch (const std::invalid_argument& error) {
        return usage_error(error.what());
    }
    // A settings file that does not load is a bad argument too (the window reads it again when it starts).
    if (!options.settings_file.empty()) {
        std::string text, error;
        if (!obscura::viewer::read_text_file(options.settings_file, &text, &error)) return usage_error(error);
        try {
            obscura::viewer::settings_from_json(text);
        } catch (const std::exception& failure) {
            return usage_error("--settings " + options.settings_file + ": " + failure.what());
        }
    }
    return obscura::viewer::run_viewer(options);
}
