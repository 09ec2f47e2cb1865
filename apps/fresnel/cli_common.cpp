#include "cli_common.h"

#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>

namespace fresnel::cli {

namespace {
// The flag a signal handler sets: process-wide by nature (InterruptGuard owns its use).
std::atomic<bool> g_interrupt_requested{false};
struct sigaction g_previous_sigint {};

void on_sigint(int) {
    if (g_interrupt_requested.exchange(true)) {
        ::signal(SIGINT, SIG_DFL);
        ::raise(SIGINT);
        return;
    }
    static const char message[] = "\nfresnel: interrupted: finishing the pass in progress and writing what is done "
                                  "(Ctrl+C again to quit now)\n";
    (void)!::write(2, message, sizeof message - 1);
}
}  // namespace

InterruptGuard::InterruptGuard() {
    g_interrupt_requested = false;
    struct sigaction sa {};
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGINT, &sa, &g_previous_sigint);
}

InterruptGuard::~InterruptGuard() { ::sigaction(SIGINT, &g_previous_sigint, nullptr); }

const std::atomic<bool>& InterruptGuard::requested() const { return g_interrupt_requested; }


void print_error(const Error& e) { std::fprintf(stderr, "fresnel: error: %s\n", e.what()); }
void print_error(const std::string& m) { std::fprintf(stderr, "fresnel: error: %s\n", m.c_str()); }

std::string human_bytes(std::uintmax_t bytes) {
    char buf[32];
    if (bytes < 1024) {
        std::snprintf(buf, sizeof buf, "%ju B", bytes);
        return buf;
    }
    const char* units[] = {"KiB", "MiB", "GiB", "TiB"};
    double v = double(bytes) / 1024.0;
    int u = 0;
    while (v >= 1024.0 && u < 3) v /= 1024.0, ++u;
    std::snprintf(buf, sizeof buf, v < 10.0 ? "%.2f %s" : v < 100.0 ? "%.1f %s" : "%.0f %s", v, units[u]);
    return buf;
}

void print_warnings(const Diagnostics& d) {
    auto lines = d.lines();
    for (const auto& l : lines) std::fprintf(stderr, "fresnel: warning: %s\n", l.c_str());
    if (!lines.empty())
        std::fprintf(stderr, "fresnel: %zu warning%s (%zu unique%s)\n", d.total(), d.total() == 1 ? "" : "s",
                     d.warnings().size(), d.suppressed() > 0 ? " shown" : "");
}

std::string lower_extension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

}  // namespace fresnel::cli
