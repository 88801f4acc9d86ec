#include "viewer_app.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <optional>
#include <stdexcept>
#include <vector>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "method_spec_parser.h"
#include "settings_document.h"
#include "viewer_camera.h"
#include "viewer_presets.h"
#include "viewer_truth.h"

namespace obscura::viewer {
namespace {

constexpr float kPanelWidth = 390.0f;
constexpr size_t kHistory = 240;
// The geometry truth restarts once the view has held still this long (seconds): orbiting does not start (and
// cancel) a job per frame, and a cancelled worker has long returned when the next one is started.
constexpr double kTruthRestartDelay = 0.25;
constexpr int kTruthBatchRays = 8;  // rays per pixel per published batch of the geometry truth
const char* const kTruthUnavailable =
    "The geometry truth traces rays against the scene's triangles: a depth file (.pfm) has none. "
    "Open a built-in scene or an .obj to compare against it.";

// A line of explanation, wrapped to the panel, in the dimmed text colour.
void note(const char* text) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", text);
    ImGui::PopStyleColor();
}

double sky_fraction(const samples::ErrorMetrics& metrics) {
    return metrics.pixels_total > 0 ? 1.0 - double(metrics.pixels) / double(metrics.pixels_total) : 0.0;
}

// Temporal accumulation changes the method's image from frame to frame with the view held still: its metrics are
// measured again each frame rather than once per view (its first, unconverged frame).
bool accumulates(const obscura_settings& settings) { return settings.temporal.enabled == OBSCURA_TOGGLE_ON; }

obscura_gl_function glfw_proc(const char* name) { return reinterpret_cast<obscura_gl_function>(glfwGetProcAddress(name)); }

std::vector<obscura_method> methods() {
    std::vector<obscura_method> out;
    for (int m = OBSCURA_METHOD_HBAO; m < OBSCURA_METHOD_COUNT_; ++m) out.push_back(obscura_method(m));
    return out;
}

// The method's rows and the shared ones (temporal accumulation, resolution).
std::vector<obscura_setting_info> infos_of(obscura_method method) {
    try {
        return samples::setting_infos(method);
    } catch (const std::exception&) {
        return {};
    }
}


// A bad argument found once the window is open (a --viewpoint the scene does not have): exit 2, as the
// command line's usage errors.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// One method's panel state: its settings and the text boxes of save/load, copy-as-C and the falloff table's
// file.
struct MethodPanel {
    obscura_settings settings{};
    std::string path;
    std::string table_path;
    std::string c_code;
    std::string message;
};

struct TimingState {
    std::vector<std::pair<std::string, float>> passes;  // latest, "total" first
    std::deque<float> total_history, frame_history;
    uint64_t frame_index = 0;
    uint64_t memory_bytes = 0;
};

class ViewerApp {
public:
    explicit ViewerApp(const ViewerOptions& options) : options_(options) {}
    int run();

private:
    void open_scene(const std::string& name);
    void handle_input();
    void build_panel();
    bool method_panel(const char* id, MethodPanel& panel);
    void timings_panel();
    void comparison_panel();
    void reference_section();
    void truth_section();
    void metrics_text(const samples::ErrorMetrics& metrics, const std::string& against, const char* short_name);
    void update_timings();
    // The geometry truth for the current frame: (re)starts the worker when the view, the size or the falloff
    // changed, uploads its newest estimate and measures the method against it. `wait` (screenshot mode, the
    // frame before the last, so that the last frame's panel shows the result): waits for it to complete.
    // Not `wanted` (another view or comparison): only cancels a job that is of another view.
    void update_truth(bool wanted, bool wait);
    bool truth_available() const { return scene_.mesh.has_value(); }
    std::string truth_key(const samples::TruthView& view) const;
    std::string comparison_label() const;
    // The captions over the scene area; scene_x and width in ImGui points (not framebuffer pixels).
    void draw_scene_caption(int scene_x, int width);
    // Screenshot mode: prints the metrics of the comparison shown (stdout); a failed geometry truth sets 1.
    void report_comparison(int* exit_code);
    std::string view_key() const;
    // view_key() and the rays: what the screen-space reference is of (the rays slider restarts it).
    std::string reference_key() const { return view_key() + "|rays=" + std::to_string(reference_rays_); }
    bool save_screenshot(const std::string& path);

