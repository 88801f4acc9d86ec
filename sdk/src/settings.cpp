#include "settings.h"

#include "common/shader_interface.h"
#include "host_enum.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

namespace obscura {
namespace {

#define OBSCURA_HBAO_FIELD(field) offsetof(obscura_settings, hbao) + offsetof(obscura_hbao_settings, field)

// HBAO (LSAO paper sec. 3 and 6; the falloff rho0 is its eq. 3). Defaults follow the paper (C = 0.3)
// and common HBAO practice (8 directions, 12 steps, 4-tap bilateral blur).
const obscura_setting_info kHbaoSettings[] = {
    {"radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m",
     "distance where the falloff reaches zero; the steps cover it", OBSCURA_HBAO_FIELD(radius)},
    {"falloff_c", OBSCURA_SETTING_FLOAT, 0.3, 1e-3, 0.999, "",
     "C of rho0(d) = max(0, r(1+C)/(r+d^2) - C): how far the falloff is sunk", OBSCURA_HBAO_FIELD(falloff_c)},
    {"decay_rate", OBSCURA_SETTING_FLOAT, 0.0, 1e-10, 1e8, "m^2",
     "r of rho0; 0 derives C*radius^2 so rho0 reaches zero at the radius", OBSCURA_HBAO_FIELD(decay_rate)},
    {"directions", OBSCURA_SETTING_INT, 8, 1, 32, "", "K azimuthal directions per pixel",
     OBSCURA_HBAO_FIELD(directions)},
    {"steps", OBSCURA_SETTING_INT, 12, 1, 128, "", "N ray-march steps per direction", OBSCURA_HBAO_FIELD(steps)},
    {"estimator", OBSCURA_SETTING_INT, 1, 1, 2, "",
     "1: horizon-split integration (Bavoil 2008); 2: largest falloff-weighted occluder (LSAO eq. 1)",
     OBSCURA_HBAO_FIELD(estimator)},
    {"bias", OBSCURA_SETTING_FLOAT, 0.0, 0.0, 0.5, "",
     "subtracted from sin(h) - sin(t) to hide tessellation; the default is zero", OBSCURA_HBAO_FIELD(bias)},
    {"intensity", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "obscurance multiplier", OBSCURA_HBAO_FIELD(intensity)},
    {"power", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "exponent applied to the visibility",
     OBSCURA_HBAO_FIELD(power)},
    {"max_radius_pixels", OBSCURA_SETTING_FLOAT, 256.0, 1.0, 4096.0, "px",
     "cap of the radius on screen, bounding the cost of close-ups", OBSCURA_HBAO_FIELD(max_radius_pixels)},
    {"blur", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "depth-aware bilateral blur of the AO", OBSCURA_HBAO_FIELD(blur)},
    {"blur_radius", OBSCURA_SETTING_INT, 4, 1, 16, "px", "blur taps on each side", OBSCURA_HBAO_FIELD(blur_radius)},
    {"blur_sharpness", OBSCURA_SETTING_FLOAT, 16.0, 1e-3, 1000.0, "",
     "how strongly the blur stops at depth edges (relative depth difference scale)",
     OBSCURA_HBAO_FIELD(blur_sharpness)},
};

#undef OBSCURA_HBAO_FIELD

#define OBSCURA_REFERENCE_FIELD(field) \
    offsetof(obscura_settings, reference) + offsetof(obscura_reference_settings, field)

// REFERENCE, the screen-space reference: FFAO paper eq. 1 by ray casting through the depth buffer (its sec. 8),
// the limit screen-space methods converge to, not the geometry truth (the samples' rays against the scene's
// triangles; the SDK only sees depth). The falloff defaults match HBAO's, so the default reference is the
// screen-space reference of the default HBAO.
const obscura_setting_info kReferenceSettings[] = {
    {"radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m",
     "where rho0 (with the default decay rate) and the falloff table reach zero", OBSCURA_REFERENCE_FIELD(radius)},
    {"falloff", OBSCURA_SETTING_INT, 1, 1, 4, "",
     "1: rho0 (LSAO eq. 3); 2: inverse quadratic r/(r+d^2) (LSAO eq. 2); 3: exponential exp(-d/sqrt(r)); 4: table",
     OBSCURA_REFERENCE_FIELD(falloff)},
    {"falloff_c", OBSCURA_SETTING_FLOAT, 0.3, 1e-3, 0.999, "", "C of rho0(d) = max(0, r(1+C)/(r+d^2) - C)",
     OBSCURA_REFERENCE_FIELD(falloff_c)},
    {"decay_rate", OBSCURA_SETTING_FLOAT, 0.0, 1e-10, 1e8, "m^2",
     "r of the falloff; 0 derives C*radius^2 (rho0 then reaches zero at the radius)",
     OBSCURA_REFERENCE_FIELD(decay_rate)},
    {"thickness", OBSCURA_SETTING_FLOAT, 0.0, 0.0, 1e4, "m",
     "solid assumed behind every depth texel; 0: infinitely thick (a continuous depth field: every ray behind a "
     "silhouette is blocked); 0.3 brought the atrium at 320x180 from 0.085 to 0.026 mean abs error against the "
     "geometry truth (rays against the scene's triangles)",
     OBSCURA_REFERENCE_FIELD(thickness)},
    {"rays", OBSCURA_SETTING_INT, 256, 1, 65536, "", "cosine-weighted rays per pixel", OBSCURA_REFERENCE_FIELD(rays)},
    {"rays_per_dispatch", OBSCURA_SETTING_INT, 16, 1, 1024, "",
     "rays per pixel in one compute dispatch (progressive accumulation keeps each dispatch short)",
     OBSCURA_REFERENCE_FIELD(rays_per_dispatch)},
    {"first_ray", OBSCURA_SETTING_INT, 0, 0, 16777216, "",
     "index of the first ray in the per-pixel sequence; average frames with 0, rays, 2*rays ... to accumulate",
     OBSCURA_REFERENCE_FIELD(first_ray)},
};

#undef OBSCURA_REFERENCE_FIELD

#define OBSCURA_SAO_FIELD(field) offsetof(obscura_settings, sao) + offsetof(obscura_sao_settings, field)

// SAO (McGuire et al. 2012). Defaults are the paper's: s = 9, tau = 7, q' = 2^3, rotated-grid MIPs, 7-tap
// blur with stride 3 and edge constant 2^11 over z packed across 200 m. The estimator constants follow
// AlchemyAO (sigma = k = 1); beta and epsilon were chosen against the screen-space reference (docs/quality.md).
const obscura_setting_info kSaoSettings[] = {
    {"radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m", "world-space radius r of the sample ball (eq. 5)",
     OBSCURA_SAO_FIELD(radius)},
    {"samples", OBSCURA_SETTING_INT, 9, 1, 64, "", "s spiral taps per pixel", OBSCURA_SAO_FIELD(samples)},
    {"turns", OBSCURA_SETTING_INT, 0, 1, 1024, "",
     "tau turns of the spiral; 0 derives the integer nearest 7s/9 sharing no factor with s (7 for s = 9)",
     OBSCURA_SAO_FIELD(turns)},
    {"mip", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "z-MIP hierarchy; off: every tap reads level 0 (quality baseline)",
     OBSCURA_SAO_FIELD(mip)},
    {"mip_filter", OBSCURA_SETTING_INT, 1, 1, 5, "",
     "MIP filter (Table 1): 1 rotated-grid subsample, 2 mean, 3 harmonic mean, 4 min, 5 max",
     OBSCURA_SAO_FIELD(mip_filter)},
    {"log_q", OBSCURA_SETTING_INT, 3, 1, 8, "", "log2 q': taps move one MIP level down per doubling past q' px",
     OBSCURA_SAO_FIELD(log_q)},
    {"intensity", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "sigma of the AlchemyAO estimator",
     OBSCURA_SAO_FIELD(intensity)},
    {"bias", OBSCURA_SETTING_FLOAT, 1e-3, 1e-6, 0.1, "", "beta: v.n must exceed beta * receiver distance",
     OBSCURA_SAO_FIELD(bias)},
    {"contrast", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "k: exponent of the visibility",
     OBSCURA_SAO_FIELD(contrast)},
    {"epsilon", OBSCURA_SETTING_FLOAT, 0.01, 1e-6, 1.0, "", "epsilon / r^2 in the estimator's denominator",
     OBSCURA_SAO_FIELD(epsilon)},
    {"max_radius_pixels", OBSCURA_SETTING_FLOAT, 256.0, 1.0, 4096.0, "px", "cap of the screen radius r'",
     OBSCURA_SAO_FIELD(max_radius_pixels)},
    {"quad_filter", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "2x2 bilateral step at the end of the AO pass",
     OBSCURA_SAO_FIELD(quad_filter)},
    {"blur", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "separable bilateral blur", OBSCURA_SAO_FIELD(blur)},
    {"blur_radius", OBSCURA_SETTING_INT, 3, 1, 8, "", "blur taps on each side (3: the paper's 7 taps)",
     OBSCURA_SAO_FIELD(blur_radius)},
    {"blur_stride", OBSCURA_SETTING_INT, 3, 1, 4, "px", "pixels between blur taps", OBSCURA_SAO_FIELD(blur_stride)},
    {"blur_sharpness", OBSCURA_SETTING_FLOAT, 2048.0, 1.0, 1e6, "",
     "edge weight max(0, 1 - sharpness |dz| / blur_depth_range)", OBSCURA_SAO_FIELD(blur_sharpness)},
    {"blur_depth_range", OBSCURA_SETTING_FLOAT, 200.0, 1e-2, 1e5, "m",
     "distance over which z is packed in 16 bits beside the AO (the paper's z_min)", OBSCURA_SAO_FIELD(blur_depth_range)},
};

#undef OBSCURA_SAO_FIELD

#define OBSCURA_LSAO_FIELD(field) offsetof(obscura_settings, lsao) + offsetof(obscura_lsao_settings, field)

// LSAO (Timonen 2013). Defaults are the paper's: falloff r/(r+d^2), the K = 16 configuration of Table 2,
// aligned sampling patterns, fixed tangent sin(t) = -0.85 for hull and occlusion (strategy 3).
const obscura_setting_info kLsaoSettings[] = {
    {"radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m", "falloff scale: the decay rate defaults to C*radius^2",
     OBSCURA_LSAO_FIELD(radius)},
    {"falloff", OBSCURA_SETTING_INT, 2, 1, 2, "", "1: rho0 (LSAO eq. 3, HBAO's); 2: r/(r+d^2) (LSAO eq. 2)",
     OBSCURA_LSAO_FIELD(falloff)},
    {"falloff_c", OBSCURA_SETTING_FLOAT, 0.3, 1e-3, 0.999, "", "C: rho0's sink and the decay-rate default",
     OBSCURA_LSAO_FIELD(falloff_c)},
    {"decay_rate", OBSCURA_SETTING_FLOAT, 0.0, 1e-10, 1e8, "m^2", "r of the falloff; 0 derives C*radius^2",
     OBSCURA_LSAO_FIELD(decay_rate)},
    {"preset", OBSCURA_SETTING_INT, 2, 1, 6, "",
     "K/D_S/D_L: 1 8/1.41/1.41, 2 16/2.43/1.64, 3 24/3.56/1.69, 4 32/4.69/1.70, 5 8/2.83/2.12, 6 16/4.87/2.46",
     OBSCURA_LSAO_FIELD(preset)},
    {"pattern", OBSCURA_SETTING_INT, 1, 1, 2, "", "1: aligned 8n directions on texel centres; 2: free (interpolated)",
     OBSCURA_LSAO_FIELD(pattern)},
    {"directions", OBSCURA_SETTING_INT, 0, 1, 64, "", "K; aligned patterns need a multiple of 8; 0: the preset's",
     OBSCURA_LSAO_FIELD(directions)},
    {"step_length", OBSCURA_SETTING_FLOAT, 0.0, 0.5, 16.0, "px", "D_S (free pattern); 0: the preset's",
     OBSCURA_LSAO_FIELD(step_length)},
    {"line_spacing", OBSCURA_SETTING_FLOAT, 0.0, 0.5, 16.0, "px", "D_L between parallel lines; 0: the preset's",
     OBSCURA_LSAO_FIELD(line_spacing)},
    {"tangent", OBSCURA_SETTING_FLOAT, -0.85, -1.0, 0.5, "", "the fixed sin(t) of the hull and the occlusion",
     OBSCURA_LSAO_FIELD(tangent)},
    {"tangent_strategy", OBSCURA_SETTING_INT, 3, 1, 3, "",
     "1: receiver's tangent for hull and occlusion; 2: fixed for the hull, receiver's for occlusion; 3: fixed",
     OBSCURA_LSAO_FIELD(tangent_strategy)},
    {"hull_capacity", OBSCURA_SETTING_INT, 24, 2, OBSCURA_LSAO_MAX_HULL, "",
     "points kept per line; the oldest is dropped when full", OBSCURA_LSAO_FIELD(hull_capacity)},
    {"exact", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "", "brute-force largest occluder instead of the hull (validation)",
     OBSCURA_LSAO_FIELD(exact)},
    {"segment_steps", OBSCURA_SETTING_INT, 0, -1, 4096, "",
     "steps per line segment (one GPU thread each, after a warm-up); -1: whole lines; 0: whole on CPU renderers, "
     "128 on GPUs", OBSCURA_LSAO_FIELD(segment_steps)},
    {"warmup_tolerance", OBSCURA_SETTING_FLOAT, 0.1, 1e-4, 1.0, "",
     "segments: most obscurance an occluder before the warm-up may cast (sets the warm-up length)",
     OBSCURA_LSAO_FIELD(warmup_tolerance)},
    {"warmup_stride", OBSCURA_SETTING_INT, 4, 1, 64, "",
     "segments: the warm-up before the last 16 steps samples every n-th step (far occluders need less detail)",
     OBSCURA_LSAO_FIELD(warmup_stride)},
    {"depth_threshold", OBSCURA_SETTING_FLOAT, 0.05, 1e-4, 10.0, "", "gather: relative depth difference that rejects",
     OBSCURA_LSAO_FIELD(depth_threshold)},
    {"normal_test", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "", "gather: also reject by normal", OBSCURA_LSAO_FIELD(normal_test)},
    {"normal_threshold", OBSCURA_SETTING_FLOAT, 0.8, -1.0, 1.0, "", "gather: minimum dot of the normals",
     OBSCURA_LSAO_FIELD(normal_threshold)},
    {"intensity", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "obscurance multiplier", OBSCURA_LSAO_FIELD(intensity)},
    {"power", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "exponent applied to the visibility", OBSCURA_LSAO_FIELD(power)},
};

#undef OBSCURA_LSAO_FIELD

#define OBSCURA_FFAO_FIELD(field) offsetof(obscura_settings, ffao) + offsetof(obscura_ffao_settings, field)

// FFAO (Timonen, HPG 2013). Defaults are the paper's: K = 16x2, B0 = 10, an exponential falloff. The falloff
// fields mirror the reference's, so obscura_reference_settings_for() gives the screen-space reference FFAO
// converges to (same falloff and thickness).
const obscura_setting_info kFfaoSettings[] = {
    {"radius", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 1e4, "m",
     "where rho0 (with the default decay rate) and the falloff table reach zero", OBSCURA_FFAO_FIELD(radius)},
    {"falloff", OBSCURA_SETTING_INT, 3, 1, 4, "",
     "1: rho0 (LSAO eq. 3); 2: inverse quadratic r/(r+d^2); 3: exponential exp(-d/sqrt(r)); 4: table",
     OBSCURA_FFAO_FIELD(falloff)},
    {"falloff_c", OBSCURA_SETTING_FLOAT, 0.3, 1e-3, 0.999, "", "C of rho0(d) = max(0, r(1+C)/(r+d^2) - C)",
     OBSCURA_FFAO_FIELD(falloff_c)},
    {"decay_rate", OBSCURA_SETTING_FLOAT, 0.0, 1e-10, 1e8, "m^2", "r of the falloff; 0 derives C*radius^2",
     OBSCURA_FFAO_FIELD(decay_rate)},
    {"sectors", OBSCURA_SETTING_INT, 16, 4, 64, "", "K azimuthal sectors (even: one line orientation serves two)",
     OBSCURA_FFAO_FIELD(sectors)},
    {"segments", OBSCURA_SETTING_INT, 2, 1, 4, "", "parts of a sector averaged and evaluated separately (K x this)",
     OBSCURA_FFAO_FIELD(segments)},
    {"base_interval", OBSCURA_SETTING_INT, 10, 2, 64, "px",
     "B0: scan steps per level-0 interval; the near field covers the first B0 to 2 B0 texels",
     OBSCURA_FFAO_FIELD(base_interval)},
    {"geometry", OBSCURA_SETTING_INT, 1, 1, 2, "",
     "far-field points: 1 scanned peaks (sec. 6-7); 2 depth MIP pyramid at distances x1.5 (sec. 5 baseline)",
     OBSCURA_FFAO_FIELD(geometry)},
    {"thickness", OBSCURA_SETTING_FLOAT, 0.0, 0.0, 1e4, "m",
     "solid behind every depth texel; 0: infinitely thick; > 0 reads single lines (no sector averages)",
     OBSCURA_FFAO_FIELD(thickness)},
    {"jitter", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "", "offset each sector's lines per pixel: banding becomes noise",
     OBSCURA_FFAO_FIELD(jitter)},
    {"saao", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "",
     "SAAO: each pixel of a 3x3 group evaluates 1/9 of the far field; a gather adds its accepted neighbours'",
     OBSCURA_FFAO_FIELD(saao)},
    {"saao_blur", OBSCURA_SETTING_TOGGLE, 1, 0, 1, "", "SAAO: 5x5 box blur over values within 7 % of the pixel's",
     OBSCURA_FFAO_FIELD(saao_blur)},
    {"intensity", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "obscurance multiplier", OBSCURA_FFAO_FIELD(intensity)},
    {"power", OBSCURA_SETTING_FLOAT, 1.0, 1e-3, 16.0, "", "exponent applied to the visibility",
     OBSCURA_FFAO_FIELD(power)},
};

#undef OBSCURA_FFAO_FIELD

struct LsaoPreset {
    int directions;
    double step_length, line_spacing;
};
// LSAO paper Table 2 (1-4) and Figures 1 and 13 (5, 6).
const LsaoPreset kLsaoPresets[] = {{8, 1.41, 1.41}, {16, 2.43, 1.64}, {24, 3.56, 1.69},
                                   {32, 4.69, 1.70}, {8, 2.83, 2.12}, {16, 4.87, 2.46}};

template <class T>
T* field_at(obscura_settings* settings, size_t offset) {
    return reinterpret_cast<T*>(reinterpret_cast<unsigned char*>(settings) + offset);
}
template <class T>
const T* field_at(const obscura_settings* settings, size_t offset) {
    return reinterpret_cast<const T*>(reinterpret_cast<const unsigned char*>(settings) + offset);
}

// The method field as the int the host stored (host_enum.h).
int32_t stored_method(const obscura_settings& settings) { return stored_enum(settings.method); }

obscura_method resolve_method_value(int32_t value) {
    if (value == OBSCURA_METHOD_DEFAULT) return OBSCURA_METHOD_HBAO;
    if (value < 0 || value >= int32_t(OBSCURA_METHOD_COUNT_)) return OBSCURA_METHOD_COUNT_;
    return obscura_method(value);
}

const obscura_setting_info* find_info(obscura_method method, const char* name) {
    uint32_t count = 0;
    const obscura_setting_info* infos = setting_infos(method, &count);
    for (uint32_t i = 0; i < count; ++i) {
        if (std::strcmp(infos[i].name, name) == 0) return &infos[i];
    }
    return nullptr;
}

// Stored value of a field as a double, with 0 meaning "default" (toggles: 0 default, 1 on, 2 off).
double stored_value(const obscura_settings& settings, const obscura_setting_info& info) {
    switch (info.type) {
        case OBSCURA_SETTING_FLOAT: return *field_at<float>(&settings, info.offset);
        case OBSCURA_SETTING_INT: return *field_at<int32_t>(&settings, info.offset);
        case OBSCURA_SETTING_TOGGLE: {
            int32_t toggle = *field_at<int32_t>(&settings, info.offset);
            return toggle == OBSCURA_TOGGLE_DEFAULT ? 0.0 : toggle == OBSCURA_TOGGLE_ON ? 1.0 : -1.0;
        }
    }
    return 0.0;
}

Error check_value(const obscura_setting_info& info, obscura_method method, double value) {
    if (!std::isfinite(value)) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s is %g; it must be finite", obscura_method_name(method),
                           info.name, value);
    }
    // Float settings live in floats: compare the value a float field holds (or will hold) with the range's edges
    // as floats hold them. Compared as doubles, the documented edges themselves were refused once stored:
    // float(1e-8) is below 1e-8 and float(0.999) above 0.999, so set_setting accepted them and resolve did not.
    // (A double beyond the float range stays as it is: converting it would be undefined, and it is out of range.)
    const bool as_float = info.type == OBSCURA_SETTING_FLOAT;
    const bool fits_float = std::fabs(value) <= double(std::numeric_limits<float>::max());
    const double stored = as_float && fits_float ? double(float(value)) : value;
    const double min_value = as_float ? double(float(info.min_value)) : info.min_value;
    const double max_value = as_float ? double(float(info.max_value)) : info.max_value;
    if (stored < min_value || stored > max_value) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s = %g is outside [%g, %g]%s%s",
                           obscura_method_name(method), info.name, value, info.min_value, info.max_value,
                           info.unit[0] ? " " : "", info.unit);
    }
    if (info.type != OBSCURA_SETTING_FLOAT && value != std::floor(value)) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s = %g must be a whole number",
                           obscura_method_name(method), info.name, value);
    }
    return Error();
}

