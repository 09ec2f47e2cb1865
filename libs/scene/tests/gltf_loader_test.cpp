// Tests of the glTF 2.0 loader on documents built in the test (nlohmann::json plus a
// base64 data-URI buffer, or GLB bytes assembled in memory), and on the shared sample
// models when ../shared is present.
#include "fresnel/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "fresnel/core/image.h"

#include "gltf_test_doc.h"

using namespace fresnel;
using namespace fresnel::gltf_test;
using json = nlohmann::json;
namespace fs = std::filesystem;

// =============================================================================================
// Accessors: component types, normalisation, strides, sparse

namespace {
struct ComponentCase {
    int ctype;
    bool normalized;
    std::vector<double> raw;  // 3 vertices x 3 components
};
double dequantize(int ctype, bool normalized, double v) {
    if (!normalized) return v;
    switch (ctype) {
        case BYTE: return std::max(v / 127.0, -1.0);
        case UNSIGNED_BYTE: return v / 255.0;
        case SHORT: return std::max(v / 32767.0, -1.0);
        case UNSIGNED_SHORT: return v / 65535.0;
    }
    return v;
}
}  // namespace

TEST(GltfAccessors, PositionEveryComponentType) {
    // Non-normalized and normalized integer positions (KHR_mesh_quantization) and floats.
    const ComponentCase cases[] = {
        {BYTE, false, {-128, 127, 5, -1, 0, 64, 100, -100, 3}},
        {BYTE, true, {-128, 127, 5, -127, 0, 64, 100, -100, 3}},
        {UNSIGNED_BYTE, false, {255, 0, 7, 128, 1, 200, 3, 4, 5}},
        {UNSIGNED_BYTE, true, {255, 0, 7, 128, 1, 200, 3, 4, 5}},
        {SHORT, false, {-32768, 32767, 1000, -5, 0, 12345, 7, -7, 300}},
        {SHORT, true, {-32768, 32767, 1000, -5, 0, 12345, 7, -7, 300}},
        {UNSIGNED_SHORT, false, {65535, 0, 1, 40000, 2, 3, 4, 5, 6}},
        {UNSIGNED_SHORT, true, {65535, 0, 1, 40000, 2, 3, 4, 5, 6}},
        {FLOAT, false, {0.5, -1.25, 3e5, 1e-3, 2.0, -7.0, 0.0, 0.25, 9.5}},
    };
    for (const auto& tc : cases) {
        Doc doc;
        if (tc.ctype != FLOAT) doc.j["extensionsUsed"] = {"KHR_mesh_quantization"};
        int pos = doc.attribute(tc.ctype, "VEC3", tc.raw, tc.normalized);
        doc.mesh({{"attributes", {{"POSITION", pos}}}});
        Scene s = load(doc.gltf());
        ASSERT_EQ(s.meshes.size(), 1u);
        ASSERT_EQ(s.meshes[0].primitives.size(), 1u) << "ctype " << tc.ctype;
        const Primitive& p = s.meshes[0].primitives[0];
        ASSERT_EQ(p.positions.size(), 3u);
        EXPECT_EQ(p.source_vertex_count, 3u);
        for (int i = 0; i < 3; ++i)
            for (int c = 0; c < 3; ++c)
                EXPECT_FLOAT_EQ(p.positions[std::size_t(i)][c], float(dequantize(tc.ctype, tc.normalized, tc.raw[std::size_t(i * 3 + c)])))
                    << "ctype " << tc.ctype << " normalized " << tc.normalized << " vertex " << i << " component " << c;
        // Bounds come from the data.
        for (int c = 0; c < 3; ++c) {
            float lo = std::numeric_limits<float>::max(), hi = -lo;
            for (int i = 0; i < 3; ++i) {
                lo = std::min(lo, p.positions[std::size_t(i)][c]);
                hi = std::max(hi, p.positions[std::size_t(i)][c]);
            }
            EXPECT_EQ(p.bounds_min[c], lo);
            EXPECT_EQ(p.bounds_max[c], hi);
        }
    }
}

TEST(GltfAccessors, NormalizedIntegerTexcoords) {
    struct Case {
        int ctype;
        std::vector<double> raw;  // 3 x VEC2
    };
    const Case cases[] = {
        {UNSIGNED_BYTE, {255, 0, 51, 128, 1, 254}},
        {UNSIGNED_SHORT, {65535, 0, 13107, 32768, 1, 65534}},
        {BYTE, {127, -128, -127, 64, 0, 1}},
        {SHORT, {32767, -32768, -32767, 16384, 0, 1}},
    };
    for (const auto& tc : cases) {
        Doc doc;
        int pos = doc.positions(kTriangle);
        int uv0 = doc.attribute(tc.ctype, "VEC2", tc.raw, true);
        int uv1 = doc.attribute(FLOAT, "VEC2", {0.25, 0.5, -1.5, 2.0, 1e-3, 0.0});
        doc.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}}}});
        Scene s = load(doc.gltf());
        const Primitive& p = s.meshes.at(0).primitives.at(0);
        ASSERT_EQ(p.uv0.size(), 3u);
        ASSERT_EQ(p.uv1.size(), 3u);
        for (int i = 0; i < 3; ++i)
            for (int c = 0; c < 2; ++c)
                EXPECT_FLOAT_EQ(p.uv0[std::size_t(i)][c], float(dequantize(tc.ctype, true, tc.raw[std::size_t(i * 2 + c)])))
                    << "ctype " << tc.ctype << " vertex " << i << " component " << c;
        EXPECT_FLOAT_EQ(p.uv1[1].x, -1.5f);
        EXPECT_FLOAT_EQ(p.uv1[1].y, 2.0f);
    }
    // The exact published conversions at the extremes.
    EXPECT_EQ(float(dequantize(UNSIGNED_BYTE, true, 255)), 1.0f);
    EXPECT_EQ(float(dequantize(BYTE, true, -128)), -1.0f);
}

TEST(GltfAccessors, NonNormalizedIntegerTexcoordIsAnError) {
    // Core glTF: TEXCOORD_n is float or normalized unsigned byte/short.
    Doc doc;
    int pos = doc.positions(kTriangle);
    int uv = doc.attribute(UNSIGNED_SHORT, "VEC2", {1, 2, 3, 4, 5, 6}, false);
    doc.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}});
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/meshes/0/primitives/0/attributes/TEXCOORD_0") << e.what();
}

TEST(GltfAccessors, QuantizedNonNormalizedTexcoordWithMeshQuantization) {
    // KHR_mesh_quantization allows non-normalized (u)byte/(u)short TEXCOORD_n (used with a texture transform).
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_mesh_quantization"};
    doc.j["extensionsRequired"] = {"KHR_mesh_quantization"};
    int pos = doc.positions(kTriangle);
    int uv = doc.attribute(UNSIGNED_SHORT, "VEC2", {0, 0, 1024, 0, 0, 1024}, false);
    doc.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    const Primitive& p = s.meshes.at(0).primitives.at(0);
    ASSERT_EQ(p.uv0.size(), 3u);
    EXPECT_FLOAT_EQ(p.uv0[1].x, 1024.0f);
    EXPECT_FLOAT_EQ(p.uv0[2].y, 1024.0f);
}

TEST(GltfAccessors, ColorVec3AndVec4) {
    {
        // VEC4 normalized unsigned bytes.
        Doc doc;
        int pos = doc.positions(kTriangle);
        int col = doc.attribute(UNSIGNED_BYTE, "VEC4", {255, 0, 51, 255, 0, 255, 0, 128, 102, 204, 255, 0}, true);
        doc.mesh({{"attributes", {{"POSITION", pos}, {"COLOR_0", col}}}});
        const Primitive p = load(doc.gltf()).meshes.at(0).primitives.at(0);
        ASSERT_EQ(p.colors.size(), 3u);
        EXPECT_FLOAT_EQ(p.colors[0].x, 1.0f);
        EXPECT_FLOAT_EQ(p.colors[0].z, 0.2f);
        EXPECT_FLOAT_EQ(p.colors[1].w, 128.0f / 255.0f);
        EXPECT_FLOAT_EQ(p.colors[2].x, 0.4f);
        EXPECT_FLOAT_EQ(p.colors[2].w, 0.0f);
    }
    {
        // VEC3 normalized unsigned shorts: alpha is 1.
        Doc doc;
        int pos = doc.positions(kTriangle);
        int col = doc.attribute(UNSIGNED_SHORT, "VEC3", {65535, 0, 13107, 0, 65535, 0, 32768, 32768, 65535}, true);
        doc.mesh({{"attributes", {{"POSITION", pos}, {"COLOR_0", col}}}});
        const Primitive p = load(doc.gltf()).meshes.at(0).primitives.at(0);
        ASSERT_EQ(p.colors.size(), 3u);
        EXPECT_FLOAT_EQ(p.colors[0].x, 1.0f);
        EXPECT_FLOAT_EQ(p.colors[0].z, 0.2f);
        EXPECT_FLOAT_EQ(p.colors[2].x, 32768.0f / 65535.0f);
        for (const auto& c : p.colors) EXPECT_EQ(c.w, 1.0f);
    }
    {
        // VEC3 and VEC4 floats.
        Doc doc;
        int pos = doc.positions(kTriangle);
        int c3 = doc.attribute(FLOAT, "VEC3", {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9});
        doc.mesh({{"attributes", {{"POSITION", pos}, {"COLOR_0", c3}}}});
        int c4 = doc.attribute(FLOAT, "VEC4", {0.1, 0.2, 0.3, 0.25, 0.4, 0.5, 0.6, 0.5, 0.7, 0.8, 0.9, 0.75});
        doc.mesh({{"attributes", {{"POSITION", pos}, {"COLOR_0", c4}}}});
        Scene s = load(doc.gltf());
        const Primitive& p3 = s.meshes.at(0).primitives.at(0);
        const Primitive& p4 = s.meshes.at(1).primitives.at(0);
        EXPECT_FLOAT_EQ(p3.colors[1].y, 0.5f);
        EXPECT_EQ(p3.colors[1].w, 1.0f);
        EXPECT_FLOAT_EQ(p4.colors[1].y, 0.5f);
        EXPECT_FLOAT_EQ(p4.colors[2].w, 0.75f);
    }
}

TEST(GltfAccessors, IndexComponentTypes) {
    // Two triangles of a quad, in a non-identity order so the index buffer is kept.
    const std::vector<double> idx = {2, 1, 0, 0, 3, 2};
    for (int ctype : {UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT}) {
        Doc doc;
        int pos = doc.positions(kQuad);
        int nrm = doc.normals(4);
        int ind = doc.indices(ctype, idx);
        doc.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", ind}});
        const Primitive p = load(doc.gltf()).meshes.at(0).primitives.at(0);
        ASSERT_EQ(p.indices.size(), 6u) << "ctype " << ctype;
        for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(p.indices[i], std::uint32_t(idx[i])) << "ctype " << ctype;
        EXPECT_EQ(p.positions.size(), 4u);
        EXPECT_EQ(p.triangle_count(), 2u);
        EXPECT_FALSE(p.generated_normals);
    }
    // A large UNSIGNED_INT index value is read in full (not truncated to 16 bits).
    Doc doc;
    std::vector<glm::vec3> many(70000, glm::vec3(0.0f));
    many[69999] = glm::vec3(5, 6, 7);
    many[1] = glm::vec3(1, 0, 0);
    int pos = doc.positions(many);
    int nrm = doc.normals(many.size());
    int ind = doc.indices(UNSIGNED_INT, {69999, 1, 0});
    doc.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", ind}});
    const Primitive p = load(doc.gltf()).meshes.at(0).primitives.at(0);
    ASSERT_FALSE(p.indices.empty());
    EXPECT_EQ(p.positions[p.indices[0]], glm::vec3(5, 6, 7));
}

TEST(GltfAccessors, InvalidIndexAndNormalizedTypesAreErrors) {
    {
        Doc doc;  // float indices
        int pos = doc.positions(kTriangle);
        int ind = doc.indices(FLOAT, {0, 1, 2});
        doc.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", ind}});
        Error e = load_error(doc.gltf());
        EXPECT_EQ(e.where(), "/meshes/0/primitives/0/indices") << e.what();
    }
    {
        Doc doc;  // normalized UNSIGNED_INT is not a thing
        int pos = doc.positions(kTriangle);
        int uv = doc.attribute(UNSIGNED_INT, "VEC2", {0, 0, 1, 0, 0, 1}, true);
        doc.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", uv}}}});
        Error e = load_error(doc.gltf());
        EXPECT_EQ(e.where(), "/accessors/1/normalized") << e.what();
    }
    {
        Doc doc;  // attribute counts must match POSITION
        int pos = doc.positions(kTriangle);
        int nrm = doc.normals(4);
        doc.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}});
        Error e = load_error(doc.gltf());
        EXPECT_EQ(e.where(), "/meshes/0/primitives/0/attributes/NORMAL") << e.what();
    }
}

