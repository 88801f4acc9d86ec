// BilateralBlur: separable depth-aware Gaussian blur (sdk/glsl/bilateral_blur.comp), x then y; the y pass can write
// the host's target image itself as the frame's last pass.
#ifndef OBSCURA_BILATERAL_BLUR_H
#define OBSCURA_BILATERAL_BLUR_H

#include "gl/program_cache.h"
#include "output_writer.h"
#include "passes/pass_common.h"

namespace obscura {

class BilateralBlurPass {
public:
    static constexpr int kMaxRadius = 16;  // the top of HBAO's blur_radius setting (hbao.cpp)
    // Builds the programs for `radius` (1 ... kMaxRadius, compiled in): the one that writes a texture and, with a
    // `target` (format != 0), the one that writes the host's target image (its format and blend compiled in).
    Error prepare(const PassEnv& env, int radius, const TargetWrite& target = TargetWrite());
    static BlurConstants constants(int radius, float sharpness, int axis_x, int axis_y);
    // Blurs `source` into `destination` over `region` along x or y with the constants `pass` (constants(radius, ...,
    // the same axis)), at prepare's radius.
    void run(const PassEnv& env, bool along_x, const UniformRange& frame, const UniformRange& pass,
             const Region& region, const gl::Texture2D& linear_depth, const gl::Texture2D& source,
             const gl::Texture2D& destination) const;
    // The y pass into the host's target image `target_texture` (prepare's `target`) instead of a texture.
    void run_into_target(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
                         const gl::Texture2D& linear_depth, const gl::Texture2D& source, GLuint target_texture) const;

private:
    void dispatch(const PassEnv& env, bool along_x, const UniformRange& frame, const UniformRange& pass,
                  const Region& region, const gl::Texture2D& linear_depth, const gl::Texture2D& source) const;
    // Pixels an invocation filters along the axis (bilateral_blur.comp).
    static int run_length(const PassEnv& env);
    gl::Object programs_[kMaxRadius + 1];  // by radius: both passes into a texture
    // The y pass's target variants by their defines (radius, target format and blend), the last
    // gl::kProgramVariantsKept used.
    gl::ProgramCache<gl::DefineLines> target_programs_;
    GLuint program_ = 0, target_program_ = 0;  // prepare's
    TargetWrite target_;
};

}  // namespace obscura

#endif  // OBSCURA_BILATERAL_BLUR_H
