// Image error metrics for AO: what the golden tests, `obscura diff` and method comparisons measure.
//
// Pure CPU code (no GL). Images are FloatImage (image_io.h), rows bottom-up; AO images hold ambient
// visibility in [0, 1], one channel. The error of a pixel is |image - reference|; for images of
// several channels it is the largest channel difference (convert to one channel with luminance()
// first to compare brightness only). A NaN or infinite sample in either image makes that pixel's
// error 1, the largest error two visibility images can have, so broken pixels are never hidden.
//
// The two main metrics are those of Timonen, "Screen-Space Far-Field Ambient Obscurance" (HPG 2013),
// sec. 8: e_A, the mean absolute error, and e_<5%, the fraction of pixels within 5 % of the reference.
// PSNR, the largest error and the fraction over a CI threshold are added for logs and tolerances.
#ifndef OBSCURA_SAMPLES_METRICS_H
#define OBSCURA_SAMPLES_METRICS_H

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "image_io.h"

namespace obscura::samples {

// The default "off by more than" threshold of ErrorMetrics::over_threshold: 4 steps of an 8-bit image.
constexpr double kDefaultErrorThreshold = 4.0 / 255.0;

struct ErrorMetrics {
    double mean_abs = 0.0;        // e_A: mean pixel error
    double mean_signed = 0.0;     // mean of image - reference (first channel; non-finite pixels left out):
                                  // > 0 the image is brighter (less occluded) than the reference
    double within_5pct = 1.0;     // e_<5%: fraction of pixels with error <= 0.05 (absolute, visibility units)
    double over_threshold = 0.0;  // fraction of pixels with error > `threshold`
    double threshold = kDefaultErrorThreshold;
    double psnr = 0.0;            // 10 log10(1 / MSE) in dB (peak 1); +infinity when no pixel differs.
                                  // JSON has no infinity: writers print null (JsonWriter does so).
    double max_abs = 0.0;         // largest pixel error
    size_t pixels = 0;            // pixels compared
    size_t signed_pixels = 0;     // of them, those whose signed difference is finite (mean_signed's count)
    size_t pixels_total = 0;      // pixels of the image: pixels_total - pixels were masked out (sky)
};

// Compares `image` against `reference`. Both must have the same width, height and channel count and
// hold width * height * channels values (std::invalid_argument otherwise). `mask`, when given, holds
// one byte per pixel (same row order); only pixels whose byte is non-zero are compared, and a mask of
// another size is std::invalid_argument. With no pixel compared every fraction and error is 0 except
// within_5pct (1) and psnr (+infinity): nothing differs.
ErrorMetrics compare_images(const FloatImage& image, const FloatImage& reference,
                            const std::vector<uint8_t>* mask = nullptr,
                            double threshold = kDefaultErrorThreshold);

// One channel per pixel: 1 channel is kept, 3 or 4 become the mean of R, G and B (alpha ignored).
// std::invalid_argument for other channel counts.
FloatImage luminance(const FloatImage& image);

// What an image looks like after write_png and read_png: every sample clamped to [0, 1] and rounded
// to the nearest of 256 levels. NaN stays NaN (write_png would store 0), so it is still caught.
FloatImage quantize_8bit(const FloatImage& image);

// RGB heat map of the pixel error (see above): white at 0, yellow at a third of `full_scale`, red at
// two thirds, black at `full_scale` and above (the FFAO paper's error images use 0.2: white 0 %, black
// >= 20 %). Same size rules as compare_images; `full_scale` must be > 0.
FloatImage error_heat_map(const FloatImage& image, const FloatImage& reference, double full_scale = 0.2);

// RGB map of the signed error image - reference (first channel): white at 0, towards red where the image is
// darker than the reference (too much occlusion: halos, darkened silhouettes), towards blue where it is
// brighter (missing occlusion: lost contact shadows), saturated from `full_scale` on. Non-finite samples are
// black. Same size rules as compare_images; `full_scale` must be > 0.
FloatImage signed_error_map(const FloatImage& image, const FloatImage& reference, double full_scale = 0.2);

// Temporal stability against a reference along the same camera path: the mean over consecutive frame
// pairs i, i+1 and over pixels of |(m[i+1] - m[i]) - (r[i+1] - r[i])|, so a method that changes
// exactly as the reference does scores 0 whatever its constant error. Needs as many method frames as
// reference frames, at least two, all of one size (std::invalid_argument otherwise). Several channels:
// the largest channel difference; non-finite samples: 1.
// `masks`, when given, holds one mask per frame (compare_images' kind): only pixels that are non-zero in both
// frames of a pair count (the geometry seen in both); with none counted the flicker is 0.
double flicker(const std::vector<FloatImage>& method_frames, const std::vector<FloatImage>& reference_frames,
               const std::vector<std::vector<uint8_t>>* masks = nullptr);

// How the camera saw one frame: each output pixel's view depth and the matrices that take it to the world.
struct FrameGeometry {
    FloatImage view_depth;        // positive view depth of each pixel of the output rectangle; sky: 0 or not finite
    glm::dmat4 view{1.0};         // world -> view
    glm::dmat4 projection{1.0};   // view -> clip of the whole depth texture (guard band included)
    int depth_width = 0;          // the depth texture's size, and where the output rectangle sits in it
    int depth_height = 0;
    int rect_x = 0;
    int rect_y = 0;
    // The pixels that see a part of the scene that moved since the previous frame (one byte per pixel, as
    // view_depth; empty: none), and how far that part moved (world space): surface_flicker follows such a point
    // back to where it was.
    std::vector<uint8_t> moving;
    glm::dvec3 motion{0.0};
    // The world-space unit normal of each pixel's surface (one per pixel, as view_depth; empty: the depth alone
    // decides what is the same surface). Either facing counts: the scene's faces are seen from both sides.
    std::vector<glm::vec3> normal;
};

// Two texels see the same surface only if their normals are within 45 degrees (either facing), when both frames
// carry normals: at a crease the other face's texels lie within any depth tolerance of the point, and reading the
// previous image across the fold measured the fold's AO kink as flicker (a view-independent truth "flickered" twice
// as much as accumulated HBAO on the atrium's orbit). Curved meshes' neighbouring facets stay well inside it.
constexpr double kSameSurfaceMinCosine = 0.70710678;

// Flicker as a viewer sees it: how much the AO of a surface point changes from one frame to the next. Each geometry
// pixel of frame f is taken to the world through its view depth (on a moving part, moved back by its motion),
// projected into frame f - 1 and compared with frame f - 1's image there (bilinear), where every texel around that
// point with bilinear weight sees the same surface (its view depth within depth_tolerance of the point's, relative,
// and, with normals, its normal within kSameSurfaceMinCosine of the point's);
// other pixels (disoccluded, off screen, sky) do not count. The mean of |difference| over the counted pixels and frame
// pairs (first channels); nullopt when none counts (nothing was measured, which is not "no flicker"). A still camera
// and scene make it the plain mean change per geometry pixel. `frames` and `geometry` of one count, >= 2, and one
// size (std::invalid_argument otherwise).
std::optional<double> surface_flicker(const std::vector<FloatImage>& frames, const std::vector<FrameGeometry>& geometry,
                                      double depth_tolerance = 0.02);

// Frames since each pixel's surface point came into view, following the point from frame to frame as
// surface_flicker does: 0 where the previous frame did not see it (off the image, or none of the four texels around
// it within depth_tolerance of its depth: hidden, disoccluded now), the age of the nearest texel that saw it plus one
// where one did, -1 where that was -1, on sky and everywhere in frame 0 (no event seen yet). What the ghosting
// measure of a moving camera counts from (samples::error_by_age). std::invalid_argument for images of different sizes.
std::vector<std::vector<int>> frames_since_disocclusion(const std::vector<FrameGeometry>& geometry,
                                                        double depth_tolerance = 0.02);

// ---- Ghosting: how far a temporal accumulation lags behind a change -------------------------------------
//
// Frames since each pixel's last event, per frame: ages[f][i] = 0 where alive[f][i] and event[f][i]; ages[f-1][i] + 1
// where alive[f][i], no event, and ages[f-1][i] >= 0; -1 otherwise (no event since the pixel came alive, or not alive
// now: on the moving object, sky). `event` and `alive`: one byte per pixel per frame, as many frames and pixels each
// (std::invalid_argument otherwise).
std::vector<std::vector<int>> frames_since_event(const std::vector<std::vector<uint8_t>>& event,
                                                 const std::vector<std::vector<uint8_t>>& alive);

// The error of the pixels of one age, pooled over the frames.
struct AgeErrors {
    size_t pixels = 0;
    double mean_abs = 0.0;            // |frames - truth|
    double converged_mean_abs = 0.0;  // |converged - truth| of the same pixels in the same frames
};
// Buckets 0 .. max_age - 1 hold the pixels of that age (frames_since_event), bucket max_age every age >= max_age.
// First channels; every image of one size and as many frames of each as `ages` has (std::invalid_argument
// otherwise). A bucket without pixels has errors 0.
std::vector<AgeErrors> error_by_age(const std::vector<FloatImage>& frames, const std::vector<FloatImage>& converged,
                                    const std::vector<FloatImage>& truth, const std::vector<std::vector<int>>& ages,
                                    int max_age);

// Mean angle in degrees between the directions in the first three channels of `image` and of `reference` (each
// normalised; a zero or non-finite vector counts 180 degrees), over the pixels `mask` (compare_images' kind) keeps:
// bent normals against the geometry truth's. Both need >= 3 channels and one size (std::invalid_argument
// otherwise); 0 when no pixel counts.
double mean_angle_degrees(const FloatImage& image, const FloatImage& reference, const std::vector<uint8_t>* mask = nullptr);

// ---- Thickness classes: where a screen-space method's thickness assumption matters -------------------
//
// A screen-space method sees only the depth buffer's front surfaces and must assume how thick they are. Its
// error against the geometry truth is then concentrated in two kinds of pixels, told apart here so that an
// error can be split by where it is (obscura compare --classes):
//   Silhouette  the near side of a depth discontinuity: a geometry pixel p with a 4-neighbour q whose view
//               depth exceeds p's by more than max(kSilhouetteMinStep, kSilhouetteRelativeStep * depth(p));
//               a sky neighbour counts as infinitely far; neighbours outside the image do not count.
//   Halo        not a silhouette, and some silhouette pixel within the AO radius on screen is nearer to the
//               camera than p by more than the thickness T: min of the silhouettes' view depth over the square
//               window of half-size r_px(p) around p (clipped to the image) < depth(p) - T. p lies behind an
//               occluder's edge: a method that takes the occluder as infinitely thick darkens p there although
//               the truth's rays may pass behind it. (Any nearer pixel would make every receding floor a halo
//               of its own nearer part: 79 % of the atrium at 320x180.)
//   Rest        every other geometry pixel.
//   Sky         no geometry (the mask's 0).
// r_px(p) = min(max_radius_px, radius_m * pixels_per_metre_at_1m / depth(p)), rounded down: how many pixels the
// radius covers at p's depth under a perspective projection (pixels_per_metre_at_1m = 0.5 * H * |P[1][1]| for
// an image H pixels high and the GL projection P of that image; the same scale horizontally with square pixels).
enum class ThicknessClass : uint8_t { Sky = 0, Rest = 1, Halo = 2, Silhouette = 3 };
constexpr int kThicknessClassCount = 4;
constexpr double kSilhouetteMinStep = 0.1;        // metres
constexpr double kSilhouetteRelativeStep = 0.05;  // of p's depth

// "sky", "rest", "halo", "silhouette".
const char* thickness_class_name(ThicknessClass value);

// One byte per pixel (a ThicknessClass, rows as `view_depth`'s: bottom-up) for `view_depth`: 1 channel,
// positive view depth in metres (distance from the eye plane) on geometry, anything on sky, and
// `geometry_mask`: compare_images' kind, one byte per pixel, non-zero on geometry. Units: radius_m and
// thickness_m in metres (the method's AO radius and the thickness T), pixels_per_metre_at_1m in pixels,
// max_radius_px in pixels (caps the window: its cost and the reach of a radius seen from very close).
// Cost: O(pixels * log(window)) for a min pyramid (WindowMinimum), then O(1) per pixel.
// std::invalid_argument for a view_depth whose size and pixel count do not match or that has more than one
// channel, a mask of another size, a geometry pixel whose depth is not finite and positive, radius_m or
// pixels_per_metre_at_1m not finite and > 0, thickness_m or max_radius_px not finite and >= 0.
std::vector<uint8_t> thickness_classes(const FloatImage& view_depth, const std::vector<uint8_t>& geometry_mask,
                                       double radius_m, double thickness_m, double pixels_per_metre_at_1m,
                                       double max_radius_px);

// An RGB picture of thickness_classes' result (`width` * `height` bytes, rows bottom-up): sky black, rest
// white, halo blue, silhouette red. std::invalid_argument for a size that does not match or a byte that
// is not a class.
FloatImage thickness_class_image(const std::vector<uint8_t>& classes, int width, int height);

// The minimum of a 1-channel image over square windows, O(1) per query: a sparse table (min pyramid) of the
// minima over every 2^k x 2^k window at every position, k = 0 ... floor(log2(2 max_half_size + 1)) (limited by
// the image's size), level k holding (W - 2^k + 1) x (H - 2^k + 1) floats (about 16 M, 64 MB, at 1920x1080 with
// a half size of 256); a query covers its window with overlapping 2^k squares (4 for a
// window inside the image, a few more where the image's border cuts it: at most 8 while the image is larger than
// the half size both ways). Samples that must not count are +infinity.
class WindowMinimum {
public:
    // std::invalid_argument for an image whose size and pixel count do not match, more than one channel, a NaN
    // sample, or max_half_size < 0.
    WindowMinimum(const FloatImage& image, int max_half_size);