TEST(GltfAccessors, ByteStrideInterleaving) {
    // One bufferView, stride 36: POSITION (12) NORMAL (12) TEXCOORD_0 (8), 4 bytes of padding.
    const std::size_t stride = 36;
    const std::vector<glm::vec3> pos = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {2, 3, 1}};
    const std::vector<glm::vec3> nrm = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}};
    const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0.25f}};
    std::vector<std::uint8_t> bytes(stride * 4, 0xEE);  // padding filled with junk
    for (std::size_t i = 0; i < 4; ++i) {
        std::memcpy(&bytes[i * stride + 0], &pos[i], 12);
        std::memcpy(&bytes[i * stride + 12], &nrm[i], 12);
        std::memcpy(&bytes[i * stride + 24], &uv[i], 8);
    }
    Doc doc;
    doc.bin.assign(8, 0xAB);  // the view starts 8 bytes into the buffer
    int v = doc.view(bytes, stride);
    int a_pos = doc.add_accessor({{"bufferView", v}, {"byteOffset", 0}, {"componentType", FLOAT}, {"count", 4}, {"type", "VEC3"}});
    int a_nrm = doc.add_accessor({{"bufferView", v}, {"byteOffset", 12}, {"componentType", FLOAT}, {"count", 4}, {"type", "VEC3"}});
    int a_uv = doc.add_accessor({{"bufferView", v}, {"byteOffset", 24}, {"componentType", FLOAT}, {"count", 4}, {"type", "VEC2"}});
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 2, 1, 3});
    doc.mesh({{"attributes", {{"POSITION", a_pos}, {"NORMAL", a_nrm}, {"TEXCOORD_0", a_uv}}}, {"indices", ind}});
    const Primitive p = load(doc.gltf()).meshes.at(0).primitives.at(0);
    ASSERT_EQ(p.positions.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(p.positions[i], pos[i]) << i;
        EXPECT_EQ(p.normals[i], nrm[i]) << i;
        EXPECT_EQ(p.uv0[i], uv[i]) << i;
    }
    // The same accessors through a GLB (BIN chunk) give the same data.
    const Primitive g = load(doc.glb()).meshes.at(0).primitives.at(0);
    EXPECT_EQ(g.positions, p.positions);
    EXPECT_EQ(g.normals, p.normals);
    EXPECT_EQ(g.uv0, p.uv0);
}

TEST(GltfAccessors, StrideSmallerThanElementIsAnError) {
    Doc doc;
    int v = doc.view(pack(FLOAT, 3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0}), 8);
    int pos = doc.add_accessor({{"bufferView", v}, {"componentType", FLOAT}, {"count", 3}, {"type", "VEC3"}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}});
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/accessors/0") << e.what();
}

TEST(GltfAccessors, SparseWithBufferView) {
    Doc doc;
    const std::vector<glm::vec3> base = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 2, 2}};
    int v = doc.view(pack(FLOAT, 3, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 2, 2}));
    int iv = doc.view(pack(UNSIGNED_BYTE, 1, {1, 4}));
    int vv = doc.view(pack(FLOAT, 3, {9, 8, 7, -1, -2, -3}));
    int pos = doc.add_accessor({{"bufferView", v},
                                {"componentType", FLOAT},
                                {"count", 5},
                                {"type", "VEC3"},
                                {"sparse",
                                 {{"count", 2},
                                  {"indices", {{"bufferView", iv}, {"componentType", UNSIGNED_BYTE}}},
                                  {"values", {{"bufferView", vv}}}}}});
    int nrm = doc.normals(5);
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3, 4, 1, 2});
    doc.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", ind}});
    const Primitive p = load(doc.gltf()).meshes.at(0).primitives.at(0);
    ASSERT_EQ(p.positions.size(), 5u);
    EXPECT_EQ(p.positions[0], base[0]);
    EXPECT_EQ(p.positions[1], glm::vec3(9, 8, 7));    // substituted
    EXPECT_EQ(p.positions[2], base[2]);
    EXPECT_EQ(p.positions[3], base[3]);
    EXPECT_EQ(p.positions[4], glm::vec3(-1, -2, -3));  // substituted
    EXPECT_EQ(p.bounds_max, glm::vec3(9, 8, 7));
    EXPECT_EQ(p.bounds_min, glm::vec3(-1, -2, -3));
}

TEST(GltfAccessors, SparseWithoutBufferViewStartsFromZeros) {
    Doc doc;
    // Indices as UNSIGNED_SHORT and UNSIGNED_INT, values with byte offsets inside their views.
    std::vector<std::uint8_t> idx_bytes = pack(UNSIGNED_SHORT, 1, {0, 0, 1, 3});  // first 4 bytes skipped
    int iv = doc.view(idx_bytes);
    int vv = doc.view(pack(FLOAT, 3, {99, 99, 99, 1, 0, 0, 0, 1, 0}));
    int pos = doc.add_accessor({{"componentType", FLOAT},
                                {"count", 4},
                                {"type", "VEC3"},
                                {"sparse",
                                 {{"count", 2},
                                  {"indices", {{"bufferView", iv}, {"byteOffset", 4}, {"componentType", UNSIGNED_SHORT}}},
                                  {"values", {{"bufferView", vv}, {"byteOffset", 12}}}}}});
    int nrm = doc.normals(4);
    int ind = doc.indices(UNSIGNED_BYTE, {0, 1, 3, 3, 2, 0});
    doc.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", ind}});
    // And a sparse accessor with UNSIGNED_INT indices over normalized bytes (no bufferView).
    int iv2 = doc.view(pack(UNSIGNED_INT, 1, {2}));
    int vv2 = doc.view(pack(UNSIGNED_BYTE, 2, {255, 51}));
    int uv = doc.add_accessor({{"componentType", UNSIGNED_BYTE},
                               {"normalized", true},
                               {"count", 4},
                               {"type", "VEC2"},
                               {"sparse",
                                {{"count", 1},
                                 {"indices", {{"bufferView", iv2}, {"componentType", UNSIGNED_INT}}},
                                 {"values", {{"bufferView", vv2}}}}}});
    doc.j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
    const Primitive p = load(doc.gltf()).meshes.at(0).primitives.at(0);
    ASSERT_EQ(p.positions.size(), 4u);
    EXPECT_EQ(p.positions[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(p.positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(p.positions[2], glm::vec3(0, 0, 0));
    EXPECT_EQ(p.positions[3], glm::vec3(0, 1, 0));
    ASSERT_EQ(p.uv0.size(), 4u);
    EXPECT_EQ(p.uv0[0], glm::vec2(0, 0));
    EXPECT_FLOAT_EQ(p.uv0[2].x, 1.0f);
    EXPECT_FLOAT_EQ(p.uv0[2].y, 0.2f);
}

// Zero-filled accessors (no bufferView) are legal and cost nothing in the file: the geometry a
// load decodes and keeps is bounded by the input (256 MiB + 64 bytes per byte by default), so a
// few hundred bytes cannot take gigabytes, whether one accessor is huge or a big one is shared
// by many primitives; the error names the accessor and the budget; --max-memory (the
// budget itself) lets a file that needs more through.
TEST(GltfAccessors, ZeroFilledAccessorsStayWithinTheMemoryBudget) {
    auto bomb = [](long long count, int primitives) {
        json j = {{"asset", {{"version", "2.0"}}},
                  {"accessors", {{{"componentType", FLOAT}, {"count", count}, {"type", "VEC3"},
                                  {"min", {0, 0, 0}}, {"max", {0, 0, 0}}}}},
                  {"meshes", {{{"primitives", json::array()}}}},
                  {"nodes", {{{"mesh", 0}}}},
                  {"scenes", {{{"nodes", {0}}}}}};
        for (int i = 0; i < primitives; ++i) j["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}});
        const std::string text = j.dump();
        return std::vector<std::uint8_t>(text.begin(), text.end());
    };
    for (const auto& [count, primitives] : {std::pair{150'000'000LL, 1}, std::pair{5'000'000LL, 64}}) {
        Diagnostics diag;
        try {
            load(bomb(count, primitives), diag);
            ADD_FAILURE() << count << " x " << primitives << " loaded";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("memory budget of 257 MiB"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("/accessors/0"), std::string::npos) << e.what();
        }
    }
    // The same shape within the budget loads; a budget of its own lets a bigger one through.
    Diagnostics diag;
    EXPECT_EQ(load(bomb(1000, 64), diag).meshes.at(0).primitives.size(), 64u);
    GltfLoadOptions opt;
    opt.max_geometry_bytes = std::size_t(1) << 20;
    EXPECT_THROW(load(bomb(100'000, 1), diag, opt), Error);  // 2.4 MB of doubles over a 1 MiB budget
    opt.max_geometry_bytes = std::size_t(64) << 20;
    EXPECT_EQ(load(bomb(100'000, 2), diag, opt).meshes.at(0).primitives.size(), 2u);
}

// =============================================================================================
// Primitives: indexing, topology, generated normals

TEST(GltfPrimitives, NonIndexedAndIndexed) {
    Doc doc;
    int pos = doc.positions(kQuad);
    int nrm = doc.normals(4);
    // Non-indexed: only the first 3 vertices form a triangle; the 4th is an incomplete triangle.
    doc.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}});
    // Indexed with the identity list 0..3: the same single triangle as non-indexed.
    int id = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 3});
    doc.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", id}});
    // Indexed quad.
    int q = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3});
    doc.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", q}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    ASSERT_EQ(s.meshes.size(), 3u);
    const Primitive& a = s.meshes[0].primitives.at(0);
    EXPECT_EQ(a.triangle_count(), 1u);
    EXPECT_EQ(triangle_corners(a), (std::vector<glm::vec3>{kQuad[0], kQuad[1], kQuad[2]}));
    EXPECT_TRUE(has_warning(d, "/meshes/0/primitives/0/attributes", "not a whole number")) << all_warnings(d);
    const Primitive& b = s.meshes[1].primitives.at(0);
    EXPECT_EQ(b.triangle_count(), 1u);
    EXPECT_EQ(triangle_corners(b), (std::vector<glm::vec3>{kQuad[0], kQuad[1], kQuad[2]}));
    EXPECT_TRUE(has_warning(d, "/meshes/1/primitives/0/indices", "not a whole number")) << all_warnings(d);
    const Primitive& c = s.meshes[2].primitives.at(0);
    EXPECT_EQ(c.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(c.triangle_count(), 2u);
    EXPECT_EQ(c.positions.size(), 4u);
    EXPECT_EQ(c.topology, Topology::Triangles);

    // An identity index buffer over exactly the used vertices is dropped (drawn non-indexed).
    Doc tri;
    int tp = tri.positions(kTriangle);
    int tn = tri.normals(3);
    int ti = tri.indices(UNSIGNED_BYTE, {0, 1, 2});
    tri.mesh({{"attributes", {{"POSITION", tp}, {"NORMAL", tn}}}, {"indices", ti}});
    const Primitive t = load(tri.gltf()).meshes.at(0).primitives.at(0);
    EXPECT_TRUE(t.indices.empty());
    EXPECT_EQ(t.positions, kTriangle);
    EXPECT_EQ(t.triangle_count(), 1u);
}

TEST(GltfPrimitives, TriangleStripBecomesList) {
    // v0..v5 zig-zag up the +y axis in the z = 0 plane; all strip triangles face +z.
    const std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0}};
    // Indexed, in a permuted vertex order, with normals (so the indices survive).
    const std::vector<std::uint32_t> strip = {5, 3, 4, 2, 0};
    Doc doc;
    // Vertex strip[k] of the buffer holds the k-th zig-zag position; vertex 1 is unused.
    std::vector<glm::vec3> shuffled(6, glm::vec3(9, 9, 9));
    for (std::size_t k = 0; k < strip.size(); ++k) shuffled[strip[k]] = pos[k];
    int p_acc = doc.positions(shuffled);
    int nrm = doc.normals(6);
    std::vector<double> idx(strip.begin(), strip.end());
    int ind = doc.indices(UNSIGNED_BYTE, idx);
    doc.mesh({{"attributes", {{"POSITION", p_acc}, {"NORMAL", nrm}}}, {"indices", ind}, {"mode", 5}});
    // Non-indexed, no normals: flat normals are generated from the converted winding.
    int p2 = doc.positions(pos);
    doc.mesh({{"attributes", {{"POSITION", p2}}}, {"mode", 5}});
    Scene s = load(doc.gltf());

    const Primitive& a = s.meshes.at(0).primitives.at(0);
    EXPECT_EQ(a.topology, Topology::Triangles);
    ASSERT_EQ(a.indices.size(), 9u);
    // glTF 2.0 section 3.7.2.1: triangle i of a strip is {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}.
    for (std::size_t i = 0; i + 2 < strip.size(); ++i) {
        std::array<std::uint32_t, 3> want = {strip[i], strip[i + 1 + i % 2], strip[i + 2 - i % 2]};
        EXPECT_TRUE(same_triangle(&a.indices[3 * i], want))
            << "triangle " << i << ": got " << a.indices[3 * i] << "," << a.indices[3 * i + 1] << ","
            << a.indices[3 * i + 2] << " want " << want[0] << "," << want[1] << "," << want[2];
        // And every triangle faces +z (consistent winding).
        glm::vec3 n = glm::cross(a.positions[a.indices[3 * i + 1]] - a.positions[a.indices[3 * i]],
                                 a.positions[a.indices[3 * i + 2]] - a.positions[a.indices[3 * i]]);
        EXPECT_GT(n.z, 0.0f) << "triangle " << i;
    }

    const Primitive& b = s.meshes.at(1).primitives.at(0);
    EXPECT_TRUE(b.generated_normals);
    EXPECT_EQ(b.triangle_count(), 4u);
    ASSERT_EQ(b.positions.size(), 12u);
    for (std::size_t i = 0; i < 4; ++i) {
        std::array<glm::vec3, 3> want = {pos[i], pos[i + 1 + i % 2], pos[i + 2 - i % 2]};
        bool match = false;
        for (int r = 0; r < 3 && !match; ++r)
            match = b.positions[3 * i] == want[std::size_t(r)] && b.positions[3 * i + 1] == want[std::size_t((r + 1) % 3)] &&
                    b.positions[3 * i + 2] == want[std::size_t((r + 2) % 3)];
        EXPECT_TRUE(match) << "triangle " << i;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(b.normals[3 * i + std::size_t(k)], glm::vec3(0, 0, 1)) << "triangle " << i;
    }
}

TEST(GltfPrimitives, TriangleFanBecomesList) {
    // Centre v0 and a counter-clockwise rim: all fan triangles face +z.
    const std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}};
    Doc doc;
    int p_acc = doc.positions(pos);
    int nrm = doc.normals(6);
    const std::vector<std::uint32_t> fan = {0, 1, 2, 3, 4, 5};
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 3, 4, 5});
    doc.mesh({{"attributes", {{"POSITION", p_acc}, {"NORMAL", nrm}}}, {"indices", ind}, {"mode", 6}});
    int p2 = doc.positions(pos);
    doc.mesh({{"attributes", {{"POSITION", p2}}}, {"mode", 6}});
    Scene s = load(doc.gltf());
    const Primitive& a = s.meshes.at(0).primitives.at(0);
    ASSERT_EQ(a.indices.size(), 12u);
    // glTF 2.0 section 3.7.2.1: triangle i of a fan is {v_{i+1}, v_{i+2}, v_0}.
    for (std::size_t i = 0; i + 2 < fan.size(); ++i) {
        std::array<std::uint32_t, 3> want = {fan[i + 1], fan[i + 2], fan[0]};
        EXPECT_TRUE(same_triangle(&a.indices[3 * i], want)) << "triangle " << i;
    }
    const Primitive& b = s.meshes.at(1).primitives.at(0);
    EXPECT_TRUE(b.generated_normals);
    ASSERT_EQ(b.positions.size(), 12u);
    for (const auto& n : b.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
    for (std::size_t i = 0; i < 4; ++i) {
        // Each triangle contains the centre.
        bool centre = b.positions[3 * i] == pos[0] || b.positions[3 * i + 1] == pos[0] || b.positions[3 * i + 2] == pos[0];
        EXPECT_TRUE(centre) << "triangle " << i;
    }
}

