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

std::string format_signed(double value, int digits) {
    return (value >= 0.0 ? "+" : "") + format_fixed(value, digits);
}

// "geometry truth (1024 rays)", "screen-space reference (256 rays)".
std::string describe_truth(const ComparedTruth& truth) {
    return std::string(truth.kind == TruthKind::Geometry ? "geometry truth" : "screen-space reference") + " (" +
           std::to_string(truth.rays) + " rays)";
}

constexpr int kStripMaxColumns = 4;
constexpr const char* kClassesImage = "classes.png";

// "1 m", "0.3 m".
std::string format_metres(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g m", value);
    return text;
}

// The classes' pixel counts and the table of each method's error per class against truth t.
void print_class_table(const CompareResult& result, size_t t) {
    const PixelClasses& classes = *result.classes;
    std::printf("\nclasses (radius %s, thickness %s, window <= %g px):", format_metres(classes.radius_m).c_str(),
                format_metres(classes.thickness_m).c_str(), classes.max_radius_px);
    for (size_t c = 0; c < kMeasuredClassCount; ++c) {
        const double share = classes.geometry_pixels > 0 ? double(classes.pixels[c]) / double(classes.geometry_pixels) : 0.0;
        std::printf("%s %s %zu px (%.1f %%)", c == 0 ? "" : ",", samples::thickness_class_name(kMeasuredClasses[c]),
                    classes.pixels[c], 100.0 * share);
    }
    std::printf(" of %zu geometry pixels%s\n", classes.geometry_pixels,
                classes.frames.size() > 1 ? (", " + std::to_string(classes.frames.size()) + " frames pooled").c_str() : "");
    std::vector<std::string> header = {"method"};
    for (samples::ThicknessClass value : kMeasuredClasses) {
        header.push_back(std::string(samples::thickness_class_name(value)) + ": mean_abs");
        header.push_back("signed");
        if (result.frames > 1) header.push_back("flicker");
        if (result.converged_frames > 0) header.push_back("noise");
    }
    TextTable table(header);
    for (const ComparedMethod& method : result.methods) {
        std::vector<std::string> row = {method.spec.text};
        for (const ClassErrors& errors : method.errors[t].classes) {
            row.push_back(errors.pixels > 0 ? format_fixed(errors.mean_abs, 5) : "-");
            row.push_back(errors.pixels > 0 ? format_signed(errors.mean_signed, 5) : "-");
            if (result.frames > 1) row.push_back(errors.flicker ? format_fixed(*errors.flicker, 5) : "-");
            if (result.converged_frames > 0) row.push_back(errors.noise_flicker ? format_fixed(*errors.noise_flicker, 5) : "-");
        }
        table.add_row(row);
    }
    table.print(stdout);
}

// The first age from which a curve's error stays within `tolerance` of its converged error (the last bucket counts as
// one age), or -1 when it never does.
int settles_at(const std::vector<samples::AgeErrors>& curve, double tolerance) {
    int settled = -1;
    for (int age = int(curve.size()) - 1; age >= 0; --age) {
        const samples::AgeErrors& bucket = curve[size_t(age)];
        if (bucket.pixels > 0 && bucket.mean_abs - bucket.converged_mean_abs > tolerance) break;
        if (bucket.pixels > 0) settled = age;
    }
    return settled;
}

