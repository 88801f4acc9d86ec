#include "viewer_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "host_gl_program.h"

namespace obscura::viewer {
namespace {

constexpr const char* kFullscreenVertex = R"(#version 430 core
out vec2 v_uv;
void main() {
    // One triangle over the viewport: (0,0), (2,0), (0,2) in uv.
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    v_uv = p;
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Modes follow ViewMode. Lighting is deliberately plain (a grey albedo, one directional light in view space
// without shadows, a sky-blue ambient term) so that the AO on the ambient term is what the eye judges.
constexpr const char* kCompositeFragment = R"(#version 430 core
in vec2 v_uv;
out vec4 o_color;
layout(binding = 0) uniform sampler2D u_ao0;
layout(binding = 1) uniform sampler2D u_ao1;
layout(binding = 2) uniform sampler2D u_normals;  // the whole depth texture's size
layout(binding = 3) uniform sampler2D u_heat;
uniform int u_mode;
uniform float u_split;
uniform vec4 u_visible;   // the visible rectangle in the normal texture's uv: offset, scale
uniform int u_has_normals;
uniform int u_has_right;  // split: the right side has an image
uniform int u_has_heat;

vec3 sky(float v) { return mix(vec3(0.72, 0.80, 0.90), vec3(0.38, 0.52, 0.74), v); }

vec3 lit(vec3 n, float ao) {
    const vec3 light = normalize(vec3(0.35, 0.85, 0.40));
    const vec3 albedo = vec3(0.62);
    float diffuse = max(dot(n, light), 0.0);
    return albedo * (vec3(0.34, 0.38, 0.46) * ao + vec3(0.62, 0.58, 0.52) * diffuse);
}

void main() {
    vec4 n = u_has_normals != 0 ? texture(u_normals, u_visible.xy + v_uv * u_visible.zw) : vec4(0.0, 0.0, 1.0, 1.0);
    bool geometry = n.a > 0.5;
    float ao = texture(u_ao0, v_uv).r;
    vec3 color;
    if (u_mode == 0) {
        color = vec3(ao);
    } else if (u_mode == 1 || u_mode == 2) {
        color = geometry ? lit(normalize(n.xyz), u_mode == 1 ? ao : 1.0) : sky(v_uv.y);
    } else if (u_mode == 3) {
        bool right = v_uv.x >= u_split;
        float value = right ? (u_has_right != 0 ? texture(u_ao1, v_uv).r : 0.5) : ao;
        color = vec3(value);
        if (abs(v_uv.x - u_split) * float(textureSize(u_ao0, 0).x) < 1.0) color = vec3(1.0, 0.55, 0.1);
    } else {
        // The heat map; sky (left out of the metrics) in a pale blue-grey so that it is not read as 0 error.
        color = u_has_heat != 0 ? (geometry ? texture(u_heat, v_uv).rgb : vec3(0.74, 0.80, 0.88)) : vec3(ao);
    }
    // Lit views are linear radiance, shown with the display's gamma; AO, split and heat maps as values.
    bool radiance = u_mode == 1 || u_mode == 2;
    o_color = vec4(radiance ? pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)) : clamp(color, 0.0, 1.0), 1.0);
}
)";

std::string lower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

bool ends_with(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void set_texture_filtering(GLenum filter) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GLint(filter));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GLint(filter));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

// Uploads a 1- or 3-channel float image (rows bottom-up) into `texture` (R32F / RGB32F).
void upload_image(samples::HostTexture& texture, const samples::FloatImage& image) {
    if (!texture.get()) texture = samples::HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const bool rgb = image.channels == 3;
    glTexImage2D(GL_TEXTURE_2D, 0, rgb ? GL_RGB32F : GL_R32F, image.width, image.height, 0, rgb ? GL_RGB : GL_RED,
                 GL_FLOAT, image.pixels.data());
    set_texture_filtering(GL_LINEAR);
    glBindTexture(GL_TEXTURE_2D, 0);
}