void store_value(obscura_settings* settings, const obscura_setting_info& info, double value) {
    switch (info.type) {
        case OBSCURA_SETTING_FLOAT: *field_at<float>(settings, info.offset) = float(value); break;
        case OBSCURA_SETTING_INT: *field_at<int32_t>(settings, info.offset) = int32_t(std::lround(value)); break;
        case OBSCURA_SETTING_TOGGLE:
            *field_at<int32_t>(settings, info.offset) = value != 0.0 ? OBSCURA_TOGGLE_ON : OBSCURA_TOGGLE_OFF;
            break;
    }
}

// LSAO's derived values: the preset fills K, D_S and D_L, the decay rate follows the radius. An aligned
// pattern exists only for K = 8n.
Error resolve_lsao(obscura_lsao_settings* lsao) {
    const LsaoPreset& preset = kLsaoPresets[lsao->preset - 1];
    if (lsao->directions == 0) lsao->directions = preset.directions;
    if (lsao->step_length == 0.0f) lsao->step_length = float(preset.step_length);
    if (lsao->line_spacing == 0.0f) lsao->line_spacing = float(preset.line_spacing);
    if (lsao->decay_rate == 0.0f) lsao->decay_rate = lsao->falloff_c * lsao->radius * lsao->radius;
    // Segments start on the sweep's 8-value stores; 0 (auto) is settled by the context, which knows the renderer.
    if (lsao->segment_steps > 0) lsao->segment_steps = (lsao->segment_steps + 7) / 8 * 8;
    if (lsao->pattern == 1 && lsao->directions % 8 != 0) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "lsao.directions = %d: the aligned pattern has K = 8n directions (8, 16, 24 ... 64); "
                           "use pattern 2 (free) for other counts",
                           int(lsao->directions));
    }
    return Error();
}

