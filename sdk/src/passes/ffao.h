// FFAO (sdk/glsl/ffao_table.comp, ffao_scan.comp, ffao_prefix.comp, ffao_obscurance.comp): the estimator
// table for the falloff's shape (rebuilt on the GPU only when the shape changes), the scan layout for the
// current size in buffers, and the per-frame scan, prefix-sum and obscurance dispatches.
#ifndef OBSCURA_FFAO_H
#define OBSCURA_FFAO_H

#include "frame_input.h"
#include "layout_phase.h"
#include "passes/ffao_estimator.h"
#include "passes/ffao_layout.h"
#include "passes/pass_common.h"


namespace obscura {

// Whether the obscurance reads single lines rather than sector averages (a finite thickness: sec. 11), in
// which case no prefix sums are built.
inline bool ffao_single_lines(const obscura_ffao_settings& settings) { return settings.thickness > 0.0f; }
// The paper's baseline (sec. 5): far-field points from a depth MIP pyramid instead of the scan.
inline bool ffao_uses_mipmap(const obscura_ffao_settings& settings) { return settings.geometry == 2; }
inline bool ffao_uses_saao(const obscura_ffao_settings& settings) { return settings.saao == OBSCURA_TOGGLE_ON; }
// The pyramid's filter for it: the mean of the geometry, or (finite thickness: no averaging) the nearest depth.
inline int ffao_mipmap_filter(const obscura_ffao_settings& settings) {
    return settings.thickness > 0.0f ? OBSCURA_MIP_FILTER_MIN : OBSCURA_MIP_FILTER_MEAN_OF_GEOMETRY;
}
constexpr int kFfaoMipmapLevels = 13;  // wanted levels (level_count caps them at the texture's size)

class FfaoPass {
public:
    // Builds the programs these settings run and the table's texture and sampler on first use.
    Error prepare(const PassEnv& env, const obscura_ffao_settings& settings);
    // Selects the layout of the frame's phase (layout_phase(frame_index); with a frame split the technique passes
    // frame_index / N, so the phase moves once per N frames): drops every phase's layout and buffers
    // when the size, K or B0 changed, and builds the phase's on its first use (the mipmap method keeps only the
    // orientations: it allocates no scan buffers). Chunked without SAAO, it sizes the running total to
    // `obscurance`, the region run_obscurance will cover (a frame's AO region, inside the guard band); an empty
    // region (obscura_prepare: no output yet) keeps the last one's size, or takes the whole texture.
    Error ensure_layout(const PassEnv& env, const obscura_ffao_settings& settings, int width, int height,
                        uint32_t frame_index = 0, const Region& obscurance = Region());
    // Whether the table must be (re)built for these settings' falloff shape.
    bool table_stale(const obscura_ffao_settings& settings) const { return !table_valid_ || !(shape_ == ffao_falloff_shape(settings)); }
    static FfaoTableConstants table_constants(const obscura_ffao_settings& settings);
    // `mipmap_levels`: the depth pyramid's levels for the mipmap method (1 otherwise); `frame_split`: the orientations
    // spread over that many frames (obscura_ffao_added_settings), the pattern turned by input.frame_index.
    FfaoConstants constants(const obscura_ffao_settings& settings, const FrameInput& input, int mipmap_levels = 1,
                            int frame_split = 1) const;
    // The per-chunk constants of the scan, the prefix sums and the obscurance, pushed with the frame's other blocks
    // (a UniformWriter or a UniformArena) before them.
    template <class Writer>
    void push_chunk_constants(Writer& writer) {
        const Grid& grid = grids_[current_];
        for (int c = 0; c < grid.chunk_count; ++c) {
            FfaoChunkConstants block = {};
            block.range[0] = grid.chunks[c].first_orientation;
            block.range[1] = grid.chunks[c].orientations;
            block.range[2] = int32_t(grid.chunks[c].first);
            block.range[3] = (c == 0 ? OBSCURA_FFAO_CHUNK_FIRST : 0) | (c + 1 == grid.chunk_count ? OBSCURA_FFAO_CHUNK_LAST : 0);
            chunk_uniforms_[c] = writer.push(block);
        }
    }
    // Chunks of the peaks: one when they fit a storage block (and always for the mipmap baseline, which has none);
    // more at sizes where they do not, and then the scan, the prefix sums and the obscurance run once per chunk, in
    // order (chunk c's obscurance before chunk c + 1's scan: they share the buffer).
    int chunk_count() const { return grids_[current_].chunk_count; }
    bool chunked() const { return chunk_count() > 1; }
    void run_table(const PassEnv& env, const obscura_ffao_settings& settings, const UniformRange& pass);
    void run_scan(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const FrameResources& resources,
                  int chunk);
    void run_prefix(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, int chunk);
    // Without SAAO: visibility into resources.ao over `region`. With SAAO: the near and far sums over `region`
    // (the gather's region grown by a pixel), after the box average over the same region. Chunk `chunk`'s
    // orientations (all of them when there is one chunk): the last chunk writes the result.
    void run_obscurance(const PassEnv& env, const obscura_ffao_settings& settings, const UniformRange& frame,
                        const UniformRange& pass, const Region& region, FrameResources& resources, int chunk);
    void run_box_average(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
                         const FrameResources& resources);
    // SAAO: visibility into resources.ao over `region`; then optionally the blur into resources.ao_blurred.
    void run_gather(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
                    FrameResources& resources);
    void run_saao_blur(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
                       FrameResources& resources);
    // The current phase's layout.
    const FfaoLayout& layout() const { return grids_[current_].layout; }
    uint64_t bytes() const;
    void release();  // the per-size buffers (the table stays)
    void release_table();  // the estimator table too: rebuilt on the next frame that needs it
private:
    friend class FfaoPassInspection;  // the tests' readbacks (testing/pass_inspection.h)
    static void dispatch_pixels(const PassEnv& env, const UniformRange& frame, const UniformRange& pass,
                                const Region& region);
    gl::Object table_program_, scan_program_, prefix_program_, box_program_, gather_program_, blur_program_;
    gl::Object obscurance_programs_[2][2][2][2];  // [mipmap geometry][SAAO][chunked][finite thickness], on first use
    gl::Texture2D box_, terms_;                // SAAO: averaged receivers, (near, far) sums
    gl::Texture2D running_;                    // chunked without SAAO: the obscurance's running total (r32f)
                                               // over its region, from the region's corner
    gl::Object table_, table_sampler_;
    gl::Object peaks_texture_;  // a buffer texture over peaks_ (CPU rasterisers only)
    bool table_valid_ = false;
    FfaoFalloffShape shape_;
    struct LayoutKey {
        int width = 0, height = 0, sectors = 0, base_interval = 0;
        bool buffers = false, saao = false;
        int64_t storage_block_limit = 0;
        bool operator==(const LayoutKey& o) const {
            return width == o.width && height == o.height && sectors == o.sectors && base_interval == o.base_interval &&
                   buffers == o.buffers && saao == o.saao && storage_block_limit == o.storage_block_limit;
        }
    };
    void bind_chunk(const gl::Table& gl, int chunk) const;  // the peaks buffer at OBSCURA_SSBO_FFAO_PEAKS, its size
    LayoutKey key_;
    // The chunks: runs of whole orientations whose entries [first, end) the peaks buffer holds one at a time.
    struct Chunk {
        int first_orientation = 0, orientations = 0;
        int64_t first = 0, end = 0;
    };
    // One layout phase's scan grid: its layout, line and column records, and chunks.
    struct Grid {
        FfaoLayout layout;
        gl::Buffer lines, columns;
        gl::Object columns_texture;  // RGBA32UI over columns (CPU rasterisers only)
        Chunk chunks[OBSCURA_FFAO_PEAK_CHUNKS];
        int chunk_count = 0;
    };
    Error build_grid(const PassEnv& env, const obscura_ffao_settings& settings, int phase);
    Grid grids_[kLayoutPhases];
    int current_ = 0;
    gl::Buffer peaks_;  // shared by the phases: the largest chunk of any phase built
    UniformRange chunk_uniforms_[OBSCURA_FFAO_PEAK_CHUNKS];
    int64_t storage_block_limit_ = 0;  // tests: a smaller storage block than GL's (FfaoPassInspection)
    // The last layout refused for its size (INVALID_SIZE), by its key: ensure_layout answers it again, in every phase.
    LayoutKey refused_key_;  // the last size refused with INVALID_SIZE (in any layout phase), and why
    Error refused_;
    int layouts_built_ = 0;  // tests (FfaoPassInspection)
};

}  // namespace obscura

#endif  // OBSCURA_FFAO_H
