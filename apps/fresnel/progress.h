#pragma once
// A progress bar on stderr for long work, drawn only when stderr is a terminal
// (so logs and pipes stay clean). Thread-safe: update() may be called from workers.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

namespace fresnel::cli {

class ProgressBar {
public:
    // With `time_left`, the bar also shows the time remaining, extrapolated from the time
    // since construction and the fraction done.
    explicit ProgressBar(std::string label, bool time_left = false)
        : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0), time_left_(time_left),
          start_(std::chrono::steady_clock::now()) {}
    ~ProgressBar() { finish(); }
    void update(double fraction) {
        if (!enabled_) return;
        std::lock_guard lock(mutex_);
        int pct = int(fraction * 100.0 + 0.5);
        auto now = std::chrono::steady_clock::now();
        if (pct == last_pct_ || (now - last_draw_ < std::chrono::milliseconds(50) && pct < 100)) return;
        last_pct_ = pct;
        last_draw_ = now;
        drawn_ = true;
        int filled = pct * 30 / 100;
        std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), filled, "##############################",
                     30 - filled, "", pct);
        if (time_left_ && fraction > 0.0) {
            double elapsed = std::chrono::duration<double>(now - start_).count();
            int left = int(elapsed * (1.0 - fraction) / fraction + 0.5);
            std::fprintf(stderr, "  %d:%02d left ", left / 60, left % 60);
        }
        std::fflush(stderr);
    }
    void finish() {
        std::lock_guard lock(mutex_);
        if (drawn_) std::fprintf(stderr, "\n");
        drawn_ = false;
    }

private:
    std::string label_;
    bool enabled_;
    bool time_left_ = false;
    std::chrono::steady_clock::time_point start_;
    bool drawn_ = false;
    int last_pct_ = -1;
    std::chrono::steady_clock::time_point last_draw_{};
    std::mutex mutex_;
};

}  // namespace fresnel::cli