// The falloff table is read only with OBSCURA_FALLOFF_TABLE, where it must describe a falloff.
Error check_falloff_table(const char* method, int32_t falloff, const float (&table)[OBSCURA_FALLOFF_TABLE_SIZE]) {
    if (falloff != OBSCURA_FALLOFF_TABLE) return Error();
    bool any_positive = false;
    for (int i = 0; i < OBSCURA_FALLOFF_TABLE_SIZE; ++i) {
        float value = table[i];
        if (!(value >= 0.0f && value <= 1.0f)) {
            return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.falloff_table[%d] = %g is outside [0, 1]", method, i,
                               double(value));
        }
        any_positive = any_positive || value > 0.0f;
    }
    if (!any_positive) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "%s.falloff is TABLE but %s.falloff_table is all zero: fill it with rho(d) at d = i/%d * "
                           "radius",
                           method, method, OBSCURA_FALLOFF_TABLE_SIZE - 1);
    }
    return Error();
}

// FFAO's derived values: the decay rate follows the radius; a line orientation serves two opposite sectors;
// SAAO spreads the orientations over 3x3 pixels (`sectors_given`: whether the host set K).
Error resolve_ffao(obscura_ffao_settings* ffao, bool sectors_given) {
    if (ffao->decay_rate == 0.0f) ffao->decay_rate = ffao->falloff_c * ffao->radius * ffao->radius;
    if (ffao->saao == OBSCURA_TOGGLE_ON) {
        if (!sectors_given) ffao->sectors = 18;
        if (ffao->sectors % 18 != 0) {
            return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                               "ffao.sectors = %d with saao: K must be a multiple of 18 (the 9 pixels of a 3x3 group "
                               "share the K/2 line orientations); the paper uses 18",
                               int(ffao->sectors));
        }
    }
    if (ffao->sectors % 2 != 0) {
        return Error::make(OBSCURA_STATUS_INVALID_SETTING,
                           "ffao.sectors = %d: K must be even (each scanned line orientation serves two opposite "
                           "sectors)",
                           int(ffao->sectors));
    }
    return check_falloff_table("ffao", ffao->falloff, ffao->falloff_table);
}

}  // namespace

