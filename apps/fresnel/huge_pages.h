#pragma once
// Transparent huge pages for the commands that load large textures. A 512x512 render of
// DamagedHelmet touches ~300 MB of fresh memory (five decoded 2048^2 maps, their mip chains,
// the GL driver's texture storage); with 4 KiB pages that is ~100k page faults, which in a
// virtual machine cost more than the rendering (1.4 s of a 1.6 s process on the project's
// machine, 0.6 s with huge pages). Where the kernel gives huge pages only on request
// (/sys/kernel/mm/transparent_hugepage/enabled = madvise, Debian's and Ubuntu's default) and
// glibc is the C library, glibc asks for them when its tunable glibc.malloc.hugetlb=1 is set,
// which it reads at start-up only: so the process starts itself again once with the tunable
// added to GLIBC_TUNABLES (the driver's allocations benefit as well as ours). Nothing happens
// when the tunable is already there, FRESNEL_NO_HUGE_PAGES is set, or anything fails.
namespace fresnel::cli {

// Call first thing in main(); returns only when the process goes on as it is.
void restart_with_huge_pages_if_useful(int argc, char** argv);

}  // namespace fresnel::cli
