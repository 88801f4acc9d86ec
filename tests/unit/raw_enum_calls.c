/* Calls with raw enum values, as a C host makes them: in C an enum is an int, so any value is defined here,
   while forming one outside the C++ enum's range in a C++ test would be undefined (UBSan reports the load). */
#include "obscura/obscura.h"

const char* obscura_test_status_string_raw(int value) { return obscura_status_string((obscura_status)value); }
