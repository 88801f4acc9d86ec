// Shared by the libFuzzer targets: a reader that turns the input bytes into values (zeros once the input is
// used up, so every input, even an empty one, is a complete test case), the failure report, and the C
// shims (raw_enum_calls.c) that pass arbitrary ints where the API takes an enum.
#ifndef OBSCURA_TESTS_FUZZ_SUPPORT_H
#define OBSCURA_TESTS_FUZZ_SUPPORT_H

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "obscura/obscura.h"

// A C host may pass any int where the API takes an enum. Forming such a value in C++ is undefined (and
// -fsanitize=enum reports the load), so these calls go through a C file, exactly as a C host makes them.
extern "C" {
const char* fuzz_status_string(int32_t status);
const char* fuzz_method_name(int32_t method);
int fuzz_method_available(int32_t method);
int32_t fuzz_default_settings(int32_t method, obscura_settings* out);
int32_t fuzz_get_setting_infos(int32_t method, const obscura_setting_info** out_infos, uint32_t* out_count);
}

namespace obscura_fuzz {

// Prints "<target>: <message>" and the context the target registered, then traps: libFuzzer reports a
// crash and writes the input to the artifact prefix.
[[noreturn]] void fail(const char* format, ...) __attribute__((format(printf, 1, 2)));
// Extra lines printed by fail() (the operation being checked); the target keeps it up to date.
void set_failure_context(const std::string& context);

#define FUZZ_CHECK(condition, ...)                     \
    do {                                               \
        if (!(condition)) ::obscura_fuzz::fail(__VA_ARGS__); \
    } while (0)

// An API status as the int it holds (never loaded through the enum type: an out-of-range value would be a
// finding of its own, reported by the range check rather than by -fsanitize=enum in this code).
inline int32_t status_code(const obscura_status& status) {
    int32_t value;
    std::memcpy(&value, &status, sizeof value);
    return value;
}

// Stores any int into an int-sized enum field of an API struct.
template <class Enum>
void store_raw(Enum* field, int32_t value) {
    static_assert(sizeof(Enum) == sizeof(int32_t), "the API's C enums are int-sized");
    std::memcpy(field, &value, sizeof value);
}
template <class Enum>
int32_t load_raw(const Enum& field) {
    static_assert(sizeof(Enum) == sizeof(int32_t), "the API's C enums are int-sized");
    int32_t value;
    std::memcpy(&value, &field, sizeof value);
    return value;
}

// Consumes the input front to back; reads past the end give zeros.
class Reader {
public:
    Reader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

    size_t remaining() const { return size_ - offset_; }
    bool empty() const { return offset_ >= size_; }

    void bytes(void* out, size_t count) {
        auto* dst = static_cast<uint8_t*>(out);
        size_t available = count < remaining() ? count : remaining();
        if (available) std::memcpy(dst, data_ + offset_, available);
        if (available < count) std::memset(dst + available, 0, count - available);
        offset_ += available;
    }
    uint8_t u8() { return take<uint8_t>(); }
    uint16_t u16() { return take<uint16_t>(); }
    uint32_t u32() { return take<uint32_t>(); }
    int32_t i32() { return take<int32_t>(); }
    float f32() { return take<float>(); }
    double f64() { return take<double>(); }
    bool flag() { return (u8() & 1) != 0; }
    // A value in [0, n) (n > 0).
    uint32_t index(uint32_t n) { return n <= 256 ? u8() % n : u32() % n; }
    // Up to max_length bytes, as a string (may hold any byte; c_str() ends at the first NUL).
    std::string text(size_t max_length) {
        size_t length = u8() % (max_length + 1);
        std::string out(length, '\0');
        bytes(&out[0], length);
        return out;
    }

private:
    template <class T>
    T take() {
        T value;
        bytes(&value, sizeof value);
        return value;
    }

    const uint8_t* data_;
    size_t size_;
    size_t offset_ = 0;
};

// A value for a setting with metadata `info`, picked by `selector`: the range's edges, just outside and
// just inside them, the default, zero, NaN and infinities, non-integral values, and raw doubles from `reader`.
double pick_setting_value(const obscura_setting_info& info, uint8_t selector, Reader& reader);

}  // namespace obscura_fuzz

#endif  // OBSCURA_TESTS_FUZZ_SUPPORT_H
