#pragma once
// A test's full disk without root or a small file system: while a FileSizeLimit lives, writes
// past `limit` bytes of a file fail with EFBIG (RLIMIT_FSIZE; its signal, SIGXFSZ, ignored).
#include <sys/resource.h>

#include <csignal>

// (tests/support: shared by the suites)

namespace fresnel::test {

struct FileSizeLimit {
    rlimit old{};
    void (*old_handler)(int) = nullptr;
    explicit FileSizeLimit(rlim_t limit) {
        old_handler = std::signal(SIGXFSZ, SIG_IGN);
        ::getrlimit(RLIMIT_FSIZE, &old);
        rlimit r = old;
        r.rlim_cur = limit;
        ::setrlimit(RLIMIT_FSIZE, &r);
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &old);
        std::signal(SIGXFSZ, old_handler);
    }
};
}  // namespace fresnel::test
