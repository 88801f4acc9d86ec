#include "scene_source.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "cli_errors.h"

namespace obscura::cli {
namespace {

glm::vec3 parse_vec3(const std::string& option, const std::string& text) {
    const std::vector<std::string> parts = split_list(option, text);
    if (parts.size() != 3) throw UsageError(option + ": '" + text + "' is not X,Y,Z");
    return glm::vec3(float(parse_double(option, parts[0])), float(parse_double(option, parts[1])),
                     float(parse_double(option, parts[2])));
}

// --guard-band F, scenes and depth files alike: a fraction per side in [0, kGuardBandBelow). A depth file's
// (samples::DepthFileOptions) must be below 1, and truth --depth-out writes a scene's for --depth to read back, so the
// two take the same range.
constexpr float kGuardBandBelow = 1.0f;

float parse_guard_band(const std::string& text) {
    // Checked as the float it is kept in: 0.9999999999 rounds to 1.
    const float value = float(parse_double("--guard-band", text));
    if (!(value >= 0.0f && value < kGuardBandBelow)) {
        char range[32];
        std::snprintf(range, sizeof range, "[0, %g)", double(kGuardBandBelow));
        throw UsageError("--guard-band: " + text + " is outside " + range);
    }
    return value;
}

// Options that only one kind of source has: given with the other kind, they are a UsageError.
struct Given {
    std::string name;
    bool present;
};

void reject(const std::vector<Given>& options, const std::string& why) {
    for (const Given& option : options) {
        if (option.present) throw UsageError(option.name + " " + why);
    }
}

// glm::lookAt needs an up vector that is not along the view direction (its cross product with it is the image's x
// axis: zero gives a NaN view matrix). At or below this sine of the angle between them the camera takes another.
constexpr float kParallelUpSine = 1e-3f;

// `up`, or for a camera looking (nearly) straight along it another: -Z, as the scene library's "top" viewpoint has
// (the image's top towards -Z), or +Y for a camera looking along Z.
glm::vec3 up_for_view(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
    const glm::vec3 forward = glm::normalize(target - eye);
    if (glm::length(glm::cross(forward, glm::normalize(up))) > kParallelUpSine) return up;
    return std::fabs(forward.z) < 0.5f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

// Turns the scene library's std::invalid_argument (unknown names) into a UsageError.
template <class Function>
auto as_usage_error(Function&& function) -> decltype(function()) {
    try {
        return function();
    } catch (const std::invalid_argument& error) {
        throw UsageError(error.what());
    }
}

// samples::render_scene: its std::invalid_argument is a request of the command line that this GL context cannot
// meet (--msaa past the context's sample limit) and so a UsageError; the requests it also refuses that way
// (motion vectors with MSAA) the commands refuse before any GL.
samples::RenderedScene rasterise(const samples::SceneMesh& mesh, const samples::SceneRenderOptions& raster) {
    return as_usage_error([&] { return samples::render_scene(mesh, raster); });
}

}  // namespace

SceneSourceOptions take_scene_source_options(ArgumentList& arguments, bool takes_size,
                                             const std::string& depth_options_hint) {
    SceneSourceOptions options;
    const std::optional<std::string> depth = arguments.take_value("--depth");
    const std::optional<std::string> scene = arguments.take_value("--scene");
    options.viewpoint = arguments.take_value("--viewpoint");
    if (auto eye = arguments.take_value("--eye")) options.eye = parse_vec3("--eye", *eye);
    if (auto target = arguments.take_value("--target")) options.target = parse_vec3("--target", *target);
    if (auto fovy = arguments.take_value("--fovy")) {
        options.fov_y_degrees = float(parse_double_in("--fovy", *fovy, 1.0, 170.0));
    }
    const std::optional<std::string> guard_band = arguments.take_value("--guard-band");
    const std::optional<std::string> size = takes_size ? arguments.take_value("--size") : std::nullopt;
    const std::optional<std::string> projection = arguments.take_value("--projection");
    const std::optional<std::string> depth_format = arguments.take_value("--depth-format");
    const std::optional<std::string> msaa = arguments.take_value("--msaa");
    const bool no_clip_control = arguments.take_flag("--no-clip-control");
    options.use_normals = arguments.take_flag("--normals");
    const std::optional<std::string> depth_kind = arguments.take_value("--depth-kind");
    const std::optional<std::string> near_plane = arguments.take_value("--near");
    const std::optional<std::string> far_plane = arguments.take_value("--far");
    const bool reversed_z = arguments.take_flag("--reversed-z");

    if (depth) {
        if (scene) throw UsageError("--depth and --scene are alternatives: give one");
        reject({{"--viewpoint", options.viewpoint.has_value()}, {"--eye", options.eye.has_value()},
                {"--target", options.target.has_value()}, {"--size", size.has_value()},
                {"--projection", projection.has_value()}, {"--depth-format", depth_format.has_value()},
                {"--msaa", msaa.has_value()}, {"--no-clip-control", no_clip_control},
                {"--normals", options.use_normals}},
               "does not apply to --depth (the file is the depth buffer, its size the file's)");
        samples::DepthFileOptions file;
        file.path = *depth;
        if (depth_kind) file.kind = as_usage_error([&] { return samples::parse_depth_file_kind(*depth_kind); });
        if (options.fov_y_degrees) file.fov_y_degrees = *options.fov_y_degrees;
        if (guard_band) file.guard_band = parse_guard_band(*guard_band);
        if (near_plane) file.near_plane = float(parse_double_in("--near", *near_plane, 1e-6, 1e9));
        if (far_plane) {
            file.far_plane = *far_plane == "inf" ? std::numeric_limits<float>::infinity()
                                                 : float(parse_double_in("--far", *far_plane, 1e-6, 1e30));
        }
        if (!(file.far_plane > file.near_plane)) throw UsageError("--far must be greater than --near (or inf)");
        if (reversed_z && file.kind != samples::DepthFileKind::Hardware) {
            throw UsageError("--reversed-z applies to --depth-kind hardware only");
        }
        file.reversed_z = reversed_z;
        options.depth_file = file;
        return options;
    }

    reject({{"--depth-kind", depth_kind.has_value()}, {"--near", near_plane.has_value()},
            {"--far", far_plane.has_value()}, {"--reversed-z", reversed_z}},
           depth_options_hint);
    if (scene) options.scene = *scene;
    if (options.eye.has_value() != options.target.has_value()) throw UsageError("--eye and --target go together");
    if (options.eye && options.viewpoint) throw UsageError("--viewpoint and --eye/--target are alternatives: give one");
    if (options.eye && glm::length(*options.eye - *options.target) <= 0.0f) {
        throw UsageError("--eye and --target are the same point");
    }
    if (size) {
        const ImageSize parsed = parse_size("--size", *size);
        options.raster.width = parsed.width;
        options.raster.height = parsed.height;
    }
    if (guard_band) options.raster.guard_band = parse_guard_band(*guard_band);
    if (projection) options.raster.projection = as_usage_error([&] { return samples::parse_projection_kind(*projection); });
    if (depth_format) {
        options.raster.depth_format = as_usage_error([&] { return samples::parse_depth_format(*depth_format); });
    }
    if (msaa) options.raster.samples = parse_int("--msaa", *msaa, 1, 32);
    options.raster.use_clip_control = !no_clip_control;
    options.raster.normals = options.use_normals;
    return options;
}

SceneSource::SceneSource(SceneSourceOptions options) : options_(std::move(options)) {
    if (is_depth_file()) return;
    scene_ = as_usage_error([&] { return samples::load_scene(options_.scene); });
    if (options_.eye) {
        camera_ = scene_.viewpoints.front().camera;
        camera_.eye = *options_.eye;
        camera_.target = *options_.target;
        camera_.up = up_for_view(camera_.eye, camera_.target, camera_.up);
        camera_name_ = "command-line camera";
    } else {
        const std::string name = options_.viewpoint.value_or("default");
        camera_ = as_usage_error([&] { return samples::find_viewpoint(scene_, name).camera; });
        camera_name_ = "viewpoint " + name;
    }
    if (options_.fov_y_degrees) camera_.fov_y_degrees = *options_.fov_y_degrees;
}

const std::string& SceneSource::name() const {
    return is_depth_file() ? options_.depth_file->path : scene_.name;
}

void SceneSource::check_size(ImageSize size) const {
    if (is_depth_file()) return;
    const samples::GuardBandLayout layout =
        samples::guard_band_layout(size.width, size.height, options_.raster.guard_band);
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (layout.depth_width > max_size || layout.depth_height > max_size) {
        char message[256];
        std::snprintf(message, sizeof message,
                      "%dx%d with guard band %g needs a %dx%d depth texture, past this GL context's "
                      "GL_MAX_TEXTURE_SIZE of %d: give a smaller size or --guard-band",
                      size.width, size.height, double(options_.raster.guard_band), layout.depth_width,
                      layout.depth_height, int(max_size));
        throw UsageError(message);
    }
}

samples::RenderedScene SceneSource::render(const samples::Camera& camera, ImageSize size) const {
    if (is_depth_file()) return samples::load_depth_file(*options_.depth_file);
    check_size(size);
    samples::SceneRenderOptions raster = options_.raster;
    raster.width = size.width;
    raster.height = size.height;
    raster.camera = camera;
    return rasterise(scene_.mesh, raster);
}

samples::RenderedScene SceneSource::render_frame(int frame, const samples::Camera& camera, ImageSize size,
                                                 const samples::Camera* previous_camera) const {
    if (is_depth_file()) return render(camera, size);
    check_size(size);
    samples::SceneRenderOptions raster = options_.raster;
    raster.width = size.width;
    raster.height = size.height;
    raster.camera = camera;
    const samples::SceneMesh mesh = scene_.mesh_at(frame);
    samples::SceneMesh previous_mesh;
    if (previous_camera) {
        raster.motion_vectors = true;
        raster.previous_camera = *previous_camera;
        if (scene_.animated()) {
            previous_mesh = scene_.mesh_at(frame - 1);
            raster.previous_mesh = &previous_mesh;
        }
    }
    return rasterise(mesh, raster);
}

std::string SceneSource::describe(const samples::SceneFrame& frame) const {
    char text[512];
    const obscura_rect& rect = frame.output_rect;
    if (is_depth_file()) {
        const samples::DepthFileOptions& file = *options_.depth_file;
        std::snprintf(text, sizeof text, "depth file %s (%s%s): %dx%d, depth %dx%d (guard band %.2f), fovy %g",
                      file.path.c_str(), samples::depth_file_kind_name(file.kind), file.reversed_z ? ", reversed-Z" : "",
                      rect.width, rect.height, frame.depth_width, frame.depth_height, double(file.guard_band),
                      double(file.fov_y_degrees));
        return text;
    }
    const samples::SceneRenderOptions& raster = options_.raster;
    std::string msaa = frame.samples > 1 ? ", " + std::to_string(frame.samples) + "x MSAA" : "";
    std::snprintf(text, sizeof text, "%s (%s): %dx%d, depth %dx%d (guard band %.2f), %s, %s%s, clip depth %s%s",
                  scene_.name.c_str(), camera_name_.c_str(), rect.width, rect.height, frame.depth_width,
                  frame.depth_height, double(raster.guard_band), samples::projection_kind_name(raster.projection),
                  samples::depth_format_name(raster.depth_format), msaa.c_str(),
                  frame.clip_depth == OBSCURA_CLIP_DEPTH_ZERO_TO_ONE ? "[0,1]" : "[-1,1]",
                  options_.use_normals ? ", scene normals" : "");
    return text;
}

}  // namespace obscura::cli
