// The samples' JSON reader (samples/common/json_reader.h): RFC 8259 documents accepted, malformed ones
// rejected with the position, escapes and numbers decoded exactly, and JsonWriter output read back.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "json_reader.h"
#include "json_writer.h"

namespace {

using obscura::samples::JsonParseError;
using obscura::samples::JsonValue;
using obscura::samples::parse_json;

std::string nested_arrays(int depth) { return std::string(size_t(depth), '[') + std::string(size_t(depth), ']'); }

TEST(JsonReader, AcceptsValidDocuments) {
    const std::vector<std::string> valid = {
        "{}",
        "[]",
        "0",
        "-0",
        "1.5e-3",
        "\"\"",
        "true",
        "false",
        "null",
        " \t\r\n{ \"a\" : [ 1 , 2 , { \"b\" : null } ] , \"c\" : \"d\" } \n",
        "[1,-1,0.5,1e2,1E+2,1e-2,-0.0,123456789]",
        "{\"\":0}",
        "[[[]],{},\"x\"]",
        "\"\\\"\\\\\\/\\b\\f\\n\\r\\t\\u0041\"",
        "\"caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80\"",  // raw UTF-8 of 2, 3 and 4 bytes
        "\xEF\xBB\xBF{}",                               // a byte order mark is ignored
        "1e-400",                                       // underflows to zero
        nested_arrays(obscura::samples::kMaxJsonDepth),
    };
    for (const std::string& text : valid) {
        EXPECT_NO_THROW(parse_json(text)) << text;
    }
}

TEST(JsonReader, RejectsInvalidDocuments) {
    const std::vector<std::string> invalid = {
        "",
        "   ",
        "{}x",
        "[] []",
        "[1,]",
        "{\"a\":1,}",
        "[,1]",
        "{,}",
        "[1 2]",
        "{\"a\" 1}",
        "{\"a\":}",
        "{a:1}",
        "{'a':1}",
        "{1:2}",
        "[",
        "{",
        "]",
        "{\"a\":1",
        "01",
        "-01",
        "00",
        "1.",
        ".5",
        "+1",
        "1e",
        "1e+",
        "--1",
        "-",
        "0x10",
        "NaN",
        "Infinity",
        "-Infinity",
        "1e400",
        "-1e400",
        "tru",
        "truex",
        "nul",
        "True",
        "\"abc",
        "\"a\tb\"",        // raw control character
        "\"a\nb\"",
        std::string("\"a\0b\"", 5),
        "\"\\x\"",         // unknown escape
        "\"\\u12G4\"",
        "\"\\u123\"",
        "\"\\uD83D\"",     // lone high surrogate
        "\"\\uD83Dx\"",
        "\"\\uD83D\\u0041\"",
        "\"\\uDE00\"",     // lone low surrogate
        "\"\xFF\"",        // invalid UTF-8
        "\"\xC3\"",        // truncated
        "\"\xC0\xAF\"",    // overlong
        "\"\xED\xA0\x80\"",  // encoded surrogate
        "\"\xF4\x90\x80\x80\"",  // above U+10FFFF
        "{\"a\":1,\"a\":2}",  // duplicate key
        "\xEF\xBB\xBF",
        "[1]\x01",
        nested_arrays(obscura::samples::kMaxJsonDepth + 1),
        "{\"a\":" + nested_arrays(obscura::samples::kMaxJsonDepth) + "}",
    };
    for (const std::string& text : invalid) {
        EXPECT_THROW(parse_json(text), JsonParseError) << text;
    }
}

TEST(JsonReader, ErrorMessageSaysWhatWasExpectedAndWhere) {
    try {
        parse_json("{\n  \"a\": tru\n}");
        FAIL() << "no exception";
    } catch (const JsonParseError& error) {
        EXPECT_EQ(error.line(), 2u);
        EXPECT_EQ(error.column(), 11u);  // the 'e' missing after "tru" (found '\n' at column 11)
        EXPECT_NE(std::string(error.what()).find("2:11"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("expected 'true'"), std::string::npos) << error.what();
    }
    try {
        parse_json("[1,\n 2,\n]");
        FAIL() << "no exception";
    } catch (const JsonParseError& error) {
        EXPECT_EQ(error.line(), 3u);
        EXPECT_EQ(error.column(), 1u);
        EXPECT_NE(std::string(error.what()).find("3:1"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("trailing comma"), std::string::npos) << error.what();
    }
    try {
        parse_json("{\"\xC3\xA9\": 1 2}");  // the column counts the two-byte character once
        FAIL() << "no exception";
    } catch (const JsonParseError& error) {
        EXPECT_EQ(error.line(), 1u);
        EXPECT_EQ(error.column(), 9u);
        EXPECT_NE(std::string(error.what()).find("expected ',' or '}'"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("found '2'"), std::string::npos) << error.what();
    }
    // The error is a std::runtime_error.
    EXPECT_THROW(parse_json("[1,]"), std::runtime_error);
}

TEST(JsonReader, DecodesEscapesToUtf8) {
    EXPECT_EQ(parse_json("\"\\\"\\\\\\/\\b\\f\\n\\r\\t\"").as_string(), "\"\\/\b\f\n\r\t");
    EXPECT_EQ(parse_json("\"\\u0041\\u00e9\\u20AC\"").as_string(), "A\xC3\xA9\xE2\x82\xAC");
    EXPECT_EQ(parse_json("\"\\uD83D\\uDE00\"").as_string(), "\xF0\x9F\x98\x80");  // U+1F600
    EXPECT_EQ(parse_json("\"\\uDBFF\\uDFFF\"").as_string(), "\xF4\x8F\xBF\xBF");  // U+10FFFF
    EXPECT_EQ(parse_json("\"\\u0000\"").as_string(), std::string(1, '\0'));
    EXPECT_EQ(parse_json("\"\\u07FF\\u0800\\uFFFF\"").as_string(), "\xDF\xBF\xE0\xA0\x80\xEF\xBF\xBF");
    EXPECT_EQ(parse_json("\"caf\xC3\xA9\"").as_string(), "caf\xC3\xA9");
}

TEST(JsonReader, DecodesNumbersExactly) {
    EXPECT_EQ(parse_json("0").as_number(), 0.0);
    EXPECT_TRUE(std::signbit(parse_json("-0").as_number()));
    EXPECT_EQ(parse_json("0.1").as_number(), 0.1);
    EXPECT_EQ(parse_json("-1.5").as_number(), -1.5);
    EXPECT_EQ(parse_json("1e2").as_number(), 100.0);
    EXPECT_EQ(parse_json("1E+2").as_number(), 100.0);
    EXPECT_EQ(parse_json("25e-2").as_number(), 0.25);
    EXPECT_EQ(parse_json("123456789012").as_number(), 123456789012.0);
    EXPECT_EQ(parse_json("9007199254740993").as_number(), 9007199254740992.0);  // nearest double
    EXPECT_EQ(parse_json("0.30000001192092896").as_number(), double(0.3f));
    EXPECT_EQ(parse_json("1.7976931348623157e308").as_number(), std::numeric_limits<double>::max());
    EXPECT_EQ(parse_json("5e-324").as_number(), std::numeric_limits<double>::denorm_min());
    EXPECT_EQ(parse_json("-1e-400").as_number(), 0.0);
    EXPECT_TRUE(std::signbit(parse_json("-1e-400").as_number()));
}

TEST(JsonReader, KeepsStructureAndOrder) {
    const JsonValue value = parse_json(R"({"z": 1, "a": [true, false, null, "s"], "m": {"k": -2}})");
    ASSERT_TRUE(value.is_object());
    const JsonValue::Object& members = value.members();
    ASSERT_EQ(members.size(), 3u);
    EXPECT_EQ(members[0].first, "z");
    EXPECT_EQ(members[1].first, "a");
    EXPECT_EQ(members[2].first, "m");
    EXPECT_EQ(value.find("z")->as_number(), 1.0);
    EXPECT_EQ(value.find("missing"), nullptr);
    const JsonValue::Array& items = value.find("a")->items();
    ASSERT_EQ(items.size(), 4u);
    EXPECT_TRUE(items[0].is_bool());
    EXPECT_TRUE(items[0].as_bool());
    EXPECT_FALSE(items[1].as_bool());
    EXPECT_TRUE(items[2].is_null());
    EXPECT_EQ(items[3].as_string(), "s");
    EXPECT_EQ(value.find("m")->find("k")->as_number(), -2.0);
    // find() on a non-object, and a wrong-type accessor.
    EXPECT_EQ(items[3].find("k"), nullptr);
    EXPECT_THROW(items[3].as_number(), std::logic_error);
    EXPECT_THROW(value.items(), std::logic_error);
}

TEST(JsonReader, ReadsWhatJsonWriterWrites) {
    obscura::samples::JsonWriter json;
    json.begin_object().field("text", "a \"q\" \\ \n\t\x01 \xE2\x82\xAC").field("third", 1.0 / 3.0);
    json.field("big", -1234567890123LL).field("flag", false);
    json.key("list").begin_array().value(0.1).null().end_array();
    json.key("empty").begin_object().end_object();
    json.end_object();
    const JsonValue value = parse_json(json.str());
    EXPECT_EQ(value.find("text")->as_string(), "a \"q\" \\ \n\t\x01 \xE2\x82\xAC");
    EXPECT_EQ(value.find("third")->as_number(), 1.0 / 3.0);
    EXPECT_EQ(value.find("big")->as_number(), -1234567890123.0);
    EXPECT_FALSE(value.find("flag")->as_bool());
    ASSERT_EQ(value.find("list")->items().size(), 2u);
    EXPECT_EQ(value.find("list")->items()[0].as_number(), 0.1);
    EXPECT_TRUE(value.find("list")->items()[1].is_null());
    EXPECT_TRUE(value.find("empty")->members().empty());
}

}  // namespace
