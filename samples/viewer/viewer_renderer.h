// ViewerRenderer: what the viewer draws each frame, with host GL and two Obscura contexts (the method's, and the
// comparison's: the split view's second method and the reference chunks).
//
//   1. the scene (a library mesh through the camera, or a captured depth file) rasterised into a depth texture
//      with a guard band and a view-space normal texture, as an engine's G-buffer pass would;
//   2. AO of one or two method settings into R16F targets of the visible size (obscura_render);
//   3. a composite into the window: AO only, lit with or without AO on the ambient term, a split screen, or the
//      error heat map against what the method is compared with (the comparison).
// Two comparisons: the screen-space reference (REFERENCE, rays marched through the depth buffer, every surface
// infinitely thick), which ReferenceJob accumulates for a frozen view a chunk of rays per frame on the GPU so the
// window stays responsive; and the geometry truth (rays against the scene's triangles on the CPU), which
// TruthJob (viewer_truth.h) traces on a worker thread and whose estimates the renderer only uploads.
#ifndef OBSCURA_VIEWER_RENDERER_H
#define OBSCURA_VIEWER_RENDERER_H

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <obscura/obscura.h>

#include "demo_scene.h"
#include "depth_file.h"
#include "host_gl_objects.h"
#include "image_io.h"
#include "metrics.h"
#include "scene_library.h"

namespace obscura::viewer {

// A library scene or OBJ file (mesh) or a captured depth buffer (PFM, its own fixed size and camera).
struct ViewerScene {
    std::string name;
    std::optional<samples::Scene> mesh;
    // A depth file, read, checked and uploaded when it is opened (shared with the renderer, which draws it every
    // frame), so that a missing or bad file is refused there and the scene shown stays.
    std::shared_ptr<const samples::RenderedScene> depth_file;
};
// A built-in name, an .obj or a .pfm path (linear depth, 60 degrees vertical field of view). A .pfm is uploaded
// with the current GL context (GL 4.3 core), which must then be current where the scene is destroyed. Throws
// std::invalid_argument / std::runtime_error with the loader's message.
ViewerScene load_viewer_scene(const std::string& name_or_path);

enum class ViewMode { AoOnly, LitWithAo, LitWithoutAo, Split, ErrorMap };
const char* view_mode_name(ViewMode mode);  // "ao", "lit", "lit-no-ao", "split", "error"

// What the heat map and the split view compare the method with.
enum class Comparison {
    ScreenSpaceReference,  // REFERENCE: the depth buffer ray-traced on the GPU (sees only what the camera sees)
    GeometryTruth          // the scene's triangles ray-traced on the CPU (mesh scenes only)
};
const char* comparison_name(Comparison comparison);  // "reference", "truth" (the --compare values)

// An R16F or R32F texture of the visible size that obscura_render writes.
struct AoTexture {
    samples::HostTexture texture;
    int width = 0, height = 0;
    GLenum format = 0;
    void ensure(int w, int h, GLenum internal_format);
};

// The reference for one view, accumulated in chunks of rays (one chunk per step()), then the error of the
// method's AO image against it.
class ReferenceJob {
public:
    // Chunk size in rays: small enough that a step stays interactive on llvmpipe at window sizes. The last chunk
    // traces what is left, so a job traces exactly the rays it was started with.
    static constexpr int kChunkRays = 8;

    bool active() const { return total_rays_ > 0; }
    bool done() const { return active() && traced_rays_ >= total_rays_; }
    float progress() const { return active() ? float(traced_rays_) / float(total_rays_) : 0.0f; }
    int traced_rays() const { return traced_rays_; }
    // The view it belongs to: the renderer restarts it when this no longer matches.
    const std::string& key() const { return key_; }

    // A job of `rays` rays per pixel (at least 1) of the reference of `method`, for the view `key`.
    void start(const std::string& key, const obscura_settings& method, int rays);
    void cancel() { *this = ReferenceJob(); }

    obscura_settings reference{};      // the settings of one chunk (first_ray moves on)
    samples::FloatImage sum;           // accumulated visibility x rays
    samples::FloatImage method_image;  // the method's AO at the time the reference completed
    std::optional<samples::ErrorMetrics> metrics;  // over geometry pixels (sky excluded)

private:
    friend class ViewerRenderer;
    std::string key_;
    int total_rays_ = 0;
    int traced_rays_ = 0;
};

// Owns an Obscura context: obscura_destroy_context (with the context's GL context current).
struct ObscuraContextDeleter {
    void operator()(obscura_context* context) const;
};
using ObscuraContextPtr = std::unique_ptr<obscura_context, ObscuraContextDeleter>;

class ViewerRenderer {
public:
    // Needs the window's GL 4.3 core context current and the host loader loaded. `software`: the renderer is
    // a CPU rasteriser (its timer queries read 0, so passes are timed by glFinish). Throws std::runtime_error.
    ViewerRenderer(obscura_get_proc_address_fn get_proc_address, bool software);
    ~ViewerRenderer();
    ViewerRenderer(const ViewerRenderer&) = delete;
    ViewerRenderer& operator=(const ViewerRenderer&) = delete;

