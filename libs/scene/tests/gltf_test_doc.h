#pragma once
// glTF documents built in tests: nlohmann::json plus one binary buffer, written as a data-URI
// .gltf or as GLB bytes (Doc), and the helpers the glTF loader tests share (load, load_error,
// warnings, temporary folders, a small PNG). Header-only, for the scene tests.
#include "fresnel/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fresnel/core/image.h"
#include "gltf_builders.h"
#include "temp_dir.h"

namespace fresnel::gltf_test {


using json = nlohmann::json;
namespace fs = std::filesystem;


constexpr double kPi = 3.14159265358979323846;
constexpr int BYTE = 5120, UNSIGNED_BYTE = 5121, SHORT = 5122, UNSIGNED_SHORT = 5123, UNSIGNED_INT = 5125,
              FLOAT = 5126;

inline int component_size(int ctype) {
    switch (ctype) {
        case BYTE: case UNSIGNED_BYTE: return 1;
        case SHORT: case UNSIGNED_SHORT: return 2;
        default: return 4;
    }
}

inline int type_components(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    return 4;  // VEC4
}

// Writes one component of type `ctype` (values are cast, NaN/inf allowed for FLOAT).
inline void put_component(std::vector<std::uint8_t>& out, std::size_t at, int ctype, double v) {
    switch (ctype) {
        case BYTE: { std::int8_t x = std::int8_t(v); std::memcpy(&out[at], &x, 1); break; }
        case UNSIGNED_BYTE: { std::uint8_t x = std::uint8_t(v); std::memcpy(&out[at], &x, 1); break; }
        case SHORT: { std::int16_t x = std::int16_t(v); std::memcpy(&out[at], &x, 2); break; }
        case UNSIGNED_SHORT: { std::uint16_t x = std::uint16_t(v); std::memcpy(&out[at], &x, 2); break; }
        case UNSIGNED_INT: { std::uint32_t x = std::uint32_t(v); std::memcpy(&out[at], &x, 4); break; }
        default: { float x = float(v); std::memcpy(&out[at], &x, 4); break; }
    }
}

// Packs `values` (count * comps) as `ctype` elements `stride` bytes apart (0 = tightly packed).
inline std::vector<std::uint8_t> pack(int ctype, int comps, const std::vector<double>& values, std::size_t stride = 0) {
    std::size_t cs = std::size_t(component_size(ctype)), elem = cs * std::size_t(comps);
    if (stride == 0) stride = elem;
    std::size_t count = values.size() / std::size_t(comps);
    std::vector<std::uint8_t> out(stride * (count - 1) + elem, 0);
    for (std::size_t i = 0; i < count; ++i)
        for (int c = 0; c < comps; ++c) put_component(out, i * stride + std::size_t(c) * cs, ctype, values[i * std::size_t(comps) + std::size_t(c)]);
    return out;
}

using fresnel::test::base64;


inline void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
}

// A glTF document under construction with one binary buffer.
struct Doc {
    json j = {{"asset", {{"version", "2.0"}}}};
    std::vector<std::uint8_t> bin;

    // Appends bytes (4-byte aligned) as a new bufferView; returns its index.
    int view(const std::vector<std::uint8_t>& bytes, std::size_t stride = 0) {
        while (bin.size() % 4) bin.push_back(0);
        json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}};
        if (stride) v["byteStride"] = stride;
        bin.insert(bin.end(), bytes.begin(), bytes.end());
        j["bufferViews"].push_back(v);
        return int(j["bufferViews"].size()) - 1;
    }
    int add_accessor(json a) {
        j["accessors"].push_back(std::move(a));
        return int(j["accessors"].size()) - 1;
    }
    // A vertex attribute accessor in its own bufferView; elements padded to 4 bytes as glTF requires.
    int attribute(int ctype, const std::string& type, const std::vector<double>& values, bool normalized = false) {
        int comps = type_components(type);
        std::size_t elem = std::size_t(component_size(ctype) * comps);
        std::size_t stride = (elem + 3) & ~std::size_t(3);
        int v = view(pack(ctype, comps, values, stride), stride != elem ? stride : 0);
        json a = {{"bufferView", v}, {"componentType", ctype}, {"count", values.size() / std::size_t(comps)}, {"type", type}};
        if (normalized) a["normalized"] = true;
        return add_accessor(a);
    }
    int positions(const std::vector<glm::vec3>& p) {
        std::vector<double> v;
        for (auto& x : p) v.insert(v.end(), {x.x, x.y, x.z});
        return attribute(FLOAT, "VEC3", v);
    }
    int normals(std::size_t count, glm::vec3 n = glm::vec3(0, 0, 1)) {
        std::vector<double> v;
        for (std::size_t i = 0; i < count; ++i) v.insert(v.end(), {n.x, n.y, n.z});
        return attribute(FLOAT, "VEC3", v);
    }
    int indices(int ctype, const std::vector<double>& idx) {
        int v = view(pack(ctype, 1, idx));
        return add_accessor({{"bufferView", v}, {"componentType", ctype}, {"count", idx.size()}, {"type", "SCALAR"}});
    }
    // Adds a mesh with the given primitives, a node using it, and makes sure a scene lists the node.
    int mesh(json primitives) {
        if (!primitives.is_array()) primitives = json::array({primitives});
        j["meshes"].push_back({{"primitives", primitives}});
        int m = int(j["meshes"].size()) - 1;
        j["nodes"].push_back({{"mesh", m}});
        int n = int(j["nodes"].size()) - 1;
        if (!j.contains("scenes")) j["scenes"] = json::array({{{"nodes", json::array()}}});
        j["scenes"][0]["nodes"].push_back(n);
        return m;
    }
    json with_buffer_uri(const std::string& uri) const {
        json d = j;
        if (!bin.empty() || !uri.empty()) d["buffers"] = json::array({{{"uri", uri}, {"byteLength", bin.size()}}});
        return d;
    }
    std::string data_uri() const { return "data:application/octet-stream;base64," + base64(bin); }
    std::vector<std::uint8_t> gltf() const {
        json d = bin.empty() ? j : with_buffer_uri(data_uri());
        std::string s = d.dump();
        return {s.begin(), s.end()};
    }
    std::vector<std::uint8_t> glb() const {
        json d = j;
        if (!bin.empty()) d["buffers"] = json::array({{{"byteLength", bin.size()}}});
        std::string text = d.dump();
        while (text.size() % 4) text += ' ';
        std::vector<std::uint8_t> b = bin;
        while (b.size() % 4) b.push_back(0);
        std::size_t total = 12 + 8 + text.size() + (b.empty() ? 0 : 8 + b.size());
        std::vector<std::uint8_t> out;
        put_u32(out, 0x46546C67);  // "glTF"
        put_u32(out, 2);
        put_u32(out, std::uint32_t(total));
        put_u32(out, std::uint32_t(text.size()));
        put_u32(out, 0x4E4F534A);  // JSON
        out.insert(out.end(), text.begin(), text.end());
        if (!b.empty()) {
            put_u32(out, std::uint32_t(b.size()));
            put_u32(out, 0x004E4942);  // BIN
            out.insert(out.end(), b.begin(), b.end());
        }
        return out;
    }
};

