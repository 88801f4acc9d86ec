// TemporalPass: temporal accumulation after every method (sdk/glsl/temporal_accumulate.comp), and the history it
// reads and writes, one per view (obscura_view). The history ping-pongs between two RG32F textures (visibility;
// linear depth with the age in its low mantissa bits), two more (RGBA32F) with bent normals.
#ifndef OBSCURA_TEMPORAL_H
#define OBSCURA_TEMPORAL_H

#include "frame_input.h"
#include "gl/program_cache.h"
#include "output_writer.h"
#include "passes/pass_common.h"

namespace obscura {

// One view's history. A frame continues it only when the frame has the same size, output rectangle and outputs,
// the same method and method settings (`signature`), a reprojection, and no reset; with motion vectors (which span
// one frame) also only when its frame index follows the history's (+1, or equal for hosts that keep it constant).
// The history keeps the view-projection of the frame that wrote it: with matrices the next frame reprojects from
// there, not from the host's previous frame, which may have been a debug view's (it leaves the history alone).
class TemporalHistory {
public:
    // The texture a frame writes (and the composite then reads), and the one it reads.
    const gl::Texture2D& next() const { return ao_[1 - current_]; }
    const gl::Texture2D& previous() const { return ao_[current_]; }
    const gl::Texture2D& next_bent() const { return bent_[1 - current_]; }
    const gl::Texture2D& previous_bent() const { return bent_[current_]; }
    // Makes the history fit a frame: (re)allocates on a size or outputs change, and says whether the previous
    // frame's history may be read (`*continues`).
    Error prepare(const PassEnv& env, const FrameInput& input, bool bent_normals, uint64_t signature, bool reproject,
                  bool* continues);
    // The frame's writes become the history, made at `input`'s view-projection and frame index.
    void swap(const FrameInput& input);
    bool valid() const { return valid_; }
    // The view-projection (column-major) of the frame the history was made at; null if it had no matrices.
    const double* view_projection() const { return has_view_projection_ ? view_projection_ : nullptr; }
    // Drops the history (the next frame starts anew) but keeps the textures.
    void invalidate() { valid_ = false; }
    void release();
    uint64_t bytes() const { return ao_[0].bytes() + ao_[1].bytes() + bent_[0].bytes() + bent_[1].bytes(); }

private:
    gl::Texture2D ao_[2], bent_[2];
    int current_ = 0;
    bool valid_ = false;
    obscura_rect rect_ = {};
    int host_width_ = 0, host_height_ = 0;  // FrameInput's: the host's depth size (the frame's own at full resolution)
    uint64_t signature_ = 0;
    bool has_view_projection_ = false;
    double view_projection_[16] = {};
    uint32_t frame_index_ = 0;
};

class TemporalPass {
public:
    // Where a frame's previous positions come from (OBSCURA_TEMPORAL_REPROJECT_*), each its own program variant: the
    // host's motion vectors, or the matrices, or (equal view-projections, no vectors) the same texel.
    static int reprojection(const FrameInput& input) {
        if (input.motion_vector_texture != 0) return OBSCURA_TEMPORAL_REPROJECT_MOTION;
        return input.identity_reprojection ? OBSCURA_TEMPORAL_REPROJECT_IDENTITY : OBSCURA_TEMPORAL_REPROJECT_MATRICES;
    }
    // Builds the frame's variant: bent normals, the reprojection and whether it also writes the host's target image
    // (`target`, at full resolution without a debug view: the composite would only copy the history's visibility
    // there; format 0: it does not).
    Error prepare(const PassEnv& env, bool bent_normals, int reprojection, const TargetWrite& target = TargetWrite());
    static TemporalConstants constants(const obscura_temporal_settings& settings, const FrameInput& input,
                                       bool continues);
    // Blends `source` (R16F visibility; `bent_source`, RGBA16F, with bent normals) over `region` into the history's
    // next textures, and with a target write the visibility into `target_texture` too; the caller swaps the history
    // after the frame.
    void run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
             const FrameInput& input, const FrameResources& resources, const gl::Texture2D& source,
             const gl::Texture2D* bent_source, const TemporalHistory& history, GLuint target_texture = 0);

private:
    // The variants by their defines (a static camera's reads one history texel and does no matrix work), the last
    // gl::kProgramVariantsKept used: a host whose frames need more (views with their own target formats, blends,
    // bent outputs and cameras) compiles one again each time it comes back.
    gl::ProgramCache<gl::DefineLines> programs_;
    GLuint program_ = 0;  // prepare's variant
    TargetWrite target_;
};

// The temporal pass as the output writer's image write (full resolution, no debug view): the frame's run, into the
// image the writer names. Holds references: it lives for the frame's output write.
class TemporalImageWrite final : public OutputImageWrite {
public:
    TemporalImageWrite(TemporalPass& pass, const UniformRange& frame, const UniformRange& constants,
                       const Region& region, const FrameInput& input, const FrameResources& resources,
                       const gl::Texture2D* source, const gl::Texture2D* bent_source, const TemporalHistory& history)
        : pass_(pass), frame_(frame), constants_(constants), region_(region), input_(input), resources_(resources),
          source_(source), bent_source_(bent_source), history_(history) {}
    void write_image(const PassEnv& env, GLuint texture, GLenum) const override {
        pass_.run(env, frame_, constants_, region_, input_, resources_, *source_, bent_source_, history_, texture);
    }

private:
    TemporalPass& pass_;
    const UniformRange& frame_;
    const UniformRange& constants_;
    const Region& region_;
    const FrameInput& input_;
    const FrameResources& resources_;
    const gl::Texture2D* source_;
    const gl::Texture2D* bent_source_;
    const TemporalHistory& history_;
};

}  // namespace obscura

#endif  // OBSCURA_TEMPORAL_H
