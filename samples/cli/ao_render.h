// What render, compare and bench share: the AO target texture, one AO render of a scene, and timing a
// series of warm frames into per-pass statistics.
#ifndef OBSCURA_CLI_AO_RENDER_H
#define OBSCURA_CLI_AO_RENDER_H

#include <string>
#include <vector>

#include "demo_scene.h"
#include "host_gl_objects.h"
#include "image_io.h"
#include "obscura/obscura.h"

namespace obscura::cli {

class ObscuraSession;

// The texture Obscura writes into: the size of the output rectangle.
class AoTarget {
public:
    // internal_format: GL_R8, GL_R32F, GL_RGBA16F ...
    AoTarget(int width, int height, GLenum internal_format);

    GLuint texture() const { return texture_.get(); }
    int width() const { return width_; }
    int height() const { return height_; }
    // Reads the whole target back (GL rows, bottom-up): 1 channel, or 4 for RGBA targets.
    samples::FloatImage read() const;

private:
    samples::HostTexture texture_;
    int width_;
    int height_;
    GLenum internal_format_;
};

struct AoRenderRequest {
    const samples::SceneFrame* scene = nullptr;
    const obscura_settings* settings = nullptr;
    const AoTarget* target = nullptr;
    const AoTarget* bent_target = nullptr;  // RGBA: output.bent_normal_texture (methods that write bent normals)
    bool use_normals = false;
    obscura_debug_view debug_view = OBSCURA_DEBUG_NONE;
    // Temporal accumulation: the previous frame's camera (null: this one, a static camera), the frame index that
    // moves the methods' noise, and whether the history starts anew.
    const samples::SceneFrame* previous_scene = nullptr;
    uint32_t frame_index = 0;
    bool reset_history = false;
    obscura_view* view = nullptr;  // the history read and written; null: the context's own
    bool use_motion_vectors = true;  // hand the scene's motion vectors over when it has them
};

// One obscura_render into the target; throws ApiError on failure.
void render_ao(const ObscuraSession& session, const AoRenderRequest& request);

// Median and minimum of one timed quantity over the frames.
struct TimingRow {
    std::string label;  // "total", a pass ("hbao", "blur" ...), or "wall"
    double median_ms = 0.0;
    double min_ms = 0.0;
    size_t samples = 0;
};

struct TimingSummary {
    std::vector<TimingRow> passes;  // from obscura_get_timings, "total" first; empty if none arrived
    TimingRow wall;                 // CPU clock around obscura_render + glFinish
    uint64_t memory_bytes = 0;      // obscura_get_memory_usage after the frames
    // The SDK's "total" row, or an empty row (0 ms, 0 samples) when the SDK reported none.
    TimingRow sdk_total() const;
};

// How many frames a quick measurement renders: the reference is slow by design, so it is timed once.
struct FramePlan {
    int warmup = 2;
    int frames = 5;
};
FramePlan quick_frame_plan(obscura_method method);

// Compiles and allocates what a render of `request` needs with one untimed frame (for the REFERENCE a
// single ray, so the warm-up costs nothing next to the real frames).
void warm_up(const ObscuraSession& session, const AoRenderRequest& request);

// Renders `warmup` untimed frames, then `frames` timed ones (each followed by glFinish). Pass times are
// those the SDK reports for exactly these frames (told apart by their frame index); the target holds
// the last frame's result afterwards. With `alternate`, every other frame renders it instead (a camera that moves
// back and forth between two views, each frame reprojecting the other's history).
TimingSummary time_frames(const ObscuraSession& session, const AoRenderRequest& request, int warmup, int frames,
                          const AoRenderRequest* alternate = nullptr);

double median(std::vector<double> values);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_AO_RENDER_H
