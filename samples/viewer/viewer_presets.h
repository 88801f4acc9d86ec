// The viewer's presets: named configurations a technical artist picks from the "preset" combo of a method (spec
// keys over the method's defaults, in the samples' method-spec syntax, samples/common/method_spec_parser.h). They
// reproduce the papers' configurations (LSAO's own `preset` setting selects its paper's Table 2), the defaults
// before 0.5, and the measured temporal, reduced-resolution and quality configurations of docs/quality.md.
// tests/unit/viewer_presets_test.cpp parses every spec and checks that it names its method and resolves.
#ifndef OBSCURA_VIEWER_PRESETS_H
#define OBSCURA_VIEWER_PRESETS_H

#include "obscura/obscura.h"

namespace obscura::viewer {

struct ViewerPreset {
    obscura_method method;  // the method whose combo lists it
    const char* label;      // what the combo shows
    const char* spec;       // the settings: a method spec ("gtao:slices=2:steps=12")
};

// (The specs start from obscura_default_settings: the preset moves LSAO's K, D_S and D_L, and SAAO FFAO's K.)
inline constexpr ViewerPreset kViewerPresets[] = {
    {OBSCURA_METHOD_HBAO, "defaults (K=8, N=7, tuned)", "hbao"},
    {OBSCURA_METHOD_HBAO, "defaults before 0.5 (K=8, N=12)",
     "hbao:steps=12:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16"},
    {OBSCURA_METHOD_HBAO, "K=16, N=48: the docs' quality baseline", "hbao:directions=16:steps=48:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16"},
    {OBSCURA_METHOD_SAO, "paper: s=9, tau=7, q'=8 (defaults)", "sao"},
    {OBSCURA_METHOD_LSAO, "paper Table 2, K=8, receiver's tangent (defaults)", "lsao"},
    {OBSCURA_METHOD_LSAO, "paper Table 2, K=16, fixed tangent (defaults before 0.5)", "lsao:preset=k16:tangent_strategy=fixed"},
    {OBSCURA_METHOD_LSAO, "paper Table 2, K=24, fixed tangent", "lsao:preset=k24:tangent_strategy=fixed"},
    {OBSCURA_METHOD_LSAO, "paper Table 2, K=32, fixed tangent", "lsao:preset=k32:tangent_strategy=fixed"},
    {OBSCURA_METHOD_LSAO, "paper Figure 1, K=8, fixed tangent", "lsao:preset=k8_figure1:tangent_strategy=fixed"},
    {OBSCURA_METHOD_LSAO, "paper Figure 13, K=16, fixed tangent", "lsao:preset=k16_figure13:tangent_strategy=fixed"},
    // FFAO's paper renders an infinitely thick depth field (thickness 0, docs/parameters.md, "FFAO's thickness"): the
    // presets that say "paper" set it, since the defaults are 0.4 m thick (and so the defaults preset's label does not
    // claim the paper). tests/unit/viewer_presets_test.cpp checks it.
    {OBSCURA_METHOD_FFAO, "K=16x2, B0=10, 0.4 m thick (defaults)", "ffao"},
    {OBSCURA_METHOD_FFAO, "paper: K=16x2, infinitely thick (defaults before 0.5)", "ffao:thickness=0"},
    {OBSCURA_METHOD_FFAO, "paper: K=8x2", "ffao:sectors=8:thickness=0"},
    {OBSCURA_METHOD_FFAO, "paper: SAAO, K=18x2", "ffao:saao=on:thickness=0"},
    {OBSCURA_METHOD_FFAO, "paper sec. 5: mipmap baseline", "ffao:geometry=mipmap:thickness=0"},
    {OBSCURA_METHOD_REFERENCE, "256 rays (defaults)", "reference"},
    {OBSCURA_METHOD_GTAO, "High, 3x3 (XeGTAO's counts), horizon (defaults)", "gtao"},
    {OBSCURA_METHOD_GTAO, "Low, 1x2 (XeGTAO's counts)", "gtao:preset=low"},
    {OBSCURA_METHOD_GTAO, "Medium, 2x2 (XeGTAO's counts)", "gtao:preset=medium"},
    {OBSCURA_METHOD_GTAO, "Ultra, 9x3 (XeGTAO's counts)", "gtao:preset=ultra"},
    {OBSCURA_METHOD_GTAO, "XeGTAO's High, step distribution 2", "gtao:step_power=2"},
    {OBSCURA_METHOD_GTAO, "visibility bitmask, 0.4 m thick", "gtao:thickness_mode=bitmask"},
    // Lower than HBAO's default on all seven scenes at 640x360, at 1.3x its cost on llvmpipe (docs/quality.md, "The
    // bitmask's error at High is a step-count bias"): steps, not slices, set the bitmask's error.
    {OBSCURA_METHOD_GTAO, "visibility bitmask, 2 x 12 steps", "gtao:thickness_mode=bitmask:slices=2:steps=12:power=1"},
    // Temporal presets: fewer samples a frame, accumulated over up to 16 (docs/quality.md, "Temporal presets": each
    // converges, on a still camera, to less error than its method's defaults).
    {OBSCURA_METHOD_HBAO, "temporal: K=4, no blur, 16 frames", "hbao:directions=4:blur=off:temporal.enabled=on:temporal.max_frames=16"},
    {OBSCURA_METHOD_SAO, "temporal: s=3, 16 frames", "sao:samples=3:temporal.enabled=on:temporal.max_frames=16"},
    {OBSCURA_METHOD_GTAO, "temporal: 1 slice x 4 steps, 16 frames", "gtao:slices=1:steps=4:power=1.65:temporal.enabled=on:temporal.max_frames=16"},
    // REFERENCE's frames trace the next rays of each pixel's sequence: 16 a frame over 16 frames are the 256 of its
    // defaults, at 0.07x of their cost a frame.
    {OBSCURA_METHOD_REFERENCE, "temporal: 16 rays a frame, 16 frames", "reference:rays=16:temporal.enabled=on:temporal.max_frames=16"},
    // LSAO's free directions turn with the layout phase: 4 of them a frame cover 32 over 8 frames.
    {OBSCURA_METHOD_LSAO, "temporal: 4 free directions, 16 frames",
     "lsao:pattern=free:directions=4:step_length=1.41:line_spacing=1.41:temporal.enabled=on:temporal.max_frames=16"},
    // FFAO's orientations spread over 4 frames (each 2x2 pixel block evaluates all of them in every frame): a still
    // view converges to its defaults' image at about 0.35x of their cost (docs/quality.md, "Temporal presets").
    {OBSCURA_METHOD_FFAO, "temporal: 1/4 of the orientations a frame, 16 frames",
     "ffao:frame_split=4:temporal.enabled=on:temporal.max_frames=16"},
    // Reduced resolution: half costs 0.25-0.34x of full on llvmpipe, within +0.01 of its error at 640x360 for these
    // (docs/performance.md, docs/quality.md, "Reduced resolution").
    {OBSCURA_METHOD_HBAO, "half resolution", "hbao:resolution.scale=half"},
    {OBSCURA_METHOD_GTAO, "half resolution", "gtao:resolution.scale=half"},
    {OBSCURA_METHOD_SAO, "half resolution", "sao:resolution.scale=half"},
    {OBSCURA_METHOD_FFAO, "half resolution (a quarter of the memory)", "ffao:resolution.scale=half"},
    {OBSCURA_METHOD_LSAO, "half resolution", "lsao:resolution.scale=half"},
};

}  // namespace obscura::viewer

#endif  // OBSCURA_VIEWER_PRESETS_H
