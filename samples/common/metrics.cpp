#include "metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

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
    metrics.signed_pixels = finite;
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

namespace {

bool sees_surface(float depth) { return std::isfinite(depth) && depth > 0.0f; }

// The world point a pixel (centre) of `frame` sees at view depth `depth`: the view-space point on the pixel's ray at
// z = -depth (the projections here are affine in x and y for a given depth, perspective or not), to the world.
glm::dvec3 pixel_to_world(const FrameGeometry& frame, int x, int y, double depth) {
    const glm::dvec2 ndc((double(x + frame.rect_x) + 0.5) / double(frame.depth_width) * 2.0 - 1.0,
                         (double(y + frame.rect_y) + 0.5) / double(frame.depth_height) * 2.0 - 1.0);
    const glm::dmat4& p = frame.projection;
    const double z = -depth;
    const double w = p[2][3] * z + p[3][3];
    // p[0][0] x + p[1][0] y = ndc.x w - p[2][0] z - p[3][0], likewise for y (p[0][3] = p[1][3] = 0 here).
    const glm::dmat2 a(p[0][0], p[0][1], p[1][0], p[1][1]);
    const glm::dvec2 b(ndc.x * w - p[2][0] * z - p[3][0], ndc.y * w - p[2][1] * z - p[3][1]);
    const glm::dvec2 xy = glm::inverse(a) * b;
    const glm::dvec4 world = glm::inverse(frame.view) * glm::dvec4(xy, z, 1.0);
    return glm::dvec3(world) / world.w;
}

// Where pixel (x, y) of `now` was in the previous frame `before`.
enum class Previously { NoSurface, Elsewhere, Seen };
struct Reprojection {
    // NoSurface: sky now; Elsewhere: off the image, or a texel around it with bilinear weight does not see its surface;
    // Seen: every texel with weight does.
    Previously what = Previously::NoSurface;
    double u = 0.0, v = 0.0;              // on the image: texel coordinates in the previous image (centres at integers)
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;   // on the image: the four texels around it
    bool matches[4] = {false, false, false, false};  // which of (x0, y0), (x1, y0), (x0, y1), (x1, y1) see it
};

// The pixel's surface point (on a moving part, moved back by its motion) projected into `before`: seen there when the
// texels around it that carry bilinear weight see the same surface (their view depth within depth_tolerance of the
// point's, relative). A texel of weight 0 does not count: a still camera lands each point on its own texel, whose
// neighbours may lie on another surface (or at another depth of a slanted one) without changing the value read.
Reprojection reproject(const FrameGeometry& now, const FrameGeometry& before, int x, int y, double depth_tolerance) {
    Reprojection r;
    const int width = now.view_depth.width, height = now.view_depth.height;
    const float depth = now.view_depth.at(x, y);
    if (!sees_surface(depth)) return r;
    r.what = Previously::Elsewhere;
    // A moving part translates: its normal is the same in both frames.
    const bool with_normals = !now.normal.empty() && !before.normal.empty();
    const glm::vec3 point_normal = with_normals ? now.normal[size_t(y) * size_t(width) + size_t(x)] : glm::vec3(0.0f);
    glm::dvec3 world = pixel_to_world(now, x, y, double(depth));
    if (!now.moving.empty() && now.moving[size_t(y) * size_t(width) + size_t(x)]) world -= now.motion;
    const glm::dvec4 clip = before.projection * before.view * glm::dvec4(world, 1.0);
    if (!(clip.w > 0.0)) return r;
    const double expected_depth = -(before.view * glm::dvec4(world, 1.0)).z;
    r.u = (clip.x / clip.w * 0.5 + 0.5) * before.depth_width - before.rect_x - 0.5;
    r.v = (clip.y / clip.w * 0.5 + 0.5) * before.depth_height - before.rect_y - 0.5;
    if (!(r.u >= 0.0 && r.v >= 0.0 && r.u <= width - 1 && r.v <= height - 1)) return r;
    r.x0 = std::clamp(int(r.u), 0, std::max(width - 2, 0));
    r.y0 = std::clamp(int(r.v), 0, std::max(height - 2, 0));
    r.x1 = std::min(r.x0 + 1, width - 1);
    r.y1 = std::min(r.y0 + 1, height - 1);
    const std::pair<int, int> texels[4] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x0, r.y1}, {r.x1, r.y1}};
    const double fx = r.u - r.x0, fy = r.v - r.y0;
    const double weights[4] = {(1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy};
    bool all = true;
    for (int k = 0; k < 4; ++k) {
        const float texel_depth = before.view_depth.at(texels[k].first, texels[k].second);
        r.matches[k] = sees_surface(texel_depth) &&
                       std::fabs(double(texel_depth) - expected_depth) <= depth_tolerance * expected_depth;
        if (with_normals && r.matches[k]) {
            const glm::vec3 texel_normal = before.normal[size_t(texels[k].second) * size_t(width) + size_t(texels[k].first)];
            r.matches[k] = std::fabs(double(glm::dot(point_normal, texel_normal))) >= kSameSurfaceMinCosine;
        }
        // Below 1e-9 of weight a texel's value changes the reading by less than the images' float precision.
        all = all && (r.matches[k] || weights[k] < 1e-9);
    }
    if (all) r.what = Previously::Seen;
    return r;
}

