#include "fresnel/core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>

#include "fresnel/core/error.h"

namespace fresnel {

namespace fs = std::filesystem;

fs::path temporary_path_beside(const fs::path& path) {
    // std::hash of a thread id is the thread's handle in libstdc++: unique among live threads.
    char suffix[64];
    std::snprintf(suffix, sizeof suffix, ".partial-%ld-%zx", static_cast<long>(::getpid()),
                  std::hash<std::thread::id>{}(std::this_thread::get_id()));
    return path.parent_path() / ("." + path.stem().string() + suffix + path.extension().string());
}

namespace {
// Flushes a written file to the disk: errors a full disk or a failing device reports late.
void sync_file(const fs::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw Error(file.string(), "", std::string("cannot reopen to flush: ") + std::strerror(errno));
    const int r = ::fsync(fd);
    const int e = errno;
    ::close(fd);
    // EINVAL: a file system without fsync (some pseudo file systems); the data is where it goes.
    if (r != 0 && e != EINVAL) throw Error(file.string(), "", std::string("cannot flush to the disk: ") + std::strerror(e));
}
}  // namespace

void write_file_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    const fs::path tmp = temporary_path_beside(path);
    auto discard = [&] {
        std::error_code ec;
        fs::remove(tmp, ec);
    };
    try {
        write(tmp);
        sync_file(tmp);
    } catch (const Error& e) {
        discard();
        throw Error(path.string(), e.where(), e.reason());  // the destination, not the temporary
    } catch (const std::exception& e) {
        discard();
        throw Error(path.string(), "", e.what());
    } catch (...) {
        discard();
        throw;
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        discard();
        throw Error(path.string(), "", "cannot move the written file into place: " + ec.message());
    }
}

void write_file_atomically(const fs::path& path, std::span<const std::uint8_t> bytes) {
    write_file_atomically(path, [&](const fs::path& tmp) {
        std::FILE* f = std::fopen(tmp.c_str(), "wb");
        if (!f) throw Error(tmp.string(), "", std::string("cannot write: ") + std::strerror(errno));
        const std::size_t n = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), f);
        const int write_errno = errno;
        const bool flushed = std::fflush(f) == 0;
        const int flush_errno = errno;
        const bool closed = std::fclose(f) == 0;
        if (n != bytes.size()) throw Error(tmp.string(), "", std::string("write failed: ") + std::strerror(write_errno));
        if (!flushed || !closed)
            throw Error(tmp.string(), "", std::string("write failed: ") + std::strerror(flushed ? errno : flush_errno));
    });
}

void write_file_atomically(const fs::path& path, std::string_view text) {
    write_file_atomically(path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace fresnel
