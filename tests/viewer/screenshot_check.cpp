// obscura_viewer_screenshot_check SHOT.png PANEL_WIDTH: checks a screenshot of obscura-viewer.
//   - the scene (right of the panel) is not blank: its luminance varies (standard deviation >= 0.02) and it
//     is not all one extreme;
//   - the panel is there: most of its pixels have the dark window background of Dear ImGui's dark style and a
//     few percent are light (its text and widgets).
// Exit 0 when both hold, 1 otherwise (with the measured numbers), 2 for bad arguments or an unreadable file.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "image_io.h"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s SHOT.png PANEL_WIDTH\n", argv[0]);
        return 2;
    }
    obscura::samples::FloatImage image;
    try {
        image = obscura::samples::read_png(argv[1]);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 2;
    }
    const int panel = std::atoi(argv[2]);
    if (panel <= 0 || panel >= image.width) {
        std::fprintf(stderr, "%s: %dx%d does not fit a %d px panel\n", argv[1], image.width, image.height, panel);
        return 2;
    }
    auto luma = [&](int x, int y) {
        if (image.channels < 3) return double(image.at(x, y, 0));
        return (image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2)) / 3.0;
    };
    double sum = 0.0, sum_sq = 0.0, n = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = panel + 4; x < image.width; ++x) {
            const double v = luma(x, y);
            sum += v;
            sum_sq += v * v;
            n += 1.0;
        }
    const double mean = sum / n, deviation = std::sqrt(std::max(sum_sq / n - mean * mean, 0.0));
    double dark = 0.0, light = 0.0, panel_pixels = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < panel - 4; ++x) {
            const double v = luma(x, y);
            dark += v < 0.2 ? 1.0 : 0.0;
            light += v > 0.6 ? 1.0 : 0.0;
            panel_pixels += 1.0;
        }
    dark /= panel_pixels;
    light /= panel_pixels;
    const bool scene_ok = deviation >= 0.02 && mean > 0.02 && mean < 0.98;
    const bool panel_ok = dark >= 0.3 && light >= 0.01;
    std::printf("%s: scene mean %.3f deviation %.3f (%s); panel dark %.2f light %.3f (%s)\n", argv[1], mean, deviation,
                scene_ok ? "ok" : "BLANK", dark, light, panel_ok ? "ok" : "NO PANEL");
    return scene_ok && panel_ok ? 0 : 1;
}