TEST(GltfPrimitives, LinesAndPointsKeepTheirTopology) {
    Doc doc;
    int pos = doc.positions(kQuad);
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 0}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 1}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"mode", 3}});
    Scene s = load(doc.gltf());
    EXPECT_EQ(s.meshes.at(0).primitives.at(0).topology, Topology::Points);
    EXPECT_EQ(s.meshes.at(1).primitives.at(0).topology, Topology::Lines);
    EXPECT_EQ(s.meshes.at(2).primitives.at(0).topology, Topology::LineStrip);
    for (int m = 0; m < 3; ++m) {
        EXPECT_EQ(s.meshes[std::size_t(m)].primitives[0].triangle_count(), 0u);
        EXPECT_TRUE(s.meshes[std::size_t(m)].primitives[0].normals.empty());
    }
}

TEST(GltfPrimitives, MissingNormalsGetFlatNormals) {
    Doc doc;
    // A quad whose second triangle is folded up out of the plane (a 90 degree crease).
    const std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 1}};
    int p_acc = doc.positions(pos);
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 3, 1});
    doc.mesh({{"attributes", {{"POSITION", p_acc}}}, {"indices", ind}});
    Scene s = load(doc.gltf());
    const Primitive& p = s.meshes.at(0).primitives.at(0);
    EXPECT_TRUE(p.generated_normals);
    EXPECT_EQ(p.source_vertex_count, 4u);
    // Each triangle gets its own three vertices (flat shading), the index buffer becomes the identity.
    ASSERT_EQ(p.positions.size(), 6u);
    ASSERT_EQ(p.normals.size(), 6u);
    EXPECT_TRUE(p.indices.empty());
    EXPECT_EQ(p.triangle_count(), 2u);
    EXPECT_EQ(p.positions[3], pos[0]);
    EXPECT_EQ(p.positions[4], pos[3]);
    EXPECT_EQ(p.positions[5], pos[1]);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(p.normals[std::size_t(k)], glm::vec3(0, 0, 1));
        // cross((0,0,1), (1,0,0)) = (0,1,0)
        EXPECT_EQ(p.normals[std::size_t(3 + k)], glm::vec3(0, 1, 0));
    }
    // Given normals are kept (normalised).
    Doc doc2;
    int p2 = doc2.positions(kTriangle);
    int n2 = doc2.normals(3, glm::vec3(0, 0, 2));
    doc2.mesh({{"attributes", {{"POSITION", p2}, {"NORMAL", n2}}}});
    const Primitive q = load(doc2.gltf()).meshes.at(0).primitives.at(0);
    EXPECT_FALSE(q.generated_normals);
    for (const auto& n : q.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(GltfPrimitives, NonFinitePositionSkipsPrimitiveWithWarning) {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        Doc doc;
        int pos = doc.attribute(FLOAT, "VEC3", {0, 0, 0, 1, bad, 0, 0, 1, 0});
        int good = doc.positions(kTriangle);
        doc.mesh(json::array({{{"attributes", {{"POSITION", pos}}}}, {{"attributes", {{"POSITION", good}}}}}));
        Diagnostics d;
        Scene s = load(doc.gltf(), d);
        ASSERT_EQ(s.meshes.size(), 1u);
        ASSERT_EQ(s.meshes[0].primitives.size(), 1u) << "the bad primitive is skipped, the good one kept";
        EXPECT_EQ(s.meshes[0].primitives[0].positions, kTriangle);
        EXPECT_TRUE(has_warning(d, "/meshes/0/primitives/0/attributes/POSITION", "non-finite")) << all_warnings(d);
    }
}

// =============================================================================================
// Nodes and scenes

namespace {
// 90 degrees about +y as a glTF quaternion [x, y, z, w].
const double kHalf = std::sqrt(0.5);
}  // namespace

TEST(GltfNodes, TrsAndMatrixGiveTheSameWorldMatrix) {
    Doc doc;
    // T = (1, 2, 3), R = 90 deg about +y, S = (2, 3, 4). Column-major:
    // col0 = R * (2,0,0) = (0,0,-2), col1 = (0,3,0), col2 = R * (0,0,4) = (4,0,0), col3 = (1,2,3,1).
    const std::vector<float> m = {0, 0, -2, 0, 0, 3, 0, 0, 4, 0, 0, 0, 1, 2, 3, 1};
    doc.j["nodes"] = json::array({{{"translation", {1, 2, 3}}, {"rotation", {0, kHalf, 0, kHalf}}, {"scale", {2, 3, 4}}},
                                  {{"matrix", m}}});
    doc.j["scenes"] = json::array({{{"nodes", {0, 1}}}});
    Scene s = load(doc.gltf());
    auto inst = flatten(s);
    ASSERT_EQ(inst.size(), 2u);
    glm::mat4 expected = glm::make_mat4(m.data());
    expect_mat_near(inst[0].world, expected, 1e-5f, "TRS");
    expect_mat_near(inst[1].world, expected, 0.0f, "matrix");
    // And the matrix does what it says on a point.
    glm::vec4 pt = inst[0].world * glm::vec4(1, 1, 1, 1);
    EXPECT_NEAR(pt.x, 1 + 4, 1e-5f);
    EXPECT_NEAR(pt.y, 2 + 3, 1e-5f);
    EXPECT_NEAR(pt.z, 3 - 2, 1e-5f);
}

TEST(GltfNodes, NonUnitQuaternionIsNormalised) {
    Doc doc;
    doc.j["nodes"] = json::array({{{"rotation", {0, 2 * kHalf, 0, 2 * kHalf}}}, {{"rotation", {0, kHalf, 0, kHalf}}}});
    Scene s = load(doc.gltf());
    expect_mat_near(s.nodes[0].local, s.nodes[1].local, 1e-6f);
}

TEST(GltfNodes, HierarchyWorldMatrices) {
    Doc doc;
    int pos = doc.positions(kTriangle);
    doc.j["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}}})}}});
    // 0: translate (10,0,0), children 1 and 3
    // 1: rotate 90 deg about +z, scale 2, child 2
    // 2: translate (1,0,0), mesh
    // 3: translate (0,0,5)
    doc.j["nodes"] = json::array({
        {{"name", "root"}, {"translation", {10, 0, 0}}, {"children", {1, 3}}},
        {{"name", "arm"}, {"rotation", {0, 0, kHalf, kHalf}}, {"scale", {2, 2, 2}}, {"children", {2}}},
        {{"name", "hand"}, {"translation", {1, 0, 0}}, {"mesh", 0}},
        {{"name", "other"}, {"translation", {0, 0, 5}}},
    });
    doc.j["scenes"] = json::array({{{"nodes", {0}}}});
    Scene s = load(doc.gltf());
    ASSERT_EQ(s.nodes.size(), 4u);
    EXPECT_EQ(s.nodes[0].children, (std::vector<int>{1, 3}));
    auto inst = flatten(s);
    ASSERT_EQ(inst.size(), 4u);
    // Depth-first, children in order.
    EXPECT_EQ(inst[0].node, 0);
    EXPECT_EQ(inst[1].node, 1);
    EXPECT_EQ(inst[2].node, 2);
    EXPECT_EQ(inst[3].node, 3);
    glm::mat4 w0 = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0));
    glm::mat4 w1 = w0 * glm::rotate(glm::mat4(1.0f), float(kPi / 2), glm::vec3(0, 0, 1)) *
                   glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
    glm::mat4 w2 = w1 * glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0));
    glm::mat4 w3 = w0 * glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
    expect_mat_near(inst[0].world, w0, 1e-5f, "root");
    expect_mat_near(inst[1].world, w1, 1e-5f, "arm");
    expect_mat_near(inst[2].world, w2, 1e-5f, "hand");
    expect_mat_near(inst[3].world, w3, 1e-5f, "other");
    // Hand-computed: the hand's origin is at (10,0,0) + Rz(90) * 2 * (1,0,0) = (10, 2, 0).
    glm::vec4 o = inst[2].world * glm::vec4(0, 0, 0, 1);
    EXPECT_NEAR(o.x, 10.0f, 1e-5f);
    EXPECT_NEAR(o.y, 2.0f, 1e-5f);
    EXPECT_NEAR(o.z, 0.0f, 1e-5f);
    // World bounds follow the camera convention: the 8 corners of the POSITION box [0,1]x[0,1]x[0,0]
    // transformed (x -> 10 - 2y, y -> 2 + 2(x + 1)): corners (0,0), (1,0), (0,1), (1,1) land at
    // (10,2), (10,4), (8,2), (8,4).
    Bounds b = scene_bounds(s, inst);
    ASSERT_FALSE(b.empty);
    EXPECT_NEAR(b.min.x, 8.0f, 1e-5f);
    EXPECT_NEAR(b.max.x, 10.0f, 1e-5f);
    EXPECT_NEAR(b.min.y, 2.0f, 1e-5f);
    EXPECT_NEAR(b.max.y, 4.0f, 1e-5f);
}

