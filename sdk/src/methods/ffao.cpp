// FFAO (Timonen, HPG 2013): its settings metadata, its derived values, the falloff it is compared with, its
// technique (the estimator table when the falloff's shape changed, the scan and prefix sums or the mipmap
// baseline's z pyramid, the obscurance, and with SAAO the box average, the gather and the blur) and its
// registry row.
#include <algorithm>
#include <cstring>

#include "falloff.h"
#include "method_registry.h"
#include "passes/ffao.h"
#include "passes/z_pyramid.h"
#include "settings.h"
#include "technique.h"

namespace obscura {
namespace {

constexpr const char* const kFfaoGeometryNames[] = {"peaks", "mipmap"};

// FFAO (Timonen, HPG 2013). Defaults are the paper's: K = 16x2, B0 = 10, an exponential falloff; and 0.4 m of thickness
// (sec. 11; 0, infinitely thick, until 2026-12-06): once a finite thickness interpolated planar quads, it took the
// mean error against the geometry truth over the seven built-in scenes at 320x180 from 0.0294 to 0.0150 (better on 6
// of 7, terrain +0.0015) and on 4 of 5 held-out views (docs/parameters.md), at 0.93x the cost. The falloff
// fields mirror the reference's, so obscura_reference_settings_for() gives the screen-space reference FFAO
// converges to (same falloff and thickness).
const obscura_setting_info kFfaoSettings[] = {
    setting_row("radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m",
     "where rho0 (with the default decay rate) and the falloff table reach zero", OBSCURA_SETTING_OFFSET(ffao, radius)),
    enum_row("falloff", 3, 1,
             "rho0 (LSAO eq. 3), inverse_quadratic r/(r+d^2), exponential exp(-d/sqrt(r)) (the paper's), or table "
             "(falloff_table)",
             OBSCURA_SETTING_OFFSET(ffao, falloff), kFalloffNames),
    setting_row("falloff_c", OBSCURA_SETTING_FLOAT, 0.3, 1e-3, 0.999, "", "C of rho0(d) = max(0, r(1+C)/(r+d^2) - C)",
     OBSCURA_SETTING_OFFSET(ffao, falloff_c)),
    setting_row("decay_rate", OBSCURA_SETTING_FLOAT, 0.0, 1e-10, 1e8, "m^2", "r of the falloff; derived: C*radius^2",
     OBSCURA_SETTING_OFFSET(ffao, decay_rate), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("sectors", OBSCURA_SETTING_INT, 0, 4, 64, "",
     "K azimuthal sectors (even: one line orientation serves two); derived: 16, or 18 with saao",
     OBSCURA_SETTING_OFFSET(ffao, sectors), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("segments", OBSCURA_SETTING_INT, 2, 1, 4, "", "parts of a sector averaged and evaluated separately (K x this)",
     OBSCURA_SETTING_OFFSET(ffao, segments)),
    setting_row("base_interval", OBSCURA_SETTING_INT, 10, 2, 64, "px",
     "B0: scan steps per level-0 interval; the near field covers the first B0 to 2 B0 texels",
     OBSCURA_SETTING_OFFSET(ffao, base_interval)),
    enum_row("geometry", 1, 1,
             "far-field points: peaks: the scanned peaks (sec. 6-7); mipmap: a depth MIP pyramid at distances x1.5 "
             "(sec. 5 baseline)",
             OBSCURA_SETTING_OFFSET(ffao, geometry), kFfaoGeometryNames),
    setting_row("thickness", OBSCURA_SETTING_FLOAT, 0.4, 0.0, 1e4, "m",
     "solid behind every depth texel; 0: infinitely thick; > 0 reads single lines (no sector averages)",
     OBSCURA_SETTING_OFFSET(ffao, thickness)),
    setting_row("jitter", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "", "offset each sector's lines per pixel: banding becomes noise",
     OBSCURA_SETTING_OFFSET(ffao, jitter)),
    setting_row("saao", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "",
     "SAAO: each pixel of a 3x3 group evaluates 1/9 of the far field; a gather adds its accepted neighbours'",
     OBSCURA_SETTING_OFFSET(ffao, saao)),
    setting_row("saao_blur", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "SAAO: 5x5 box blur over values within 7 % of the pixel's",
     OBSCURA_SETTING_OFFSET(ffao, saao_blur)),
    setting_row("intensity", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "obscurance multiplier", OBSCURA_SETTING_OFFSET(ffao, intensity)),
    setting_row("power", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "exponent applied to the visibility",
     OBSCURA_SETTING_OFFSET(ffao, power)),
    array_row("falloff_table", OBSCURA_FALLOFF_TABLE_SIZE, 0.0, 1.0,
              "falloff = table: rho at i/15 * radius (i = 0..15), linear in between, 0 beyond; not all 0",
              OBSCURA_SETTING_OFFSET(ffao, falloff_table)),
    added_row(setting_row("frame_split", OBSCURA_SETTING_INT, 1, 1, 4, "frames",
                          "spread the orientations over N frames (a 2x2 pixel pattern turning with frame_index), for "
                          "temporal accumulation: about 1/N of the obscurance's cost a frame; at most K/2, not with saao",
                          OBSCURA_SETTING_OFFSET(ffao_added, frame_split)),
              500),
};

// FFAO's derived values: the decay rate follows the radius; a line orientation serves two opposite sectors;
// SAAO spreads the orientations over 3x3 pixels (K derived: the paper's 18).
Error derive_ffao(const obscura_settings&, obscura_settings* resolved) {
    obscura_ffao_settings* ffao = &resolved->ffao;
    if (ffao->decay_rate == 0.0f) ffao->decay_rate = derived_decay_rate(ffao->falloff_c, ffao->radius);
    if (ffao->saao == OBSCURA_TOGGLE_ON) {
        if (ffao->sectors == 0) ffao->sectors = 18;
        if (ffao->sectors % 18 != 0) {
            return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                               "ffao.sectors = %d with saao: K must be a multiple of 18 (the 9 pixels of a 3x3 group "
                               "share the K/2 line orientations); the paper uses 18",
                               int(ffao->sectors));
        }
    }
    if (ffao->sectors == 0) ffao->sectors = 16;
    if (ffao->sectors % 2 != 0) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "ffao.sectors = %d: K must be even (each scanned line orientation serves two opposite "
                           "sectors)",
                           int(ffao->sectors));
    }
    const int32_t split = resolved->ffao_added.frame_split;
    if (split > 1 && ffao->saao == OBSCURA_TOGGLE_ON) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "ffao_added.frame_split = %d with saao: SAAO already spreads the far field over 3x3 pixels; use "
                           "one or the other",
                           int(split));
    }
    if (split > ffao->sectors / 2) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "ffao_added.frame_split = %d with K = %d sectors: a frame would have no orientation to evaluate "
                           "(at most K/2 = %d)",
                           int(split), int(ffao->sectors), int(ffao->sectors / 2));
    }
    return check_falloff_table("ffao", ffao->falloff, ffao->falloff_table);
}

