// What `compare` writes: the images (each method's AO and its error heat map against each truth, each truth's
// images, a labelled contact sheet), the tables on stdout and the JSON report.
#ifndef OBSCURA_CLI_COMPARE_OUTPUT_H
#define OBSCURA_CLI_COMPARE_OUTPUT_H

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ao_render.h"
#include "image_io.h"
#include "method_spec.h"
#include "metrics.h"

namespace obscura::cli {

// What a method is measured against:
//   Geometry  the geometry truth: rays against the scene's triangles (samples/common/geometry_truth.h), what a
//             viewer sees; mesh scenes only.
//   Screen    the screen-space reference: the SDK's REFERENCE method, rays through the depth buffer, which
//             takes every depth texel as infinitely thick unless its `thickness` is set; the ceiling of what a
//             screen-space method can compute, and the only reference a captured depth buffer has.
enum class TruthKind { Geometry, Screen };
// "geometry", "screen".
const char* truth_kind_name(TruthKind kind);

// One falloff's images of one truth.
struct ComparedReference {
    obscura_settings settings{};              // REFERENCE, resolved: the falloff (screen: and the ray count)
    std::string description;                  // "rho0 r=1 m"
    std::vector<samples::FloatImage> frames;  // one per camera (one without --orbit)
    std::vector<samples::FloatImage> bent_frames;  // geometry: the truth's bent normals, one per camera
    double seconds = 0.0;                     // screen: its wall time; geometry: 0 (see ComparedTruth::seconds)
};

struct ComparedTruth {
    TruthKind kind = TruthKind::Geometry;
    int rays = 0;                 // per pixel
    uint32_t seed = 0;            // geometry
    int triangles = 0;            // geometry
    uint64_t rays_cast = 0;       // geometry: hemisphere rays of every frame
    double seconds = 0.0;         // every reference of every frame
    std::vector<ComparedReference> references;  // ComparedMethod::reference indexes it
};

// --classes: the geometry pixels split by where a screen-space method's thickness assumption matters
// (samples::thickness_classes): silhouettes, halos and the rest.
constexpr double kClassesDefaultRadius = 1.0;     // metres: GTAO's and HBAO's default radius
constexpr double kClassesDefaultThickness = 0.3;  // metres
constexpr double kClassesMaxRadiusPx = 256.0;     // the window's largest half size
// The classes measured, in the order tables and reports list them.
constexpr samples::ThicknessClass kMeasuredClasses[] = {samples::ThicknessClass::Silhouette,
                                                       samples::ThicknessClass::Halo, samples::ThicknessClass::Rest};
constexpr size_t kMeasuredClassCount = sizeof kMeasuredClasses / sizeof kMeasuredClasses[0];

struct PixelClasses {
    double radius_m = kClassesDefaultRadius;
    double thickness_m = kClassesDefaultThickness;
    double max_radius_px = kClassesMaxRadiusPx;
    std::vector<std::vector<uint8_t>> frames;  // per frame, one samples::ThicknessClass per pixel (rows bottom-up)
    size_t pixels[kMeasuredClassCount] = {};   // per measured class, summed over the frames
    size_t geometry_pixels = 0;                // summed over the frames
};

// A method's error over the pixels of one class, pooled over the frames (every pixel of every frame weighs the
// same).
struct ClassErrors {
    size_t pixels = 0;
    double mean_abs = 0.0;
    double mean_signed = 0.0;  // method - truth
    double within_5pct = 0.0;
    std::optional<double> flicker;  // with --frames: samples::flicker over the class's pixels
    std::optional<double> noise_flicker;  // with --converged: against the converged frames, over the class's pixels
};

// The ghosting of a temporal accumulation: the method's error by the frames since an event (samples::error_by_age:
// ages 0 .. kGhostMaxAge - 1, then every older one pooled), beside the error of the method's converged images in the
// same pixels and frames. An animated scene seen by a still camera has two curves: "uncovered" (the pixels the moving
// object uncovered) and "changed" (those whose converged image it changed by more than 0.02: its contact shadow
// passing; uncovered pixels included). An orbit has one, "disoccluded": the pixels whose surface point came into
// view (samples::frames_since_disocclusion: off the previous image or hidden there).
constexpr int kGhostMaxAge = 8;
constexpr double kGhostChangedThreshold = 0.02;
constexpr double kGhostTolerance = 0.02;  // the "back within 0.02 of the converged error"
struct GhostCurve {
    const char* name = "";
    std::vector<samples::AgeErrors> buckets;  // kGhostMaxAge + 1
};
struct GhostErrors {
    std::vector<GhostCurve> curves;
};

// A method's error against one truth, averaged over the frames.
struct MethodErrors {
    samples::ErrorMetrics metrics;
    std::optional<double> flicker;  // with --orbit: samples::flicker against the truth's frames
    std::optional<double> last_mean_abs;  // with --frames: the last frame's mean_abs (temporal: the converged error)
    // With --converged: the flicker against the method's own converged frames (the sampling noise's alone), and those
    // frames' mean_abs averaged over the frames.
    std::optional<double> noise_flicker;
    std::optional<double> converged_mean_abs;
    // With --frames on a scene: samples::surface_flicker of the method's frames (how much a surface point's AO changes
    // from frame to frame, what a viewer sees flicker), and of its converged frames with --converged.
    std::optional<double> surface_flicker;
    std::optional<double> converged_surface_flicker;
    std::optional<GhostErrors> ghosting;  // an animated scene seen still, or an orbit, with --converged
    std::optional<double> bent_degrees;  // geometry truth, methods that write bent normals: mean angle to the truth's
    std::optional<double> normal_degrees;  // the same for the surface normals the method used (the baseline)
    std::vector<ClassErrors> classes;      // with --classes: one per kMeasuredClasses
};

struct ComparedMethod {
    MethodSpec spec;
    size_t reference = 0;                     // the falloff: index into every ComparedTruth::references
    TimingSummary timing;                     // warm frames of the first camera
    std::vector<samples::FloatImage> frames;  // one per camera
    std::vector<samples::FloatImage> bent_frames;  // methods that write bent normals: RGBA, one per camera
    std::vector<samples::FloatImage> normal_frames;  // and the normals they used (debug view, decoded), per camera
    std::vector<samples::FloatImage> converged_frames;  // --converged: the many-sample image of each frame
    std::vector<MethodErrors> errors;         // one per CompareResult::truths
};

struct CompareResult {
    std::string device;  // GL_RENDERER
    std::string scene;
    int width = 0;
    int height = 0;
    int frames = 1;
    std::optional<double> orbit_degrees;
    bool motion_vectors = false;  // the frames handed their motion vectors over
    int converged_frames = 0;     // --converged: still frames accumulated into each frame's many-sample image
    // The ghosting's pixels (an animated scene seen still), per frame: the still geometry the camera sees, and the
    // pixels the moving object has just uncovered. Empty: no ghosting measured.
    std::vector<std::vector<uint8_t>> still_geometry;
    // With --frames on a scene: each frame's view depth (the truth's primary hits) and matrices (surface_flicker).
    std::vector<samples::FrameGeometry> geometry;
    std::vector<std::optional<double>> truth_surface_flicker;  // per truth, its first reference's: the floor its rays' noise and the bilinear read set
    std::vector<std::vector<uint8_t>> uncovered;
    // With --orbit and --converged: each frame's per-pixel frames since the pixel's surface point came into view
    // (samples::frames_since_disocclusion). Empty: no orbit ghosting.
    std::vector<std::vector<int>> disocclusion_ages;
    // Metrics cover the geometry pixels (sky left out: a view of much sky would otherwise score better than
    // its geometry deserves) unless all_pixels (--metrics-pixels all).
    bool all_pixels = false;
    std::vector<std::vector<uint8_t>> masks;  // per frame, one byte per pixel: 1 geometry, 0 sky
    std::vector<ComparedTruth> truths;        // in the order asked for; the first one is the headline
    std::vector<ComparedMethod> methods;
    std::optional<PixelClasses> classes;      // --classes

