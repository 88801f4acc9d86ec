// What render, bench and demo share: the AO target texture, one AO render of a scene, and timing a
// series of frames into per-pass statistics.
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
    bool use_normals = false;
    obscura_debug_view debug_view = OBSCURA_DEBUG_NONE;
};

// One obscura_render into the target; throws ApiError on failure.
void render_ao(const ObscuraSession& session, const AoRenderRequest& request);

// Median and minimum of one timed quantity over the frames.
struct TimingRow {
    std::string label;  // "total", "hbao.ao" ..., or "wall (render + glFinish)"
    double median_ms = 0.0;
    double min_ms = 0.0;
    size_t samples = 0;
};

struct TimingSummary {
    std::vector<TimingRow> passes;  // from obscura_get_timings, "total" first; empty if none arrived
    TimingRow wall;                 // CPU clock around obscura_render + glFinish
    uint64_t memory_bytes = 0;      // obscura_get_memory_usage after the frames
    // The "total" row if the SDK reported one, else the wall-clock row.
    const TimingRow& best_total() const;
};

// Renders `warmup` untimed frames, then `frames` timed ones (each followed by glFinish).
TimingSummary time_frames(const ObscuraSession& session, const AoRenderRequest& request, int warmup, int frames);

double median(std::vector<double> values);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_AO_RENDER_H
