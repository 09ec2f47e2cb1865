#include "cli_common.h"

#include <cctype>
#include <cstdio>
#include <filesystem>

namespace fresnel::cli {

void print_error(const Error& e) { std::fprintf(stderr, "fresnel: error: %s\n", e.what()); }
void print_error(const std::string& m) { std::fprintf(stderr, "fresnel: error: %s\n", m.c_str()); }

void print_warnings(const Diagnostics& d) {
    auto lines = d.lines();
    for (const auto& l : lines) std::fprintf(stderr, "fresnel: warning: %s\n", l.c_str());
    if (!lines.empty())
        std::fprintf(stderr, "fresnel: %zu warning%s (%zu unique)\n", d.total(), d.total() == 1 ? "" : "s", lines.size());
}

std::string lower_extension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

}  // namespace fresnel::cli
