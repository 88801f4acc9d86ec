// Error: a status plus a message, returned by everything below the C boundary that can fail.
#ifndef OBSCURA_ERROR_H
#define OBSCURA_ERROR_H

#include <cstdarg>
#include <cstdio>

#include "obscura/obscura.h"

namespace obscura {

class Error {
public:
    Error() = default;
    // printf-style message; truncated to the buffer size.
    static Error make(obscura_status status, const char* format, ...)
#if defined(__GNUC__)
        __attribute__((format(printf, 2, 3)))
#endif
    {
        Error error;
        error.status_ = status;
        va_list args;
        va_start(args, format);
        std::vsnprintf(error.message_, sizeof error.message_, format, args);
        va_end(args);
        return error;
    }
    bool ok() const { return status_ == OBSCURA_STATUS_OK; }
    explicit operator bool() const { return !ok(); }  // true when it holds an error
    obscura_status status() const { return status_; }
    const char* message() const { return message_; }

private:
    obscura_status status_ = OBSCURA_STATUS_OK;
    char message_[1024] = {};
};

}  // namespace obscura

#endif  // OBSCURA_ERROR_H
