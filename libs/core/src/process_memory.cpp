#include "fresnel/core/process_memory.h"

#include <cstdlib>
#include <fstream>
#include <string>

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

}  // namespace fresnel