void ffao_reference_falloff(const obscura_settings& resolved, obscura_reference_settings* reference) {
    reference->falloff = resolved.ffao.falloff;
    reference->radius = resolved.ffao.radius;
    reference->falloff_c = resolved.ffao.falloff_c;
    reference->decay_rate = resolved.ffao.decay_rate;
    reference->thickness = resolved.ffao.thickness;
    std::memcpy(reference->falloff_table, resolved.ffao.falloff_table, sizeof reference->falloff_table);
}

bool ffao_blurs(const obscura_ffao_settings& ffao, bool raw_view) {
    return ffao_uses_saao(ffao) && !raw_view && ffao.saao_blur == OBSCURA_TOGGLE_ON;
}

class FfaoTechnique final : public Technique {
public:
    TechniquePlan plan(const obscura_settings& settings, int width, int height,
                       const FrameRequest& request) const override {
        const obscura_ffao_settings& ffao = settings.ffao;
        TechniquePlan plan;
        plan.apron = ffao_blurs(ffao, request.raw_view) ? 2 : 0;  // the 5x5 box
        if (ffao_uses_mipmap(ffao)) plan.depth_levels = ZPyramidPass::level_count(width, height, kFfaoMipmapLevels);
        plan.radius = ffao.radius;
        plan.uses_ao_blurred = ffao_blurs(ffao, false);
        // SAAO's box average reads the 3x3 around a region one pixel wider than the AO's (write_constants).
        plan.normals_margin = 2;
        return plan;
    }

    Error prepare(const PassEnv& env, const obscura_settings& settings, const FrameRequest& request,
                  FrameResources& resources) override {
        Error error = ffao_.prepare(env, settings.ffao);
        if (!error && ffao_uses_mipmap(settings.ffao)) {
            error = pyramid_pass_.prepare(env, ffao_mipmap_filter(settings.ffao));
        }
        // The obscurance covers the AO region (SAAO's a pixel more, but its running sums are its whole-size terms).
        // With the orientations split over N frames the layout phase moves every N frames: the N shares of a window
        // see the same lines, so the window's mean is the image of every orientation at that phase (a phase moving
        // every frame would pair each share with the same two of the eight phases, pixel by pixel).
        if (!error) {
            const uint32_t split = uint32_t(std::max(settings.ffao_added.frame_split, 1));
            error = ffao_.ensure_layout(env, settings.ffao, resources.width, resources.height,
                                        request.frame_index / split, request.ao_region);
        }
        return error;
    }

