// Scene rasteriser: one draw of the whole mesh into a depth texture and a view-space normal
// texture. This is host code (what an engine's G-buffer pass does), not part of the SDK.
#include "demo_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "headless_gl.h"
#include "host_gl_objects.h"
#include "host_gl_program.h"
#include "image_io.h"

namespace obscura::samples {
namespace {

constexpr DepthFormat kAllDepthFormats[] = {DepthFormat::D32F, DepthFormat::D24, DepthFormat::D24S8};

const char* const kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_previous_position;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat4 u_previous_view_projection;
out vec3 v_view_normal;
out vec4 v_clip;
out vec4 v_previous_clip;
void main() {
    // The view matrix is rigid, so its upper 3x3 transforms normals too.
    v_view_normal = mat3(u_view) * a_normal;
    v_clip = u_projection * (u_view * vec4(a_position, 1.0));
    v_previous_clip = u_previous_view_projection * vec4(a_previous_position, 1.0);
    gl_Position = v_clip;
}
)";

// The clip positions interpolate perspective-correctly, so each fragment divides its own: the surface point's place
// in both frames.
const char* const kFragmentShader = R"(#version 330 core
in vec3 v_view_normal;
in vec4 v_clip;
in vec4 v_previous_clip;
uniform vec2 u_viewport_size;
layout(location = 0) out vec4 o_normal;
layout(location = 1) out vec2 o_motion;
void main() {
    // Facing the camera, as the geometry truth turns its normals: a surface seen from behind (a clockwise face, a
    // flipped vn, an open mesh) would otherwise hand the SDK a normal pointing into it.
    vec3 n = normalize(v_view_normal);
    o_normal = vec4(gl_FrontFacing ? n : -n, 1.0);
    o_motion = (v_previous_clip.xy / v_previous_clip.w - v_clip.xy / v_clip.w) * 0.5 * u_viewport_size;
}
)";

void throw_gl_error_if_any(const char* during) {
    const GLenum error = glGetError();
    if (error == GL_NO_ERROR) return;
    while (glGetError() != GL_NO_ERROR) {
    }
    char message[128];
    std::snprintf(message, sizeof message, "GL error 0x%04x while %s", error, during);
    throw std::runtime_error(message);
}

bool context_has_extension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const GLubyte* extension = glGetStringi(GL_EXTENSIONS, GLuint(i));
        if (extension && std::strcmp(reinterpret_cast<const char*>(extension), name) == 0) return true;
    }
    return false;
}

using ClipControlFn = void (*)(GLenum origin, GLenum depth);

// glClipControl when the context has it (GL 4.5 or ARB_clip_control), else nullptr. The pointer alone
// proves nothing: glvnd returns a stub for any name.
ClipControlFn find_clip_control(obscura_get_proc_address_fn get_proc_address) {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45 && !context_has_extension("GL_ARB_clip_control")) return nullptr;
    return reinterpret_cast<ClipControlFn>(get_proc_address("glClipControl"));
}

// Saves the GL state the rasteriser changes and restores it on destruction.
class SceneStateGuard {
public:
    explicit SceneStateGuard(ClipControlFn clip_control) : clip_control_(clip_control) {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
        glGetIntegerv(GL_RENDERBUFFER_BINDING, &renderbuffer_);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
        glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer_);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_2d_);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE, &texture_2d_multisample_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
        glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
        glGetBooleanv(GL_COLOR_WRITEMASK, color_mask_);
        glGetFloatv(GL_DEPTH_CLEAR_VALUE, &clear_depth_);
        glGetFloatv(GL_COLOR_CLEAR_VALUE, clear_color_);
        glGetIntegerv(GL_STENCIL_CLEAR_VALUE, &clear_stencil_);
        for (size_t i = 0; i < kCapabilities.size(); ++i) enabled_[i] = glIsEnabled(kCapabilities[i]);
        if (clip_control_) {
            glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_);
            glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_mode_);
        }
    }

    ~SceneStateGuard() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_framebuffer_));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_framebuffer_));
        glBindRenderbuffer(GL_RENDERBUFFER, GLuint(renderbuffer_));
        glUseProgram(GLuint(program_));
        glBindVertexArray(GLuint(vertex_array_));
        glBindBuffer(GL_ARRAY_BUFFER, GLuint(array_buffer_));
        glActiveTexture(GLenum(active_texture_));
        glBindTexture(GL_TEXTURE_2D, GLuint(texture_2d_));
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, GLuint(texture_2d_multisample_));
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
        glDepthFunc(GLenum(depth_func_));
        glDepthMask(depth_mask_);
        glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
        glClearDepth(clear_depth_);
        glClearColor(clear_color_[0], clear_color_[1], clear_color_[2], clear_color_[3]);
        glClearStencil(clear_stencil_);
        for (size_t i = 0; i < kCapabilities.size(); ++i) {
            if (enabled_[i]) glEnable(kCapabilities[i]);
            else glDisable(kCapabilities[i]);
        }
        if (clip_control_) clip_control_(GLenum(clip_origin_), GLenum(clip_depth_mode_));
    }

    SceneStateGuard(const SceneStateGuard&) = delete;
    SceneStateGuard& operator=(const SceneStateGuard&) = delete;

