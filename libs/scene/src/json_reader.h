#pragma once
// Typed, bounds-checked reads from a glTF JSON document. Every failure throws
// fresnel::Error with the file name and the JSON pointer of the offending value.
#include <nlohmann/json.hpp>
#include <string>

#include "fresnel/core/error.h"

namespace fresnel::gltf {

using json = nlohmann::json;

class JsonReader {
public:
    explicit JsonReader(std::string file) : file_(std::move(file)) {}
    const std::string& file() const { return file_; }

    [[noreturn]] void fail(const std::string& pointer, const std::string& what) const { throw Error(file_, pointer, what); }

    static std::string at(const std::string& pointer, const std::string& key) { return pointer + "/" + key; }
    static std::string at(const std::string& pointer, std::size_t index) { return pointer + "/" + std::to_string(index); }

    // The member, or nullptr when absent (or null).
    const json* find(const json& obj, const char* key) const {
        if (!obj.is_object()) return nullptr;
        auto it = obj.find(key);
        if (it == obj.end() || it->is_null()) return nullptr;
        return &*it;
    }
    const json& object(const json& obj, const char* key, const std::string& ptr) const {
        static const json empty = json::object();
        const json* v = find(obj, key);
        if (!v) return empty;
        if (!v->is_object()) fail(at(ptr, key), "must be an object");
        return *v;
    }
    const json& array(const json& obj, const char* key, const std::string& ptr) const {
        static const json empty = json::array();
        const json* v = find(obj, key);
        if (!v) return empty;
        if (!v->is_array()) fail(at(ptr, key), "must be an array");
        return *v;
    }
    bool has(const json& obj, const char* key) const { return find(obj, key) != nullptr; }

    double number(const json& obj, const char* key, const std::string& ptr, double fallback) const {
        const json* v = find(obj, key);
        if (!v) return fallback;
        if (!v->is_number()) fail(at(ptr, key), "must be a number");
        double d = v->get<double>();
        if (!std::isfinite(d)) fail(at(ptr, key), "must be finite");
        return d;
    }
    // An integer in [lo, hi]; `required` absent values fail, others return fallback.
    long long integer(const json& obj, const char* key, const std::string& ptr, long long fallback, long long lo,
                      long long hi, bool required = false) const {
        const json* v = find(obj, key);
        if (!v) {
            if (required) fail(at(ptr, key), "is required");
            return fallback;
        }
        long long n = 0;
        if (v->is_number_integer()) {
            if (v->is_number_unsigned() && v->get<unsigned long long>() > (unsigned long long)LLONG_MAX)
                fail(at(ptr, key), "integer out of range");
            n = v->get<long long>();
        } else if (v->is_number_float()) {
            double d = v->get<double>();
            if (!(d == std::floor(d)) || std::fabs(d) > 9e15) fail(at(ptr, key), "must be an integer");
            n = (long long)d;
        } else {
            fail(at(ptr, key), "must be an integer");
        }
        if (n < lo || n > hi)
            fail(at(ptr, key), "value " + std::to_string(n) + " out of range [" + std::to_string(lo) + ", " +
                                   std::to_string(hi) + "]");
        return n;
    }
    // A JSON value (e.g. an array element) that must be an index into `count` elements.
    // Integers written as floats (1.0) are accepted, as the spec's JSON number allows.
    int index_value(const json& v, const std::string& ptr, std::size_t count, const char* what) const {
        double d = 0;
        if (v.is_number_integer() || v.is_number_float()) d = v.get<double>();
        else fail(ptr, std::string("must be an index of a ") + what);
        if (!(d == std::floor(d)) || d < 0 || d >= double(count))
            fail(ptr, std::string(what) + " " + v.dump() + " does not exist (there are " + std::to_string(count) + ")");
        return int(d);
    }
    // An index into an array of `count` elements; -1 when absent and not required.
    int index(const json& obj, const char* key, const std::string& ptr, std::size_t count, const char* what,
              bool required = false) const {
        const json* v = find(obj, key);
        if (!v) {
            if (required) fail(at(ptr, key), "is required");
            return -1;
        }
        long long n = integer(obj, key, ptr, -1, 0, LLONG_MAX);
        if (std::size_t(n) >= count)
            fail(at(ptr, key), std::string("refers to ") + what + " " + std::to_string(n) + ", but there are only " +
                                   std::to_string(count));
        return int(n);
    }
    std::string string(const json& obj, const char* key, const std::string& ptr, const std::string& fallback = "") const {
        const json* v = find(obj, key);
        if (!v) return fallback;
        if (!v->is_string()) fail(at(ptr, key), "must be a string");
        return v->get<std::string>();
    }
    bool boolean(const json& obj, const char* key, const std::string& ptr, bool fallback) const {
        const json* v = find(obj, key);
        if (!v) return fallback;
        if (!v->is_boolean()) fail(at(ptr, key), "must be a boolean");
        return v->get<bool>();
    }
    // A fixed-size numeric array.
    template <std::size_t N>
    std::array<double, N> numbers(const json& obj, const char* key, const std::string& ptr,
                                  const std::array<double, N>& fallback) const {
        const json* v = find(obj, key);
        if (!v) return fallback;
        if (!v->is_array() || v->size() != N) fail(at(ptr, key), "must be an array of " + std::to_string(N) + " numbers");
        std::array<double, N> out{};
        for (std::size_t i = 0; i < N; ++i) {
            if (!(*v)[i].is_number()) fail(at(at(ptr, key), i), "must be a number");
            out[i] = (*v)[i].get<double>();
            if (!std::isfinite(out[i])) fail(at(at(ptr, key), i), "must be finite");
        }
        return out;
    }

private:
    std::string file_;
};

}  // namespace fresnel::gltf