// The heat map of |method - reference| with the sky (mask 0) in the composite's sky colour (kCompositeFragment):
// the composite tells sky by the normals' alpha, which a depth file has none of, so its sky would otherwise be
// painted as the heat of 0 error (white) although the metrics leave it out.
samples::FloatImage heat_map(const samples::FloatImage& method, const samples::FloatImage& reference,
                             const std::vector<uint8_t>& mask) {
    samples::FloatImage heat = samples::error_heat_map(method, reference);
    const float sky[3] = {0.74f, 0.80f, 0.88f};
    for (size_t i = 0; i < mask.size() && 3 * i + 2 < heat.pixels.size(); ++i) {
        if (!mask[i]) std::copy(sky, sky + 3, heat.pixels.begin() + std::ptrdiff_t(3 * i));
    }
    return heat;
}

ObscuraContextPtr create_context(obscura_get_proc_address_fn get_proc_address, bool software) {
    obscura_context_desc desc = {};
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = get_proc_address;
    desc.flags = software ? uint32_t(OBSCURA_CONTEXT_FLAG_SYNC_TIMING) : 0u;
    desc.log = [](obscura_log_level, obscura_status, const char* message, void*) {
        std::fprintf(stderr, "obscura: %s\n", message);
    };
    obscura_context* context = nullptr;
    const obscura_status status = obscura_create_context(&desc, &context);
    if (status != OBSCURA_STATUS_OK) {
        throw std::runtime_error(std::string("obscura_create_context: ") + obscura_status_string(status));
    }
    return ObscuraContextPtr(context);
}

samples::FloatImage average(const ReferenceJob& job) {
    samples::FloatImage out = job.sum;
    const float scale = job.traced_rays() > 0 ? 1.0f / float(job.traced_rays()) : 0.0f;
    for (float& v : out.pixels) v *= scale;
    return out;
}

}  // namespace

ViewerScene load_viewer_scene(const std::string& name_or_path) {
    ViewerScene scene;
    scene.name = name_or_path;
    if (ends_with(lower(name_or_path), ".pfm")) {
        samples::DepthFileOptions options;
        options.path = name_or_path;
        scene.depth_file = std::make_shared<const samples::RenderedScene>(samples::load_depth_file(options));
    } else {
        scene.mesh = samples::load_scene(name_or_path);
    }
    return scene;
}

const char* view_mode_name(ViewMode mode) {
    switch (mode) {
        case ViewMode::AoOnly: return "ao";
        case ViewMode::LitWithAo: return "lit";
        case ViewMode::LitWithoutAo: return "lit-no-ao";
        case ViewMode::Split: return "split";
        case ViewMode::ErrorMap: return "error";
    }
    return "?";
}

const char* comparison_name(Comparison comparison) {
    return comparison == Comparison::GeometryTruth ? "truth" : "reference";
}

void AoTexture::ensure(int w, int h, GLenum internal_format) {
    if (texture.get() && width == w && height == h && format == internal_format) return;
    texture = samples::HostTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, w, h);
    set_texture_filtering(GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    width = w;
    height = h;
    format = internal_format;
}

void ReferenceJob::start(const std::string& key, const obscura_settings& method, int rays) {
    *this = ReferenceJob();
    reference.struct_size = sizeof(obscura_settings);
    if (obscura_reference_settings_for(&method, &reference) != OBSCURA_STATUS_OK) return;
    key_ = key;
    total_rays_ = std::max(rays, 1);
}

void ObscuraContextDeleter::operator()(obscura_context* context) const { obscura_destroy_context(context); }

ViewerRenderer::ViewerRenderer(obscura_get_proc_address_fn get_proc_address, bool software)
    : context_(create_context(get_proc_address, software)),
      compare_context_(create_context(get_proc_address, software)) {
    // The contexts own their views, and are owned here from the start: a throw below (a view, the composite
    // program) destroys them.
    obscura_context* const contexts[2] = {context_.get(), compare_context_.get()};
    for (int slot = 0; slot < 2; ++slot) {
        if (obscura_create_view(contexts[slot], &views_[slot]) != OBSCURA_STATUS_OK) {
            throw std::runtime_error(std::string("obscura_create_view: ") + obscura_get_last_error(contexts[slot]));
        }
    }
    composite_ = samples::link_host_program(kFullscreenVertex, kCompositeFragment, "viewer composite");
    empty_vao_ = samples::HostVertexArray::create();
    const GLubyte* renderer = glGetString(GL_RENDERER);
    renderer_name_ = renderer ? reinterpret_cast<const char*>(renderer) : "?";
}

ViewerRenderer::~ViewerRenderer() {
    scene_.reset();
    // The members go in reverse order: the host's textures and program, then the contexts (views included).
}

