#pragma once
// Small glTF files that tests write from scratch: base64 for data URIs, and a UV sphere with
// its buffer embedded, for suites that need a model whose every pixel they can predict.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace fresnel::test {

// Standard base64 with '=' padding (RFC 4648), as glTF data URIs carry their bytes.
inline std::string base64(std::string_view bytes) {
    static const char* tbl = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= std::uint8_t(bytes[i + 2]);
        out += tbl[(v >> 18) & 63];
        out += tbl[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? tbl[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? tbl[v & 63] : '=';
    }
    return out;
}
inline std::string base64(const std::vector<std::uint8_t>& bytes) {
    return base64(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// A UV sphere of radius 1 (normals = positions; `segments` around, `rings` from pole to pole)
// as a glTF document with its buffer in a data URI: one node at `translation`, one mesh, one
// material (`material`, a glTF material object).
inline nlohmann::json uv_sphere_gltf(int segments, int rings, const nlohmann::json& material,
                                     glm::vec3 translation = glm::vec3(0.0f)) {
    std::vector<float> pos;
    std::vector<std::uint32_t> idx;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            double th = pi * i / rings, ph = 2 * pi * j / segments;
            pos.insert(pos.end(), {float(std::sin(th) * std::sin(ph)), float(std::cos(th)), float(std::sin(th) * std::cos(ph))});
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            std::uint32_t a = std::uint32_t(i * (segments + 1) + j), c = a + std::uint32_t(segments) + 1;
            idx.insert(idx.end(), {a, c, a + 1, a + 1, c, c + 1});
        }
    std::string buf(reinterpret_cast<const char*>(pos.data()), pos.size() * 4);
    const std::size_t pos_bytes = buf.size();
    buf.append(reinterpret_cast<const char*>(pos.data()), pos.size() * 4);  // normals = positions
    buf.append(reinterpret_cast<const char*>(idx.data()), idx.size() * 4);
    const std::size_t count = pos.size() / 3;
    return {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}, {"translation", {translation.x, translation.y, translation.z}}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
        {"materials", {material}},
        {"buffers", {{{"byteLength", buf.size()}, {"uri", "data:application/octet-stream;base64," + base64(buf)}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos_bytes}},
                         {{"buffer", 0}, {"byteOffset", pos_bytes}, {"byteLength", pos_bytes}},
                         {{"buffer", 0}, {"byteOffset", 2 * pos_bytes}, {"byteLength", idx.size() * 4}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", count}, {"type", "VEC3"}, {"min", {-1, -1, -1}}, {"max", {1, 1, 1}}},
                       {{"bufferView", 1}, {"componentType", 5126}, {"count", count}, {"type", "VEC3"}},
                       {{"bufferView", 2}, {"componentType", 5125}, {"count", idx.size()}, {"type", "SCALAR"}}}},
    };
}

}  // namespace fresnel::test
