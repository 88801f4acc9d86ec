#include "ao_render.h"

#include <algorithm>
#include <chrono>
#include <map>

#include "obscura_session.h"

namespace obscura::cli {

AoTarget::AoTarget(int width, int height, GLenum internal_format)
    : texture_(samples::HostTexture::create()), width_(width), height_(height), internal_format_(internal_format) {
    GLint previous = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous);
    glBindTexture(GL_TEXTURE_2D, texture_.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, GLuint(previous));
}

samples::FloatImage AoTarget::read() const {
    const bool rgba = internal_format_ == GL_RGBA8 || internal_format_ == GL_RGBA16F || internal_format_ == GL_RGBA32F;
    return samples::read_texture_region(texture_.get(), 0, 0, width_, height_,
                                        rgba ? samples::TextureReadFormat::Rgba : samples::TextureReadFormat::Red);
}

void render_ao(const ObscuraSession& session, const AoRenderRequest& request) {
    obscura_input input = request.scene->make_input(request.use_normals, request.previous_scene, request.frame_index);
    if (request.reset_history) input.flags |= OBSCURA_INPUT_FLAG_RESET_HISTORY;
    input.view = request.view;
    if (!request.use_motion_vectors) input.motion_vector_texture = 0;
    obscura_output output{};
    output.struct_size = sizeof output;
    output.texture = request.target->texture();
    output.bent_normal_texture = request.bent_target ? request.bent_target->texture() : 0;
    output.debug_view = request.debug_view;
    session.check(obscura_render(session.get(), &input, request.settings, &output), "obscura_render");
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const size_t middle = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + long(middle), values.end());
    double result = values[middle];
    if (values.size() % 2 == 0) result = 0.5 * (result + *std::max_element(values.begin(), values.begin() + long(middle)));
    return result;
}

TimingRow TimingSummary::sdk_total() const {
    for (const TimingRow& row : passes) {
        if (row.label == "total") return row;
    }
    TimingRow none;
    none.label = "total";
    return none;
}

FramePlan quick_frame_plan(obscura_method method) {
    FramePlan plan;
    if (method == OBSCURA_METHOD_REFERENCE) {
        plan.warmup = 0;
        plan.frames = 1;
    }
    return plan;
}

void warm_up(const ObscuraSession& session, const AoRenderRequest& request) {
    obscura_settings settings = *request.settings;
    if (settings.method == OBSCURA_METHOD_REFERENCE) settings.reference.rays = 1;
    AoRenderRequest warm = request;
    warm.settings = &settings;
    session.check(obscura_prepare(session.get(), request.scene->depth_width, request.scene->depth_height, &settings),
                  "obscura_prepare");
    render_ao(session, warm);
    glFinish();
}

namespace {

TimingRow summarise(const std::string& label, const std::vector<double>& values) {
    TimingRow row;
    row.label = label;
    row.samples = values.size();
    if (!values.empty()) {
        row.median_ms = median(values);
        row.min_ms = *std::min_element(values.begin(), values.end());
    }
    return row;
}

// Collects obscura_get_timings once per new frame index, keeping the labels in the order the SDK
// reports them. Frames rendered before start() (another method's, say) are never counted.
class PassTimes {
public:
    void start(obscura_context* context) {
        uint32_t count = 0;
        obscura_get_timings(context, nullptr, 0, &count, &last_frame_);
    }
    void collect(obscura_context* context) {
        obscura_timing timings[64];
        uint32_t count = 0;
        uint64_t frame = 0;
        if (obscura_get_timings(context, timings, 64, &count, &frame) != OBSCURA_OK) return;
        if (count == 0 || frame <= last_frame_) return;
        last_frame_ = frame;
        ++frames_;
        for (uint32_t i = 0; i < std::min<uint32_t>(count, 64); ++i) {
            const std::string label = timings[i].label ? timings[i].label : "?";
            auto found = values_.find(label);
            if (found == values_.end()) {
                order_.push_back(label);
                found = values_.emplace(label, std::vector<double>()).first;
            }
            found->second.push_back(timings[i].milliseconds);
        }
    }
    int frames() const { return frames_; }
    std::vector<TimingRow> rows() const {
        std::vector<TimingRow> result;
        for (const std::string& label : order_) result.push_back(summarise(label, values_.at(label)));
        return result;
    }

private:
    uint64_t last_frame_ = 0;
    int frames_ = 0;
    std::vector<std::string> order_;
    std::map<std::string, std::vector<double>> values_;
};

}  // namespace

TimingSummary time_frames(const ObscuraSession& session, const AoRenderRequest& request, int warmup, int frames,
                          const AoRenderRequest* alternate) {
    session.check(obscura_prepare(session.get(), request.scene->depth_width, request.scene->depth_height,
                                  request.settings),
                  "obscura_prepare");
    int rendered = 0;
    auto next = [&]() -> const AoRenderRequest& { return alternate && rendered++ % 2 == 1 ? *alternate : request; };
    for (int i = 0; i < warmup; ++i) render_ao(session, next());
    glFinish();

    PassTimes pass_times;
    pass_times.start(session.get());
    std::vector<double> wall;
    for (int i = 0; i < frames; ++i) {
        const AoRenderRequest& frame = next();
        const auto start = std::chrono::steady_clock::now();
        render_ao(session, frame);
        glFinish();
        const auto end = std::chrono::steady_clock::now();
        wall.push_back(std::chrono::duration<double, std::milli>(end - start).count());
        // After glFinish this frame's timer queries are complete (sync timing reports at once).
        pass_times.collect(session.get());
    }

    TimingSummary summary;
    summary.passes = pass_times.rows();
    summary.wall = summarise("wall", wall);
    session.check(obscura_get_memory_usage(session.get(), &summary.memory_bytes), "obscura_get_memory_usage");
    return summary;
}

}  // namespace obscura::cli
