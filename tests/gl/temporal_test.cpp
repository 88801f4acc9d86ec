// Temporal accumulation (settings.temporal, obscura_input's view, frame index, matrices and motion vectors) on
// the analytic box scene (CPU ray cast, D32F depth, 320x180):
//   - a static camera converges towards the many-sample image: the error falls with the frames;
//   - FFAO's frame split: one frame shows its 2x2 pattern, the mean of a window of N frames and the accumulated image
//     are the image of every orientation;
//   - an identity reprojection with the same noise every frame reproduces the one-frame image exactly;
//   - a reset flag, and a frame without matrices, drop the history;
//   - a debug-view frame leaves the history and the camera it was made with (a reset on it drops the history);
//   - motion vectors continue a history only from the previous frame index;
//   - two views keep separate histories, and a resize of one leaves the other's history alone;
//   - a host resize at reduced resolution, a change of meters_to_view_units, and a camera cut on a refused frame drop
//     the history; bent normals follow the clamp where the AO changed under a surface;
//   - motion vectors and matrices reproject alike after a camera move; a point reprojected past the texture's edge
//     starts a new history; an orbit with a guard band stays on the still image of its last camera, at the output
//     rectangle's edge too;
//   - the API refuses foreign views, unknown flags, singular matrices and unreadable motion vectors.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <vector>

#include "ao_test_scene.h"

namespace obscura_test {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

void store(const glm::dmat4& m, float out[16]) {
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row) out[column * 4 + row] = float(m[column][row]);
}

glm::dmat4 projection_of(const Camera& camera) {
    glm::dmat4 p;
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row) p[column][row] = camera.matrix()[column * 4 + row];
    return p;
}

// This frame's view-projection into the input; `previous` (null: the same) as the previous frame's.
void set_matrices(obscura_input* input, const Camera& camera, const Camera* previous = nullptr) {
    store(projection_of(camera) * camera.view(), input->view_projection);
    const Camera& before = previous ? *previous : camera;
    store(projection_of(before) * before.view(), input->previous_view_projection);
}

// The box on its floor (ao_test_scene.h) through a camera at `eye` looking at `target`.
AoScene box_seen_from(glm::dvec3 eye, glm::dvec3 target) {
    return make_ao_scene(Projection::Perspective, look_at(eye, target),
                         {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                          box(2, glm::dvec3(-kBoxHalf, 0.0, -kBoxHalf), glm::dvec3(kBoxHalf, kBoxHeight, kBoxHalf))});
}

// HBAO with few directions: noisy enough that accumulation shows.
obscura_settings noisy_hbao(bool temporal) {
    obscura_settings settings;
    obscura_default_settings(OBSCURA_METHOD_HBAO, &settings);
    settings.hbao.directions = 2;
    settings.temporal.enabled = temporal ? OBSCURA_TOGGLE_ON : OBSCURA_TOGGLE_OFF;
    return settings;
}

std::vector<bool> geometry_mask(const AoScene& scene) {
    return select(scene.hits, kWidth, kHeight, 2, [](const Hit&) { return true; });
}

double mean_abs_difference(const std::vector<float>& a, const std::vector<float>& b, const std::vector<bool>& mask) {
    double sum = 0.0;
    int count = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!mask[i]) continue;
        sum += std::fabs(double(a[i]) - double(b[i]));
        ++count;
    }
    return count > 0 ? sum / count : 0.0;
}

// A frame rendered alone ends with its method's last pass writing the target at the target's own precision; an
// accumulated one blends the method's R16F result, which drivers round or truncate (llvmpipe truncates). A frame
// that keeps no history, and a history of frames, match frames rendered alone to one R16F step below 1.
constexpr double kAloneRounding = 1.0 / 2048.0;

double max_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
    double m = 0.0;
    for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::fabs(double(a[i]) - double(b[i])));
    return m;
}

// One frame's bent normals (RGBA: visibility, bent normal xyz) through an R32F visibility target and an RGBA32F
// bent-normal target.
std::vector<float> render_bent_normals(obscura_context* context, const obscura_input& input,
                                       const obscura_settings& settings) {
    HostTexture ao = make_texture(GL_R32F, kWidth, kHeight);
    HostTexture bent = make_texture(GL_RGBA32F, kWidth, kHeight);
    obscura_output output = make_output(ao.get());
    output.bent_normal_texture = bent.get();
    EXPECT_EQ(obscura_render(context, &input, &settings, &output), OBSCURA_OK) << obscura_get_last_error(context);
    return read_texture(bent.get(), kWidth, kHeight, 4);
}

// Renders frames first .. first + count - 1 of a static camera through `view`; returns the last image.
std::vector<float> render_frames(obscura_context* context, obscura_input input, const obscura_settings& settings,
                                 uint32_t first, uint32_t count, obscura_view* view = nullptr) {
    std::vector<float> image;
    input.view = view;
    for (uint32_t f = first; f < first + count; ++f) {
        input.frame_index = f;
        image = render_visibility(context, input, settings);
    }
    return image;
}

TEST_F(GLTest, TemporalStaticCameraConvergesTowardsTheManySampleImage) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    // The many-sample image: the mean of 32 frames' noise patterns, each rendered alone.
    const std::vector<bool> mask = geometry_mask(scene);
    std::vector<double> sum(size_t(kWidth) * kHeight, 0.0);
    constexpr uint32_t kReferenceFrames = 32;
    for (uint32_t f = 0; f < kReferenceFrames; ++f) {
        const std::vector<float> frame = render_frames(ctx(), scene.input, noisy_hbao(false), f, 1);
        for (size_t i = 0; i < sum.size(); ++i) sum[i] += frame[i];
    }
    std::vector<float> reference(sum.size());
    for (size_t i = 0; i < sum.size(); ++i) reference[i] = float(sum[i] / kReferenceFrames);

    const obscura_settings settings = noisy_hbao(true);
    std::vector<double> error;
    std::string trace;
    obscura_input input = scene.input;
    for (uint32_t f = 0; f < 8; ++f) {
        input.frame_index = f;
        error.push_back(mean_abs_difference(render_visibility(ctx(), input, settings), reference, mask));
        trace += std::to_string(error.back()) + " ";
    }
    // Measured on llvmpipe (mean over the geometry): 0.0029 0.0019 0.0013 0.00086 0.00088 0.00085 0.00076 0.00067.
    EXPECT_LT(error[3], 0.7 * error[0]) << trace;
    EXPECT_LT(error[7], 0.9 * error[3]) << trace;
    EXPECT_LT(error[7], 0.4 * error[0]) << trace;
}