    // Of the first frame.
    size_t geometry_pixels() const;
    double sky_fraction() const;
};

// "<index>_<method name>" (1-based index), the stem of a method's image files.
std::string method_file_stem(const CompareResult& result, size_t method_index);
// "<stem>_error_<truth>.png" (heat map of |method - truth|), "<stem>_signed_<truth>.png" (red too dark, blue too
// bright) and the truth's image of falloff k: "geometry_truth_<k>.png" or "reference_<k>.png".
std::string error_file(const CompareResult& result, size_t method_index, TruthKind truth);
std::string signed_error_file(const CompareResult& result, size_t method_index, TruthKind truth);
std::string truth_file(TruthKind truth, size_t reference_index);

// Writes <stem>.png, <stem>_error_<truth>.png and <stem>_signed_<truth>.png per method and truth, each truth's
// image per falloff (first frame) and contact_sheet.png (per method: AO, then for each truth the truth and the
// signed error map) into `directory` (created if needed), and with --classes classes.png (first frame: sky black,
// rest white, halo blue, silhouette red). Returns the file names written.
std::vector<std::string> write_compare_images(const CompareResult& result, const std::filesystem::path& directory);
// The --strip sheet, for documentation: each method's AO (first frame) labelled with its settings (the
// spec without the method's name when every spec names the same method), then, when the methods were
// measured against more than one falloff, the first truth's image of each labelled "truth: " (geometry) or
// "ref: " (screen) and the label of the first method measured against it; at most four images per row, the rows balanced. Gray when every
// image is.
samples::FloatImage compare_strip(const CompareResult& result);
// One table per truth: a line per method with spec, times and errors (and flicker with --orbit); with --classes
// then the classes' pixel counts and a line per method with its error in each class.
void print_compare_table(const CompareResult& result);
// With --classes the report adds "classes" (radius_m, thickness_m, max_radius_px, frames, image, geometry_pixels and
// per class {pixels, fraction}) and per method and truth errors.<truth>.classes (per class {pixels, mean_abs,
// signed_mean, within_5pct}; the errors null for a class without pixels).
// `context`: the session's, through which the methods' settings are resolved (the values its renderer derives).
void write_compare_json(const CompareResult& result, const std::string& path, obscura_context* context);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_COMPARE_OUTPUT_H