private:
    static constexpr std::array<GLenum, 6> kCapabilities = {GL_DEPTH_TEST, GL_BLEND,        GL_CULL_FACE,
                                                            GL_SCISSOR_TEST, GL_STENCIL_TEST, GL_MULTISAMPLE};
    ClipControlFn clip_control_;
    GLint draw_framebuffer_ = 0, read_framebuffer_ = 0, renderbuffer_ = 0, program_ = 0, vertex_array_ = 0;
    GLint array_buffer_ = 0, active_texture_ = GL_TEXTURE0, texture_2d_ = 0, texture_2d_multisample_ = 0;
    GLint viewport_[4] = {};
    GLint depth_func_ = GL_LESS;
    GLboolean depth_mask_ = GL_TRUE;
    GLboolean color_mask_[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    GLfloat clear_depth_ = 1.0f;
    GLfloat clear_color_[4] = {};
    GLint clear_stencil_ = 0;
    std::array<GLboolean, kCapabilities.size()> enabled_{};
    GLint clip_origin_ = 0, clip_depth_mode_ = 0;
};

HostProgram link_scene_program() { return link_host_program(kVertexShader, kFragmentShader, "scene"); }

HostTexture create_depth_texture(const SceneRenderOptions& options, int width, int height) {
    HostTexture texture = HostTexture::create();
    const GLenum format = depth_internal_format(options.depth_format);
    if (options.samples > 1) {
        glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, texture.get());
        glTexStorage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, options.samples, format, width, height, GL_TRUE);
    } else {
        glBindTexture(GL_TEXTURE_2D, texture.get());
        glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    return texture;
}

// A single-sample colour target (normals, motion vectors) read with nearest filtering.
HostTexture create_color_texture(GLenum internal_format, int width, int height) {
    HostTexture texture = HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

void require_complete(GLenum target, const char* what) {
    const GLenum status = glCheckFramebufferStatus(target);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        // The usual cause is an attachment GL refused to allocate (a texture past GL_MAX_TEXTURE_SIZE): its error is
        // named and drained (render_scene leaves no GL error behind, on failure either).
        GLint max_size = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
        char message[160];
        std::snprintf(message, sizeof message, "making the %s framebuffer (incomplete: status 0x%04x; GL_MAX_TEXTURE_SIZE %d)",
                      what, status, max_size);
        throw_gl_error_if_any(message);
        throw std::runtime_error(message);
    }
}

void check_sample_count(const SceneRenderOptions& options) {
    if (options.samples <= 1) return;
    GLint max_depth = 0, max_color = 0;
    glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &max_depth);
    glGetIntegerv(GL_MAX_SAMPLES, &max_color);
    if (options.samples > max_depth || (options.normals && options.samples > max_color)) {
        throw std::invalid_argument("MSAA " + std::to_string(options.samples) + " exceeds the context's limit of " +
                                    std::to_string(options.normals ? std::min(max_depth, max_color) : max_depth));
    }
}

struct DrawMatrices {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::mat4 previous_view_projection{1.0f};
    glm::vec2 viewport_size{1.0f};
};