// LSAO's and FFAO's lines move with the frame index through eight layout phases (layout_phase.h): another
// frame gives another image of the same AO, frame 8 repeats frame 0, and phase 0 is the image of a host from before
// the frame index (a 0.4 obscura_input).
TEST_F(GLTest, LayoutPhasesMoveLsaoAndFfaoLinesWithTheFrameIndex) {
    AoScene scene = box_scene();
    const std::vector<bool> mask = geometry_mask(scene);
    const size_t pixels = size_t(std::count(mask.begin(), mask.end(), true));
    obscura_settings lsao, lsao_free, ffao;
    obscura_default_settings(OBSCURA_METHOD_LSAO, &lsao);
    lsao_free = lsao;
    lsao_free.lsao.pattern = 2;
    obscura_default_settings(OBSCURA_METHOD_FFAO, &ffao);
    const struct {
        const char* name;
        obscura_settings settings;
    } cases[] = {{"lsao", lsao}, {"lsao free", lsao_free}, {"ffao", ffao}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const std::vector<float> first = render_frames(ctx(), scene.input, c.settings, 0, 1);
        const std::vector<float> next = render_frames(ctx(), scene.input, c.settings, 1, 1);
        const std::vector<float> ninth = render_frames(ctx(), scene.input, c.settings, 8, 1);
        EXPECT_EQ(max_abs_difference(ninth, first), 0.0);
        // A host from before the frame index (a 0.4 obscura_input, which ends after normal_texture) renders phase 0, whatever
        // lies in memory past its struct_size.
        obscura_input older = scene.input;
        older.struct_size = uint32_t(offsetof(obscura_input, normal_texture) + sizeof(uint32_t));
        older.frame_index = 5;
        EXPECT_EQ(max_abs_difference(render_visibility(ctx(), older, c.settings), first), 0.0);
        size_t moved = 0;
        for (size_t i = 0; i < first.size(); ++i) moved += mask[i] && std::fabs(first[i] - next[i]) > 1e-3f;
        // Planes give the same AO in every phase; around the box it moves (by more than 1e-3 on llvmpipe: 4.6 % of the
        // pixels with the aligned lines, 1.3 % with FFAO's, whose lines move by less than a texel).
        EXPECT_GT(moved, pixels / 200) << moved << " of " << pixels;
        EXPECT_LT(mean_abs_difference(next, first, mask), 0.02);
    }
}

// FFAO's frame split (ffao_added.frame_split = N): each pixel evaluates every Nth orientation, weighted N times, in a
// 2x2 pattern that the frame index turns, and the layout phase moves once per N frames. A single frame shows the
// pattern; the mean of a window of N frames is the image of every orientation at the window's phase (the whole
// image at frame w, for window w), up to R16F rounding and the clamp of the obscurance to [0, 1], which a share
// weighted N times can reach at the box's foot; accumulated on a still camera (temporal.enabled, a running mean up to
// max_frames) it is the mean of those images, so the neighbourhood clamp does not hold the history to the pattern.
TEST_F(GLTest, FfaoFrameSplitAveragesToEveryOrientation) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    const std::vector<bool> mask = geometry_mask(scene);
    obscura_settings whole;
    obscura_default_settings(OBSCURA_METHOD_FFAO, &whole);
    const size_t pixels = size_t(kWidth) * kHeight;
    auto mean_of = [&](const obscura_settings& settings, uint32_t first, uint32_t count) {
        std::vector<double> sum(pixels, 0.0);
        for (uint32_t f = first; f < first + count; ++f) {
            const std::vector<float> frame = render_frames(ctx(), scene.input, settings, f, 1);
            for (size_t i = 0; i < pixels; ++i) sum[i] += frame[i];
        }
        std::vector<float> mean(pixels);
        for (size_t i = 0; i < pixels; ++i) mean[i] = float(sum[i] / count);
        return mean;
    };

    for (uint32_t split : {2u, 4u}) {
        SCOPED_TRACE("frame_split " + std::to_string(split));
        obscura_settings settings = whole;
        settings.ffao_added.frame_split = int32_t(split);
        const double single =
            mean_abs_difference(render_frames(ctx(), scene.input, settings, 0, 1), mean_of(whole, 0, 1), mask);
        for (uint32_t window = 0; window < 2; ++window) {
            const std::vector<float> mean = mean_of(settings, window * split, split);
            const std::vector<float> whole_at_phase = mean_of(whole, window, 1);
            const double averaged = mean_abs_difference(mean, whole_at_phase, mask);
            // Measured on llvmpipe: one frame 0.0013 (N = 2) and 0.0039 (N = 4) from the whole image with an infinitely
            // thick field, 0.00094 (N = 2) with the default 0.4 m (the mean over the geometry, most of it open floor); a
            // window's mean 0.00011-0.00013 from its phase's whole image, at most 0.00037 in any pixel: 1.5 steps of
            // R16F below 1 (2^-12), the rounding of the frames' values alone.
            EXPECT_GT(single, 5e-4) << "one frame of a split shows its pattern";
            EXPECT_LT(averaged, 2e-4) << "window " << window;
            EXPECT_LE(max_abs_difference(mean, whole_at_phase), 2.0 / 4096.0) << "window " << window;
        }

        // Accumulated over 16 frames of the still camera with a history of up to 16 (a running mean): the windows'
        // images, 16 / N of them.
        settings.temporal.enabled = OBSCURA_TOGGLE_ON;
        settings.temporal.max_frames = 16;
        obscura_view* view = nullptr;
        ASSERT_EQ(obscura_create_view(ctx(), &view), OBSCURA_OK);
        const std::vector<float> accumulated = render_frames(ctx(), scene.input, settings, 0, 16, view);
        const std::vector<float> windows = mean_of(whole, 0, 16 / split);
        const double converged = mean_abs_difference(accumulated, windows, mask);
        // Measured: 0.00006 (N = 2) and 0.00009 (N = 4), the same rounding, but for 2 and 12 of the 55,616 geometry
        // pixels (4 by more than 0.01): at the box's silhouette the 7 texels' clamp reaches another surface's values.
        EXPECT_LT(converged, 2e-4) << converged;
        size_t beyond_rounding = 0, geometry = 0;
        for (size_t i = 0; i < pixels; ++i) {
            geometry += mask[i];
            beyond_rounding += mask[i] && std::fabs(accumulated[i] - windows[i]) > 2.0 / 4096.0;
        }
        EXPECT_LT(beyond_rounding, geometry / 1000) << beyond_rounding << " of " << geometry;
        EXPECT_EQ(obscura_destroy_view(ctx(), view), OBSCURA_OK);
    }
}

