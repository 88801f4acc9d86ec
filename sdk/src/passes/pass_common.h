// What every pass needs from the context, and the small helpers they share (binding a texture with the
// SDK's sampler, binding uniform ranges, dispatching over a 2D region).
#ifndef OBSCURA_PASS_COMMON_H
#define OBSCURA_PASS_COMMON_H

#include <cstring>

#include "common/shader_interface.h"
#include "error.h"
#include "gl/gl_objects.h"
#include "gl/program.h"
#include "host_allocator.h"

namespace obscura {

// Per-size GPU resources every method shares; all cover the whole depth texture. A technique's own
// resources live in the technique (sdk/src/methods/).
struct FrameResources {
    int width = 0, height = 0;
    gl::Texture2D linear_depth; // R32F positive view depth, OBSCURA_SKY_DEPTH for sky; levels above 0: a z pyramid
    gl::Texture2D normals;      // RG16_SNORM octahedral view-space normals
    // The working textures below exist only where the technique's plan uses them (TechniquePlan::uses_*): else empty.
    gl::Texture2D ao;           // R16F visibility before the reconstruction
    gl::Texture2D blur_temp;    // R16F after a separable reconstruction's horizontal pass
    gl::Texture2D ao_blurred;   // R16F final visibility (not where the last pass writes the host's target)
    uint64_t bytes() const {
        return linear_depth.bytes() + normals.bytes() + ao.bytes() + blur_temp.bytes() + ao_blurred.bytes();
    }
};

struct UniformRange {
    GLintptr offset = 0;
    GLsizeiptr size = 0;
};

// Collects one frame's uniform blocks in CPU memory, uploads them in one call, hands out ranges.
class UniformArena {
public:
    static constexpr size_t kCapacity = 16384;
    void reset(GLint alignment) {
        used_ = 0;
        alignment_ = alignment > 0 ? size_t(alignment) : 256;
    }
    template <class Block>
    UniformRange push(const Block& block) {
        static_assert(sizeof(Block) % 16 == 0, "std140 blocks here hold only vec4/ivec4 members");
        size_t offset = (used_ + alignment_ - 1) / alignment_ * alignment_;
        if (offset + sizeof(Block) > kCapacity) return {};  // cannot happen with the SDK's fixed pass count
        std::memcpy(bytes_ + offset, &block, sizeof(Block));
        used_ = offset + sizeof(Block);
        return {GLintptr(offset), GLsizeiptr(sizeof(Block))};
    }
    // Orphans and refills the buffer so the driver never waits on the previous frame's reads.
    void upload(const gl::Table& gl, GLuint buffer) const {
        gl.BindBuffer(GL_UNIFORM_BUFFER, buffer);
        gl.BufferData(GL_UNIFORM_BUFFER, GLsizeiptr(kCapacity), nullptr, GL_STREAM_DRAW);
        gl.BufferSubData(GL_UNIFORM_BUFFER, 0, GLsizeiptr(used_), bytes_);
    }

private:
    alignas(16) unsigned char bytes_[kCapacity] = {};
    size_t used_ = 0;
    size_t alignment_ = 256;
};

struct PassEnv {
    const gl::Table& gl;
    const AllocatorCallbacks& alloc;
    obscura_log_fn log;
    void* log_user_data;
    GLuint sampler;         // nearest, clamp, compare off
    GLuint sampler_mipmap;  // the same with nearest MIP selection (texelFetch of the z pyramid's levels)
    GLuint uniform_buffer;  // the UniformArena's buffer
    bool cpu_renderer;      // llvmpipe and the like: no idle lanes, so extra parallelism only adds work

    Error build(const char* entry, const char* defines, gl::Object* program) const {
        return gl::build_compute_program(gl, entry, defines, alloc, log, log_user_data, program);
    }
    void bind_texture(int unit, GLenum target, GLuint texture) const {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        gl.BindTexture(target, texture);
        gl.BindSampler(GLuint(unit), target == GL_TEXTURE_2D_MULTISAMPLE ? 0 : sampler);
    }
    void bind_texture_mipmapped(int unit, GLuint texture) const {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        gl.BindTexture(GL_TEXTURE_2D, texture);
        gl.BindSampler(GLuint(unit), sampler_mipmap);
    }
    void bind_uniforms(GLuint binding, const UniformRange& range) const {
        gl.BindBufferRange(GL_UNIFORM_BUFFER, binding, uniform_buffer, range.offset, range.size);
    }
    // A texture of the SDK's own. Creating one binds it on the active unit: make that a unit the StateGuard
    // restores (obscura_prepare runs with the host's active unit, e.g. GL_TEXTURE5).
    gl::Texture2D create_texture(GLenum internal_format, int width, int height, int levels = 1) const {
        gl.ActiveTexture(GLenum(GL_TEXTURE0 + OBSCURA_UNIT_SOURCE));
        return gl::Texture2D::create(gl, internal_format, width, height, levels);
    }
    // A working texture that the configuration `needed` or not: kept at width x height, created at that size, or
    // freed (so the memory report holds what the configuration uses). False only when a needed one failed.
    bool fit_texture(gl::Texture2D* texture, bool needed, GLenum internal_format, int width, int height) const {
        if (!needed) {
            *texture = gl::Texture2D();
            return true;
        }
        if (!*texture || texture->width() != width || texture->height() != height) {
            *texture = create_texture(internal_format, width, height);
        }
        return static_cast<bool>(*texture);
    }
    void dispatch(int width, int height, int group_x, int group_y) const {
        if (width <= 0 || height <= 0) return;
        gl.DispatchCompute(GLuint((width + group_x - 1) / group_x), GLuint((height + group_y - 1) / group_y), 1);
    }
};

// A region of the depth texture: x, y, width, height.
struct Region {
    int x = 0, y = 0, width = 0, height = 0;
    // Grows by `margin` on the chosen axes, clamped to a width x height texture.
    Region expanded(int margin_x, int margin_y, int width_limit, int height_limit) const {
        Region r;
        r.x = x - margin_x < 0 ? 0 : x - margin_x;
        r.y = y - margin_y < 0 ? 0 : y - margin_y;
        int right = x + width + margin_x > width_limit ? width_limit : x + width + margin_x;
        int top = y + height + margin_y > height_limit ? height_limit : y + height + margin_y;
        r.width = right - r.x;
        r.height = top - r.y;
        return r;
    }
};

// `frame` with its work rectangle (the region the pass computes) set to `work`.
inline FrameConstants with_work_rect(FrameConstants frame, const Region& work) {
    frame.work_rect[0] = work.x;
    frame.work_rect[1] = work.y;
    frame.work_rect[2] = work.width;
    frame.work_rect[3] = work.height;
    return frame;
}

}  // namespace obscura

#endif  // OBSCURA_PASS_COMMON_H