int default_spiral_turns(int samples) {
    if (samples <= 2) return 1;
    auto coprime = [samples](int t) {
        int a = samples, b = t;
        while (b != 0) {
            int r = a % b;
            a = b;
            b = r;
        }
        return a == 1;
    };
    // Nearest to 7s/9 (the paper's ratio), the larger on a tie; 1 is coprime with everything.
    const double target = 7.0 * samples / 9.0;
    int best = 1;
    for (int t = 1; t < samples; ++t) {
        if (!coprime(t)) continue;
        if (std::fabs(t - target) <= std::fabs(best - target)) best = t;
    }
    return best;
}

obscura_method resolve_method(obscura_method method) { return resolve_method_value(int32_t(method)); }

const obscura_setting_info* setting_infos(obscura_method method, uint32_t* count) {
    switch (resolve_method(method)) {
        case OBSCURA_METHOD_HBAO:
            *count = uint32_t(sizeof kHbaoSettings / sizeof kHbaoSettings[0]);
            return kHbaoSettings;
        case OBSCURA_METHOD_REFERENCE:
            *count = uint32_t(sizeof kReferenceSettings / sizeof kReferenceSettings[0]);
            return kReferenceSettings;
        case OBSCURA_METHOD_SAO:
            *count = uint32_t(sizeof kSaoSettings / sizeof kSaoSettings[0]);
            return kSaoSettings;
        case OBSCURA_METHOD_LSAO:
            *count = uint32_t(sizeof kLsaoSettings / sizeof kLsaoSettings[0]);
            return kLsaoSettings;
        case OBSCURA_METHOD_FFAO:
            *count = uint32_t(sizeof kFfaoSettings / sizeof kFfaoSettings[0]);
            return kFfaoSettings;
        default:
            *count = 0;
            return nullptr;
    }
}

