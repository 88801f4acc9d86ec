// obscura diff: compares two PNG images (an AO capture against its reference) as a CI gate. No GL.
//
// Both images become luminance in [0, 1] (gray as is, RGB as the mean of the channels). The check
// passes when the mean absolute error is at most `mean` AND the fraction of pixels off by more than
// `threshold`/255 is at most `pixels`. Exit status: 0 within tolerance, 1 outside, 2 on bad input
// (unreadable file, size mismatch, bad option, an output file that cannot be written), reported as one
// line on stderr.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_errors.h"
#include "commands.h"
#include "image_io.h"
#include "json_writer.h"
#include "metrics.h"

namespace obscura::cli {
namespace {

struct DiffTolerance {
    double mean = 0.005;     // largest mean absolute error
    double pixels = 0.005;   // largest fraction of pixels over the threshold
    double threshold = 4.0;  // in 1/255 steps
};

// "mean=0.005,pixels=0.005,threshold=4": any subset of the keys; the others keep their defaults.
DiffTolerance parse_tolerance(const std::string& text) {
    DiffTolerance tolerance;
    if (text.empty()) throw UsageError("--tolerance is empty (expected e.g. mean=0.005,pixels=0.005,threshold=4)");
    std::vector<std::string> keys;  // given so far: a key given twice would keep its last value silently
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, end - start);
        const size_t equals = item.find('=');
        if (equals == std::string::npos) {
            throw UsageError("--tolerance: '" + item + "' is not KEY=VALUE (keys: mean, pixels, threshold)");
        }
        const std::string key = item.substr(0, equals);
        if (std::find(keys.begin(), keys.end(), key) != keys.end()) {
            throw UsageError("--tolerance gives " + key + " twice");
        }
        keys.push_back(key);
        const double value = parse_double("--tolerance " + key, item.substr(equals + 1));
        if (key == "mean" || key == "pixels") {
            if (value < 0.0 || value > 1.0) throw UsageError("--tolerance: " + key + " must be in [0, 1]");
            (key == "mean" ? tolerance.mean : tolerance.pixels) = value;
        } else if (key == "threshold") {
            if (value < 0.0 || value > 255.0) throw UsageError("--tolerance: threshold must be in [0, 255] (1/255 steps)");
            tolerance.threshold = value;
        } else {
            throw UsageError("--tolerance: unknown key '" + key + "' (keys: mean, pixels, threshold)");
        }
        start = end + 1;
    }
    return tolerance;
}

void write_json_report(const std::string& path, const std::string& image_path, const std::string& reference_path,
                       const samples::FloatImage& image, const DiffTolerance& tolerance,
                       const samples::ErrorMetrics& metrics, bool pass) {
    samples::JsonWriter json;
    json.begin_object();
    json.field("image", image_path).field("reference", reference_path);
    json.field("width", image.width).field("height", image.height).field("pixels", metrics.pixels);
    json.field("mean_abs", metrics.mean_abs).field("max_abs", metrics.max_abs);
    json.field("over_threshold", metrics.over_threshold).field("within_5pct", metrics.within_5pct);
    json.field("psnr_db", metrics.psnr);  // null when the images are identical (infinite PSNR)
    json.key("tolerance").begin_object();
    json.field("mean", tolerance.mean).field("pixels", tolerance.pixels).field("threshold", tolerance.threshold);
    json.end_object();
    json.field("pass", pass);
    json.end_object().write_file(path);
}

// PNG, or PFM (exact floats, as `render --pfm` and `truth --out` write them) by the file's extension.
samples::FloatImage read_image(const std::string& path) {
    return image_format_of(path) == ImageFormat::Pfm ? samples::read_pfm(path) : samples::read_png(path);
}

int diff(ArgumentList& arguments) {
    const std::optional<std::string> tolerance_text = arguments.take_value("--tolerance");
    const std::optional<std::string> heat_map_path = arguments.take_value("--out");
    if (heat_map_path) check_image_path("--out", *heat_map_path, ImageFormat::Png);
    const std::optional<std::string> json_path = arguments.take_value("--json");
    const std::vector<std::string> paths = arguments.take_positionals();
    arguments.require_all_taken();
    if (paths.size() != 2) {
        throw UsageError("diff needs two images, IMAGE.png REFERENCE.png (got " + std::to_string(paths.size()) + ")");
    }
    const DiffTolerance tolerance = tolerance_text ? parse_tolerance(*tolerance_text) : DiffTolerance{};
    std::vector<OutputFile> outputs;
    if (heat_map_path) outputs.push_back({"--out", *heat_map_path});
    if (json_path) outputs.push_back({"--json", *json_path});
    check_output_files(outputs);

    const samples::FloatImage image = samples::luminance(read_image(paths[0]));
    const samples::FloatImage reference = samples::luminance(read_image(paths[1]));
    if (image.width != reference.width || image.height != reference.height) {
        throw std::runtime_error("size mismatch: '" + paths[0] + "' is " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + ", '" + paths[1] + "' is " +
                             std::to_string(reference.width) + "x" + std::to_string(reference.height));
    }
    const samples::ErrorMetrics metrics = samples::compare_images(image, reference, nullptr, tolerance.threshold / 255.0);
    const bool pass = metrics.mean_abs <= tolerance.mean && metrics.over_threshold <= tolerance.pixels;

    // One line: what a CI log shows.
    std::printf("mean abs %.5f, max abs %.4f, %.3f %% of pixels off by more than %g/255, PSNR %.2f dB: %s",
                metrics.mean_abs, metrics.max_abs, 100.0 * metrics.over_threshold, tolerance.threshold, metrics.psnr,
                pass ? "PASS" : "FAIL");
    if (!pass) std::printf(" (tolerance: mean abs <= %g, at most %g %% of pixels)", tolerance.mean, 100.0 * tolerance.pixels);
    std::printf("\n");
    if (heat_map_path) {
        samples::write_png(*heat_map_path, samples::error_heat_map(image, reference));
        std::printf("wrote %s (error heat map: white 0, black >= 0.2)\n", heat_map_path->c_str());
    }
    if (json_path) {
        write_json_report(*json_path, paths[0], paths[1], image, tolerance, metrics, pass);
        std::printf("wrote %s\n", json_path->c_str());
    }
    return pass ? 0 : 1;
}

}  // namespace

int run_diff(ArgumentList& arguments) {
    // Every kind of bad input is exit code 2 with one line on stderr, so a CI log shows exactly why.
    try {
        return diff(arguments);
    } catch (const UsageError& error) {
        std::fprintf(stderr, "obscura diff: %s (see 'obscura --help')\n", error.what());
    } catch (const std::exception& error) {
        // Unreadable or mismatched images, and --out / --json files that cannot be written.
        std::fprintf(stderr, "obscura diff: %s\n", error.what());
    }
    return 2;
}

}  // namespace obscura::cli
