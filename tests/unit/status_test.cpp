// Status strings, method names and the version query: pure C API, no GL.
#include <cstdint>
#include <cstring>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "obscura/obscura.h"

namespace {

struct StatusEntry {
    obscura_status status;
    const char* name;
    const char* description;
};

// Generated from the header's own list (for the descriptions); EveryCodeIsCovered checks the codes against a
// table written out by hand.
#define OBSCURA_TEST_STATUS_ENTRY(name, value, desc) StatusEntry{OBSCURA_STATUS_##name, #name, desc},
const StatusEntry kStatuses[] = {OBSCURA_STATUS_LIST(OBSCURA_TEST_STATUS_ENTRY)};
#undef OBSCURA_TEST_STATUS_ENTRY

// Written out by hand, independently of OBSCURA_STATUS_LIST: the codes are ABI, so a renumbered, renamed or
// dropped code fails here, and a new code fails until it gets an entry (OBSCURA_STATUS_COUNT_ is checked).
struct ExpectedStatus {
    obscura_status status;
    int value;
    const char* name;
};
const ExpectedStatus kExpectedStatuses[] = {
    {OBSCURA_STATUS_OK, 0, "OK"},
    {OBSCURA_STATUS_NULL_ARGUMENT, 1, "NULL_ARGUMENT"},
    {OBSCURA_STATUS_INVALID_STRUCT_SIZE, 2, "INVALID_STRUCT_SIZE"},
    {OBSCURA_STATUS_VERSION_MISMATCH, 3, "VERSION_MISMATCH"},
    {OBSCURA_STATUS_NO_GL_CONTEXT, 4, "NO_GL_CONTEXT"},
    {OBSCURA_STATUS_GL_VERSION_UNSUPPORTED, 5, "GL_VERSION_UNSUPPORTED"},
    {OBSCURA_STATUS_MISSING_GL_FUNCTION, 6, "MISSING_GL_FUNCTION"},
    {OBSCURA_STATUS_WRONG_GL_CONTEXT, 7, "WRONG_GL_CONTEXT"},
    {OBSCURA_STATUS_INVALID_SIZE, 8, "INVALID_SIZE"},
    {OBSCURA_STATUS_INVALID_RECT, 9, "INVALID_RECT"},
    {OBSCURA_STATUS_INVALID_TEXTURE, 10, "INVALID_TEXTURE"},
    {OBSCURA_STATUS_UNSUPPORTED_FORMAT, 11, "UNSUPPORTED_FORMAT"},
    {OBSCURA_STATUS_INVALID_PROJECTION, 12, "INVALID_PROJECTION"},
    {OBSCURA_STATUS_PROJECTION_TRANSPOSED, 13, "PROJECTION_TRANSPOSED"},
    {OBSCURA_STATUS_INVALID_SETTING, 14, "INVALID_SETTING"},
    {OBSCURA_STATUS_INVALID_ENUM, 15, "INVALID_ENUM"},
    {OBSCURA_STATUS_METHOD_NOT_AVAILABLE, 16, "METHOD_NOT_AVAILABLE"},
    {OBSCURA_STATUS_INVALID_FRAMEBUFFER, 17, "INVALID_FRAMEBUFFER"},
    {OBSCURA_STATUS_SHADER_COMPILE_FAILED, 18, "SHADER_COMPILE_FAILED"},
    {OBSCURA_STATUS_OUT_OF_MEMORY, 19, "OUT_OF_MEMORY"},
    {OBSCURA_STATUS_HOST_GL_ERROR, 20, "HOST_GL_ERROR"},
    {OBSCURA_STATUS_GL_ERROR, 21, "GL_ERROR"},
    {OBSCURA_STATUS_UNKNOWN_SETTING, 22, "UNKNOWN_SETTING"},
    {OBSCURA_STATUS_INTERNAL_ERROR, 23, "INTERNAL_ERROR"},
    {OBSCURA_STATUS_CONTEXT_LOST, 24, "CONTEXT_LOST"},
    {OBSCURA_STATUS_INVALID_VIEW, 25, "INVALID_VIEW"},
};

// Any int as a status, as a C caller may pass it (raw_enum_calls.c): no out-of-range value of the C++ enum is
// ever formed here.
extern "C" const char* obscura_test_status_string_raw(int value);

TEST(StatusString, EveryCodeIsCovered) {
    const size_t expected_count = sizeof kExpectedStatuses / sizeof kExpectedStatuses[0];
    EXPECT_EQ(size_t(OBSCURA_STATUS_COUNT_), expected_count)
        << "a status code was added or removed: update this table (the values are ABI)";
    const std::string unknown = "OBSCURA_STATUS_?: unknown status code";  // the fixed string for unknown codes
    for (const ExpectedStatus& entry : kExpectedStatuses) {
        EXPECT_EQ(int(entry.status), entry.value) << entry.name;
        const char* text = obscura_test_status_string_raw(entry.value);
        ASSERT_NE(text, nullptr) << entry.name;
        const std::string prefix = std::string("OBSCURA_STATUS_") + entry.name + ": ";
        EXPECT_EQ(std::string(text).rfind(prefix, 0), 0u) << "code " << entry.value << ": \"" << text << "\"";
        EXPECT_GT(std::strlen(text), prefix.size()) << entry.name << " has no description";
        EXPECT_NE(std::string(text), unknown) << entry.name;
    }
    // Out of range, on either side and just past the last code: the one fixed unknown string.
    EXPECT_EQ(std::string(obscura_status_string(OBSCURA_STATUS_COUNT_)), unknown);
    EXPECT_EQ(std::string(obscura_test_status_string_raw(int(expected_count))), unknown);
    EXPECT_EQ(std::string(obscura_test_status_string_raw(-1)), unknown);
    EXPECT_EQ(std::string(obscura_test_status_string_raw(1000)), unknown);
    EXPECT_EQ(obscura_test_status_string_raw(int(expected_count)), obscura_test_status_string_raw(-1))
        << "the unknown string is one fixed string";
}

TEST(StatusString, NameAndDescriptionForEveryCode) {
    for (const StatusEntry& entry : kStatuses) {
        const char* text = obscura_status_string(entry.status);
        ASSERT_NE(text, nullptr) << entry.name;
        const std::string expected = std::string("OBSCURA_STATUS_") + entry.name + ": " + entry.description;
        EXPECT_EQ(std::string(text), expected);
    }
}

TEST(StatusString, NonEmptyWithPrefix) {
    for (const StatusEntry& entry : kStatuses) {
        const std::string text = obscura_status_string(entry.status);
        EXPECT_GT(text.size(), std::strlen("OBSCURA_STATUS_")) << entry.name;
        EXPECT_EQ(text.rfind("OBSCURA_STATUS_", 0), 0u) << text;
    }
}

TEST(StatusString, Unique) {
    std::set<std::string> seen;
    for (const StatusEntry& entry : kStatuses) {
        EXPECT_TRUE(seen.insert(obscura_status_string(entry.status)).second) << entry.name;
    }
}

TEST(StatusString, UnknownCodeGivesFixedString) {
    const char* unknown = obscura_status_string(OBSCURA_STATUS_COUNT_);
    ASSERT_NE(unknown, nullptr);
    EXPECT_GT(std::strlen(unknown), 0u);
    EXPECT_EQ(std::string(unknown).rfind("OBSCURA_STATUS_", 0), 0u);
    EXPECT_STREQ(obscura_status_string(obscura_status(-1)), unknown);
    EXPECT_STREQ(obscura_status_string(obscura_status(1000)), unknown);
    for (const StatusEntry& entry : kStatuses) EXPECT_STRNE(obscura_status_string(entry.status), unknown);
}

TEST(StatusString, OkAliasIsZero) {
    EXPECT_EQ(OBSCURA_OK, OBSCURA_STATUS_OK);
    EXPECT_EQ(int(OBSCURA_OK), 0);
}

TEST(Version, LinkedMatchesHeader) {
    EXPECT_EQ(obscura_version(), uint32_t(OBSCURA_VERSION));
    EXPECT_EQ(uint32_t(OBSCURA_VERSION),
              uint32_t(OBSCURA_VERSION_MAJOR * 10000 + OBSCURA_VERSION_MINOR * 100 + OBSCURA_VERSION_PATCH));
}

TEST(MethodName, KnownMethods) {
    EXPECT_STREQ(obscura_method_name(OBSCURA_METHOD_HBAO), "hbao");
    EXPECT_STREQ(obscura_method_name(OBSCURA_METHOD_SAO), "sao");
    EXPECT_STREQ(obscura_method_name(OBSCURA_METHOD_LSAO), "lsao");
    EXPECT_STREQ(obscura_method_name(OBSCURA_METHOD_FFAO), "ffao");
    EXPECT_STREQ(obscura_method_name(OBSCURA_METHOD_REFERENCE), "reference");
    EXPECT_STREQ(obscura_method_name(OBSCURA_METHOD_DEFAULT), "hbao");  // DEFAULT is HBAO
}

TEST(MethodName, UnknownIsNull) {
    EXPECT_EQ(obscura_method_name(OBSCURA_METHOD_COUNT_), nullptr);
    EXPECT_EQ(obscura_method_name(obscura_method(-1)), nullptr);
}

TEST(MethodAvailable, EveryMethod) {
    EXPECT_EQ(obscura_method_available(OBSCURA_METHOD_DEFAULT), 1);
    EXPECT_EQ(obscura_method_available(OBSCURA_METHOD_HBAO), 1);
    EXPECT_EQ(obscura_method_available(OBSCURA_METHOD_SAO), 1);
    EXPECT_EQ(obscura_method_available(OBSCURA_METHOD_LSAO), 1);
    EXPECT_EQ(obscura_method_available(OBSCURA_METHOD_FFAO), 1);
    EXPECT_EQ(obscura_method_available(OBSCURA_METHOD_REFERENCE), 1);
    EXPECT_EQ(obscura_method_available(obscura_method(99)), 0);
}

// Calls that need no GL context still answer NULL handles.
TEST(NullContext, QueriesRejectNull) {
    uint64_t bytes = 0;
    uint32_t count = 0;
    obscura_timing timing[2];
    EXPECT_EQ(obscura_get_memory_usage(nullptr, &bytes), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_get_timings(nullptr, timing, 2, &count, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_render(nullptr, nullptr, nullptr, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(obscura_prepare(nullptr, 16, 16, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    const char* message = obscura_get_last_error(nullptr);
    ASSERT_NE(message, nullptr);
    EXPECT_GT(std::strlen(message), 0u);
    obscura_destroy_context(nullptr);       // documented no-op
    obscura_release_resources(nullptr);     // must not crash
}

TEST(NullContext, CreateRejectsNullArguments) {
    obscura_context* context = reinterpret_cast<obscura_context*>(0x1);
    EXPECT_EQ(obscura_create_context(nullptr, &context), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(context, nullptr);  // cleared on failure
    obscura_context_desc desc;
    std::memset(&desc, 0, sizeof desc);
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    EXPECT_EQ(obscura_create_context(&desc, nullptr), OBSCURA_STATUS_NULL_ARGUMENT);
    // get_proc_address is required.
    EXPECT_EQ(obscura_create_context(&desc, &context), OBSCURA_STATUS_NULL_ARGUMENT);
}

}  // namespace