    void write_constants(const Frame& frame, UniformWriter& uniforms) override {
        const obscura_ffao_settings& ffao = frame.settings.ffao;
        // SAAO's gather reads the 3x3 neighbours of its region: the box average and the obscurance cover one
        // pixel more.
        saao_region_ = frame.regions.ao.expanded(1, 1, frame.input.width, frame.input.height);
        if (ffao_uses_saao(ffao)) saao_frame_ = uniforms.frame_constants(saao_region_);
        levels_ = ffao_uses_mipmap(ffao) ? frame.resources.linear_depth.levels() : 1;
        pyramid_dispatches_ = ZPyramidPass::dispatch_count(levels_);
        for (int d = 0; d < pyramid_dispatches_ && d < kMaxPyramidDispatches; ++d) {
            pyramid_[d] = uniforms.push(ZPyramidPass::constants(d, levels_));
        }
        pass_ = uniforms.push(ffao_.constants(ffao, frame.input, levels_, frame.settings.ffao_added.frame_split));
        ffao_.push_chunk_constants(uniforms);
        table_ = uniforms.push(FfaoPass::table_constants(ffao));
    }

    Error record(const Frame& frame, PassRecorder& recorder, TechniqueOutput* out) override {
        const PassEnv& env = frame.env;
        const obscura_ffao_settings& ffao = frame.settings.ffao;
        FrameResources& r = frame.resources;
        const bool mipmap = ffao_uses_mipmap(ffao), saao = ffao_uses_saao(ffao);
        out->raw = out->result = &r.ao;
        Error error;
        if (ffao_.table_stale(ffao)) {
            ffao_.run_table(env, ffao, table_);
            if ((error = recorder.end(PassId::FfaoTable))) return error;
        }
        if (mipmap && levels_ > 1) {
            pyramid_pass_.run(env, ffao_mipmap_filter(ffao), pyramid_, pyramid_dispatches_, r.linear_depth);
            if ((error = recorder.end(PassId::ZPyramid))) return error;
        }
        if (saao) {
            ffao_.run_box_average(env, saao_frame_, pass_, saao_region_, r);
            if ((error = recorder.end(PassId::FfaoBoxAverage))) return error;
        }
        // Chunk by chunk (one chunk unless the peaks outgrow a storage block): the scan and the prefix sums fill the
        // peaks buffer with the chunk's orientations, the obscurance adds their share.
        for (int c = 0; c < ffao_.chunk_count(); ++c) {
            if (!mipmap) {
                ffao_.run_scan(env, frame.uniforms.whole, pass_, r, c);
                if ((error = recorder.end(PassId::FfaoScan))) return error;
            }
            if (!mipmap && !ffao_single_lines(ffao)) {
                ffao_.run_prefix(env, frame.uniforms.whole, pass_, c);
                if ((error = recorder.end(PassId::FfaoPrefix))) return error;
            }
            ffao_.run_obscurance(env, ffao, saao ? saao_frame_ : frame.uniforms.ao, pass_,
                                 saao ? saao_region_ : frame.regions.ao, r, c);
            if ((error = recorder.end(PassId::FfaoObscurance))) return error;
            if (ffao_.chunked()) recorder.flush();
        }
        if (saao) {
            ffao_.run_gather(env, frame.uniforms.ao, pass_, frame.regions.ao, r);
            if ((error = recorder.end(PassId::FfaoGather))) return error;
        }
        if (!ffao_blurs(ffao, frame.raw_view)) return error;
        ffao_.run_saao_blur(env, frame.uniforms.output, pass_, frame.regions.output, r);
        out->result = &r.ao_blurred;
        return recorder.end(PassId::Blur);
    }

    uint64_t memory_bytes() const override { return ffao_.bytes(); }
    void release() override {
        ffao_.release();
        ffao_.release_table();
    }
    // A resize keeps the estimator table: it depends on the falloff's shape alone (rebuilding it cost a 3D texture
    // allocation and the ffao_table pass on every frame of a host resizing its window).
    void release_sized() override { ffao_.release(); }

private:
    static constexpr int kMaxPyramidDispatches = 4;
    FfaoPass ffao_;
    ZPyramidPass pyramid_pass_;  // the mipmap baseline's depth pyramid
    Region saao_region_;
    int levels_ = 1, pyramid_dispatches_ = 0;
    UniformRange saao_frame_, pyramid_[kMaxPyramidDispatches], pass_, table_;
};

const PassId kFfaoPasses[] = {PassId::FfaoTable,      PassId::ZPyramid,       PassId::FfaoBoxAverage,
                              PassId::FfaoScan,       PassId::FfaoPrefix,     PassId::FfaoObscurance,
                              PassId::FfaoGather,     PassId::Blur};

}  // namespace

extern const MethodDescriptor kFfaoMethod = {
    OBSCURA_METHOD_FFAO,
    "ffao",
    offsetof(obscura_settings, ffao),
    sizeof(obscura_ffao_settings),
    kFfaoSettings,
    uint32_t(sizeof kFfaoSettings / sizeof kFfaoSettings[0]),
    derive_ffao,
    ffao_reference_falloff,
    kFfaoPasses,
    uint32_t(sizeof kFfaoPasses / sizeof kFfaoPasses[0]),
    create_technique<FfaoTechnique>,
    false,
    nullptr,
    offsetof(obscura_settings, ffao_added),
    sizeof(obscura_ffao_added_settings),
};

}  // namespace obscura
