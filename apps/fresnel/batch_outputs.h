#pragma once
// What `fresnel batch` knows of its outputs: their canonical names (so two spellings of one
// file are one name) and the log of the outputs it committed, which --resume trusts instead of
// a file's mere existence.
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>

namespace fresnel::cli {

// An output name relative to --out, lexically normalised ("./a.png", "sub/../a.png" -> "a.png";
// "sub//x.png" -> "sub/x.png"); its collision key is the same, lower-cased when the folder's
// file system ignores case.
std::string canonical_output_name(const std::string& name);
std::string output_key(const std::string& canonical_name, bool ignores_case);
// Whether names in `folder` (which exists) are case-insensitive: a probe file made and removed.
bool folder_ignores_case(const std::filesystem::path& folder);

// The log of committed outputs: one JSON line per output written ({"output": NAME relative to
// --out, "bytes": N, "fnv1a64": "HEX"} of the file as it is on disk), appended and flushed to the
// disk after the output is in place. Each shard appends to its own file in --out
// (".fresnel-batch.jsonl", ".fresnel-batch-I-of-N.jsonl"), so shards sharing a folder never
// share a log; --resume reads them all.
class OutputLog {
public:
    struct Entry {
        std::uintmax_t bytes = 0;
        std::uint64_t hash = 0;
    };
    // Every entry of the logs in `out` (the latest per output); a line cut short by a killed
    // process is ignored.
    static std::map<std::string, Entry> read(const std::filesystem::path& out);
    // Whether `file` is whole: its size and content are what the log recorded for `name`.
    static bool verified(const std::map<std::string, Entry>& log, const std::string& name,
                         const std::filesystem::path& file);
    static std::filesystem::path file_for(const std::filesystem::path& out, long shard, long shards);

    explicit OutputLog(std::filesystem::path file) : file_(std::move(file)) {}
    // Records `file` (committed) as `name`. Thread-safe; throws fresnel::Error naming the log
    // file and the reason when the line cannot be written and flushed.
    void record(const std::string& name, const std::filesystem::path& file);

private:
    std::filesystem::path file_;
    std::mutex mutex_;
};

}  // namespace fresnel::cli
