// Output helpers shared by render, compare and bench: the JSON pieces their reports have in common
// (effective settings, per-pass times) and a plain-text table for the terminal.
#ifndef OBSCURA_CLI_REPORT_H
#define OBSCURA_CLI_REPORT_H

#include <cstdio>
#include <string>
#include <vector>

#include "ao_render.h"
#include "json_writer.h"
#include "obscura/obscura.h"

namespace obscura::cli {

// "settings": {NAME: value, ...}: the effective values (obscura_resolve_settings + obscura_get_setting)
// by metadata name; toggles as true/false, enums as their numbers, arrays (falloff_table) as arrays.
void write_settings_json(samples::JsonWriter& json, const obscura_settings& settings, obscura_context* context = nullptr);
// "gpu_ms": {"total": ms, "passes": {NAME: ms, ...}}: medians of the SDK's per-pass times.
void write_gpu_ms_json(samples::JsonWriter& json, const TimingSummary& timing);

// "12.34" style numbers for tables: `digits` decimals.
std::string format_fixed(double value, int digits);

// Columns padded to their widest cell; the first column left-aligned, the others right-aligned.
class TextTable {
public:
    explicit TextTable(std::vector<std::string> header) { rows_.push_back(std::move(header)); }
    void add_row(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
    void print(std::FILE* out, const std::string& indent = "") const;

private:
    std::vector<std::vector<std::string>> rows_;
};

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_REPORT_H
