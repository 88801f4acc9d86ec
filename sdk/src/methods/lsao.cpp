// LSAO (Timonen, EGSR 2013): its settings metadata and presets, its derived values, the falloff it is compared
// with, its technique (the line sweeps over the whole depth texture, then the gather) and its registry row.
#include "falloff.h"
#include "method_registry.h"
#include "passes/lsao.h"
#include "settings.h"
#include "technique.h"

namespace obscura {
namespace {

constexpr const char* const kLsaoPresetNames[] = {"k8", "k16", "k24", "k32", "k8_figure1", "k16_figure13"};
constexpr const char* const kLsaoPatternNames[] = {"aligned", "free"};
constexpr const char* const kLsaoTangentStrategyNames[] = {"receiver", "fixed_hull", "fixed"};
constexpr int kLsaoFixedTangent = 3;  // tangent_strategy "fixed": no normal read by the sweeps

// LSAO (Timonen 2013). Defaults from the paper's options: falloff r/(r+d^2), aligned sampling patterns, the K = 8
// configuration of Table 2 and the receiver's own tangent for hull and occlusion (sec. 4.1, strategy 1). Until
// 2026-12-05 they were K = 16 and the fixed tangent sin(t) = -0.85 (strategy 3): against the geometry truth the
// receiver's tangent halves the error (mean over the seven built-in scenes at 320x180 0.0487 -> 0.0263; twelve
// held-out views 0.0535 -> 0.0343, better on 11), and with K = 8 it costs 0.85-0.96x of the old default on llvmpipe
// (docs/quality.md, "LSAO's defaults").
const obscura_setting_info kLsaoSettings[] = {
    setting_row("radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m", "falloff scale: the decay rate defaults to C*radius^2",
     OBSCURA_SETTING_OFFSET(lsao, radius)),
    enum_row("falloff", 2, 1, "rho0 (LSAO eq. 3, HBAO's) or inverse_quadratic r/(r+d^2) (LSAO eq. 2)",
             OBSCURA_SETTING_OFFSET(lsao, falloff), kFalloffNames, 2),
    setting_row("falloff_c", OBSCURA_SETTING_FLOAT, 0.3, 1e-3, 0.999, "", "C: rho0's sink and the decay-rate default",
     OBSCURA_SETTING_OFFSET(lsao, falloff_c)),
    setting_row("decay_rate", OBSCURA_SETTING_FLOAT, 0.0, 1e-10, 1e8, "m^2", "r of the falloff; derived: C*radius^2",
     OBSCURA_SETTING_OFFSET(lsao, decay_rate), OBSCURA_SETTING_FLAG_DERIVED),
    enum_row("preset", 0, 1,
             "K/D_S/D_L of the paper: k8 8/1.41/1.41, k16 16/2.43/1.64, k24 24/3.56/1.69, k32 32/4.69/1.70 (Table 2), "
             "k8_figure1 8/2.83/2.12, k16_figure13 16/4.87/2.46; derived: k8 (with the receiver's tangent as close "
             "to the geometry truth as k16, at less cost; its step, the shortest, also keeps reduced resolution near "
             "full size's error)",
             OBSCURA_SETTING_OFFSET(lsao, preset), kLsaoPresetNames, 6, OBSCURA_SETTING_FLAG_DERIVED),
    enum_row("pattern", 1, 1, "aligned: 8n directions on texel centres; free: any K, interpolated depth",
             OBSCURA_SETTING_OFFSET(lsao, pattern), kLsaoPatternNames),
    setting_row("directions", OBSCURA_SETTING_INT, 0, 1, 64, "", "K; aligned patterns need a multiple of 8; derived: the preset's",
     OBSCURA_SETTING_OFFSET(lsao, directions), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("step_length", OBSCURA_SETTING_FLOAT, 0.0, 0.5, 16.0, "px",
                "D_S; an aligned pattern walks the nearest whole number (at least 1) of its template's steps; derived: "
                "the preset's",
     OBSCURA_SETTING_OFFSET(lsao, step_length), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("line_spacing", OBSCURA_SETTING_FLOAT, 0.0, 0.5, 16.0, "px", "D_L between parallel lines; derived: the preset's",
     OBSCURA_SETTING_OFFSET(lsao, line_spacing), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("tangent", OBSCURA_SETTING_FLOAT, -0.85, -1.0, 0.5, "", "the fixed sin(t) of the hull and the occlusion (tangent_strategy fixed; the hull's with fixed_hull)",
     OBSCURA_SETTING_OFFSET(lsao, tangent)),
    enum_row("tangent_strategy", 1, 1,
             "sec. 4.1: receiver: the receiver's tangent for hull and occlusion; fixed_hull: fixed for the hull, the "
             "receiver's for occlusion; fixed: fixed for both",
             OBSCURA_SETTING_OFFSET(lsao, tangent_strategy), kLsaoTangentStrategyNames),
    setting_row("hull_capacity", OBSCURA_SETTING_INT, 24, 2, OBSCURA_LSAO_MAX_HULL, "",
     "points kept per line; the oldest is dropped when full", OBSCURA_SETTING_OFFSET(lsao, hull_capacity)),
    setting_row("exact", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "", "brute-force largest occluder instead of the hull (validation)",
     OBSCURA_SETTING_OFFSET(lsao, exact)),
    setting_row("segment_steps", OBSCURA_SETTING_INT, 0, -1, 4096, "",
     "steps per line segment (one GPU thread each, after a warm-up); -1: whole lines; derived: whole lines on CPU "
     "renderers, 128 on GPUs", OBSCURA_SETTING_OFFSET(lsao, segment_steps), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("warmup_tolerance", OBSCURA_SETTING_FLOAT, 0.1, 1e-4, 1.0, "",
     "segments: most obscurance an occluder before the warm-up may cast (sets the warm-up length)",
     OBSCURA_SETTING_OFFSET(lsao, warmup_tolerance)),
    setting_row("warmup_stride", OBSCURA_SETTING_INT, 4, 1, 64, "",
     "segments: the warm-up before the last 16 steps samples every n-th step (far occluders need less detail)",
     OBSCURA_SETTING_OFFSET(lsao, warmup_stride)),
    setting_row("depth_threshold", OBSCURA_SETTING_FLOAT, 0.05, 1e-4, 10.0, "", "gather: relative depth difference that rejects",
     OBSCURA_SETTING_OFFSET(lsao, depth_threshold)),
    setting_row("normal_test", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "", "gather: also reject by normal", OBSCURA_SETTING_OFFSET(lsao, normal_test)),
    setting_row("normal_threshold", OBSCURA_SETTING_FLOAT, 0.8, -1.0, 1.0, "", "gather: minimum dot of the normals",
     OBSCURA_SETTING_OFFSET(lsao, normal_threshold)),
    setting_row("intensity", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "obscurance multiplier", OBSCURA_SETTING_OFFSET(lsao, intensity)),
    setting_row("power", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "exponent applied to the visibility", OBSCURA_SETTING_OFFSET(lsao, power)),
};

struct LsaoPreset {
    int directions;
    double step_length, line_spacing;
};
// LSAO paper Table 2 (1-4) and Figures 1 and 13 (5, 6).
const LsaoPreset kLsaoPresets[] = {{8, 1.41, 1.41}, {16, 2.43, 1.64}, {24, 3.56, 1.69},
                                   {32, 4.69, 1.70}, {8, 2.83, 2.12}, {16, 4.87, 2.46}};

// LSAO's derived values: the preset fills K, D_S and D_L, the decay rate follows the radius. An aligned
// pattern exists only for K = 8n.
Error derive_lsao(const obscura_settings&, obscura_settings* resolved) {
    obscura_lsao_settings* lsao = &resolved->lsao;
    // k8 at every resolution: with the receiver's tangent it is as close to the geometry truth as k16 at full size,
    // and at reduced resolution, where a reduced texel spans 2 or 4 of the host's and so does every step, its step
    // of 1.41 texels (the shortest aligned one) keeps the error near full size's (k16's 2.43 walks 4.9 host texels
    // at half size, and its sweeps miss the occluders in between; docs/quality.md).
    if (lsao->preset == 0) lsao->preset = 1;
    const LsaoPreset& preset = kLsaoPresets[lsao->preset - 1];
    if (lsao->directions == 0) lsao->directions = preset.directions;
    if (lsao->step_length == 0.0f) lsao->step_length = float(preset.step_length);
    if (lsao->line_spacing == 0.0f) lsao->line_spacing = float(preset.line_spacing);
    if (lsao->decay_rate == 0.0f) lsao->decay_rate = derived_decay_rate(lsao->falloff_c, lsao->radius);
    // Segments start on the sweep's 8-value stores; 0 (auto) is settled by the context, which knows the renderer.
    if (lsao->segment_steps > 0) lsao->segment_steps = (lsao->segment_steps + 7) / 8 * 8;
    if (lsao->pattern == 1 && lsao->directions % 8 != 0) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "lsao.directions = %d: the aligned pattern has K = 8n directions (8, 16, 24 ... 64); "
                           "use the free pattern (pattern 2, \"free\") for other counts",
                           int(lsao->directions));
    }
    return Error();
}

void lsao_reference_falloff(const obscura_settings& resolved, obscura_reference_settings* reference) {
    reference->falloff =
        resolved.lsao.falloff == OBSCURA_FALLOFF_RHO0 ? OBSCURA_FALLOFF_RHO0 : OBSCURA_FALLOFF_INVERSE_QUADRATIC;
    reference->radius = resolved.lsao.radius;
    reference->falloff_c = resolved.lsao.falloff_c;
    reference->decay_rate = resolved.lsao.decay_rate;
}

class LsaoTechnique final : public Technique {
public:
    TechniquePlan plan(const obscura_settings& settings, int, int, const FrameRequest&) const override {
        const obscura_lsao_settings& lsao = settings.lsao;
        TechniquePlan plan;
        plan.radius = lsao.radius;
        // With the fixed tangent and no normal test only the gather's receiver reads its normal.
        // Otherwise the whole texture: with the receiver's tangent (strategies receiver and fixed_hull) the sweeps
        // read the normal of every point of their lines, the guard band's included, and the normal test reads the
        // gather's nearest samples, which lie beyond a lattice step of the pixel where a line ends short of it.
        const bool receiver_only = lsao.tangent_strategy == kLsaoFixedTangent && lsao.normal_test != OBSCURA_TOGGLE_ON;
        plan.normals_margin = receiver_only ? 0 : TechniquePlan::kNormalsEverywhere;
        plan.writes_target = true;  // the gather, over the output rectangle (no apron)
        // The gather writes resources.ao wherever it does not write the target: debug views too, so ao stays.
        return plan;
    }

    Error prepare(const PassEnv& env, const obscura_settings& settings, const FrameRequest& request,
                  FrameResources& resources) override {
        Error error = pass_.prepare(env, settings.lsao, request.target);
        if (!error) error = pass_.ensure_layout(env, settings.lsao, resources.width, resources.height, request.frame_index);
        return error;
    }

    void write_constants(const Frame& frame, UniformWriter& uniforms) override {
        constants_ = uniforms.push(pass_.constants(frame.settings.lsao, frame.input, frame.env.cpu_renderer));
    }

    Error record(const Frame& frame, PassRecorder& recorder, TechniqueOutput* out) override {
        out->raw = out->result = &frame.resources.ao;
        pass_.run_sweeps(frame.env, frame.settings.lsao, frame.uniforms.whole, constants_, frame.resources);
        Error error = recorder.end(PassId::LineSweep);
        if (error) return error;
        if (frame.target.format != 0) {  // the gather runs as the output's write
            return target_write_.defer(frame, PassId::Gather, out);
        }
        pass_.run_gather(frame.env, frame.uniforms.ao, constants_, frame.regions.ao, frame.resources);
        return recorder.end(PassId::Gather);
    }

    uint64_t memory_bytes() const override { return pass_.bytes(); }
    void release() override { pass_.release(); }

    // The gather into the host's target image (LastPassTargetWrite, during `frame`'s output write), over the output
    // rectangle: LSAO's AO region is that rectangle, without an apron, and the target holds nothing beyond it.
    void write_target(const PassEnv& env, const Frame& frame, GLuint texture) const {
        pass_.run_gather_into_target(env, frame.uniforms.output, constants_, frame.regions.output, frame.resources,
                                     texture);
    }

private:
    LsaoPass pass_;
    UniformRange constants_;
    LastPassTargetWrite<LsaoTechnique> target_write_{*this};
};

const PassId kLsaoPasses[] = {PassId::LineSweep, PassId::Gather};

// segment_steps 0 (auto) as the context settles it: whole lines (-1) on CPU renderers, kLsaoGpuSegmentSteps on GPUs.
void derive_lsao_for_renderer(bool cpu_renderer, obscura_settings* resolved) {
    if (resolved->lsao.segment_steps == 0) resolved->lsao.segment_steps = cpu_renderer ? -1 : kLsaoGpuSegmentSteps;
}

}  // namespace

extern const MethodDescriptor kLsaoMethod = {
    OBSCURA_METHOD_LSAO,
    "lsao",
    offsetof(obscura_settings, lsao),
    sizeof(obscura_lsao_settings),
    kLsaoSettings,
    uint32_t(sizeof kLsaoSettings / sizeof kLsaoSettings[0]),
    derive_lsao,
    lsao_reference_falloff,
    kLsaoPasses,
    uint32_t(sizeof kLsaoPasses / sizeof kLsaoPasses[0]),
    create_technique<LsaoTechnique>,
    false,
    derive_lsao_for_renderer,
};

}  // namespace obscura
