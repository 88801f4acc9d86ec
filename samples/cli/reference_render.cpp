#include "reference_render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "ao_render.h"
#include "cli_errors.h"
#include "obscura_session.h"

namespace obscura::cli {
namespace {

const char* falloff_name(int32_t falloff) {
    switch (falloff) {
    case OBSCURA_FALLOFF_RHO0: return "rho0";
    case OBSCURA_FALLOFF_INVERSE_QUADRATIC: return "inverse-quadratic";
    case OBSCURA_FALLOFF_EXPONENTIAL: return "exponential";
    case OBSCURA_FALLOFF_TABLE: return "table";
    default: return "falloff?";
    }
}

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

}  // namespace

obscura_settings reference_settings_for(const obscura_settings& method_settings, int rays) {
    obscura_settings reference{};
    const obscura_status status = obscura_reference_settings_for(&method_settings, &reference);
    if (status != OBSCURA_OK) throw ApiError(api_error_message(status, "obscura_reference_settings_for", nullptr));
    reference.reference.rays = rays;
    reference.reference.first_ray = kReferenceTruthFirstRay;
    // How the rays are batched into dispatches is scheduling, not the picture: one reference serves
    // reference:rays_per_dispatch=4 and =64 alike (the default batch size traces it).
    reference.reference.rays_per_dispatch = 0;
    return reference;
}

bool same_reference(const obscura_settings& a, const obscura_settings& b) {
    // Plain floats and int32s only (no padding), so the bytes say it.
    return std::memcmp(&a.reference, &b.reference, sizeof a.reference) == 0;
}

std::string describe_reference(const obscura_settings& reference) {
    const obscura_reference_settings& r = reference.reference;
    std::string text = std::string(falloff_name(r.falloff)) + " r=" + format_number(r.radius) + " m";
    if (r.falloff == OBSCURA_FALLOFF_RHO0 && std::fabs(r.falloff_c - 0.3f) > 1e-6f) {
        text += " C=" + format_number(r.falloff_c);
    }
    const float derived_decay = r.falloff_c * r.radius * r.radius;
    if (r.falloff != OBSCURA_FALLOFF_TABLE && std::fabs(r.decay_rate - derived_decay) > 1e-6f * derived_decay) {
        text += " decay=" + format_number(r.decay_rate) + " m^2";
    }
    if (r.thickness > 0.0f) text += " thickness=" + format_number(r.thickness) + " m";
    return text;
}

samples::FloatImage render_reference(const ObscuraSession& session, const samples::SceneFrame& frame,
                                     bool use_normals, const obscura_settings& reference,
                                     const std::string& progress_label) {
    const int total_rays = reference.reference.rays;
    const AoTarget target(frame.output_rect.width, frame.output_rect.height, GL_R32F);
    std::vector<double> sum;
    samples::FloatImage result;
    const auto start = std::chrono::steady_clock::now();
    for (int done = 0; done < total_rays;) {
        const int rays = std::min(kReferenceChunkRays, total_rays - done);
        obscura_settings chunk = reference;
        chunk.reference.first_ray = reference.reference.first_ray + done;
        chunk.reference.rays = rays;
        AoRenderRequest request;
        request.scene = &frame;
        request.settings = &chunk;
        request.target = &target;
        request.use_normals = use_normals;
        render_ao(session, request);
        result = target.read();
        sum.resize(result.pixels.size(), 0.0);
        for (size_t i = 0; i < sum.size(); ++i) sum[i] += double(rays) * double(result.pixels[i]);
        done += rays;
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "%s: %d/%d rays, %.1f s\n", progress_label.c_str(), done, total_rays, seconds);
    }
    for (size_t i = 0; i < sum.size(); ++i) result.pixels[i] = float(sum[i] / double(total_rays));
    return result;
}

}  // namespace obscura::cli
