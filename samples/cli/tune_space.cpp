#include "tune_space.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>

#include "cli_errors.h"
#include "method_spec_parser.h"
#include "reference_render.h"

namespace obscura::cli {
namespace {

// Continuous values are rounded to this many significant digits before they are measured, so that the spec
// printed is exactly what was measured and reads as a person would write it.
constexpr int kSignificantDigits = 3;
// A range spans "many decades" beyond this ratio of max to min: it is searched on a log scale.
constexpr double kLogScaleRatio = 100.0;
// Ranges from 0 to a large max (thickness [0, 1e4] m) are searched as 0 or a log scale over the top 6 decades.
constexpr double kZeroOrLogDecades = 6.0;
// Integer rows on a log scale: at most this many levels (geometric, rounded, deduplicated).
constexpr int kLogIntegerLevels = 33;
// On log scales the most a first step multiplies or divides a value by: a quarter of [0.001, 16] would be a
// factor of 11.
constexpr double kLogFirstFactor = 2.0;
// Integer rows on a linear scale with more values than this are searched on a grid of this many levels.
constexpr int kMaxIntegerLevels = 4097;

// Rows never searched: they choose how the work is scheduled or where the noise falls, not how good the picture
// is, so a search over them would only fit the noise of one frame.
struct NeverSearched {
    const char* name;
    const char* why;
};
constexpr NeverSearched kNeverSearched[] = {
    {"frame_index", "moves the noise pattern only"},
    {"first_ray", "picks which rays of the sequence are traced, not how many"},
    {"rays_per_dispatch", "batches the rays into dispatches: scheduling only"},
    {"frame_split", "spreads FFAO's orientations over frames; tune weighs one frame"},
    {"temporal.enabled", "accumulates over frames; tune weighs one frame"},
    {"temporal.max_frames", "accumulates over frames; tune weighs one frame"},
    {"temporal.clamp", "accumulates over frames; tune weighs one frame"},
    {"temporal.plane_tolerance", "accumulates over frames; tune weighs one frame"},
};

const char* never_searched_reason(const std::string& name) {
    for (const NeverSearched& row : kNeverSearched) {
        if (name == row.name) return row.why;
    }
    return nullptr;
}

// ---- Values as specs and C code write them ------------------------------------------------------------

// The shortest decimal that reads back as the same float: "1.5", "0.3", "1e-05".
std::string shortest_float_text(double value) {
    const float stored = float(value);
    char text[32];
    for (int digits = 1; digits <= 9; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, double(stored));
        if (std::strtof(text, nullptr) == stored) break;
    }
    return text;
}

double round_significant(double value, int digits) {
    if (value == 0.0 || !std::isfinite(value)) return value;
    const double scale = std::pow(10.0, double(digits - 1) - std::floor(std::log10(std::fabs(value))));
    return std::round(value * scale) / scale;
}

// What the user wrote, for a row of `settings` as stored (not resolved): derived fields that derive read 0.
double user_value(const obscura_settings& settings, const obscura_setting_info& info) {
    if (samples::derives(settings, info)) return 0.0;
    double value = 0.0;
    if (obscura_get_setting(&settings, info.name, &value) != OBSCURA_OK) return samples::stored_value(settings, info);
    return value;
}

bool same_array(const obscura_settings& a, const obscura_settings& b, const obscura_setting_info& info) {
    return std::memcmp(samples::array_values(a, info), samples::array_values(b, info),
                       sizeof(float) * info.value_count) == 0;
}

// The rows of `settings` that differ from the method's editable defaults (arrays only where the falloff reads
// the table).
std::vector<obscura_setting_info> changed_rows(const obscura_settings& settings) {
    obscura_settings defaults{};
    obscura_default_settings(settings.method, &defaults);
    const bool table = samples::uses_falloff_table(settings);
    std::vector<obscura_setting_info> rows;
    for (const obscura_setting_info& info : setting_infos(settings.method)) {
        if (samples::is_array(info)) {
            if (table && !same_array(settings, defaults, info)) rows.push_back(info);
        } else if (samples::stored_value(settings, info) != samples::stored_value(defaults, info)) {
            rows.push_back(info);
        }
    }
    return rows;
}

// Whether setting the row to any of a few values (its ends, its middle, every enum value) moves the falloff.
bool row_changes_falloff(const obscura_settings& start, const obscura_setting_info& info) {
    const std::optional<obscura_settings> base = geometry_falloff(start, 0);
    if (!base) return false;
    std::vector<double> probes;
    if (info.type == OBSCURA_SETTING_ENUM || info.type == OBSCURA_SETTING_TOGGLE) {
        for (double value = info.min_value; value <= info.max_value; value += 1.0) probes.push_back(value);
    } else {
        probes = {info.min_value, info.max_value, 0.5 * (info.min_value + info.max_value)};
        if (info.min_value > 0.0) probes.push_back(std::sqrt(info.min_value * info.max_value));
    }
    for (double value : probes) {
        obscura_settings probe = start;
        if (obscura_set_setting(&probe, info.name, value) != OBSCURA_OK) continue;
        const std::optional<obscura_settings> falloff = geometry_falloff(probe, 0);
        if (falloff && !same_reference(*falloff, *base)) return true;
    }
    return false;
}

// The value the SDK uses for the row (derived fields: what they derive to).
double effective_value(const obscura_settings& settings, const obscura_setting_info& info) {
    obscura_settings resolved{};
    obscura_status status = obscura_resolve_settings(nullptr, &settings, &resolved);
    if (status != OBSCURA_OK) throw ApiError(context_free_error(status, "obscura_resolve_settings"));
    double value = 0.0;
    status = obscura_get_setting(&resolved, info.name, &value);
    if (status != OBSCURA_OK) {
        throw ApiError(context_free_error(status, std::string("obscura_get_setting(") + info.name + ")"));
    }
    return value;
}

// The scale of a log coordinate over a range of ratio `ratio`: its first step is a factor of kLogFirstFactor.
double log_step_scale(double ratio) {
    return std::min(1.0, std::log(kLogFirstFactor) / (kTuneInitialStep * std::log(ratio)));
}

TunedKey make_tuned_key(const obscura_settings& start, const obscura_setting_info& info) {
    TunedKey key;
    key.info = info;
    key.start_value = effective_value(start, info);
    const double min = info.min_value;
    const double max = info.max_value;
    if (info.type == OBSCURA_SETTING_FLOAT) {
        key.parameter = samples::continuous_parameter();
        key.low = min;
        key.high = max;
        if (min > 0.0 && max / min > kLogScaleRatio) {
            key.scale = TuneScale::Log;
        } else if (min == 0.0 && max > kLogScaleRatio) {
            key.scale = TuneScale::ZeroOrLog;
            key.low = max * std::pow(10.0, -kZeroOrLogDecades);
        } else {
            key.scale = TuneScale::Linear;
        }
        if (key.scale != TuneScale::Linear) key.parameter.scale = log_step_scale(key.high / key.low);
    } else {
        key.scale = TuneScale::Levels;
        const bool log_levels = info.type == OBSCURA_SETTING_INT && min > 0.0 && max / min > kLogScaleRatio;
        if (log_levels) {
            for (int i = 0; i < kLogIntegerLevels; ++i) {
                key.levels.push_back(std::round(min * std::pow(max / min, double(i) / double(kLogIntegerLevels - 1))));
            }
        } else if (info.type == OBSCURA_SETTING_INT && max - min + 1.0 > double(kMaxIntegerLevels)) {
            for (int i = 0; i < kMaxIntegerLevels; ++i) {
                key.levels.push_back(std::round(min + (max - min) * double(i) / double(kMaxIntegerLevels - 1)));
            }
        } else {
            for (double value = min; value <= max; value += 1.0) key.levels.push_back(value);
        }
        key.levels.push_back(key.start_value);  // the start is always one of the levels
        std::sort(key.levels.begin(), key.levels.end());
        key.levels.erase(std::unique(key.levels.begin(), key.levels.end()), key.levels.end());
        const int count = int(key.levels.size());
        key.parameter = info.type == OBSCURA_SETTING_INT
                            ? samples::integer_parameter(count, log_levels ? log_step_scale(max / min) : 1.0)
                            : samples::enumerated_parameter(count);
    }
    key.start_coordinate = samples::snap_point({key.parameter}, {key.coordinate_of(key.start_value)}).front();
    key.changes_falloff = row_changes_falloff(start, info);
    return key;
}

std::string setting_names(const std::vector<obscura_setting_info>& infos) {
    std::string names;
    for (const obscura_setting_info& info : infos) names += (names.empty() ? "" : ", ") + std::string(info.name);
    return names;
}

}  // namespace

