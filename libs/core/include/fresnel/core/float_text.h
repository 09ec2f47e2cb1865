#pragma once
// The shortest decimal text of a float that reads back (strtof) as the same float, for
// writers whose numbers must round-trip (scene files, glTF and OBJ writers).
// std::to_chars where the standard library has its floating-point overloads; Emscripten's
// libc++ (Debian's, LLVM 14) has none, so there the shortest of printf's %.Ng forms
// (N = 1..9) that reads back is used: the same value, possibly written another way
// (1e+10 instead of 1e10).
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace fresnel {

inline std::string shortest_text(float v) {
#ifdef __EMSCRIPTEN__
    char buf[32];
    // Whole numbers as integers (10, not printf's shortest 1e+01), as std::to_chars writes them.
    if (v == float(static_cast<long long>(v)) && v > -1e9f && v < 1e9f) {
        std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(v));
        return buf;
    }
    for (int precision = 1; precision < 9; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, double(v));
        if (std::strtof(buf, nullptr) == v) return buf;
    }
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return buf;
#else
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
#endif
}

}  // namespace fresnel