    ViewerOptions options_;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<ViewerRenderer> renderer_;
    ViewerScene scene_;
    ViewerCamera camera_;
    MethodPanel panels_[2];
    ViewMode view_ = ViewMode::LitWithAo;
    float split_ = 0.5f;
    bool split_reference_ = true;
    int reference_rays_ = 64;
    bool use_normals_ = false;
    float spin_ = 0.0f;  // degrees per frame the camera turns by itself
    Comparison comparison_ = Comparison::ScreenSpaceReference;
    ReferenceJob job_;
    // The geometry truth: the worker, and what the GL thread has of it.
    TruthJob truth_;
    int truth_rays_ = 256;
    std::string truth_wanted_key_;   // the key the current view wants, and since when (glfwGetTime)
    double truth_wanted_since_ = 0.0;
    uint64_t truth_generation_ = 0;  // of the last snapshot taken from the worker
    TruthSnapshot truth_snapshot_;   // the estimate uploaded (its key says which view it is of)
    bool truth_current_ = false;     // truth_snapshot_ is of the current view
    int scene_generation_ = 0;       // counts open_scene() calls: one BVH per scene opened
    std::string truth_method_key_;   // the method (view_key()) truth_metrics_ were measured for
    std::optional<samples::ErrorMetrics> truth_metrics_;
    TimingState timings_;
    std::string status_;       // the latest event's message (a scene opened, a file saved, a failure)
    std::string frame_error_;  // the current frame's render error: "" again once a frame renders
    std::string pending_drop_;
    std::string screenshot_path_;  // --screenshot, or the panel's (a path of any length)
    bool screenshot_requested_ = false;
    double last_cursor_[2] = {0.0, 0.0};
};

void ViewerApp::open_scene(const std::string& name) {
    const bool first = scene_.name.empty();  // the command line's --scene and --viewpoint: bad ones are usage errors
    try {
        ViewerScene scene;
        try {
            scene = load_viewer_scene(name);
        } catch (const std::exception& error) {
            if (first) throw UsageError(std::string("--scene ") + name + ": " + error.what());
            throw;
        }
        if (first && scene.depth_file && !options_.viewpoint.empty()) {
            throw UsageError("--viewpoint " + options_.viewpoint + ": " + name +
                             " is a depth file, seen from its own camera; viewpoints are of mesh scenes");
        }
        if (scene.mesh) {
            const std::string viewpoint = first && !options_.viewpoint.empty() ? options_.viewpoint : "default";
            try {
                camera_.reset(samples::find_viewpoint(*scene.mesh, viewpoint).camera);
            } catch (const std::invalid_argument& error) {
                if (first) throw UsageError(error.what());
                throw;
            }
        }
        scene_ = std::move(scene);
        renderer_->reset_history();  // a cut: the old scene's history must not be blended into the new one
        ++scene_generation_;  // a reopened OBJ may have changed on disk: the truth's BVH is rebuilt
        job_.cancel();
        truth_.cancel();
        status_ = "opened " + name;
        if (comparison_ == Comparison::GeometryTruth && !truth_available()) {
            comparison_ = Comparison::ScreenSpaceReference;
            status_ = "the geometry truth is unavailable for " + name +
                      " (a depth file has no triangles): comparing with the screen-space reference instead";
            std::fprintf(stderr, "obscura-viewer: %s\n", status_.c_str());
        }
    } catch (const std::exception& error) {
        if (scene_.name.empty()) throw;  // nothing to show: the caller reports it and exits
        status_ = std::string("cannot open ") + name + ": " + error.what();
        std::fprintf(stderr, "obscura-viewer: %s\n", status_.c_str());
    }
}

void ViewerApp::handle_input() {
    ImGuiIO& io = ImGui::GetIO();
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    const float dx = float(x - last_cursor_[0]), dy = float(y - last_cursor_[1]);
    last_cursor_[0] = x;
    last_cursor_[1] = y;
    if (!scene_.mesh) return;
    if (!io.WantCaptureMouse) {
        const bool turn = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS ||
                          glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        if (turn && (dx != 0.0f || dy != 0.0f)) camera_.rotate(0.25f * dx, -0.25f * dy);
        if (io.MouseWheel != 0.0f) {
            if (camera_.mode == ViewerCamera::Mode::Orbit) {
                camera_.dolly(io.MouseWheel);
            } else {
                camera_.move(0.1f * camera_.distance() * io.MouseWheel, 0.0f, 0.0f);
            }
        }
    }
    if (!io.WantCaptureKeyboard && camera_.mode == ViewerCamera::Mode::Fly) {
        const float speed = 0.5f * std::max(camera_.distance(), 0.5f) * io.DeltaTime;
        auto down = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS ? 1.0f : 0.0f; };
        camera_.move(speed * (down(GLFW_KEY_W) - down(GLFW_KEY_S)), speed * (down(GLFW_KEY_D) - down(GLFW_KEY_A)),
                     speed * (down(GLFW_KEY_E) - down(GLFW_KEY_Q)));
    }
}

// A text box over a std::string, which grows as it is typed into (ImGui's resize callback, as misc/cpp/imgui_stdlib
// does): paths are not cut at a fixed buffer's length.
bool input_text(const char* label, std::string& text) {
    const ImGuiInputTextCallback resize = [](ImGuiInputTextCallbackData* data) {
        if (data->EventFlag == ImGuiInputTextFlags_CallbackResize) {
            auto* const string = static_cast<std::string*>(data->UserData);
            string->resize(size_t(data->BufTextLen));
            data->Buf = string->data();
        }
        return 0;
    };
    return ImGui::InputText(label, text.data(), text.capacity() + 1, ImGuiInputTextFlags_CallbackResize, resize, &text);
}

// Switching to the table falloff with an empty table: the table starts as the falloff that was selected
// (obscura_evaluate_falloff at d = i/(N-1) * radius), so the picture does not jump and every value is a start.
void seed_falloff_table(obscura_settings& settings) {
    const obscura_setting_info* table = samples::falloff_table_info(settings.method);
    if (!table) return;
    float* values = samples::array_values(settings, *table);
    if (std::any_of(values, values + table->value_count, [](float v) { return v != 0.0f; })) return;
    double radius = 0.0;
    if (obscura_get_setting(&settings, "radius", &radius) != OBSCURA_STATUS_OK) return;
    std::vector<float> distances(table->value_count), rho(table->value_count);
    for (uint32_t i = 0; i < table->value_count; ++i) {
        distances[i] = float(radius * double(i) / double(table->value_count - 1));
    }
    if (obscura_evaluate_falloff(&settings, distances.data(), rho.data(), table->value_count) != OBSCURA_STATUS_OK) {
        return;
    }
    for (uint32_t i = 0; i < table->value_count; ++i) values[i] = std::clamp(rho[i], 0.0f, 1.0f);
}

