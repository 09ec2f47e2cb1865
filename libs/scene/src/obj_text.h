#pragma once
// Line and number reading shared by the OBJ and MTL parsers: logical lines (with '\'
// continuations and their first physical line number), whitespace tokens, numbers in the
// forms OBJ writers produce ("+1", "2.", "1e+2"), and names made safe for messages.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fresnel/core/error.h"

namespace fresnel::obj {

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

inline std::string_view trim(std::string_view s) {
    while (!s.empty() && (is_space(s.front()) || s.front() == '\0')) s.remove_prefix(1);
    while (!s.empty() && (is_space(s.back()) || s.back() == '\0')) s.remove_suffix(1);
    return s;
}

// Reads logical lines: a line whose last non-blank character is '\' continues on the next.
class LineReader {
public:
    explicit LineReader(std::string_view text) : text_(text) {
        if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);  // a UTF-8 byte order mark
    }
    // The next logical line (comments not removed) and the number of its first physical line.
    bool next(std::string_view& line, int& number) {
        if (pos_ >= text_.size()) return false;
        number = line_ + 1;
        joined_.clear();
        bool continued = false;
        while (pos_ < text_.size()) {
            std::size_t end = text_.find('\n', pos_);
            if (end == std::string_view::npos) end = text_.size();
            std::string_view physical = text_.substr(pos_, end - pos_);
            pos_ = end + 1;
            ++line_;
            std::string_view t = trim(physical);
            bool more = !t.empty() && t.back() == '\\' && pos_ < text_.size();
            if (more) t.remove_suffix(1);
            if (!more && !continued) {
                line = physical;
                return true;
            }
            joined_.append(t.data(), t.size());
            joined_ += ' ';
            continued = true;
            if (!more) break;
        }
        line = joined_;
        return true;
    }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
    int line_ = 0;
    std::string joined_;
};

// Splits at blanks; a token starting with '#' ends the line (a trailing comment).
inline void tokenize(std::string_view line, std::vector<std::string_view>& out) {
    out.clear();
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (is_space(line[i]) || line[i] == '\0')) ++i;
        if (i >= line.size()) break;
        if (line[i] == '#') break;
        std::size_t j = i;
        while (j < line.size() && !is_space(line[j]) && line[j] != '\0') ++j;
        out.push_back(line.substr(i, j - i));
        i = j;
    }
}

// The text after the keyword (names, paths): trimmed, trailing "# comment" kept (names may
// hold '#'), blanks inside kept.
inline std::string_view rest_after(std::string_view line, std::string_view keyword) {
    std::string_view t = trim(line);
    t.remove_prefix(std::min(t.size(), keyword.size()));
    return trim(t);
}

// std::from_chars for double; libc++ before 17 (the web build's, Emscripten 3.1.6) has none,
// so there it is strtod on a copy, limited to what from_chars takes (no leading blanks, no hex).
inline std::from_chars_result from_chars_double(const char* first, const char* last, double& v) {
#if defined(_LIBCPP_VERSION) && _LIBCPP_VERSION < 170000
    std::string copy(first, last);
    if (copy.empty()) return {first, std::errc::invalid_argument};
    std::size_t digits = copy[0] == '-' ? 1 : 0;
    if (std::isspace(static_cast<unsigned char>(copy[0])) || copy[0] == '+')
        return {first, std::errc::invalid_argument};
    if (copy.size() > digits + 1 && copy[digits] == '0' && (copy[digits + 1] == 'x' || copy[digits + 1] == 'X'))
        copy.resize(digits + 1);  // from_chars reads the "0" of "0x..." and stops
    errno = 0;
    char* end = nullptr;
    double r = std::strtod(copy.c_str(), &end);
    if (end == copy.c_str()) return {first, std::errc::invalid_argument};
    const char* ptr = first + (end - copy.c_str());
    if (errno == ERANGE) return {ptr, std::errc::result_out_of_range};
    v = r;
    return {ptr, std::errc()};
#else
    return std::from_chars(first, last, v);
#endif
}

// A number; `partial` is set when only a prefix of the token is a number ("3.1+e2" -> 3.1).
// Non-finite results (nan, inf, 1e999) are returned as such for the caller to judge.
inline std::optional<double> parse_number(std::string_view s, bool& partial) {
    partial = false;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    if (s.empty()) return std::nullopt;
    double v = 0.0;
    auto [ptr, ec] = from_chars_double(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::result_out_of_range) {
        // Overflow or underflow: tell them apart by the exponent's sign.
        bool negative = s.front() == '-';
        std::size_t e = s.find_first_of("eE");
        bool tiny = e != std::string_view::npos && e + 1 < s.size() && s[e + 1] == '-';
        v = tiny ? 0.0 : (negative ? -1.0 : 1.0) * 1e308 * 10.0;
        return v;
    }
    if (ec != std::errc()) return std::nullopt;
    partial = ptr != s.data() + s.size();
    return v;
}

inline std::optional<long long> parse_integer(std::string_view s) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    if (s.empty()) return std::nullopt;
    long long v = 0;
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
    return v;
}

// Valid UTF-8 is kept; any other byte becomes '?', so names can go into messages and JSON.
inline std::string printable(std::string_view s, std::size_t max_length = 200) {
    std::string out;
    std::size_t i = 0;
    while (i < s.size() && out.size() < max_length) {
        unsigned char c = static_cast<unsigned char>(s[i]);
        int extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
        bool ok = extra >= 0 && i + std::size_t(extra < 0 ? 0 : extra) < s.size();
        for (int k = 1; ok && k <= extra; ++k) ok = (static_cast<unsigned char>(s[i + std::size_t(k)]) >> 6) == 0x2;
        if (ok && extra == 0 && (c < 0x20 || c == 0x7F)) ok = false;
        if (!ok) {
            out += '?';
            ++i;
            continue;
        }
        out.append(s.data() + i, std::size_t(extra) + 1);
        i += std::size_t(extra) + 1;
    }
    if (i < s.size()) out += "...";
    return out;
}

// Lower-case ASCII copy (MTL keywords are matched without case: Kd, kd, map_Bump, map_bump).
inline std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    return out;
}

// A text file's warnings, as the OBJ and MTL parsers give them: at most 64 of their own (the
// rest counted in one), and kinds that may repeat on every line collapsed into one at their
// first line with a count ("(N <unit>)"), passed on by flush().
class LineWarnings {
public:
    LineWarnings(std::string file, Diagnostics& diag, std::string unit)
        : file_(std::move(file)), diag_(diag), unit_(std::move(unit)) {}
    // `line` 0: the file as a whole (no place).
    void warn(int line, const std::string& message) {
        if (warned_++ < 64) diag_.warn(file_, line > 0 ? "line " + std::to_string(line) : "", message);
        else once(line, "more", "more warnings of this file not shown");
    }
    void once(int line, const std::string& kind, const std::string& message) {
        Once& o = once_[kind];
        if (o.count++ == 0) {
            o.first_line = line;
            o.message = message;
        }
    }
    void flush() {
        for (const auto& [kind, w] : once_)
            diag_.warn(file_, "line " + std::to_string(w.first_line),
                       w.message + (w.count > 1 ? " (" + std::to_string(w.count) + " " + unit_ + ")" : ""));
        once_.clear();
    }

private:
    struct Once {
        int first_line = 0;
        std::size_t count = 0;
        std::string message;
    };
    std::string file_;
    Diagnostics& diag_;
    std::string unit_;
    std::map<std::string, Once> once_;
    std::size_t warned_ = 0;
};

}  // namespace fresnel::obj
