// SAO's distributed AO sample pass (sdk/glsl/sao.comp) and its spiral: the unrotated taps are computed
// here, once per settings change, and uploaded with the pass constants.
#ifndef OBSCURA_SAO_H
#define OBSCURA_SAO_H

#include "frame_input.h"
#include "gl/program_cache.h"
#include "output_writer.h"
#include "passes/pass_common.h"

namespace obscura {

// Tap i of an s-tap spiral with tau turns (SAO eq. 6-7) before the per-pixel rotation: the fraction of the
// screen radius alpha_i = (i + 0.5) / s and the angle 2 pi tau alpha_i.
struct SpiralTap {
    float alpha;
    float angle;
};
SpiralTap spiral_tap(int i, int samples, int turns);

// The default spiral turns for s samples: the integer nearest 7s/9 sharing no factor with s (the paper's 7 for
// s = 9), so the s angles are all different.
int default_spiral_turns(int samples);

// Eq. 8: the per-pixel rotation phi = 30 x ^ y + 10 x y in radians, reduced to [0, 2 pi) in double
// precision, as the shader does.
float spiral_rotation(int x, int y);

class SaoPass {
public:
    // Builds the program of these settings' MIP filter (compiled in) on first use.
    Error prepare(const PassEnv& env, const obscura_sao_settings& settings);
    // The deepest z-pyramid level the taps can ask for (eq. 9 at the largest screen radius), plus one.
    static int wanted_levels(const obscura_sao_settings& settings);
    // Resolved settings (metres) -> the shader's constants (view units). `deepest_level`: the last level of
    // the z pyramid (0 without the hierarchy).
    static SaoConstants constants(const obscura_sao_settings& settings, const FrameInput& input, int deepest_level);
    // Writes packed visibility into `packed_ao` (RGBA8) over `region` (which starts on even coordinates).
    void run(const PassEnv& env, const obscura_sao_settings& settings, const UniformRange& frame,
             const UniformRange& pass, const Region& region, const FrameResources& resources,
             const gl::Texture2D& packed_ao);

private:
    static constexpr int kMaxFilter = OBSCURA_MIP_FILTER_MAX;  // SAO's filters: rotated grid, mean ... max (Table 1)
    gl::Object programs_[kMaxFilter + 1];  // by filter
};

// The separable bilateral blur (sdk/glsl/sao_blur.comp): the horizontal pass keeps the packed RGBA8 layout,
// the vertical one (`final`) writes plain visibility to an R16F texture.
class SaoBlurPass {
public:
    static constexpr int kMaxRadius = 8;  // the top of SAO's blur_radius setting (sao.cpp)
    // Builds both programs for `radius` (1 ... kMaxRadius, compiled in) on first use and, with a `target` (format
    // != 0), the vertical pass's variant that writes the host's target image (its format and blend compiled in).
    Error prepare(const PassEnv& env, int radius, const TargetWrite& target = TargetWrite());
    static SaoBlurConstants constants(const obscura_sao_settings& settings, int axis_x, int axis_y);
    // Blurs along x (the packed horizontal pass) or y (`final`) with the constants `pass` of `settings`.
    void run(const PassEnv& env, const obscura_sao_settings& settings, const UniformRange& frame,
             const UniformRange& pass, const Region& region, const gl::Texture2D& source,
             const gl::Texture2D& destination, bool final) const;
    // The vertical pass into the host's target image `target_texture` (prepare's `target`) instead of a texture.
    void run_into_target(const PassEnv& env, const obscura_sao_settings& settings, const UniformRange& frame,
                         const UniformRange& pass, const Region& region, const gl::Texture2D& source,
                         GLuint target_texture) const;

private:
    void dispatch(const PassEnv& env, const obscura_sao_settings& settings, const UniformRange& frame,
                  const UniformRange& pass, const Region& region, const gl::Texture2D& source, bool final) const;
    // Pixels an invocation filters along the axis (sao_blur.comp).
    static int run_length(const PassEnv& env);
    gl::Object programs_[kMaxRadius + 1][2];  // by radius, then final
    // The vertical pass's target variants by their defines, the last gl::kProgramVariantsKept used.
    gl::ProgramCache<gl::DefineLines> target_programs_;
    GLuint target_program_ = 0;  // prepare's
    TargetWrite target_;
};

}  // namespace obscura

#endif  // OBSCURA_SAO_H