// `previous` (may be null): the previous frame's vertices, positions and normals as `mesh` has them.
void draw_mesh(const SceneMesh& mesh, const SceneMesh* previous, const DrawMatrices& matrices) {
    HostProgram program = link_scene_program();
    HostVertexArray vertex_array = HostVertexArray::create();
    HostBuffer buffer = HostBuffer::create();
    HostBuffer previous_buffer;
    glBindVertexArray(vertex_array.get());
    glBindBuffer(GL_ARRAY_BUFFER, buffer.get());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertices.size() * sizeof(float)), mesh.vertices.data(),
                 GL_STATIC_DRAW);
    const GLsizei stride = 6 * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(3 * sizeof(float)));
    if (previous) {
        previous_buffer = HostBuffer::create();
        glBindBuffer(GL_ARRAY_BUFFER, previous_buffer.get());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(previous->vertices.size() * sizeof(float)), previous->vertices.data(),
                     GL_STATIC_DRAW);
    }
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride, nullptr);

    glUseProgram(program.get());
    const auto matrix = [&](const char* name, const glm::mat4& value) {
        glUniformMatrix4fv(glGetUniformLocation(program.get(), name), 1, GL_FALSE, glm::value_ptr(value));
    };
    matrix("u_view", matrices.view);
    matrix("u_projection", matrices.projection);
    matrix("u_previous_view_projection", matrices.previous_view_projection);
    glUniform2f(glGetUniformLocation(program.get(), "u_viewport_size"), matrices.viewport_size.x,
                matrices.viewport_size.y);
    glDrawArrays(GL_TRIANGLES, 0, mesh.vertex_count());
    // Unbind before the owners delete the objects; the state guard then restores the host's bindings.
    glUseProgram(0);
    glBindVertexArray(0);
}

}  // namespace

const char* depth_format_name(DepthFormat format) {
    switch (format) {
    case DepthFormat::D32F: return "d32f";
    case DepthFormat::D24: return "d24";
    case DepthFormat::D24S8: return "d24s8";
    }
    return "unknown";
}

DepthFormat parse_depth_format(const std::string& name) {
    std::string valid;
    for (DepthFormat format : kAllDepthFormats) {
        if (name == depth_format_name(format)) return format;
        valid += std::string(valid.empty() ? "" : ", ") + depth_format_name(format);
    }
    throw std::invalid_argument("unknown depth format '" + name + "' (valid: " + valid + ")");
}

GLenum depth_internal_format(DepthFormat format) {
    switch (format) {
    case DepthFormat::D32F: return GL_DEPTH_COMPONENT32F;
    case DepthFormat::D24: return GL_DEPTH_COMPONENT24;
    case DepthFormat::D24S8: return GL_DEPTH24_STENCIL8;
    }
    return GL_DEPTH_COMPONENT32F;
}

obscura_input SceneFrame::make_input(bool use_normals, const SceneFrame* previous, uint32_t frame_index) const {
    obscura_input input{};
    input.struct_size = sizeof input;
    input.depth_texture = depth_texture;
    input.depth_kind = depth_kind;
    input.depth_width = depth_width;
    input.depth_height = depth_height;
    input.output_rect = output_rect;
    std::memcpy(input.projection, projection, sizeof input.projection);
    input.projection_layout = OBSCURA_MATRIX_COLUMN_MAJOR;
    input.clip_depth = clip_depth;
    input.meters_to_view_units = 1.0f;
    input.normal_texture = use_normals ? normal_texture : 0;
    // World -> clip, the depth's: the projection (guard band included) after the view.
    auto view_projection = [](const SceneFrame& frame, float out[16]) {
        const glm::mat4 m = glm::make_mat4(frame.projection) * frame.view;
        std::memcpy(out, glm::value_ptr(m), sizeof(float) * 16);
    };
    view_projection(*this, input.view_projection);
    view_projection(previous ? *previous : *this, input.previous_view_projection);
    input.frame_index = frame_index;
    if (motion_texture != 0) {
        input.motion_vector_texture = motion_texture;
        input.motion_vector_units = OBSCURA_MOTION_PIXELS;
    }
    return input;
}

RenderedScene::~RenderedScene() {
    destroy();
}

RenderedScene::RenderedScene(RenderedScene&& other) noexcept : frame_(std::exchange(other.frame_, SceneFrame{})) {}

RenderedScene& RenderedScene::operator=(RenderedScene&& other) noexcept {
    if (this != &other) {
        destroy();
        frame_ = std::exchange(other.frame_, SceneFrame{});
    }
    return *this;
}

