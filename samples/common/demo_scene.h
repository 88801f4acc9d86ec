// The scene rasteriser and the built-in demo room.
//
// render_scene() rasterises any triangle mesh with host GL into a depth texture with a guard band and
// a view-space normal texture, exactly what a host engine would hand to obscura_render(). More scenes
// (procedural ones, OBJ files) are in scene_library.h; captured depth buffers in depth_file.h.
//
// The demo room: open towards the camera (floor, back wall, two side walls, optional ceiling) with boxes
// on the floor (one against the back wall, one against the left wall) and a sphere resting on the floor.
// render_demo_scene() draws it.
#ifndef OBSCURA_SAMPLES_DEMO_SCENE_H
#define OBSCURA_SAMPLES_DEMO_SCENE_H

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "host_gl.h"
#include "image_io.h"
#include "obscura/obscura.h"
#include "scene_projection.h"

namespace obscura::samples {

// Triangle list in world space (metres, y up): 6 floats per vertex, position then unit normal.
struct SceneMesh {
    std::vector<float> vertices;
    int vertex_count() const { return int(vertices.size() / 6); }
    int triangle_count() const { return vertex_count() / 3; }
};
SceneMesh build_demo_scene_mesh(bool with_ceiling = false);

enum class DepthFormat { D32F, D24, D24S8 };
// "d32f", "d24", "d24s8".
const char* depth_format_name(DepthFormat format);
// Throws std::invalid_argument listing the valid names.
DepthFormat parse_depth_format(const std::string& name);
GLenum depth_internal_format(DepthFormat format);

struct SceneRenderOptions {
    int width = 640;   // the visible image; the depth texture adds the guard band around it
    int height = 360;
    float guard_band = 0.10f;  // fraction of width / height added on each side
    ProjectionKind projection = ProjectionKind::Perspective;
    DepthFormat depth_format = DepthFormat::D32F;
    int samples = 1;         // > 1: the depth texture is GL_TEXTURE_2D_MULTISAMPLE
    bool normals = true;     // also write view-space normals (always a single-sample texture)
    // Reversed variants: use glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) when the context has it
    // (GL 4.5 or ARB_clip_control); otherwise reversed-Z is rendered with [-1, 1] clip depth.
    bool use_clip_control = true;
    bool ceiling = false;    // render_demo_scene only
    Camera camera;
    // Motion vectors, what the temporal accumulation of a scene with moving objects needs: also write a GL_RG32F
    // texture (the depth texture's size) of how far each texel's surface point moved on screen since the previous
    // frame, in pixels, previous - current (OBSCURA_MOTION_PIXELS): the previous frame seen by previous_camera
    // (unset: `camera`), its vertices where previous_mesh has them (the same vertex count and order; nullptr: where
    // the mesh has them). Single-sample depth only (std::invalid_argument otherwise).
    bool motion_vectors = false;
    std::optional<Camera> previous_camera;
    const SceneMesh* previous_mesh = nullptr;
    // Looks up glClipControl; nullptr: HeadlessGL::get_proc_address.
    obscura_get_proc_address_fn get_proc_address = nullptr;
};

// Plain description of a rasterised frame.
struct SceneFrame {
    // HARDWARE: a depth texture written through `projection`; LINEAR_VIEW: a GL_R32F texture of
    // positive view depth in metres (depth files, depth_file.h).
    obscura_depth_kind depth_kind = OBSCURA_DEPTH_HARDWARE;
    GLuint depth_texture = 0;
    GLuint normal_texture = 0;  // GL_RGBA16F, view-space normal in rgb, alpha 1 on geometry, 0 on sky
    GLuint motion_texture = 0;  // GL_RG32F motion vectors in pixels (SceneRenderOptions::motion_vectors), or 0
    GLenum depth_target = GL_TEXTURE_2D;  // GL_TEXTURE_2D_MULTISAMPLE when samples > 1
    GLenum depth_internal_format = GL_DEPTH_COMPONENT32F;
    int samples = 1;
    int depth_width = 0;
    int depth_height = 0;
    obscura_rect output_rect{};  // the visible image inside the depth texture
    float projection[16] = {};   // column-major, guard band included: what the depth was written with
    obscura_clip_depth clip_depth = OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
    float near_plane = 0.0f;
    float far_plane = 0.0f;      // +infinity with an infinite projection
    bool reversed_z = false;
    bool infinite_far = false;
    bool orthographic = false;
    glm::mat4 view{1.0f};        // world -> view (identity for depth files)

    // The obscura_input for this frame (depth_kind, column-major projection, 1 view unit per metre);
    // normal_texture is passed only when `use_normals` and normals were rendered. The view-projections for the
    // temporal accumulation: this frame's, and `previous`'s (null: this frame's again, a static camera); the motion
    // vectors when they were rendered (they then take precedence over the matrices, as the SDK has it).
    obscura_input make_input(bool use_normals = false, const SceneFrame* previous = nullptr,
                             uint32_t frame_index = 0) const;
};

// Owns the textures of a SceneFrame and deletes them (needs the same GL context current).
class RenderedScene {
public:
    explicit RenderedScene(const SceneFrame& frame) : frame_(frame) {}
    ~RenderedScene();
    RenderedScene(RenderedScene&& other) noexcept;
    RenderedScene& operator=(RenderedScene&& other) noexcept;
    RenderedScene(const RenderedScene&) = delete;
    RenderedScene& operator=(const RenderedScene&) = delete;

    const SceneFrame& frame() const { return frame_; }
    const SceneFrame* operator->() const { return &frame_; }

private:
    void destroy();
    SceneFrame frame_;
};

// Rasterises `mesh` seen by options.camera with the current context (GL 4.3 core). The mesh is uploaded
// for this call only (one vertex buffer, one draw). GL state it changes is restored (bindings,
// viewport, depth/blend/cull/scissor/stencil state, clear values, clip control), and it leaves no GL
// error. Throws std::invalid_argument (empty mesh, bad options) or std::runtime_error on failure.
RenderedScene render_scene(const SceneMesh& mesh, const SceneRenderOptions& options);

// One byte per pixel of the frame's output rectangle (rows bottom-up): 1 where it has geometry, 0 on sky
// (hardware depth at the clear value; linear depth that is not finite and positive). What error metrics
// count by default (compare_images' mask), so that a view with much sky does not score better than its
// geometry deserves. Reads the depth texture back: std::runtime_error for a multisampled one.
std::vector<uint8_t> read_geometry_mask(const SceneFrame& frame);

// Positive view depth in metres (distance from the eye plane) of each texel of `region` of the frame's depth texture
// (one channel, rows bottom-up), +infinity where read_geometry_mask says sky: linear depth as stored, hardware depth
// taken back through the inverse of the frame's projection (its clip depth convention). Reads the depth texture
// back: std::runtime_error for a multisampled one.
FloatImage read_view_depth(const SceneFrame& frame, const obscura_rect& region);

// render_scene(build_demo_scene_mesh(options.ceiling), options).
RenderedScene render_demo_scene(const SceneRenderOptions& options = {});

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_DEMO_SCENE_H
