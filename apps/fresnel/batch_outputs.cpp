#include "batch_outputs.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/ibl/bake.h"

namespace fresnel::cli {

namespace fs = std::filesystem;

std::string canonical_output_name(const std::string& name) {
    std::string n = fs::path(name).lexically_normal().generic_string();
    return n.empty() ? std::string(".") : n;
}

std::string output_key(const std::string& canonical_name, bool ignores_case) {
    std::string k = canonical_name;
    if (ignores_case)
        for (char& c : k) c = char(std::tolower(static_cast<unsigned char>(c)));
    return k;
}

bool folder_ignores_case(const fs::path& folder) {
    char name[64];
    std::snprintf(name, sizeof name, ".fresnel-case-probe-%ld-%zx", long(::getpid()),
                  std::hash<std::thread::id>{}(std::this_thread::get_id()));
    const fs::path lower = folder / name;
    std::string upper_name = name;
    for (char& c : upper_name) c = char(std::toupper(static_cast<unsigned char>(c)));
    std::error_code ec;
    {
        std::ofstream probe(lower);
        if (!probe) return false;  // unwritable: the write of the outputs will say so
    }
    const bool ignores = fs::exists(folder / upper_name, ec);
    fs::remove(lower, ec);
    return ignores;
}

namespace {
// FNV-1a of a file's bytes (ibl::content_hash, the cache's key function), and its size.
bool hash_file(const fs::path& file, OutputLog::Entry& e) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec) return false;
    std::ifstream in(file, std::ios::binary);
    if (!in) return false;
    std::uint64_t h = 1469598103934665603ull;
    std::vector<std::uint8_t> buffer(1 << 16);
    std::uintmax_t total = 0;
    while (in) {
        in.read(reinterpret_cast<char*>(buffer.data()), std::streamsize(buffer.size()));
        const std::size_t n = std::size_t(in.gcount());
        h = ibl::content_hash(std::span<const std::uint8_t>(buffer.data(), n), h);
        total += n;
    }
    if (total != size) return false;
    e.bytes = size;
    e.hash = h;
    return true;
}
}  // namespace

fs::path OutputLog::file_for(const fs::path& out, long shard, long shards) {
    if (shards <= 1) return out / ".fresnel-batch.jsonl";
    return out / (".fresnel-batch-" + std::to_string(shard) + "-of-" + std::to_string(shards) + ".jsonl");
}

std::map<std::string, OutputLog::Entry> OutputLog::read(const fs::path& out) {
    std::map<std::string, Entry> log;
    std::error_code ec;
    std::vector<fs::path> files;
    for (fs::directory_iterator it(out, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string n = it->path().filename().string();
        if (n.rfind(".fresnel-batch", 0) == 0 && n.size() > 6 && n.compare(n.size() - 6, 6, ".jsonl") == 0)
            files.push_back(it->path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
        std::ifstream in(f);
        std::string line;
        while (std::getline(in, line)) {
            // A record glued to one cut short (a process killed mid-line) starts at its last '{'.
            const std::size_t start = line.rfind("{\"bytes\"");
            if (start == std::string::npos) continue;
            const auto j = nlohmann::json::parse(line.substr(start), nullptr, false);
            if (!j.is_object() || !j.contains("output") || !j["output"].is_string() || !j.contains("bytes") ||
                !j["bytes"].is_number_unsigned() || !j.contains("fnv1a64") || !j["fnv1a64"].is_string())
                continue;  // a line cut short, or not ours
            Entry e;
            e.bytes = j["bytes"].get<std::uintmax_t>();
            const std::string hex = j["fnv1a64"].get<std::string>();
            char* end = nullptr;
            e.hash = std::strtoull(hex.c_str(), &end, 16);
            if (hex.empty() || *end) continue;
            log[j["output"].get<std::string>()] = e;
        }
    }
    return log;
}

bool OutputLog::verified(const std::map<std::string, Entry>& log, const std::string& name, const fs::path& file) {
    const auto it = log.find(name);
    if (it == log.end()) return false;
    Entry e;
    return hash_file(file, e) && e.bytes == it->second.bytes && e.hash == it->second.hash;
}

void OutputLog::record(const std::string& name, const fs::path& file) {
    Entry e;
    if (!hash_file(file, e)) throw Error(file.string(), "", "cannot read back the written output to record it");
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016" PRIx64, e.hash);
    const std::string line =
        nlohmann::json{{"output", name}, {"bytes", e.bytes}, {"fnv1a64", hex}}.dump() + "\n";
    std::lock_guard lock(mutex_);
    const int fd = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(file_.string(), "", std::string("cannot record the output: ") + std::strerror(errno));
    std::size_t done = 0;
    int err = 0;
    while (done < line.size()) {
        const ssize_t n = ::write(fd, line.data() + done, line.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            err = n < 0 ? errno : ENOSPC;
            break;
        }
        done += std::size_t(n);
    }
    if (!err && ::fsync(fd) != 0 && errno != EINVAL) err = errno;
    if (::close(fd) != 0 && !err) err = errno;
    if (err) {
        // A line cut short is ignored by read(), and so is nothing after it: read() parses from
        // the last start of a record on each line.
        throw Error(file_.string(), "", std::string("cannot record the output: ") + std::strerror(err));
    }
}

}  // namespace fresnel::cli
