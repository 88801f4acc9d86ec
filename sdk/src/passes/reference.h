// Reference: the screen-space reference (sdk/glsl/reference.comp), ambient obscurance ray-traced through the
// depth buffer, infinitely thick unless `thickness` is set: what screen-space methods converge to (and what
// `compare --truth screen` measures them against), not the geometry truth (rays against the scene's
// triangles, in the samples; the SDK only sees depth). Rays are traced in batches, one dispatch each,
// accumulating into an R32F texture whose last batch leaves visibility in it.
#ifndef OBSCURA_REFERENCE_H
#define OBSCURA_REFERENCE_H

#include <algorithm>

#include "frame_input.h"
#include "passes/pass_common.h"

namespace obscura {

class ReferencePass {
public:
    // Builds the program on first use: hosts that never render the reference never compile it.
    Error prepare(const PassEnv& env);
    // Converts resolved settings (metres) to the shader's constants (view units).
    static ReferenceConstants constants(const obscura_reference_settings& settings, const FrameInput& input);
    // The index of frame `frame_index`'s first ray in the per-pixel sequence: the frames of a host that advances
    // frame_index trace consecutive, disjoint runs of one low-discrepancy sequence, rays apart (as renders with
    // first_ray 0, rays, 2 rays ... do), so accumulated frames converge like one render of all their rays. (The
    // frame's R2 offset of the other methods' noise, added to this sequence's rotation, only shifted it by one ray
    // a frame: 8 accumulated frames of 16 rays held 23 distinct rays.) Wraps modulo 2^32, as the shader's index does.
    static uint32_t first_ray_of_frame(const obscura_reference_settings& settings, uint32_t frame_index) {
        return uint32_t(settings.first_ray) + frame_index * uint32_t(settings.rays);
    }
    // Traces settings.rays rays per pixel of `region` into `accumulator` (R32F), which then holds visibility.
    // `between_batches` runs after every dispatch but the last (the context flushes there). A batch is dispatched in
    // tiles of kTile x kTile pixels: a ray walks up to the whole texture (the falloffs that never reach zero), so one
    // dispatch of a large image (8K: 6.7e7 pixels x 16 rays x thousands of texels) ran for seconds, past the watchdogs
    // that reset a GPU whose submission runs long (2 s on Windows), and the host's context with it.
    static constexpr int kTile = 512;
    template <class Callback>
    void run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
             const obscura_reference_settings& settings, uint32_t frame_index, FrameResources& resources,
             const gl::Texture2D& accumulator, Callback&& between_batches) {
        bind(env, frame, pass, resources, accumulator);
        const int total = settings.rays, per_batch = settings.rays_per_dispatch;
        const uint32_t first = first_ray_of_frame(settings, frame_index);
        for (int done = 0; done < total; done += per_batch) {
            const int count = total - done < per_batch ? total - done : per_batch;
            const bool last = done + count >= total;
            for (int y = region.y; y < region.y + region.height; y += kTile) {
                for (int x = region.x; x < region.x + region.width; x += kTile) {
                    const Region tile{x, y, std::min(kTile, region.x + region.width - x),
                                      std::min(kTile, region.y + region.height - y)};
                    const bool batch_done = x + kTile >= region.x + region.width && y + kTile >= region.y + region.height;
                    dispatch_tile(env, region, tile, first + uint32_t(done), count, done == 0, last, batch_done);
                    if (!(last && batch_done)) between_batches();
                }
            }
        }
    }

private:
    void bind(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const FrameResources& resources,
              const gl::Texture2D& accumulator);
    // `batch_done`: the batch's last tile, after which its barrier goes (tiles of one batch touch disjoint texels).
    void dispatch_tile(const PassEnv& env, const Region& region, const Region& tile, uint32_t first_ray, int count,
                       bool first, bool last, bool batch_done);
    gl::Object program_;
};

}  // namespace obscura

#endif  // OBSCURA_REFERENCE_H
