#include "json_reader.h"

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <set>
#include <system_error>

namespace obscura::samples {

// ---- JsonValue -----------------------------------------------------------------------------------

JsonValue JsonValue::boolean(bool flag) {
    JsonValue value;
    value.type_ = Type::boolean;
    value.bool_ = flag;
    return value;
}

JsonValue JsonValue::number(double number) {
    JsonValue value;
    value.type_ = Type::number;
    value.number_ = number;
    return value;
}

JsonValue JsonValue::string(std::string text) {
    JsonValue value;
    value.type_ = Type::string;
    value.string_ = std::move(text);
    return value;
}

JsonValue JsonValue::array(Array items) {
    JsonValue value;
    value.type_ = Type::array;
    value.items_ = std::move(items);
    return value;
}

JsonValue JsonValue::object(Object members) {
    JsonValue value;
    value.type_ = Type::object;
    value.members_ = std::move(members);
    return value;
}

const char* JsonValue::type_name(Type type) {
    switch (type) {
        case Type::null: return "null";
        case Type::boolean: return "a boolean";
        case Type::number: return "a number";
        case Type::string: return "a string";
        case Type::array: return "an array";
        case Type::object: return "an object";
    }
    return "an unknown type";
}

void JsonValue::expect(Type wanted, const char* accessor) const {
    if (type_ != wanted) {
        throw std::logic_error(std::string("JsonValue::") + accessor + ": the value is " + type_name(type_) +
                               ", not " + type_name(wanted));
    }
}

bool JsonValue::as_bool() const {
    expect(Type::boolean, "as_bool");
    return bool_;
}

double JsonValue::as_number() const {
    expect(Type::number, "as_number");
    return number_;
}

const std::string& JsonValue::as_string() const {
    expect(Type::string, "as_string");
    return string_;
}

const JsonValue::Array& JsonValue::items() const {
    expect(Type::array, "items");
    return items_;
}

const JsonValue::Object& JsonValue::members() const {
    expect(Type::object, "members");
    return members_;
}

const JsonValue* JsonValue::find(std::string_view key) const {
    if (type_ != Type::object) return nullptr;
    for (const Member& member : members_) {
        if (member.first == key) return &member.second;
    }
    return nullptr;
}

// ---- The parser ----------------------------------------------------------------------------------

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

void append_utf8(std::string& out, uint32_t code_point) {
    if (code_point < 0x80) {
        out += char(code_point);
    } else if (code_point < 0x800) {
        out += char(0xC0 | (code_point >> 6));
        out += char(0x80 | (code_point & 0x3F));
    } else if (code_point < 0x10000) {
        out += char(0xE0 | (code_point >> 12));
        out += char(0x80 | ((code_point >> 6) & 0x3F));
        out += char(0x80 | (code_point & 0x3F));
    } else {
        out += char(0xF0 | (code_point >> 18));
        out += char(0x80 | ((code_point >> 12) & 0x3F));
        out += char(0x80 | ((code_point >> 6) & 0x3F));
        out += char(0x80 | (code_point & 0x3F));
    }
}

class Parser {
public:
    explicit Parser(std::string_view text) : text_(text) {}

    JsonValue document() {
        // A UTF-8 byte order mark may be ignored (RFC 8259 sec. 8.1).
        if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
        skip_whitespace();
        if (at_end()) fail("expected a JSON value", pos_);
        JsonValue root = value(0);
        skip_whitespace();
        if (!at_end()) fail("expected the end of the document after the top-level value", pos_);
        return root;
    }

private:
    bool at_end() const { return pos_ >= text_.size(); }
    char peek() const { return at_end() ? '\0' : text_[pos_]; }
    unsigned char byte_at(size_t at) const { return static_cast<unsigned char>(text_[at]); }

    // What stands at `at`, for messages: 'x', "the end of the text", "U+000A" ...
    std::string describe(size_t at) const {
        if (at >= text_.size()) return "the end of the text";
        const unsigned char c = byte_at(at);
        char buffer[32];
        if (c < 0x20 || c == 0x7F) {
            std::snprintf(buffer, sizeof buffer, "control character U+%04X", unsigned(c));
        } else if (c >= 0x80) {
            std::snprintf(buffer, sizeof buffer, "byte 0x%02X", unsigned(c));
        } else {
            std::snprintf(buffer, sizeof buffer, "'%c'", char(c));
        }
        return buffer;
    }

    // Throws JsonParseError: "JSON error at L:C: <expected>, found <what is at `at`>".
    [[noreturn]] void fail(const std::string& expected, size_t at) const {
        size_t line = 1, column = 1;
        for (size_t i = 0; i < at && i < text_.size(); ++i) {
            const unsigned char c = byte_at(i);
            if (c == '\n') {
                ++line;
                column = 1;
            } else if ((c & 0xC0) != 0x80) {  // UTF-8 continuation bytes do not start a character
                ++column;
            }
        }
        throw JsonParseError("JSON error at " + std::to_string(line) + ":" + std::to_string(column) + ": " +
                                 expected + ", found " + describe(at),
                             line, column);
    }