void RenderedScene::destroy() {
    const GLuint textures[] = {frame_.depth_texture, frame_.normal_texture, frame_.motion_texture};
    for (GLuint texture : textures) {
        if (texture != 0) glDeleteTextures(1, &texture);
    }
    frame_.depth_texture = 0;
    frame_.normal_texture = 0;
    frame_.motion_texture = 0;
}

RenderedScene render_scene(const SceneMesh& mesh, const SceneRenderOptions& options) {
    if (mesh.vertex_count() < 3 || mesh.vertices.size() % 6 != 0) {
        throw std::invalid_argument("render_scene: the mesh has no triangles");
    }
    const GuardBandLayout layout = guard_band_layout(options.width, options.height, options.guard_band);
    check_sample_count(options);
    if (options.motion_vectors && options.samples > 1) {
        throw std::invalid_argument("render_scene: motion vectors need a single-sample depth (MSAA " +
                                    std::to_string(options.samples) + ")");
    }
    if (options.previous_mesh && options.previous_mesh->vertices.size() != mesh.vertices.size()) {
        throw std::invalid_argument("render_scene: the previous frame's mesh has another vertex count");
    }
    const bool reversed = options.projection == ProjectionKind::ReversedZ ||
                          options.projection == ProjectionKind::ReversedInfinite;
    const obscura_get_proc_address_fn get_proc_address =
        options.get_proc_address ? options.get_proc_address : &HeadlessGL::get_proc_address;
    const ClipControlFn clip_control = find_clip_control(get_proc_address);
    const bool zero_to_one = reversed && options.use_clip_control && clip_control != nullptr;

    const Projection projection = make_projection(options.projection, options.camera,
                                                  float(options.width) / float(options.height), zero_to_one);
    const glm::mat4 widened = widen_for_guard_band(projection.matrix, layout);
    const glm::mat4 view = options.camera.view();
    DrawMatrices matrices;
    matrices.view = view;
    matrices.projection = widened;
    matrices.previous_view_projection = widened * view;
    matrices.viewport_size = glm::vec2(float(layout.depth_width), float(layout.depth_height));
    if (options.previous_camera) {
        const Projection previous = make_projection(options.projection, *options.previous_camera,
                                                    float(options.width) / float(options.height), zero_to_one);
        matrices.previous_view_projection = widen_for_guard_band(previous.matrix, layout) * options.previous_camera->view();
    }

    SceneStateGuard state(clip_control);
    HostTexture depth = create_depth_texture(options, layout.depth_width, layout.depth_height);
    HostTexture normals = options.normals ? create_color_texture(GL_RGBA16F, layout.depth_width, layout.depth_height)
                                          : HostTexture();
    // Multisampled normals are drawn into a renderbuffer and resolved into `normals`.
    HostRenderbuffer multisampled_normals;
    if (options.normals && options.samples > 1) {
        multisampled_normals = HostRenderbuffer::create();
        glBindRenderbuffer(GL_RENDERBUFFER, multisampled_normals.get());
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, options.samples, GL_RGBA16F, layout.depth_width,
                                         layout.depth_height);
    }

    HostTexture motion = options.motion_vectors ? create_color_texture(GL_RG32F, layout.depth_width, layout.depth_height)
                                                : HostTexture();

    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    const bool has_stencil = options.depth_format == DepthFormat::D24S8;
    glFramebufferTexture(GL_FRAMEBUFFER, has_stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                         depth.get(), 0);
    if (multisampled_normals.get() != 0) {
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, multisampled_normals.get());
    } else if (options.normals) {
        glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, normals.get(), 0);
    }
    if (options.motion_vectors) glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, motion.get(), 0);
    const GLenum draw_buffers[2] = {options.normals ? GL_COLOR_ATTACHMENT0 : GLenum(GL_NONE),
                                    options.motion_vectors ? GL_COLOR_ATTACHMENT1 : GLenum(GL_NONE)};
    glDrawBuffers(2, draw_buffers);
    glReadBuffer(draw_buffers[0]);
    require_complete(GL_FRAMEBUFFER, "scene");

    if (clip_control) clip_control(GL_LOWER_LEFT, zero_to_one ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    glViewport(0, 0, layout.depth_width, layout.depth_height);
    for (GLenum capability : {GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST, GL_STENCIL_TEST}) glDisable(capability);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_MULTISAMPLE);
    glDepthFunc(projection.reversed_z ? GL_GREATER : GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearDepth(projection.clear_depth());
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | (has_stencil ? GL_STENCIL_BUFFER_BIT : 0));
    draw_mesh(mesh, options.previous_mesh, matrices);

    if (multisampled_normals.get() != 0) {
        HostFramebuffer resolve = HostFramebuffer::create();
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve.get());
        glFramebufferTexture(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, normals.get(), 0);
        require_complete(GL_DRAW_FRAMEBUFFER, "normal resolve");
        glBlitFramebuffer(0, 0, layout.depth_width, layout.depth_height, 0, 0, layout.depth_width,
                          layout.depth_height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    throw_gl_error_if_any("rasterising the scene");

    SceneFrame frame;
    frame.depth_target = options.samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    frame.depth_internal_format = depth_internal_format(options.depth_format);
    frame.samples = options.samples > 1 ? options.samples : 1;
    frame.depth_width = layout.depth_width;
    frame.depth_height = layout.depth_height;
    frame.output_rect = layout.output_rect;
    std::memcpy(frame.projection, glm::value_ptr(widened), sizeof frame.projection);
    frame.clip_depth = projection.clip_depth;
    frame.near_plane = projection.near_plane;
    frame.far_plane = projection.far_plane;
    frame.reversed_z = projection.reversed_z;
    frame.infinite_far = projection.infinite_far;
    frame.orthographic = projection.orthographic;
    frame.view = view;
    // Hand the names over only once nothing can throw any more.
    frame.depth_texture = depth.release();
    frame.normal_texture = normals.release();
    frame.motion_texture = motion.release();
    return RenderedScene(frame);
}

