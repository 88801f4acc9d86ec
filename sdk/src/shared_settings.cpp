#include "shared_settings.h"

#include "settings.h"

namespace obscura {
namespace {

constexpr const char* const kResolutionNames[] = {"full", "half", "quarter"};

// Temporal defaults: 8 frames (the 4x4 noise patterns of HBAO and GTAO then average 128 rotations per pixel, and a
// disocclusion recovers within a few frames), a clamp of 3 deviations (wide enough that the per-frame noise of a
// converged pixel stays inside it: at 2 the clamp clipped the moving noise pattern, and HBAO's and GTAO's flicker
// stayed at 0.35-0.37 of the unaccumulated image's; at 3 it is 0.33 on the atrium and the clutter room, with the
// sliding box's trail still gone after 8 frames; docs/quality.md), a 1 % plane tolerance (2 % before 0.5; 1 % gave the
// lower orbit error once the history was 32-bit: docs/quality.md).
const obscura_setting_info kSharedSettings[] = {
    setting_row("temporal.enabled", OBSCURA_SETTING_TOGGLE, 0, 0, 1, "",
     "accumulate frames per view: reprojected history, disocclusion rejection, neighbourhood clamp",
     OBSCURA_SETTING_OFFSET(temporal, enabled)),
    setting_row("temporal.max_frames", OBSCURA_SETTING_INT, 8, 1, 64, "frames",
     "the most frames the history averages (exponential blend with weight 1 / min(age + 1, N))",
     OBSCURA_SETTING_OFFSET(temporal, max_frames)),
    setting_row("temporal.clamp", OBSCURA_SETTING_FLOAT, 3.0, 0.25, 64.0, "sigma",
     "the history is held within this frame's 7-texel mean +- this many standard deviations (bounds ghosting)",
     OBSCURA_SETTING_OFFSET(temporal, clamp)),
    setting_row("temporal.plane_tolerance", OBSCURA_SETTING_FLOAT, 0.01, 1e-4, 1.0, "",
     "a history texel farther from the pixel's tangent plane than this fraction of its distance is dropped",
     OBSCURA_SETTING_OFFSET(temporal, plane_tolerance)),
    // Reduced resolution: the upsample's tolerance is a soft weight (1/e at one tolerance) where the temporal pass's
    // plane tolerance is a hard test, so their defaults differ (0.02 and 0.01; docs/algorithms.md).
    enum_row("resolution.scale", 1, 1,
             "the size the method runs at: full, half or quarter of the depth texture on each axis; a depth- and "
             "plane-aware upsample writes the full-size result",
             OBSCURA_SETTING_OFFSET(resolution, scale), kResolutionNames),
    setting_row("resolution.upsample_tolerance", OBSCURA_SETTING_FLOAT, 0.02, 1e-4, 1.0, "",
     "the upsample weighs a reduced texel down by its tangent plane's distance from the pixel in units of this "
     "fraction of the pixel's distance (the weight falls to 1/e at 1)",
     OBSCURA_SETTING_OFFSET(resolution, upsample_tolerance)),
};

}  // namespace

const obscura_setting_info* shared_setting_infos(uint32_t* count) {
    *count = uint32_t(sizeof kSharedSettings / sizeof kSharedSettings[0]);
    return kSharedSettings;
}

}  // namespace obscura
