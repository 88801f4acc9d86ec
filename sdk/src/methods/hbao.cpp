// HBAO (LSAO paper sec. 3 and 6): its settings metadata, its derived values, the falloff it is compared with,
// its technique (the horizon search, then the separable bilateral blur) and its registry row.
#include "falloff.h"
#include "method_registry.h"
#include "passes/bilateral_blur.h"
#include "passes/hbao.h"
#include "settings.h"
#include "technique.h"

namespace obscura {
namespace {

constexpr const char* const kHbaoEstimatorNames[] = {"horizon_split", "largest_occluder"};

// HBAO (LSAO paper sec. 3 and 6; the falloff rho0 is its eq. 3). The falloff follows the paper (C = 0.3); the
// sampling, estimator, shaping and blur defaults were set by `obscura tune` against the geometry truth and checked
// on held-out views (docs/parameters.md, "Tuned defaults"): 8 directions x 7 steps, the largest occluder,
// intensity 2 and power 0.5, a 1-tap bilateral blur (they were 12 steps, horizon split, 1, 1, 4 taps at 16).
const obscura_setting_info kHbaoSettings[] = {
    setting_row("radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m",
     "distance where the falloff reaches zero; the steps cover it", OBSCURA_SETTING_OFFSET(hbao, radius)),
    setting_row("falloff_c", OBSCURA_SETTING_FLOAT, 0.3, 1e-3, 0.999, "",
     "C of rho0(d) = max(0, r(1+C)/(r+d^2) - C): how far the falloff is sunk", OBSCURA_SETTING_OFFSET(hbao, falloff_c)),
    setting_row("decay_rate", OBSCURA_SETTING_FLOAT, 0.0, 1e-10, 1e8, "m^2",
     "r of rho0; derived: C*radius^2, so rho0 reaches zero at the radius (the steps stop at the radius whatever "
     "r: a larger one is cut off there)",
     OBSCURA_SETTING_OFFSET(hbao, decay_rate), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("directions", OBSCURA_SETTING_INT, 8, 1, 32, "", "K azimuthal directions per pixel",
     OBSCURA_SETTING_OFFSET(hbao, directions)),
    setting_row("steps", OBSCURA_SETTING_INT, 7, 1, 128, "", "N ray-march steps per direction", OBSCURA_SETTING_OFFSET(hbao, steps)),
    enum_row("estimator", 2, 1,
             "horizon_split: horizon-split integration (Bavoil 2008); largest_occluder: the largest falloff-weighted "
             "occluder only (LSAO eq. 1)",
             OBSCURA_SETTING_OFFSET(hbao, estimator), kHbaoEstimatorNames),
    setting_row("bias", OBSCURA_SETTING_FLOAT, 0.0, 0.0, 0.5, "",
     "subtracted from sin(h) - sin(t) to hide tessellation; the default is zero", OBSCURA_SETTING_OFFSET(hbao, bias)),
    setting_row("intensity", OBSCURA_SETTING_FLOAT, 2.0, 1e-3, 16.0, "", "obscurance multiplier", OBSCURA_SETTING_OFFSET(hbao, intensity)),
    setting_row("power", OBSCURA_SETTING_FLOAT, 0.5, 1e-3, 16.0, "", "exponent applied to the visibility",
     OBSCURA_SETTING_OFFSET(hbao, power)),
    setting_row("max_radius_pixels", OBSCURA_SETTING_FLOAT, 256.0, 1.0, 4096.0, "px",
     "cap of the radius on screen, bounding the cost of close-ups", OBSCURA_SETTING_OFFSET(hbao, max_radius_pixels)),
    setting_row("blur", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "depth-aware bilateral blur of the AO", OBSCURA_SETTING_OFFSET(hbao, blur)),
    setting_row("blur_radius", OBSCURA_SETTING_INT, 1, 1, BilateralBlurPass::kMaxRadius, "px", "blur taps on each side",
     OBSCURA_SETTING_OFFSET(hbao, blur_radius)),
    setting_row("blur_sharpness", OBSCURA_SETTING_FLOAT, 89.3, 1e-3, 1000.0, "",
     "how strongly the blur stops at depth edges (relative depth difference scale)",
     OBSCURA_SETTING_OFFSET(hbao, blur_sharpness)),
};

Error derive_hbao(const obscura_settings&, obscura_settings* resolved) {
    // The decay rate defaults to C * radius^2, where rho0 reaches zero exactly at the radius.
    obscura_hbao_settings& hbao = resolved->hbao;
    if (hbao.decay_rate == 0.0f) hbao.decay_rate = derived_decay_rate(hbao.falloff_c, hbao.radius);
    return Error();
}

void hbao_reference_falloff(const obscura_settings& resolved, obscura_reference_settings* reference) {
    reference->falloff = OBSCURA_FALLOFF_RHO0;
    reference->radius = resolved.hbao.radius;
    reference->falloff_c = resolved.hbao.falloff_c;
    reference->decay_rate = resolved.hbao.decay_rate;
}

bool hbao_blurs(const obscura_hbao_settings& hbao, bool raw_view) { return !raw_view && hbao.blur == OBSCURA_TOGGLE_ON; }

class HbaoTechnique final : public Technique {
public:
    TechniquePlan plan(const obscura_settings& settings, int, int, const FrameRequest& request) const override {
        TechniquePlan plan;
        plan.apron = hbao_blurs(settings.hbao, request.raw_view) ? settings.hbao.blur_radius : 0;
        plan.radius = settings.hbao.radius;
        plan.uses_blur_temp = plan.uses_ao_blurred = hbao_blurs(settings.hbao, false);
        plan.writes_target = hbao_blurs(settings.hbao, false);  // the blur's y pass
        return plan;
    }

    Error prepare(const PassEnv& env, const obscura_settings& settings, const FrameRequest& request,
                  FrameResources&) override {
        Error error = hbao_.prepare(env);
        if (!error && hbao_blurs(settings.hbao, request.raw_view)) {
            error = blur_.prepare(env, settings.hbao.blur_radius, request.target);
        }
        return error;
    }

    void write_constants(const Frame& frame, UniformWriter& uniforms) override {
        const obscura_hbao_settings& hbao = frame.settings.hbao;
        const int apron = hbao_blurs(hbao, frame.raw_view) ? hbao.blur_radius : 0;
        pass_ = uniforms.push(HbaoPass::constants(hbao, frame.input));
        blur_x_ = uniforms.push(BilateralBlurPass::constants(apron, hbao.blur_sharpness, 1, 0));
        blur_y_ = uniforms.push(BilateralBlurPass::constants(apron, hbao.blur_sharpness, 0, 1));
    }

    Error record(const Frame& frame, PassRecorder& recorder, TechniqueOutput* out) override {
        FrameResources& r = frame.resources;
        hbao_.run(frame.env, frame.settings.hbao, frame.uniforms.ao, pass_, frame.regions.ao, r);
        out->raw = out->result = &r.ao;
        Error error = recorder.end(PassId::Hbao);
        if (error || !hbao_blurs(frame.settings.hbao, frame.raw_view)) return error;
        blur_.run(frame.env, true, frame.uniforms.blur_x, blur_x_, frame.regions.blur_x, r.linear_depth, r.ao,
                  r.blur_temp);
        out->result = &r.ao_blurred;
        if (frame.target.format != 0) {
            // The y pass runs as the output's write, its time under "blur" with the x pass's.
            return target_write_.defer(frame, PassId::Blur, out);
        }
        blur_.run(frame.env, false, frame.uniforms.output, blur_y_, frame.regions.output, r.linear_depth, r.blur_temp,
                  r.ao_blurred);
        return recorder.end(PassId::Blur);
    }

    uint64_t memory_bytes() const override { return 0; }  // the shared AO and blur textures only
    void release() override {}

    // The blur's y pass into the host's target image (LastPassTargetWrite, during `frame`'s output write).
    void write_target(const PassEnv& env, const Frame& frame, GLuint texture) const {
        blur_.run_into_target(env, frame.uniforms.output, blur_y_, frame.regions.output, frame.resources.linear_depth,
                              frame.resources.blur_temp, texture);
    }

private:
    HbaoPass hbao_;
    BilateralBlurPass blur_;
    UniformRange pass_, blur_x_, blur_y_;
    LastPassTargetWrite<HbaoTechnique> target_write_{*this};
};

const PassId kHbaoPasses[] = {PassId::Hbao, PassId::Blur};

}  // namespace

extern const MethodDescriptor kHbaoMethod = {
    OBSCURA_METHOD_HBAO,
    "hbao",
    offsetof(obscura_settings, hbao),
    sizeof(obscura_hbao_settings),
    kHbaoSettings,
    uint32_t(sizeof kHbaoSettings / sizeof kHbaoSettings[0]),
    derive_hbao,
    hbao_reference_falloff,
    kHbaoPasses,
    uint32_t(sizeof kHbaoPasses / sizeof kHbaoPasses[0]),
    create_technique<HbaoTechnique>,
};

}  // namespace obscura
