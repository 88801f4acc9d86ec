// Shared by the libFuzzer targets: a reader that turns the input bytes into values (zeros once the input is
// used up, so every input, even an empty one, is a complete test case), the failure report, the C shims
// (raw_enum_calls.c) that pass arbitrary ints where the API takes an enum, and the released sizes of
// obscura_settings with a buffer that holds a host's struct of exactly such a size.
#ifndef OBSCURA_TESTS_FUZZ_SUPPORT_H
#define OBSCURA_TESTS_FUZZ_SUPPORT_H

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "obscura/obscura.h"

// A C host may pass any int where the API takes an enum. Forming such a value in C++ is undefined (and
// -fsanitize=enum reports the load), so these calls go through a C file, exactly as a C host makes them.
extern "C" {
const char* fuzz_status_string(int32_t status);
const char* fuzz_method_name(int32_t method);
int fuzz_method_available(int32_t method);
int32_t fuzz_default_settings(int32_t method, obscura_settings* out);
int32_t fuzz_get_setting_infos(int32_t method, const obscura_setting_info** out_infos, uint32_t* out_count);
int32_t fuzz_default_settings_sized(int32_t method, obscura_settings* out, uint32_t out_size);
int32_t fuzz_get_setting_infos_sized(int32_t method, const obscura_setting_info** out_infos, uint32_t* out_count,
                                     uint32_t info_size);
// The 0.3 ABI symbols, (obscura_default_settings) and (obscura_get_setting_infos).
int32_t fuzz_default_settings_03(int32_t method, obscura_settings* out);
int32_t fuzz_get_setting_infos_03(int32_t method, const obscura_setting_info** out_infos, uint32_t* out_count);
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

// ---- Struct versions --------------------------------------------------------------------------------------

// sizeof(obscura_settings) in every released header (obscura.h, SETTINGS: each release appended to the end).
constexpr uint32_t kSettingsSize01 = uint32_t(offsetof(obscura_settings, reference));  // HBAO only
constexpr uint32_t kSettingsSize02 = uint32_t(offsetof(obscura_settings, sao));        // + REFERENCE
constexpr uint32_t kSettingsSize03 = uint32_t(offsetof(obscura_settings, flags));      // + SAO, LSAO, FFAO
constexpr uint32_t kSettingsSize04 = uint32_t(offsetof(obscura_settings, gtao));       // + flags
constexpr uint32_t kSettingsSize05 = uint32_t(sizeof(obscura_settings));               // + GTAO
constexpr uint32_t kReleasedSettingsSizes[5] = {kSettingsSize01, kSettingsSize02, kSettingsSize03, kSettingsSize04,
                                                kSettingsSize05};
inline bool is_released_settings_size(uint32_t size) {
    for (uint32_t released : kReleasedSettingsSizes) {
        if (size == released) return true;
    }
    return false;
}

// obscura_input and obscura_output as 0.4 declared them, which obscura_render still takes (the fields added since read
// 0): the input ended at normal_texture, before the temporal fields; the output before bent_normal_texture.
constexpr uint32_t kInputSize04 = uint32_t(offsetof(obscura_input, normal_texture) + sizeof(uint32_t));
constexpr uint32_t kOutputSize04 = uint32_t(offsetof(obscura_output, bent_normal_texture));
inline bool is_released_input_size(uint32_t size) { return size == sizeof(obscura_input) || size == kInputSize04; }
inline bool is_released_output_size(uint32_t size) { return size == sizeof(obscura_output) || size == kOutputSize04; }

// obscura_setting_info as the 0.3 header declared it: the first eight fields of today's.
struct SettingInfo03 {
    const char* name;
    obscura_setting_type type;
    double default_value, min_value, max_value;
    const char* unit;
    const char* description;
    size_t offset;
};
static_assert(sizeof(SettingInfo03) == offsetof(obscura_setting_info, flags), "0.4 appended to the 0.3 layout");
// ... and as the 0.4 header declared it: three more fields; today's adds added_in (0.5).
struct SettingInfo04 {
    SettingInfo03 first;  // the 0.3 fields
    uint32_t flags;
    uint32_t value_count;
    const char* const* value_names;
};
static_assert(sizeof(SettingInfo04) == offsetof(obscura_setting_info, added_in), "0.5 appended to the 0.4 layout");

// A host's obscura_settings of exactly `size` bytes on the heap (never less than the struct_size field), so that
// AddressSanitizer reports any read or write of the library past the caller's struct. The settings functions take
// it as an obscura_settings*; this code reads it only as bytes.
class SettingsBuffer {
public:
    // The first `size` bytes of `settings`.
    SettingsBuffer(const obscura_settings& settings, size_t size)
        : bytes_(reinterpret_cast<const unsigned char*>(&settings),
                 reinterpret_cast<const unsigned char*>(&settings) + clamp(size)) {}
    // `size` bytes of `fill`.
    SettingsBuffer(unsigned char fill, size_t size) : bytes_(clamp(size), fill) {}

    obscura_settings* get() { return reinterpret_cast<obscura_settings*>(bytes_.data()); }
    const obscura_settings* get() const { return reinterpret_cast<const obscura_settings*>(bytes_.data()); }
    size_t size() const { return bytes_.size(); }
    const unsigned char* bytes() const { return bytes_.data(); }
    unsigned char* get_bytes() { return bytes_.data(); }
    uint32_t struct_size() const {
        uint32_t value;
        std::memcpy(&value, bytes_.data(), sizeof value);
        return value;
    }
    bool operator==(const SettingsBuffer& other) const { return bytes_ == other.bytes_; }
    bool operator!=(const SettingsBuffer& other) const { return bytes_ != other.bytes_; }
    // The bytes as a whole obscura_settings: zeros after them (struct_size as stored).
    obscura_settings whole() const {
        obscura_settings out;
        std::memset(&out, 0, sizeof out);
        std::memcpy(&out, bytes_.data(), bytes_.size());
        return out;
    }

private:
    static size_t clamp(size_t size) {
        return size < sizeof(uint32_t) ? sizeof(uint32_t) : size > sizeof(obscura_settings) ? sizeof(obscura_settings) : size;
    }
    std::vector<unsigned char> bytes_;
};

// A value for a setting with metadata `info`, picked by `selector`: the range's edges, just outside and
// just inside them, the default, zero, NaN and infinities, non-integral values, and raw doubles from `reader`.
double pick_setting_value(const obscura_setting_info& info, uint8_t selector, Reader& reader);

}  // namespace obscura_fuzz

#endif  // OBSCURA_TESTS_FUZZ_SUPPORT_H