TEST(GltfNodes, MultipleScenesAndDefault) {
    Doc doc;
    doc.j["nodes"] = json::array({{{"name", "a"}}, {{"name", "b"}}, {{"name", "c"}, {"children", {0}}}});
    doc.j["scenes"] = json::array({{{"nodes", {2}}}, {{"nodes", {1}}}});
    doc.j["scene"] = 1;
    Scene s = load(doc.gltf());
    ASSERT_EQ(s.scenes.size(), 2u);
    EXPECT_EQ(s.default_scene, 1);
    EXPECT_EQ(s.scenes[0], (std::vector<int>{2}));
    EXPECT_EQ(s.scenes[1], (std::vector<int>{1}));
    auto def = flatten(s);
    ASSERT_EQ(def.size(), 1u);
    EXPECT_EQ(def[0].node, 1);
    auto first = flatten(s, 0);
    ASSERT_EQ(first.size(), 2u);
    EXPECT_EQ(first[0].node, 2);
    EXPECT_EQ(first[1].node, 0);
    EXPECT_TRUE(flatten(s, 5).empty());

    // Without `scene` the default is the first.
    doc.j.erase("scene");
    EXPECT_EQ(load(doc.gltf()).default_scene, 0);

    // `scene` out of range is an error.
    doc.j["scene"] = 2;
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/scene") << e.what();

    // No scenes at all: every root node is shown, with a warning.
    Doc none;
    none.j["nodes"] = json::array({{{"name", "a"}}, {{"name", "b"}, {"children", {0}}}, {{"name", "c"}}});
    Diagnostics d;
    Scene n = load(none.gltf(), d);
    ASSERT_EQ(n.scenes.size(), 1u);
    EXPECT_EQ(n.scenes[0], (std::vector<int>{1, 2}));
    EXPECT_TRUE(has_warning(d, "/scenes", "no scenes")) << all_warnings(d);
}

// =============================================================================================
// Cameras, lights, materials, textures

TEST(GltfCameras, PerspectiveAndOrthographic) {
    Doc doc;
    doc.j["cameras"] = json::array({
        {{"type", "perspective"}, {"name", "p"}, {"perspective", {{"yfov", 0.7}, {"aspectRatio", 1.5}, {"znear", 0.1}, {"zfar", 100}}}},
        {{"type", "perspective"}, {"perspective", {{"yfov", 1.2}, {"znear", 0.05}}}},
        {{"type", "orthographic"}, {"name", "o"}, {"orthographic", {{"xmag", 2.0}, {"ymag", 1.0}, {"znear", 0.01}, {"zfar", 50}}}},
    });
    doc.j["nodes"] = json::array({{{"camera", 2}, {"translation", {0, 0, 3}}}});
    doc.j["scenes"] = json::array({{{"nodes", {0}}}});
    Scene s = load(doc.gltf());
    ASSERT_EQ(s.cameras.size(), 3u);
    const Camera& p = s.cameras[0];
    EXPECT_EQ(p.type, Camera::Type::Perspective);
    EXPECT_EQ(p.name, "p");
    EXPECT_FLOAT_EQ(p.yfov, 0.7f);
    ASSERT_TRUE(p.aspect_ratio.has_value());
    EXPECT_FLOAT_EQ(*p.aspect_ratio, 1.5f);
    EXPECT_FLOAT_EQ(p.znear, 0.1f);
    ASSERT_TRUE(p.zfar.has_value());
    EXPECT_FLOAT_EQ(*p.zfar, 100.0f);
    const Camera& inf = s.cameras[1];
    EXPECT_FALSE(inf.aspect_ratio.has_value());
    EXPECT_FALSE(inf.zfar.has_value()) << "perspective without zfar is infinite";
    EXPECT_FLOAT_EQ(inf.yfov, 1.2f);
    const Camera& o = s.cameras[2];
    EXPECT_EQ(o.type, Camera::Type::Orthographic);
    EXPECT_FLOAT_EQ(o.xmag, 2.0f);
    EXPECT_FLOAT_EQ(o.ymag, 1.0f);
    EXPECT_FLOAT_EQ(o.znear, 0.01f);
    ASSERT_TRUE(o.zfar.has_value());
    EXPECT_FLOAT_EQ(*o.zfar, 50.0f);
    EXPECT_EQ(s.nodes[0].camera, 2);

    // Errors carry the pointer of the bad value.
    Doc bad;
    bad.j["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.0}}}}});
    EXPECT_EQ(load_error(bad.gltf()).where(), "/cameras/0/perspective/znear");
    bad.j["cameras"] = json::array({{{"type", "fisheye"}}});
    EXPECT_EQ(load_error(bad.gltf()).where(), "/cameras/0/type");
    bad.j["cameras"] = json::array({{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 2}, {"zfar", 1}}}}});
    EXPECT_EQ(load_error(bad.gltf()).where(), "/cameras/0/orthographic");
}

