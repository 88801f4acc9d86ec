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
#include <string>
#include <vector>

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

// Mean angle in degrees between the directions in the first three channels of `image` and of `reference` (each
// normalised; a zero or non-finite vector counts 180 degrees), over the pixels `mask` (compare_images' kind) keeps:
// bent normals against the geometry truth's. Both need >= 3 channels and one size (std::invalid_argument
// otherwise); 0 when no pixel counts.
double mean_angle_degrees(const FloatImage& image, const FloatImage& reference, const std::vector<uint8_t>* mask = nullptr);

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