// Each method's ghosting against truth t: per curve the pixels, then per age the error above the converged one.
void print_ghosting_table(const CompareResult& result, size_t t) {
    if (result.disocclusion_ages.empty()) {
        std::printf("\nghosting (the moving object, a still camera): error - converged error (%d still frames) of the "
                    "pixels it uncovered and of those whose converged AO it changed by > %g, by frames since; within "
                    "0.02 from: the first age after which it stays within\n",
                    result.converged_frames, kGhostChangedThreshold);
    } else {
        std::printf("\nghosting (the moving camera): error - converged error (%d still frames) of the pixels whose "
                    "surface came into view (off the previous frame or hidden there), by frames since; within 0.02 "
                    "from: the first age after which it stays within\n",
                    result.converged_frames);
    }
    std::vector<std::string> header = {"method", "pixels", "within 0.02 from"};
    for (int age = 0; age < kGhostMaxAge; ++age) header.push_back(std::to_string(age));
    header.push_back(">=" + std::to_string(kGhostMaxAge));
    TextTable table(header);
    for (const ComparedMethod& method : result.methods) {
        const std::optional<GhostErrors>& ghosting = method.errors[t].ghosting;
        if (!ghosting) continue;
        for (const GhostCurve& curve : ghosting->curves) {
            const std::vector<samples::AgeErrors>& buckets = curve.buckets;
            size_t pixels = 0;
            for (const samples::AgeErrors& bucket : buckets) pixels += bucket.pixels;
            const int settled = settles_at(buckets, kGhostTolerance);
            std::vector<std::string> row = {method.spec.text + " " + curve.name, std::to_string(pixels),
                                            settled < 0 ? "never" : std::to_string(settled)};
            for (const samples::AgeErrors& bucket : buckets) {
                row.push_back(bucket.pixels > 0 ? format_signed(bucket.mean_abs - bucket.converged_mean_abs, 4) : "-");
            }
            table.add_row(row);
        }
    }
    table.print(stdout);
}

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

const char* truth_kind_name(TruthKind kind) {
    return kind == TruthKind::Geometry ? "geometry" : "screen";
}

size_t CompareResult::geometry_pixels() const {
    if (masks.empty()) return size_t(width) * size_t(height);
    size_t count = 0;
    for (uint8_t value : masks.front()) count += value != 0;
    return count;
}

double CompareResult::sky_fraction() const {
    const double total = double(width) * double(height);
    return total > 0.0 ? 1.0 - double(geometry_pixels()) / total : 0.0;
}

std::string method_file_stem(const CompareResult& result, size_t method_index) {
    return std::to_string(method_index + 1) + "_" + result.methods[method_index].spec.name();
}

std::string error_file(const CompareResult& result, size_t method_index, TruthKind truth) {
    return method_file_stem(result, method_index) + "_error_" + truth_kind_name(truth) + ".png";
}

std::string signed_error_file(const CompareResult& result, size_t method_index, TruthKind truth) {
    return method_file_stem(result, method_index) + "_signed_" + truth_kind_name(truth) + ".png";
}

std::string truth_file(TruthKind truth, size_t reference_index) {
    return std::string(truth == TruthKind::Geometry ? "geometry_truth_" : "reference_") +
           std::to_string(reference_index + 1) + ".png";
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
        write(method_file_stem(result, i) + ".png", method.frames.front());
        sheet.push_back(method.frames.front());
        labels.push_back(std::to_string(i + 1) + " " + method.spec.text);
        for (size_t t = 0; t < result.truths.size(); ++t) {
            const ComparedTruth& truth = result.truths[t];
            const ComparedReference& reference = truth.references[method.reference];
            const samples::ErrorMetrics& metrics = method.errors[t].metrics;
            write(error_file(result, i, truth.kind),
                  samples::error_heat_map(method.frames.front(), reference.frames.front()));
            const samples::FloatImage signed_errors =
                samples::signed_error_map(method.frames.front(), reference.frames.front());
            write(signed_error_file(result, i, truth.kind), signed_errors);
            sheet.push_back(reference.frames.front());
            labels.push_back(std::string(truth.kind == TruthKind::Geometry ? "truth: " : "screen ref: ") +
                             reference.description);
            sheet.push_back(signed_errors);
            labels.push_back(std::string(truth_kind_name(truth.kind)) + " " + format_fixed(metrics.mean_abs, 4) + " " +
                             format_signed(metrics.mean_signed, 3) + " " + format_fixed(100.0 * metrics.within_5pct, 0) +
                             "%");
        }
    }
    for (const ComparedTruth& truth : result.truths) {
        for (size_t k = 0; k < truth.references.size(); ++k) write(truth_file(truth.kind, k), truth.references[k].frames.front());
    }
    write("contact_sheet.png", samples::contact_sheet(sheet, labels, int(1 + 2 * result.truths.size())));
    if (result.classes) {
        write(kClassesImage, samples::thickness_class_image(result.classes->frames.front(), result.width, result.height));
    }
    return written;
}

