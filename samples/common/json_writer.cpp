#include "json_writer.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace obscura::samples {
namespace {

// The length of the well-formed UTF-8 sequence (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF)
// that starts at text[at], 1 to 4; 0 when the bytes there are not one.
size_t utf8_sequence_length(std::string_view text, size_t at) {
    const auto byte = [&](size_t k) {
        return at + k < text.size() ? unsigned(static_cast<unsigned char>(text[at + k])) : 0u;  // 0: past the end
    };
    const unsigned lead = byte(0);
    if (lead < 0x80) return 1;
    size_t length = 0;
    unsigned second_min = 0x80, second_max = 0xBF;  // the second byte's range, narrower after some leads
    if (lead >= 0xC2 && lead <= 0xDF) {
        length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        length = 3;
        if (lead == 0xE0) second_min = 0xA0;  // below: overlong
        if (lead == 0xED) second_max = 0x9F;  // above: surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        length = 4;
        if (lead == 0xF0) second_min = 0x90;  // below: overlong
        if (lead == 0xF4) second_max = 0x8F;  // above: beyond U+10FFFF
    } else {
        return 0;  // a continuation byte, an overlong lead (C0, C1) or F5-FF
    }
    if (byte(1) < second_min || byte(1) > second_max) return 0;
    for (size_t k = 2; k < length; ++k) {
        if (byte(k) < 0x80 || byte(k) > 0xBF) return 0;
    }
    return length;
}

}  // namespace

std::string JsonWriter::quote(std::string_view text) {
    std::string quoted;
    quoted.reserve(text.size() + 2);
    quoted += '"';
    for (size_t at = 0; at < text.size();) {
        // JSON text is UTF-8: a byte that does not begin a well-formed sequence (a Latin-1 file name, say) becomes
        // U+FFFD, the replacement character, and the text goes on after it.
        if (static_cast<unsigned char>(text[at]) >= 0x80) {
            const size_t length = utf8_sequence_length(text, at);
            if (length == 0) {
                quoted += "\xEF\xBF\xBD";
                ++at;
            } else {
                quoted.append(text.substr(at, length));
                at += length;
            }
            continue;
        }
        const char character = text[at++];
        switch (character) {
            case '"': quoted += "\\\""; break;
            case '\\': quoted += "\\\\"; break;
            case '\b': quoted += "\\b"; break;
            case '\f': quoted += "\\f"; break;
            case '\n': quoted += "\\n"; break;
            case '\r': quoted += "\\r"; break;
            case '\t': quoted += "\\t"; break;
            default:
                if (static_cast<unsigned char>(character) < 0x20) {
                    char escape[8];
                    std::snprintf(escape, sizeof escape, "\\u%04x", unsigned(static_cast<unsigned char>(character)));
                    quoted += escape;
                } else {
                    quoted += character;  // printable ASCII
                }
        }
    }
    quoted += '"';
    return quoted;
}

void JsonWriter::newline_and_indent() {
    text_ += '\n';
    text_.append(2 * levels_.size(), ' ');
}

void JsonWriter::begin_value(bool is_key) {
    if (done_) throw std::logic_error("JsonWriter: the document already has its top-level value");
    if (levels_.empty()) {
        if (is_key) throw std::logic_error("JsonWriter: key outside an object");
        return;
    }
    Level& level = levels_.back();
    if (level.object) {
        if (is_key) {
            if (level.have_key) throw std::logic_error("JsonWriter: two keys without a value between them");
        } else {
            if (!level.have_key) throw std::logic_error("JsonWriter: a value inside an object needs a key first");
            return;  // the value follows its key on the same line
        }
    } else if (is_key) {
        throw std::logic_error("JsonWriter: key inside an array");
    }
    if (!level.empty) text_ += ',';
    newline_and_indent();
}

void JsonWriter::end_value() {
    if (levels_.empty()) {
        done_ = true;
        return;
    }
    levels_.back().empty = false;
    levels_.back().have_key = false;
}

JsonWriter& JsonWriter::begin_object() {
    begin_value(false);
    text_ += '{';
    levels_.emplace_back();
    levels_.back().object = true;
    return *this;
}

JsonWriter& JsonWriter::begin_array() {
    begin_value(false);
    text_ += '[';
    levels_.emplace_back();
    return *this;
}

JsonWriter& JsonWriter::close(bool object) {
    if (levels_.empty() || levels_.back().object != object) {
        throw std::logic_error(object ? "JsonWriter: end_object without a matching begin_object"
                                      : "JsonWriter: end_array without a matching begin_array");
    }
    if (levels_.back().have_key) throw std::logic_error("JsonWriter: key without a value at the end of an object");
    const bool empty = levels_.back().empty;
    levels_.pop_back();
    if (!empty) newline_and_indent();
    text_ += object ? '}' : ']';
    end_value();
    return *this;
}

JsonWriter& JsonWriter::end_object() { return close(true); }
JsonWriter& JsonWriter::end_array() { return close(false); }

JsonWriter& JsonWriter::key(std::string_view name) {
    begin_value(true);
    text_ += quote(name);
    text_ += ": ";
    levels_.back().have_key = true;
    levels_.back().empty = false;
    return *this;
}

JsonWriter& JsonWriter::write_raw_value(std::string_view text) {
    begin_value(false);
    text_ += text;
    end_value();
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view text) { return write_raw_value(quote(text)); }

JsonWriter& JsonWriter::value(double number) {
    if (!std::isfinite(number)) return null();
    char digits[64];
    const std::to_chars_result result = std::to_chars(digits, digits + sizeof digits, number);
    return write_raw_value(std::string_view(digits, size_t(result.ptr - digits)));
}

JsonWriter& JsonWriter::value(bool flag) { return write_raw_value(flag ? "true" : "false"); }

JsonWriter& JsonWriter::write_integer(long long number) { return write_raw_value(std::to_string(number)); }

JsonWriter& JsonWriter::write_unsigned(unsigned long long number) { return write_raw_value(std::to_string(number)); }

JsonWriter& JsonWriter::null() { return write_raw_value("null"); }

const std::string& JsonWriter::str() const {
    if (!done_) throw std::logic_error("JsonWriter: the document is not complete");
    return text_;
}

void JsonWriter::write_file(const std::string& path) const {
    const std::string& document = str();
    std::ofstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot open '" + path + "' for writing");
    file << document << '\n';
    file.flush();
    if (!file) throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace obscura::samples
