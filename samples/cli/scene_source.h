// Where the depth buffer comes from, shared by render, compare and bench: a scene of the scene
// library (a built-in name or an .obj path) rasterised through a camera, or a captured depth buffer
// (a PFM file). The command-line options:
//   --scene NAME|FILE.obj (default atrium), --viewpoint NAME, or --eye X,Y,Z --target X,Y,Z [--fovy DEG];
//   --size WxH (visible image, default 640x360; commands that take several sizes parse their own),
//   --guard-band F (default 0.1 per side, in [0, 1) as a depth file's), --projection P, --depth-format D, --msaa N,
//   --no-clip-control, --normals (hand the scene's view-space normals to the SDK; otherwise it reconstructs them);
// or instead of a scene:
//   --depth FILE.pfm [--depth-kind linear|hardware] [--near N] [--far F|inf] [--reversed-z] [--fovy DEG]
//   [--guard-band F (default 0: what the file includes per side)]; the size is the file's.
#ifndef OBSCURA_CLI_SCENE_SOURCE_H
#define OBSCURA_CLI_SCENE_SOURCE_H

#include <optional>
#include <string>

#include "cli_args.h"
#include "demo_scene.h"
#include "depth_file.h"
#include "scene_library.h"

namespace obscura::cli {

struct SceneSourceOptions {
    std::string scene = "atrium";
    std::optional<std::string> viewpoint;
    std::optional<glm::vec3> eye;
    std::optional<glm::vec3> target;
    std::optional<float> fov_y_degrees;
    std::optional<samples::DepthFileOptions> depth_file;  // set: --depth replaces the scene
    samples::SceneRenderOptions raster;  // size, guard band, projection, depth format, MSAA, clip control
    bool use_normals = false;
};

// Takes the options above out of `arguments`, checking that they go together (UsageError otherwise).
// `takes_size`: whether --size is one of this command's options. `depth_options_hint`: what the message says of a
// depth file's option (--depth-kind, --near, --far, --reversed-z) given without --depth, after its name; commands
// that take no --depth say where such options belong with them.
SceneSourceOptions take_scene_source_options(ArgumentList& arguments, bool takes_size,
                                             const std::string& depth_options_hint = "needs --depth FILE.pfm");

class SceneSource {
public:
    // Loads the scene's mesh and picks the camera (CPU only, no GL). UsageError for an unknown scene
    // or viewpoint; a missing or unreadable OBJ file is a std::runtime_error.
    explicit SceneSource(SceneSourceOptions options);

    bool is_depth_file() const { return options_.depth_file.has_value(); }
    // The scene's name, the OBJ path, or the depth file's path.
    const std::string& name() const;
    // The camera chosen on the command line (rasterised scenes).
    const samples::Camera& camera() const { return camera_; }
    // The visible size asked for (rasterised scenes; a depth file's comes from the file).
    ImageSize size() const { return {options_.raster.width, options_.raster.height}; }
    bool use_normals() const { return options_.use_normals; }
    // The scene's mesh and viewpoints; nullptr for a depth file (it has no triangles).
    const samples::Scene* scene() const { return is_depth_file() ? nullptr : &scene_; }
    // The guard band per side (scenes: --guard-band; depth files: what the file includes).
    float guard_band() const { return is_depth_file() ? options_.depth_file->guard_band : options_.raster.guard_band; }

    // UsageError when the current GL context cannot hold a depth texture of `size` with the guard band (past
    // GL_MAX_TEXTURE_SIZE). Scenes only (a depth file's texture is the file's size); render() checks it too, and a
    // command that renders several sizes checks them all before the first.
    void check_size(ImageSize size) const;
    // The depth (and normals) for obscura_render, with the current GL context: the scene rasterised at
    // `size` through `camera`, or the depth file uploaded (then both are ignored). UsageError for a size or an
    // MSAA sample count past the context's limits.
    samples::RenderedScene render(const samples::Camera& camera, ImageSize size) const;
    samples::RenderedScene render() const { return render(camera_, size()); }

    // Frame `frame` of a sequence (an animated scene's moving part where that frame has it) through `camera`;
    // `previous_camera` set: the motion vectors too, from the previous frame (frame - 1 through it). Scenes only.
    samples::RenderedScene render_frame(int frame, const samples::Camera& camera, ImageSize size,
                                        const samples::Camera* previous_camera) const;

    // "atrium (viewpoint default): 640x360, depth 768x432 (guard band 0.10), perspective, d32f".
    std::string describe(const samples::SceneFrame& frame) const;

private:
    SceneSourceOptions options_;
    samples::Scene scene_;
    samples::Camera camera_;
    std::string camera_name_;
};

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_SCENE_SOURCE_H