samples::FloatImage compare_strip(const CompareResult& result) {
    std::vector<samples::FloatImage> images;
    std::vector<std::string> labels;
    for (size_t i = 0; i < result.methods.size(); ++i) {
        images.push_back(result.methods[i].frames.front());
        labels.push_back(strip_label(result, i));
    }
    // One falloff's truth is its own file; several differ in what the labels of their methods say (their
    // descriptions would not fit a tile), so each is labelled with the first method measured against it.
    const std::vector<ComparedReference>& references = result.truths.front().references;
    for (size_t k = 0; references.size() > 1 && k < references.size(); ++k) {
        for (size_t i = 0; i < result.methods.size(); ++i) {
            if (result.methods[i].reference == k) {
                images.push_back(references[k].frames.front());
                labels.push_back(std::string(result.truths.front().kind == TruthKind::Geometry ? "truth: " : "ref: ") +
                                 strip_label(result, i));
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
    for (size_t t = 0; t < result.truths.size(); ++t) {
        const ComparedTruth& truth = result.truths[t];
        std::printf("\nerrors against the %s over %s of the %dx%d output rectangle (sky %.1f %%)%s:\n",
                    describe_truth(truth).c_str(),
                    result.all_pixels ? "every pixel" : (std::to_string(result.geometry_pixels()) + " geometry pixels").c_str(),
                    result.width, result.height, 100.0 * result.sky_fraction(),
                    result.frames > 1 ? ", averaged over the frames" : "");
        std::vector<std::string> header = {"method", "gpu ms", "wall ms", "mean_abs", "within_5pct", "psnr dB", "max_abs",
                                           "signed"};
        if (result.frames > 1) {
            header.push_back("flicker");
            header.push_back("last");
        }
        if (!result.geometry.empty()) header.push_back("surface flicker");
        if (result.converged_frames > 0) {
            header.push_back("noise flicker");
            header.push_back("converged");
            header.push_back("its surface flicker");
        }
        header.push_back(truth.kind == TruthKind::Geometry ? "truth" : "ref");
        TextTable table(header);
        for (const ComparedMethod& method : result.methods) {
            const MethodErrors& errors = method.errors[t];
            std::vector<std::string> row = {method.spec.text,
                                            format_fixed(method.timing.sdk_total().median_ms, 2),
                                            format_fixed(method.timing.wall.median_ms, 2),
                                            format_fixed(errors.metrics.mean_abs, 5),
                                            format_fixed(errors.metrics.within_5pct, 4),
                                            format_psnr(errors.metrics.psnr),
                                            format_fixed(errors.metrics.max_abs, 4),
                                            format_signed(errors.metrics.mean_signed, 5)};
            if (result.frames > 1) {
                row.push_back(format_fixed(errors.flicker.value_or(0.0), 5));
                row.push_back(format_fixed(errors.last_mean_abs.value_or(0.0), 5));
            }
            // "-": no pixel could be followed from frame to frame (nothing measured, not "no flicker").
            auto optional_fixed = [](const std::optional<double>& value) {
                return value ? format_fixed(*value, 5) : std::string("-");
            };
            if (!result.geometry.empty()) row.push_back(optional_fixed(errors.surface_flicker));
            if (result.converged_frames > 0) {
                row.push_back(format_fixed(errors.noise_flicker.value_or(0.0), 5));
                row.push_back(format_fixed(errors.converged_mean_abs.value_or(0.0), 5));
                row.push_back(optional_fixed(errors.converged_surface_flicker));
            }
            row.push_back(std::to_string(method.reference + 1));
            table.add_row(row);
        }
        table.print(stdout);
        if (t < result.truth_surface_flicker.size()) {
            const std::optional<double>& floor = result.truth_surface_flicker[t];
            std::printf("surface flicker: how much a surface point's AO changes from frame to frame (reprojected); the "
                        "%s's own: %s (its first falloff's; the floor its rays' noise and the previous frame's bilinear "
                        "read set)\n",
                        truth.kind == TruthKind::Geometry ? "truth" : "reference",
                        floor ? format_fixed(*floor, 5).c_str() : "- (no pixel could be followed)");
        }
        for (const ComparedMethod& method : result.methods) {
            const MethodErrors& errors = method.errors[t];
            if (errors.bent_degrees) {
                std::printf("bent normals of %s: mean angle to the truth's %.2f degrees (its surface normals': %.2f)\n",
                            method.spec.text.c_str(), *errors.bent_degrees, errors.normal_degrees.value_or(0.0));
            }
        }
        if (result.classes) print_class_table(result, t);
        if (!result.still_geometry.empty() || !result.disocclusion_ages.empty()) print_ghosting_table(result, t);
    }
    std::printf("signed = mean of method - truth: > 0 brighter (less occlusion) than the truth, < 0 darker\n");
}

void write_compare_json(const CompareResult& result, const std::string& path, obscura_context* context) {
    samples::JsonWriter json;
    json.begin_object();
    json.field("device", result.device);
    json.field("scene", result.scene);
    json.field("width", result.width).field("height", result.height);
    json.key("pixels").begin_object();
    json.field("metrics_over", result.all_pixels ? "all" : "geometry");
    json.field("total", double(result.width) * double(result.height));
    json.field("geometry", double(result.geometry_pixels()));
    json.field("sky_fraction", result.sky_fraction());
    json.end_object();
    if (result.orbit_degrees) json.field("orbit_degrees", *result.orbit_degrees);
    if (result.frames > 1) json.field("frames", result.frames).field("motion_vectors", result.motion_vectors);
    if (result.converged_frames > 0) json.field("converged_frames", result.converged_frames);
    if (result.classes) {
        const PixelClasses& classes = *result.classes;
        json.key("classes").begin_object();
        json.field("radius_m", classes.radius_m);
        json.field("thickness_m", classes.thickness_m);
        json.field("max_radius_px", classes.max_radius_px);
        json.field("frames", double(classes.frames.size()));
        json.field("image", kClassesImage);
        json.field("geometry_pixels", double(classes.geometry_pixels));
        for (size_t c = 0; c < kMeasuredClassCount; ++c) {
            json.key(samples::thickness_class_name(kMeasuredClasses[c])).begin_object();
            json.field("pixels", double(classes.pixels[c]));
            json.field("fraction", classes.geometry_pixels > 0
                                       ? double(classes.pixels[c]) / double(classes.geometry_pixels) : 0.0);
            json.end_object();
        }
        json.end_object();
    }
    json.key("methods").begin_array();
    for (size_t i = 0; i < result.methods.size(); ++i) {
        const ComparedMethod& method = result.methods[i];
        json.begin_object();
        json.field("method", method.spec.text);
        write_settings_json(json, method.spec.settings, context);
        write_gpu_ms_json(json, method.timing);
        json.field("wall_ms", method.timing.wall.median_ms);
        json.field("image", method_file_stem(result, i) + ".png");
        json.field("falloff", int(method.reference) + 1);
        json.key("errors").begin_object();
        for (size_t t = 0; t < result.truths.size(); ++t) {
            const MethodErrors& errors = method.errors[t];
            json.key(truth_kind_name(result.truths[t].kind)).begin_object();
            json.field("mean_abs", errors.metrics.mean_abs);
            json.field("signed_mean", errors.metrics.mean_signed);
            json.field("within_5pct", errors.metrics.within_5pct);
            json.field("psnr", errors.metrics.psnr);  // null when the images are identical
            json.field("max_abs", errors.metrics.max_abs);
            json.field("pixels", double(errors.metrics.pixels));
            if (errors.flicker) json.field("flicker", *errors.flicker);
            if (errors.last_mean_abs) json.field("last_frame_mean_abs", *errors.last_mean_abs);
            if (errors.noise_flicker) json.field("noise_flicker", *errors.noise_flicker);
            if (errors.surface_flicker) json.field("surface_flicker", *errors.surface_flicker);
            if (errors.converged_surface_flicker) json.field("converged_surface_flicker", *errors.converged_surface_flicker);
            if (errors.converged_mean_abs) json.field("converged_mean_abs", *errors.converged_mean_abs);
            if (errors.ghosting) {
                json.key("ghosting").begin_object();
                for (const GhostCurve& curve : errors.ghosting->curves) {
                    const std::vector<samples::AgeErrors>& buckets = curve.buckets;
                    json.key(curve.name).begin_object();
                    const int settled = settles_at(buckets, kGhostTolerance);
                    json.key("within_0_02_from");  // null: never
                    if (settled < 0) json.null(); else json.value(settled);
                    json.key("ages").begin_array();
                    for (size_t age = 0; age < buckets.size(); ++age) {
                        json.begin_object();
                        json.field("age", int(age)).field("older", age + 1 == buckets.size());
                        json.field("pixels", double(buckets[age].pixels));
                        json.field("mean_abs", buckets[age].mean_abs);
                        json.field("converged_mean_abs", buckets[age].converged_mean_abs);
                        json.end_object();
                    }
                    json.end_array();
                    json.end_object();
                }
                json.end_object();
            }
            if (errors.bent_degrees) json.field("bent_normal_degrees", *errors.bent_degrees);
            if (errors.normal_degrees) json.field("surface_normal_degrees", *errors.normal_degrees);
            if (!errors.classes.empty()) {
                json.key("classes").begin_object();
                for (size_t c = 0; c < errors.classes.size(); ++c) {
                    const ClassErrors& class_errors = errors.classes[c];
                    // A class without pixels has no error: null, not a perfect 0.
                    const auto error_field = [&](const char* name, double value) {
                        json.key(name);
                        if (class_errors.pixels > 0) {
                            json.value(value);
                        } else {
                            json.null();
                        }
                    };
                    json.key(samples::thickness_class_name(kMeasuredClasses[c])).begin_object();
                    json.field("pixels", double(class_errors.pixels));
                    error_field("mean_abs", class_errors.mean_abs);
                    // With --frames (--converged): null where no pixel of the class was seen in both frames of a pair.
                    const auto flicker_field = [&](const char* name, const std::optional<double>& value) {
                        json.key(name);
                        if (value) {
                            json.value(*value);
                        } else {
                            json.null();
                        }
                    };
                    if (result.frames > 1) flicker_field("flicker", class_errors.flicker);
                    if (result.converged_frames > 0) flicker_field("noise_flicker", class_errors.noise_flicker);
                    error_field("signed_mean", class_errors.mean_signed);
                    error_field("within_5pct", class_errors.within_5pct);
                    json.end_object();
                }
                json.end_object();
            }
            json.field("error_image", error_file(result, i, result.truths[t].kind));
            json.field("signed_error_image", signed_error_file(result, i, result.truths[t].kind));
            json.field("truth_image", truth_file(result.truths[t].kind, method.reference));
            json.end_object();
        }
        json.end_object();
        json.end_object();
    }
    json.end_array();
    json.key("truths").begin_array();
    for (size_t t = 0; t < result.truths.size(); ++t) {
        const ComparedTruth& truth = result.truths[t];
        json.begin_object();
        if (t < result.truth_surface_flicker.size() && result.truth_surface_flicker[t]) {
            json.field("surface_flicker", *result.truth_surface_flicker[t]);
        }
        json.key("truth").begin_object();
        json.field("kind", truth_kind_name(truth.kind));
        json.field("rays", truth.rays);
        json.field("seconds", truth.seconds);
        if (truth.kind == TruthKind::Geometry) {
            json.field("seed", double(truth.seed));
            json.field("triangles", truth.triangles);
            json.field("rays_cast", double(truth.rays_cast));
            json.field("rays_per_second", truth.seconds > 0.0 ? double(truth.rays_cast) / truth.seconds : 0.0);
        }
        json.end_object();
        json.key("references").begin_array();
        for (size_t k = 0; k < truth.references.size(); ++k) {
            const ComparedReference& reference = truth.references[k];
            json.begin_object();
            json.field("falloff", reference.description);
            write_settings_json(json, reference.settings);
            json.field("image", truth_file(truth.kind, k));
            if (truth.kind == TruthKind::Screen) json.field("seconds", reference.seconds);
            json.end_object();
        }
        json.end_array();
        json.end_object();
    }
    json.end_array();
    json.end_object().write_file(path);
}

}  // namespace obscura::cli
