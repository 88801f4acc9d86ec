#include "fuzz_support.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>

namespace obscura_fuzz {
namespace {
std::string g_context;
}

void set_failure_context(const std::string& context) { g_context = context; }

void fail(const char* format, ...) {
    std::fprintf(stderr, "\n==== obscura fuzz invariant violated: ");
    va_list args;
    va_start(args, format);
    std::vfprintf(stderr, format, args);
    va_end(args);
    std::fprintf(stderr, "\n");
    if (!g_context.empty()) std::fprintf(stderr, "while: %s\n", g_context.c_str());
    std::fflush(stderr);
    __builtin_trap();
}

double pick_setting_value(const obscura_setting_info& info, uint8_t selector, Reader& reader) {
    const double lo = info.min_value, hi = info.max_value;
    const double inf = std::numeric_limits<double>::infinity();
    switch (selector % 20) {
        case 0: return lo;
        case 1: return hi;
        case 2: return info.default_value;
        case 3: return std::nextafter(lo, -inf);                  // just below the range
        case 4: return std::nextafter(hi, inf);                   // just above it
        case 5: return std::nextafter(lo, inf);                   // just inside
        case 6: return std::nextafter(hi, -inf);
        case 7: return 0.5 * (lo + hi);
        case 8: return std::numeric_limits<double>::quiet_NaN();
        case 9: return inf;
        case 10: return -inf;
        case 11: return 0.0;
        case 12: return -0.0;
        case 13: return lo + (hi - lo) * (reader.u8() / 255.0);   // inside, often not integral
        case 14: return std::floor(lo + (hi - lo) * (reader.u16() / 65535.0));
        case 15: return lo - 1.0;
        case 16: return hi + 1.0;
        case 17: return std::floor(0.5 * (lo + hi)) + 0.5;        // never integral
        case 18: return double(float(hi));                     // the edge as a float stores it
        default: return reader.f64();                             // anything, subnormals and NaN payloads too
    }
}

}  // namespace obscura_fuzz
