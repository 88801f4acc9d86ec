// SAO (McGuire et al., HPG 2012): its settings metadata, its derived values, the falloff it is compared with,
// its technique (z pyramid, spiral taps with the AlchemyAO estimator and the 2x2 step, the separable bilateral
// blur over packed AO and z) and its registry row.
#include "method_registry.h"
#include "passes/sao.h"
#include "passes/z_pyramid.h"
#include "settings.h"
#include "technique.h"

namespace obscura {
namespace {

constexpr const char* const kSaoMipFilterNames[] = {"rotated_grid", "mean", "harmonic_mean", "min", "max"};

// SAO (McGuire et al. 2012). Defaults are the paper's: s = 9, tau = 7, q' = 2^3, rotated-grid MIPs, 7-tap
// blur with stride 3 and edge constant 2^11 over z packed across 200 m. The estimator constants follow
// AlchemyAO (sigma = k = 1); beta and epsilon were chosen against the screen-space reference (docs/quality.md).
const obscura_setting_info kSaoSettings[] = {
    setting_row("radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m", "world-space radius r of the sample ball (eq. 5)",
     OBSCURA_SETTING_OFFSET(sao, radius)),
    setting_row("samples", OBSCURA_SETTING_INT, 9, 1, 64, "", "s spiral taps per pixel", OBSCURA_SETTING_OFFSET(sao, samples)),
    setting_row("turns", OBSCURA_SETTING_INT, 0, 1, 1024, "",
     "tau turns of the spiral; derived: the integer nearest 7s/9 sharing no factor with s (7 for s = 9)",
     OBSCURA_SETTING_OFFSET(sao, turns), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("mip", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "z-MIP hierarchy; off: every tap reads level 0 (quality baseline)",
     OBSCURA_SETTING_OFFSET(sao, mip)),
    enum_row("mip_filter", 1, 1, "z^(m+1) from z^m (Table 1): rotated-grid subsample, mean, harmonic mean, min, max",
             OBSCURA_SETTING_OFFSET(sao, mip_filter), kSaoMipFilterNames),
    setting_row("log_q", OBSCURA_SETTING_INT, 3, 1, 8, "", "log2 q': taps move one MIP level down per doubling past q' px",
     OBSCURA_SETTING_OFFSET(sao, log_q)),
    setting_row("intensity", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "sigma of the AlchemyAO estimator",
     OBSCURA_SETTING_OFFSET(sao, intensity)),
    setting_row("bias", OBSCURA_SETTING_FLOAT, 1e-3, 1e-6, 0.1, "", "beta: v.n must exceed beta * receiver distance",
     OBSCURA_SETTING_OFFSET(sao, bias)),
    setting_row("contrast", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "k: exponent of the visibility",
     OBSCURA_SETTING_OFFSET(sao, contrast)),
    setting_row("epsilon", OBSCURA_SETTING_FLOAT, 0.01, 1e-6, 1.0, "", "epsilon / r^2 in the estimator's denominator",
     OBSCURA_SETTING_OFFSET(sao, epsilon)),
    setting_row("max_radius_pixels", OBSCURA_SETTING_FLOAT, 256.0, 1.0, 4096.0, "px", "cap of the screen radius r'",
     OBSCURA_SETTING_OFFSET(sao, max_radius_pixels)),
    setting_row("quad_filter", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "2x2 bilateral step at the end of the AO pass",
     OBSCURA_SETTING_OFFSET(sao, quad_filter)),
    setting_row("blur", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "separable bilateral blur", OBSCURA_SETTING_OFFSET(sao, blur)),
    setting_row("blur_radius", OBSCURA_SETTING_INT, 3, 1, SaoBlurPass::kMaxRadius, "", "blur taps on each side (3: the paper's 7 taps)",
     OBSCURA_SETTING_OFFSET(sao, blur_radius)),
    setting_row("blur_stride", OBSCURA_SETTING_INT, 3, 1, 4, "px", "pixels between blur taps", OBSCURA_SETTING_OFFSET(sao, blur_stride)),
    setting_row("blur_sharpness", OBSCURA_SETTING_FLOAT, 2048.0, 1.0, 1e6, "",
     "edge weight max(0, 1 - sharpness |dz| / blur_depth_range)", OBSCURA_SETTING_OFFSET(sao, blur_sharpness)),
    setting_row("blur_depth_range", OBSCURA_SETTING_FLOAT, 200.0, 1e-2, 1e5, "m",
     "distance over which z is packed in 16 bits beside the AO (the paper's z_min)", OBSCURA_SETTING_OFFSET(sao, blur_depth_range)),
};

Error derive_sao(const obscura_settings&, obscura_settings* resolved) {
    obscura_sao_settings& sao = resolved->sao;
    if (sao.turns == 0) sao.turns = default_spiral_turns(sao.samples);
    return Error();
}

void sao_reference_falloff(const obscura_settings& resolved, obscura_reference_settings* reference) {
    // The AlchemyAO estimator counts every occluder inside the ball of radius r at full weight: a step falloff
    // (1 up to r, 0 beyond).
    reference->falloff = OBSCURA_FALLOFF_TABLE;
    reference->radius = resolved.sao.radius;
    for (float& value : reference->falloff_table) value = 1.0f;
}

bool sao_blurs(const obscura_sao_settings& sao, bool raw_view) { return !raw_view && sao.blur == OBSCURA_TOGGLE_ON; }

class SaoTechnique final : public Technique {
public:
    TechniquePlan plan(const obscura_settings& settings, int width, int height,
                       const FrameRequest& request) const override {
        const obscura_sao_settings& sao = settings.sao;
        TechniquePlan plan;
        plan.apron = sao_blurs(sao, request.raw_view) ? sao.blur_radius * sao.blur_stride : 0;
        plan.ao_on_quads = true;  // the quad filter pairs pixels of 2x2 quads in absolute coordinates
        plan.depth_levels = ZPyramidPass::level_count(width, height, SaoPass::wanted_levels(sao));
        plan.radius = sao.radius;
        plan.uses_ao = false;  // its passes write packed_ao_ and packed_temp_
        plan.uses_ao_blurred = sao_blurs(sao, false);
        plan.writes_target = sao_blurs(sao, false);  // the blur's vertical pass
        return plan;
    }

    Error prepare(const PassEnv& env, const obscura_settings& settings, const FrameRequest& request,
                  FrameResources& resources) override {
        Error error = pyramid_pass_.prepare(env, settings.sao.mip_filter);
        if (!error) error = sao_.prepare(env, settings.sao);
        if (!error && sao_blurs(settings.sao, request.raw_view)) {
            error = blur_.prepare(env, settings.sao.blur_radius, request.target);
        }
        if (error) return error;
        // The blur's intermediate only where the settings blur (debug views aside, as the plan: a debug view does not
        // reallocate); blur=off frees it, so the memory report holds what the configuration needs.
        const bool blurs = sao_blurs(settings.sao, false);
        if (!env.fit_texture(&packed_ao_, true, GL_RGBA8, resources.width, resources.height) ||
            !env.fit_texture(&packed_temp_, blurs, GL_RGBA8, resources.width, resources.height)) {
            release();
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d SAO textures failed",
                               resources.width, resources.height);
        }
        return Error();
    }

    void write_constants(const Frame& frame, UniformWriter& uniforms) override {
        const obscura_sao_settings& sao = frame.settings.sao;
        levels_ = frame.resources.linear_depth.levels();
        pyramid_dispatches_ = ZPyramidPass::dispatch_count(levels_);
        for (int d = 0; d < pyramid_dispatches_ && d < kMaxPyramidDispatches; ++d) {
            pyramid_[d] = uniforms.push(ZPyramidPass::constants(d, levels_));
        }
        pass_ = uniforms.push(SaoPass::constants(sao, frame.input, levels_ - 1));
        blur_x_ = uniforms.push(SaoBlurPass::constants(sao, 1, 0));
        blur_y_ = uniforms.push(SaoBlurPass::constants(sao, 0, 1));
    }

    Error record(const Frame& frame, PassRecorder& recorder, TechniqueOutput* out) override {
        Error error;
        if (levels_ > 1) {
            pyramid_pass_.run(frame.env, frame.settings.sao.mip_filter, pyramid_, pyramid_dispatches_,
                              frame.resources.linear_depth);
            error = recorder.end(PassId::ZPyramid);
            if (error) return error;
        }
        sao_.run(frame.env, frame.settings.sao, frame.uniforms.ao, pass_, frame.regions.ao, frame.resources,
                 packed_ao_);
        out->raw = out->result = &packed_ao_;
        error = recorder.end(PassId::Sao);
        if (error || !sao_blurs(frame.settings.sao, frame.raw_view)) return error;
        const obscura_sao_settings& sao = frame.settings.sao;
        blur_.run(frame.env, sao, frame.uniforms.blur_x, blur_x_, frame.regions.blur_x, packed_ao_, packed_temp_, false);
        out->result = &frame.resources.ao_blurred;
        if (frame.target.format != 0) {
            // The vertical pass runs as the output's write, its time under "blur" with the horizontal one's.
            return target_write_.defer(frame, PassId::Blur, out);
        }
        blur_.run(frame.env, sao, frame.uniforms.output, blur_y_, frame.regions.output, packed_temp_,
                  frame.resources.ao_blurred, true);
        return recorder.end(PassId::Blur);
    }

    uint64_t memory_bytes() const override { return packed_ao_.bytes() + packed_temp_.bytes(); }
    void release() override {
        packed_ao_ = gl::Texture2D();
        packed_temp_ = gl::Texture2D();
    }

    // The blur's vertical pass into the host's target image (LastPassTargetWrite, during `frame`'s output write).
    void write_target(const PassEnv& env, const Frame& frame, GLuint texture) const {
        blur_.run_into_target(env, frame.settings.sao, frame.uniforms.output, blur_y_, frame.regions.output,
                              packed_temp_, texture);
    }

private:
    static constexpr int kMaxPyramidDispatches = 4;
    ZPyramidPass pyramid_pass_;
    SaoPass sao_;
    SaoBlurPass blur_;
    gl::Texture2D packed_ao_;    // RGBA8 visibility + 16-bit z key + geometry flag ...
    gl::Texture2D packed_temp_;  // ... and the same after the horizontal blur
    int levels_ = 1, pyramid_dispatches_ = 0;
    UniformRange pyramid_[kMaxPyramidDispatches], pass_, blur_x_, blur_y_;
    LastPassTargetWrite<SaoTechnique> target_write_{*this};
};

const PassId kSaoPasses[] = {PassId::ZPyramid, PassId::Sao, PassId::Blur};

}  // namespace

extern const MethodDescriptor kSaoMethod = {
    OBSCURA_METHOD_SAO,
    "sao",
    offsetof(obscura_settings, sao),
    sizeof(obscura_sao_settings),
    kSaoSettings,
    uint32_t(sizeof kSaoSettings / sizeof kSaoSettings[0]),
    derive_sao,
    sao_reference_falloff,
    kSaoPasses,
    uint32_t(sizeof kSaoPasses / sizeof kSaoPasses[0]),
    create_technique<SaoTechnique>,
};

}  // namespace obscura