void ViewerRenderer::render_scene(const ViewerScene& scene, const samples::Camera& camera, int width, int height,
                                  obscura_get_proc_address_fn get_proc_address) {
    if (scene.depth_file) {
        scene_ = scene.depth_file;  // loaded (and checked) when the scene was opened
    } else {
        samples::SceneRenderOptions options;
        options.width = std::max(width, 1);
        options.height = std::max(height, 1);
        options.camera = camera;
        options.get_proc_address = get_proc_address;
        scene_.reset();  // the last frame's textures go before this one's are made
        scene_ = std::make_shared<const samples::RenderedScene>(samples::render_scene(scene.mesh->mesh, options));
    }
    visible_width_ = scene_->frame().output_rect.width;
    visible_height_ = scene_->frame().output_rect.height;
}

bool ViewerRenderer::render_ao(int slot, const obscura_settings& settings, bool use_scene_normals) {
    if (!scene_) return false;
    ao_[slot].ensure(visible_width_, visible_height_, GL_R16F);
    return render_into(ao_[slot].texture.get(), settings, use_scene_normals, slot);
}

bool ViewerRenderer::render_into(GLuint texture, const obscura_settings& settings, bool use_scene_normals, int slot) {
    const samples::SceneFrame& frame = scene_->frame();
    obscura_input input = frame.make_input(use_scene_normals);
    if (slot >= 0) {
        const samples::SceneFrame* previous = previous_[slot] ? &*previous_[slot] : nullptr;
        // The frame index moves the methods' noise: it advances only while frames accumulate. Without accumulation
        // it stays 0 (as `obscura compare` and a host keep it), so a still view renders the same image every frame,
        // the image its error was measured on once per view.
        const bool accumulates = settings.temporal.enabled == OBSCURA_TOGGLE_ON;
        input = frame.make_input(use_scene_normals, previous, accumulates ? frame_index_[slot]++ : 0u);
        input.view = views_[slot];
        if (reset_history_[slot]) input.flags |= OBSCURA_INPUT_FLAG_RESET_HISTORY;
    }
    obscura_output output = {};
    output.struct_size = sizeof output;
    output.texture = texture;
    obscura_context* const context = slot == 0 ? context_.get() : compare_context_.get();
    const obscura_status status = obscura_render(context, &input, &settings, &output);
    if (status != OBSCURA_STATUS_OK) {
        // A refused frame leaves the view's history as it was: the reset it asked for stays due (a camera cut
        // followed by a refused frame must still cut the next one).
        last_error_ = std::string(obscura_status_string(status)) + ": " + obscura_get_last_error(context);
        return false;
    }
    if (slot >= 0) {
        reset_history_[slot] = false;
        previous_[slot] = frame;  // its camera, for the next frame's reprojection
    }
    last_error_.clear();
    return true;
}

void ViewerRenderer::reset_history() {
    for (int slot = 0; slot < 2; ++slot) {
        previous_[slot].reset();  // of the old scene or viewpoint: nothing to reproject from
        reset_history_[slot] = true;
    }
}

bool ViewerRenderer::step_reference(ReferenceJob& job, bool use_scene_normals) {
    if (!scene_ || !job.active() || job.done()) return false;
    chunk_.ensure(visible_width_, visible_height_, GL_R32F);
    // Chunks of kChunkRays, the last one what is left: exactly the rays asked for.
    const int rays = std::min(ReferenceJob::kChunkRays, job.total_rays_ - job.traced_rays_);
    obscura_settings chunk = job.reference;
    chunk.reference.rays = rays;
    chunk.reference.first_ray = job.traced_rays_;
    if (!render_into(chunk_.texture.get(), chunk, use_scene_normals)) {
        job.cancel();
        return false;
    }
    samples::FloatImage image = samples::read_texture_region(chunk_.texture.get(), 0, 0, chunk_.width, chunk_.height);
    if (job.sum.pixels.size() != image.pixels.size()) {
        job.sum = image;
        for (float& v : job.sum.pixels) v = 0.0f;
    }
    for (size_t i = 0; i < image.pixels.size(); ++i) job.sum.pixels[i] += image.pixels[i] * float(rays);
    job.traced_rays_ += rays;
    const samples::FloatImage reference = average(job);
    upload_image(reference_, reference);
    if (job.done()) measure_reference(job);
    return true;
}

