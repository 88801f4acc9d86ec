#include "metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace obscura::samples {
namespace {

// Float images hold k/255 or 0.55 only to float precision: a difference meant to be exactly 0.05 or
// 4/255 may come out a few 1e-8 above it. Comparisons against thresholds allow this much.
constexpr double kThresholdSlack = 1e-6;
constexpr double kWithinLimit = 0.05;

size_t sample_count(const FloatImage& image) {
    return size_t(image.width) * size_t(image.height) * size_t(image.channels);
}

void check_image(const FloatImage& image, const char* what) {
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0 || image.pixels.size() != sample_count(image)) {
        throw std::invalid_argument(std::string(what) + ": size and pixel count do not match");
    }
}

void check_same_size(const FloatImage& image, const FloatImage& reference) {
    check_image(image, "image");
    check_image(reference, "reference");
    if (image.width != reference.width || image.height != reference.height || image.channels != reference.channels) {
        throw std::invalid_argument("images differ in size: " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + "x" + std::to_string(image.channels) + " vs " +
                                    std::to_string(reference.width) + "x" + std::to_string(reference.height) + "x" +
                                    std::to_string(reference.channels));
    }
}

// The error of one pixel: the largest channel difference; 1 when any sample is not finite.
double pixel_error(const float* image, const float* reference, int channels) {
    double error = 0.0;
    for (int c = 0; c < channels; ++c) {
        if (!std::isfinite(image[c]) || !std::isfinite(reference[c])) return 1.0;
        error = std::max(error, std::fabs(double(image[c]) - double(reference[c])));
    }
    return error;
}

// White -> yellow -> red -> black as t goes 0 -> 1/3 -> 2/3 -> 1.
std::array<float, 3> heat_colour(double t) {
    t = std::clamp(t, 0.0, 1.0);
    if (t <= 1.0 / 3.0) return {1.0f, 1.0f, float(1.0 - 3.0 * t)};
    if (t <= 2.0 / 3.0) return {1.0f, float(1.0 - 3.0 * (t - 1.0 / 3.0)), 0.0f};
    return {float(1.0 - 3.0 * (t - 2.0 / 3.0)), 0.0f, 0.0f};
}

// ---- A 5x7 bitmap font --------------------------------------------------------------------------
struct Glyph {
    char character;
    std::array<const char*, 7> rows;  // top row first, '#' = ink
};

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 7;
constexpr int kGlyphAdvance = kGlyphWidth + 1;

constexpr Glyph kUnknownGlyph = {'?', {"#####", "#...#", "#...#", "#...#", "#...#", "#...#", "#####"}};

