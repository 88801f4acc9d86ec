#include "report.h"

#include <algorithm>
#include <cstdlib>

#include "method_spec.h"

namespace obscura::cli {
namespace {

// Float settings are stored as float: report the shortest decimal that is that float (0.3, not
// 0.30000001192092896).
double float_as_decimal(double value) {
    const float stored = float(value);
    char text[32];
    for (int digits = 6; digits <= 9; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, double(stored));
        if (std::strtof(text, nullptr) == stored) break;
    }
    return std::strtod(text, nullptr);
}

}  // namespace

void write_settings_json(samples::JsonWriter& json, const obscura_settings& settings, obscura_context* context) {
    json.key("settings").begin_object();
    for (const EffectiveSetting& setting : effective_settings(settings, context)) {
        if (setting.info.type == OBSCURA_SETTING_TOGGLE) {
            json.field(setting.info.name, setting.value != 0.0);
        } else if (setting.info.type == OBSCURA_SETTING_INT || setting.info.type == OBSCURA_SETTING_ENUM) {
            // Enums by number, as the reports always had them (scripts compare them with spec values).
            json.field(setting.info.name, static_cast<long long>(setting.value));
        } else if (setting.info.type == OBSCURA_SETTING_FLOAT_ARRAY) {
            json.key(setting.info.name).begin_array();
            for (float value : setting.values) json.value(float_as_decimal(value));
            json.end_array();
        } else {
            json.field(setting.info.name, float_as_decimal(setting.value));
        }
    }
    json.end_object();
}

void write_gpu_ms_json(samples::JsonWriter& json, const TimingSummary& timing) {
    json.key("gpu_ms").begin_object();
    json.field("total", timing.sdk_total().median_ms);
    json.key("passes").begin_object();
    for (const TimingRow& row : timing.passes) {
        if (row.label != "total") json.field(row.label, row.median_ms);
    }
    json.end_object();
    json.end_object();
}

std::string format_fixed(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

void TextTable::print(std::FILE* out, const std::string& indent) const {
    std::vector<size_t> widths;
    for (const std::vector<std::string>& row : rows_) {
        widths.resize(std::max(widths.size(), row.size()), 0);
        for (size_t column = 0; column < row.size(); ++column) {
            widths[column] = std::max(widths[column], row[column].size());
        }
    }
    for (const std::vector<std::string>& row : rows_) {
        std::string line = indent;
        for (size_t column = 0; column < row.size(); ++column) {
            const std::string& cell = row[column];
            const std::string padding(widths[column] - cell.size(), ' ');
            if (column > 0) line += "  ";
            line += column == 0 ? cell + (column + 1 < row.size() ? padding : "") : padding + cell;
        }
        std::fprintf(out, "%s\n", line.c_str());
    }
}

}  // namespace obscura::cli