std::string spec_value_text(const obscura_setting_info& info, double value) {
    if (info.type == OBSCURA_SETTING_TOGGLE) return value != 0.0 ? "on" : "off";
    if (info.type == OBSCURA_SETTING_ENUM) {
        const std::string name = samples::value_name(info, value);
        if (!name.empty()) return name;
    }
    if (info.type == OBSCURA_SETTING_FLOAT) return shortest_float_text(value);
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", value);
    return text;
}

double TunedKey::value_at(double coordinate) const {
    if (coordinate == start_coordinate) return start_value;
    double value = 0.0;
    switch (scale) {
    case TuneScale::Levels: return levels[size_t(samples::level_of(parameter, coordinate))];
    case TuneScale::Linear: value = low + coordinate * (high - low); break;
    case TuneScale::Log: value = low * std::pow(high / low, coordinate); break;
    case TuneScale::ZeroOrLog:
        if (coordinate <= 0.0) return 0.0;
        value = low * std::pow(high / low, coordinate);
        break;
    }
    return std::clamp(round_significant(value, kSignificantDigits), info.min_value, info.max_value);
}

double TunedKey::coordinate_of(double value) const {
    switch (scale) {
    case TuneScale::Levels: {
        const auto nearest = std::min_element(levels.begin(), levels.end(), [&](double a, double b) {
            return std::fabs(a - value) < std::fabs(b - value);
        });
        return samples::coordinate_of_level(parameter, int(nearest - levels.begin()));
    }
    case TuneScale::Linear: return high > low ? (value - low) / (high - low) : 0.0;
    case TuneScale::Log: return std::log(std::max(value, low) / low) / std::log(high / low);
    case TuneScale::ZeroOrLog:
        if (value <= 0.0) return 0.0;
        return std::max(std::log(std::max(value, low) / low) / std::log(high / low), 1e-6);
    }
    return 0.0;
}

