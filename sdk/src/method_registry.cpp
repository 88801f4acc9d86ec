#include "method_registry.h"

#include "host_enum.h"

namespace obscura {

// Each method's row is defined beside its technique (sdk/src/methods/<method>.cpp).
extern const MethodDescriptor kHbaoMethod;
extern const MethodDescriptor kSaoMethod;
extern const MethodDescriptor kLsaoMethod;
extern const MethodDescriptor kFfaoMethod;
extern const MethodDescriptor kReferenceMethod;
extern const MethodDescriptor kGtaoMethod;

namespace {

// In obscura_method order: the enum value of row i is i + 1.
const MethodDescriptor* const kMethods[] = {
    &kHbaoMethod,
    &kSaoMethod,
    &kLsaoMethod,
    &kFfaoMethod,
    &kReferenceMethod,
    &kGtaoMethod,
};
static_assert(sizeof kMethods / sizeof kMethods[0] == size_t(OBSCURA_METHOD_COUNT_) - 1,
              "one registry row per obscura_method (OBSCURA_METHOD_DEFAULT excluded)");

}  // namespace

const MethodDescriptor* const* method_descriptors(uint32_t* count) {
    *count = uint32_t(sizeof kMethods / sizeof kMethods[0]);
    return kMethods;
}

const MethodDescriptor* find_method_value(int32_t value) {
    if (value == OBSCURA_METHOD_DEFAULT) value = OBSCURA_METHOD_HBAO;
    if (value < 1 || value >= int32_t(OBSCURA_METHOD_COUNT_)) return nullptr;
    const MethodDescriptor* row = kMethods[value - 1];
    return row->method == obscura_method(value) ? row : nullptr;  // a row out of order is no row
}

const MethodDescriptor* find_method(const obscura_method& method) { return find_method_value(stored_enum(method)); }

}  // namespace obscura
