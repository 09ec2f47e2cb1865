#pragma once
// Helpers shared by the subcommands: exit codes, error and warning printing.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "fresnel/core/error.h"

namespace fresnel::cli {

// Exit codes: 0 success, 1 bad input, 2 bad usage, 130 interrupted (Ctrl+C; what was done is
// written, as the shell's code for SIGINT says).
inline constexpr int kExitOk = 0, kExitBadInput = 1, kExitUsage = 2, kExitInterrupted = 130;

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

// Ctrl+C as a request: while an InterruptGuard lives, the first SIGINT sets requested() and says
// on stderr that the command is finishing (long work checks it, ends early and keeps what it
// has); a second SIGINT ends the process as SIGINT does. One per process at a time (a signal
// handler's flag is necessarily the process's); the previous handler is restored after.
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;
    const std::atomic<bool>& requested() const;
};

// The lower-case extension of a path (".png").
std::string lower_extension(const std::string& path);

// A byte count for people: "812 B", "35.2 KiB", "3.81 MiB", "1.20 GiB".
std::string human_bytes(std::uintmax_t bytes);

}  // namespace fresnel::cli