std::string TunedKey::describe() const {
    const std::string unit = info.unit && *info.unit ? std::string(" ") + info.unit : std::string();
    char text[128];
    switch (scale) {
    case TuneScale::Levels:
        if (info.type == OBSCURA_SETTING_ENUM || info.type == OBSCURA_SETTING_TOGGLE) {
            std::string names;
            for (double value : levels) names += (names.empty() ? "" : ", ") + spec_value_text(info, value);
            return "{" + names + "}";
        }
        std::snprintf(text, sizeof text, "%.0f..%.0f%s%s", levels.front(), levels.back(), unit.c_str(),
                      levels.size() < size_t(levels.back() - levels.front() + 1) ? " log" : "");
        return text;
    case TuneScale::Linear: std::snprintf(text, sizeof text, "[%g, %g]%s", low, high, unit.c_str()); return text;
    case TuneScale::Log: std::snprintf(text, sizeof text, "[%g, %g]%s log", low, high, unit.c_str()); return text;
    case TuneScale::ZeroOrLog:
        std::snprintf(text, sizeof text, "0 or [%g, %g]%s log", low, high, unit.c_str());
        return text;
    }
    return "";
}

const char* TunedKey::scale_name() const {
    switch (scale) {
    case TuneScale::Linear: return "linear";
    case TuneScale::Log: return "log";
    case TuneScale::ZeroOrLog: return "zero-or-log";
    case TuneScale::Levels: return "levels";
    }
    return "";
}

std::string settings_spec(const obscura_settings& settings) {
    std::string text = obscura_method_name(settings.method);
    for (const obscura_setting_info& info : changed_rows(settings)) {
        text += std::string(":") + info.name + "=";
        if (samples::is_array(info)) {
            text += samples::format_array_value(samples::array_values(settings, info), info.value_count);
        } else {
            text += spec_value_text(info, user_value(settings, info));
        }
    }
    return text;
}

