#pragma once
// This process's memory as the kernel counts it (Linux /proc/self/status), in MiB; 0 where
// there is no /proc. The peak is this program's own (VmHWM: since its exec), unlike
// getrusage's ru_maxrss, which keeps the high-water mark of the process that exec'd it.

namespace fresnel {

double resident_mib();       // VmRSS: resident now
double peak_resident_mib();  // VmHWM: the most resident so far

}  // namespace fresnel