constexpr Glyph kFont[] = {
    {'a', {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'b', {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."}},
    {'c', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {'d', {"####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."}},
    {'e', {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
    {'f', {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
    {'g', {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"}},
    {'h', {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'i', {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'j', {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
    {'k', {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
    {'l', {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
    {'m', {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
    {'n', {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"}},
    {'o', {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'p', {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."}},
    {'q', {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"}},
    {'r', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {'s', {".####", "#....", "#....", ".###.", "....#", "....#", "####."}},
    {'t', {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {'u', {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'v', {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {'w', {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."}},
    {'x', {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
    {'y', {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
    {'z', {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"}},
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {' ', {".....", ".....", ".....", ".....", ".....", ".....", "....."}},
    {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
    {'=', {".....", ".....", "#####", ".....", "#####", ".....", "....."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {',', {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
    {'%', {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'_', {".....", ".....", ".....", ".....", ".....", ".....", "#####"}},
    {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
    {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
    {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
    {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
    {'#', {".#.#.", ".#.#.", "#####", ".#.#.", "#####", ".#.#.", ".#.#."}},
};

const Glyph& find_glyph(char character) {
    if (character >= 'A' && character <= 'Z') character = char(character - 'A' + 'a');
    for (const Glyph& glyph : kFont) {
        if (glyph.character == character) return glyph;
    }
    return kUnknownGlyph;
}

// ---- Contact sheet ------------------------------------------------------------------------------
constexpr int kSheetGap = 4;
constexpr float kSheetBackground = 0.2f;
constexpr float kSheetInk = 1.0f;

// Sets one pixel of an RGB image given in top-down coordinates.
void put_rgb(FloatImage& sheet, int x, int top_y, const float rgb[3]) {
    if (x < 0 || top_y < 0 || x >= sheet.width || top_y >= sheet.height) return;
    float* target = sheet.pixels.data() + (size_t(sheet.height - 1 - top_y) * size_t(sheet.width) + size_t(x)) * 3;
    std::copy(rgb, rgb + 3, target);
}

// Draws `text` from (left, top) at `scale` pixels per font pixel, at most `max_width` pixels wide.
void draw_text(FloatImage& sheet, const std::string& text, int left, int top, int scale, int max_width) {
    const float ink[3] = {kSheetInk, kSheetInk, kSheetInk};
    const int fitting = (max_width + scale) / (kGlyphAdvance * scale);
    for (int i = 0; i < int(text.size()) && i < fitting; ++i) {
        const Glyph& glyph = find_glyph(text[size_t(i)]);
        const int glyph_left = left + i * kGlyphAdvance * scale;
        for (int row = 0; row < kGlyphHeight; ++row) {
            for (int column = 0; column < kGlyphWidth; ++column) {
                if (glyph.rows[size_t(row)][column] != '#') continue;
                for (int dy = 0; dy < scale; ++dy) {
                    for (int dx = 0; dx < scale; ++dx) {
                        put_rgb(sheet, glyph_left + column * scale + dx, top + row * scale + dy, ink);
                    }
                }
            }
        }
    }
}

}  // namespace

ErrorMetrics compare_images(const FloatImage& image, const FloatImage& reference, const std::vector<uint8_t>* mask,
                            double threshold) {
    check_same_size(image, reference);
    const size_t pixel_count = size_t(image.width) * size_t(image.height);
    if (mask && mask->size() != pixel_count) {
        throw std::invalid_argument("mask has " + std::to_string(mask->size()) + " entries for " +
                                    std::to_string(pixel_count) + " pixels");
    }
    ErrorMetrics metrics;
    metrics.threshold = threshold;
    metrics.pixels_total = pixel_count;
    double sum = 0.0;
    double sum_signed = 0.0;
    size_t finite = 0;
    double sum_squares = 0.0;
    size_t within = 0;
    size_t over = 0;
    const int channels = image.channels;
    for (size_t i = 0; i < pixel_count; ++i) {
        if (mask && (*mask)[i] == 0) continue;
        const double error = pixel_error(&image.pixels[i * size_t(channels)], &reference.pixels[i * size_t(channels)],
                                         channels);
        ++metrics.pixels;
        const double difference = double(image.pixels[i * size_t(channels)]) - double(reference.pixels[i * size_t(channels)]);
        if (std::isfinite(difference)) {
            sum_signed += difference;
            ++finite;
        }
        sum += error;
        sum_squares += error * error;
        metrics.max_abs = std::max(metrics.max_abs, error);
        within += error <= kWithinLimit + kThresholdSlack;
        over += error > threshold + kThresholdSlack;
    }
    if (metrics.pixels == 0) {
        metrics.psnr = std::numeric_limits<double>::infinity();
        return metrics;
    }
    const double count = double(metrics.pixels);
    metrics.mean_abs = sum / count;
    metrics.mean_signed = finite > 0 ? sum_signed / double(finite) : 0.0;
    metrics.within_5pct = double(within) / count;
    metrics.over_threshold = double(over) / count;
    const double mse = sum_squares / count;
    metrics.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    return metrics;
}

FloatImage luminance(const FloatImage& image) {
    check_image(image, "image");
    if (image.channels == 1) return image;
    if (image.channels != 3 && image.channels != 4) {
        throw std::invalid_argument("luminance of an image of " + std::to_string(image.channels) + " channels");
    }
    FloatImage gray;
    gray.width = image.width;
    gray.height = image.height;
    gray.channels = 1;
    gray.pixels.resize(size_t(image.width) * size_t(image.height));
    for (size_t i = 0; i < gray.pixels.size(); ++i) {
        const float* rgb = &image.pixels[i * size_t(image.channels)];
        gray.pixels[i] = float((double(rgb[0]) + double(rgb[1]) + double(rgb[2])) / 3.0);
    }
    return gray;
}

FloatImage quantize_8bit(const FloatImage& image) {
    FloatImage quantized = image;
    for (float& value : quantized.pixels) {
        if (std::isnan(value)) continue;
        value = float(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)) / 255.0f;
    }
    return quantized;
}

namespace {

// An RGB map of the size of `image`, one colour per pixel from colour(image pixel, reference pixel, channels):
// what the heat map and the signed map share.
template <typename Colour>
FloatImage error_map(const FloatImage& image, const FloatImage& reference, double full_scale, const char* name,
                     Colour colour) {
    check_same_size(image, reference);
    if (!(full_scale > 0.0)) throw std::invalid_argument(std::string(name) + " full scale must be positive");
    FloatImage map;
    map.width = image.width;
    map.height = image.height;
    map.channels = 3;
    const size_t pixel_count = size_t(image.width) * size_t(image.height);
    map.pixels.resize(pixel_count * 3);
    const size_t channels = size_t(image.channels);
    for (size_t i = 0; i < pixel_count; ++i) {
        const std::array<float, 3> rgb = colour(&image.pixels[i * channels], &reference.pixels[i * channels]);
        std::copy(rgb.begin(), rgb.end(), map.pixels.begin() + long(i * 3));
    }
    return map;
}

}  // namespace

FloatImage error_heat_map(const FloatImage& image, const FloatImage& reference, double full_scale) {
    const int channels = image.channels;
    return error_map(image, reference, full_scale, "heat map", [&](const float* a, const float* b) {
        return heat_colour(pixel_error(a, b, channels) / full_scale);
    });
}

FloatImage signed_error_map(const FloatImage& image, const FloatImage& reference, double full_scale) {
    return error_map(image, reference, full_scale, "signed error map", [&](const float* a, const float* b) {
        const double difference = double(*a) - double(*b);
        if (!std::isfinite(difference)) return std::array<float, 3>{0.0f, 0.0f, 0.0f};
        const float fade = float(1.0 - std::min(1.0, std::fabs(difference) / full_scale));
        // Too dark: red stays 1 and the others fade; too bright: blue stays 1.
        return std::array<float, 3>{difference < 0.0 ? 1.0f : fade, fade, difference > 0.0 ? 1.0f : fade};
    });
}

double mean_angle_degrees(const FloatImage& image, const FloatImage& reference, const std::vector<uint8_t>* mask) {
    if (image.channels < 3 || reference.channels < 3 || image.width != reference.width ||
        image.height != reference.height) {
        throw std::invalid_argument("mean_angle_degrees: two images of one size with at least 3 channels are needed");
    }
    const size_t pixels = size_t(image.width) * size_t(image.height);
    if (mask && mask->size() != pixels) throw std::invalid_argument("mean_angle_degrees: the mask's size differs");
    double sum = 0.0;
    size_t counted = 0;
    for (size_t i = 0; i < pixels; ++i) {
        if (mask && !(*mask)[i]) continue;
        double a[3], b[3], aa = 0.0, bb = 0.0, ab = 0.0;
        for (int c = 0; c < 3; ++c) {
            a[c] = image.pixels[i * size_t(image.channels) + size_t(c)];
            b[c] = reference.pixels[i * size_t(reference.channels) + size_t(c)];
            aa += a[c] * a[c];
            bb += b[c] * b[c];
            ab += a[c] * b[c];
        }
        const double denominator = std::sqrt(aa * bb);
        const bool valid = std::isfinite(denominator) && denominator > 0.0 && std::isfinite(ab);
        sum += valid ? std::acos(std::clamp(ab / denominator, -1.0, 1.0)) * (180.0 / 3.14159265358979323846) : 180.0;
        ++counted;
    }
    return counted ? sum / double(counted) : 0.0;
}

double flicker(const std::vector<FloatImage>& method_frames, const std::vector<FloatImage>& reference_frames,
               const std::vector<std::vector<uint8_t>>* masks) {
    if (method_frames.size() != reference_frames.size()) {
        throw std::invalid_argument("flicker: " + std::to_string(method_frames.size()) + " method frames but " +
                                    std::to_string(reference_frames.size()) + " reference frames");
    }
    if (method_frames.size() < 2) throw std::invalid_argument("flicker needs at least two frames");
    for (size_t f = 0; f < method_frames.size(); ++f) {
        check_same_size(method_frames[f], reference_frames[0]);
        check_same_size(reference_frames[f], reference_frames[0]);
    }
    const size_t pixel_count = size_t(reference_frames[0].width) * size_t(reference_frames[0].height);
    if (masks && (masks->size() != method_frames.size())) {
        throw std::invalid_argument("flicker: " + std::to_string(masks->size()) + " masks for " +
                                    std::to_string(method_frames.size()) + " frames");
    }
    for (size_t f = 0; masks && f < masks->size(); ++f) {
        if ((*masks)[f].size() != pixel_count) throw std::invalid_argument("flicker: a mask of another size");
    }
    const int channels = reference_frames[0].channels;
    double sum = 0.0;
    size_t counted = 0;
    for (size_t f = 0; f + 1 < method_frames.size(); ++f) {
        const float* m0 = method_frames[f].pixels.data();
        const float* m1 = method_frames[f + 1].pixels.data();
        const float* r0 = reference_frames[f].pixels.data();
        const float* r1 = reference_frames[f + 1].pixels.data();
        for (size_t i = 0; i < pixel_count; ++i) {
            if (masks && ((*masks)[f][i] == 0 || (*masks)[f + 1][i] == 0)) continue;
            ++counted;
            double error = 0.0;
            for (int c = 0; c < channels; ++c) {
                const size_t k = i * size_t(channels) + size_t(c);
                const double change = double(m1[k]) - double(m0[k]) - (double(r1[k]) - double(r0[k]));
                if (!std::isfinite(change)) {
                    error = 1.0;
                    break;
                }
                error = std::max(error, std::fabs(change));
            }
            sum += error;
        }
    }
    return counted > 0 ? sum / double(counted) : 0.0;
}

FloatImage contact_sheet(const std::vector<FloatImage>& images, const std::vector<std::string>& labels, int columns) {
    if (images.empty()) throw std::invalid_argument("contact sheet of no images");
    if (!labels.empty() && labels.size() != images.size()) {
        throw std::invalid_argument("contact sheet: " + std::to_string(labels.size()) + " labels for " +
                                    std::to_string(images.size()) + " images");
    }
    int cell_width = 0;
    int cell_height = 0;
    for (const FloatImage& image : images) {
        check_image(image, "contact sheet image");
        if (image.channels != 1 && image.channels != 3 && image.channels != 4) {
            throw std::invalid_argument("contact sheet: images of " + std::to_string(image.channels) + " channels");
        }
        cell_width = std::max(cell_width, image.width);
        cell_height = std::max(cell_height, image.height);
    }
    const int count = int(images.size());
    columns = columns <= 0 ? count : std::min(columns, count);
    const int rows = (count + columns - 1) / columns;
    // Labels of big cells at double size; a strip of 2 pixels above and below the text.
    const int text_scale = cell_width >= 256 ? 2 : 1;
    const int label_height = labels.empty() ? 0 : kGlyphHeight * text_scale + 4;

    FloatImage sheet;
    sheet.channels = 3;
    sheet.width = columns * cell_width + (columns + 1) * kSheetGap;
    sheet.height = rows * (cell_height + label_height) + (rows + 1) * kSheetGap;
    sheet.pixels.assign(size_t(sheet.width) * size_t(sheet.height) * 3, kSheetBackground);

    for (int index = 0; index < count; ++index) {
        const FloatImage& image = images[size_t(index)];
        const int left = kSheetGap + (index % columns) * (cell_width + kSheetGap);
        const int top = kSheetGap + (index / columns) * (cell_height + label_height + kSheetGap);
        for (int y = 0; y < image.height; ++y) {
            // Image rows are bottom-up: its top row (y = height - 1) goes to `top`.
            const int sheet_top_y = top + (image.height - 1 - y);
            for (int x = 0; x < image.width; ++x) {
                const float* source = &image.pixels[(size_t(y) * size_t(image.width) + size_t(x)) * size_t(image.channels)];
                const float rgb[3] = {source[0], image.channels == 1 ? source[0] : source[1],
                                      image.channels == 1 ? source[0] : source[2]};
                put_rgb(sheet, left + x, sheet_top_y, rgb);
            }
        }
        if (!labels.empty()) {
            draw_text(sheet, labels[size_t(index)], left, top + cell_height + 2, text_scale, cell_width);
        }
    }
    return sheet;
}

}  // namespace obscura::samples
