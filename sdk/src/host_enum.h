// Enum values as the host passed them. A C host may store or pass any int where the API has an enum; loading
// a value outside the enumerators through the C++ enum type is undefined (-fsanitize=enum reports it), so the
// SDK reads the bytes as an int and validates that.
#ifndef OBSCURA_HOST_ENUM_H
#define OBSCURA_HOST_ENUM_H

#include <cstdint>
#include <cstring>

namespace obscura {

template <class Enum>
int32_t stored_enum(const Enum& value) {
    static_assert(sizeof(Enum) == sizeof(int32_t), "the API's C enums are int-sized");
    int32_t raw;
    std::memcpy(&raw, &value, sizeof raw);
    return raw;
}

}  // namespace obscura

#endif  // OBSCURA_HOST_ENUM_H
