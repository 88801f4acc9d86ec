// GTAO (Jimenez et al. 2016) with the visibility bitmask (Therrien et al. 2023) as its finite-thickness mode: its
// settings metadata, its derived values (the preset's slices and steps), the falloff it is compared with, its
// technique (z pyramid, slices, denoise) and its registry row.
#include "method_registry.h"
#include "passes/gtao.h"
#include "passes/z_pyramid.h"
#include "settings.h"
#include "technique.h"

namespace obscura {
namespace {

constexpr const char* const kGtaoPresetNames[] = {"low", "medium", "high", "ultra"};
constexpr const char* const kGtaoModeNames[] = {"horizon", "bitmask"};

// Defaults: XeGTAO's High preset (3 slices x 3 steps per side) and MIP offset (3.3); its step distribution (2) until
// 2026-12-05 (below).
// Measured against the geometry truth on the atrium, objects, clutter and terrain at 320x180 (docs/quality.md):
// horizon mode and power 1.5 beat the bitmask mode and power 1 or 2 on every scene; `obscura tune` then moved the
// falloff range to the whole radius (XeGTAO: 0.615; the falloff becomes 1 - d/R, close to HBAO's rho0) and the
// denoise sharpness to 256 (mean over the four scenes 0.0263 -> 0.0253). Bitmask: 32 sectors and (until 2026-12-05) 0.3 m of
// thickness (the value that brought REFERENCE closest to the geometry truth on the atrium). Power 1.5 -> 1.75
// (2026-12-04) after the normals of features narrower than two texels stopped turning toward the background, which
// brightened GTAO: lower error on 13 of the 7 scenes x 2 sizes in horizon mode (atrium 0.0276 -> 0.0269 at 320x180,
// 0.0235 -> 0.0219 at 640x360; the terrain +0.00008) and on 12 in bitmask mode (not the atrium: 0.0295 -> 0.0311).
// Bitmask 0.3 m and power 1.75 -> 0.4 m and 1.5 (2026-12-05, after the step distribution): at 3 steps a side a
// thicker slab makes up for part of the occluders between the samples; lower on all seven scenes at both sizes
// (mean 0.0188 -> 0.0177 at 320x180, 0.0175 -> 0.0165 at 640x360) and on 11 of 12 held-out views (the clutter room's
// table close-up +0.0056). The power derives from the mode.
// Step distribution 2 -> 1.5 (2026-12-05): the farther steps closer together, where 3 steps per side missed the
// broad occlusion of creases (mean over the seven scenes 0.0160 -> 0.0153 at 640x360, lower on all seven; 0.0168 ->
// 0.0165 at 320x180, lower on five; the atrium +0.0003 there), at the same cost (u sqrt u compiled in).
const obscura_setting_info kGtaoSettings[] = {
    setting_row("radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m", "occluders farther than this do not count",
     OBSCURA_SETTING_OFFSET(gtao, radius)),
    enum_row("preset", 3, 1, "slices x steps per side: low 1x2, medium 2x2, high 3x3, ultra 9x3 (XeGTAO's names)",
             OBSCURA_SETTING_OFFSET(gtao, preset), kGtaoPresetNames),
    setting_row("slices", OBSCURA_SETTING_INT, 0, 1, 16, "", "S slices per pixel; derived: the preset's",
     OBSCURA_SETTING_OFFSET(gtao, slices), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("steps", OBSCURA_SETTING_INT, 0, 1, 32, "", "N steps to each side of a slice; derived: the preset's",
     OBSCURA_SETTING_OFFSET(gtao, steps), OBSCURA_SETTING_FLAG_DERIVED),
    enum_row("thickness_mode", 1, 1,
             "horizon: the paper's two horizons per slice (every occluder infinitely thick); bitmask: each sample "
             "occupies the sectors from its front to thickness behind it (Therrien et al. 2023)",
             OBSCURA_SETTING_OFFSET(gtao, thickness_mode), kGtaoModeNames),
    setting_row("thickness", OBSCURA_SETTING_FLOAT, 0.4, 1e-3, 1e4, "m", "bitmask: solid assumed behind every depth sample",
     OBSCURA_SETTING_OFFSET(gtao, thickness)),
    setting_row("thickness_blend", OBSCURA_SETTING_FLOAT, 0.0, 0.0, 1.0, "",
     "horizon: the paper's thickness heuristic, the fraction by which a lower sample pulls the horizon down",
     OBSCURA_SETTING_OFFSET(gtao, thickness_blend)),
    setting_row("sectors", OBSCURA_SETTING_INT, 32, 4, 32, "", "bitmask: sectors of the normal's half-circle per slice",
     OBSCURA_SETTING_OFFSET(gtao, sectors)),
    setting_row("falloff_range", OBSCURA_SETTING_FLOAT, 1.0, 0.01, 1.0, "",
     "fraction of the radius over which an occluder's weight fades to zero at the radius",
     OBSCURA_SETTING_OFFSET(gtao, falloff_range)),
    setting_row("step_power", OBSCURA_SETTING_FLOAT, 1.5, 1.0, 4.0, "",
     "steps at radius * ((j + jitter) / N)^power on screen: denser near the pixel", OBSCURA_SETTING_OFFSET(gtao, step_power)),
    setting_row("mip", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "steps read the z pyramid where they are far apart",
     OBSCURA_SETTING_OFFSET(gtao, mip)),
    setting_row("mip_offset", OBSCURA_SETTING_FLOAT, 3.3, 0.0, 8.0, "",
     "log2 of the step distance (px) at which a step reads one z-pyramid level down", OBSCURA_SETTING_OFFSET(gtao, mip_offset)),
    setting_row("intensity", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "obscurance multiplier", OBSCURA_SETTING_OFFSET(gtao, intensity)),
    setting_row("power", OBSCURA_SETTING_FLOAT, 0.0, 1e-3, 16.0, "",
     "exponent applied to the visibility, making up for the occluders that 3 steps per side miss; derived: 1.75 in "
     "horizon mode, 1.5 in bitmask mode, whose slabs already make up for part of them (docs/quality.md)",
     OBSCURA_SETTING_OFFSET(gtao, power), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("albedo", OBSCURA_SETTING_FLOAT, 0.0, 0.0, 0.95, "",
     "the paper's multi-bounce fit for this surface albedo; 0: none (plain visibility)", OBSCURA_SETTING_OFFSET(gtao, albedo)),
    setting_row("max_radius_pixels", OBSCURA_SETTING_FLOAT, 256.0, 1.0, 4096.0, "px",
     "cap of the radius on screen, bounding the step spacing of close-ups", OBSCURA_SETTING_OFFSET(gtao, max_radius_pixels)),
    setting_row("denoise", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "edge-aware separable 5x5 denoise over the 4x4 noise pattern",
     OBSCURA_SETTING_OFFSET(gtao, denoise)),
    setting_row("denoise_sharpness", OBSCURA_SETTING_FLOAT, 256.0, 1e-3, 1000.0, "",
     "how strongly the denoise stops at neighbours off the pixel's plane (per relative distance)",
     OBSCURA_SETTING_OFFSET(gtao, denoise_sharpness)),
    setting_row("frame_index", OBSCURA_SETTING_INT, 0, 0, 16777216, "",
     "moves the per-pixel noise; advance it each frame when accumulating frames", OBSCURA_SETTING_OFFSET(gtao, frame_index)),
};

Error derive_gtao(const obscura_settings&, obscura_settings* resolved) {
    obscura_gtao_settings& gtao = resolved->gtao;
    const GtaoPresetCounts counts = gtao_preset_counts(gtao.preset);
    if (gtao.slices == 0) gtao.slices = counts.slices;
    if (gtao.steps == 0) gtao.steps = counts.steps;
    if (gtao.power == 0.0f) gtao.power = gtao.thickness_mode == OBSCURA_GTAO_MODE_BITMASK ? 1.5f : 1.75f;
    return Error();
}

// The falloff GTAO weighs an occluder with: 1 up to radius * (1 - range), falling linearly to 0 at the radius (the
// horizon is faded towards the tangent plane by that weight; the bitmask occupies sectors with that probability).
// In bitmask mode the reference gets the same thickness.
void gtao_reference_falloff(const obscura_settings& resolved, obscura_reference_settings* reference) {
    const obscura_gtao_settings& gtao = resolved.gtao;
    reference->falloff = OBSCURA_FALLOFF_TABLE;
    reference->radius = gtao.radius;
    for (int i = 0; i < OBSCURA_FALLOFF_TABLE_SIZE; ++i) {
        const float d = float(i) / float(OBSCURA_FALLOFF_TABLE_SIZE - 1);  // in units of the radius
        const float weight = (1.0f - d) / gtao.falloff_range;
        reference->falloff_table[i] = weight < 0.0f ? 0.0f : (weight > 1.0f ? 1.0f : weight);
    }
    reference->thickness = gtao.thickness_mode == OBSCURA_GTAO_MODE_BITMASK ? gtao.thickness : 0.0f;
}

bool gtao_denoises(const obscura_gtao_settings& gtao, bool raw_view) {
    return !raw_view && gtao.denoise == OBSCURA_TOGGLE_ON;
}

constexpr bool kGtaoMethodWritesBentNormals = true;

// The pyramid's texels: means of the geometry below (sky left out) that are exact on planes at the block's centre,
// where gtao.comp reconstructs a step's sample. Under perspective 1/z is affine on screen, so the harmonic mean is;
// under an orthographic projection z itself is, so the plain mean is (the harmonic mean there left tilted planes up to
// 0.036 dark at mip_offset 0, and the image depended on where the eye sat along its axis: 0.0038 mean, 0.17 at most,
// found by a read-only review).
int gtao_pyramid_filter(const FrameInput& input) {
    return input.projection.perspective ? OBSCURA_MIP_FILTER_HARMONIC_MEAN_OF_GEOMETRY : OBSCURA_MIP_FILTER_MEAN_OF_GEOMETRY;
}

class GtaoTechnique final : public Technique {
public:
    TechniquePlan plan(const obscura_settings& settings, int width, int height,
                       const FrameRequest& request) const override {
        const obscura_gtao_settings& gtao = settings.gtao;
        TechniquePlan plan;
        plan.apron = gtao_denoises(gtao, request.raw_view) ? 2 : 0;
        plan.depth_levels = ZPyramidPass::level_count(width, height, GtaoPass::wanted_levels(gtao));
        plan.radius = gtao.radius;
        plan.bent_normals = kGtaoMethodWritesBentNormals;
        // With bent normals visibility and bent normal travel together in its own RGBA16F textures until the
        // denoise's final pass (record()); obscura_prepare, which knows no output, goes by the last render's request.
        const bool bent = request.output_known ? request.bent_normals : bent_requested_;
        plan.uses_ao = !bent;
        plan.uses_blur_temp = gtao_denoises(gtao, false) && !bent;
        plan.uses_ao_blurred = gtao_denoises(gtao, false);
        plan.writes_target = gtao_denoises(gtao, false);  // the denoise's final pass
        return plan;
    }

    Error prepare(const PassEnv& env, const obscura_settings& settings, const FrameRequest& request,
                  FrameResources& resources) override {
        // obscura_prepare (output unknown) allocates the bent-normal textures when the last render asked for them.
        if (request.output_known) bent_requested_ = request.bent_normals;
        const bool bent = request.output_known ? request.bent_normals : bent_requested_;
        // Both filters (the frame's projection picks one at record; a host may switch projections).
        Error error = pyramid_pass_.prepare(env, OBSCURA_MIP_FILTER_HARMONIC_MEAN_OF_GEOMETRY);
        if (!error) error = pyramid_pass_.prepare(env, OBSCURA_MIP_FILTER_MEAN_OF_GEOMETRY);
        if (!error) error = gtao_.prepare(env, settings.gtao, bent);
        if (!error) error = denoise_.prepare(env, bent, request.target);
        if (error) return error;
        if (!bent) {  // the shared R16F textures suffice
            release();
            return Error();
        }
        // Visibility and the bent normal travel together: the pass's output, and with the denoise (debug views aside,
        // as the plan) its x pass and the result; denoise=off frees those two.
        const bool denoises = gtao_denoises(settings.gtao, false);
        if (!env.fit_texture(&bent_raw_, true, GL_RGBA16F, resources.width, resources.height) ||
            !env.fit_texture(&bent_temp_, denoises, GL_RGBA16F, resources.width, resources.height) ||
            !env.fit_texture(&bent_, denoises, GL_RGBA16F, resources.width, resources.height)) {
            release();
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d GTAO bent-normal textures failed",
                               resources.width, resources.height);
        }
        return Error();
    }

    void write_constants(const Frame& frame, UniformWriter& uniforms) override {
        const obscura_gtao_settings& gtao = frame.settings.gtao;
        levels_ = frame.resources.linear_depth.levels();
        pyramid_dispatches_ = ZPyramidPass::dispatch_count(levels_);
        for (int d = 0; d < pyramid_dispatches_ && d < kMaxPyramidDispatches; ++d) {
            pyramid_[d] = uniforms.push(ZPyramidPass::constants(d, levels_));
        }
        pass_ = uniforms.push(GtaoPass::constants(gtao, frame.input, levels_ - 1));
        denoise_x_ = uniforms.push(GtaoDenoisePass::constants(gtao, false));
        denoise_y_ = uniforms.push(GtaoDenoisePass::constants(gtao, true));
    }

    Error record(const Frame& frame, PassRecorder& recorder, TechniqueOutput* out) override {
        FrameResources& r = frame.resources;
        const bool bent = frame.bent_normals;
        Error error;
        if (levels_ > 1) {
            pyramid_pass_.run(frame.env, gtao_pyramid_filter(frame.input), pyramid_, pyramid_dispatches_, r.linear_depth);
            error = recorder.end(PassId::ZPyramid);
            if (error) return error;
        }
        const gl::Texture2D& raw = bent ? bent_raw_ : r.ao;
        gtao_.run(frame.env, frame.settings.gtao, bent, frame.uniforms.ao, pass_, frame.regions.ao, r, raw);
        out->raw = out->result = &raw;
        out->bent = bent ? &bent_raw_ : nullptr;
        error = recorder.end(PassId::Gtao);
        if (error || !gtao_denoises(frame.settings.gtao, frame.raw_view)) return error;
        denoise_.run(frame.env, bent, false, frame.uniforms.blur_x, denoise_x_, frame.regions.blur_x, r, raw,
                     bent ? bent_temp_ : r.blur_temp, nullptr);
        out->result = &r.ao_blurred;
        out->bent = bent ? &bent_ : nullptr;
        if (frame.target.format != 0) {
            // The final pass runs as the output's write, its time under "gtao_denoise" with the first pass's.
            return target_write_.defer(frame, PassId::GtaoDenoise, out);
        }
        denoise_.run(frame.env, bent, true, frame.uniforms.output, denoise_y_, frame.regions.output, r,
                     bent ? bent_temp_ : r.blur_temp, r.ao_blurred, bent ? &bent_ : nullptr);
        return recorder.end(PassId::GtaoDenoise);
    }

    uint64_t memory_bytes() const override { return bent_raw_.bytes() + bent_temp_.bytes() + bent_.bytes(); }
    void release() override {
        bent_raw_ = gl::Texture2D();
        bent_temp_ = gl::Texture2D();
        bent_ = gl::Texture2D();
    }

    // The denoise's final pass into the host's target image (LastPassTargetWrite, during `frame`'s output write).
    void write_target(const PassEnv& env, const Frame& frame, GLuint texture) const {
        const bool bent = frame.bent_normals;
        denoise_.run_into_target(env, bent, frame.uniforms.output, denoise_y_, frame.regions.output, frame.resources,
                                 bent ? bent_temp_ : frame.resources.blur_temp, texture, bent ? &bent_ : nullptr);
    }

private:
    static constexpr int kMaxPyramidDispatches = 4;
    ZPyramidPass pyramid_pass_;
    GtaoPass gtao_;
    GtaoDenoisePass denoise_;
    // With bent normals only (RGBA16F: visibility, view-space bent normal): the pass's output, the denoise's x
    // pass and its result.
    gl::Texture2D bent_raw_, bent_temp_, bent_;
    int levels_ = 1, pyramid_dispatches_ = 0;
    bool bent_requested_ = false;  // the last render's output had a bent-normal texture
    UniformRange pyramid_[kMaxPyramidDispatches], pass_, denoise_x_, denoise_y_;
    LastPassTargetWrite<GtaoTechnique> target_write_{*this};
};

const PassId kGtaoPasses[] = {PassId::ZPyramid, PassId::Gtao, PassId::GtaoDenoise};

}  // namespace

extern const MethodDescriptor kGtaoMethod = {
    OBSCURA_METHOD_GTAO,
    "gtao",
    offsetof(obscura_settings, gtao),
    sizeof(obscura_gtao_settings),
    kGtaoSettings,
    uint32_t(sizeof kGtaoSettings / sizeof kGtaoSettings[0]),
    derive_gtao,
    gtao_reference_falloff,
    kGtaoPasses,
    uint32_t(sizeof kGtaoPasses / sizeof kGtaoPasses[0]),
    create_technique<GtaoTechnique>,
    kGtaoMethodWritesBentNormals,
};

}  // namespace obscura
