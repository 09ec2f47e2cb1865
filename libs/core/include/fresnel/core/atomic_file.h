#pragma once
// Files written whole or not at all: every writer of fresnel goes through here.
//
// The content goes to a temporary file in the destination's folder (so the rename stays on one
// file system), named uniquely per process *and* thread (two threads of a batch writing the same
// output never share a temporary), is flushed to the disk (fsync: a full disk is found here, not
// after the rename), then renamed over the destination. On any failure the temporary is
// removed and the destination is left as it was; the error names the destination, never the
// temporary.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

namespace fresnel {

// A temporary name beside `path`: ".NAME.partial-PID-THREAD-HOST" plus `path`'s extension
// (writers that look at the extension see the right one). Not created.
std::filesystem::path temporary_path_beside(const std::filesystem::path& path);

// `write` writes the whole content to the path it is given (throwing on failure: a
// fresnel::Error's reason is kept, renamed to the destination). Throws fresnel::Error.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path& temporary)>& write);
void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void write_file_atomically(const std::filesystem::path& path, std::string_view text);

// Throws fresnel::Error naming `path` and the reason when a file cannot be written there (the
// folder is missing or read-only, `path` is a folder): a temporary is created beside it and
// removed. For commands to say so before the work whose result would be lost.
void check_writable(const std::filesystem::path& path);

// Several files committed together or not at all: a glTF with its .bin and images, an OBJ with
// its MTL and textures. Each stage() writes its content to a temporary beside the destination
// and flushes it (a full disk fails here, before any destination is touched); commit() then
// moves every staged file into place in the order staged (stage the file that names the
// others last), keeping each old destination under a backup name until all are in place. If
// a move fails, the ones made are undone and the old files restored. A FileSet destroyed
// without commit() removes its temporaries. Temporaries left by a process that was killed
// (".NAME.partial-PID-THREAD-HOST" of this machine and a PID no longer running) beside a
// destination are removed when a later set stages that destination. Errors are fresnel::Error naming the destination.
class FileSet {
public:
    FileSet() = default;
    FileSet(const FileSet&) = delete;
    FileSet& operator=(const FileSet&) = delete;
    ~FileSet();

    void stage(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
    void stage(const std::filesystem::path& path, std::string_view text);
    // `write` writes the content to the temporary path it is given.
    void stage(const std::filesystem::path& path,
               const std::function<void(const std::filesystem::path& temporary)>& write);
    // True when `path` is already staged (two names for one file count as one).
    bool staged(const std::filesystem::path& path) const;
    void commit();
    // The destinations staged, in order (after commit(): the files written).
    std::vector<std::filesystem::path> paths() const;

private:
    struct Entry {
        std::filesystem::path destination, temporary, backup;
        bool had_old = false, moved = false;
    };
    std::vector<Entry> entries_;
    bool committed_ = false;
    void discard() noexcept;
};

// Removes temporaries fresnel's writers left beside `path` when their process was killed
// (".STEM.partial-PID-THREAD-HOST.EXT" and ".STEM.previous-...", made on this machine by a PID
// that is no longer a running process; another machine's are never touched). Returns how many were removed; never throws.
std::size_t remove_stale_temporaries(const std::filesystem::path& path) noexcept;
// The same for every file under `folder`, recursively (batch, once per run over --out).
std::size_t remove_stale_temporaries_in(const std::filesystem::path& folder) noexcept;

}  // namespace fresnel