    void skip_whitespace() {
        while (!at_end()) {
            const char c = text_[pos_];
            if (c != ' ' && c != '\t' && c != '\n' && c != '\r') break;
            ++pos_;
        }
    }

    JsonValue value(int depth) {
        switch (peek()) {
            case '{': return object(depth + 1);
            case '[': return array(depth + 1);
            case '"': return JsonValue::string(string());
            case 't': literal("true"); return JsonValue::boolean(true);
            case 'f': literal("false"); return JsonValue::boolean(false);
            case 'n': literal("null"); return JsonValue();
            default:
                if (peek() == '-' || is_digit(peek())) return JsonValue::number(number());
                fail("expected a JSON value (object, array, string, number, true, false or null)", pos_);
        }
    }

    void check_depth(int depth) const {
        if (depth > kMaxJsonDepth) {
            fail("expected at most " + std::to_string(kMaxJsonDepth) + " levels of nested arrays and objects",
                 pos_);
        }
    }

    void literal(std::string_view word) {
        for (size_t i = 0; i < word.size(); ++i) {
            if (pos_ + i >= text_.size() || text_[pos_ + i] != word[i]) {
                fail("expected '" + std::string(word) + "'", pos_ + i);
            }
        }
        pos_ += word.size();
    }

    JsonValue object(int depth) {
        check_depth(depth);
        ++pos_;  // '{'
        JsonValue::Object members;
        std::set<std::string> keys;
        skip_whitespace();
        if (peek() == '}') {
            ++pos_;
            return JsonValue::object(std::move(members));
        }
        for (;;) {
            skip_whitespace();
            if (peek() != '"') {
                fail(members.empty() ? "expected a string key or '}'"
                                     : "expected a string key after ',' (a trailing comma is not JSON)",
                     pos_);
            }
            const size_t key_at = pos_;
            std::string key = string();
            if (!keys.insert(key).second) fail("expected a key not used before in this object", key_at);
            skip_whitespace();
            if (peek() != ':') fail("expected ':' after the key", pos_);
            ++pos_;
            skip_whitespace();
            JsonValue member = value(depth);
            members.emplace_back(std::move(key), std::move(member));
            skip_whitespace();
            if (peek() == ',') {
                ++pos_;
                continue;
            }
            if (peek() == '}') {
                ++pos_;
                return JsonValue::object(std::move(members));
            }
            fail("expected ',' or '}' after an object member", pos_);
        }
    }

    JsonValue array(int depth) {
        check_depth(depth);
        ++pos_;  // '['
        JsonValue::Array items;
        skip_whitespace();
        if (peek() == ']') {
            ++pos_;
            return JsonValue::array(std::move(items));
        }
        for (;;) {
            skip_whitespace();
            if (!items.empty() && peek() == ']') {
                fail("expected a value after ',' (a trailing comma is not JSON)", pos_);
            }
            items.push_back(value(depth));
            skip_whitespace();
            if (peek() == ',') {
                ++pos_;
                continue;
            }
            if (peek() == ']') {
                ++pos_;
                return JsonValue::array(std::move(items));
            }
            fail("expected ',' or ']' after an array item", pos_);
        }
    }

    // Four hex digits after "\u".
    uint32_t hex4() {
        uint32_t code = 0;
        for (int i = 0; i < 4; ++i) {
            const char c = peek();
            uint32_t digit;
            if (c >= '0' && c <= '9') digit = uint32_t(c - '0');
            else if (c >= 'a' && c <= 'f') digit = uint32_t(c - 'a' + 10);
            else if (c >= 'A' && c <= 'F') digit = uint32_t(c - 'A' + 10);
            else fail("expected four hex digits after \\u", pos_);
            code = code * 16 + digit;
            ++pos_;
        }
        return code;
    }

    void escape(std::string& out) {
        const size_t backslash = pos_;
        ++pos_;  // '\'
        const char c = peek();
        ++pos_;
        switch (c) {
            case '"': out += '"'; return;
            case '\\': out += '\\'; return;
            case '/': out += '/'; return;
            case 'b': out += '\b'; return;
            case 'f': out += '\f'; return;
            case 'n': out += '\n'; return;
            case 'r': out += '\r'; return;
            case 't': out += '\t'; return;
            case 'u': break;
            default:
                fail("expected an escape (\\\" \\\\ \\/ \\b \\f \\n \\r \\t or \\uXXXX) after '\\'", backslash + 1);
        }
        uint32_t code = hex4();
        if (code >= 0xDC00 && code <= 0xDFFF) {
            fail("expected a high surrogate (\\uD800-\\uDBFF) before a low surrogate", backslash);
        }
        if (code >= 0xD800 && code <= 0xDBFF) {
            const size_t low_at = pos_;
            if (text_.substr(pos_, 2) != "\\u") {
                fail("expected a low surrogate (\\uDC00-\\uDFFF) after the high surrogate", low_at);
            }
            pos_ += 2;
            const uint32_t low = hex4();
            if (low < 0xDC00 || low > 0xDFFF) {
                fail("expected a low surrogate (\\uDC00-\\uDFFF) after the high surrogate", low_at);
            }
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
        }
        append_utf8(out, code);
    }