void ViewerRenderer::measure_reference(ReferenceJob& job) {
    if (!job.done() || !ao_[0].texture.get()) return;
    const samples::FloatImage reference = average(job);
    job.method_image = samples::read_texture_region(ao_[0].texture.get(), 0, 0, ao_[0].width, ao_[0].height);
    const std::vector<uint8_t> mask = geometry_mask();
    job.metrics = samples::compare_images(job.method_image, reference, &mask);
    upload_image(heat_, heat_map(job.method_image, reference, mask));
}

void ViewerRenderer::upload_truth(const samples::FloatImage& visibility) { upload_image(truth_, visibility); }

samples::ErrorMetrics ViewerRenderer::compare_with_truth(const samples::FloatImage& truth,
                                                         const std::vector<uint8_t>& mask) {
    if (!ao_[0].texture.get()) throw std::runtime_error("no AO image to compare with the geometry truth");
    const samples::FloatImage method =
        samples::read_texture_region(ao_[0].texture.get(), 0, 0, ao_[0].width, ao_[0].height);
    const samples::ErrorMetrics metrics = samples::compare_images(method, truth, &mask);
    upload_image(truth_heat_, heat_map(method, truth, mask));
    return metrics;
}

std::vector<uint8_t> ViewerRenderer::geometry_mask() const {
    std::vector<uint8_t> mask(size_t(visible_width_) * size_t(visible_height_), 1);
    if (!scene_) return mask;
    const samples::SceneFrame& frame = scene_->frame();
    const obscura_rect& r = frame.output_rect;
    if (frame.normal_texture) {
        const samples::FloatImage normals = samples::read_texture_region(frame.normal_texture, r.x, r.y, r.width, r.height,
                                                                         samples::TextureReadFormat::Rgba);
        for (size_t i = 0; i < mask.size(); ++i) mask[i] = normals.pixels[4 * i + 3] > 0.5f ? 1 : 0;
    } else if (frame.depth_kind == OBSCURA_DEPTH_LINEAR_VIEW && frame.samples == 1) {
        // A depth file: positive view depth, sky stored as +infinity.
        const samples::FloatImage depth = samples::read_texture_region(frame.depth_texture, r.x, r.y, r.width, r.height);
        for (size_t i = 0; i < mask.size(); ++i) {
            const float d = depth.pixels[i];
            mask[i] = std::isfinite(d) && d > 0.0f ? 1 : 0;
        }
    }
    return mask;
}

GLuint ViewerRenderer::reference_texture(const ReferenceJob& job) const {
    return job.active() && job.traced_rays() > 0 ? reference_.get() : 0;
}

GLuint ViewerRenderer::reference_heat(const ReferenceJob& job) const { return job.done() ? heat_.get() : 0; }

void ViewerRenderer::composite(ViewMode mode, float split, GLuint right, GLuint heat) {
    const GLuint program = composite_.get();
    glUseProgram(program);
    const samples::SceneFrame* frame = scene_ ? &scene_->frame() : nullptr;
    const bool has_normals = frame && frame->normal_texture != 0;
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, ao_[0].texture.get());
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, right);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, has_normals ? frame->normal_texture : 0);
    glActiveTexture(GL_TEXTURE3);
    const bool has_heat = heat != 0;
    glBindTexture(GL_TEXTURE_2D, heat);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(glGetUniformLocation(program, "u_mode"), int(mode));
    glUniform1f(glGetUniformLocation(program, "u_split"), split);
    glUniform1i(glGetUniformLocation(program, "u_has_normals"), has_normals ? 1 : 0);
    glUniform1i(glGetUniformLocation(program, "u_has_right"), right ? 1 : 0);
    glUniform1i(glGetUniformLocation(program, "u_has_heat"), has_heat ? 1 : 0);
    if (frame) {
        const float w = float(frame->depth_width), h = float(frame->depth_height);
        glUniform4f(glGetUniformLocation(program, "u_visible"), float(frame->output_rect.x) / w,
                    float(frame->output_rect.y) / h, float(frame->output_rect.width) / w,
                    float(frame->output_rect.height) / h);
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(empty_vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    for (int unit = 3; unit >= 0; --unit) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        glBindTexture(GL_TEXTURE_2D, 0);
    }
    glUseProgram(0);
}

}  // namespace obscura::viewer
