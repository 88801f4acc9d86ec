// The screen-space reference of `compare --truth screen|both`: the REFERENCE method (rays through the depth
// buffer, infinitely thick unless `thickness` is set) with the same falloff as the method measured
// (obscura_reference_settings_for), traced in chunks of rays so that a progress line can be printed after
// each one. It is the limit a screen-space method converges to, not what a viewer sees: the geometry truth
// (rays against the scene's triangles) is truth_render.h.
//
// Chunk k renders rays [k * kReferenceChunkRays, ...) of every pixel's ray sequence (reference.first_ray)
// into an R32F target; the chunk images are averaged on the CPU, weighted by their ray counts. Since
// every ray of the SDK's per-pixel sequence depends only on its index, that average is the image one
// render of all the rays would give (up to float rounding).
#ifndef OBSCURA_CLI_REFERENCE_RENDER_H
#define OBSCURA_CLI_REFERENCE_RENDER_H

#include <string>

#include "demo_scene.h"
#include "image_io.h"
#include "obscura/obscura.h"

namespace obscura::cli {

class ObscuraSession;

constexpr int kReferenceChunkRays = 32;

// The resolved REFERENCE settings matching `method_settings`' falloff, with `rays` rays per pixel.
obscura_settings reference_settings_for(const obscura_settings& method_settings, int rays);
// Whether two references (from reference_settings_for) render the same image.
bool same_reference(const obscura_settings& a, const obscura_settings& b);
// "rho0 r=1 m", with C, the decay rate and the thickness where they are not the defaults.
std::string describe_reference(const obscura_settings& reference);

// Renders `reference` (settings.reference.rays rays) for the output rectangle of `frame`. After each
// chunk, prints "<progress_label>: 96/256 rays, 12.4 s" on stderr. Returns visibility, one channel.
samples::FloatImage render_reference(const ObscuraSession& session, const samples::SceneFrame& frame,
                                     bool use_normals, const obscura_settings& reference,
                                     const std::string& progress_label);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_REFERENCE_RENDER_H