TEST(GltfLights, KhrLightsPunctual) {
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_lights_punctual"};
    doc.j["extensions"] = {{"KHR_lights_punctual",
                            {{"lights", json::array({
                                            {{"type", "directional"}, {"name", "sun"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 3.0}},
                                            {{"type", "point"}, {"intensity", 10.0}, {"range", 5.0}},
                                            {{"type", "spot"}, {"intensity", 20.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
                                            {{"type", "spot"}},
                                        })}}}};
    doc.j["nodes"] = json::array({{{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}}, {{"name", "no light"}}});
    doc.j["scenes"] = json::array({{{"nodes", {0, 1}}}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    ASSERT_EQ(s.lights.size(), 4u);
    EXPECT_EQ(s.lights[0].type, Light::Type::Directional);
    EXPECT_EQ(s.lights[0].name, "sun");
    EXPECT_EQ(s.lights[0].color, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(s.lights[0].intensity, 3.0f);
    EXPECT_EQ(s.lights[1].type, Light::Type::Point);
    EXPECT_FLOAT_EQ(s.lights[1].intensity, 10.0f);
    EXPECT_FLOAT_EQ(s.lights[1].range, 5.0f);
    EXPECT_EQ(s.lights[1].color, glm::vec3(1.0f));
    EXPECT_EQ(s.lights[2].type, Light::Type::Spot);
    EXPECT_FLOAT_EQ(s.lights[2].inner_cone_angle, 0.2f);
    EXPECT_FLOAT_EQ(s.lights[2].outer_cone_angle, 0.6f);
    EXPECT_FLOAT_EQ(s.lights[3].inner_cone_angle, 0.0f);
    EXPECT_NEAR(s.lights[3].outer_cone_angle, kPi / 4, 1e-6);
    EXPECT_FLOAT_EQ(s.lights[3].intensity, 1.0f);
    EXPECT_EQ(s.lights[3].range, 0.0f);
    EXPECT_EQ(s.nodes[0].light, 2);
    EXPECT_EQ(s.nodes[1].light, -1);
    EXPECT_EQ(d.total(), 0u) << all_warnings(d);

    // A node referring to a light that does not exist.
    doc.j["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 7;
    EXPECT_EQ(load_error(doc.gltf()).where(), "/nodes/0/extensions/KHR_lights_punctual/light");
    // Bad cone angles.
    doc.j["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 2;
    doc.j["extensions"]["KHR_lights_punctual"]["lights"][2]["spot"]["innerConeAngle"] = 0.9;
    EXPECT_EQ(load_error(doc.gltf()).where(), "/extensions/KHR_lights_punctual/lights/2/spot");
}

// EXT_lights_area (fresnel's): rect, disk and sphere lights after the punctual ones in
// Scene::lights, a node naming one by its index in the extension's own list; bad sizes and
// indices refused with their place, an unknown type ignored with a warning.
TEST(GltfLights, ExtLightsArea) {
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_lights_punctual", "EXT_lights_area"};
    doc.j["extensions"] = {{"KHR_lights_punctual", {{"lights", json::array({{{"type", "point"}}})}}},
                           {"EXT_lights_area",
                            {{"lights", json::array({
                                            {{"type", "rect"}, {"name", "panel"}, {"width", 2.0}, {"height", 0.5}, {"intensity", 40.0}},
                                            {{"type", "disk"}, {"radius", 0.25}, {"color", {1.0, 0.9, 0.8}}},
                                            {{"type", "sphere"}},
                                            {{"type", "tube"}, {"length", 2.0}, {"radius", 0.03}},
                                        })}}}};
    doc.j["nodes"] = json::array({{{"extensions", {{"EXT_lights_area", {{"light", 1}}}}}},
                                  {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                                  {{"extensions", {{"EXT_lights_area", {{"light", 0}}}}}}});
    doc.j["scenes"] = json::array({{{"nodes", {0, 1, 2}}}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    EXPECT_EQ(d.total(), 0u) << all_warnings(d);
    ASSERT_EQ(s.lights.size(), 5u);
    EXPECT_EQ(s.lights[4].type, Light::Type::Tube);
    EXPECT_FLOAT_EQ(s.lights[4].length, 2.0f);
    EXPECT_FLOAT_EQ(s.lights[4].radius, 0.03f);
    EXPECT_EQ(s.lights[0].type, Light::Type::Point);
    EXPECT_EQ(s.lights[1].type, Light::Type::Rect);
    EXPECT_EQ(s.lights[1].name, "panel");
    EXPECT_FLOAT_EQ(s.lights[1].width, 2.0f);
    EXPECT_FLOAT_EQ(s.lights[1].height, 0.5f);
    EXPECT_FLOAT_EQ(s.lights[1].intensity, 40.0f);
    EXPECT_EQ(s.lights[2].type, Light::Type::Disk);
    EXPECT_FLOAT_EQ(s.lights[2].radius, 0.25f);
    EXPECT_EQ(s.lights[3].type, Light::Type::Sphere);
    EXPECT_FLOAT_EQ(s.lights[3].radius, 0.5f) << "the default";
    EXPECT_EQ(s.nodes[0].light, 2) << "the area list's light 1, after one punctual light";
    EXPECT_EQ(s.nodes[1].light, 0);
    EXPECT_EQ(s.nodes[2].light, 1);
    EXPECT_EQ(gltf_extension_support("EXT_lights_area"), GltfExtensionSupport::Supported);

    Doc bad = doc;
    bad.j["nodes"][0]["extensions"]["EXT_lights_area"]["light"] = 4;
    EXPECT_EQ(load_error(bad.gltf()).where(), "/nodes/0/extensions/EXT_lights_area/light");
    bad = doc;
    bad.j["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 1;  // only one punctual light
    EXPECT_EQ(load_error(bad.gltf()).where(), "/nodes/1/extensions/KHR_lights_punctual/light");
    bad = doc;
    bad.j["extensions"]["EXT_lights_area"]["lights"][0]["width"] = -1.0;
    EXPECT_EQ(load_error(bad.gltf()).where(), "/extensions/EXT_lights_area/lights/0/width");
    bad = doc;
    bad.j["extensions"]["EXT_lights_area"]["lights"][1]["radius"] = 0.0;
    EXPECT_EQ(load_error(bad.gltf()).where(), "/extensions/EXT_lights_area/lights/1/radius");
    bad = doc;
    bad.j["extensions"]["EXT_lights_area"]["lights"][2]["type"] = "strip";
    Diagnostics w;
    Scene t = load(bad.gltf(), w);
    EXPECT_EQ(t.lights[3].intensity, 0.0f) << "an unknown type is ignored";
    EXPECT_EQ(w.total(), 1u);
}

TEST(GltfNodes, KhrNodeVisibility) {
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_node_visibility"};
    doc.j["nodes"] = json::array({{{"children", {1}}, {"extensions", {{"KHR_node_visibility", {{"visible", false}}}}}},
                                  {{"extensions", {{"KHR_node_visibility", {{"visible", true}}}}}},
                                  {{"extensions", {{"KHR_node_visibility", json::object()}}}}});
    doc.j["scenes"] = json::array({{{"nodes", {0, 2}}}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    EXPECT_FALSE(s.nodes[0].visible);
    EXPECT_TRUE(s.nodes[1].visible);
    EXPECT_TRUE(s.nodes[2].visible);  // the default
    EXPECT_EQ(d.total(), 0u) << all_warnings(d);
    auto inst = flatten(s);
    ASSERT_EQ(inst.size(), 3u);
    EXPECT_FALSE(inst[0].visible);
    EXPECT_FALSE(inst[1].visible);  // below a hidden node, whatever its own flag says
    EXPECT_TRUE(inst[2].visible);
    EXPECT_EQ(gltf_extension_support("KHR_node_visibility"), GltfExtensionSupport::Supported);
    doc.j["nodes"][0]["extensions"]["KHR_node_visibility"]["visible"] = 0;
    EXPECT_EQ(load_error(doc.gltf()).where(), "/nodes/0/extensions/KHR_node_visibility/visible");
}

// EXT_mesh_gpu_instancing: each instance a child node holding the mesh at the node's world
// transform times its TRS; the node itself keeps its light but no mesh; bad accessors are refused.
TEST(GltfNodes, ExtMeshGpuInstancing) {
    Doc doc;
    int pos = doc.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}});
    doc.j["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    doc.j["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
    int t = doc.attribute(FLOAT, "VEC3", {0, 0, 0, 10, 0, 0, 0, 0, 5});
    // 90 degrees about +Z for the second instance, as normalized shorts.
    const double h = std::sqrt(0.5) * 32767.0;
    int r = doc.attribute(SHORT, "VEC4", {0, 0, 0, 32767, 0, 0, h, h, 0, 0, 0, 32767}, true);
    int sc = doc.attribute(FLOAT, "VEC3", {1, 1, 1, 1, 1, 1, 2, 2, 2});
    int id = doc.attribute(FLOAT, "SCALAR", {7, 8, 9});
    doc.j["nodes"][0]["translation"] = {0, 100, 0};
    doc.j["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
        {"TRANSLATION", t}, {"ROTATION", r}, {"SCALE", sc}, {"_ID", id}};
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    EXPECT_EQ(d.total(), 0u) << all_warnings(d);
    EXPECT_EQ(gltf_extension_support("EXT_mesh_gpu_instancing"), GltfExtensionSupport::Supported);
    ASSERT_EQ(s.nodes.size(), 4u);
    EXPECT_EQ(s.nodes[0].mesh, -1);
    auto inst = flatten(s);
    std::vector<glm::vec3> corner;  // where each instance puts the vertex (1, 0, 0)
    for (const NodeInstance& i : inst)
        if (s.nodes[std::size_t(i.node)].mesh == 0) corner.push_back(glm::vec3(i.world * glm::vec4(1, 0, 0, 1)));
    ASSERT_EQ(corner.size(), 3u);
    EXPECT_NEAR(glm::distance(corner[0], glm::vec3(1, 100, 0)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::distance(corner[1], glm::vec3(10, 101, 0)), 0.0f, 1e-3f);  // rotated onto +Y
    EXPECT_NEAR(glm::distance(corner[2], glm::vec3(2, 100, 5)), 0.0f, 1e-4f);   // scaled by 2
    EXPECT_EQ(s.nodes[2].name, "node 0 #1");
    Bounds b = scene_bounds(s, inst);
    EXPECT_NEAR(b.max.x, 10.0f, 1e-3f);  // the rotated instance reaches x = 10 with its origin
    EXPECT_NEAR(b.max.z, 5.0f, 1e-4f);

    // Counts that differ, a wrong type, no attribute at all: refused where they are.
    const std::string where = "/nodes/0/extensions/EXT_mesh_gpu_instancing/attributes";
    Doc bad = doc;
    bad.j["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["SCALE"] = bad.attribute(FLOAT, "VEC3", {1, 1, 1});
    EXPECT_EQ(load_error(bad.gltf()).where(), where + "/SCALE");  // read in name order: ROTATION, SCALE, ...
    bad = doc;
    bad.j["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"] = id;
    EXPECT_EQ(load_error(bad.gltf()).where(), where + "/TRANSLATION");
    bad = doc;
    bad.j["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {{"_ID", id}};
    EXPECT_EQ(load_error(bad.gltf()).where(), where);
    // A node without a mesh: a warning, nothing instanced.
    bad = doc;
    bad.j["nodes"][0].erase("mesh");
    Diagnostics d2;
    Scene none = load(bad.gltf(), d2);
    EXPECT_EQ(none.nodes.size(), 1u);
    EXPECT_TRUE(has_warning(d2, "/nodes/0/extensions/EXT_mesh_gpu_instancing", "no mesh"));
}

TEST(GltfMaterials, FactorsModesAndExtensions) {
    Image8 pixels;
    auto png = make_png(3, 2, &pixels);
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_materials_unlit"};
    doc.j["images"] = json::array({{{"uri", "data:image/png;base64," + base64(png)}}});
    doc.j["samplers"] = json::array({{{"magFilter", 9728}, {"minFilter", 9984}, {"wrapS", 33071}, {"wrapT", 33648}}});
    doc.j["textures"] = json::array({{{"source", 0}, {"sampler", 0}}, {{"source", 0}}});
    doc.j["materials"] = json::array({
        {{"name", "full"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.5, 0.25, 1.0, 0.75}},
           {"metallicFactor", 0.3},
           {"roughnessFactor", 0.6},
           {"baseColorTexture", {{"index", 0}}},
           {"metallicRoughnessTexture", {{"index", 1}, {"texCoord", 1}}}}},
         {"normalTexture", {{"index", 0}, {"scale", 0.8}}},
         {"occlusionTexture", {{"index", 1}, {"strength", 0.4}}},
         {"emissiveTexture", {{"index", 0}}},
         {"emissiveFactor", {1.0, 0.5, 0.25}},
         {"alphaMode", "MASK"},
         {"alphaCutoff", 0.3},
         {"doubleSided", true},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 5.0}}}}}},
        {{"alphaMode", "BLEND"}, {"extensions", {{"KHR_materials_unlit", json::object()}}}},
        json::object(),
    });
    // A primitive with the normal-mapped material and UVs gets generated tangents.
    int pos = doc.positions(kQuad);
    int nrm = doc.normals(4);
    int uv = doc.attribute(FLOAT, "VEC2", {0, 0, 1, 0, 1, 1, 0, 1});
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3});
    doc.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}, {"indices", ind}, {"material", 0}},
                          {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", ind}, {"material", 2}}}));
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    ASSERT_EQ(s.materials.size(), 3u);
    const Material& m = s.materials[0];
    EXPECT_EQ(m.name, "full");
    EXPECT_EQ(m.base_color_factor, glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
    EXPECT_FLOAT_EQ(m.metallic_factor, 0.3f);
    EXPECT_FLOAT_EQ(m.roughness_factor, 0.6f);
    EXPECT_EQ(m.base_color.texture, 0);
    EXPECT_EQ(m.base_color.tex_coord, 0);
    EXPECT_FALSE(m.base_color.has_transform);
    EXPECT_EQ(m.metallic_roughness.texture, 1);
    EXPECT_EQ(m.metallic_roughness.tex_coord, 1);
    EXPECT_EQ(m.normal.texture, 0);
    EXPECT_FLOAT_EQ(m.normal_scale, 0.8f);
    EXPECT_EQ(m.occlusion.texture, 1);
    EXPECT_FLOAT_EQ(m.occlusion_strength, 0.4f);
    EXPECT_EQ(m.emissive.texture, 0);
    EXPECT_EQ(m.emissive_factor, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(m.emissive_strength_value(), 5.0f);
    EXPECT_EQ(m.alpha_mode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.3f);
    EXPECT_TRUE(m.double_sided);
    EXPECT_FALSE(m.unlit);

    const Material& u = s.materials[1];
    EXPECT_EQ(u.alpha_mode, AlphaMode::Blend);
    EXPECT_TRUE(u.unlit);
    EXPECT_FALSE(u.double_sided);

    // Defaults from the specification.
    const Material& def = s.materials[2];
    EXPECT_EQ(def.base_color_factor, glm::vec4(1.0f));
    EXPECT_EQ(def.metallic_factor, 1.0f);
    EXPECT_EQ(def.roughness_factor, 1.0f);
    EXPECT_EQ(def.emissive_factor, glm::vec3(0.0f));
    EXPECT_EQ(def.emissive_strength_value(), 1.0f);
    EXPECT_EQ(def.alpha_mode, AlphaMode::Opaque);
    EXPECT_EQ(def.alpha_cutoff, 0.5f);
    EXPECT_FALSE(def.double_sided);
    EXPECT_FALSE(def.unlit);
    EXPECT_FALSE(def.base_color.valid());
    EXPECT_FALSE(def.normal.valid());

    // Textures, samplers, images.
    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_EQ(s.textures[0].image, 0);
    EXPECT_EQ(s.textures[0].sampler.mag_filter, Filter::Nearest);
    EXPECT_EQ(s.textures[0].sampler.min_filter, Filter::Nearest);
    EXPECT_EQ(s.textures[0].sampler.mipmap, MipmapMode::Nearest);
    EXPECT_EQ(s.textures[0].sampler.wrap_s, Wrap::ClampToEdge);
    EXPECT_EQ(s.textures[0].sampler.wrap_t, Wrap::MirroredRepeat);
    EXPECT_EQ(s.textures[1].sampler.mag_filter, Filter::Linear);  // defaults
    EXPECT_EQ(s.textures[1].sampler.wrap_s, Wrap::Repeat);
    ASSERT_EQ(s.images.size(), 1u);
    ASSERT_TRUE(s.images[0].valid());
    EXPECT_EQ(s.images[0].pixels.width, 3);
    EXPECT_EQ(s.images[0].pixels.height, 2);
    EXPECT_EQ(s.images[0].pixels.pixels, pixels.pixels);

    // Tangents generated for the normal-mapped primitive only.
    const Mesh& mesh = s.meshes.at(0);
    ASSERT_EQ(mesh.primitives.size(), 2u);
    EXPECT_TRUE(mesh.primitives[0].generated_tangents);
    EXPECT_EQ(mesh.primitives[0].tangents.size(), mesh.primitives[0].positions.size());
    for (const auto& t : mesh.primitives[0].tangents) {
        EXPECT_NEAR(t.x, 1.0f, 1e-5f);  // u increases along +x on this quad
        EXPECT_TRUE(t.w == 1.0f || t.w == -1.0f);
    }
    EXPECT_EQ(mesh.primitives[0].material, 0);
    EXPECT_FALSE(mesh.primitives[1].generated_tangents);
    EXPECT_TRUE(mesh.primitives[1].tangents.empty());

    // Invalid alpha mode.
    doc.j["materials"][1]["alphaMode"] = "TRANSLUCENT";
    EXPECT_EQ(load_error(doc.gltf()).where(), "/materials/1/alphaMode");
}

TEST(GltfMaterials, KhrMaterialsClearcoat) {
    auto png = make_png(2, 2, nullptr);
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_materials_clearcoat"};
    doc.j["extensionsRequired"] = {"KHR_materials_clearcoat"};  // supported, so not an error
    doc.j["images"] = json::array({{{"uri", "data:image/png;base64," + base64(png)}}});
    doc.j["textures"] = json::array({{{"source", 0}}});
    doc.j["materials"] = json::array({
        {{"extensions",
          {{"KHR_materials_clearcoat",
            {{"clearcoatFactor", 0.7},
             {"clearcoatTexture", {{"index", 0}}},
             {"clearcoatRoughnessFactor", 2.0},  // clamped to 1
             {"clearcoatRoughnessTexture", {{"index", 0}, {"texCoord", 1}}},
             {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}}}}},
        {{"extensions", {{"KHR_materials_clearcoat", json::object()}}}},
    });
    // Only a clearcoat normal map: the primitive still needs (generated) tangents.
    int pos = doc.positions(kQuad);
    int nrm = doc.normals(4);
    int uv = doc.attribute(FLOAT, "VEC2", {0, 0, 1, 0, 1, 1, 0, 1});
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3});
    doc.mesh(json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}, {"indices", ind}, {"material", 0}}}));
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    ASSERT_EQ(s.materials.size(), 2u);
    const Material& m = s.materials[0];
    EXPECT_TRUE(m.has_clearcoat());
    EXPECT_FLOAT_EQ(m.clearcoat->clearcoat_factor, 0.7f);
    EXPECT_EQ(m.clearcoat->clearcoat_texture.texture, 0);
    EXPECT_FLOAT_EQ(m.clearcoat->clearcoat_roughness_factor, 1.0f);
    EXPECT_EQ(m.clearcoat->clearcoat_roughness_texture.tex_coord, 1);
    EXPECT_EQ(m.clearcoat->clearcoat_normal_texture.texture, 0);
    EXPECT_FLOAT_EQ(m.clearcoat->clearcoat_normal_scale, 0.5f);
    EXPECT_TRUE(s.meshes.at(0).primitives[0].generated_tangents);
    // Defaults: factor 0 turns the coat off.
    EXPECT_FALSE(s.materials[1].has_clearcoat());
    ASSERT_TRUE(s.materials[1].clearcoat);
    EXPECT_FLOAT_EQ(s.materials[1].clearcoat->clearcoat_roughness_factor, 0.0f);
    EXPECT_EQ(d.total(), 0u);
}

