#include "reduced_resolution.h"

namespace obscura {
namespace {

// Remaps row `row` (0: x, 1: y) of a column-major clip matrix so that host NDC n becomes the reduced grid's
// a n + b: the host texel x (centre x + 0.5 of `extent`) lands on reduced texel x >> k's centre (x / 2^k + 0.5 of
// `reduced`) whenever x is a multiple of 2^k. With c = ndc_host, ndc_reduced = (2 (x / 2^k + 0.5)) / R - 1 and
// x + 0.5 = (c + 1) E / 2: a = E / (2^k R), b = a - 1 + (1 - 2^-k) / R. On clip coordinates: row += b * row 3.
void remap_clip_row(float m[16], int row, int extent, int reduced, int shift) {
    const double scale = double(1 << shift);
    const double a = double(extent) / (scale * double(reduced));
    const double b = a - 1.0 + (1.0 - 1.0 / scale) / double(reduced);
    for (int column = 0; column < 4; ++column) {
        float& element = m[column * 4 + row];
        element = float(a * double(element) + b * double(m[column * 4 + 3]));
    }
}

}  // namespace

int resolution_shift(const obscura_settings& settings) {
    switch (settings.resolution.scale) {
        case OBSCURA_RESOLUTION_HALF: return 1;
        case OBSCURA_RESOLUTION_QUARTER: return 2;
        default: return 0;
    }
}

FrameInput reduced_frame_input(const FrameInput& host, int shift) {
    FrameInput frame = host;
    frame.resolution_shift = shift;
    frame.host_width = host.width;
    frame.host_height = host.height;
    frame.width = reduced_extent(host.width, shift);
    frame.height = reduced_extent(host.height, shift);
    // Every host pixel of the rectangle lies between reduced texels x >> k and (x >> k) + 1: both are computed.
    const obscura_rect& rect = host.output_rect;
    const int x0 = rect.x >> shift, y0 = rect.y >> shift;
    const int x1 = ((rect.x + rect.width - 1) >> shift) + 1, y1 = ((rect.y + rect.height - 1) >> shift) + 1;
    frame.output_rect.x = x0;
    frame.output_rect.y = y0;
    frame.output_rect.width = (x1 < frame.width ? x1 : frame.width - 1) - x0 + 1;
    frame.output_rect.height = (y1 < frame.height ? y1 : frame.height - 1) - y0 + 1;
    // The temporal pass takes the previous clip position as this projection applied to the reprojected point, so the
    // remapped projection serves both frames (the reprojection maps view spaces and needs no remapping).
    remap_clip_row(frame.projection.m, 0, host.width, frame.width, shift);
    remap_clip_row(frame.projection.m, 1, host.height, frame.height, shift);
    return frame;
}

}  // namespace obscura
