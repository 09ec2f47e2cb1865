#include "huge_pages.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace fresnel::cli {

namespace {

// The commands that upload or read large images (not view: a long-lived window, whose
// resident memory the soak test follows page by page).
bool loads_large_textures(const char* command) {
    for (const char* c : {"render", "bake", "batch", "trace"})
        if (std::strcmp(command, c) == 0) return true;
    return false;
}

bool huge_pages_on_request() {
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    return std::getline(in, line) && line.find("[madvise]") != std::string::npos;
}

}  // namespace

void restart_with_huge_pages_if_useful(int argc, char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
    if (argc < 2 || !loads_large_textures(argv[1]) || std::getenv("FRESNEL_NO_HUGE_PAGES")) return;
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    std::string value = tunables ? tunables : "";
    if (value.find("glibc.malloc.hugetlb") != std::string::npos || !huge_pages_on_request()) return;
    value += std::string(value.empty() ? "" : ":") + "glibc.malloc.hugetlb=1";
    if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
    execv("/proc/self/exe", argv);
    // exec failed (no /proc, say): go on without, and keep the environment as it was.
    if (tunables) setenv("GLIBC_TUNABLES", tunables, 1);
    else unsetenv("GLIBC_TUNABLES");
#else
    (void)argc;
    (void)argv;
#endif
}

}  // namespace fresnel::cli
