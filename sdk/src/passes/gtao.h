// GTAO: S slices x N steps per side per pixel, horizons (or a visibility bitmask) integrated in closed form
// against the projected normal (sdk/glsl/gtao.comp), and its edge-aware 5x5 denoise (gtao_denoise.comp).
#ifndef OBSCURA_GTAO_H
#define OBSCURA_GTAO_H

#include <cstdint>

#include "frame_input.h"
#include "gl/program_cache.h"
#include "output_writer.h"
#include "passes/pass_common.h"

namespace obscura {

// The slices and steps of a GTAO preset (1 low ... 4 ultra), as XeGTAO names them.
struct GtaoPresetCounts {
    int slices, steps;
};
GtaoPresetCounts gtao_preset_counts(int preset);

class GtaoPass {
public:
    // Builds the program of these settings' variant (thickness mode, step distribution, slices and steps) with
    // bent normals or not on first use: variants are compiled in (CPU rasterisers run both sides of a branch on a
    // uniform; constant loop counts unroll).
    Error prepare(const PassEnv& env, const obscura_gtao_settings& settings, bool bent_normals);
    // Levels of the z pyramid the steps can read (counting level 0) for these settings.
    static int wanted_levels(const obscura_gtao_settings& settings);
    // Converts resolved settings (metres) to the shader's constants (view units); `deepest_level`: the last level of
    // the z pyramid (0: level 0 only).
    static GtaoConstants constants(const obscura_gtao_settings& settings, const FrameInput& input, int deepest_level);
    // Writes visibility over `region` into `destination`: R16F, or RGBA16F (visibility, bent normal) with bent
    // normals. The linear depth is read through its levels.
    void run(const PassEnv& env, const obscura_gtao_settings& settings, bool bent_normals, const UniformRange& frame,
             const UniformRange& pass, const Region& region, const FrameResources& resources,
             const gl::Texture2D& destination);

private:
    // By variant: thickness mode, step distribution, bent normals, slices, steps, thickness blend on (variant_key).
    // The last few (a tuning session that sweeps slices x steps held a program per pair it tried).
    gl::ProgramCache<uint32_t> programs_;
    static int step_distribution(const obscura_gtao_settings& settings);
    static uint32_t variant_key(const obscura_gtao_settings& settings, bool bent_normals);
};

// Separable: along x into a temporary (the first pass), then along y into the result (the final pass); each
// invocation filters a run of OBSCURA_GTAO_DENOISE_RUN pixels along its pass's axis.
class GtaoDenoisePass {
public:
    // Builds both passes' programs and, with a `target` (format != 0), the final pass's variant that writes the host's
    // target image (its format and blend compiled in).
    Error prepare(const PassEnv& env, bool bent_normals, const TargetWrite& target = TargetWrite());
    static GtaoDenoiseConstants constants(const obscura_gtao_settings& settings, bool final);
    // Denoises `source` over `region` along the pass's axis into `destination`: with `final` the visibility (R16F)
    // and, with bent normals, `bent` (RGBA16F: visibility, unit bent normal xyz); else the same values as `source`
    // (R16F, or RGBA16F with bent normals).
    void run(const PassEnv& env, bool bent_normals, bool final, const UniformRange& frame, const UniformRange& pass,
             const Region& region, const FrameResources& resources, const gl::Texture2D& source,
             const gl::Texture2D& destination, const gl::Texture2D* bent) const;
    // The final pass with the visibility into the host's target image `target_texture` (prepare's `target`) instead
    // of a texture; the bent normals, if any, still into `bent`.
    void run_into_target(const PassEnv& env, bool bent_normals, const UniformRange& frame, const UniformRange& pass,
                         const Region& region, const FrameResources& resources, const gl::Texture2D& source,
                         GLuint target_texture, const gl::Texture2D* bent) const;

private:
    void dispatch(const PassEnv& env, bool bent_normals, bool final, const UniformRange& frame, const UniformRange& pass,
                  const Region& region, const FrameResources& resources, const gl::Texture2D& source,
                  const gl::Texture2D* bent) const;
    static int run_length(const PassEnv& env);  // pixels per invocation (OBSCURA_GTAO_DENOISE_RUN_CPU / _GPU)
    gl::Object programs_[2][2];  // [bent normals][final]
    // The final pass's target variants by their defines, the last gl::kProgramVariantsKept used.
    gl::ProgramCache<gl::DefineLines> target_programs_;
    GLuint target_program_ = 0;  // prepare's
    TargetWrite target_;
};

}  // namespace obscura

#endif  // OBSCURA_GTAO_H
