#pragma once
// What the CLI tests share: a program's result, shell quoting for the command line they run,
// and reading a file whole.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fresnel::test {

struct Result {
    int exit_code = -1;
    std::string out, err;
};

// `s` in single quotes for /bin/sh.
inline std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace fresnel::test
