// LSAO (sdk/glsl/line_sweep.comp, lsao_gather.comp): the line layout for the current size and pattern
// (passes/lsao_pattern.h) in buffers, the sweep dispatch (one invocation per line segment, a direction per
// workgroup layer) and the gather.
#ifndef OBSCURA_LSAO_H
#define OBSCURA_LSAO_H

#include "frame_input.h"
#include "gl/program_cache.h"
#include "layout_phase.h"
#include "passes/lsao_pattern.h"
#include "output_writer.h"
#include "passes/pass_common.h"

namespace obscura {

// The directions of resolved LSAO settings in a layout phase (layout_phase.h): the aligned 8n pattern for K = 8n
// (the same in every phase: its directions are fixed by the texel template), or K free directions turned by the
// phase's fraction of the angle between them.
LsaoDirections lsao_directions(const obscura_lsao_settings& settings, int phase = 0,
                               const AllocatorCallbacks& alloc = AllocatorCallbacks::system());

// The layout of resolved LSAO settings over a width x height texture in a layout phase: lsao_directions, with
// every line shifted across by the phase's fraction of D_L.
LsaoLayout lsao_layout(const obscura_lsao_settings& settings, int width, int height, int phase,
                       const AllocatorCallbacks& alloc = AllocatorCallbacks::system());

// Steps per sweep segment for resolved settings, 0 for whole lines: segment_steps, or for 0 (auto) whole
// lines on a CPU renderer and kLsaoGpuSegmentSteps on a GPU.
constexpr int kLsaoGpuSegmentSteps = 128;
int lsao_segment_steps(const obscura_lsao_settings& settings, bool cpu_renderer);

// The warm-up distance (view units) beyond which an occluder casts at most `warmup_tolerance` on any
// receiver under the settings' falloff and tangent; 0 when every occluder casts less (a tolerance above the
// falloff's largest value), +infinity when no distance bounds it (a tolerance of 0 with a falloff that never
// reaches 0).
double lsao_warmup_distance(const obscura_lsao_settings& settings, float meters_to_view_units);

// The margin (texels) of the depth tile a GPU gather group shares: how far from a pixel the nearest sample
// of a direction can lie under the settings' pattern, step length and line spacing.
constexpr int kLsaoMaxGatherMargin = 8;
// Directions whose value loads the gather issues together (fewer when K is smaller).
constexpr int kLsaoGatherBatch = 16;
int lsao_gather_margin(const obscura_lsao_settings& settings);

class LsaoPass {
public:
    // Selects the programs for the settings, building them if no kept variant matches; with a `target` (format != 0)
    // the gather's variant that writes the host's target image (its format and blend compiled in) instead of the one
    // that writes resources.ao.
    Error prepare(const PassEnv& env, const obscura_lsao_settings& settings, const TargetWrite& target = TargetWrite());
    // Selects the layout of the frame's phase (layout_phase(frame_index)): drops every phase's layout when the
    // size, the pattern, K, D_S or D_L changed, and builds the phase's on its first use.
    Error ensure_layout(const PassEnv& env, const obscura_lsao_settings& settings, int width, int height,
                        uint32_t frame_index = 0);
    // Resolved settings (metres) -> the shaders' constants (view units), for the current layout.
    LsaoConstants constants(const obscura_lsao_settings& settings, const FrameInput& input, bool cpu_renderer) const;
    // The sweeps over every line (segment), then the gather over `region` into resources.ao.
    void run_sweeps(const PassEnv& env, const obscura_lsao_settings& settings, const UniformRange& frame,
                    const UniformRange& pass, FrameResources& resources);
    void run_gather(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
                    const FrameResources& resources) const;
    // The gather into the host's target image `target_texture` (prepare's `target`) instead of resources.ao.
    void run_gather_into_target(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                                const Region& region, const FrameResources& resources, GLuint target_texture) const;
    // The current phase's layout.
    const LsaoLayout& layout() const { return phases_[current_].layout; }
    uint64_t bytes() const;
    void release();
private:
    friend class LsaoPassInspection;  // the tests' readbacks (testing/pass_inspection.h)
    // Programs with the settings that select code compiled in (the pattern, the tangent strategy, the hull
    // capacity, the normal test), by their #define lines: the last few of each shader.
    using VariantCache = gl::ProgramCache<gl::DefineLines>;
    static Error program_for(const PassEnv& env, const char* shader, const gl::DefineLines& defines,
                             VariantCache* cache, GLuint* program);
    void dispatch_gather(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
                         const FrameResources& resources) const;
    VariantCache sweep_variants_, gather_variants_;
    GLuint sweep_program_ = 0, gather_program_ = 0;  // the current settings' variants
    GLuint gather_target_program_ = 0;               // with prepare's target
    TargetWrite target_;
    int gather_group_[2] = {OBSCURA_LSAO_GATHER_GROUP_X, OBSCURA_LSAO_GATHER_GROUP_Y};
    bool collect_stats_ = false;
    // What the layout was built for (D_S: the free pattern's step, an aligned pattern's whole template steps).
    struct LayoutKey {
        int width = 0, height = 0, pattern = 0, directions = 0;
        float step_length = 0.0f, line_spacing = 0.0f;
        bool cpu_renderer = false;  // whether the buffer textures exist
        bool operator==(const LayoutKey& o) const {
            return width == o.width && height == o.height && pattern == o.pattern && directions == o.directions &&
                   step_length == o.step_length && line_spacing == o.line_spacing && cpu_renderer == o.cpu_renderer;
        }
    };
    // One layout phase: its lines and their records. CPU rasterisers read the line records and values through
    // buffer textures, GPUs as storage buffers.
    struct Phase {
        LsaoLayout layout;
        gl::Buffer lines;             // 16-byte line records
        gl::Object lines_texture;     // RGBA32UI over lines (CPU rasterisers only)
    };
    Error build_phase(const PassEnv& env, const obscura_lsao_settings& settings, int phase);
    Phase phases_[kLayoutPhases];
    int current_ = 0;
    LayoutKey key_;
    gl::Buffer values_;           // the sweeps' halves, written as a storage buffer: the largest phase's
    gl::Buffer stats_;
    gl::Object values_texture_;   // R16F over values_ (CPU rasterisers only)
};

}  // namespace obscura

#endif  // OBSCURA_LSAO_H
