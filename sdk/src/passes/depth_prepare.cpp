#include "passes/depth_prepare.h"

namespace obscura {

Error DepthPreparePass::prepare(const PassEnv& env, const FrameInput& input) {
    gl::Object& program = program_for(input);
    if (program) return Error();
    char defines[160];
    std::snprintf(defines, sizeof defines,
                  "DEPTH_LINEAR %d\nDEPTH_MULTISAMPLE %d\nOBSCURA_CPU_RASTERISER %d\nOBSCURA_NORMAL_SOURCE %d\n",
                  input.depth_linear ? 1 : 0, input.depth_multisample ? 1 : 0, env.cpu_renderer ? 1 : 0,
                  input.normal_mode);
    return env.build("depth_prepare.comp", defines, &program);
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

void DepthPreparePass::run(const PassEnv& env, const FrameInput& input, const UniformRange& frame,
                           FrameResources& resources) {
    const gl::Table& gl = env.gl;
    gl.UseProgram(program_for(input).name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, input.normal_texture);
    gl.BindImageTexture(OBSCURA_IMAGE_OUT0, resources.linear_depth.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    gl.BindImageTexture(OBSCURA_IMAGE_OUT1, resources.normals.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16_SNORM);
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    {
        HostDepthBinding depth(env, input);
        // CPU rasterisers: one invocation per block of texels (depth_prepare.comp).
        const int texels_per_invocation = env.cpu_renderer ? OBSCURA_DEPTH_PREPARE_CPU_BLOCK : 1;
        env.dispatch((input.width + texels_per_invocation - 1) / texels_per_invocation,
                     (input.height + texels_per_invocation - 1) / texels_per_invocation, OBSCURA_DEPTH_PREPARE_GROUP_X,
                     OBSCURA_DEPTH_PREPARE_GROUP_Y);
    }
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace obscura