bool is_known_settings_size(uint32_t struct_size) { return struct_size == sizeof(obscura_settings); }

Error resolve_settings(const obscura_settings& in, obscura_settings* out) {
    if (!is_known_settings_size(in.struct_size)) {
        return Error::make(OBSCURA_STATUS_INVALID_STRUCT_SIZE, "obscura_settings.struct_size is %u; expected %u",
                           in.struct_size, unsigned(sizeof(obscura_settings)));
    }
    obscura_method method = resolve_method_value(stored_method(in));
    if (method == OBSCURA_METHOD_COUNT_) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "obscura_settings.method = %d is not an obscura_method",
                           int(stored_method(in)));
    }
    obscura_settings resolved = in;
    resolved.method = method;
    // Every method's table is defaulted and validated, so a later method switch cannot surprise.
    for (int m = OBSCURA_METHOD_HBAO; m < OBSCURA_METHOD_COUNT_; ++m) {
        uint32_t count = 0;
        const obscura_setting_info* infos = setting_infos(obscura_method(m), &count);
        for (uint32_t i = 0; i < count; ++i) {
            const obscura_setting_info& info = infos[i];
            if (info.type == OBSCURA_SETTING_TOGGLE) {
                int32_t toggle = *field_at<int32_t>(&resolved, info.offset);
                if (toggle < OBSCURA_TOGGLE_DEFAULT || toggle > OBSCURA_TOGGLE_OFF) {
                    return Error::make(OBSCURA_STATUS_INVALID_ENUM, "%s.%s = %d is not an obscura_toggle",
                                       obscura_method_name(obscura_method(m)), info.name, toggle);
                }
                if (toggle == OBSCURA_TOGGLE_DEFAULT) {
                    *field_at<int32_t>(&resolved, info.offset) =
                        info.default_value != 0.0 ? OBSCURA_TOGGLE_ON : OBSCURA_TOGGLE_OFF;
                }
                continue;
            }
            double value = stored_value(resolved, info);
            if (value == 0.0) {
                store_value(&resolved, info, info.default_value);
                continue;
            }
            Error error = check_value(info, obscura_method(m), value);
            if (error) return error;
        }
    }
    // HBAO: the decay rate defaults to C * radius^2, where rho0 reaches zero exactly at the radius.
    obscura_hbao_settings& hbao = resolved.hbao;
    if (hbao.decay_rate == 0.0f) hbao.decay_rate = hbao.falloff_c * hbao.radius * hbao.radius;
    obscura_reference_settings& reference = resolved.reference;
    if (reference.decay_rate == 0.0f) reference.decay_rate = reference.falloff_c * reference.radius * reference.radius;
    obscura_sao_settings& sao = resolved.sao;
    if (sao.turns == 0) sao.turns = default_spiral_turns(sao.samples);
    Error error = resolve_lsao(&resolved.lsao);
    if (error) return error;
    error = check_falloff_table("reference", reference.falloff, reference.falloff_table);
    if (!error) error = resolve_ffao(&resolved.ffao, in.ffao.sectors != 0);
    if (error) return error;
    *out = resolved;
    return Error();
}

