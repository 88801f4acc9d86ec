#include "cli_args.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "cli_errors.h"

namespace obscura::cli {
namespace {

std::string format_bound(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

}  // namespace

bool ArgumentList::take_flag(const std::string& name) {
    bool found = false;
    for (auto it = arguments_.begin(); it != arguments_.end();) {
        if (*it == name) {
            found = true;
            it = arguments_.erase(it);
        } else {
            ++it;
        }
    }
    return found;
}

std::vector<std::string> ArgumentList::take_values(const std::string& name) {
    std::vector<std::string> values;
    const std::string with_equals = name + "=";
    for (size_t i = 0; i < arguments_.size();) {
        if (arguments_[i] == name) {
            if (i + 1 >= arguments_.size()) throw UsageError(name + " needs a value");
            // The next argument is another option when it starts with "--" (a value such as "-1,2,3" does not):
            // taken as the value it went missing itself (`--json --sync-timing` wrote a report named
            // "--sync-timing" and timed without sync). A value that does start with "--" is given as --name=VALUE.
            if (arguments_[i + 1].compare(0, 2, "--") == 0) {
                throw UsageError(name + " needs a value, not the option '" + arguments_[i + 1] + "' (give " + name +
                                 "=VALUE for a value that starts with --)");
            }
            values.push_back(arguments_[i + 1]);
            arguments_.erase(arguments_.begin() + long(i), arguments_.begin() + long(i) + 2);
        } else if (arguments_[i].compare(0, with_equals.size(), with_equals) == 0) {
            values.push_back(arguments_[i].substr(with_equals.size()));
            arguments_.erase(arguments_.begin() + long(i));
        } else {
            ++i;
        }
    }
    return values;
}

std::optional<std::string> ArgumentList::take_value(const std::string& name) {
    std::vector<std::string> values = take_values(name);
    if (values.size() > 1) throw UsageError(name + " given more than once");
    if (values.empty()) return std::nullopt;
    return values.front();
}

std::optional<std::string> ArgumentList::take_optional_value(const std::string& name) {
    std::optional<std::string> found;
    const std::string with_equals = name + "=";
    for (size_t i = 0; i < arguments_.size();) {
        std::optional<std::string> value;
        if (arguments_[i] == name) {
            const bool has_value = i + 1 < arguments_.size() && arguments_[i + 1].compare(0, 2, "--") != 0;
            value = has_value ? arguments_[i + 1] : std::string();
            arguments_.erase(arguments_.begin() + long(i), arguments_.begin() + long(i) + (has_value ? 2 : 1));
        } else if (arguments_[i].compare(0, with_equals.size(), with_equals) == 0) {
            value = arguments_[i].substr(with_equals.size());
            if (value->empty()) throw UsageError(with_equals + " needs a value (or give " + name + " alone)");
            arguments_.erase(arguments_.begin() + long(i));
        } else {
            ++i;
            continue;
        }
        if (found) throw UsageError(name + " given more than once");
        found = std::move(value);
    }
    return found;
}

std::vector<std::string> ArgumentList::take_positionals() {
    std::vector<std::string> positionals;
    for (auto it = arguments_.begin(); it != arguments_.end();) {
        if (it->compare(0, 2, "--") != 0) {
            positionals.push_back(*it);
            it = arguments_.erase(it);
        } else {
            ++it;
        }
    }
    return positionals;
}

bool ArgumentList::contains(const std::string& name) const {
    for (const std::string& argument : arguments_) {
        if (argument == name || argument.compare(0, name.size() + 1, name + "=") == 0) return true;
    }
    return false;
}

void ArgumentList::require_all_taken() const {
    if (!arguments_.empty()) throw UsageError("unknown argument '" + arguments_.front() + "'");
}

ImageFormat image_format_of(const std::string& path) {
    const std::string extension = std::filesystem::path(path).extension().string();
    std::string lower;
    for (char c : extension) lower += char(std::tolower(static_cast<unsigned char>(c)));
    return lower == ".pfm" ? ImageFormat::Pfm : ImageFormat::Png;
}

const std::string& check_image_path(const std::string& option, const std::string& path, ImageFormat format,
                                    const char* other_option) {
    if (image_format_of(path) == format) return path;
    const bool png = format == ImageFormat::Png;
    std::string message = option + " writes " + (png ? "PNG" : "PFM") + ", but '" + path + "' is " +
                          (png ? "named as a PFM file" : "not named .pfm") +
                          " (diff reads a .pfm name as PFM, any other as PNG)";
    if (other_option) message += "; " + std::string(other_option) + " writes " + (png ? "PFM" : "PNG");
    throw UsageError(message);
}

namespace {

// The file `path` names, for telling two names of one file apart ("ao.png" and "./ao.png"): symbolic links resolved
// where the path exists.
std::filesystem::path file_identity(const std::string& path) {
    // Absolute first: weakly_canonical leaves a relative path relative when its first element does not exist
    // ("a.pfm"), and makes it absolute when it does ("./a.pfm").
    const std::filesystem::path absolute = std::filesystem::absolute(path).lexically_normal();
    std::error_code error;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, error);
    return error ? absolute : canonical;
}

}  // namespace

void check_output_files(const std::vector<OutputFile>& outputs) {
    for (size_t i = 0; i < outputs.size(); ++i) {
        for (size_t j = 0; j < i; ++j) {
            if (file_identity(outputs[i].path) == file_identity(outputs[j].path)) {
                throw UsageError(outputs[j].option + " " + outputs[j].path + " and " + outputs[i].option + " " +
                                 outputs[i].path + " name the same file: give each its own");
            }
        }
    }
    for (const OutputFile& output : outputs) {
        std::error_code error;
        const bool existed = std::filesystem::exists(output.path, error);
        std::FILE* probe = std::fopen(output.path.c_str(), "ab");
        if (!probe) throw UsageError(output.option + ": cannot open " + output.path + " for writing");
        std::fclose(probe);
        if (!existed) std::filesystem::remove(output.path, error);
    }
}

void check_output_directory(const std::string& option, const std::string& path) {
    std::error_code error;
    std::filesystem::create_directories(path, error);
    if (error) throw UsageError(option + ": cannot create the directory " + path + " (" + error.message() + ")");
}

std::vector<std::string> split_list(const std::string& option, const std::string& text) {
    std::vector<std::string> items;
    size_t start = 0;
    while (true) {
        const size_t end = text.find(',', start);
        items.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
        if (items.back().empty()) throw UsageError(option + " '" + text + "' has an empty entry");
        if (end == std::string::npos) return items;
        start = end + 1;
    }
}

ImageSize parse_size(const std::string& option, const std::string& text) {
    const size_t separator = text.find('x');
    if (separator == std::string::npos) throw UsageError(option + ": '" + text + "' is not WIDTHxHEIGHT");
    ImageSize size;
    size.width = parse_int(option + " (width)", text.substr(0, separator), 1, 16384);
    size.height = parse_int(option + " (height)", text.substr(separator + 1), 1, 16384);
    return size;
}

int parse_int(const std::string& option, const std::string& text, int min_value, int max_value) {
    // std::from_chars, not strtol: digits with an optional '-' only (no leading spaces, no '+').
    long value = 0;
    const char* const end = text.data() + text.size();
    const std::from_chars_result parsed = std::from_chars(text.data(), end, value);
    if (text.empty() || parsed.ec != std::errc() || parsed.ptr != end || value < min_value || value > max_value) {
        throw UsageError(option + ": '" + text + "' is not an integer in [" + std::to_string(min_value) + ", " +
                         std::to_string(max_value) + "]");
    }
    return int(value);
}

double parse_double(const std::string& option, const std::string& text) {
    // std::from_chars, not strtod: a decimal (or exponent) form with an optional '-' only (no leading spaces, no
    // '+', no hexadecimal floats such as 0x10).
    double value = 0.0;
    const char* const end = text.data() + text.size();
    const std::from_chars_result parsed = std::from_chars(text.data(), end, value);
    if (text.empty() || parsed.ec != std::errc() || parsed.ptr != end || !std::isfinite(value)) {
        throw UsageError(option + ": '" + text + "' is not a number");
    }
    return value;
}

double parse_double_in(const std::string& option, const std::string& text, double min_value, double max_value) {
    const double value = parse_double(option, text);
    if (value < min_value || value > max_value) {
        throw UsageError(option + ": " + text + " is outside [" + format_bound(min_value) + ", " +
                         format_bound(max_value) + "]");
    }
    return value;
}

}  // namespace obscura::cli