void normalise_start(obscura_settings* settings) {
    for (const obscura_setting_info& info : setting_infos(settings->method)) {
        if (samples::is_array(info) || samples::derives(*settings, info)) continue;
        double value = 0.0;
        if (obscura_get_setting(settings, info.name, &value) != OBSCURA_OK) continue;
        if (value != samples::stored_value(*settings, info)) obscura_set_setting(settings, info.name, value);
    }
}

// The spec printed should always read back as the settings measured: a check on the formatting above, which
// tune reports rather than trusts.
bool spec_reads_back(const std::string& spec, const obscura_settings& settings) {
    obscura_settings parsed{};
    try {
        parsed = samples::parse_method_spec(spec);
    } catch (const std::exception&) {
        return false;
    }
    for (const obscura_setting_info& info : setting_infos(settings.method)) {
        if (samples::is_array(info)) {
            if (samples::uses_falloff_table(settings) && !same_array(parsed, settings, info)) return false;
        } else if (samples::stored_value(parsed, info) != samples::stored_value(settings, info)) {
            return false;
        }
    }
    return true;
}

void copy_setting(obscura_settings& to, const obscura_settings& from, const obscura_setting_info& info) {
    static_assert(sizeof(float) == sizeof(int32_t), "settings fields are 4 bytes");
    if (samples::is_array(info) || info.offset + sizeof(float) > sizeof(obscura_settings)) {
        throw std::logic_error(std::string("copy_setting: ") + info.name + " is not a single field");
    }
    std::memcpy(reinterpret_cast<unsigned char*>(&to) + info.offset,
                reinterpret_cast<const unsigned char*>(&from) + info.offset, sizeof(float));
}

std::string context_free_error(obscura_status status, const std::string& call) {
    std::string message = call + " failed: " + obscura_status_string(status);
    const char* detail = obscura_get_last_error(nullptr);
    if (detail && *detail) message += std::string(": ") + detail;
    return message;
}

std::optional<obscura_settings> geometry_falloff(const obscura_settings& settings, int rays) {
    obscura_settings reference{};
    if (obscura_reference_settings_for(&settings, &reference) != OBSCURA_OK) return std::nullopt;
    reference.reference.rays = rays;
    reference.reference.first_ray = 0;
    reference.reference.rays_per_dispatch = 0;
    reference.reference.thickness = 0.0f;
    return reference;
}

SearchSpace make_search_space(const MethodSpec& start, const std::optional<std::vector<std::string>>& keys) {
    const std::vector<obscura_setting_info> infos = setting_infos(start.method());
    SearchSpace space;
    if (keys) {
        for (const std::string& name : *keys) {
            const obscura_setting_info* info = samples::find_setting(infos, name);
            if (!info) {
                throw UsageError("--keys: " + std::string(start.name()) + " has no setting '" + name +
                                 "' (its settings: " + setting_names(infos) + ")");
            }
            if (samples::is_array(*info)) {
                throw UsageError("--keys: " + name + " is an array (" + std::to_string(info->value_count) +
                                 " values): tune searches single values; give the table in --method");
            }
            if (const char* why = never_searched_reason(name)) {
                throw UsageError("--keys: " + name + " is not searched: it " + why);
            }
            space.keys.push_back(make_tuned_key(start.settings, *info));
        }
        for (const obscura_setting_info& info : infos) {
            if (std::find(keys->begin(), keys->end(), info.name) == keys->end()) {
                space.left_out.emplace_back(info.name, "not in --keys");
            }
        }
        return space;
    }
    for (const obscura_setting_info& info : infos) {
        if (samples::is_array(info)) {
            space.left_out.emplace_back(info.name, "arrays");
        } else if (const char* why = never_searched_reason(info.name)) {
            space.left_out.emplace_back(info.name, why);
        } else if (samples::is_derived(info)) {
            space.left_out.emplace_back(info.name,
                                        "derived from the searched settings; name them in --keys to fix them");
        } else if (row_changes_falloff(start.settings, info)) {
            space.left_out.emplace_back(info.name,
                                        "they define the falloff the truth weighs with: the target, not the match");
        } else {
            space.keys.push_back(make_tuned_key(start.settings, info));
        }
    }
    if (space.keys.empty()) {
        throw UsageError(std::string(start.name()) + " has no setting tune searches by default: name them with --keys");
    }
    return space;
}

}  // namespace obscura::cli