Error reference_settings_for(const obscura_settings& method_settings, obscura_settings* out) {
    obscura_settings resolved;
    Error error = resolve_settings(method_settings, &resolved);
    if (error) return error;
    if (resolved.method == OBSCURA_METHOD_REFERENCE) {
        *out = resolved;
        return Error();
    }
    obscura_settings reference;
    std::memset(&reference, 0, sizeof reference);
    reference.struct_size = sizeof reference;
    reference.method = OBSCURA_METHOD_REFERENCE;
    switch (resolved.method) {
        case OBSCURA_METHOD_HBAO:
            reference.reference.falloff = OBSCURA_FALLOFF_RHO0;
            reference.reference.radius = resolved.hbao.radius;
            reference.reference.falloff_c = resolved.hbao.falloff_c;
            reference.reference.decay_rate = resolved.hbao.decay_rate;
            break;
        case OBSCURA_METHOD_LSAO:
            reference.reference.falloff =
                resolved.lsao.falloff == 1 ? OBSCURA_FALLOFF_RHO0 : OBSCURA_FALLOFF_INVERSE_QUADRATIC;
            reference.reference.radius = resolved.lsao.radius;
            reference.reference.falloff_c = resolved.lsao.falloff_c;
            reference.reference.decay_rate = resolved.lsao.decay_rate;
            break;
        case OBSCURA_METHOD_FFAO:
            reference.reference.falloff = resolved.ffao.falloff;
            reference.reference.radius = resolved.ffao.radius;
            reference.reference.falloff_c = resolved.ffao.falloff_c;
            reference.reference.decay_rate = resolved.ffao.decay_rate;
            reference.reference.thickness = resolved.ffao.thickness;
            std::memcpy(reference.reference.falloff_table, resolved.ffao.falloff_table,
                        sizeof reference.reference.falloff_table);
            break;
        case OBSCURA_METHOD_SAO:
            // The AlchemyAO estimator counts every occluder inside the ball of radius r at full weight: a step
            // falloff (1 up to r, 0 beyond).
            reference.reference.falloff = OBSCURA_FALLOFF_TABLE;
            reference.reference.radius = resolved.sao.radius;
            for (float& value : reference.reference.falloff_table) value = 1.0f;
            break;
        default:
            // Methods without a falloff of their own yet are compared with the default reference.
            break;
    }
    return resolve_settings(reference, out);
}

