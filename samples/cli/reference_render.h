// The screen-space reference of `compare --truth screen|both`: the REFERENCE method (rays through the depth
// buffer, infinitely thick unless `thickness` is set) with the same falloff as the method measured
// (obscura_reference_settings_for), traced in chunks of rays so that a progress line can be printed after
// each one. It is the limit a screen-space method converges to, not what a viewer sees: the geometry truth
// (rays against the scene's triangles) is truth_render.h.
//
// Chunk k renders rays [first_ray + k * kReferenceChunkRays, ...) of every pixel's ray sequence (reference.first_ray)
// into an R32F target; the chunk images are averaged on the CPU, weighted by their ray counts. Since
// every ray of the SDK's per-pixel sequence depends only on its index, that average is the image one
// render of all the rays would give (up to float rounding).
#ifndef OBSCURA_CLI_REFERENCE_RENDER_H
#define OBSCURA_CLI_REFERENCE_RENDER_H

#include <cstdint>
#include <string>

#include "demo_scene.h"
#include "image_io.h"
#include "obscura/obscura.h"

namespace obscura::cli {

class ObscuraSession;

constexpr int kReferenceChunkRays = 32;

// Where the screen-space reference's rays start in each pixel's sequence. A REFERENCE method measured against it
// traces rays 0, 1, ... of the same sequences (first_ray 0, its default): from 0 the reference was that method's own
// image, and its error read 0 whatever its ray count. 2^23 is half the SDK's first_ray range ([0, 2^24]), beyond the
// rays a compared REFERENCE traces (8192 rays a frame for 1000 frames) and leaving room for the most a reference
// traces itself (65536).
constexpr int32_t kReferenceTruthFirstRay = 1 << 23;

// The resolved REFERENCE settings matching `method_settings`' falloff, with `rays` rays per pixel, from ray
// kReferenceTruthFirstRay on.
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
