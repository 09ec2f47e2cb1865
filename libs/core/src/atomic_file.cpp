#include "fresnel/core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "fresnel/core/error.h"

namespace fresnel {

namespace fs = std::filesystem;

namespace {
// This machine, as 8 hex digits (FNV-1a of its host name): temporaries carry it, so a process
// cleaning up after killed writers never touches one of another machine's writing to a shared
// folder (Slurm shards on NFS), whose PID means nothing here.
const std::string& host_tag() {
    static const std::string tag = [] {
        char host[256] = {};
        if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
        std::uint32_t h = 2166136261u;
        for (const char* c = host; *c; ++c) h = (h ^ std::uint8_t(*c)) * 16777619u;
        char out[16];
        std::snprintf(out, sizeof out, "%08x", h);
        return std::string(out);
    }();
    return tag;
}

// ".STEM.KIND-PID-THREAD-HOST.EXT" beside `path`. std::hash of a thread id is the thread's handle
// in libstdc++: unique among live threads.
fs::path name_beside(const fs::path& path, const char* kind) {
    char suffix[96];
    std::snprintf(suffix, sizeof suffix, ".%s-%ld-%zx-%s", kind, static_cast<long>(::getpid()),
                  std::hash<std::thread::id>{}(std::this_thread::get_id()), host_tag().c_str());
    return path.parent_path() / ("." + path.stem().string() + suffix + path.extension().string());
}
}  // namespace

fs::path temporary_path_beside(const fs::path& path) { return name_beside(path, "partial"); }

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
// Flushes a folder's entries (a rename into it) to the disk. Best effort: the data is already
// flushed, and some file systems refuse to open or flush folders.
void sync_folder(const fs::path& file) noexcept {
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    (void)::fsync(fd);
    ::close(fd);
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
    sync_folder(path);
}

namespace {
// Writes `bytes` to `file` with every write, flush and close checked; errors name `name`.
void write_checked(const fs::path& file, std::span<const std::uint8_t> bytes, const std::string& name) {
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (!f) throw Error(name, "", std::string("cannot write: ") + std::strerror(errno));
    const std::size_t n = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), f);
    const int write_errno = errno;
    const bool flushed = std::fflush(f) == 0;
    const int flush_errno = errno;
    const bool closed = std::fclose(f) == 0;
    if (n != bytes.size()) throw Error(name, "", std::string("cannot write: ") + std::strerror(write_errno));
    if (!flushed || !closed)
        throw Error(name, "", std::string("cannot write: ") + std::strerror(flushed ? errno : flush_errno));
}
}  // namespace

void write_file_atomically(const fs::path& path, std::span<const std::uint8_t> bytes) {
    write_file_atomically(path, [&](const fs::path& tmp) { write_checked(tmp, bytes, tmp.string()); });
}