void check_geometry(const char* what, const std::vector<FrameGeometry>& geometry, int width, int height) {
    for (const FrameGeometry& frame : geometry) {
        if (frame.view_depth.width != width || frame.view_depth.height != height) {
            throw std::invalid_argument(std::string(what) + ": a depth image of another size than the frames");
        }
        if (!frame.moving.empty() && frame.moving.size() != size_t(width) * size_t(height)) {
            throw std::invalid_argument(std::string(what) + ": a moving mask of another size than the frames");
        }
        if (!frame.normal.empty() && frame.normal.size() != size_t(width) * size_t(height)) {
            throw std::invalid_argument(std::string(what) + ": normals of another size than the frames");
        }
    }
}

}  // namespace

std::optional<double> surface_flicker(const std::vector<FloatImage>& frames, const std::vector<FrameGeometry>& geometry,
                                      double depth_tolerance) {
    if (frames.size() != geometry.size() || frames.size() < 2) {
        throw std::invalid_argument("surface_flicker: " + std::to_string(frames.size()) + " frames and " +
                                    std::to_string(geometry.size()) + " geometries (two or more of each)");
    }
    const int width = frames[0].width, height = frames[0].height;
    for (const FloatImage& frame : frames) check_same_size(frame, frames[0]);
    check_geometry("surface_flicker", geometry, width, height);
    double sum = 0.0;
    size_t counted = 0;
    for (size_t f = 1; f < frames.size(); ++f) {
        const FloatImage& image = frames[f];
        const FloatImage& previous = frames[f - 1];
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const Reprojection r = reproject(geometry[f], geometry[f - 1], x, y, depth_tolerance);
                if (r.what != Previously::Seen) continue;
                const double fx = r.u - r.x0, fy = r.v - r.y0;
                // Texels of weight 0 are left out, not multiplied: they may lie on sky (any value) or another surface.
                const double weights[4] = {(1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy};
                const int xs[4] = {r.x0, r.x1, r.x0, r.x1}, ys[4] = {r.y0, r.y0, r.y1, r.y1};
                double value = 0.0;
                for (int k = 0; k < 4; ++k) {
                    if (weights[k] >= 1e-9) value += weights[k] * previous.at(xs[k], ys[k]);
                }
                const double change = double(image.at(x, y)) - value;
                sum += std::isfinite(change) ? std::fabs(change) : 1.0;
                ++counted;
            }
        }
    }
    if (counted == 0) return std::nullopt;
    return sum / double(counted);
}

std::vector<std::vector<int>> frames_since_disocclusion(const std::vector<FrameGeometry>& geometry,
                                                        double depth_tolerance) {
    if (geometry.empty()) return {};
    const int width = geometry[0].view_depth.width, height = geometry[0].view_depth.height;
    check_geometry("frames_since_disocclusion", geometry, width, height);
    std::vector<std::vector<int>> ages(geometry.size(), std::vector<int>(size_t(width) * size_t(height), -1));
    for (size_t f = 1; f < geometry.size(); ++f) {
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const Reprojection r = reproject(geometry[f], geometry[f - 1], x, y, depth_tolerance);
                if (r.what == Previously::NoSurface) continue;
                // Seen where any texel around the point saw its surface (on a slanted surface the four texels'
                // depths spread wider than the tolerance): the nearest such texel's age, plus one.
                const int xs[4] = {r.x0, r.x1, r.x0, r.x1}, ys[4] = {r.y0, r.y0, r.y1, r.y1};
                int nearest = -1;
                double nearest_distance = 1e30;
                for (int k = 0; k < 4; ++k) {
                    const double distance = std::hypot(xs[k] - r.u, ys[k] - r.v);
                    if (r.matches[k] && distance < nearest_distance) {
                        nearest = k;
                        nearest_distance = distance;
                    }
                }
                int& age = ages[f][size_t(y) * size_t(width) + size_t(x)];
                if (nearest < 0) {
                    age = 0;  // off the previous image, or hidden there
                } else {
                    const int before = ages[f - 1][size_t(ys[nearest]) * size_t(width) + size_t(xs[nearest])];
                    age = before >= 0 ? before + 1 : -1;
                }
            }
        }
    }
    return ages;
}

