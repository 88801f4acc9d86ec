// Reduced resolution (obscura_resolution_settings): the frame a method runs on at 1/2 or 1/4 of the host's depth
// texture on each axis. Reduced texel t is the host's texel t << k (k = 1, 2), so the depth preparation reads real
// texels at their own positions; the reduced frame's projection is the host's with its x and y rows remapped so
// that texel t's centre lands on the host texel's centre, and every pass of the method (and the temporal pass) runs
// on it unchanged. The upsample (passes/upsample.h) brings the result back to the host's texels.
#ifndef OBSCURA_REDUCED_RESOLUTION_H
#define OBSCURA_REDUCED_RESOLUTION_H

#include "frame_input.h"

namespace obscura {

// k of the settings' resolution: 0 full, 1 half, 2 quarter (resolved settings).
int resolution_shift(const obscura_settings& settings);

// Texels of the reduced grid along an axis of `extent` host texels: the first lies on host texel 0, the last on host
// texel ((extent - 1) >> shift) << shift; the host texels past it (when extent - 1 is not a multiple of 2^shift) take
// the last texel alone (the upsample clamps).
inline int reduced_extent(int extent, int shift) { return ((extent - 1) >> shift) + 1; }

// The frame the method sees at reduced resolution `shift` > 0: the reduced size, the output rectangle grown to the
// reduced texels every pixel of the host's rectangle interpolates between, the remapped projection; the host's
// textures stay (read at t << shift).
FrameInput reduced_frame_input(const FrameInput& host, int shift);

}  // namespace obscura

#endif  // OBSCURA_REDUCED_RESOLUTION_H