// KHR_materials_anisotropy's direction lies in the tangent frame: a primitive without TANGENT
// gets MikkTSpace tangents, as for a normal map (the Khronos viewer derives a frame from the UVs);
// without texture coordinates it warns and stays isotropic.
TEST(GltfMaterials, AnisotropyGeneratesTangents) {
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_materials_anisotropy"};
    doc.j["materials"] = json::array({
        {{"extensions", {{"KHR_materials_anisotropy", {{"anisotropyStrength", 0.5}}}}}},
        {{"extensions", {{"KHR_materials_anisotropy", json::object()}}}},  // strength 0: not shaded
    });
    int pos = doc.positions(kQuad);
    int nrm = doc.normals(4);
    int uv = doc.attribute(FLOAT, "VEC2", {0, 0, 1, 0, 1, 1, 0, 1});
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3});
    doc.mesh(json::array({
        {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}, {"indices", ind}, {"material", 0}},
        {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}}}, {"indices", ind}, {"material", 1}},
        {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", ind}, {"material", 0}},
    }));
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    ASSERT_EQ(s.meshes.at(0).primitives.size(), 3u);
    EXPECT_TRUE(s.materials[0].has_anisotropy());
    EXPECT_FALSE(s.materials[1].has_anisotropy());
    EXPECT_TRUE(s.meshes[0].primitives[0].generated_tangents);
    EXPECT_EQ(s.meshes[0].primitives[0].tangents.size(), 4u);
    EXPECT_FALSE(s.meshes[0].primitives[1].generated_tangents);
    EXPECT_TRUE(s.meshes[0].primitives[2].tangents.empty());
    EXPECT_EQ(d.total(), 1u);  // the primitive without UVs
}

// Extensions land in their blocks as written: the loader does not rewrite factors
// (specular-glossiness stays its own block; evaluate converts it).
TEST(GltfMaterials, ExtensionBlocksAsWritten) {
    Doc doc;
    doc.j["images"] = json::array({{{"uri", "data:image/png;base64," + base64(make_png(2, 2))}}});
    doc.j["textures"] = json::array({{{"source", 0}}});
    doc.j["materials"] = json::parse(R"([
        {"extensions": {
            "KHR_materials_ior": {"ior": 1.33},
            "KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [2, 1, 0.5],
                                       "specularColorTexture": {"index": 0}},
            "KHR_materials_pbrSpecularGlossiness": {"diffuseFactor": [0.5, 0.4, 0.3, 0.9],
                "specularFactor": [0.2, 0.3, 0.4], "glossinessFactor": 0.7,
                "diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 0, "texCoord": 1}}}},
        {"extensions": {
            "KHR_materials_sheen": {}, "KHR_materials_transmission": {}, "KHR_materials_volume": {},
            "KHR_materials_iridescence": {}, "KHR_materials_anisotropy": {}, "KHR_materials_dispersion": {},
            "KHR_materials_diffuse_transmission": {}, "KHR_materials_specular": {}}},
        {"extensions": {
            "KHR_materials_sheen": {"sheenColorFactor": [1, 0.5, 0.25], "sheenRoughnessFactor": 0.3},
            "KHR_materials_transmission": {"transmissionFactor": 0.8, "transmissionTexture": {"index": 0}},
            "KHR_materials_volume": {"thicknessFactor": 2, "attenuationDistance": 0.5, "attenuationColor": [0.9, 0.8, 0.7]},
            "KHR_materials_iridescence": {"iridescenceFactor": 1, "iridescenceIor": 1.8,
                                          "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 800},
            "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 1.5},
            "KHR_materials_dispersion": {"dispersion": 0.1},
            "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.25,
                                                   "diffuseTransmissionColorFactor": [0.1, 0.2, 0.3]}}},
        {}
    ])");
    int pos = doc.positions(kQuad);
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3});
    doc.mesh(json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", ind}, {"material", 0}}}));
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    ASSERT_EQ(s.materials.size(), 4u);
    const Material& a = s.materials[0];
    ASSERT_TRUE(a.ior && a.specular && a.specular_glossiness);
    EXPECT_FLOAT_EQ(a.ior->ior, 1.33f);
    EXPECT_FLOAT_EQ(a.specular->specular_factor, 0.5f);
    EXPECT_EQ(a.specular->specular_color_factor, glm::vec3(2.0f, 1.0f, 0.5f));  // not clamped: the extension allows > 1
    EXPECT_EQ(a.specular->specular_color_texture.texture, 0);
    const SpecularGlossinessExt& sg = *a.specular_glossiness;
    EXPECT_EQ(sg.diffuse_factor, glm::vec4(0.5f, 0.4f, 0.3f, 0.9f));
    EXPECT_EQ(sg.specular_factor, glm::vec3(0.2f, 0.3f, 0.4f));
    EXPECT_FLOAT_EQ(sg.glossiness_factor, 0.7f);
    EXPECT_EQ(sg.diffuse_texture.texture, 0);
    EXPECT_EQ(sg.specular_glossiness_texture.tex_coord, 1);
    // The core stays as the file has it (absent pbrMetallicRoughness: defaults).
    EXPECT_EQ(a.base_color_factor, glm::vec4(1.0f));
    EXPECT_FALSE(a.base_color.valid());
    EXPECT_EQ(a.metallic_factor, 1.0f);

    const Material& b = s.materials[1];  // the specification's defaults
    ASSERT_TRUE(b.sheen && b.transmission && b.volume && b.iridescence && b.anisotropy && b.dispersion &&
                b.diffuse_transmission && b.specular);
    EXPECT_EQ(b.sheen->sheen_color_factor, glm::vec3(0.0f));
    EXPECT_EQ(b.sheen->sheen_roughness_factor, 0.0f);
    EXPECT_EQ(b.transmission->transmission_factor, 0.0f);
    EXPECT_EQ(b.volume->thickness_factor, 0.0f);
    EXPECT_TRUE(std::isinf(b.volume->attenuation_distance));
    EXPECT_EQ(b.volume->attenuation_color, glm::vec3(1.0f));
    EXPECT_EQ(b.iridescence->iridescence_factor, 0.0f);
    EXPECT_FLOAT_EQ(b.iridescence->iridescence_ior, 1.3f);
    EXPECT_EQ(b.iridescence->iridescence_thickness_minimum, 100.0f);
    EXPECT_EQ(b.iridescence->iridescence_thickness_maximum, 400.0f);
    EXPECT_EQ(b.anisotropy->anisotropy_strength, 0.0f);
    EXPECT_EQ(b.anisotropy->anisotropy_rotation, 0.0f);
    EXPECT_EQ(b.dispersion->dispersion, 0.0f);
    EXPECT_EQ(b.diffuse_transmission->diffuse_transmission_factor, 0.0f);
    EXPECT_EQ(b.diffuse_transmission->diffuse_transmission_color_factor, glm::vec3(1.0f));
    EXPECT_EQ(b.specular->specular_factor, 1.0f);
    EXPECT_EQ(b.specular->specular_color_factor, glm::vec3(1.0f));
    EXPECT_EQ(b.ior_value(), 1.5f);

    const Material& c = s.materials[2];
    EXPECT_EQ(c.sheen->sheen_color_factor, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(c.sheen->sheen_roughness_factor, 0.3f);
    EXPECT_FLOAT_EQ(c.transmission->transmission_factor, 0.8f);
    EXPECT_EQ(c.transmission->transmission_texture.texture, 0);
    EXPECT_FLOAT_EQ(c.volume->thickness_factor, 2.0f);
    EXPECT_FLOAT_EQ(c.volume->attenuation_distance, 0.5f);
    EXPECT_EQ(c.volume->attenuation_color, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_FLOAT_EQ(c.iridescence->iridescence_ior, 1.8f);
    EXPECT_FLOAT_EQ(c.iridescence->iridescence_thickness_maximum, 800.0f);
    EXPECT_FLOAT_EQ(c.anisotropy->anisotropy_strength, 0.6f);
    EXPECT_FLOAT_EQ(c.anisotropy->anisotropy_rotation, 1.5f);
    EXPECT_FLOAT_EQ(c.dispersion->dispersion, 0.1f);
    EXPECT_FLOAT_EQ(c.diffuse_transmission->diffuse_transmission_factor, 0.25f);
    EXPECT_EQ(c.diffuse_transmission->diffuse_transmission_color_factor, glm::vec3(0.1f, 0.2f, 0.3f));

    const Material& none = s.materials[3];
    EXPECT_FALSE(none.ior || none.specular || none.clearcoat || none.specular_glossiness || none.sheen ||
                 none.transmission || none.volume || none.iridescence || none.anisotropy || none.dispersion ||
                 none.diffuse_transmission || none.unlit || none.emissive_strength);
}

TEST(GltfMaterials, KhrTextureTransform) {
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_texture_transform"};
    doc.j["images"] = json::array({{{"uri", "data:image/png;base64," + base64(make_png(2, 2))}}});
    doc.j["textures"] = json::array({{{"source", 0}}});
    // The specification's example: offset [0, 1], rotation pi/2, scale [0.5, 0.5].
    doc.j["materials"] = json::parse(R"([
        {"emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform":
            {"offset": [0, 1], "rotation": 1.57079632679, "scale": [0.5, 0.5]}}}},
        {"emissiveTexture": {"index": 0, "texCoord": 0, "extensions": {"KHR_texture_transform":
            {"offset": [0.25, -0.5], "texCoord": 1}}}},
        {"emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform":
            {"scale": [2, 3], "rotation": 0.3}}}}
    ])");
    Scene s = load(doc.gltf());
    ASSERT_EQ(s.materials.size(), 3u);
    const TextureRef& t = s.materials[0].emissive;
    ASSERT_TRUE(t.has_transform);
    auto apply = [](const glm::mat3& m, glm::vec2 uv) { return glm::vec2(m * glm::vec3(uv, 1.0f)); };
    // uv' = T * R * S * uv with, in GLSL column-major order,
    //   T = mat3(1,0,0, 0,1,0, ox,oy,1), R = mat3(cos,-sin,0, sin,cos,0, 0,0,1), S = mat3(sx,0,0, 0,sy,0, 0,0,1):
    //   u' = ox + sx*u*cos + sy*v*sin,  v' = oy - sx*u*sin + sy*v*cos.
    // With rotation pi/2: u' = 0.5 v, v' = 1 - 0.5 u. The unit square maps onto u' in [0, 0.5],
    // v' in [0.5, 1]: the lower-left quadrant (glTF v points down), rotated as the example says.
    const std::pair<glm::vec2, glm::vec2> cases[] = {
        {{1, 0}, {0, 0.5f}}, {{0, 0}, {0, 1}}, {{0, 1}, {0.5f, 1}}, {{1, 1}, {0.5f, 0.5f}}, {{0.5f, 0.5f}, {0.25f, 0.75f}},
    };
    for (const auto& [in, want] : cases) {
        glm::vec2 got = apply(t.transform, in);
        EXPECT_NEAR(got.x, want.x, 1e-6f) << "uv (" << in.x << ", " << in.y << ")";
        EXPECT_NEAR(got.y, want.y, 1e-6f) << "uv (" << in.x << ", " << in.y << ")";
    }
    // Offset only, with the extension's texCoord overriding the textureInfo's.
    const TextureRef& o = s.materials[1].emissive;
    EXPECT_EQ(o.tex_coord, 1);
    glm::vec2 g = apply(o.transform, glm::vec2(0.5f, 0.5f));
    EXPECT_NEAR(g.x, 0.75f, 1e-6f);
    EXPECT_NEAR(g.y, 0.0f, 1e-6f);
    // General case against the formula above.
    const TextureRef& r = s.materials[2].emissive;
    const float c = std::cos(0.3f), sn = std::sin(0.3f);
    for (glm::vec2 uv : {glm::vec2(0.2f, 0.7f), glm::vec2(1.0f, 0.0f), glm::vec2(-0.5f, 2.0f)}) {
        glm::vec2 got = apply(r.transform, uv);
        EXPECT_NEAR(got.x, 2 * uv.x * c + 3 * uv.y * sn, 1e-5f);
        EXPECT_NEAR(got.y, -2 * uv.x * sn + 3 * uv.y * c, 1e-5f);
    }
    // No extension: identity, no transform flag.
    Doc plain;
    plain.j["images"] = doc.j["images"];
    plain.j["textures"] = doc.j["textures"];
    plain.j["materials"] = json::array({{{"emissiveTexture", {{"index", 0}}}}});
    const TextureRef p = load(plain.gltf()).materials.at(0).emissive;
    EXPECT_FALSE(p.has_transform);
    EXPECT_EQ(p.transform, glm::mat3(1.0f));
}

