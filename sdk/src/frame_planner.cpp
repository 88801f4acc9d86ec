#include "frame_planner.h"

#include <algorithm>
#include <cmath>

namespace obscura {
namespace {

// A frame's shared constants, the work rectangle left for each pass.
FrameConstants base_constants(const FrameInput& input, const OutputTarget& target, float debug_depth_scale) {
    const float* m = input.projection.m;
    FrameConstants c = {};
    c.proj_scale[0] = m[0]; c.proj_scale[1] = m[5]; c.proj_scale[2] = m[8]; c.proj_scale[3] = m[9];
    c.proj_depth[0] = m[10]; c.proj_depth[1] = m[14]; c.proj_depth[2] = m[11]; c.proj_depth[3] = m[15];
    c.proj_offset[0] = m[12]; c.proj_offset[1] = m[13];
    c.proj_offset[2] = input.projection.clip_scale; c.proj_offset[3] = input.projection.clip_bias;
    c.depth_params[0] = input.projection.sky_window_depth;
    c.depth_params[1] = input.meters_to_view_units;
    c.depth_params[2] = 1.0f / float(input.width);
    c.depth_params[3] = 1.0f / float(input.height);
    int source = input.depth_linear ? OBSCURA_DEPTH_SOURCE_LINEAR : OBSCURA_DEPTH_SOURCE_HARDWARE;
    if (input.depth_multisample) source += 1;
    c.depth_size[0] = input.width; c.depth_size[1] = input.height;
    c.depth_size[2] = source; c.depth_size[3] = input.normal_mode;
    c.output_rect[0] = input.output_rect.x; c.output_rect[1] = input.output_rect.y;
    c.output_rect[2] = input.output_rect.width; c.output_rect[3] = input.output_rect.height;
    c.target_params[0] = target.kind == TargetKind::Image ? target.x : 0;
    c.target_params[1] = target.kind == TargetKind::Image ? target.y : 0;
    c.target_params[2] = int(target.blend);
    c.target_params[3] = int(target.debug_view);
    c.debug_params[0] = debug_depth_scale;
    // Frame n moves every pixel's noise by the n-th point of the R2 sequence (Roberts 2018: the plastic number's
    // powers), in double so that late frames keep their offsets; accumulated frames then cover the strata evenly.
    const double n = double(input.frame_index);
    const double rx = n * 0.7548776662466927, ry = n * 0.5698402909980532;
    c.noise_offset[0] = float(rx - std::floor(rx));
    c.noise_offset[1] = float(ry - std::floor(ry));
    c.resolution[0] = input.resolution_shift;
    c.resolution[1] = 1;  // a working-size frame reads working-size textures
    return c;
}

// SAO's quad filter pairs pixels of 2x2 quads in absolute coordinates: such regions start and end on quad boundaries
// (clamped to the texture), so the last column or row keeps its partner (it was left unpaired when the region ended
// on an even coordinate, and a pixel's AO then depended on where the output rectangle ended).
Region aligned_to_quads(Region r, int width_limit, int height_limit) {
    const int x0 = r.x & ~1, y0 = r.y & ~1;
    const int x1 = std::min((r.x + r.width + 1) & ~1, width_limit), y1 = std::min((r.y + r.height + 1) & ~1, height_limit);
    return Region{x0, y0, x1 - x0, y1 - y0};
}

}  // namespace

void FramePlanner::create(const gl::Table& gl, GLint alignment) {
    alignment_ = alignment;
    buffer_ = gl::Buffer::create(gl, GL_UNIFORM_BUFFER, UniformArena::kCapacity);
}

FrameRegions FramePlanner::regions(const FrameInput& input, const TechniquePlan& plan) {
    const obscura_rect& rect = input.output_rect;
    FrameRegions r;
    r.whole = Region{0, 0, input.width, input.height};
    r.output = Region{rect.x, rect.y, rect.width, rect.height};
    r.ao = r.output.expanded(plan.apron, plan.apron, input.width, input.height);
    if (plan.ao_on_quads) r.ao = aligned_to_quads(r.ao, input.width, input.height);
    r.blur_x = r.output.expanded(0, plan.apron, input.width, input.height);
    r.normals = plan.normals_margin == TechniquePlan::kNormalsEverywhere
                    ? r.whole
                    : r.ao.expanded(plan.normals_margin, plan.normals_margin, input.width, input.height);
    return r;
}

FrameUniforms FramePlanner::begin(const FrameInput& input, const OutputTarget& target, const FrameRegions& regions,
                                  const TechniquePlan& plan) {
    arena_.reset(alignment_);
    base_ = base_constants(input, target, 1.0f / (4.0f * plan.radius * input.meters_to_view_units));
    FrameUniforms u;
    u.whole = frame_constants(regions.whole);
    u.ao = frame_constants(regions.ao);
    u.blur_x = frame_constants(regions.blur_x);
    u.output = frame_constants(regions.output);
    return u;
}

UniformRange FramePlanner::host_constants(const FrameInput& host, const OutputTarget& target,
                                          const TechniquePlan& plan, int shift, bool ao_reduced) {
    const obscura_rect& rect = host.output_rect;
    FrameConstants c =
        with_work_rect(base_constants(host, target, 1.0f / (4.0f * plan.radius * host.meters_to_view_units)),
                       Region{rect.x, rect.y, rect.width, rect.height});
    c.resolution[0] = shift;
    c.resolution[1] = ao_reduced ? 1 : 0;
    return arena_.push(c);
}

UniformRange FramePlanner::frame_constants(const Region& work) { return arena_.push(with_work_rect(base_, work)); }

}  // namespace obscura
