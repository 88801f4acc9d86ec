// What `compare` writes: the images (each method's AO and error heat map, each reference, a labelled
// contact sheet), the table on stdout and the JSON report.
#ifndef OBSCURA_CLI_COMPARE_OUTPUT_H
#define OBSCURA_CLI_COMPARE_OUTPUT_H

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ao_render.h"
#include "image_io.h"
#include "method_spec.h"
#include "metrics.h"

namespace obscura::cli {

struct ComparedReference {
    obscura_settings settings{};              // REFERENCE, resolved, with the command's ray count
    std::string description;                  // "rho0 r=1 m"
    std::vector<samples::FloatImage> frames;  // one per camera (one without --orbit)
    double seconds = 0.0;                     // wall time of all its frames
};

struct ComparedMethod {
    MethodSpec spec;
    size_t reference = 0;                     // index into CompareResult::references
    TimingSummary timing;                     // warm frames of the first camera
    std::vector<samples::FloatImage> frames;  // one per camera
    samples::ErrorMetrics metrics;            // against its reference, averaged over the frames
    std::optional<double> flicker;            // with --orbit: samples::flicker against the reference's frames
};

struct CompareResult {
    std::string device;  // GL_RENDERER
    std::string scene;
    int width = 0;
    int height = 0;
    int reference_rays = 0;
    int frames = 1;
    std::optional<double> orbit_degrees;
    std::vector<ComparedReference> references;
    std::vector<ComparedMethod> methods;
};

// "<index>_<method name>" (1-based index), the stem of a method's image files.
std::string method_file_stem(const CompareResult& result, size_t method_index);

// Writes <stem>.png and <stem>_error.png per method, reference_<k>.png per reference (first frame of
// each) and contact_sheet.png into `directory` (created if needed). Returns the file names written.
std::vector<std::string> write_compare_images(const CompareResult& result, const std::filesystem::path& directory);
// The --strip sheet, for documentation: each method's AO (first frame) labelled with its settings (the
// spec without the method's name when every spec names the same method), then, when the methods were
// measured against more than one reference, each reference labelled "ref: " and the label of the first
// method measured against it; at most four images per row, the rows balanced. Gray when every image is.
samples::FloatImage compare_strip(const CompareResult& result);
// One line per method: spec, times, errors (and flicker with --orbit).
void print_compare_table(const CompareResult& result);
void write_compare_json(const CompareResult& result, const std::string& path);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_COMPARE_OUTPUT_H