TEST_F(GLTest, TemporalIdentityReprojectionReproducesTheHistoryExactly) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    obscura_settings settings = noisy_hbao(true);
    // The frame as the pass reads it (the method's R16F result): a frame that starts a new history; the frame rendered
    // alone, to that rounding.
    obscura_input reset = scene.input;
    reset.flags |= OBSCURA_INPUT_FLAG_RESET_HISTORY;
    const std::vector<float> one_frame = render_frames(ctx(), reset, settings, 0, 1);
    EXPECT_LE(max_abs_difference(one_frame, render_frames(ctx(), scene.input, noisy_hbao(false), 0, 1)), kAloneRounding);
    // The same noise every frame: each frame blends an image into an equal history.
    obscura_input input = scene.input;
    std::vector<float> accumulated;
    for (int f = 0; f < 6; ++f) accumulated = render_visibility(ctx(), input, settings);
    EXPECT_EQ(max_abs_difference(accumulated, one_frame), 0.0);

    // The noise moving with the frame index: the history is this view's earlier frames, reproduced exactly, so
    // frame n is the mean of the n + 1 frames rendered alone (weight 1 / age), wherever the neighbourhood clamp
    // leaves the history as it is. That is predicted here from the frames alone: the 7-texel window (the 3x3 less
    // (+1, -1) and (-1, +1)), mean +- clamp deviations widened to the pixel's own value; a pixel is checked while the
    // history has stayed inside it by a margin in every frame so far. An accumulation that ignored, resampled or
    // blurred the history would miss the mean.
    obscura_settings wide = settings;
    wide.temporal.clamp = 64.0f;
    obscura_view* view = nullptr;
    ASSERT_EQ(obscura_create_view(ctx(), &view), OBSCURA_OK);
    std::vector<double> sum(one_frame.size(), 0.0);
    std::vector<bool> exact(one_frame.size(), true);
    double worst = 0.0, moved = 0.0;
    size_t checked = 0;
    for (uint32_t f = 0; f < 4; ++f) {
        const std::vector<float> alone = render_frames(ctx(), reset, settings, f, 1);
        EXPECT_LE(max_abs_difference(alone, render_frames(ctx(), scene.input, noisy_hbao(false), f, 1)), kAloneRounding);
        for (size_t i = 0; f > 0 && i < sum.size(); ++i) {
            const int x = int(i % kWidth), y = int(i / kWidth);
            const int window[7][2] = {{-1, -1}, {0, -1}, {-1, 0}, {0, 0}, {1, 0}, {0, 1}, {1, 1}};
            double s1 = 0.0, s2 = 0.0;
            for (const auto& o : window) {
                const int u = x + o[0], v = y + o[1];
                const double value = u >= 0 && u < kWidth && v >= 0 && v < kHeight ? alone[size_t(v) * kWidth + u] : alone[i];
                s1 += value;
                s2 += value * value;
            }
            const double mean = s1 / 7.0, spread = 64.0 * std::sqrt(std::max(0.0, s2 / 7.0 - mean * mean));
            const double history = sum[i] / f;
            const double low = std::min(mean - spread, double(alone[i])), high = std::max(mean + spread, double(alone[i]));
            const bool unchanged = std::fabs(history - alone[i]) < 1e-7;  // nothing for the clamp to move
            if (!unchanged && !(history > low + 1e-4 && history < high - 1e-4)) exact[i] = false;
        }
        for (size_t i = 0; i < sum.size(); ++i) sum[i] += alone[i];
        accumulated = render_frames(ctx(), scene.input, wide, f, 1, view);
        for (size_t i = 0; i < sum.size(); ++i) {
            if (!exact[i]) continue;
            worst = std::max(worst, std::fabs(accumulated[i] - sum[i] / (f + 1)));
            moved = std::max(moved, std::fabs(double(accumulated[i]) - alone[i]));
            checked += f == 3;
        }
    }
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(moved, 0.01) << "the frames' noise differs, so the mean is not any one frame";
    EXPECT_GT(checked, one_frame.size() / 2) << "the clamp left most pixels' histories alone";
    EXPECT_EQ(obscura_destroy_view(ctx(), view), OBSCURA_OK);
}

TEST_F(GLTest, TemporalResetAndMissingMatricesDropTheHistory) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    const obscura_settings settings = noisy_hbao(true);
    const std::vector<float> frame5_alone = render_frames(ctx(), scene.input, noisy_hbao(false), 5, 1);
    const std::vector<float> accumulated = render_frames(ctx(), scene.input, settings, 0, 6);
    EXPECT_GT(max_abs_difference(accumulated, frame5_alone), 0.01) << "the history should change frame 5";

    render_frames(ctx(), scene.input, settings, 0, 5);
    obscura_input cut = scene.input;
    cut.frame_index = 5;
    cut.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
    EXPECT_LE(max_abs_difference(render_visibility(ctx(), cut, settings), frame5_alone), kAloneRounding);

    render_frames(ctx(), scene.input, settings, 0, 5);
    obscura_input no_matrices = scene.input;
    no_matrices.frame_index = 5;
    std::memset(no_matrices.previous_view_projection, 0, sizeof no_matrices.previous_view_projection);
    EXPECT_LE(max_abs_difference(render_visibility(ctx(), no_matrices, settings), frame5_alone), kAloneRounding);
}

