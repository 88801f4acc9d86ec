#include "passes/upsample.h"

#include "output_writer.h"          // image_format_qualifier
#include "passes/depth_prepare.h"  // HostDepthBinding, host_depth_variant

#include <cstdio>

namespace obscura {

Error UpsamplePass::prepare(const PassEnv& env, const FrameInput& host, bool bent_normals,
                            const TargetWrite& destination) {
    char defines[160];
    std::snprintf(defines, sizeof defines,
                  "DEPTH_LINEAR %d\nDEPTH_MULTISAMPLE %d\nOBSCURA_UPSAMPLE_BENT_NORMALS %d\nOBSCURA_UPSAMPLE_TARGET %d\n",
                  host.depth_linear ? 1 : 0, host.depth_multisample ? 1 : 0, bent_normals ? 1 : 0,
                  destination.format != 0 ? 1 : 0);
    Error error = target_variant(env, "upsample.comp", defines, destination, &programs_, &program_);
    if (error) return error;
    destination_ = destination;
    return allocate(env, host.width, host.height, bent_normals, destination.format == 0);
}

Error UpsamplePass::allocate(const PassEnv& env, int width, int height, bool bent_normals, bool own_result) {
    // Both results follow the host's size: a size change drops them together.
    const gl::Texture2D& sized = ao_ ? ao_ : bent_;
    if (sized && (sized.width() != width || sized.height() != height)) release();
    // The R16F result (the visibility the pass writes beside the bent normals when a debug view shows the reduced
    // grid) is made for the first such view and kept: a host that shows a debug inset beside its main view every frame
    // would otherwise free and make it twice a frame.
    if (own_result && !ao_) {
        ao_ = env.create_texture(GL_R16F, width, height);
        if (!ao_) return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d upsampled AO failed", width, height);
    }
    if (bent_normals != static_cast<bool>(bent_)) {
        bent_ = bent_normals ? env.create_texture(GL_RGBA16F, width, height) : gl::Texture2D();
        if (bent_normals && !bent_) {
            return Error::make(OBSCURA_STATUS_OUT_OF_MEMORY, "allocating the %dx%d upsampled bent normals failed",
                               width, height);
        }
    }
    return Error();
}

UpsampleConstants UpsamplePass::constants(const obscura_resolution_settings& settings, const FrameInput& reduced) {
    UpsampleConstants c = {};
    c.params[0] = 1.0f / settings.upsample_tolerance;
    c.params[1] = 1.0f / float(1 << reduced.resolution_shift);
    c.params[2] = 1.0f / float(reduced.width);
    c.params[3] = 1.0f / float(reduced.height);
    c.config[0] = reduced.width - 1;
    c.config[1] = reduced.height - 1;
    c.config[2] = reduced.resolution_shift;
    return c;
}

void UpsamplePass::run(const PassEnv& env, const UniformRange& frame, const UniformRange& pass, const FrameInput& host,
                       const FrameResources& resources, const gl::Texture2D& source, const gl::Texture2D* bent_source,
                       GLuint target_texture) {
    const gl::Table& gl = env.gl;
    const bool bent = bent_source != nullptr && bent_;
    gl.UseProgram(program_);
    env.bind_texture(OBSCURA_UNIT_LINEAR_DEPTH, GL_TEXTURE_2D, resources.linear_depth.name());
    env.bind_texture(OBSCURA_UNIT_NORMALS, GL_TEXTURE_2D, resources.normals.name());
    env.bind_texture(OBSCURA_UNIT_SOURCE, GL_TEXTURE_2D, source.name());
    if (destination_.format != 0) {
        bind_target_image(gl, OBSCURA_IMAGE_OUT0, target_texture, destination_);
    } else {
        gl.BindImageTexture(OBSCURA_IMAGE_OUT0, ao_.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    }
    if (bent) {
        env.bind_texture(OBSCURA_UNIT_BENT_SOURCE, GL_TEXTURE_2D, bent_source->name());
        gl.BindImageTexture(OBSCURA_IMAGE_OUT1, bent_.name(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    }
    env.bind_uniforms(OBSCURA_UBO_FRAME, frame);
    env.bind_uniforms(OBSCURA_UBO_PASS, pass);
    {
        HostDepthBinding depth(env, host);
        // One invocation per 2x2 quad in absolute coordinates (the rectangle grown to even ones).
        const obscura_rect& rect = host.output_rect;
        const int x0 = rect.x & ~1, y0 = rect.y & ~1;
        env.dispatch((rect.x + rect.width - x0 + 1) / 2, (rect.y + rect.height - y0 + 1) / 2, OBSCURA_UPSAMPLE_GROUP_X,
                     OBSCURA_UPSAMPLE_GROUP_Y);
    }
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void UpsamplePass::release() {
    ao_ = gl::Texture2D();
    bent_ = gl::Texture2D();
}

}  // namespace obscura
