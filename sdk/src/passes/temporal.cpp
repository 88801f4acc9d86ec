#include "passes/temporal.h"

#include <algorithm>
#include <cstdio>
#include <iterator>

namespace obscura {

Error TemporalHistory::prepare(const PassEnv& env, const FrameInput& input, bool bent_normals, uint64_t signature,
                               bool reproject, bool* continues) {
    const int width = input.width, height = input.height;
    const bool resized = ao_[0].width() != width || ao_[0].height() != height;
    if (resized || !ao_[0]) {
        release();
        ao_[0] = env.create_texture(GL_RG32F, width, height);
        ao_[1] = env.create_texture(GL_RG32F, width, height);
        if (!ao_[0] || !ao_[1]) {
            release();
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d temporal history failed", width, height);
        }
    }
    if (bent_normals != static_cast<bool>(bent_[0])) {
        valid_ = false;  // the bent-normal history starts with this frame
        if (bent_normals) {
            // 32-bit: the history is a running average read back every frame, and GPUs that truncate fp32 -> fp16 image
            // stores (NVIDIA) lose up to 2^-11 a component a frame, which the average amplifies by (1 - a) / a: the bent
            // normal drifted by up to 2 degrees at 64 frames (found by a read-only review; llvmpipe rounds).
            bent_[0] = env.create_texture(GL_RGBA32F, width, height);
            bent_[1] = env.create_texture(GL_RGBA32F, width, height);
            if (!bent_[0] || !bent_[1]) {
                release();
                return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d bent-normal history failed",
                                   width, height);
            }
        } else {
            bent_[0] = gl::Texture2D();
            bent_[1] = gl::Texture2D();
        }
    }
    const obscura_rect& rect = input.output_rect;
    const bool same_rect = rect.x == rect_.x && rect.y == rect_.y && rect.width == rect_.width &&
                           rect.height == rect_.height;
    // Motion vectors give this frame's offsets to the host's previous frame: the history must be that frame's.
    const bool follows = input.frame_index - frame_index_ <= 1u;  // +1, or the same index (unsigned: wraps)
    const bool motion = input.motion_vector_texture != 0;
    // At reduced resolution several host sizes share one reduced size (640 and 639 wide are both 320 at half), but
    // their grids map to the screen differently: a host resize starts anew as a resize of the grid does.
    const bool same_host = input.host_width == host_width_ && input.host_height == host_height_;
    *continues = valid_ && same_rect && same_host && signature == signature_ && reproject && !input.reset_history &&
                 (!motion || follows);
    // Dropped now, not at the swap: a frame that fails after this point must not leave the old history valid.
    if (!*continues) valid_ = false;
    rect_ = rect;
    host_width_ = input.host_width;
    host_height_ = input.host_height;
    signature_ = signature;
    return Error();
}

void TemporalHistory::swap(const FrameInput& input) {
    current_ = 1 - current_;
    valid_ = true;
    has_view_projection_ = input.has_matrices;
    std::copy(std::begin(input.view_projection), std::end(input.view_projection), view_projection_);
    frame_index_ = input.frame_index;
}

void TemporalHistory::release() {
    for (gl::Texture2D& t : ao_) t = gl::Texture2D();
    for (gl::Texture2D& t : bent_) t = gl::Texture2D();
    valid_ = false;
    current_ = 0;
}

Error TemporalPass::prepare(const PassEnv& env, bool bent_normals, int reprojection, const TargetWrite& target) {
    char defines[160];
    std::snprintf(defines, sizeof defines,
                  "OBSCURA_TEMPORAL_BENT_NORMALS %d\nOBSCURA_TEMPORAL_REPROJECT %d\nOBSCURA_CPU_RASTERISER %d\n"
                  "OBSCURA_TEMPORAL_TARGET %d\n",
                  bent_normals ? 1 : 0, reprojection, env.cpu_renderer ? 1 : 0, target.format != 0 ? 1 : 0);
    Error error = target_variant(env, "temporal_accumulate.comp", defines, target, &programs_, &program_);
    if (!error) target_ = target;
    return error;
}

TemporalConstants TemporalPass::constants(const obscura_temporal_settings& settings, const FrameInput& input,
                                          bool continues) {
    TemporalConstants c = {};
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            c.reprojection[column][row] = input.reprojection[column * 4 + row];
        }
    }
    if (!input.has_matrices) {  // motion vectors alone: the point is taken as static in view space
        for (int i = 0; i < 4; ++i) c.reprojection[i][i] = 1.0f;
    }
    c.params[0] = float(settings.max_frames);
    c.params[1] = settings.clamp;
    c.params[2] = settings.plane_tolerance;
    // Host texels per unit of the vectors, then this frame's texels per host texel (reduced resolution: 2^-k).
    const bool ndc = input.motion_units == OBSCURA_MOTION_NDC;
    const float reduced = 1.0f / float(1 << input.resolution_shift);
    c.motion[0] = (ndc ? 0.5f * float(input.host_width) : 1.0f) * reduced;
    c.motion[1] = (ndc ? 0.5f * float(input.host_height) : 1.0f) * reduced;
    c.config[0] = continues ? 1 : 0;
    return c;
}

void TemporalPass::run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const Region& region,
                       const FrameInput& input, const FrameResources& resources, const gl::Texture2D& source,
                       const gl::Texture2D* bent_source, const TemporalHistory& history, GLuint target_texture) {
    const gl::Table& gl = env.gl;
    const bool bent = bent_source != nullptr;
    gl.UseProgram(program_);
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    env.bind_texture(OBSCURA_UNIT_HISTORY, GL_TEXTURE_2D, history.previous().name());
    // Without motion vectors the sampler still needs a complete texture: the history stands in (never read).
    env.bind_texture(OBSCURA_UNIT_MOTION, GL_TEXTURE_2D,
                     input.motion_vector_texture ? input.motion_vector_texture : history.previous().name());
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, history.next().name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    if (target_.format != 0) bind_target_image(gl, OBSCURA_IMAGE_OUT2, target_texture, target_);
    if (bent) {
        env.bind_texture(OBSCURA_UNIT_BENT_SOURCE, GL_TEXTURE_2D, bent_source->name());
        env.bind_texture(OBSCURA_UNIT_BENT_HISTORY, GL_TEXTURE_2D, history.previous_bent().name());
        gl.BindImageTexture(OBSCURA_IMAGE_OUT1, history.next_bent().name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    }
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    env.dispatch(region.width, region.height, OBSCURA_TEMPORAL_GROUP_X, OBSCURA_TEMPORAL_GROUP_Y);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