TEST_F(GLTest, TemporalViewsKeepSeparateHistoriesAndAResizeInvalidatesOnlyItsView) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    AoScene small = make_ao_scene(Projection::Perspective, scene.camera.view(),
                                  {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0))}, Lens(), 160, 90);
    set_matrices(&small.input, small.camera);
    const obscura_settings settings = noisy_hbao(true);
    const std::vector<float> alone = render_frames(ctx(), scene.input, settings, 0, 6);

    obscura_view* a = nullptr;
    obscura_view* b = nullptr;
    ASSERT_EQ(obscura_create_view(ctx(), &a), OBSCURA_OK);
    ASSERT_EQ(obscura_create_view(ctx(), &b), OBSCURA_OK);
    ASSERT_NE(a, b);
    std::vector<float> interleaved;
    for (uint32_t f = 0; f < 6; ++f) {
        // View b renders another scene at another size between a's frames (the context's shared textures are
        // reallocated every frame); a's history must not notice.
        render_frames(ctx(), small.input, settings, 100 + f, 1, b);
        interleaved = render_frames(ctx(), scene.input, settings, f, 1, a);
    }
    EXPECT_EQ(max_abs_difference(interleaved, alone), 0.0);
    // A resize drops the resized view's history (and only its): b at another size starts anew, as its first frame
    // alone; a goes on with its own.
    AoScene resized = make_ao_scene(Projection::Perspective, scene.camera.view(),
                                    {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0))}, Lens(), 128, 72);
    set_matrices(&resized.input, resized.camera);
    const std::vector<float> resized_alone = render_frames(ctx(), resized.input, noisy_hbao(false), 106, 1);
    EXPECT_LE(max_abs_difference(render_frames(ctx(), resized.input, settings, 106, 1, b), resized_alone), kAloneRounding);
    obscura_view* c = nullptr;
    ASSERT_EQ(obscura_create_view(ctx(), &c), OBSCURA_OK);
    const std::vector<float> seventh_alone = render_frames(ctx(), scene.input, settings, 0, 7, c);
    EXPECT_EQ(obscura_destroy_view(ctx(), c), OBSCURA_OK);
    EXPECT_EQ(max_abs_difference(render_frames(ctx(), scene.input, settings, 6, 1, a), seventh_alone), 0.0);
    EXPECT_GT(max_abs_difference(seventh_alone, render_frames(ctx(), scene.input, noisy_hbao(false), 6, 1)), 0.01)
        << "a's seventh frame carries its history";
    render_frames(ctx(), small.input, settings, 107, 1, b);  // back at 160x90 for the memory figure below
    uint64_t with_views = 0;
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &with_views), OBSCURA_OK);
    EXPECT_EQ(obscura_destroy_view(ctx(), b), OBSCURA_OK);
    uint64_t without_b = 0;
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &without_b), OBSCURA_OK);
    EXPECT_EQ(with_views - without_b, uint64_t(2) * 160 * 90 * 8) << "b's two RG32F histories";
    EXPECT_EQ(obscura_destroy_view(ctx(), b), OBSCURA_STATUS_INVALID_VIEW);
    EXPECT_EQ(obscura_destroy_view(ctx(), a), OBSCURA_OK);
}

// At reduced resolution several host sizes share one reduced grid (320 and 319 wide are both 160 at half) but map it
// to the screen differently: a host resize starts a new history as a resize of the grid does. Until 2026-12-06 only
// the grid's size was compared, and the 319-wide frame continued the 320-wide history (found by a read-only review:
// 0.118 off on a 64x48 -> 63x47 resize).
TEST_F(GLTest, TemporalHostResizeAtReducedResolutionStartsANewHistory) {
    AoScene wide = box_scene();
    AoScene narrower = make_ao_scene(Projection::Perspective, wide.camera.view(),
                                     {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                                      box(2, glm::dvec3(-kBoxHalf, 0.0, -kBoxHalf), glm::dvec3(kBoxHalf, kBoxHeight, kBoxHalf))},
                                     Lens(), kWidth - 1, kHeight);
    set_matrices(&wide.input, wide.camera);
    set_matrices(&narrower.input, narrower.camera);
    obscura_settings settings = noisy_hbao(true);
    settings.resolution.scale = OBSCURA_RESOLUTION_HALF;
    obscura_settings alone = noisy_hbao(false);
    alone.resolution.scale = OBSCURA_RESOLUTION_HALF;
    const std::vector<float> fifth_alone = render_frames(ctx(), narrower.input, alone, 5, 1);
    EXPECT_GT(max_abs_difference(render_frames(ctx(), narrower.input, settings, 0, 6), fifth_alone), 0.01)
        << "frames of one size accumulate";
    render_frames(ctx(), wide.input, settings, 0, 5);
    EXPECT_LE(max_abs_difference(render_frames(ctx(), narrower.input, settings, 5, 1), fifth_alone), kAloneRounding);
}

// A camera cut on a frame the SDK refuses (here: a bent-normal output that HBAO cannot fill) still drops the history:
// the next frame, without the flag, starts anew. Until 2026-12-06 the flag was read only once the frame got as far as
// the history, and the frame after the cut continued the history from before it.
TEST_F(GLTest, TemporalCameraCutOnARefusedFrameStillDropsTheHistory) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    const obscura_settings settings = noisy_hbao(true);
    const std::vector<float> fifth_alone = render_frames(ctx(), scene.input, noisy_hbao(false), 5, 1);
    render_frames(ctx(), scene.input, settings, 0, 5);
    obscura_input cut = scene.input;
    cut.frame_index = 5;
    cut.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
    HostTexture ao = make_texture(GL_R32F, kWidth, kHeight);
    HostTexture bent = make_texture(GL_RGBA16F, kWidth, kHeight);
    obscura_output output = make_output(ao.get());
    output.bent_normal_texture = bent.get();
    ASSERT_EQ(obscura_render(ctx(), &cut, &settings, &output), OBSCURA_STATUS_INVALID_SETTING);
    EXPECT_LE(max_abs_difference(render_frames(ctx(), scene.input, settings, 5, 1), fifth_alone), kAloneRounding);
    // The same for a cut on a frame whose output is refused before anything renders (a texture it also reads).
    render_frames(ctx(), scene.input, settings, 0, 5);
    obscura_output aliased = make_output(ao.get());
    cut.normal_texture = 0;
    cut.motion_vector_texture = ao.get();
    aliased.texture = ao.get();
    ASSERT_EQ(obscura_render(ctx(), &cut, &settings, &aliased), OBSCURA_STATUS_INVALID_TEXTURE);
    EXPECT_LE(max_abs_difference(render_frames(ctx(), scene.input, settings, 5, 1), fifth_alone), kAloneRounding);
}

// What of the input changes the AO as a setting would starts a new history: the scale of a metre (the radius in view
// units). Until 2026-12-06 only the settings were compared.
TEST_F(GLTest, TemporalChangeOfMetresToViewUnitsStartsANewHistory) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    const obscura_settings settings = noisy_hbao(true);
    obscura_input rescaled = scene.input;
    rescaled.meters_to_view_units = 2.0f;
    const std::vector<float> fifth_alone = render_frames(ctx(), rescaled, noisy_hbao(false), 5, 1);
    render_frames(ctx(), scene.input, settings, 0, 5);
    EXPECT_LE(max_abs_difference(render_frames(ctx(), rescaled, settings, 5, 1), fifth_alone), kAloneRounding);
}