Error get_setting(const obscura_settings& settings, const char* name, double* value) {
    obscura_method method = resolve_method_value(stored_method(settings));
    if (method == OBSCURA_METHOD_COUNT_) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "settings.method = %d is not an obscura_method",
                           int(stored_method(settings)));
    }
    const obscura_setting_info* info = find_info(method, name);
    if (!info) {
        return Error::make(OBSCURA_STATUS_UNKNOWN_SETTING, "%s has no setting named '%s'", obscura_method_name(method),
                           name);
    }
    double stored = stored_value(settings, *info);
    if (info->type == OBSCURA_SETTING_TOGGLE) {
        *value = stored == 0.0 ? info->default_value : (stored > 0.0 ? 1.0 : 0.0);
    } else {
        // Reported as it will be used: derived defaults for zero fields, and what resolve makes of a set
        // value (LSAO rounds segment_steps up to a multiple of 8). Settings that do not resolve read as stored.
        obscura_settings resolved;
        if (resolve_settings(settings, &resolved).ok()) stored = stored_value(resolved, *info);
        *value = stored != 0.0 ? stored : info->default_value;
    }
    return Error();
}

Error set_setting(obscura_settings* settings, const char* name, double value) {
    obscura_method method = resolve_method_value(stored_method(*settings));
    if (method == OBSCURA_METHOD_COUNT_) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "settings.method = %d is not an obscura_method",
                           int(stored_method(*settings)));
    }
    const obscura_setting_info* info = find_info(method, name);
    if (!info) {
        return Error::make(OBSCURA_STATUS_UNKNOWN_SETTING, "%s has no setting named '%s'", obscura_method_name(method),
                           name);
    }
    if (info->type == OBSCURA_SETTING_TOGGLE) {
        if (value != 0.0 && value != 1.0) {
            return Error::make(OBSCURA_STATUS_INVALID_SETTING, "%s.%s is a toggle: 0 (off) or 1 (on), not %g",
                               obscura_method_name(method), info->name, value);
        }
    } else if (!(value == 0.0 && info->min_value > 0.0)) {
        // 0 always means "default" for fields whose range excludes it.
        Error error = check_value(*info, method, value);
        if (error) return error;
    }
    store_value(settings, *info, value);
    return Error();
}

}  // namespace obscura