void write_file_atomically(const fs::path& path, std::string_view text) {
    write_file_atomically(path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void check_writable(const fs::path& path) {
    if (std::error_code ec; fs::is_directory(path, ec)) throw Error(path.string(), "", "is a folder, not a file");
    const fs::path tmp = temporary_path_beside(path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int e = errno;
        const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
        if (std::error_code ec; e == ENOENT && !fs::is_directory(folder, ec))
            throw Error(path.string(), "", "cannot write: the folder " + folder.string() + " does not exist");
        throw Error(path.string(), "", std::string("cannot write: ") + std::strerror(e));
    }
    ::close(fd);
    ::unlink(tmp.c_str());
}

// ---- FileSet --------------------------------------------------------------------------------

namespace {
// The file a path names, for comparing two spellings of one destination.
fs::path identity(const fs::path& p) {
    std::error_code ec;
    fs::path c = fs::weakly_canonical(fs::absolute(p, ec), ec);
    return ec ? fs::absolute(p).lexically_normal() : c;
}
}  // namespace

FileSet::~FileSet() {
    if (!committed_) discard();
}

void FileSet::discard() noexcept {
    std::error_code ec;
    for (Entry& e : entries_)
        if (!e.moved) fs::remove(e.temporary, ec);
}

bool FileSet::staged(const fs::path& path) const {
    const fs::path id = identity(path);
    for (const Entry& e : entries_)
        if (identity(e.destination) == id) return true;
    return false;
}

void FileSet::stage(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    if (committed_) throw Error(path.string(), "", "cannot stage a file into a set already committed");
    if (staged(path)) throw Error(path.string(), "", "written twice by one set of files");
    if (std::error_code ec; fs::is_directory(path, ec)) throw Error(path.string(), "", "is a folder, not a file");
    remove_stale_temporaries(path);
    Entry e;
    e.destination = path;
    e.temporary = temporary_path_beside(path);
    e.backup = name_beside(path, "previous");
    try {
        write(e.temporary);
        sync_file(e.temporary);
    } catch (const std::exception& x) {
        std::error_code ec;
        fs::remove(e.temporary, ec);
        const auto* fe = dynamic_cast<const Error*>(&x);
        throw Error(path.string(), fe ? fe->where() : "", fe ? fe->reason() : x.what());
    }
    entries_.push_back(std::move(e));
}

void FileSet::stage(const fs::path& path, std::span<const std::uint8_t> bytes) {
    stage(path, [&](const fs::path& tmp) { write_checked(tmp, bytes, path.string()); });
}

void FileSet::stage(const fs::path& path, std::string_view text) {
    stage(path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

std::vector<fs::path> FileSet::paths() const {
    std::vector<fs::path> out;
    out.reserve(entries_.size());
    for (const Entry& e : entries_) out.push_back(e.destination);
    return out;
}

void FileSet::commit() {
    if (committed_) return;
    std::error_code ec;
    // Undoes the moves made so far (newest first): each destination gets its old file back, or
    // is removed when it had none.
    auto roll_back = [&] {
        std::error_code rc;
        for (auto it = entries_.rbegin(); it != entries_.rend(); ++it) {
            if (it->moved) {
                if (it->had_old) fs::rename(it->backup, it->destination, rc);
                else fs::remove(it->destination, rc);
                it->moved = false;
            } else if (it->had_old) {
                fs::rename(it->backup, it->destination, rc);
            }
            it->had_old = false;
        }
        discard();
    };
    for (Entry& e : entries_) {
        // The old file, kept under a backup name until the whole set is in place.
        if (fs::exists(fs::symlink_status(e.destination, ec))) {
            fs::rename(e.destination, e.backup, ec);
            if (ec) {
                const std::string why = ec.message();
                roll_back();
                throw Error(e.destination.string(), "", "cannot replace the old file: " + why);
            }
            e.had_old = true;
        }
        fs::rename(e.temporary, e.destination, ec);
        if (ec) {
            const std::string why = ec.message();
            roll_back();
            throw Error(e.destination.string(), "", "cannot move the written file into place: " + why);
        }
        e.moved = true;
    }
    committed_ = true;
    for (Entry& e : entries_) {
        if (e.had_old) fs::remove(e.backup, ec);
        sync_folder(e.destination);
    }
}

namespace {
// A temporary or backup of fresnel's writers (".STEM.KIND-PID-THREAD-HOST[.EXT]") made on this
// machine by a process no longer running.
bool stale_temporary(const std::string& name) {
    if (name.empty() || name[0] != '.') return false;
    for (const char* kind : {".partial-", ".previous-"}) {
        const std::size_t at = name.rfind(kind);
        if (at == std::string::npos || at == 0) continue;
        const char* p = name.c_str() + at + std::strlen(kind);
        char* after = nullptr;
        const long pid = std::strtol(p, &after, 10);
        if (pid <= 0 || after == p || *after != '-') return false;
        const char* hex = after + 1;
        const char* q = hex;
        while (std::isxdigit(static_cast<unsigned char>(*q))) ++q;
        if (q == hex || *q != '-') return false;
        const std::string& host = host_tag();
        if (std::strncmp(q + 1, host.c_str(), host.size()) != 0) return false;  // another machine's, or not ours
        q += 1 + host.size();
        if (*q != '\0' && *q != '.') return false;
        return ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;  // not running (EPERM: someone else's, running)
    }
    return false;
}

std::size_t remove_stale(const fs::path& folder, const std::string& prefix, const std::string& suffix, bool recursive) {
    std::size_t removed = 0;
    std::error_code ec;
    auto consider = [&](const fs::directory_entry& entry) {
        const std::string name = entry.path().filename().string();
        if (name.size() < prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0 || !stale_temporary(name))
            return;
        std::error_code rc;
        if (entry.is_regular_file(rc) && fs::remove(entry.path(), rc)) ++removed;
    };
    if (recursive) {
        for (fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
             !ec && it != end; it.increment(ec))
            consider(*it);
    } else {
        for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) consider(*it);
    }
    return removed;
}
}  // namespace

std::size_t remove_stale_temporaries(const fs::path& path) noexcept {
    try {
        const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
        return remove_stale(folder, "." + path.stem().string() + ".", path.extension().string(), false);
    } catch (...) {
        return 0;
    }
}

std::size_t remove_stale_temporaries_in(const fs::path& folder) noexcept {
    try {
        return remove_stale(folder, ".", "", true);
    } catch (...) {
        return 0;
    }
}

}  // namespace fresnel