TEST(GltfMaterials, BadTextureReferences) {
    Doc doc;
    doc.j["images"] = json::array({{{"uri", "data:image/png;base64," + base64(make_png(2, 2))}}});
    doc.j["textures"] = json::array({{{"source", 0}}});
    doc.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 3}}}}}}});
    EXPECT_EQ(load_error(doc.gltf()).where(), "/materials/0/pbrMetallicRoughness/baseColorTexture/index");
    // A corrupt image is a warning and an invalid (fallback) image, not an error.
    doc.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    doc.j["images"] = json::array({{{"uri", "data:image/png;base64," + base64({1, 2, 3, 4, 5, 6, 7, 8})}}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    ASSERT_EQ(s.images.size(), 1u);
    EXPECT_FALSE(s.images[0].valid());
    EXPECT_TRUE(has_warning(d, "/images/0", "neutral texture")) << all_warnings(d);
}

// =============================================================================================
// GLB

TEST(GltfGlb, BinChunkWithGeometryAndImage) {
    Image8 pixels;
    auto png = make_png(4, 3, &pixels);
    Doc doc;
    int pos = doc.positions(kQuad);
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3});
    int img_view = doc.view(png);
    doc.j["images"] = json::array({{{"bufferView", img_view}, {"mimeType", "image/png"}}});
    doc.j["textures"] = json::array({{{"source", 0}}});
    doc.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", ind}, {"material", 0}});
    auto glb = doc.glb();
    ASSERT_EQ(glb.size() % 4, 0u);
    Diagnostics d;
    Scene s = load(glb, d);
    ASSERT_EQ(s.meshes.size(), 1u);
    const Primitive& p = s.meshes[0].primitives.at(0);
    EXPECT_EQ(p.source_vertex_count, 4u);
    EXPECT_EQ(p.triangle_count(), 2u);
    EXPECT_EQ(p.positions.size(), 6u);  // flat normals
    EXPECT_EQ(p.positions[4], kQuad[2]);
    ASSERT_EQ(s.images.size(), 1u);
    ASSERT_TRUE(s.images[0].valid()) << all_warnings(d);
    EXPECT_EQ(s.images[0].pixels.width, 4);
    EXPECT_EQ(s.images[0].pixels.pixels, pixels.pixels);
    EXPECT_EQ(d.total(), 0u) << all_warnings(d);
}

// GltfLoadOptions::keep_encoded_images keeps each image's bytes (SceneImage::encoded, off by
// default); release_pixels frees the decoded pixels (the size stays) only where they are kept,
// and decode_again gives them back as first decoded, or names the image when it cannot.
TEST(GltfGlb, KeptEncodedImagesDecodeAgain) {
    Image8 pixels;
    auto png = make_png(4, 3, &pixels);
    Doc doc;
    int pos = doc.positions(kQuad);
    int img_view = doc.view(png);
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3});
    doc.j["images"] = json::array({{{"bufferView", img_view}, {"mimeType", "image/png"}, {"name", "quad colour"}}});
    doc.j["textures"] = json::array({{{"source", 0}}});
    doc.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", ind}, {"material", 0}});
    const auto glb = doc.glb();
    Diagnostics d;
    Scene plain = load(glb, d);
    ASSERT_TRUE(plain.images.at(0).valid());
    EXPECT_EQ(plain.images[0].encoded, nullptr);
    EXPECT_FALSE(plain.images[0].release_pixels());  // nothing to decode again from: kept
    EXPECT_EQ(plain.images[0].pixels.pixels, pixels.pixels);
    try {
        (void)decode_again(plain.images[0]);
        FAIL() << "decoded an image without its bytes";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("quad colour"), std::string::npos) << e.what();
    }

    GltfLoadOptions keep;
    keep.keep_encoded_images = true;
    Scene s = load(glb, d, keep);
    ASSERT_TRUE(s.images.at(0).encoded);
    EXPECT_EQ(*s.images[0].encoded, png);
    EXPECT_TRUE(s.images[0].release_pixels());
    EXPECT_TRUE(s.images[0].released());
    EXPECT_TRUE(s.images[0].valid());
    EXPECT_EQ(s.images[0].pixels.width, 4);
    EXPECT_TRUE(s.images[0].pixels.pixels.empty());
    EXPECT_EQ(decode_again(s.images[0]).pixels, pixels.pixels);
    Scene copy = s;  // copies share the bytes
    EXPECT_EQ(copy.images[0].encoded.get(), s.images[0].encoded.get());
    EXPECT_EQ(d.total(), 0u) << all_warnings(d);
}

TEST(GltfGlb, JsonOnlyGlbAndBadHeaders) {
    Doc doc;
    doc.j["nodes"] = json::array({{{"name", "only"}}});
    Scene s = load(doc.glb());
    ASSERT_EQ(s.nodes.size(), 1u);
    EXPECT_EQ(s.nodes[0].name, "only");

    auto glb = doc.glb();
    auto bad_version = glb;
    bad_version[4] = 1;
    EXPECT_EQ(load_error(bad_version).where(), "byte 4");
    auto long_len = glb;
    const std::uint32_t longer = std::uint32_t(glb.size() + 4);
    std::memcpy(&long_len[8], &longer, 4);
    EXPECT_EQ(load_error(long_len).where(), "byte 8");
    auto bad_chunk = glb;
    bad_chunk[16] = 'X';  // first chunk type must be JSON
    EXPECT_EQ(load_error(bad_chunk).where(), "byte 16");
}

TEST(GltfGlb, EveryTruncationThrowsError) {
    Doc doc;
    int pos = doc.positions(kQuad);
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 2, 0, 2, 3});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", ind}});
    auto glb = doc.glb();
    ASSERT_NO_THROW(load(glb));
    for (std::size_t n = 0; n < glb.size(); ++n) {
        std::vector<std::uint8_t> cut(glb.begin(), glb.begin() + std::ptrdiff_t(n));
        Diagnostics d;
        try {
            load(cut, d);
            ADD_FAILURE() << "truncated to " << n << " bytes loaded";
        } catch (const Error&) {
        } catch (const std::exception& e) {
            ADD_FAILURE() << "truncated to " << n << " bytes: non-fresnel exception " << e.what();
        }
        // The same with the header's length patched to match: the chunk checks must catch it.
        if (n >= 12) {
            std::uint32_t len = std::uint32_t(n);
            std::memcpy(&cut[8], &len, 4);
            try {
                load(cut, d);
                ADD_FAILURE() << "truncated to " << n << " bytes (length patched) loaded";
            } catch (const Error&) {
            } catch (const std::exception& e) {
                ADD_FAILURE() << "truncated to " << n << " bytes (length patched): non-fresnel exception " << e.what();
            }
        }
    }
}

// =============================================================================================
// Errors with JSON pointers

TEST(GltfErrors, AccessorPastItsBufferView) {
    Doc doc;
    int v = doc.view(pack(FLOAT, 3, {0, 0, 0, 1, 0, 0}));  // 24 bytes
    int pos = doc.add_accessor({{"bufferView", v}, {"componentType", FLOAT}, {"count", 3}, {"type", "VEC3"}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}});
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/accessors/0") << e.what();
    EXPECT_NE(e.reason().find("bufferView"), std::string::npos) << e.what();
    // Also by byteOffset.
    doc.j["accessors"][0]["count"] = 2;
    doc.j["accessors"][0]["byteOffset"] = 4;
    EXPECT_EQ(load_error(doc.gltf()).where(), "/accessors/0");
    doc.j["accessors"][0]["byteOffset"] = 0;
    EXPECT_NO_THROW(load(doc.gltf()));
}

TEST(GltfErrors, BufferViewPastItsBuffer) {
    Doc doc;
    int pos = doc.positions(kTriangle);  // 36 bytes
    doc.mesh({{"attributes", {{"POSITION", pos}}}});
    doc.j["bufferViews"][0]["byteOffset"] = 12;
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/bufferViews/0") << e.what();
    EXPECT_NE(e.reason().find("buffer"), std::string::npos) << e.what();
}

TEST(GltfErrors, IndexOutOfRange) {
    Doc doc;
    int pos = doc.positions(kTriangle);
    int ind = doc.indices(UNSIGNED_SHORT, {0, 1, 3});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", ind}});
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/meshes/0/primitives/0/indices") << e.what();
    EXPECT_NE(e.reason().find("3"), std::string::npos) << e.what();
}

TEST(GltfErrors, SparseIndexOutOfRange) {
    Doc doc;
    int v = doc.view(pack(FLOAT, 3, {0, 0, 0, 1, 0, 0, 0, 1, 0}));
    int iv = doc.view(pack(UNSIGNED_SHORT, 1, {1, 3}));
    int vv = doc.view(pack(FLOAT, 3, {5, 5, 5, 6, 6, 6}));
    int pos = doc.add_accessor({{"bufferView", v},
                                {"componentType", FLOAT},
                                {"count", 3},
                                {"type", "VEC3"},
                                {"sparse",
                                 {{"count", 2},
                                  {"indices", {{"bufferView", iv}, {"componentType", UNSIGNED_SHORT}}},
                                  {"values", {{"bufferView", vv}}}}}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}});
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/accessors/0/sparse/indices") << e.what();
    EXPECT_NE(e.reason().find("3"), std::string::npos) << e.what();
}

TEST(GltfErrors, UnsupportedRequiredExtension) {
    Doc doc;
    doc.j["extensionsUsed"] = {"KHR_texture_transform", "EXT_texture_avif"};
    doc.j["extensionsRequired"] = {"KHR_texture_transform", "EXT_texture_avif"};
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/extensionsRequired/1") << e.what();
    EXPECT_NE(e.reason().find("EXT_texture_avif"), std::string::npos) << e.what();
    // Merely used (not required): a warning.
    doc.j["extensionsRequired"] = {"KHR_texture_transform"};
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    EXPECT_TRUE(has_warning(d, "/extensionsUsed", "EXT_texture_avif")) << all_warnings(d);
    EXPECT_EQ(s.extensions_required, (std::vector<std::string>{"KHR_texture_transform"}));
}

TEST(GltfErrors, NodeCycle) {
    Doc doc;
    doc.j["nodes"] = json::array({{{"children", {1}}}, {{"children", {0}}}});
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/nodes/0") << e.what();
    EXPECT_NE(e.reason().find("cycle"), std::string::npos) << e.what();
    // A cycle next to a valid root.
    doc.j["nodes"] = json::array({{{"name", "root"}}, {{"children", {2}}}, {{"children", {1}}}});
    Error e2 = load_error(doc.gltf());
    EXPECT_EQ(e2.where(), "/nodes/1") << e2.what();
    // Its own child.
    doc.j["nodes"] = json::array({{{"children", {0}}}});
    EXPECT_EQ(load_error(doc.gltf()).where(), "/nodes/0/children/0");
}

TEST(GltfErrors, NodeWithTwoParents) {
    Doc doc;
    doc.j["nodes"] = json::array({{{"children", {2}}}, {{"children", {2}}}, {{"name", "child"}}});
    Error e = load_error(doc.gltf());
    EXPECT_EQ(e.where(), "/nodes/1/children/0") << e.what();
    EXPECT_NE(e.reason().find("parent"), std::string::npos) << e.what();
    // A child that does not exist.
    doc.j["nodes"] = json::array({{{"children", {5}}}});
    EXPECT_EQ(load_error(doc.gltf()).where(), "/nodes/0/children/0");
    // A scene root that has a parent.
    doc.j["nodes"] = json::array({{{"children", {1}}}, {{"name", "child"}}});
    doc.j["scenes"] = json::array({{{"nodes", {1}}}});
    EXPECT_EQ(load_error(doc.gltf()).where(), "/scenes/0/nodes/0");
}

TEST(GltfErrors, InvalidJson) {
    const std::string texts[] = {"{\"asset\": {\"version\": \"2.0\"},", "", "{\"asset\": {\"version\": \"2.0\"}} x",
                                 "[1, 2, 3]", "{\"asset\": 5}", "{\"asset\": {\"version\": \"1.0\"}}", "{}"};
    for (const auto& t : texts) {
        std::vector<std::uint8_t> bytes(t.begin(), t.end());
        Error e = load_error(bytes);
        EXPECT_EQ(e.file(), "test.gltf") << t;
        EXPECT_FALSE(e.reason().empty()) << t;
    }
    std::string truncated = "{\"asset\": {\"version\": \"2.0\"},";
    Error e = load_error(std::vector<std::uint8_t>(truncated.begin(), truncated.end()));
    EXPECT_EQ(e.where().rfind("byte ", 0), 0u) << e.where();
    EXPECT_NE(e.reason().find("JSON"), std::string::npos) << e.what();
    std::string v1 = "{\"asset\": {\"version\": \"1.0\"}}";
    EXPECT_EQ(load_error(std::vector<std::uint8_t>(v1.begin(), v1.end())).where(), "/asset/version");
    std::string noasset = "{}";
    EXPECT_EQ(load_error(std::vector<std::uint8_t>(noasset.begin(), noasset.end())).where(), "/asset");
}

