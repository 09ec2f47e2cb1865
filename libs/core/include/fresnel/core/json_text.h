#pragma once
// A string as JSON text (quoted; quotes, backslashes and control characters escaped), for the
// registries' hand-written JSON (fresnel settings --json, --materials --json), which keep
// libraries that need no JSON parser free of one.
#include <cstdio>
#include <string>
#include <string_view>

namespace fresnel {

inline std::string json_string(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
            out += buf;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

}  // namespace fresnel