// REFERENCE's first_ray only picks which rays of the sequence a frame traces, as GTAO's frame_index moves its noise: a
// host that advances it while accumulating keeps its history (until 2026-12-06 it was part of the history's
// signature, and every frame started anew).
TEST_F(GLTest, TemporalReferenceFirstRayKeepsTheHistory) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    obscura_settings settings;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_REFERENCE, &settings), OBSCURA_OK);
    settings.reference.rays = 4;
    settings.temporal.enabled = OBSCURA_TOGGLE_ON;
    std::vector<float> accumulated;
    for (uint32_t f = 0; f < 4; ++f) {
        settings.reference.first_ray = int32_t(f) * settings.reference.rays;
        accumulated = render_frames(ctx(), scene.input, settings, f, 1);
    }
    obscura_settings alone = settings;
    alone.temporal.enabled = OBSCURA_TOGGLE_OFF;
    EXPECT_GT(max_abs_difference(accumulated, render_frames(ctx(), scene.input, alone, 3, 1)), 0.05)
        << "the fourth frame carries the first three";
}

// GTAO's bent normals accumulate with the visibility, and the history's (in the previous view's space) is rotated
// into the current view. The camera drops 0.5 m between two frames (its pitch changes by 6.6 degrees, and with it the
// floor's normal in view space); on the open floor GTAO's bent normal is the floor's normal, so the accumulated
// bent normal there is the second view's one-frame bent normal when the history was rotated, and half the pitch
// change away from it when not. Also: the accumulated bent normals stay unit length. Measured on llvmpipe: 0.013
// degrees on average over 32168 open-floor pixels; 3.28 with the history left in the previous view's space.
TEST_F(GLTest, TemporalBentNormalsAccumulateInTheCurrentView) {
    AoScene before = box_seen_from(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0));
    AoScene after = box_seen_from(glm::dvec3(0.9, 1.9, 3.2), glm::dvec3(0.0, 0.3, 0.0));
    set_matrices(&before.input, before.camera);
    set_matrices(&after.input, after.camera, &before.camera);
    obscura_settings settings;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_GTAO, &settings), OBSCURA_OK);
    settings.temporal.enabled = OBSCURA_TOGGLE_ON;
    settings.temporal.max_frames = 2;  // the second frame: the history and the frame, half each
    obscura_settings alone = settings;
    alone.temporal.enabled = OBSCURA_TOGGLE_OFF;
    const auto render_bent = [&](const obscura_input& input, const obscura_settings& s) {
        return render_bent_normals(ctx(), input, s);
    };
    obscura_view* view = nullptr;
    ASSERT_EQ(obscura_create_view(ctx(), &view), OBSCURA_OK);
    obscura_input first = before.input, second = after.input;
    first.view = second.view = view;
    render_bent(first, settings);
    const std::vector<float> accumulated = render_bent(second, settings);
    const std::vector<float> second_alone = render_bent(after.input, alone);
    const std::vector<float> first_alone = render_bent(before.input, alone);
    ASSERT_EQ(obscura_destroy_view(ctx(), view), OBSCURA_OK);
    const auto at = [](const std::vector<float>& b, size_t i) { return glm::dvec3(b[4 * i], b[4 * i + 1], b[4 * i + 2]); };
    const auto angle = [](glm::dvec3 a, glm::dvec3 b) {
        return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 57.29577951308232;
    };
    const auto open_floor = [](const Hit& h) {
        return h.hit && h.id == 1 && footprint_distance(h) > 1.2 && h.view_depth() < 12.0;
    };
    double sum = 0.0, worst_length = 0.0;
    size_t count = 0, first_open = 0, second_open = 0;
    for (size_t i = 0; i < after.hits.size(); ++i) {
        if (!open_floor(after.hits[i])) continue;
        sum += angle(at(accumulated, i), at(second_alone, i));
        worst_length = std::max(worst_length, std::fabs(glm::length(at(accumulated, i)) - 1.0));
        second_open = i;
        ++count;
    }
    for (size_t i = 0; i < before.hits.size(); ++i) first_open = open_floor(before.hits[i]) ? i : first_open;
    // The floor's normal in each view (the same at every open-floor pixel of a view).
    const double pitch = angle(at(first_alone, first_open), at(second_alone, second_open));
    ASSERT_GT(count, 1000u);
    std::printf("open floor: %zu pixels, accumulated against the second view's own %.4f degrees; the views' floor "
                "normals %.2f degrees apart\n", count, sum / double(count), pitch);
    EXPECT_GT(pitch, 5.0) << "the camera's pitch changed: the history must be rotated";
    EXPECT_LT(sum / double(count), 0.2);
    EXPECT_LT(worst_length, 1e-3);
}

// Where the AO changes under a surface that stays (here the box vanishes from the floor between two frames of a still
// camera), the neighbourhood clamp holds the visibility's history to this frame's, and the bent normal must follow: it
// is blended at the weight the clamp left the visibility's history. Until 2026-12-06 the bent normal kept (N - 1) / N of
// its history whatever the clamp did, so the floor beside the vanished box showed this frame's visibility with a bent
// normal still leaning away from the box (found by a read-only review).
TEST_F(GLTest, TemporalBentNormalsFollowTheClampWhereTheAoChanged) {
    AoScene with_box = box_scene();
    AoScene floor_only = make_ao_scene(Projection::Perspective, with_box.camera.view(),
                                       {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0))});
    set_matrices(&with_box.input, with_box.camera);
    set_matrices(&floor_only.input, floor_only.camera);
    obscura_settings settings;
    ASSERT_EQ(obscura_default_settings(OBSCURA_METHOD_GTAO, &settings), OBSCURA_OK);
    settings.temporal.enabled = OBSCURA_TOGGLE_ON;
    obscura_settings alone = settings;
    alone.temporal.enabled = OBSCURA_TOGGLE_OFF;
    const auto render_bent = [&](obscura_input input, const obscura_settings& s, uint32_t frame) {
        input.frame_index = frame;
        return render_bent_normals(ctx(), input, s);
    };
    for (uint32_t f = 0; f < 8; ++f) render_bent(with_box.input, settings, f);
    const std::vector<float> accumulated = render_bent(floor_only.input, settings, 8);
    const std::vector<float> box_alone = render_bent(with_box.input, alone, 8);
    const std::vector<float> floor_alone = render_bent(floor_only.input, alone, 8);
    // The bent-normal texture holds the normal in rgb and the visibility in a (obscura_output::bent_normal_texture).
    const auto at = [](const std::vector<float>& b, size_t i) { return glm::dvec3(b[4 * i], b[4 * i + 1], b[4 * i + 2]); };
    const auto visibility = [](const std::vector<float>& b, size_t i) { return b[4 * i + 3]; };
    const auto angle = [](glm::dvec3 a, glm::dvec3 b) {
        return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 57.29577951308232;
    };
    // The floor pixels whose bent normal the box tilted by more than 3 degrees (and whose visibility it lowered by more than 0.05).
    double lean = 0.0, left = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < floor_only.hits.size(); ++i) {
        if (!with_box.hits[i].hit || with_box.hits[i].id != 1) continue;  // the floor in both images
        const double tilt = angle(at(box_alone, i), at(floor_alone, i));
        if (tilt < 3.0 || visibility(floor_alone, i) - visibility(box_alone, i) < 0.05) continue;
        lean += tilt;
        left += angle(at(accumulated, i), at(floor_alone, i));
        ++count;
    }
    ASSERT_GT(count, 200u);
    std::printf("floor beside the box: %zu pixels, the box tilted their bent normals %.2f degrees; after it vanished "
                "the accumulated ones are %.2f degrees off this frame's\n", count, lean / double(count),
                left / double(count));
    EXPECT_LT(left, 0.25 * lean);
}

