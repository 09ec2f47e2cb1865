#pragma once
// One error type for every bad input: it names the file, where in the file
// (a JSON pointer such as /accessors/3/byteOffset, or "byte 1234"), and what is wrong.
#include <cstddef>
#include <functional>
#include <map>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace fresnel {

class Error : public std::runtime_error {
public:
    Error(std::string file, std::string where, std::string what);
    const std::string& file() const { return file_; }
    const std::string& where() const { return where_; }
    const std::string& reason() const { return reason_; }

private:
    std::string file_, where_, reason_;
};

// Runs `load` and returns what it returns. What it throws leaves as a fresnel::Error naming
// `file`: an Error as it is, std::bad_alloc as "out of memory while loading", any other
// exception with its message; so a loader's callers catch one type.
template <class Load>
auto as_file_error(const std::string& file, Load&& load) -> decltype(load()) {
    try {
        return load();
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw Error(file, "", "out of memory while loading");
    } catch (const std::exception& e) {
        throw Error(file, "", e.what());
    }
}

struct Warning {
    std::string file, where, message;
    std::string text() const;
};

// Collects warnings; each distinct message is kept once with a repeat count,
// so a model with a million bad normals prints one line, not a million.
class Diagnostics {
public:
    // At most this many unique warnings are kept (each with its count); past them a warning is
    // only counted (suppressed()), so a hostile file with a million bad keys costs a counter,
    // not a million strings.
    static constexpr std::size_t kMaxUnique = 200;
    void warn(const std::string& file, const std::string& where, const std::string& message);
    // Unique warnings in the order they were first seen.
    const std::vector<Warning>& warnings() const { return warnings_; }
    std::size_t count(std::size_t index) const { return counts_[index]; }
    std::size_t total() const;  // every warning given, the suppressed ones included
    std::size_t suppressed() const { return suppressed_; }
    // "text (xN)" lines, one per unique warning kept, then "N more warnings not shown" when any
    // were suppressed.
    std::vector<std::string> lines() const;

private:
    std::size_t suppressed_ = 0;
    std::vector<Warning> warnings_;
    std::vector<std::size_t> counts_;
    std::map<std::string, std::size_t> index_;
};

}  // namespace fresnel
