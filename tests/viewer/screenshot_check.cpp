// obscura_viewer_screenshot_check SHOT.png PANEL_WIDTH [heat]: checks a screenshot of obscura-viewer.
//   - the scene (right of the panel) is not blank: its luminance varies (standard deviation >= 0.02) and it
//     is not all one extreme;
//   - the panel is there: most of its pixels have the dark window background of Dear ImGui's dark style and a
//     few percent are light (its text and widgets);
//   - with `heat`, the scene is an error heat map (white 0, yellow, red, black): at least 0.5 % of its pixels
//     are warm colours (red clearly above blue), which a grey AO image never has, and it is neither all
//     white nor all black (under 98 % of the pixels near white, under 98 % near black).
// Exit 0 when all hold, 1 otherwise (with the measured numbers), 2 for bad arguments or an unreadable file.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

#include "image_io.h"

int main(int argc, char** argv) {
    const bool heat = argc == 4 && std::strcmp(argv[3], "heat") == 0;
    if (argc != 3 && !heat) {
        std::fprintf(stderr, "usage: %s SHOT.png PANEL_WIDTH [heat]\n", argv[0]);
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
    bool heat_ok = true;
    if (heat && image.channels >= 3) {
        double warm = 0.0, white = 0.0, black = 0.0;
        for (int y = 0; y < image.height; ++y)
            for (int x = panel + 4; x < image.width; ++x) {
                const double r = image.at(x, y, 0), b = image.at(x, y, 2), v = luma(x, y);
                warm += r - b > 0.25 ? 1.0 : 0.0;
                white += v > 0.97 ? 1.0 : 0.0;
                black += v < 0.03 ? 1.0 : 0.0;
            }
        warm /= n;
        white /= n;
        black /= n;
        heat_ok = warm >= 0.005 && white < 0.98 && black < 0.98;
        std::printf("%s: heat map: warm %.3f white %.3f black %.3f (%s)\n", argv[1], warm, white, black,
                    heat_ok ? "ok" : "NOT A HEAT MAP");
    } else if (heat) {
        heat_ok = false;
        std::printf("%s: heat map check needs an RGB screenshot\n", argv[1]);
    }
    return scene_ok && panel_ok && heat_ok ? 0 : 1;
}
