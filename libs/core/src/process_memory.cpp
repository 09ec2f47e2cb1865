#include "fresnel/core/process_memory.h"

#include <cstdlib>
#include <fstream>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace fresnel {

namespace {
// A "Name:   1234 kB" line of /proc/self/status, in MiB.
double status_mib(const char* name) {
    std::ifstream in("/proc/self/status");
    const std::string prefix = std::string(name) + ":";
    for (std::string line; std::getline(in, line);)
        if (line.rfind(prefix, 0) == 0) return double(std::atol(line.c_str() + prefix.size())) / 1024.0;
    return 0.0;
}
}  // namespace

double resident_mib() { return status_mib("VmRSS"); }
double peak_resident_mib() { return status_mib("VmHWM"); }

void keep_freed_memory_for_reuse() {
#if defined(__GLIBC__)
    mallopt(M_ARENA_MAX, 1);
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's most (HEAP_MAX_SIZE / 2 on 64-bit)
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace fresnel
