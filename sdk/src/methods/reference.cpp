// The screen-space reference (FFAO paper eq. 1 by rays through the depth buffer, its sec. 8): its settings
// metadata, its derived values, its technique (ray batches accumulated in an R32F texture) and its registry row.
// Its settings are the reference other methods are compared with (obscura_reference_settings_for).
#include "falloff.h"
#include "method_registry.h"
#include "passes/reference.h"
#include "settings.h"
#include "technique.h"

namespace obscura {
namespace {

// REFERENCE, the screen-space reference: FFAO paper eq. 1 by ray casting through the depth buffer (its sec. 8),
// the limit screen-space methods converge to, not the geometry truth (the samples' rays against the scene's
// triangles; the SDK only sees depth). The falloff defaults match HBAO's, so the default reference is the
// screen-space reference of the default HBAO.
const obscura_setting_info kReferenceSettings[] = {
    setting_row("radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m",
     "where rho0 (with the default decay rate) and the falloff table reach zero", OBSCURA_SETTING_OFFSET(reference, radius)),
    enum_row("falloff", 1, 1,
             "rho0 (LSAO eq. 3), inverse_quadratic r/(r+d^2) (LSAO eq. 2), exponential exp(-d/sqrt(r)), or table "
             "(falloff_table)",
             OBSCURA_SETTING_OFFSET(reference, falloff), kFalloffNames),
    setting_row("falloff_c", OBSCURA_SETTING_FLOAT, 0.3, 1e-3, 0.999, "", "C of rho0(d) = max(0, r(1+C)/(r+d^2) - C)",
     OBSCURA_SETTING_OFFSET(reference, falloff_c)),
    setting_row("decay_rate", OBSCURA_SETTING_FLOAT, 0.0, 1e-10, 1e8, "m^2",
     "r of the falloff; derived: C*radius^2 (rho0 then reaches zero at the radius)",
     OBSCURA_SETTING_OFFSET(reference, decay_rate), OBSCURA_SETTING_FLAG_DERIVED),
    setting_row("thickness", OBSCURA_SETTING_FLOAT, 0.0, 0.0, 1e4, "m",
     "solid assumed behind every depth texel; 0: infinitely thick (a continuous depth field: every ray behind a "
     "silhouette is blocked); 0.3 brought the atrium at 320x180 from 0.086 to 0.034 mean abs error against the "
     "geometry truth (rays against the scene's triangles)",
     OBSCURA_SETTING_OFFSET(reference, thickness)),
    setting_row("rays", OBSCURA_SETTING_INT, 256, 1, 65536, "", "cosine-weighted rays per pixel", OBSCURA_SETTING_OFFSET(reference, rays)),
    setting_row("rays_per_dispatch", OBSCURA_SETTING_INT, 16, 1, 1024, "",
     "rays per pixel in one compute dispatch (progressive accumulation keeps each dispatch short)",
     OBSCURA_SETTING_OFFSET(reference, rays_per_dispatch)),
    setting_row("first_ray", OBSCURA_SETTING_INT, 0, 0, 16777216, "",
     "index of the first ray in the per-pixel sequence; average frames with 0, rays, 2*rays ... to accumulate",
     OBSCURA_SETTING_OFFSET(reference, first_ray)),
    array_row("falloff_table", OBSCURA_FALLOFF_TABLE_SIZE, 0.0, 1.0,
              "falloff = table: rho at i/15 * radius (i = 0..15), linear in between, 0 beyond; not all 0",
              OBSCURA_SETTING_OFFSET(reference, falloff_table)),
};

Error derive_reference(const obscura_settings&, obscura_settings* resolved) {
    obscura_reference_settings& reference = resolved->reference;
    if (reference.decay_rate == 0.0f) reference.decay_rate = derived_decay_rate(reference.falloff_c, reference.radius);
    return check_falloff_table("reference", reference.falloff, reference.falloff_table);
}

class ReferenceTechnique final : public Technique {
public:
    TechniquePlan plan(const obscura_settings& settings, int, int, const FrameRequest&) const override {
        TechniquePlan plan;
        plan.radius = settings.reference.radius;
        plan.uses_ao = false;  // its rays accumulate in its own R32F texture, which is also its result
        return plan;
    }

    Error prepare(const PassEnv& env, const obscura_settings&, const FrameRequest&,
                  FrameResources& resources) override {
        Error error = pass_.prepare(env);
        if (error || (accumulator_.width() == resources.width && accumulator_.height() == resources.height)) {
            return error;
        }
        accumulator_ = env.create_texture(GL_R32F, resources.width, resources.height);
        if (!accumulator_) {
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d reference accumulator failed",
                               resources.width, resources.height);
        }
        return Error();
    }

    void write_constants(const Frame& frame, UniformWriter& uniforms) override {
        pass_constants_ = uniforms.push(ReferencePass::constants(frame.settings.reference, frame.input));
    }

    Error record(const Frame& frame, PassRecorder& recorder, TechniqueOutput* out) override {
        // Each batch's tiles (ReferencePass::kTile) are flushed so the GPU starts on them while the next are recorded,
        // and no single submission runs long (watchdogs, a responsive desktop).
        pass_.run(frame.env, frame.uniforms.ao, pass_constants_, frame.regions.ao, frame.settings.reference,
                  frame.input.frame_index, frame.resources, accumulator_, [&] { recorder.flush(); });
        out->raw = out->result = &accumulator_;
        return recorder.end(PassId::Reference);
    }

    uint64_t memory_bytes() const override { return accumulator_.bytes(); }
    void release() override { accumulator_ = gl::Texture2D(); }

private:
    ReferencePass pass_;
    gl::Texture2D accumulator_;  // R32F falloff sums, then visibility
    UniformRange pass_constants_;
};

const PassId kReferencePasses[] = {PassId::Reference};

}  // namespace

extern const MethodDescriptor kReferenceMethod = {
    OBSCURA_METHOD_REFERENCE,
    "reference",
    offsetof(obscura_settings, reference),
    sizeof(obscura_reference_settings),
    kReferenceSettings,
    uint32_t(sizeof kReferenceSettings / sizeof kReferenceSettings[0]),
    derive_reference,
    nullptr,  // its settings are the reference
    kReferencePasses,
    uint32_t(sizeof kReferencePasses / sizeof kReferencePasses[0]),
    create_technique<ReferenceTechnique>,
};

}  // namespace obscura
