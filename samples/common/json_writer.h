// JsonWriter: builds one JSON document (objects, arrays, strings, numbers, booleans, null) in memory,
// indented by two spaces, for the reports the CLI and the tests write.
//
//     JsonWriter json;
//     json.begin_object().field("mean_abs", 0.0012).field("pass", true);
//     json.key("size").begin_array().value(320).value(180).end_array();
//     json.end_object().write_file("report.json");
//
// Strings are UTF-8, escaped as JSON requires (quote, backslash, control characters); a byte that is not
// part of well-formed UTF-8 (a Latin-1 file name, say) is written as U+FFFD, the replacement character.
// Numbers that JSON cannot hold (NaN, +-infinity, e.g. the PSNR of identical images) are written as null; finite
// doubles in the shortest form that reads back to the same double. Misuse (a value in an object
// without a key, a key in an array, an unbalanced end, a second top-level value, str() before the
// document is complete) throws std::logic_error.
#ifndef OBSCURA_SAMPLES_JSON_WRITER_H
#define OBSCURA_SAMPLES_JSON_WRITER_H

#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace obscura::samples {

class JsonWriter {
public:
    JsonWriter& begin_object();
    JsonWriter& end_object();
    JsonWriter& begin_array();
    JsonWriter& end_array();
    // The name of the next member; only directly inside an object.
    JsonWriter& key(std::string_view name);

    JsonWriter& value(std::string_view text);
    JsonWriter& value(const char* text) { return value(std::string_view(text)); }
    JsonWriter& value(const std::string& text) { return value(std::string_view(text)); }
    JsonWriter& value(double number);  // non-finite: null
    JsonWriter& value(bool flag);
    template <class Integer, std::enable_if_t<std::is_integral_v<Integer> && !std::is_same_v<Integer, bool>, int> = 0>
    JsonWriter& value(Integer number) {
        if constexpr (std::is_signed_v<Integer>) return write_integer(static_cast<long long>(number));
        else return write_unsigned(static_cast<unsigned long long>(number));
    }
    JsonWriter& null();

    // key(name) then value(v).
    template <class T>
    JsonWriter& field(std::string_view name, const T& v) {
        key(name);
        return value(v);
    }

    // True once one complete top-level value has been written.
    bool complete() const { return done_; }
    // The document (std::logic_error unless complete()), without a trailing newline.
    const std::string& str() const;
    // Writes str() and a newline; std::runtime_error naming the path when that fails.
    void write_file(const std::string& path) const;

    // `text` as a JSON string literal, quotes included.
    static std::string quote(std::string_view text);

private:
    struct Level {
        bool object = false;
        bool empty = true;      // nothing written inside yet
        bool have_key = false;  // object: a key waits for its value
    };
    // Separator, newline and indentation before a value (or key) at the current level.
    void begin_value(bool is_key);
    void end_value();
    JsonWriter& write_raw_value(std::string_view text);
    JsonWriter& write_integer(long long number);
    JsonWriter& write_unsigned(unsigned long long number);
    JsonWriter& close(bool object);
    void newline_and_indent();

    std::string text_;
    std::vector<Level> levels_;
    bool done_ = false;
};

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_JSON_WRITER_H
