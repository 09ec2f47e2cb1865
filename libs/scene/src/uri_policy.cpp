#include "uri_policy.h"

#include <cctype>

namespace fresnel::gltf {
namespace fs = std::filesystem;

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

namespace {
int base64_value(unsigned char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+' || c == '-') return 62;
    if (c == '/' || c == '_') return 63;
    return -1;
}
int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}
}  // namespace

std::string percent_decode(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size() && hex_value(s[i + 1]) >= 0 && hex_value(s[i + 2]) >= 0) {
            out += char(hex_value(s[i + 1]) * 16 + hex_value(s[i + 2]));
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

std::optional<std::vector<std::uint8_t>> decode_data_uri(const std::string& uri, std::size_t max_bytes,
                                                         std::string& mime, std::string& error) {
    auto comma = uri.find(',');
    if (comma == std::string::npos) {
        error = "data URI has no ',' separator";
        return std::nullopt;
    }
    std::string header = uri.substr(5, comma - 5);
    bool base64 = header.size() >= 7 && header.compare(header.size() - 7, 7, ";base64") == 0;
    mime = base64 ? header.substr(0, header.size() - 7) : header;
    std::size_t payload = uri.size() - comma - 1;
    if ((base64 ? payload / 4 * 3 : payload) > max_bytes) {
        error = "data URI holds more than the limit of " + std::to_string(max_bytes) + " bytes";
        return std::nullopt;
    }
    std::vector<std::uint8_t> out;
    if (!base64) {
        std::string s = percent_decode(uri.substr(comma + 1));
        out.assign(s.begin(), s.end());
        return out;
    }
    out.reserve(payload / 4 * 3 + 3);
    unsigned acc = 0;
    int bits = 0;
    for (std::size_t i = comma + 1; i < uri.size(); ++i) {
        unsigned char c = static_cast<unsigned char>(uri[i]);
        if (c == '=') break;
        if (std::isspace(c)) continue;
        int v = base64_value(c);
        if (v < 0) {
            error = "data URI has an invalid base64 character at position " + std::to_string(i);
            return std::nullopt;
        }
        acc = (acc << 6) | unsigned(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(std::uint8_t((acc >> bits) & 0xFF));
        }
    }
    return out;
}

std::optional<fs::path> resolve_uri(const std::string& uri, const fs::path& base_dir, bool allow_external,
                                    std::string& error) {
    if (uri.empty()) {
        error = "empty URI";
        return std::nullopt;
    }
    // A scheme is letters followed by ':' (RFC 3986). Single letters are Windows drives: treat as absolute.
    std::size_t colon = uri.find(':');
    if (colon != std::string::npos && colon > 1) {
        bool scheme = std::isalpha(static_cast<unsigned char>(uri[0]));
        for (std::size_t i = 1; i < colon && scheme; ++i) {
            char c = uri[i];
            scheme = std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
        }
        if (scheme) {
            error = "URI '" + uri + "' uses the '" + uri.substr(0, colon) +
                    ":' scheme; only relative file paths and data URIs are read (never the network)";
            return std::nullopt;
        }
    }
    std::string decoded = percent_decode(uri);
    if (decoded.find('\0') != std::string::npos) {
        error = "URI '" + uri + "' contains a NUL byte";
        return std::nullopt;
    }
    fs::path p(decoded);
    bool absolute = p.is_absolute() || (colon == 1);
    if (absolute) {
        if (!allow_external) {
            error = "URI '" + uri + "' is an absolute path; refused (use --allow-external-files to permit it)";
            return std::nullopt;
        }
        return p;
    }
    std::error_code ec;
    fs::path base = fs::weakly_canonical(base_dir.empty() ? fs::path(".") : base_dir, ec);
    fs::path full = fs::weakly_canonical(base / p, ec);
    if (ec) full = (base / p).lexically_normal();
    if (!allow_external) {
        auto rel = full.lexically_relative(base);
        if (rel.empty() || *rel.begin() == "..") {
            error = "URI '" + uri + "' points outside the model's folder; refused (use --allow-external-files to permit it)";
            return std::nullopt;
        }
    }
    return full;
}

std::optional<fs::path> resolve_model_path(const std::string& path, const fs::path& base_dir, const fs::path& root_dir,
                                           bool allow_external, std::string& error) {
    if (path.empty()) {
        error = "empty path";
        return std::nullopt;
    }
    if (path.find('\0') != std::string::npos) {
        error = "path '" + path + "' contains a NUL byte";
        return std::nullopt;
    }
    std::string text = path;
    for (char& c : text)
        if (c == '\\') c = '/';
    std::size_t colon = text.find(':');
    if (colon != std::string::npos && colon > 1) {
        bool scheme = std::isalpha(static_cast<unsigned char>(text[0]));
        for (std::size_t i = 1; i < colon && scheme; ++i) {
            char c = text[i];
            scheme = std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
        }
        if (scheme) {
            error = "path '" + path + "' uses the '" + text.substr(0, colon) +
                    ":' scheme; only relative file paths are read (never the network)";
            return std::nullopt;
        }
    }
    fs::path p(text);
    if (p.is_absolute() || colon == 1) {
        if (!allow_external) {
            error = "path '" + path + "' is absolute; refused (use --allow-external-files to permit it)";
            return std::nullopt;
        }
        return p;
    }
    std::error_code ec;
    fs::path root = fs::weakly_canonical(root_dir.empty() ? fs::path(".") : root_dir, ec);
    fs::path base = fs::weakly_canonical(base_dir.empty() ? fs::path(".") : base_dir, ec);
    fs::path full = fs::weakly_canonical(base / p, ec);
    if (ec) full = (base / p).lexically_normal();
    if (!allow_external) {
        auto rel = full.lexically_relative(root);
        if (rel.empty() || *rel.begin() == "..") {
            error = "path '" + path + "' points outside the model's folder; refused (use --allow-external-files to permit it)";
            return std::nullopt;
        }
    }
    return full;
}

}  // namespace fresnel::gltf