RenderedScene render_demo_scene(const SceneRenderOptions& options) {
    return render_scene(build_demo_scene_mesh(options.ceiling), options);
}


std::vector<uint8_t> read_geometry_mask(const SceneFrame& frame) {
    if (frame.samples > 1 || frame.depth_target != GL_TEXTURE_2D) {
        throw std::runtime_error("read_geometry_mask: the depth texture is multisampled (read the normals' alpha)");
    }
    const obscura_rect& rect = frame.output_rect;
    const bool linear = frame.depth_kind == OBSCURA_DEPTH_LINEAR_VIEW;
    const FloatImage depth = read_texture_region(frame.depth_texture, rect.x, rect.y, rect.width, rect.height,
                                                 linear ? TextureReadFormat::Red : TextureReadFormat::Depth);
    const float sky = frame.reversed_z ? 0.0f : 1.0f;
    std::vector<uint8_t> mask(depth.pixels.size());
    for (size_t i = 0; i < mask.size(); ++i) {
        const float value = depth.pixels[i];
        mask[i] = linear ? uint8_t(std::isfinite(value) && value > 0.0f) : uint8_t(value != sky);
    }
    return mask;
}

FloatImage read_view_depth(const SceneFrame& frame, const obscura_rect& region) {
    if (frame.samples > 1 || frame.depth_target != GL_TEXTURE_2D) {
        throw std::runtime_error("read_view_depth: the depth texture is multisampled");
    }
    const bool linear = frame.depth_kind == OBSCURA_DEPTH_LINEAR_VIEW;
    FloatImage depth = read_texture_region(frame.depth_texture, region.x, region.y, region.width, region.height,
                                           linear ? TextureReadFormat::Red : TextureReadFormat::Depth);
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(glm::make_mat4(frame.projection)));
    const bool zero_to_one = frame.clip_depth == OBSCURA_CLIP_DEPTH_ZERO_TO_ONE;
    const float sky = frame.reversed_z ? 0.0f : 1.0f;
    for (float& value : depth.pixels) {
        if (linear ? !(std::isfinite(value) && value > 0.0f) : value == sky) {
            value = std::numeric_limits<float>::infinity();
            continue;
        }
        if (linear) continue;
        // Window depth -> NDC z -> view space; the view depth does not depend on x and y for these projections.
        const double ndc_z = zero_to_one ? double(value) : 2.0 * double(value) - 1.0;
        const glm::dvec4 view = inverse * glm::dvec4(0.0, 0.0, ndc_z, 1.0);
        value = float(-view.z / view.w);
    }
    return depth;
}

}  // namespace obscura::samples