inline std::vector<std::uint8_t> bytes_of(const json& d) {
    std::string s = d.dump();
    return {s.begin(), s.end()};
}

inline Scene load(const std::vector<std::uint8_t>& bytes, Diagnostics& diag, const GltfLoadOptions& opt = {},
           const fs::path& base = fs::temp_directory_path()) {
    return load_gltf_from_memory(bytes, "test.gltf", base, diag, opt);
}
inline Scene load(const std::vector<std::uint8_t>& bytes) {
    Diagnostics diag;
    return load(bytes, diag);
}

// Loads and returns the fresnel::Error; records a failure when none (or another type) is thrown.
inline Error load_error(const std::vector<std::uint8_t>& bytes, const GltfLoadOptions& opt = {},
                 const fs::path& base = fs::temp_directory_path()) {
    Diagnostics diag;
    try {
        load(bytes, diag, opt, base);
    } catch (const Error& e) {
        return e;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw a non-fresnel exception: " << e.what();
        return Error("", "<other exception>", e.what());
    }
    ADD_FAILURE() << "loaded without an error";
    return Error("", "<no error>", "");
}

inline bool has_warning(const Diagnostics& d, const std::string& where, const std::string& text) {
    for (const auto& w : d.warnings())
        if (w.where == where && w.message.find(text) != std::string::npos) return true;
    return false;
}
inline std::string all_warnings(const Diagnostics& d) {
    std::string s;
    for (const auto& l : d.lines()) s += "\n  " + l;
    return s;
}

// Triangle (a, b, c) equals (x, y, z) up to a cyclic rotation (same winding).
inline bool same_triangle(const std::uint32_t* t, std::array<std::uint32_t, 3> want) {
    for (int r = 0; r < 3; ++r)
        if (t[0] == want[std::size_t(r)] && t[1] == want[std::size_t((r + 1) % 3)] && t[2] == want[std::size_t((r + 2) % 3)])
            return true;
    return false;
}

// The corner positions of every triangle, in order, whether the primitive is indexed or not.
inline std::vector<glm::vec3> triangle_corners(const Primitive& p) {
    std::vector<glm::vec3> out;
    if (p.indices.empty()) {
        out.assign(p.positions.begin(), p.positions.begin() + std::ptrdiff_t(p.positions.size() / 3 * 3));
    } else {
        for (auto i : p.indices) out.push_back(p.positions.at(i));
    }
    return out;
}

inline void expect_mat_near(const glm::mat4& a, const glm::mat4& b, float tol = 1e-5f, const std::string& what = "") {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << what << " column " << c << " row " << r;
}

using fresnel::test::TempDir;  // tests/support/temp_dir.h

inline void write_file(const fs::path& p, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A small RGBA PNG (encoded by fresnel::write_png) and its pixels.
inline std::vector<std::uint8_t> make_png(int w, int h, Image8* pixels_out = nullptr) {
    Image8 img(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = img.at(x, y);
            p[0] = std::uint8_t(x * 60), p[1] = std::uint8_t(y * 60), p[2] = std::uint8_t(128), p[3] = 255;
        }
    TempDir dir;
    fs::path p = dir.path() / "tex.png";
    write_png(p, img);
    if (pixels_out) *pixels_out = img;
    return read_file_bytes(p, 1 << 20);
}

inline const std::vector<glm::vec3> kTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
inline const std::vector<glm::vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

inline std::string shared_dir() { return FRESNEL_SHARED_DIR; }

}  // namespace fresnel::gltf_test
