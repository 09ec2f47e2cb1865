#include "fresnel/core/error.h"

namespace fresnel {
namespace {
std::string join(const std::string& file, const std::string& where, const std::string& what) {
    std::string s;
    if (!file.empty()) s += file + ": ";
    if (!where.empty()) s += where + ": ";
    return s + what;
}
}  // namespace

Error::Error(std::string file, std::string where, std::string what)
    : std::runtime_error(join(file, where, what)), file_(std::move(file)), where_(std::move(where)),
      reason_(std::move(what)) {}

std::string Warning::text() const { return join(file, where, message); }

void Diagnostics::warn(const std::string& file, const std::string& where, const std::string& message) {
    Warning w{file, where, message};
    std::string key = w.text();
    auto it = index_.find(key);
    if (it != index_.end()) {
        ++counts_[it->second];
        return;
    }
    if (warnings_.size() >= kMaxUnique) {
        ++suppressed_;
        return;
    }
    index_.emplace(key, warnings_.size());
    warnings_.push_back(std::move(w));
    counts_.push_back(1);
}

std::size_t Diagnostics::total() const {
    std::size_t n = suppressed_;
    for (auto c : counts_) n += c;
    return n;
}

std::vector<std::string> Diagnostics::lines() const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < warnings_.size(); ++i) {
        std::string s = warnings_[i].text();
        if (counts_[i] > 1) s += " (x" + std::to_string(counts_[i]) + ")";
        out.push_back(std::move(s));
    }
    if (suppressed_ > 0)
        out.push_back(std::to_string(suppressed_) + " more warnings not shown (past " + std::to_string(kMaxUnique) +
                      " different ones)");
    return out;
}

}  // namespace fresnel