// The falloff table (REFERENCE, FFAO), while the falloff is `table`: a slider per entry in a collapsible node,
// and a file to load it from (what a spec's falloff_table=@FILE reads).
bool array_control(MethodPanel& panel, const obscura_setting_info& info) {
    obscura_settings& settings = panel.settings;
    if (!samples::uses_falloff_table(settings)) return false;
    bool changed = false;
    if (ImGui::TreeNode(info.name)) {
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", info.description);
        float* values = samples::array_values(settings, info);
        for (uint32_t i = 0; i < info.value_count; ++i) {
            char label[48];
            std::snprintf(label, sizeof label, "rho(%u/%u r)", i, info.value_count - 1);
            changed |= ImGui::SliderFloat(label, &values[i], float(info.min_value), float(info.max_value), "%.3f",
                                          ImGuiSliderFlags_AlwaysClamp);
        }
        if (panel.table_path.empty()) panel.table_path = "falloff.txt";
        input_text("table file", panel.table_path);
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip("%u numbers in [%g, %g], separated by spaces, commas or newlines", info.value_count,
                              info.min_value, info.max_value);
        }
        if (ImGui::Button("Load table")) {
            try {
                const std::vector<float> loaded = samples::read_array_file(info, panel.table_path, info.name);
                std::copy(loaded.begin(), loaded.end(), values);
                changed = true;
                panel.message = "loaded the falloff table from " + panel.table_path;
            } catch (const std::exception& error) {
                panel.message = error.what();
            }
        }
        ImGui::TreePop();
    }
    return changed;
}

// A setting's control: a slider over its declared range, logarithmic over wide positive ranges, a drag box
// where the range is wide and starts at 0, a checkbox for toggles, a combo box of the value names for enums;
// derived settings get a "derive" checkbox before it (ticked: the control shows what the SDK derives for renders
// with `context`, and moving it sets a value). The tooltip carries the metadata.
bool setting_control(MethodPanel& panel, const obscura_setting_info& info, obscura_context* context) {
    obscura_settings& settings = panel.settings;
    if (samples::is_array(info)) return array_control(panel, info);
    double value = 0.0;  // the effective value: derived fields show what they derive to
    if (samples::is_derived(info)) {
        // With the renderer's context: the context-free value of a renderer-dependent field (LSAO's segment_steps)
        // is 0, which is neither what renders use nor a value that unticking could set (0 derives).
        try {
            value = effective_setting_value(context, settings, info);
        } catch (const std::exception&) {
            return false;
        }
    } else if (obscura_get_setting(&settings, info.name, &value) != OBSCURA_STATUS_OK) {
        return false;
    }
    ImGui::PushID(info.name);
    bool changed = false;
    bool derive = samples::derives(settings, info);
    if (samples::is_derived(info)) {
        if (ImGui::Checkbox("derive", &derive)) {
            // Ticked: back to 0, "derive". Unticked: the derived value, now set, is where editing starts.
            ImGui::PopID();
            return set_derive(context, settings, info, derive);
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("ticked: the SDK derives %s (%s)", info.name, info.description);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::CalcItemWidth() - ImGui::GetItemRectSize().x - ImGui::GetStyle().ItemSpacing.x);
    }
    if (info.type == OBSCURA_SETTING_TOGGLE) {
        bool on = value != 0.0;
        changed = ImGui::Checkbox(info.name, &on);
        value = on ? 1.0 : 0.0;
    } else if (info.type == OBSCURA_SETTING_ENUM) {
        const std::string current = samples::format_setting_value(info, value);
        if (ImGui::BeginCombo(info.name, current.c_str())) {
            for (uint32_t i = 0; i < info.value_count; ++i) {
                const double option = info.min_value + i;
                const std::string name = samples::value_name(info, option);
                if (ImGui::Selectable(name.c_str(), option == value)) {
                    changed = option != value;
                    value = option;
                }
                if (option == value) ImGui::SetItemDefaultFocus();
            }
            ImGui::EndCombo();
        }
        if (changed && info.name == std::string("falloff") && samples::value_name(info, value) == "table") {
            seed_falloff_table(settings);
        }
    } else if (info.type == OBSCURA_SETTING_INT) {
        int v = int(value);
        const int lo = int(info.min_value), hi = int(info.max_value);
        changed = hi - lo <= 4096 ? ImGui::SliderInt(info.name, &v, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp)
                                  : ImGui::DragInt(info.name, &v, 1.0f, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp);
        value = v;
    } else {
        const double lo = info.min_value, hi = info.max_value;
        const ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
        if (hi - lo <= 100.0) {
            changed = ImGui::SliderScalar(info.name, ImGuiDataType_Double, &value, &lo, &hi, "%.4g", flags);
        } else if (lo > 0.0) {
            changed = ImGui::SliderScalar(info.name, ImGuiDataType_Double, &value, &lo, &hi, "%.4g",
                                          flags | ImGuiSliderFlags_Logarithmic);
        } else {
            changed = ImGui::DragScalar(info.name, ImGuiDataType_Double, &value,
                                        float(std::max(std::abs(value) * 0.01, 1e-3)), &lo, &hi, "%.4g", flags);
        }
    }
    if (ImGui::IsItemHovered()) {
        const std::string names = samples::value_name_list(info);
        if (samples::is_derived(info)) {
            ImGui::SetTooltip("%s\nrange [%g, %g] %s, %s", info.description, info.min_value, info.max_value, info.unit,
                              derive ? "derived: moving it sets a value" : "set (tick derive to derive it)");
        } else if (info.type == OBSCURA_SETTING_ENUM) {
            ImGui::SetTooltip("%s\nvalues %s, default %s", info.description, names.c_str(),
                              samples::value_name(info, info.default_value).c_str());
        } else {
            ImGui::SetTooltip("%s\nrange [%g, %g] %s, default %g", info.description, info.min_value, info.max_value,
                              info.unit, info.default_value);
        }
    }
    ImGui::PopID();
    return changed && obscura_set_setting(&settings, info.name, value) == OBSCURA_STATUS_OK;
}

