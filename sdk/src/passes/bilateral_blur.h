// BilateralBlur: separable depth-aware Gaussian blur (sdk/glsl/bilateral_blur.comp), x then y.
#ifndef OBSCURA_BILATERAL_BLUR_H
#define OBSCURA_BILATERAL_BLUR_H

#include <array>

#include "passes/pass_common.h"

namespace obscura {

class BilateralBlurPass {
public:
    static constexpr int kMaxRadius = 16;  // the top of HBAO's blur_radius setting (hbao.cpp)
    // Builds the program for `radius` (1 ... kMaxRadius, compiled in) on first use.
    Error prepare(const PassEnv& env, int radius);
    static BlurConstants constants(int radius, float sharpness, int axis_x, int axis_y);
    // Blurs `source` into `destination` over `region` along x or y with the constants `pass` (constants(radius, ...,
    // the same axis)).
    void run(const PassEnv& env, int radius, bool along_x, const UniformRange& frame, const UniformRange& pass,
             const Region& region, const gl::Texture2D& linear_depth, const gl::Texture2D& source,
             const gl::Texture2D& destination);

private:
    // Pixels an invocation filters along the axis (bilateral_blur.comp).
    static int run_length(const PassEnv& env);
    std::array<gl::Object, kMaxRadius + 1> programs_;  // by radius
};

}  // namespace obscura

#endif  // OBSCURA_BILATERAL_BLUR_H