TEST_F(GLTest, TemporalMotionVectorsAndMatricesReprojectAlike) {
    // The camera turns and moves a little between two frames; the motion vectors are the exact screen motion of
    // each pixel's surface point (the CPU ray cast's hit projected through the previous camera).
    AoScene before = box_seen_from(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0));
    AoScene after = box_seen_from(glm::dvec3(0.95, 2.38, 3.18), glm::dvec3(0.02, 0.3, 0.0));
    std::vector<float> motion(size_t(kWidth) * kHeight * 2, 0.0f);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const Hit& h = after.hits[size_t(y) * kWidth + x];
            if (!h.hit) continue;
            const glm::dvec2 previous = before.camera.project(h.world);
            motion[(size_t(y) * kWidth + x) * 2] = float(previous.x - (x + 0.5));
            motion[(size_t(y) * kWidth + x) * 2 + 1] = float(previous.y - (y + 0.5));
        }
    }
    HostTexture vectors = make_texture(GL_RG32F, kWidth, kHeight);
    glBindTexture(GL_TEXTURE_2D, vectors.get());
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RG, GL_FLOAT, motion.data());
    glBindTexture(GL_TEXTURE_2D, 0);

    set_matrices(&before.input, before.camera);
    set_matrices(&after.input, after.camera, &before.camera);
    const std::vector<bool> mask = geometry_mask(after);
    // At reduced resolution the temporal pass reads the host's vectors at the host's texel and scales them to the
    // reduced grid, and the matrices are remapped to it: the two must still agree.
    for (obscura_resolution scale : {OBSCURA_RESOLUTION_FULL, OBSCURA_RESOLUTION_HALF, OBSCURA_RESOLUTION_QUARTER}) {
        SCOPED_TRACE(scale);
        obscura_settings settings = noisy_hbao(true);
        settings.resolution.scale = scale;
        obscura_settings alone = noisy_hbao(false);
        alone.resolution.scale = scale;
        obscura_input first = before.input;
        obscura_input second = after.input;
        second.frame_index = 1;
        first.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
        render_visibility(ctx(), first, settings);
        const std::vector<float> by_matrices = render_visibility(ctx(), second, settings);
        const std::vector<float> second_alone = render_frames(ctx(), second, alone, 1, 1);

        render_visibility(ctx(), first, settings);
        obscura_input by_vectors_input = second;
        by_vectors_input.motion_vector_texture = vectors.get();
        std::memset(by_vectors_input.view_projection, 0, sizeof by_vectors_input.view_projection);
        std::memset(by_vectors_input.previous_view_projection, 0, sizeof by_vectors_input.previous_view_projection);
        const std::vector<float> by_vectors = render_visibility(ctx(), by_vectors_input, settings);

        // Measured on llvmpipe: the history moves the second frame by 0.0018 on average at full resolution (most
        // of the floor is unoccluded in every frame), and the two reprojections agree to 0 at every resolution.
        EXPECT_GT(mean_abs_difference(by_matrices, second_alone, mask), 0.001) << "the history was not used";
        EXPECT_LT(mean_abs_difference(by_vectors, by_matrices, mask), 1e-4);
    }
}

// A host that fits its near and far planes per frame: the camera stands still, the projection's depth row changes
// (near 0.10 -> 0.12, far 100 -> 150). The history's depths are found through the rows the two projections share;
// through the inverse of this frame's projection the points moved by up to 19 % of their distance, every texel
// failed the plane test and the history was dropped (found by a read-only review of the reprojection).
TEST_F(GLTest, TemporalChangedNearAndFarPlanesKeepTheHistory) {
    const glm::dmat4 view = look_at(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0));
    const std::vector<Primitive> box_on_floor = {
        plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
        box(2, glm::dvec3(-kBoxHalf, 0.0, -kBoxHalf), glm::dvec3(kBoxHalf, kBoxHeight, kBoxHalf))};
    Lens fitted;
    fitted.near_plane = 0.12;
    fitted.far_plane = 150.0;
    AoScene before = make_ao_scene(Projection::Perspective, view, box_on_floor);
    AoScene after = make_ao_scene(Projection::Perspective, view, box_on_floor, fitted);
    AoScene after_twice = make_ao_scene(Projection::Perspective, view, box_on_floor, fitted);
    set_matrices(&before.input, before.camera);
    set_matrices(&after.input, after.camera, &before.camera);
    set_matrices(&after_twice.input, after_twice.camera);
    const std::vector<bool> mask = geometry_mask(after);
    const obscura_settings settings = noisy_hbao(true);
    obscura_input first = before.input, second = after.input;
    first.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
    second.frame_index = 1;
    render_visibility(ctx(), first, settings);
    const std::vector<float> changed = render_visibility(ctx(), second, settings);
    const std::vector<float> second_alone = render_frames(ctx(), second, noisy_hbao(false), 1, 1);
    // The same two frames with the second frame's planes in both (a still camera: the history is kept).
    obscura_input same_first = after_twice.input, same_second = after_twice.input;
    same_first.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
    same_second.frame_index = 1;
    render_visibility(ctx(), same_first, settings);
    const std::vector<float> kept = render_visibility(ctx(), same_second, settings);
    EXPECT_GT(mean_abs_difference(kept, second_alone, mask), 0.001) << "the scene must show the history's effect";
    EXPECT_LT(mean_abs_difference(changed, kept, mask), 2e-4) << "the history was dropped";
}