std::vector<std::vector<int>> frames_since_event(const std::vector<std::vector<uint8_t>>& event,
                                                 const std::vector<std::vector<uint8_t>>& alive) {
    if (event.size() != alive.size()) {
        throw std::invalid_argument("frames_since_event: " + std::to_string(event.size()) + " event frames but " +
                                    std::to_string(alive.size()) + " alive frames");
    }
    std::vector<std::vector<int>> ages(event.size());
    for (size_t f = 0; f < event.size(); ++f) {
        if (event[f].size() != alive[f].size() || event[f].size() != event[0].size()) {
            throw std::invalid_argument("frames_since_event: frames of different sizes");
        }
        ages[f].assign(event[f].size(), -1);
        for (size_t i = 0; i < event[f].size(); ++i) {
            if (!alive[f][i]) continue;
            if (event[f][i]) {
                ages[f][i] = 0;
            } else if (f > 0 && ages[f - 1][i] >= 0) {
                ages[f][i] = ages[f - 1][i] + 1;
            }
        }
    }
    return ages;
}

std::vector<AgeErrors> error_by_age(const std::vector<FloatImage>& frames, const std::vector<FloatImage>& converged,
                                    const std::vector<FloatImage>& truth, const std::vector<std::vector<int>>& ages,
                                    int max_age) {
    if (max_age < 0) throw std::invalid_argument("error_by_age: max_age < 0");
    if (frames.size() != ages.size() || converged.size() != ages.size() || truth.size() != ages.size()) {
        throw std::invalid_argument("error_by_age: " + std::to_string(frames.size()) + " frames, " +
                                    std::to_string(converged.size()) + " converged, " + std::to_string(truth.size()) +
                                    " truth frames and " + std::to_string(ages.size()) + " age maps");
    }
    std::vector<AgeErrors> buckets(size_t(max_age) + 1);
    for (size_t f = 0; f < ages.size(); ++f) {
        check_same_size(frames[f], truth[f]);
        check_same_size(converged[f], truth[f]);
        const size_t pixels = size_t(truth[f].width) * size_t(truth[f].height);
        if (ages[f].size() != pixels) throw std::invalid_argument("error_by_age: an age map of another size");
        const auto first = [](const FloatImage& image, size_t i) { return double(image.pixels[i * size_t(image.channels)]); };
        for (size_t i = 0; i < pixels; ++i) {
            if (ages[f][i] < 0) continue;
            AgeErrors& bucket = buckets[size_t(std::min(ages[f][i], max_age))];
            const double t = first(truth[f], i);
            ++bucket.pixels;
            bucket.mean_abs += std::fabs(first(frames[f], i) - t);
            bucket.converged_mean_abs += std::fabs(first(converged[f], i) - t);
        }
    }
    for (AgeErrors& bucket : buckets) {
        if (bucket.pixels == 0) continue;
        bucket.mean_abs /= double(bucket.pixels);
        bucket.converged_mean_abs /= double(bucket.pixels);
    }
    return buckets;
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

// ---- Thickness classes ------------------------------------------------------------------------------------
namespace obscura::samples {
namespace {

// floor(log2(value)) for value >= 1.
int floor_log2(int value) {
    int level = 0;
    while ((2 << level) <= value) ++level;
    return level;
}

// The start positions of `size`-long tiles that cover [first, last] (last - first + 1 >= size): every `size`
// from `first`, the last one ending at `last`.
template <typename Visit>
void cover(int first, int last, int size, Visit visit) {
    for (int start = first;; start += size) {
        if (start + size - 1 >= last) {
            visit(last - size + 1);
            return;
        }
        visit(start);
    }
}

void check_finite_at_least(double value, double minimum, bool strict, const char* name) {
    if (!std::isfinite(value) || value < minimum || (strict && value == minimum)) {
        throw std::invalid_argument(std::string("thickness classes: ") + name + " must be finite and " +
                                    (strict ? "> " : ">= ") + std::to_string(minimum) + " (got " +
                                    std::to_string(value) + ")");
    }
}

}  // namespace

WindowMinimum::WindowMinimum(const FloatImage& image, int max_half_size)
    : width_(image.width), height_(image.height), max_half_size_(max_half_size) {
    check_image(image, "window minimum image");
    if (image.channels != 1) {
        throw std::invalid_argument("window minimum: the image has " + std::to_string(image.channels) +
                                    " channels; expected 1");
    }
    if (max_half_size < 0) throw std::invalid_argument("window minimum: max_half_size must be >= 0");
    for (float value : image.pixels) {
        if (std::isnan(value)) throw std::invalid_argument("window minimum: the image has a NaN sample");
    }
    // The largest square any query needs: the window's side, cut to the image's smaller side.
    const int largest_side = int(std::min<long long>(2LL * max_half_size + 1, std::min(width_, height_)));
    const int top_level = floor_log2(largest_side);
    levels_.push_back(image.pixels);
    level_widths_.push_back(width_);
    for (int level = 1; level <= top_level; ++level) {
        const int half = 1 << (level - 1);
        const int side = 1 << level;
        const int level_width = width_ - side + 1;
        const int level_height = height_ - side + 1;
        std::vector<float> minima(size_t(level_width) * size_t(level_height));
        for (int y = 0; y < level_height; ++y) {
            for (int x = 0; x < level_width; ++x) {
                minima[size_t(y) * size_t(level_width) + size_t(x)] =
                    std::min(std::min(level_min(level - 1, x, y), level_min(level - 1, x + half, y)),
                             std::min(level_min(level - 1, x, y + half), level_min(level - 1, x + half, y + half)));
            }
        }
        levels_.push_back(std::move(minima));
        level_widths_.push_back(level_width);
    }
}

float WindowMinimum::query(int x, int y, int half_size) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_ || half_size < 0 || half_size > max_half_size_) {
        throw std::out_of_range("window minimum: query (" + std::to_string(x) + ", " + std::to_string(y) + ", " +
                                std::to_string(half_size) + ") outside the image or the largest half size");
    }
    const int x0 = std::max(0, x - half_size);
    const int x1 = std::min(width_ - 1, x + half_size);
    const int y0 = std::max(0, y - half_size);
    const int y1 = std::min(height_ - 1, y + half_size);
    const int level = floor_log2(std::min(x1 - x0 + 1, y1 - y0 + 1));
    const int side = 1 << level;
    float minimum = std::numeric_limits<float>::infinity();
    cover(y0, y1, side, [&](int tile_y) {
        cover(x0, x1, side, [&](int tile_x) { minimum = std::min(minimum, level_min(level, tile_x, tile_y)); });
    });
    return minimum;
}

