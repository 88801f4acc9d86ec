// ArgumentList: the arguments of one subcommand, consumed option by option so that whatever is left
// at the end is reported as unknown. Plus the parsers of option values; every one of them throws
// UsageError (exit code 2) with a message that names the option.
#ifndef OBSCURA_CLI_ARGS_H
#define OBSCURA_CLI_ARGS_H

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace obscura::cli {

struct ImageSize {
    int width = 0;
    int height = 0;
};

class ArgumentList {
public:
    explicit ArgumentList(std::vector<std::string> arguments) : arguments_(std::move(arguments)) {}

    // Removes every "--name" and reports whether there was one.
    bool take_flag(const std::string& name);
    // Removes every "--name VALUE" / "--name=VALUE" and returns the values in order. UsageError when "--name" is
    // last or followed by an argument starting with "--" (another option; "-1,2,3" is a value).
    std::vector<std::string> take_values(const std::string& name);
    // The single value of "--name"; UsageError if given more than once.
    std::optional<std::string> take_value(const std::string& name);
    // An option whose value may be left out: removes "--name=VALUE", "--name VALUE" (VALUE being the next
    // argument when it does not start with "--") or a bare "--name". nullopt when absent; otherwise the value,
    // or an empty string for a bare "--name". UsageError if given more than once or as "--name=" (empty).
    std::optional<std::string> take_optional_value(const std::string& name);
    // Removes and returns the arguments that do not start with "--".
    std::vector<std::string> take_positionals();
    // Whether "--name" or "--name=..." is still there (for hints about options of other commands).
    bool contains(const std::string& name) const;
    // Removes and returns every argument left, in order (to hand them to another command).
    std::vector<std::string> take_rest() { return std::exchange(arguments_, {}); }
    // UsageError naming the first argument nobody took.
    void require_all_taken() const;

private:
    std::vector<std::string> arguments_;
};

// The image files the commands write and `diff` reads; `diff` tells them apart by the name alone.
enum class ImageFormat { Png, Pfm };
// Pfm for a name ending in ".pfm" (any case), Png for any other.
ImageFormat image_format_of(const std::string& path);
// `path`, checked as the file `option` writes in `format`: UsageError when its name says the other format (a PNG
// named .pfm, a PFM not named .pfm), so that `diff` reads back what was written. `other_option`, when given: the
// option of the same command that writes the other format, named in the message.
const std::string& check_image_path(const std::string& option, const std::string& path, ImageFormat format,
                                    const char* other_option = nullptr);

// Checks, while the arguments are read, the files a command writes at the end of a long run, so that a wrong name
// costs no minutes of tracing and leaves no half of a set of outputs behind. Each entry: the option and its path.
struct OutputFile {
    std::string option;
    std::string path;
};
// UsageError when two of `outputs` name the same file (one would overwrite the other), or when one cannot be opened
// for writing (a missing directory, no permission). Probing opens the file for appending and removes it again when
// it did not exist; an existing file keeps its contents.
void check_output_files(const std::vector<OutputFile>& outputs);
// UsageError when the directory `path` cannot be created (`option` named in the message); creates it otherwise.
void check_output_directory(const std::string& option, const std::string& path);

// "a,b,c" -> {"a", "b", "c"}; an empty entry (",," or a leading/trailing ',') or an empty text is a
// UsageError naming `option`.
std::vector<std::string> split_list(const std::string& option, const std::string& text);
// "640x360" -> {640, 360}; UsageError otherwise.
ImageSize parse_size(const std::string& option, const std::string& text);
// Decimal digits with an optional '-' ("16", "-2"; not " 16", "+16" or "0x10") in [min_value, max_value].
int parse_int(const std::string& option, const std::string& text, int min_value, int max_value);
// A finite decimal number with an optional '-' and exponent ("0.5", ".5", "-2", "1e+08"; not "+1", " 1" or the
// hexadecimal "0x10").
double parse_double(const std::string& option, const std::string& text);
// A finite number in [min_value, max_value].
double parse_double_in(const std::string& option, const std::string& text, double min_value, double max_value);

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_ARGS_H