// A pixel whose point was outside the texture in the previous frame (a camera pan uncovering a strip at the edge)
// has no history: the 2x2 block it reprojects to lies wholly past the output rectangle's edge, and the gathers'
// clamped edge texels there are another point's history. Each tap is tested against both edges of each axis (until
// 2026-12-06 a tap was tested against one edge only, and the uncovered strip of a floor continued the edge column's
// history, at its age). Motion vectors move the whole image by half its size in each of the four directions.
TEST_F(GLTest, TemporalReprojectionPastTheTexturesEdgeStartsANewHistory) {
    AoScene scene = box_scene();
    obscura_input input = scene.input;
    std::memset(input.view_projection, 0, sizeof input.view_projection);
    std::memset(input.previous_view_projection, 0, sizeof input.previous_view_projection);
    const obscura_settings on = noisy_hbao(true), off = noisy_hbao(false);
    const std::vector<bool> geometry = geometry_mask(scene);
    const glm::vec2 shifts[] = {{0.5f * kWidth + 0.3f, 0.0f},
                                {-0.5f * kWidth - 0.3f, 0.0f},
                                {0.0f, 0.5f * kHeight + 0.3f},
                                {0.0f, -0.5f * kHeight - 0.3f}};
    for (const glm::vec2 shift : shifts) {
        SCOPED_TRACE(testing::Message() << "shift " << shift.x << ", " << shift.y);
        std::vector<float> motion(size_t(kWidth) * kHeight * 2);
        for (size_t i = 0; i < motion.size(); i += 2) {
            motion[i] = shift.x;
            motion[i + 1] = shift.y;
        }
        HostTexture vectors = make_texture(GL_RG32F, kWidth, kHeight);
        glBindTexture(GL_TEXTURE_2D, vectors.get());
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RG, GL_FLOAT, motion.data());
        glBindTexture(GL_TEXTURE_2D, 0);

        obscura_input first = input;
        first.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
        render_visibility(ctx(), first, on);
        obscura_input second = input;
        second.frame_index = 1;
        second.motion_vector_texture = vectors.get();
        const std::vector<float> accumulated = render_visibility(ctx(), second, on);
        const std::vector<float> alone = render_frames(ctx(), second, off, 1, 1);

        // The pixels whose reprojected block lies wholly outside the texture (a texel or more past its edge), and
        // among them those with occlusion: where frame 0 and frame 1 differ, so that a history would show.
        std::vector<bool> uncovered(geometry.size(), false);
        int occluded = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const size_t i = size_t(y) * kWidth + x;
                const float base_x = std::floor(float(x) + shift.x), base_y = std::floor(float(y) + shift.y);
                const bool outside = base_x >= float(kWidth) || base_x + 1.0f < 0.0f || base_y >= float(kHeight) ||
                                     base_y + 1.0f < 0.0f;
                uncovered[i] = geometry[i] && outside;
                if (uncovered[i] && alone[i] < 0.95f) ++occluded;
            }
        }
        ASSERT_GT(occluded, 100) << "the test needs occluded pixels in the uncovered half";
        double worst = 0.0;
        for (size_t i = 0; i < uncovered.size(); ++i) {
            if (uncovered[i]) worst = std::max(worst, std::fabs(double(accumulated[i]) - double(alone[i])));
        }
        // Measured on llvmpipe: 0 after the fix; before it 0.37, 0.36 and 0.17 for three of the four shifts, where the
        // floor continued the edge column's history.
        EXPECT_LE(worst, kAloneRounding);
    }
}

TEST_F(GLTest, TemporalOrbitStaysOnTheStillImageUpToTheOutputRectanglesEdge) {
    // 16 frames orbiting the box 1 degree a frame, with a guard band (the output rectangle inside the depth), HBAO
    // with 32 directions (little noise): the accumulated last frame must stay on the still image of the last camera,
    // at the rectangle's edge too, where only the rectangle's texels of this frame's AO and of the history count.
    const std::vector<Primitive> primitives = {
        plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
        box(2, glm::dvec3(-kBoxHalf, 0.0, -kBoxHalf), glm::dvec3(kBoxHalf, kBoxHeight, kBoxHalf))};
    std::vector<AoScene> scenes;
    for (int f = 0; f < 16; ++f) {
        const double a = glm::radians(1.0 * f);
        const glm::dvec3 eye(0.9 * std::cos(a) - 3.2 * std::sin(a), 2.4, 0.9 * std::sin(a) + 3.2 * std::cos(a));
        scenes.push_back(make_ao_scene(Projection::Perspective, look_at(eye, glm::dvec3(0.0, 0.3, 0.0)), primitives));
    }
    const obscura_rect rect = {32, 18, 256, 144};
    obscura_settings on = noisy_hbao(true), off = noisy_hbao(false);
    on.hbao.directions = off.hbao.directions = 32;
    std::vector<float> accumulated;
    for (int f = 0; f < 16; ++f) {
        obscura_input input = scenes[f].input;
        input.output_rect = rect;
        set_matrices(&input, scenes[f].camera, f > 0 ? &scenes[f - 1].camera : nullptr);
        input.frame_index = uint32_t(f);
        accumulated = render_visibility(ctx(), input, on);
    }
    obscura_input input = scenes.back().input;
    input.output_rect = rect;
    const std::vector<float> still = render_visibility(ctx(), input, off);
    std::vector<bool> all(size_t(rect.width) * rect.height, true), edge(all.size(), false);
    for (int y = 0; y < rect.height; ++y)
        for (int x = 0; x < rect.width; ++x)
            edge[size_t(y) * rect.width + x] = x < 2 || y < 2 || x >= rect.width - 2 || y >= rect.height - 2;
    // Measured on llvmpipe: 0.00045 over the rectangle, 0.00004 on its 2-texel edge (0.0016 and 0.027 when the edge
    // read this frame's AO and the history outside the rectangle).
    EXPECT_LT(mean_abs_difference(accumulated, still, all), 0.001);
    EXPECT_LT(mean_abs_difference(accumulated, still, edge), 0.003);
    // The history was used: the last frame is not that frame rendered alone (which would also stay near the still
    // image: 32 directions are little noise). Measured: up to 0.079 apart (0.00033 on average), where a history dropped
    // every frame leaves at most one R16F step (2^-11). (The 2-texel edge is unoccluded floor in this view, 1 in every
    // frame: there the test checks that nothing outside the rectangle is read.)
    obscura_input last = input;
    last.frame_index = 15;
    EXPECT_GT(max_abs_difference(accumulated, render_visibility(ctx(), last, off)), 0.01) << "the history was not used";
}

