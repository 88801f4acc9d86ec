// Test-only views into passes (compiled into the tests, never into the library): readbacks of their GPU buffers and the switches only tests flip. Each reads back
// and so waits for the GPU; production code never includes this header. The pass classes name these as
// friends, so their own interface stays what a frame uses.
#ifndef OBSCURA_PASS_INSPECTION_H
#define OBSCURA_PASS_INSPECTION_H

#include <cstdint>
#include <vector>

#include "passes/ffao.h"
#include "passes/lsao.h"

namespace obscura {

class LsaoPassInspection {
public:
    // Whether the sweeps count their work for read_stats (off by default: the counters cost atomics).
    static void collect_stats(LsaoPass& pass, bool on) { pass.collect_stats_ = on; }
    // The counters of the last sweeps: steps, hull pops, points dropped from full hulls.
    static void read_stats(const LsaoPass& pass, const gl::Table& gl, uint32_t out[3]);
    // The sweeps' values in layout order (OBSCURA_LSAO_NO_OCCLUDER where a sample had none).
    static std::vector<float> read_values(const LsaoPass& pass, const gl::Table& gl);
    // Fills the values with one half-float bit pattern (poison before a sweep to see what it writes).
    static void fill_values(const LsaoPass& pass, const gl::Table& gl, uint16_t half_bits);
};

class FfaoPassInspection {
public:
    // The estimator table's texels (A fastest, then B, then the shared C x D axis).
    static std::vector<float> read_table(const FfaoPass& pass, const gl::Table& gl);
    // The peaks buffer, vec4s in layout order: every entry with one chunk, else the chunk the scan last filled from
    // its start (chunk_entries of them) and what is left of a larger one behind it.
    static std::vector<float> read_peaks(const FfaoPass& pass, const gl::Table& gl);
    // Chunk c's first entry in the layout and its entry count.
    static int64_t chunk_first(const FfaoPass& pass, int c) { return pass.grids_[pass.current_].chunks[c].first; }
    static int64_t chunk_entries(const FfaoPass& pass, int c) {
        const FfaoPass::Chunk& chunk = pass.grids_[pass.current_].chunks[c];
        return chunk.end - chunk.first;
    }
    // Caps the storage block the peaks may take (0: GL's limit), so that small sizes split them into chunks as 4K
    // does on Mesa; the next ensure_layout lays them out anew.
    static void limit_storage_block(FfaoPass* pass, int64_t bytes) { pass->storage_block_limit_ = bytes; }
    // How many phase layouts the pass has built.
    static int layouts_built(const FfaoPass& pass) { return pass.layouts_built_; }
};

}  // namespace obscura

#endif  // OBSCURA_PASS_INSPECTION_H
