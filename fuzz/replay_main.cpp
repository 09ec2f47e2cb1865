// Replays fuzzer inputs (files or folders of files) through a fuzz target without
// libFuzzer, so the regression corpus runs in every normal and sanitizer build. Memory is
// part of the check: the process's peak resident size must stay under 1 GiB (2 GiB in
// sanitizer builds, whose shadow memory and quarantine count too), so an input that makes a
// decoder reserve gigabytes fails here, not only under a fuzzer's -rss_limit_mb.
#include <sys/resource.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    std::size_t count = 0;
    auto run = [&](const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
        ++count;
    };
    for (int i = 1; i < argc; ++i) {
        fs::path p(argv[i]);
        std::error_code ec;
        if (fs::is_directory(p, ec)) {
            for (const auto& e : fs::recursive_directory_iterator(p, ec))
                if (e.is_regular_file() && e.path().filename() != ".gitkeep") run(e.path());
        } else if (fs::is_regular_file(p, ec)) {
            run(p);
        }
    }
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    const double peak_mib = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss: KiB on Linux
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    const double limit_mib = 2048;
#else
    const double limit_mib = 1024;
#endif
    std::printf("replayed %zu inputs, peak resident memory %.0f MiB (limit %.0f MiB)\n", count, peak_mib, limit_mib);
    return peak_mib <= limit_mib ? 0 : 1;
}