// The host's previous frame may have been a debug view, which shows that frame alone and leaves the view's history
// as it was: the next frame's previous_view_projection then describes the debug frame, a frame of motion after the
// history. With matrices the SDK reprojects from the frame the history was made at, so the debug frame between
// changes nothing; a camera cut on the debug frame still drops the history.
TEST_F(GLTest, TemporalDebugViewFramesLeaveTheHistoryAndTheCameraItWasMadeWith) {
    const std::vector<Primitive> primitives = {
        plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
        box(2, glm::dvec3(-kBoxHalf, 0.0, -kBoxHalf), glm::dvec3(kBoxHalf, kBoxHeight, kBoxHalf))};
    const glm::dvec3 target(0.0, 0.3, 0.0);
    AoScene first_scene = make_ao_scene(Projection::Perspective, look_at(glm::dvec3(0.9, 2.4, 3.2), target), primitives);
    AoScene debug_scene = make_ao_scene(Projection::Perspective, look_at(glm::dvec3(1.0, 2.4, 3.1), target), primitives);
    AoScene last_scene = make_ao_scene(Projection::Perspective, look_at(glm::dvec3(1.1, 2.4, 3.0), target), primitives);
    const obscura_settings settings = noisy_hbao(true);
    obscura_input first = first_scene.input;
    set_matrices(&first, first_scene.camera);
    first.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
    obscura_input debug = debug_scene.input;
    set_matrices(&debug, debug_scene.camera, &first_scene.camera);
    debug.frame_index = 1;

    // Without the debug frame: the last frame follows the first.
    obscura_input last = last_scene.input;
    set_matrices(&last, last_scene.camera, &first_scene.camera);
    last.frame_index = 2;
    render_visibility(ctx(), first, settings);
    const std::vector<float> direct = render_visibility(ctx(), last, settings);
    const std::vector<float> last_alone = render_frames(ctx(), last, noisy_hbao(false), 2, 1);
    EXPECT_GT(mean_abs_difference(direct, last_alone, geometry_mask(last_scene)), 0.001) << "the history was not used";

    // With it, as the host saw it: the last frame's previous camera is the debug frame's.
    obscura_input after_debug = last;
    set_matrices(&after_debug, last_scene.camera, &debug_scene.camera);
    render_visibility(ctx(), first, settings);
    render_visibility(ctx(), debug, settings, OBSCURA_DEBUG_AO_BEFORE_BLUR);
    EXPECT_EQ(max_abs_difference(render_visibility(ctx(), after_debug, settings), direct), 0.0);

    // A camera cut on the debug frame.
    render_visibility(ctx(), first, settings);
    debug.flags = OBSCURA_INPUT_FLAG_RESET_HISTORY;
    render_visibility(ctx(), debug, settings, OBSCURA_DEBUG_AO_BEFORE_BLUR);
    EXPECT_LE(max_abs_difference(render_visibility(ctx(), after_debug, settings), last_alone), kAloneRounding);
}

// Motion vectors give the offsets to the host's previous frame, so the history must be that frame's: it continues
// when the frame index advanced by one since the history was made and is dropped when it advanced by two (the
// host skipped the SDK for a frame, or showed a debug view then).
TEST_F(GLTest, TemporalMotionVectorsContinueOnlyFromThePreviousFrameIndex) {
    AoScene scene = box_scene();  // a still camera: zero vectors
    const std::vector<float> zeros(size_t(kWidth) * kHeight * 2, 0.0f);
    HostTexture vectors = make_texture(GL_RG32F, kWidth, kHeight);
    glBindTexture(GL_TEXTURE_2D, vectors.get());
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kWidth, kHeight, GL_RG, GL_FLOAT, zeros.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    obscura_input input = scene.input;  // no matrices
    input.motion_vector_texture = vectors.get();
    const obscura_settings settings = noisy_hbao(true);
    const std::vector<float> frame5_alone = render_frames(ctx(), input, noisy_hbao(false), 5, 1);
    const std::vector<float> frame6_alone = render_frames(ctx(), input, noisy_hbao(false), 6, 1);

    EXPECT_GT(max_abs_difference(render_frames(ctx(), input, settings, 0, 6), frame5_alone), 0.01)
        << "frames 0-4, then 5: the history continues";
    render_frames(ctx(), input, settings, 0, 5);
    EXPECT_LE(max_abs_difference(render_frames(ctx(), input, settings, 6, 1), frame6_alone), kAloneRounding)
        << "frames 0-4, then 6: a frame missing, the history dropped";
}

TEST_F(GLTest, TemporalInputErrors) {
    AoScene scene = box_scene();
    set_matrices(&scene.input, scene.camera);
    const obscura_settings settings = noisy_hbao(true);
    HostTexture target = make_texture(GL_R16F, kWidth, kHeight);
    const obscura_output output = make_output(target.get());

    ContextPtr other = create_context();
    obscura_view* foreign = nullptr;
    ASSERT_EQ(obscura_create_view(other.get(), &foreign), OBSCURA_OK);
    obscura_input input = scene.input;
    input.view = foreign;
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_VIEW);
    EXPECT_EQ(obscura_destroy_view(ctx(), foreign), OBSCURA_STATUS_INVALID_VIEW);
    EXPECT_EQ(obscura_destroy_view(other.get(), foreign), OBSCURA_OK);

    input = scene.input;
    input.flags = 0x10;
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_SETTING);
    input = scene.input;
    std::fill(std::begin(input.view_projection), std::end(input.view_projection), 0.0f);
    input.view_projection[0] = 1.0f;  // rank 1
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_PROJECTION);
    // Each matrix is checked on its own: a first frame (no previous matrix) with a broken one is refused then, not a
    // frame later.
    std::fill(std::begin(input.previous_view_projection), std::end(input.previous_view_projection), 0.0f);
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_PROJECTION);
    input = scene.input;
    std::fill(std::begin(input.previous_view_projection), std::end(input.previous_view_projection), 0.0f);
    input.view_projection[5] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_PROJECTION);
    input = scene.input;
    std::fill(std::begin(input.view_projection), std::end(input.view_projection), 0.0f);
    input.previous_view_projection[2] = std::numeric_limits<float>::infinity();
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_PROJECTION);
    input = scene.input;
    store_raw(&input.motion_vector_units, 7);
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_ENUM);
    HostTexture wrong_format = make_texture(GL_RGBA8, kWidth, kHeight);
    input = scene.input;
    input.motion_vector_texture = wrong_format.get();
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_UNSUPPORTED_FORMAT);
    HostTexture wrong_size = make_texture(GL_RG16F, kWidth / 2, kHeight);
    input.motion_vector_texture = wrong_size.get();
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_STATUS_INVALID_TEXTURE);

    // A 0.4 obscura_input (without the temporal fields) still renders.
    input = scene.input;
    input.struct_size = uint32_t(offsetof(obscura_input, normal_texture) + sizeof(uint32_t));
    EXPECT_EQ(obscura_render(ctx(), &input, &settings, &output), OBSCURA_OK);
    EXPECT_EQ(obscura_create_view(ctx(), nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_destroy_view(ctx(), nullptr), OBSCURA_OK);
}

}  // namespace
}  // namespace obscura_test
