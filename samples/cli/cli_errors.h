// The two ways a CLI command fails; main() prints the message and picks the exit code.
#ifndef OBSCURA_CLI_ERRORS_H
#define OBSCURA_CLI_ERRORS_H

#include <stdexcept>

namespace obscura::cli {

// Bad command line: exit code 2, followed by a hint to run --help.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// An Obscura API call failed: exit code 1. The message holds obscura_status_string() and
// obscura_get_last_error().
class ApiError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace obscura::cli

#endif  // OBSCURA_CLI_ERRORS_H
