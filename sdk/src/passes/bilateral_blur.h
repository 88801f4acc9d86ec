// BilateralBlur: separable depth-aware Gaussian blur (sdk/glsl/bilateral_blur.comp), x then y.
#ifndef OBSCURA_BILATERAL_BLUR_H
#define OBSCURA_BILATERAL_BLUR_H

#include "passes/pass_common.h"

namespace obscura {

class BilateralBlurPass {
public:
    // Builds the program on first use.
    Error prepare(const PassEnv& env) {
        if (program_) return Error();
        return env.build("bilateral_blur.comp", "", &program_);
    }
    static BlurConstants constants(int radius, float sharpness, int axis_x, int axis_y);
    // Blurs `source` into `destination` over `region` along the axis in `pass`.
    void run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
             const gl::Texture2D& linear_depth, const gl::Texture2D& source, const gl::Texture2D& destination);

private:
    gl::Object program_;
};

}  // namespace obscura

#endif  // OBSCURA_BILATERAL_BLUR_H
