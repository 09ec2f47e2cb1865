#include "fresnel/core/spelling.h"

#include <algorithm>
#include <cctype>

namespace fresnel {

std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
    auto lower = [](std::string s) {
        for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    const std::string w = lower(word);
    std::string best;
    std::size_t best_d = std::max<std::size_t>(2, w.size() / 3) + 1;
    std::vector<std::size_t> row;
    for (const std::string& name : names) {
        const std::string n = lower(name);
        if (n == w) return name;
        row.resize(n.size() + 1);
        for (std::size_t j = 0; j <= n.size(); ++j) row[j] = j;
        for (std::size_t i = 1; i <= w.size(); ++i) {
            std::size_t diag = row[0];
            row[0] = i;
            for (std::size_t j = 1; j <= n.size(); ++j) {
                const std::size_t up = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (w[i - 1] == n[j - 1] ? 0 : 1)});
                diag = up;
            }
        }
        if (row[n.size()] < best_d) best_d = row[n.size()], best = name;
    }
    return best;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& names) {
    const std::string near = nearest_name(word, names);
    return near.empty() ? std::string() : " (did you mean '" + near + "'?)";
}

}  // namespace fresnel