TEST(GltfErrors, WrongJsonTypes) {
    Doc doc;
    int pos = doc.positions(kTriangle);
    doc.mesh({{"attributes", {{"POSITION", pos}}}});
    json bad = doc.with_buffer_uri(doc.data_uri());
    bad["meshes"][0]["primitives"][0]["mode"] = "triangles";
    EXPECT_EQ(load_error(bytes_of(bad)).where(), "/meshes/0/primitives/0/mode");
    bad = doc.with_buffer_uri(doc.data_uri());
    bad["accessors"][0]["count"] = -1;
    EXPECT_EQ(load_error(bytes_of(bad)).where(), "/accessors/0/count");
    bad = doc.with_buffer_uri(doc.data_uri());
    bad["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
    EXPECT_EQ(load_error(bytes_of(bad)).where(), "/meshes/0/primitives/0/attributes/POSITION");
    bad = doc.with_buffer_uri(doc.data_uri());
    bad["nodes"][0]["matrix"] = {1, 2, 3};
    EXPECT_EQ(load_error(bytes_of(bad)).where(), "/nodes/0/matrix");
}

// =============================================================================================
// URIs

TEST(GltfUris, RefusedUnlessAllowed) {
    TempDir dir;
    fs::path model_dir = dir.path() / "model";
    fs::create_directories(model_dir);
    Doc doc;
    int pos = doc.positions(kTriangle);
    doc.mesh({{"attributes", {{"POSITION", pos}}}});
    // The same bytes inside the model folder, next to it, and outside it.
    write_file(model_dir / "tri.bin", doc.bin);
    write_file(dir.path() / "x.bin", doc.bin);

    // Relative, inside the folder: loads.
    {
        Diagnostics d;
        Scene s = load_gltf_from_memory(bytes_of(doc.with_buffer_uri("tri.bin")), "m.gltf", model_dir, d);
        EXPECT_EQ(s.meshes.at(0).primitives.at(0).positions, kTriangle);
    }
    const std::string refused[] = {"../x.bin", "%2e%2e/x.bin", "/etc/passwd", (dir.path() / "x.bin").string(),
                                   "http://example.com/a.bin", "file:///etc/passwd"};
    for (const auto& uri : refused) {
        Error e = load_error(bytes_of(doc.with_buffer_uri(uri)), {}, model_dir);
        EXPECT_EQ(e.where(), "/buffers/0/uri") << uri << ": " << e.what();
        EXPECT_NE(e.reason().find(uri), std::string::npos) << "message should name '" << uri << "': " << e.what();
    }
    // With allow_external_files: an absolute path to a real file and a ".." escape load.
    GltfLoadOptions opt;
    opt.allow_external_files = true;
    {
        Diagnostics d;
        Scene s = load_gltf_from_memory(bytes_of(doc.with_buffer_uri((dir.path() / "x.bin").string())), "m.gltf",
                                        model_dir, d, opt);
        EXPECT_EQ(s.meshes.at(0).primitives.at(0).positions, kTriangle);
        Scene r = load_gltf_from_memory(bytes_of(doc.with_buffer_uri("../x.bin")), "m.gltf", model_dir, d, opt);
        EXPECT_EQ(r.meshes.at(0).primitives.at(0).positions, kTriangle);
    }
    // ... but never the network.
    for (const std::string uri : {"http://example.com/a.bin", "https://example.com/a.bin"}) {
        Error e = load_error(bytes_of(doc.with_buffer_uri(uri)), opt, model_dir);
        EXPECT_EQ(e.where(), "/buffers/0/uri") << e.what();
        EXPECT_NE(e.reason().find(uri), std::string::npos) << e.what();
    }
    // A missing file is an error naming it.
    Error missing = load_error(bytes_of(doc.with_buffer_uri("nope.bin")), {}, model_dir);
    EXPECT_EQ(missing.where(), "/buffers/0/uri");
    EXPECT_NE(missing.reason().find("nope.bin"), std::string::npos) << missing.what();
}

TEST(GltfUris, ImageUriPolicy) {
    TempDir dir;
    fs::path model_dir = dir.path() / "model";
    fs::create_directories(model_dir);
    auto png = make_png(2, 2);
    write_file(dir.path() / "x.png", png);
    write_file(model_dir / "ok.png", png);
    Doc doc;
    doc.j["images"] = json::array({{{"uri", "ok.png"}}});
    Diagnostics d;
    Scene s = load_gltf_from_memory(doc.gltf(), "m.gltf", model_dir, d);
    ASSERT_EQ(s.images.size(), 1u);
    EXPECT_TRUE(s.images[0].valid());
    for (const std::string uri : {"../x.png", "/etc/passwd", "http://example.com/a.png"}) {
        doc.j["images"] = json::array({{{"uri", uri}}});
        Error e = load_error(doc.gltf(), {}, model_dir);
        EXPECT_EQ(e.where(), "/images/0/uri") << e.what();
        EXPECT_NE(e.reason().find(uri), std::string::npos) << e.what();
    }
    // A missing image inside the folder is only a warning.
    doc.j["images"] = json::array({{{"uri", "missing.png"}}});
    Diagnostics d2;
    Scene m = load_gltf_from_memory(doc.gltf(), "m.gltf", model_dir, d2);
    EXPECT_FALSE(m.images.at(0).valid());
    EXPECT_TRUE(has_warning(d2, "/images/0/uri", "missing.png")) << all_warnings(d2);
}

TEST(GltfUris, LoadGltfFromFile) {
    TempDir dir;
    Doc doc;
    int pos = doc.positions(kQuad);
    int ind = doc.indices(UNSIGNED_BYTE, {0, 1, 2, 0, 2, 3});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", ind}});
    write_file(dir.path() / "quad.bin", doc.bin);
    write_file(dir.path() / "quad.gltf", bytes_of(doc.with_buffer_uri("quad.bin")));
    Diagnostics d;
    Scene s = load_gltf(dir.path() / "quad.gltf", d);
    EXPECT_EQ(s.meshes.at(0).primitives.at(0).triangle_count(), 2u);
    EXPECT_NE(s.source.find("quad.gltf"), std::string::npos);
}

// =============================================================================================
// Shared sample models

TEST(GltfSamples, DamagedHelmet) {
    fs::path p = fs::path(shared_dir()) / "assets/models/DamagedHelmet/DamagedHelmet.glb";
    if (!fs::exists(p)) GTEST_SKIP() << "shared asset not found: " << p;
    Diagnostics d;
    Scene s = load_gltf(p, d);
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].primitives.size(), 1u);
    const Primitive& prim = s.meshes[0].primitives[0];
    EXPECT_EQ(prim.source_vertex_count, 14556u);
    EXPECT_EQ(prim.triangle_count(), 15452u);
    ASSERT_EQ(s.images.size(), 5u);
    for (std::size_t i = 0; i < s.images.size(); ++i) EXPECT_TRUE(s.images[i].valid()) << "image " << i;
    EXPECT_TRUE(prim.generated_tangents);
    EXPECT_EQ(prim.tangents.size(), prim.positions.size());
    EXPECT_EQ(prim.normals.size(), prim.positions.size());
    EXPECT_FALSE(prim.generated_normals);
    ASSERT_GE(prim.material, 0);
    EXPECT_TRUE(s.materials[std::size_t(prim.material)].normal.valid());
}

TEST(GltfSamples, SimpleSparseAccessor) {
    fs::path dir = fs::path(shared_dir()) / "assets/models/SimpleSparseAccessor";
    if (!fs::exists(dir / "SimpleSparseAccessor.gltf")) GTEST_SKIP() << "shared asset not found: " << dir;
    Diagnostics d;
    Scene s = load_gltf(dir / "SimpleSparseAccessor.gltf", d);
    const Primitive& p = s.meshes.at(0).primitives.at(0);
    EXPECT_EQ(p.source_vertex_count, 14u);

    // Decode the file independently: indices (view 0), base positions (view 1),
    // sparse indices (view 2, unsigned short) and values (view 3).
    auto bin = read_file_bytes(dir / "SimpleSparseAccessor.bin", 1 << 20);
    ASSERT_EQ(bin.size(), 284u);
    std::vector<std::uint16_t> idx(36);
    std::memcpy(idx.data(), bin.data(), 72);
    std::vector<glm::vec3> base(14), expected(14);
    std::memcpy(base.data(), bin.data() + 72, 168);
    expected = base;
    std::uint16_t sidx[3];
    std::memcpy(sidx, bin.data() + 240, 6);
    glm::vec3 svals[3];
    std::memcpy(svals, bin.data() + 248, 36);
    for (int i = 0; i < 3; ++i) expected[sidx[i]] = svals[i];

    // No normals in the file: flat shading expands the vertices along the index list.
    ASSERT_TRUE(p.generated_normals);
    ASSERT_EQ(p.positions.size(), 36u);
    for (std::size_t k = 0; k < 36; ++k) EXPECT_EQ(p.positions[k], expected[idx[k]]) << "corner " << k;
    // The sparse-modified vertices are displaced from the base grid.
    for (int i = 0; i < 3; ++i) {
        EXPECT_NE(expected[sidx[i]], base[sidx[i]]);
        bool found = false;
        for (std::size_t k = 0; k < 36; ++k) found = found || (idx[k] == sidx[i] && p.positions[k] == svals[i]);
        EXPECT_TRUE(found) << "sparse vertex " << sidx[i];
    }
    EXPECT_FLOAT_EQ(p.bounds_max.y, 4.0f);
}

TEST(GltfSamples, Cameras) {
    fs::path p = fs::path(shared_dir()) / "assets/models/Cameras/Cameras.gltf";
    if (!fs::exists(p)) GTEST_SKIP() << "shared asset not found: " << p;
    Diagnostics d;
    Scene s = load_gltf(p, d);
    ASSERT_EQ(s.cameras.size(), 2u);
    int persp = 0, ortho = 0;
    for (const auto& c : s.cameras) (c.type == Camera::Type::Perspective ? persp : ortho)++;
    EXPECT_EQ(persp, 1);
    EXPECT_EQ(ortho, 1);
    EXPECT_EQ(s.cameras[0].type, Camera::Type::Perspective);
    EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.7f);
    EXPECT_EQ(s.cameras[1].type, Camera::Type::Orthographic);
    EXPECT_FLOAT_EQ(s.cameras[1].xmag, 1.0f);
    // Both cameras are attached to nodes.
    int with_camera = 0;
    for (const auto& n : s.nodes) with_camera += n.camera >= 0;
    EXPECT_EQ(with_camera, 2);
}

TEST(GltfSkinning, RestPoseMovesVerticesByJointWorldTimesInverseBind) {
    // Joint node translated by (2,0,0) with an identity inverse bind matrix: a vertex fully
    // weighted to it moves by (2,0,0); the mesh node's own transform no longer applies.
    Doc doc;
    int pos = doc.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    int joints = doc.attribute(UNSIGNED_BYTE, "VEC4", {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    int weights = doc.attribute(FLOAT, "VEC4", {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
    doc.mesh({{"attributes", {{"POSITION", pos}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}}});
    doc.j["nodes"][0]["skin"] = 0;
    doc.j["nodes"][0]["translation"] = {100, 0, 0};  // ignored for skinned meshes
    doc.j["nodes"].push_back({{"translation", {2, 0, 0}}});
    doc.j["scenes"][0]["nodes"].push_back(1);
    doc.j["skins"] = json::array({{{"joints", {1}}}});
    Diagnostics d;
    GltfLoadOptions opt;
    opt.pose_skins = true;
    Scene s = load(doc.gltf(), d, opt);
    const Node& node = s.nodes.at(0);
    ASSERT_TRUE(node.world_space_mesh);
    const Primitive& p = s.meshes.at(std::size_t(node.mesh)).primitives.at(0);
    EXPECT_FLOAT_EQ(p.positions[0].x, 2.0f);
    EXPECT_FLOAT_EQ(p.positions[1].x, 3.0f);
    EXPECT_FLOAT_EQ(p.positions[2].y, 1.0f);
    // The accessor's box is unchanged (the camera convention uses it with the node's matrix).
    EXPECT_FLOAT_EQ(p.bounds_max.x, 1.0f);
}

TEST(GltfSkinning, JointIndexOutOfRangeIsAnError) {
    Doc doc;
    int pos = doc.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    int joints = doc.attribute(UNSIGNED_BYTE, "VEC4", {5, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    int weights = doc.attribute(FLOAT, "VEC4", {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
    doc.mesh({{"attributes", {{"POSITION", pos}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}}});
    doc.j["nodes"][0]["skin"] = 0;
    doc.j["nodes"].push_back(json::object());
    doc.j["scenes"][0]["nodes"].push_back(1);
    doc.j["skins"] = json::array({{{"joints", {1}}}});
    Diagnostics d;
    GltfLoadOptions opt;
    opt.pose_skins = true;
    EXPECT_THROW(load(doc.gltf(), d, opt), Error);
    // Without posing, the skin is not evaluated and the mesh loads in its bind pose.
    Diagnostics d2;
    EXPECT_NO_THROW(load(doc.gltf(), d2));
}

TEST(GltfMorphTargets, DefaultWeightsApplied) {
    Doc doc;
    int pos = doc.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    int delta = doc.positions({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"targets", json::array({{{"POSITION", delta}}})}});
    doc.j["meshes"][0]["weights"] = {0.5};
    Scene s = load(doc.gltf());
    const Primitive& p = s.meshes.at(0).primitives.at(0);
    EXPECT_FLOAT_EQ(p.positions[1].z, 0.5f);
}
