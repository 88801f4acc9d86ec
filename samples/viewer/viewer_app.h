// ViewerApp: the obscura-viewer window. GLFW owns the window and the GL 4.3 core context; the app loads its
// own host GL functions (third_party/glad_host) beside the SDK's private loader; Dear ImGui draws the panel.
#ifndef OBSCURA_VIEWER_APP_H
#define OBSCURA_VIEWER_APP_H

#include <string>

#include "viewer_renderer.h"

namespace obscura::viewer {

struct ViewerOptions {
    std::string scene = "atrium";   // built-in name, .obj or .pfm path
    std::string viewpoint;          // --viewpoint: a viewpoint of the mesh scene ("": its "default")
    std::string method = "hbao";    // NAME[:KEY=VALUE...], as the CLI's specs
    std::string compare;            // split view's right side: a spec, or "reference" / "truth" (the comparison)
    Comparison comparison = Comparison::ScreenSpaceReference;  // what the heat map and the split compare with
    std::string settings_file;      // a settings JSON to start from (replaces `method`)
    ViewMode view = ViewMode::LitWithAo;
    int width = 1280, height = 720; // window size
    bool use_normals = false;       // hand the scene's normals to the SDK (else it reconstructs them)
    int reference_rays = 64;        // rays per pixel of the on-demand screen-space reference
    int truth_rays = 256;           // rays per pixel of the geometry truth (worker thread)
    float spin = 0.0f;              // degrees the orbit camera turns each frame (watch temporal accumulation move)
    std::string screenshot;         // with frames > 0: render `frames` frames, save the window, exit
    int frames = 0;
};

// Parses NAME[:KEY=VALUE...] as the CLI does (samples/common/method_spec_parser.h: value names, the falloff
// table, derived settings left to the SDK). Throws std::invalid_argument with the parser's message.
obscura_settings settings_from_spec(const std::string& spec);

// Runs the window until it is closed (or the screenshot is written). Returns the process exit code; errors
// go to stderr.
int run_viewer(const ViewerOptions& options);

}  // namespace obscura::viewer

#endif  // OBSCURA_VIEWER_APP_H
