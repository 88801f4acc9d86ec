// What `obscura tune` searches and how it writes its result down, without GL: the method's metadata rows as
// normalised coordinates of samples/common/settings_search.h (ranges from the metadata, log scales where they
// span many decades, the levels of integers, enums and toggles), the falloff the geometry truth of a candidate
// weighs with, and settings as a method spec (as C code: samples/viewer/settings_document.h's settings_to_c).
#ifndef OBSCURA_CLI_TUNE_SPACE_H
#define OBSCURA_CLI_TUNE_SPACE_H

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "method_spec.h"
#include "obscura/obscura.h"
#include "settings_search.h"

namespace obscura::cli {

// The search's first mesh size: a quarter of each coordinate's range (log scales: see TunedKey::parameter).
constexpr double kTuneInitialStep = 0.25;

enum class TuneScale { Linear, Log, ZeroOrLog, Levels };

// One searched row: how a coordinate in [0, 1] maps to its values.
//   Linear     min + u (max - min)                        floats whose range spans at most 2 decades
//   Log        min (max / min)^u                          floats with min > 0 spanning more
//   ZeroOrLog  0 at u = 0, else low (max / low)^u         floats from 0 to a large max (thickness [0, 1e4] m),
//                                                         low = max / 1e6
//   Levels     levels[k] for the k-th of the levels        integers (every value, or a geometric grid where they
//                                                         span more than 2 decades), enums and toggles
// Continuous values are rounded to 3 significant digits (so the spec printed is what was measured); the start's
// coordinate maps back to the start's own value. On log scales the coordinate's first step is a factor of 2.
struct TunedKey {
    obscura_setting_info info{};
    samples::SearchParameter parameter;
    TuneScale scale = TuneScale::Linear;
    double low = 0.0, high = 0.0;  // continuous: the range (ZeroOrLog: low is the log part's lower end)
    std::vector<double> levels;    // Levels: the value of each level, ascending, the start's among them
    double start_value = 0.0;      // the start's effective value
    double start_coordinate = 0.0; // snapped
    bool changes_falloff = false;  // some of its values move the falloff the truth weighs with

    double value_at(double coordinate) const;
    double coordinate_of(double value) const;
    // "[0.001, 16] log", "{low, medium, high, ultra}", "1..32", "0 or [0.01, 1e+04] m log".
    std::string describe() const;
    const char* scale_name() const;  // "linear", "log", "zero-or-log", "levels"
};

struct SearchSpace {
    std::vector<TunedKey> keys;
    std::vector<std::pair<std::string, std::string>> left_out;  // name, why
};

// The rows of `start`'s method to search. Without `keys`: every FLOAT, INT, ENUM and TOGGLE row that is not
// derived, not a scheduling or noise choice (frame_index, first_ray, rays_per_dispatch) and does not move the
// falloff the truth weighs with (radius, falloff_c, falloff, GTAO's falloff_range: found by trying values);
// UsageError when none is left. With `keys`: those rows, derived and falloff ones included; UsageError for a
// name the method does not have, an array, or a scheduling or noise row.
SearchSpace make_search_space(const MethodSpec& start, const std::optional<std::vector<std::string>>& keys);

// The falloff the geometry truth of `settings` weighs hits with: obscura_reference_settings_for's, with `rays`,
// first_ray 0, the default batching and no thickness (the truth has the scene's own); nullopt when refused.
std::optional<obscura_settings> geometry_falloff(const obscura_settings& settings, int rays);

// "<call> failed: <status>: <obscura_get_last_error(NULL)>", for the context-free calls.
std::string context_free_error(obscura_status status, const std::string& call);

// Copies the row's field (a float or an int32: not an array) from `from` into `to`.
void copy_setting(obscura_settings& to, const obscura_settings& from, const obscura_setting_info& info);

// A value as a spec takes it: enums by name, toggles on/off, integers whole, floats in their shortest form.
std::string spec_value_text(const obscura_setting_info& info, double value);
// "gtao:preset=ultra:power=1.8": the method and every setting that differs from its editable defaults (derived
// ones only when fixed; the falloff table only when the falloff reads it), as --method takes it.
std::string settings_spec(const obscura_settings& settings);
// Whether `spec` parses to settings that store what `settings` stores.
bool spec_reads_back(const std::string& spec, const obscura_settings& settings);

// The start as tune searches from it: every single-valued field that is not left to derive holds the value the SDK
// reads for it (a 0 that means "default" in a field whose range excludes 0 becomes that default), so that the best
// settings, their spec and their C code name the same values.
void normalise_start(obscura_settings* settings);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_TUNE_SPACE_H
