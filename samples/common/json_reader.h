// JsonValue and parse_json: a small, strict JSON reader (RFC 8259) for the documents the samples load
// (viewer settings, reports written by JsonWriter).
//
//     JsonValue document = parse_json(text);              // JsonParseError on malformed text
//     if (const JsonValue* radius = document.find("radius"); radius && radius->is_number())
//         use(radius->as_number());
//     for (const JsonValue::Member& member : document.members()) ...  // in document order
//
// Accepted: one value (object, array, string, number, true, false, null) with optional whitespace
// around it, and an optional UTF-8 byte order mark before it (RFC 8259 sec. 8.1 allows ignoring it).
// Strings must be valid UTF-8; escapes (\" \\ \/ \b \f \n \r \t \uXXXX, surrogate pairs included) are
// decoded to UTF-8. Numbers are read as the nearest double.
// Rejected, with a JsonParseError whose message says what was expected and where (line:column, both
// from 1, the column counted in characters): trailing text, trailing commas, leading zeros, unescaped
// control characters, lone surrogates, invalid UTF-8, numbers too large for a double, duplicate keys in
// one object, and nesting of arrays and objects deeper than kMaxJsonDepth.
#ifndef OBSCURA_SAMPLES_JSON_READER_H
#define OBSCURA_SAMPLES_JSON_READER_H

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace obscura::samples {

// Arrays and objects may nest this deep; one more level is an error.
inline constexpr int kMaxJsonDepth = 64;

class JsonValue {
public:
    enum class Type { null, boolean, number, string, array, object };
    using Member = std::pair<std::string, JsonValue>;
    using Array = std::vector<JsonValue>;
    using Object = std::vector<Member>;

    // null.
    JsonValue() = default;
    static JsonValue boolean(bool flag);
    static JsonValue number(double value);
    static JsonValue string(std::string text);
    static JsonValue array(Array items);
    // Members in document order (the reader rejects duplicate keys; find() returns the first).
    static JsonValue object(Object members);

    Type type() const { return type_; }
    bool is_null() const { return type_ == Type::null; }
    bool is_bool() const { return type_ == Type::boolean; }
    bool is_number() const { return type_ == Type::number; }
    bool is_string() const { return type_ == Type::string; }
    bool is_array() const { return type_ == Type::array; }
    bool is_object() const { return type_ == Type::object; }

    // The value of that type; std::logic_error naming both types when this value is of another type.
    bool as_bool() const;
    double as_number() const;
    const std::string& as_string() const;
    const Array& items() const;
    const Object& members() const;

    // The member `key` of an object, or nullptr when there is none (or this is not an object).
    const JsonValue* find(std::string_view key) const;

    // "null", "a boolean", "a number", "a string", "an array", "an object": for messages.
    static const char* type_name(Type type);

private:
    void expect(Type wanted, const char* accessor) const;

    Type type_ = Type::null;
    bool bool_ = false;
    double number_ = 0.0;
    std::string string_;
    Array items_;
    Object members_;
};

// Malformed JSON: what() is "JSON error at LINE:COLUMN: expected ..., found ...".
class JsonParseError : public std::runtime_error {
public:
    JsonParseError(const std::string& message, std::size_t line, std::size_t column)
        : std::runtime_error(message), line_(line), column_(column) {}
    // Where the error is, both from 1.
    std::size_t line() const { return line_; }
    std::size_t column() const { return column_; }

private:
    std::size_t line_;
    std::size_t column_;
};

// Parses one complete JSON document; throws JsonParseError.
JsonValue parse_json(std::string_view text);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_JSON_READER_H
