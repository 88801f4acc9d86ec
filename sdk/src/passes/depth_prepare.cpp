#include "passes/depth_prepare.h"

#include <algorithm>
#include <cstdio>

namespace obscura {

namespace {

// `value` rounded down (up) to a multiple of `block`.
int round_down(int value, int block) { return value / block * block; }
int round_up(int value, int block) { return (value + block - 1) / block * block; }

}  // namespace

DepthPrepareRects depth_prepare_rects(const Region& whole, const Region& normals, int block) {
    const int right = whole.x + whole.width, top = whole.y + whole.height;
    Region n;
    n.x = std::max(whole.x, round_down(normals.x, block));
    n.y = std::max(whole.y, round_down(normals.y, block));
    n.width = std::min(right, round_up(normals.x + normals.width, block)) - n.x;
    n.height = std::min(top, round_up(normals.y + normals.height, block)) - n.y;
    DepthPrepareRects rects;
    rects.with_normals = n;
    const Region strips[DepthPrepareRects::kMaxDepthOnly] = {
        {whole.x, whole.y, whole.width, n.y - whole.y},                  // below (lower y)
        {whole.x, n.y + n.height, whole.width, top - (n.y + n.height)},  // above
        {whole.x, n.y, n.x - whole.x, n.height},                         // left
        {n.x + n.width, n.y, right - (n.x + n.width), n.height},         // right
    };
    for (const Region& strip : strips) {
        if (strip.width > 0 && strip.height > 0) rects.depth_only[rects.depth_only_count++] = strip;
    }
    return rects;
}

Error DepthPreparePass::prepare(const PassEnv& env, const FrameInput& input) {
    const auto build = [&](gl::Object& program, int with_normals, int normal_source) {
        if (program) return Error();
        char defines[192];
        std::snprintf(defines, sizeof defines,
                      "DEPTH_LINEAR %d\nDEPTH_MULTISAMPLE %d\nOBSCURA_CPU_RASTERISER %d\nOBSCURA_NORMAL_SOURCE %d\n"
                      "OBSCURA_DEPTH_PREPARE_NORMALS %d\n",
                      input.depth_linear ? 1 : 0, input.depth_multisample ? 1 : 0, env.cpu_renderer ? 1 : 0,
                      normal_source, with_normals);
        return env.build("depth_prepare.comp", defines, &program);
    };
    Error error = build(program_for(input), 1, input.normal_mode);
    // The linear depth alone reads no normals: one variant per host depth kind.
    if (!error) error = build(depth_only_programs_[host_depth_variant(input)], 0, OBSCURA_NORMALS_RECONSTRUCT);
    return error;
}

HostDepthBinding::HostDepthBinding(const PassEnv& env, const FrameInput& input) : env_(env), input_(input) {
    const GLenum target = input.depth_multisample ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    env.bind_texture(OBSCURA_UNIT_DEPTH, target, input.depth_texture);
    if (input.host_depth_stencil_mode) {
        env.gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_DEPTH));
        env.gl.TexParameteri(target, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
    }
}

HostDepthBinding::~HostDepthBinding() {
    if (!input_.host_depth_stencil_mode) return;
    const GLenum target = input_.depth_multisample ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    env_.gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_DEPTH));
    env_.gl.TexParameteri(target, GL_DEPTH_STENCIL_TEXTURE_MODE, input_.host_depth_stencil_mode);
}

void DepthPreparePass::run(const PassEnv& env, const FrameInput& input, const DepthPrepareRects& rects,
                           const DepthPrepareUniforms& uniforms, FrameResources& resources) {
    const gl::Table& gl = env.gl;
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, input.normal_texture);
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, resources.linear_depth.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    gl.BindImageTexture(OBSCURA_IMAGE_OUT1, resources.normals.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16_SNORM);
    {
        HostDepthBinding depth(env, input);
        const int texels = block(env);
        const auto dispatch = [&](const Region& rect, const UniformRange& frame) {
            env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
            env.dispatch((rect.width + texels - 1) / texels, (rect.height + texels - 1) / texels,
                         OBSCURA_DEPTH_PREPARE_GROUP_X, OBSCURA_DEPTH_PREPARE_GROUP_Y);
        };
        gl.UseProgram(program_for(input).name());
        dispatch(rects.with_normals, uniforms.with_normals);
        if (rects.depth_only_count > 0) gl.UseProgram(depth_only_programs_[host_depth_variant(input)].name());
        for (int i = 0; i < rects.depth_only_count; ++i) dispatch(rects.depth_only[i], uniforms.depth_only[i]);
    }
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