    // One UTF-8 encoded character of two to four bytes, checked (no overlong forms, no surrogates, at most
    // U+10FFFF) and copied.
    void utf8_character(std::string& out) {
        const size_t start = pos_;
        const unsigned char lead = byte_at(pos_);
        size_t length = 0;
        unsigned char second_min = 0x80, second_max = 0xBF;
        if (lead >= 0xC2 && lead <= 0xDF) {
            length = 2;
        } else if (lead >= 0xE0 && lead <= 0xEF) {
            length = 3;
            if (lead == 0xE0) second_min = 0xA0;
            if (lead == 0xED) second_max = 0x9F;
        } else if (lead >= 0xF0 && lead <= 0xF4) {
            length = 4;
            if (lead == 0xF0) second_min = 0x90;
            if (lead == 0xF4) second_max = 0x8F;
        } else {
            fail("expected valid UTF-8", start);
        }
        for (size_t i = 1; i < length; ++i) {
            if (start + i >= text_.size()) fail("expected valid UTF-8", start);
            const unsigned char c = byte_at(start + i);
            const unsigned char low = i == 1 ? second_min : 0x80, high = i == 1 ? second_max : 0xBF;
            if (c < low || c > high) fail("expected valid UTF-8", start);
        }
        out.append(text_.substr(start, length));
        pos_ += length;
    }

    std::string string() {
        ++pos_;  // '"'
        std::string out;
        for (;;) {
            if (at_end()) fail("expected '\"' to close the string", pos_);
            const unsigned char c = byte_at(pos_);
            if (c == '"') {
                ++pos_;
                return out;
            }
            if (c == '\\') {
                escape(out);
            } else if (c < 0x20) {
                fail("expected a character or an escape in the string (control characters must be escaped)", pos_);
            } else if (c >= 0x80) {
                utf8_character(out);
            } else {
                out += char(c);
                ++pos_;
            }
        }
    }

    // RFC 8259 sec. 6: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
    double number() {
        const size_t start = pos_;
        const bool negative = peek() == '-';
        if (negative) ++pos_;
        const size_t integer_start = pos_;
        if (peek() == '0') {
            ++pos_;
            if (is_digit(peek())) fail("expected '.', 'e' or the end of the number after 0 (no leading zeros)", pos_);
        } else if (is_digit(peek())) {
            while (is_digit(peek())) ++pos_;
        } else {
            fail("expected a digit", pos_);
        }
        const size_t integer_end = pos_;
        size_t fraction_start = pos_, fraction_end = pos_;
        if (peek() == '.') {
            ++pos_;
            if (!is_digit(peek())) fail("expected a digit after '.'", pos_);
            fraction_start = pos_;
            while (is_digit(peek())) ++pos_;
            fraction_end = pos_;
        }
        long long exponent = 0;
        if (peek() == 'e' || peek() == 'E') {
            ++pos_;
            bool exponent_negative = false;
            if (peek() == '+' || peek() == '-') exponent_negative = text_[pos_++] == '-';
            if (!is_digit(peek())) fail("expected a digit in the exponent", pos_);
            while (is_digit(peek())) {
                if (exponent < 1000000000) exponent = exponent * 10 + (text_[pos_] - '0');
                ++pos_;
            }
            if (exponent_negative) exponent = -exponent;
        }
        double result = 0.0;
        const std::from_chars_result parsed = std::from_chars(text_.data() + start, text_.data() + pos_, result);
        if (parsed.ec == std::errc::result_out_of_range) {
            // Too large or too small for a double: the decimal exponent of the first significant digit says which.
            long long magnitude;
            if (text_[integer_start] != '0') {
                magnitude = (long long)(integer_end - integer_start) - 1 + exponent;
            } else {
                size_t first = fraction_start;
                while (first < fraction_end && text_[first] == '0') ++first;
                magnitude = -(long long)(first - fraction_start) - 1 + exponent;
            }
            if (magnitude >= 0) fail("expected a number within the range of a double", start);
            result = negative ? -0.0 : 0.0;  // underflow: rounds to zero
        } else if (parsed.ec != std::errc() || parsed.ptr != text_.data() + pos_) {
            fail("expected a number", start);
        }
        return result;
    }

    std::string_view text_;
    size_t pos_ = 0;
};

}  // namespace

JsonValue parse_json(std::string_view text) { return Parser(text).document(); }

}  // namespace obscura::samples
