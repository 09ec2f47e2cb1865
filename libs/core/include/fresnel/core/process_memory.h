#pragma once
// This process's memory as the kernel counts it (Linux /proc/self/status), in MiB; 0 where
// there is no /proc. The peak is this program's own (VmHWM: since its exec), unlike
// getrusage's ru_maxrss, which keeps the high-water mark of the process that exec'd it.

namespace fresnel {

double resident_mib();       // VmRSS: resident now
double peak_resident_mib();  // VmHWM: the most resident so far

}  // namespace fresnel

namespace fresnel {

// For a one-shot process that frees large buffers and then allocates others of like size (a
// render that releases decoded images once uploaded while the GL driver copies textures into
// memory of its own): keeps freed memory in this process's heap to be reused, rather than
// handed back to the kernel and asked for again as fresh pages (which the kernel must zero:
// measured ~0.6 ms per MiB on a 2-core VM, against ~0.11 ms to write memory already touched).
// glibc: one malloc arena (what a worker thread frees, the GL thread can reuse), blocks up to
// 32 MiB from the heap, the heap trimmed only past 1 GiB free. Call before starting threads;
// elsewhere it does nothing. Not for long-lived processes (the viewer): their peak stays resident.
void keep_freed_memory_for_reuse();

}  // namespace fresnel