bool ViewerApp::method_panel(const char* id, MethodPanel& panel) {
    ImGui::PushID(id);
    bool changed = false;
    obscura_settings& settings = panel.settings;
    if (ImGui::BeginCombo("method", obscura_method_name(settings.method))) {
        for (obscura_method m : methods()) {
            const bool available = obscura_method_available(m) != 0;
            // Picking the method already selected keeps its edits; another one starts from its defaults.
            if (ImGui::Selectable(obscura_method_name(m), m == settings.method,
                                  available ? 0 : ImGuiSelectableFlags_Disabled) &&
                m != settings.method) {
                obscura_default_settings(m, &settings);
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    if (ImGui::BeginCombo("preset", "choose...")) {
        for (const ViewerPreset& preset : kViewerPresets) {
            if (preset.method != settings.method) continue;
            if (ImGui::Selectable(preset.label)) {
                settings = settings_from_spec(preset.spec);
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    for (const obscura_setting_info& info : infos_of(settings.method)) {
        changed |= setting_control(panel, info, renderer_->context());
    }
    if (ImGui::Button("Reset to defaults")) {
        obscura_default_settings(settings.method, &settings);
        changed = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Copy as C")) {
        panel.c_code = settings_to_c(settings);
        glfwSetClipboardString(window_, panel.c_code.c_str());
        panel.message = "copied to the clipboard";
    }
    if (panel.path.empty()) panel.path = std::string("obscura-") + id + ".json";
    input_text("file", panel.path);
    if (ImGui::Button("Save JSON")) {
        std::string error;
        panel.message = write_text_file(panel.path, settings_to_json(settings), &error) ? "saved " + panel.path : error;
    }
    ImGui::SameLine();
    if (ImGui::Button("Load JSON")) {
        std::string text, error;
        try {
            if (!read_text_file(panel.path, &text, &error)) throw std::runtime_error(error);
            settings = settings_from_json(text);
            changed = true;
            panel.message = "loaded " + panel.path;
        } catch (const std::exception& failure) {
            panel.message = failure.what();
        }
    }
    if (!panel.message.empty()) ImGui::TextWrapped("%s", panel.message.c_str());
    if (!panel.c_code.empty()) {
        ImGui::InputTextMultiline("##c", panel.c_code.data(), panel.c_code.size() + 1, ImVec2(-1.0f, 90.0f),
                                  ImGuiInputTextFlags_ReadOnly);
    }
    ImGui::PopID();
    return changed;
}

void ViewerApp::update_timings() {
    std::array<obscura_timing, 32> rows{};
    uint32_t count = 0;
    uint64_t frame = 0;
    obscura_get_timings(renderer_->context(), rows.data(), uint32_t(rows.size()), &count, &frame);
    if (frame != 0 && frame != timings_.frame_index) {
        timings_.frame_index = frame;
        timings_.passes.clear();
        for (uint32_t i = 0; i < std::min<uint32_t>(count, uint32_t(rows.size())); ++i) {
            timings_.passes.emplace_back(rows[i].label, float(rows[i].milliseconds));
        }
        if (!timings_.passes.empty()) timings_.total_history.push_back(timings_.passes.front().second);
        if (timings_.total_history.size() > kHistory) timings_.total_history.pop_front();
    }
    timings_.frame_history.push_back(1000.0f * ImGui::GetIO().DeltaTime);
    if (timings_.frame_history.size() > kHistory) timings_.frame_history.pop_front();
    obscura_get_memory_usage(renderer_->context(), &timings_.memory_bytes);
}

void ViewerApp::timings_panel() {
    if (!ImGui::CollapsingHeader("Performance", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::TextWrapped("%s", renderer_->renderer_name().c_str());
    float longest = 1e-3f;
    for (const auto& pass : timings_.passes) longest = std::max(longest, pass.second);
    for (const auto& pass : timings_.passes) {
        char label[96];
        std::snprintf(label, sizeof label, "%s %.3f ms", pass.first.c_str(), pass.second);
        ImGui::ProgressBar(pass.second / longest, ImVec2(-1.0f, 0.0f), label);
    }
    const std::vector<float> totals(timings_.total_history.begin(), timings_.total_history.end());
    const std::vector<float> frames(timings_.frame_history.begin(), timings_.frame_history.end());
    if (!totals.empty()) {
        ImGui::PlotLines("AO ms", totals.data(), int(totals.size()), 0, nullptr, 0.0f, FLT_MAX, ImVec2(-1.0f, 50.0f));
    }
    if (!frames.empty()) {
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "%.1f ms", frames.back());
        ImGui::PlotLines("frame ms", frames.data(), int(frames.size()), 0, overlay, 0.0f, FLT_MAX,
                         ImVec2(-1.0f, 50.0f));
    }
    ImGui::Text("GPU memory: %.2f MiB", double(timings_.memory_bytes) / (1024.0 * 1024.0));
}

std::string ViewerApp::comparison_label() const {
    char label[128];
    if (comparison_ == Comparison::GeometryTruth) {
        if (truth_current_ && truth_snapshot_.rays < truth_snapshot_.rays_total) {
            std::snprintf(label, sizeof label, "geometry truth (%d of %d rays so far)", truth_snapshot_.rays,
                          truth_snapshot_.rays_total);
        } else {
            std::snprintf(label, sizeof label, "geometry truth (%d rays)",
                          truth_current_ ? truth_snapshot_.rays : truth_rays_);
        }
    } else {
        std::snprintf(label, sizeof label, "screen-space reference (infinitely thick depth, %d rays)",
                      job_.active() ? job_.traced_rays() : reference_rays_);
    }
    return label;
}

void ViewerApp::metrics_text(const samples::ErrorMetrics& metrics, const std::string& against, const char* short_name) {
    ImGui::TextWrapped("%s against %s:", obscura_method_name(panels_[0].settings.method), against.c_str());
    ImGui::Text("mean_abs %.4f  within 5%% %.3f  PSNR %.1f dB", metrics.mean_abs, metrics.within_5pct, metrics.psnr);
    ImGui::Text("signed mean %+.4f (method - %s; + too bright)", metrics.mean_signed, short_name);
    ImGui::Text("geometry pixels only: sky %.1f %% excluded", 100.0 * sky_fraction(metrics));
}

void ViewerApp::reference_section() {
    note("REFERENCE: rays marched through the depth buffer on the GPU, every surface taken as infinitely "
         "thick, so it knows only what the camera sees. Not ground truth.");
    ImGui::SliderInt("rays", &reference_rays_, ReferenceJob::kChunkRays, 1024);
    if (ImGui::Button(job_.active() ? "Restart" : "Compute")) {
        job_.start(reference_key(), panels_[0].settings, reference_rays_);
        if (view_ != ViewMode::Split) view_ = ViewMode::ErrorMap;
    }
    if (job_.active()) {
        char label[64];
        std::snprintf(label, sizeof label, "%d / %d rays", job_.traced_rays(),
                      int(std::lround(job_.traced_rays() / std::max(job_.progress(), 1e-6f))));
        ImGui::ProgressBar(job_.progress(), ImVec2(-1.0f, 0.0f), label);
    }
    if (job_.metrics) metrics_text(*job_.metrics, comparison_label(), "reference");
}

void ViewerApp::truth_section() {
    note("Rays against the scene's triangles (Embree, on the CPU, on a worker thread), weighed with the "
         "method's falloff: what the scene really occludes, off screen and behind surfaces included.");
    ImGui::SliderInt("truth rays", &truth_rays_, kTruthBatchRays, 4096, "%d",
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::Button("Restart##truth")) {
        // Cancelled, not stopped: joining here would freeze the window until the worker returns, which a BVH build
        // (it cannot be cancelled) may take seconds to. update_truth starts the new job once the old one has
        // returned (TruthJob::busy).
        truth_.cancel();
        truth_wanted_key_.clear();  // no restart delay: the next frame the worker is idle
        if (view_ != ViewMode::Split) view_ = ViewMode::ErrorMap;
    }
    const TruthProgress progress = truth_.progress();
    if (progress.active || progress.done || !progress.error.empty()) {
        char label[96];
        if (progress.rays_done > 0 || progress.done) {
            std::snprintf(label, sizeof label, "%d / %d rays, %.1f s", progress.rays_done, progress.rays_total,
                          progress.seconds);
        } else {
            std::snprintf(label, sizeof label, "%s, %.1f s", progress.phase.c_str(), progress.seconds);
        }
        const float fraction = progress.rays_total > 0 ? float(progress.rays_done) / float(progress.rays_total) : 0.0f;
        ImGui::ProgressBar(fraction, ImVec2(-1.0f, 0.0f), label);
        if (progress.triangles > 0) ImGui::TextDisabled("%d triangles", progress.triangles);
    } else if (view_ != ViewMode::ErrorMap && !(view_ == ViewMode::Split && split_reference_)) {
        ImGui::TextDisabled("traced in the error and split views");
    }
    if (!progress.error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", progress.error.c_str());
    if (truth_current_ && truth_metrics_) metrics_text(*truth_metrics_, comparison_label(), "truth");
}

void ViewerApp::comparison_panel() {
    if (!ImGui::CollapsingHeader("Comparison", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const char* labels[] = {"screen-space reference", "geometry truth"};
    if (comparison_ == Comparison::GeometryTruth && !truth_available()) comparison_ = Comparison::ScreenSpaceReference;
    if (ImGui::BeginCombo("compare with", labels[int(comparison_)])) {
        if (ImGui::Selectable(labels[0], comparison_ == Comparison::ScreenSpaceReference)) {
            comparison_ = Comparison::ScreenSpaceReference;
        }
        if (ImGui::Selectable(truth_available() ? labels[1] : "geometry truth (unavailable: depth file)",
                              comparison_ == Comparison::GeometryTruth,
                              truth_available() ? 0 : ImGuiSelectableFlags_Disabled)) {
            comparison_ = Comparison::GeometryTruth;
        }
        if (!truth_available() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
            ImGui::SetTooltip("%s", kTruthUnavailable);
        }
        ImGui::EndCombo();
    }
    if (!truth_available()) {
        ImGui::TextDisabled("geometry truth: unavailable (depth file)");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kTruthUnavailable);
    }
    if (comparison_ == Comparison::GeometryTruth) {
        truth_section();
    } else {
        reference_section();
    }
}

void ViewerApp::build_panel() {
    // A side panel: the scene has the rest of the window.
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, ImGui::GetIO().DisplaySize.y), ImGuiCond_Always);
    ImGui::Begin("Obscura", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (ImGui::BeginCombo("scene", scene_.name.c_str())) {
            for (const samples::SceneInfo& info : samples::list_scenes()) {
                if (ImGui::Selectable(info.name.c_str(), info.name == scene_.name,
                                      info.available ? 0 : ImGuiSelectableFlags_Disabled)) {
                    pending_drop_ = info.name;
                }
            }
            ImGui::EndCombo();
        }
        if (scene_.mesh && ImGui::BeginCombo("viewpoint", "choose...")) {
            for (const samples::NamedCamera& view : scene_.mesh->viewpoints) {
                if (ImGui::Selectable(view.name.c_str())) {
                    camera_.reset(view.camera);
                    renderer_->reset_history();  // a jump, not motion that reprojection could follow
                }
            }
            ImGui::EndCombo();
        }
        ImGui::TextDisabled("drop an .obj or a .pfm depth file on the window");
        int mode = int(camera_.mode);
        ImGui::RadioButton("orbit", &mode, 0);
        ImGui::SameLine();
        ImGui::RadioButton("fly (WASD QE)", &mode, 1);
        camera_.mode = ViewerCamera::Mode(mode);
        ImGui::SliderFloat("spin (deg/frame)", &spin_, -2.0f, 2.0f, "%.2f");
        ImGui::Checkbox("pass the scene's normals", &use_normals_);
    }
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
        int view = int(view_);
        const char* names[] = {"AO only", "lit with AO", "lit without AO", "split screen", "error heat map"};
        ImGui::Combo("view", &view, names, 5);
        view_ = ViewMode(view);
        if (view_ == ViewMode::Split) {
            ImGui::SliderFloat("split", &split_, 0.0f, 1.0f);
            ImGui::Checkbox("right: the comparison (else a second method)", &split_reference_);
        }
    }
    if (ImGui::CollapsingHeader("Method", ImGuiTreeNodeFlags_DefaultOpen)) method_panel("a", panels_[0]);
    if (view_ == ViewMode::Split && !split_reference_ && ImGui::CollapsingHeader("Right side", ImGuiTreeNodeFlags_DefaultOpen)) {
        method_panel("b", panels_[1]);
    }
    comparison_panel();
    timings_panel();
    if (ImGui::CollapsingHeader("Screenshot")) {
        if (screenshot_path_.empty()) screenshot_path_ = "obscura-viewer.png";
        input_text("png", screenshot_path_);
        if (ImGui::Button("Save PNG")) screenshot_requested_ = true;
    }
    if (!frame_error_.empty()) ImGui::TextWrapped("%s", frame_error_.c_str());
    if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
    ImGui::End();
}

std::string ViewerApp::truth_key(const samples::TruthView& view) const {
    return truth_view_key(scene_.name, scene_generation_, view, truth_rays_, panels_[0].settings);
}

void ViewerApp::update_truth(bool wanted, bool wait) {
    truth_current_ = false;
    const samples::SceneFrame* frame = renderer_->frame();
    if (!frame || !scene_.mesh) return;
    const samples::TruthView view = samples::TruthView::of(*frame);
    const std::string key = truth_key(view);
    if (!wanted) {
        // A job keeps running while the view is unchanged (the error view shows it at once when it comes back).
        if (!truth_.key().empty() && truth_.key() != key) truth_.cancel();
        return;
    }
    const double now = glfwGetTime();
    if (key != truth_.key()) {
        // Another view, size or falloff: the running job is of no use any more. It is joined when the next
        // one starts, once the view has held still (or at once for the first job and in screenshot mode).
        if (!truth_.key().empty()) truth_.cancel();
        if (key != truth_wanted_key_) {
            truth_wanted_since_ = truth_wanted_key_.empty() ? now - kTruthRestartDelay : now;
            truth_wanted_key_ = key;
        }
        if ((now - truth_wanted_since_ >= kTruthRestartDelay && !truth_.busy()) || options_.frames > 0) {
            TruthRequest request;
            request.key = key;
            request.scene_name = scene_.name + "#" + std::to_string(scene_generation_);
            request.view = view;
            request.falloff = panels_[0].settings;
            request.rays = truth_rays_;
            request.batch_rays = kTruthBatchRays;
            truth_.start(std::move(request), scene_.mesh->mesh);
        }
    }
    if (wait && truth_.key() == key && !truth_.progress().done) {
        std::fprintf(stderr, "obscura-viewer: waiting for the geometry truth (%d rays per pixel)\n", truth_rays_);
        truth_.wait();
    }
    TruthSnapshot snapshot;
    if (truth_.latest(truth_generation_, &snapshot)) {
        truth_generation_ = snapshot.generation;
        if (snapshot.key == key) {
            renderer_->upload_truth(snapshot.visibility);
            truth_snapshot_ = std::move(snapshot);
            truth_method_key_.clear();
        }
    }
    truth_current_ = truth_snapshot_.generation != 0 && truth_snapshot_.key == key && truth_snapshot_.mask;
    if (!truth_current_) {
        truth_metrics_.reset();
        return;
    }
    // The method is measured again when it changes without changing the falloff (no new trace needed), and every
    // frame while it accumulates frames (temporal), so that the metrics follow its current image.
    const std::string method_key = view_key();
    if (method_key != truth_method_key_ || accumulates(panels_[0].settings)) {
        try {
            truth_metrics_ = renderer_->compare_with_truth(truth_snapshot_.visibility, *truth_snapshot_.mask);
        } catch (const std::exception& error) {
            truth_metrics_.reset();
            status_ = std::string("comparing with the geometry truth: ") + error.what();
        }
        truth_method_key_ = method_key;
    }
}

void ViewerApp::report_comparison(int* exit_code) {
    if (view_ != ViewMode::ErrorMap && !(view_ == ViewMode::Split && split_reference_)) return;
    const samples::ErrorMetrics* metrics = nullptr;
    if (comparison_ == Comparison::GeometryTruth) {
        const TruthProgress progress = truth_.progress();
        if (!progress.error.empty()) {
            std::fprintf(stderr, "obscura-viewer: the geometry truth failed: %s\n", progress.error.c_str());
            *exit_code = 1;
            return;
        }
        if (truth_current_ && truth_metrics_) metrics = &*truth_metrics_;
    } else if (job_.metrics) {
        metrics = &*job_.metrics;
    }
    if (!metrics) return;
    std::printf("obscura-viewer: %s against %s: mean_abs %.4f within_5pct %.4f mean_signed %+.4f psnr %.2f dB "
                "(geometry pixels only, sky %.1f %% excluded)\n",
                obscura_method_name(panels_[0].settings.method), comparison_label().c_str(), metrics->mean_abs,
                metrics->within_5pct, metrics->mean_signed, metrics->psnr, 100.0 * sky_fraction(*metrics));
}

// What the scene area shows, written over its top edge: which image is which, and what the comparison is.
void ViewerApp::draw_scene_caption(int scene_x, int width) {
    if (view_ != ViewMode::Split && view_ != ViewMode::ErrorMap) return;
    const bool comparison = view_ == ViewMode::ErrorMap || split_reference_;
    const std::string method = obscura_method_name(panels_[0].settings.method);
    std::string left, right;
    if (view_ == ViewMode::ErrorMap) {
        left = "|" + method + " - " + comparison_label() + "|: white 0, black >= 0.2";
    } else {
        left = method;
        right = comparison ? comparison_label() : std::string(obscura_method_name(panels_[1].settings.method));
    }
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float pad = 4.0f, line = ImGui::GetTextLineHeight();
    auto caption = [&](float x, const std::string& text) {
        const ImVec2 size = ImGui::CalcTextSize(text.c_str());
        draw->AddRectFilled(ImVec2(x, 0.0f), ImVec2(x + size.x + 2.0f * pad, line + 2.0f * pad), IM_COL32(0, 0, 0, 150));
        draw->AddText(ImVec2(x + pad, pad), IM_COL32(255, 255, 255, 230), text.c_str());
    };
    caption(float(scene_x), left);
    if (!right.empty()) {
        const float x = float(scene_x) + split_ * float(width);
        caption(std::min(x + 2.0f, float(scene_x + width) - ImGui::CalcTextSize(right.c_str()).x - 2.0f * pad), right);
    }
}

std::string ViewerApp::view_key() const {
    // Built as a string (a fixed buffer cut long scene paths short, and the camera and size fell out of the key) with
    // exact numbers (%a: %g's six digits missed small moves far from the origin). A depth file ignores the camera
    // (its view is the file's): spinning over one must not restart the reference every frame.
    std::string key = scene_.name + "|";
    char number[48];
    auto add = [&](double value) {
        std::snprintf(number, sizeof number, "%a,", value);
        key += number;
    };
    if (!scene_.depth_file) {
        const samples::Camera c = camera_.camera();
        for (double v : {c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z}) add(v);
    }
    key += "|" + std::to_string(renderer_ ? renderer_->width() : 0) + "x" +
           std::to_string(renderer_ ? renderer_->height() : 0) + "|" + (use_normals_ ? "1" : "0") + "|";
    return key + settings_to_json(panels_[0].settings);
}

bool ViewerApp::save_screenshot(const std::string& path) {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    samples::FloatImage image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.pixels.resize(size_t(width) * height * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGB, GL_FLOAT, image.pixels.data());
    try {
        samples::write_png(path, image);
    } catch (const std::exception& error) {
        status_ = error.what();
        std::fprintf(stderr, "obscura-viewer: %s\n", error.what());
        return false;
    }
    status_ = "saved " + path;
    return true;
}

int ViewerApp::run() {
    glfwSetErrorCallback([](int code, const char* text) { std::fprintf(stderr, "glfw error %d: %s\n", code, text); });
    if (!glfwInit()) {
        std::fprintf(stderr, "obscura-viewer: glfwInit failed (no display?)\n");
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(options_.width, options_.height, "Obscura viewer", nullptr, nullptr);
    if (!window_) {
        std::fprintf(stderr, "obscura-viewer: cannot create a GL 4.3 core window\n");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(options_.frames > 0 ? 0 : 1);
    // The app's own loader (what an engine has); the SDK loads its private table from the same function.
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress))) {
        std::fprintf(stderr, "obscura-viewer: loading GL functions failed\n");
        glfwDestroyWindow(window_);
        glfwTerminate();
        return 1;
    }
    glfwSetWindowUserPointer(window_, this);
    glfwSetDropCallback(window_, [](GLFWwindow* window, int count, const char** paths) {
        if (count > 0) static_cast<ViewerApp*>(glfwGetWindowUserPointer(window))->pending_drop_ = paths[0];
    });
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 430 core");
    int exit_code = 0;
    try {
        const GLubyte* name = glGetString(GL_RENDERER);
        const std::string renderer = name ? reinterpret_cast<const char*>(name) : "";
        const bool software = renderer.find("llvmpipe") != std::string::npos ||
                              renderer.find("softpipe") != std::string::npos;
        renderer_ = std::make_unique<ViewerRenderer>(glfw_proc, software);
        use_normals_ = options_.use_normals;
        spin_ = options_.spin;
        reference_rays_ = options_.reference_rays;
        truth_rays_ = options_.truth_rays;
        comparison_ = options_.comparison;
        view_ = options_.view;
        open_scene(options_.scene);
        panels_[0].settings = settings_from_spec(options_.method);
        if (!options_.settings_file.empty()) {
            std::string text, error;
            if (!read_text_file(options_.settings_file, &text, &error)) throw std::runtime_error(error);
            panels_[0].settings = settings_from_json(text);
        }
        split_reference_ = options_.compare.empty() || options_.compare == "reference" || options_.compare == "truth";
        panels_[1].settings = settings_from_spec(split_reference_ ? "hbao" : options_.compare);
        screenshot_path_ = options_.screenshot;
        int frame = 0;
        while (!glfwWindowShouldClose(window_)) {
            glfwPollEvents();
            if (!pending_drop_.empty()) {
                open_scene(pending_drop_);
                pending_drop_.clear();
            }
            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            handle_input();
            build_panel();
            int window_width = 0, height = 0;
            glfwGetFramebufferSize(window_, &window_width, &height);
            // The panel is kPanelWidth ImGui points wide; the scene's viewport is in framebuffer pixels, which
            // are more than points on a HiDPI display.
            const float pixels_per_point = std::max(ImGui::GetIO().DisplayFramebufferScale.x, 1e-3f);
            const int scene_x =
                std::min(int(std::lround(kPanelWidth * pixels_per_point)), std::max(window_width - 16, 0));
            const int width = window_width - scene_x;
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, window_width, height);
            glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            if (width > 0 && height > 0) {
                if (spin_ != 0.0f) camera_.rotate(spin_, 0.0f);  // moves the camera for temporal accumulation to follow
                frame_error_.clear();
                renderer_->render_scene(scene_, camera_.camera(), width, height, glfw_proc);
                bool ok = renderer_->render_ao(0, panels_[0].settings, use_normals_);
                if (ok && view_ == ViewMode::Split && !split_reference_) {
                    ok = renderer_->render_ao(1, panels_[1].settings, use_normals_);
                }
                if (!ok) frame_error_ = renderer_->last_error();
                const bool wants_comparison =
                    view_ == ViewMode::ErrorMap || (view_ == ViewMode::Split && split_reference_);
                const bool wait_for_truth = options_.frames > 0 && frame + 2 >= options_.frames;
                truth_current_ = false;
                if (wants_comparison && ok && comparison_ == Comparison::ScreenSpaceReference) {
                    const std::string key = reference_key();
                    if (!job_.active() || job_.key() != key) job_.start(key, panels_[0].settings, reference_rays_);
                    if (!job_.done()) {
                        if (!renderer_->step_reference(job_, use_normals_)) frame_error_ = renderer_->last_error();
                    } else if (accumulates(panels_[0].settings)) {
                        renderer_->measure_reference(job_);  // the method's current frame, not its first
                    }
                }
                if (ok && comparison_ == Comparison::ScreenSpaceReference) {
                    // Comparing with the reference: a geometry truth job is of no use and would keep the CPU busy.
                    if (!truth_.key().empty()) truth_.cancel();
                } else if (ok) {
                    update_truth(wants_comparison && comparison_ == Comparison::GeometryTruth, wait_for_truth);
                }
                update_timings();
                GLuint right = 0, heat = 0;
                if (view_ == ViewMode::Split && !split_reference_) {
                    right = renderer_->ao_texture(1);
                } else if (comparison_ == Comparison::GeometryTruth) {
                    right = truth_current_ ? renderer_->truth_texture() : 0;
                    heat = truth_current_ && truth_metrics_ ? renderer_->truth_heat() : 0;
                } else {
                    right = renderer_->reference_texture(job_);
                    heat = renderer_->reference_heat(job_);
                }
                glBindFramebuffer(GL_FRAMEBUFFER, 0);
                glViewport(scene_x, 0, width, height);
                renderer_->composite(view_, split_, right, heat);
                glViewport(0, 0, window_width, height);
                draw_scene_caption(int(float(scene_x) / pixels_per_point), int(float(width) / pixels_per_point));
            }
            ImGui::Render();
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            ++frame;
            const bool last = options_.frames > 0 && frame >= options_.frames;
            if (screenshot_requested_ || (last && !options_.screenshot.empty())) {
                if (!save_screenshot(screenshot_path_) && last) exit_code = 1;
                screenshot_requested_ = false;
            }
            glfwSwapBuffers(window_);
            if (last) break;
        }
        if (options_.frames > 0) report_comparison(&exit_code);
        const GLenum error = glGetError();
        if (error != GL_NO_ERROR) {
            std::fprintf(stderr, "obscura-viewer: GL error 0x%04x left pending\n", error);
            exit_code = 1;
        }
        if (!frame_error_.empty()) {  // the last frame did not render
            std::fprintf(stderr, "obscura-viewer: %s\n", frame_error_.c_str());
            exit_code = 1;
        }
    } catch (const UsageError& error) {
        std::fprintf(stderr, "obscura-viewer: %s\n", error.what());
        exit_code = 2;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "obscura-viewer: %s\n", error.what());
        exit_code = 1;
    }
    truth_.stop();  // the window is closing: the worker is cancelled and joined
    scene_ = ViewerScene();  // a depth file's textures, while the GL context is current
    renderer_.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
    return exit_code;
}

}  // namespace

obscura_settings settings_from_spec(const std::string& spec) {
    try {
        return samples::parse_method_spec(spec);
    } catch (const samples::MethodSpecError& error) {
        throw std::invalid_argument(error.what());
    } catch (const samples::SettingsLibraryError& error) {
        throw std::invalid_argument(error.what());
    }
}

int run_viewer(const ViewerOptions& options) { return ViewerApp(options).run(); }

}  // namespace obscura::viewer