    // Rasterises the scene at width x height visible pixels (mesh scenes; a depth file keeps its size).
    // Throws std::runtime_error.
    void render_scene(const ViewerScene& scene, const samples::Camera& camera, int width, int height,
                      obscura_get_proc_address_fn get_proc_address);
    // AO of `settings` for the current scene into slot 0 or 1. False on failure, with last_error() set. Each slot
    // is one obscura_view with its own frame index and previous camera, so with `temporal` on the two sides of the
    // split accumulate their own histories as the camera moves. The frame index (the methods' noise) advances only
    // while `settings` accumulate (temporal on); otherwise it is 0, and a still view renders the same image every
    // frame. Slot 0 renders with context() (the method's:
    // its timings and memory are the method's alone), slot 1 and the reference with a second context, so that
    // alternating methods does not make the SDK free and rebuild one method's resources every frame.
    bool render_ao(int slot, const obscura_settings& settings, bool use_scene_normals);
    // The next render of each slot starts a new temporal history (OBSCURA_INPUT_FLAG_RESET_HISTORY): another
    // scene or a viewpoint jump is a camera cut, not motion to reproject.
    void reset_history();
    // One step of `job` (a chunk of reference rays) for the current scene, given slot 0 holds the method's
    // AO. False on failure (last_error()).
    bool step_reference(ReferenceJob& job, bool use_scene_normals);
    // Measures slot 0 against `job`'s completed reference again (metrics, heat map): the method's current frame,
    // for temporal accumulation, whose image changes after the reference is done.
    void measure_reference(ReferenceJob& job);
    // The geometry truth's estimate (visible size, rows bottom-up) into the truth texture, for the split view.
    void upload_truth(const samples::FloatImage& visibility);
    // Measures slot 0 (the method) against `truth` over the pixels where `mask` is non-zero and uploads the
    // heat map of the truth comparison. Throws std::runtime_error / std::invalid_argument (sizes differ).
    samples::ErrorMetrics compare_with_truth(const samples::FloatImage& truth, const std::vector<uint8_t>& mask);
    // One byte per visible pixel, 1 where the rasterised scene has geometry (normals' alpha; depth for a depth
    // file), 0 on sky.
    std::vector<uint8_t> geometry_mask() const;
    // Draws `mode` into the current framebuffer's viewport. Split: slot 0 left of `split` (0..1 of the
    // width), `right` (an R16F/R32F texture, 0 for none: mid grey) to the right. Error: the RGB heat map `heat`
    // (0: the method's AO while the comparison is not ready).
    void composite(ViewMode mode, float split, GLuint right, GLuint heat);

    GLuint ao_texture(int slot) const { return ao_[slot].texture.get(); }
    // The screen-space reference so far, and its heat map once the job is done (0 otherwise).
    GLuint reference_texture(const ReferenceJob& job) const;
    GLuint reference_heat(const ReferenceJob& job) const;
    GLuint truth_texture() const { return truth_.get(); }
    GLuint truth_heat() const { return truth_heat_.get(); }
    // The current frame (nullptr before the first render_scene()).
    const samples::SceneFrame* frame() const { return scene_ ? &scene_->frame() : nullptr; }

    // The size of the visible image of the current scene.
    int width() const { return visible_width_; }
    int height() const { return visible_height_; }
    obscura_context* context() const { return context_.get(); }
    const std::string& last_error() const { return last_error_; }
    const std::string& renderer_name() const { return renderer_name_; }

private:
    // obscura_render of the current scene into `texture` (in `slot`'s view and frame sequence; -1: none, a static
    // view of the context's own); false with last_error() set on failure.
    bool render_into(GLuint texture, const obscura_settings& settings, bool use_scene_normals, int slot = -1);
    ObscuraContextPtr context_;                     // slot 0: the method
    ObscuraContextPtr compare_context_;             // slot 1 and the reference chunks
    obscura_view* views_[2] = {};                        // the AO slots' temporal histories (of their contexts)
    std::optional<samples::SceneFrame> previous_[2];     // each slot's previous frame (its camera), not owned
    uint32_t frame_index_[2] = {};                       // each slot's next frame index while it accumulates
    bool reset_history_[2] = {};                         // the slot's next render starts a new history
    // The current frame: rasterised every frame for a mesh, the scene's own upload for a depth file.
    std::shared_ptr<const samples::RenderedScene> scene_;
    int visible_width_ = 0, visible_height_ = 0;
    AoTexture ao_[2];
    AoTexture chunk_;                // one chunk of reference rays
    samples::HostTexture reference_; // the accumulated reference (R32F), for the split view
    samples::HostTexture heat_;      // the error heat map against the reference (RGB32F)
    samples::HostTexture truth_;     // the geometry truth's latest estimate (R32F)
    samples::HostTexture truth_heat_;// the error heat map against the truth (RGB32F)
    samples::HostProgram composite_;
    samples::HostVertexArray empty_vao_;
    std::string last_error_;
    std::string renderer_name_;
};

}  // namespace obscura::viewer

#endif  // OBSCURA_VIEWER_RENDERER_H