const char* thickness_class_name(ThicknessClass value) {
    switch (value) {
    case ThicknessClass::Sky: return "sky";
    case ThicknessClass::Rest: return "rest";
    case ThicknessClass::Halo: return "halo";
    case ThicknessClass::Silhouette: return "silhouette";
    }
    return "unknown";
}

std::vector<uint8_t> thickness_classes(const FloatImage& view_depth, const std::vector<uint8_t>& geometry_mask,
                                       double radius_m, double thickness_m, double pixels_per_metre_at_1m,
                                       double max_radius_px) {
    check_image(view_depth, "view depth");
    if (view_depth.channels != 1) {
        throw std::invalid_argument("thickness classes: the view depth has " + std::to_string(view_depth.channels) +
                                    " channels; expected 1");
    }
    const int width = view_depth.width;
    const int height = view_depth.height;
    const size_t pixel_count = size_t(width) * size_t(height);
    if (geometry_mask.size() != pixel_count) {
        throw std::invalid_argument("thickness classes: the mask has " + std::to_string(geometry_mask.size()) +
                                    " entries for " + std::to_string(pixel_count) + " pixels");
    }
    check_finite_at_least(radius_m, 0.0, true, "radius_m");
    check_finite_at_least(thickness_m, 0.0, false, "thickness_m");
    check_finite_at_least(pixels_per_metre_at_1m, 0.0, true, "pixels_per_metre_at_1m");
    check_finite_at_least(max_radius_px, 0.0, false, "max_radius_px");

    // Sky is infinitely far: it never occludes and is always the far side of a step.
    const float infinity = std::numeric_limits<float>::infinity();
    FloatImage depth = view_depth;
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < pixel_count; ++i) {
        if (geometry_mask[i] == 0) {
            depth.pixels[i] = infinity;
            continue;
        }
        const float value = view_depth.pixels[i];
        if (!std::isfinite(value) || !(value > 0.0f)) {
            throw std::invalid_argument("thickness classes: geometry pixel (" + std::to_string(i % size_t(width)) + ", " +
                                        std::to_string(i / size_t(width)) + ") has view depth " +
                                        std::to_string(value) + "; expected finite and positive");
        }
        nearest = std::min(nearest, double(value));
    }
    const double reach = radius_m * pixels_per_metre_at_1m;  // pixels the radius covers at 1 m
    // Windows beyond the image's larger side are the whole image; the cap also keeps the int in range.
    const double radius_cap = std::min(max_radius_px, double(std::max(width, height)));
    const auto half_size_at = [&](double pixel_depth) { return int(std::floor(std::min(radius_cap, reach / pixel_depth))); };
    const int largest_half_size = std::isfinite(nearest) ? half_size_at(nearest) : 0;

    // Silhouettes first; their depths (everything else +infinity) are the occluders a halo lies behind, so a
    // surface that merely recedes (a floor, a wall seen at an angle) is no halo of its own nearer part.
    std::vector<uint8_t> classes(pixel_count, uint8_t(ThicknessClass::Sky));
    FloatImage silhouette_depth = depth;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const size_t index = size_t(y) * size_t(width) + size_t(x);
            silhouette_depth.pixels[index] = infinity;
            if (geometry_mask[index] == 0) continue;
            const double here = depth.pixels[index];
            const double step = std::max(kSilhouetteMinStep, kSilhouetteRelativeStep * here);
            const auto farther = [&](int nx, int ny) {
                return nx >= 0 && ny >= 0 && nx < width && ny < height &&
                       double(depth.pixels[size_t(ny) * size_t(width) + size_t(nx)]) > here + step;
            };
            if (farther(x - 1, y) || farther(x + 1, y) || farther(x, y - 1) || farther(x, y + 1)) {
                classes[index] = uint8_t(ThicknessClass::Silhouette);
                silhouette_depth.pixels[index] = depth.pixels[index];
            } else {
                classes[index] = uint8_t(ThicknessClass::Rest);
            }
        }
    }
    const WindowMinimum window(silhouette_depth, largest_half_size);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const size_t index = size_t(y) * size_t(width) + size_t(x);
            if (classes[index] != uint8_t(ThicknessClass::Rest)) continue;
            const double here = depth.pixels[index];
            const int half_size = half_size_at(here);
            if (half_size > 0 && double(window.query(x, y, half_size)) < here - thickness_m) {
                classes[index] = uint8_t(ThicknessClass::Halo);
            }
        }
    }
    return classes;
}

FloatImage thickness_class_image(const std::vector<uint8_t>& classes, int width, int height) {
    if (width <= 0 || height <= 0 || classes.size() != size_t(width) * size_t(height)) {
        throw std::invalid_argument("thickness class image: " + std::to_string(classes.size()) + " classes for " +
                                    std::to_string(width) + "x" + std::to_string(height) + " pixels");
    }
    static constexpr std::array<std::array<float, 3>, kThicknessClassCount> kColours = {{
        {0.0f, 0.0f, 0.0f},    // sky
        {1.0f, 1.0f, 1.0f},    // rest
        {0.25f, 0.45f, 1.0f},  // halo
        {0.9f, 0.15f, 0.1f},   // silhouette
    }};
    FloatImage image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.pixels.resize(classes.size() * 3);
    for (size_t i = 0; i < classes.size(); ++i) {
        if (classes[i] >= kThicknessClassCount) {
            throw std::invalid_argument("thickness class image: byte " + std::to_string(int(classes[i])) + " at " +
                                        std::to_string(i) + " is not a class");
        }
        std::copy(kColours[classes[i]].begin(), kColours[classes[i]].end(), image.pixels.begin() + long(i * 3));
    }
    return image;
}

}  // namespace obscura::samples