    // The minimum over the pixels (x', y') of the image with |x' - x| <= half_size and |y' - y| <= half_size.
    // Needs 0 <= x < width, 0 <= y < height and 0 <= half_size <= max_half_size (std::out_of_range otherwise).
    float query(int x, int y, int half_size) const;

private:
    float level_min(int level, int x, int y) const {
        return levels_[size_t(level)][size_t(y) * size_t(level_widths_[size_t(level)]) + size_t(x)];
    }
    int width_ = 0;
    int height_ = 0;
    int max_half_size_ = 0;
    std::vector<std::vector<float>> levels_;  // level k: min over [x, x + 2^k) x [y, y + 2^k)
    std::vector<int> level_widths_;           // width - 2^k + 1
};

// A contact sheet of `images` (1, 3 or 4 channels; alpha dropped) in a grid of `columns` columns
// (<= 0: one row), left to right and top to bottom, on a dark grey background with a 4-pixel gap.
// Every cell has the size of the largest image; a smaller image sits in the cell's top-left corner.
// When `labels` is not empty it needs one label per image (std::invalid_argument otherwise), drawn
// under each image in a built-in 5x7 font (a-z drawn as capitals, 0-9, space and : = . , % - _ / + ( )
// #; anything else as a box), cut to the cell width. Always 3 channels; values are copied unclamped.
// std::invalid_argument for no images or an image of another channel count.
FloatImage contact_sheet(const std::vector<FloatImage>& images, const std::vector<std::string>& labels, int columns);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_METRICS_H
