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

namespace fresnel {

// A temporary name beside `path`: ".NAME.partial-PID-THREAD" plus `path`'s extension (writers
// that look at the extension see the right one). Not created.
std::filesystem::path temporary_path_beside(const std::filesystem::path& path);

// `write` writes the whole content to the path it is given (throwing on failure: a
// fresnel::Error's reason is kept, renamed to the destination). Throws fresnel::Error.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path& temporary)>& write);
void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
void write_file_atomically(const std::filesystem::path& path, std::string_view text);

}  // namespace fresnel
