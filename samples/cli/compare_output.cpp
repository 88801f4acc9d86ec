#include "compare_output.h"

#include <cmath>
#include <cstdio>

#include "json_writer.h"
#include "report.h"

namespace obscura::cli {
namespace {

std::string format_psnr(double psnr) {
    return std::isfinite(psnr) ? format_fixed(psnr, 2) : "inf";
}

std::string reference_file(size_t reference_index) {
    return "reference_" + std::to_string(reference_index + 1) + ".png";
}

constexpr int kStripMaxColumns = 4;

// A method's label in the strip: its spec, less "NAME:" when every spec of the run names the same method
// (a 320-pixel tile holds 26 characters of the sheet's font).
std::string strip_label(const CompareResult& result, size_t method_index) {
    const MethodSpec& spec = result.methods[method_index].spec;
    for (const ComparedMethod& other : result.methods) {
        if (other.spec.method() != spec.method()) return spec.text;
    }
    const size_t colon = spec.text.find(':');
    return colon == std::string::npos ? spec.text : spec.text.substr(colon + 1);
}

// The first channel of a sheet whose tiles and labels are all gray: a third of the PNG's bytes.
samples::FloatImage first_channel(const samples::FloatImage& image) {
    samples::FloatImage gray;
    gray.width = image.width;
    gray.height = image.height;
    gray.channels = 1;
    const size_t count = size_t(image.width) * size_t(image.height);
    gray.pixels.resize(count);
    for (size_t i = 0; i < count; ++i) gray.pixels[i] = image.pixels[i * size_t(image.channels)];
    return gray;
}

}  // namespace

std::string method_file_stem(const CompareResult& result, size_t method_index) {
    return std::to_string(method_index + 1) + "_" + result.methods[method_index].spec.name();
}

std::vector<std::string> write_compare_images(const CompareResult& result, const std::filesystem::path& directory) {
    std::filesystem::create_directories(directory);
    std::vector<std::string> written;
    auto write = [&](const std::string& name, const samples::FloatImage& image) {
        samples::write_png((directory / name).string(), image);
        written.push_back(name);
    };

    std::vector<samples::FloatImage> sheet;
    std::vector<std::string> labels;
    for (size_t i = 0; i < result.methods.size(); ++i) {
        const ComparedMethod& method = result.methods[i];
        const ComparedReference& reference = result.references[method.reference];
        const std::string stem = method_file_stem(result, i);
        const samples::FloatImage errors = samples::error_heat_map(method.frames.front(), reference.frames.front());
        write(stem + ".png", method.frames.front());
        write(stem + "_error.png", errors);

        sheet.push_back(method.frames.front());
        labels.push_back(std::to_string(i + 1) + " " + method.spec.text);
        sheet.push_back(errors);
        labels.push_back("error: mean " + format_fixed(method.metrics.mean_abs, 4) + ", " +
                         format_fixed(100.0 * method.metrics.within_5pct, 1) + "%");
        sheet.push_back(reference.frames.front());
        labels.push_back("ref " + std::to_string(method.reference + 1) + ": " + reference.description);
    }
    for (size_t k = 0; k < result.references.size(); ++k) write(reference_file(k), result.references[k].frames.front());
    write("contact_sheet.png", samples::contact_sheet(sheet, labels, 3));
    return written;
}

samples::FloatImage compare_strip(const CompareResult& result) {
    std::vector<samples::FloatImage> images;
    std::vector<std::string> labels;
    for (size_t i = 0; i < result.methods.size(); ++i) {
        images.push_back(result.methods[i].frames.front());
        labels.push_back(strip_label(result, i));
    }
    // One reference is reference_1.png; several differ in what the labels of their methods say (their
    // descriptions would not fit a tile), so each is labelled with the first method measured against it.
    for (size_t k = 0; result.references.size() > 1 && k < result.references.size(); ++k) {
        for (size_t i = 0; i < result.methods.size(); ++i) {
            if (result.methods[i].reference == k) {
                images.push_back(result.references[k].frames.front());
                labels.push_back("ref: " + strip_label(result, i));
                break;
            }
        }
    }
    bool gray = true;
    for (const samples::FloatImage& image : images) gray = gray && image.channels == 1;
    const int count = int(images.size());
    const int rows = (count + kStripMaxColumns - 1) / kStripMaxColumns;
    const samples::FloatImage sheet = samples::contact_sheet(images, labels, (count + rows - 1) / rows);
    return gray ? first_channel(sheet) : sheet;
}

void print_compare_table(const CompareResult& result) {
    std::vector<std::string> header = {"method", "gpu ms", "wall ms", "mean_abs", "within_5pct", "psnr dB", "max_abs"};
    if (result.orbit_degrees) header.push_back("flicker");
    header.push_back("ref");
    TextTable table(header);
    for (const ComparedMethod& method : result.methods) {
        std::vector<std::string> row = {method.spec.text,
                                        format_fixed(method.timing.sdk_total().median_ms, 2),
                                        format_fixed(method.timing.wall.median_ms, 2),
                                        format_fixed(method.metrics.mean_abs, 5),
                                        format_fixed(method.metrics.within_5pct, 4),
                                        format_psnr(method.metrics.psnr),
                                        format_fixed(method.metrics.max_abs, 4)};
        if (result.orbit_degrees) row.push_back(format_fixed(method.flicker.value_or(0.0), 5));
        row.push_back(std::to_string(method.reference + 1));
        table.add_row(row);
    }
    table.print(stdout);
}

void write_compare_json(const CompareResult& result, const std::string& path) {
    samples::JsonWriter json;
    json.begin_object();
    json.field("device", result.device);
    json.field("scene", result.scene);
    json.field("width", result.width).field("height", result.height);
    json.field("reference_rays", result.reference_rays);
    if (result.orbit_degrees) json.field("orbit_degrees", *result.orbit_degrees).field("frames", result.frames);
    json.key("methods").begin_array();
    for (size_t i = 0; i < result.methods.size(); ++i) {
        const ComparedMethod& method = result.methods[i];
        json.begin_object();
        json.field("method", method.spec.text);
        write_settings_json(json, method.spec.settings);
        write_gpu_ms_json(json, method.timing);
        json.field("wall_ms", method.timing.wall.median_ms);
        json.field("mean_abs", method.metrics.mean_abs);
        json.field("within_5pct", method.metrics.within_5pct);
        json.field("psnr", method.metrics.psnr);  // null when the images are identical
        json.field("max_abs", method.metrics.max_abs);
        if (method.flicker) json.field("flicker", *method.flicker);
        json.field("image", method_file_stem(result, i) + ".png");
        json.field("reference_image", reference_file(method.reference));
        json.end_object();
    }
    json.end_array();
    json.key("references").begin_array();
    for (const ComparedReference& reference : result.references) {
        json.begin_object();
        json.field("falloff", reference.description);
        write_settings_json(json, reference.settings);
        json.field("seconds", reference.seconds);
        json.end_object();
    }
    json.end_array();
    json.end_object().write_file(path);
}

}  // namespace obscura::cli
