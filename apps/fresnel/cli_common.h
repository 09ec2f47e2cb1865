#pragma once
// Helpers shared by the subcommands: exit codes, error and warning printing.
#include <chrono>
#include <string>

#include "fresnel/core/error.h"

namespace fresnel::cli {

// Exit codes: 0 success, 1 bad input, 2 bad usage.
inline constexpr int kExitOk = 0, kExitBadInput = 1, kExitUsage = 2;

// Prints "fresnel: error: FILE: WHERE: WHAT" to stderr.
void print_error(const Error& e);
void print_error(const std::string& message);
// Prints each unique warning once to stderr ("fresnel: warning: ... (xN)"), then a count.
void print_warnings(const Diagnostics& d);

using Clock = std::chrono::steady_clock;
// Milliseconds since `t`.
inline double ms_since(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// The lower-case extension of a path (".png").
std::string lower_extension(const std::string& path);

}  // namespace fresnel::cli
