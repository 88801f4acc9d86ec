// The layout phase of a frame. HBAO, SAO, GTAO and the REFERENCE move their per-pixel noise with the frame index
// (frame_planner.cpp), so accumulated frames converge to the many-sample image. LSAO's sweep lines and FFAO's scan
// grid are laid out on the CPU and shared by every pixel: they move instead by cycling through kLayoutPhases
// layouts, each rotated (directions) or shifted (lines) by a fraction of its spacing, built the first time a frame
// asks for its phase. Phase 0 is the layout of a host that leaves frame_index at 0.
#ifndef OBSCURA_LAYOUT_PHASE_H
#define OBSCURA_LAYOUT_PHASE_H

#include <cstdint>

namespace obscura {

// As many phases as the temporal pass blends by default (temporal.max_frames): its history then holds one frame of
// each.
constexpr int kLayoutPhases = 8;

// The phase of a frame: the frame index mod 8, bit-reversed (0, 4, 2, 6, 1, 5, 3, 7), so that any 2^n consecutive
// frames spread their offsets evenly over the spacing, as the R2 offsets of the per-pixel noise do.
constexpr int layout_phase(uint32_t frame_index) {
    const uint32_t f = frame_index & 7u;
    return int(((f & 1u) << 2) | (f & 2u) | ((f >> 2) & 1u));
}

// The offset of a phase as a fraction of the spacing it moves across: phase / kLayoutPhases.
constexpr double layout_phase_fraction(int phase) { return double(phase) / double(kLayoutPhases); }

}  // namespace obscura

#endif  // OBSCURA_LAYOUT_PHASE_H
