// Status strings, method names and the version query: pure C API, no GL.
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

// Generated from the header's own list, so every code the enum has is covered.
#define OBSCURA_TEST_STATUS_ENTRY(name, value, desc) StatusEntry{OBSCURA_STATUS_##name, #name, desc},
const StatusEntry kStatuses[] = {OBSCURA_STATUS_LIST(OBSCURA_TEST_STATUS_ENTRY)};
#undef OBSCURA_TEST_STATUS_ENTRY

TEST(StatusString, EveryCodeIsCovered) {
    EXPECT_EQ(sizeof kStatuses / sizeof kStatuses[0], size_t(OBSCURA_STATUS_COUNT_));
    for (size_t i = 0; i < sizeof kStatuses / sizeof kStatuses[0]; ++i) EXPECT_EQ(int(kStatuses[i].status), int(i));
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
