// Tests of the glTF geometry and texture extensions on GLB files assembled in memory:
// EXT_meshopt_compression, KHR_draco_mesh_compression (encoded here with the libraries'
// own encoders), EXT_texture_webp, KHR_texture_basisu (KTX2 in place of the core source) and
// KHR_materials_variants. Corrupt compressed data (every truncation, wrong counts) must
// give a fresnel::Error naming the extension and the glTF place, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <webp/encode.h>

#include "fresnel/scene/gltf_loader.h"
#include "../src/meshopt_filters.h"

using namespace fresnel;
using json = nlohmann::json;

namespace {
namespace fs = std::filesystem;

constexpr int FLOAT = 5126, UNSIGNED_SHORT = 5123, UNSIGNED_INT = 5125, BYTE = 5120;

void append(std::vector<std::uint8_t>& out, const void* p, std::size_t n) {
    auto b = static_cast<const std::uint8_t*>(p);
    out.insert(out.end(), b, b + n);
}
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) { append(out, &v, 4); }
void align4(std::vector<std::uint8_t>& v, std::uint8_t fill = 0) {
    while (v.size() % 4) v.push_back(fill);
}

std::vector<std::uint8_t> glb(const json& j, std::vector<std::uint8_t> bin) {
    std::string text = j.dump();
    while (text.size() % 4) text += ' ';
    align4(bin);
    std::vector<std::uint8_t> out;
    put_u32(out, 0x46546C67);
    put_u32(out, 2);
    put_u32(out, std::uint32_t(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
    put_u32(out, std::uint32_t(text.size()));
    put_u32(out, 0x4E4F534A);
    append(out, text.data(), text.size());
    if (!bin.empty()) {
        put_u32(out, std::uint32_t(bin.size()));
        put_u32(out, 0x004E4942);
        append(out, bin.data(), bin.size());
    }
    return out;
}

Scene load(const json& j, const std::vector<std::uint8_t>& bin, Diagnostics& d, GltfLoadOptions o = {}) {
    auto bytes = glb(j, bin);
    return load_gltf_from_memory(bytes, "test.glb", "/nonexistent-fresnel-test", d, o);
}

// The Error of loading (fails the test when it loads).
Error load_error(const json& j, const std::vector<std::uint8_t>& bin) {
    Diagnostics d;
    try {
        load(j, bin, d);
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "loaded without an error";
    return Error("", "", "");
}

std::string warnings(const Diagnostics& d) {
    std::string s;
    for (const auto& l : d.lines()) s += l + "\n";
    return s;
}

const std::vector<float> kQuad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};  // 4 vertices
const std::vector<unsigned> kQuadIndices = {0, 1, 2, 0, 2, 3};

json base_doc() {
    return {{"asset", {{"version", "2.0"}}},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}}};
}

// ---- EXT_meshopt_compression ---------------------------------------------------------

struct MeshoptFile {
    json j;
    std::vector<std::uint8_t> bin;
    std::size_t vertex_bytes = 0, index_bytes = 0;
};

MeshoptFile meshopt_quad() {
    MeshoptFile f;
    std::vector<std::uint8_t> vbuf(meshopt_encodeVertexBufferBound(4, 12));
    f.vertex_bytes = meshopt_encodeVertexBuffer(vbuf.data(), vbuf.size(), kQuad.data(), 4, 12);
    vbuf.resize(f.vertex_bytes);
    std::vector<std::uint8_t> ibuf(meshopt_encodeIndexBufferBound(6, 4));
    f.index_bytes = meshopt_encodeIndexBuffer(ibuf.data(), ibuf.size(), kQuadIndices.data(), 6);
    ibuf.resize(f.index_bytes);
    f.bin = vbuf;
    align4(f.bin);
    std::size_t ioff = f.bin.size();
    append(f.bin, ibuf.data(), ibuf.size());
    f.j = base_doc();
    f.j["extensionsUsed"] = {"EXT_meshopt_compression"};
    f.j["extensionsRequired"] = {"EXT_meshopt_compression"};
    f.j["buffers"] = {{{"byteLength", f.bin.size() + (4 - f.bin.size() % 4) % 4}},
                      {{"byteLength", 60}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
    f.j["bufferViews"] = {
        {{"buffer", 1}, {"byteOffset", 0}, {"byteLength", 48}, {"byteStride", 12},
         {"extensions", {{"EXT_meshopt_compression", {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", f.vertex_bytes},
                                                      {"byteStride", 12}, {"count", 4}, {"mode", "ATTRIBUTES"}}}}}},
        {{"buffer", 1}, {"byteOffset", 48}, {"byteLength", 12},
         {"extensions", {{"EXT_meshopt_compression", {{"buffer", 0}, {"byteOffset", ioff}, {"byteLength", f.index_bytes},
                                                      {"byteStride", 2}, {"count", 6}, {"mode", "TRIANGLES"}}}}}}};
    f.j["accessors"] = {{{"bufferView", 0}, {"componentType", FLOAT}, {"count", 4}, {"type", "VEC3"},
                         {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                        {{"bufferView", 1}, {"componentType", UNSIGNED_SHORT}, {"count", 6}, {"type", "SCALAR"}}};
    f.j["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}};
    return f;
}

json& meshopt_ext(json& j, int view) { return j["bufferViews"][std::size_t(view)]["extensions"]["EXT_meshopt_compression"]; }

TEST(GltfMeshopt, DecodesAttributesAndTriangles) {
    MeshoptFile f = meshopt_quad();
    Diagnostics d;
    Scene s = load(f.j, f.bin, d);
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].primitives.size(), 1u);
    const Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.triangle_count(), 2u);
    ASSERT_EQ(p.source_vertex_count, 4u);
    // Whatever re-indexing happened, every triangle corner is one of the quad's vertices, in order.
    std::vector<glm::vec3> corners;
    for (std::size_t i = 0; i < 6; ++i) corners.push_back(p.positions[p.indices.empty() ? i : p.indices[i]]);
    for (std::size_t i = 0; i < 6; ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(corners[i][c], kQuad[kQuadIndices[i] * 3 + std::size_t(c)]) << i;
    EXPECT_EQ(warnings(d).find("no uri"), std::string::npos) << warnings(d);  // the fallback buffer is expected
}

TEST(GltfMeshopt, OctahedralFilterNormals) {
    MeshoptFile f = meshopt_quad();
    // Normals as 8-bit octahedral (stride 4), filtered and encoded as gltfpack does.
    std::vector<float> normals = {0, 0, 1, 0, 0.6f, 0, 0.8f, 0, 0, 1, 0, 0, 1, 0, 0, 0};
    std::vector<std::int8_t> oct(16);
    meshopt_encodeFilterOct(oct.data(), 4, 4, 8, normals.data());
    std::vector<std::uint8_t> enc(meshopt_encodeVertexBufferBound(4, 4));
    enc.resize(meshopt_encodeVertexBuffer(enc.data(), enc.size(), oct.data(), 4, 4));
    align4(f.bin);
    std::size_t off = f.bin.size();
    append(f.bin, enc.data(), enc.size());
    f.j["buffers"][0]["byteLength"] = f.bin.size();
    f.j["bufferViews"].push_back(
        {{"buffer", 1}, {"byteOffset", 0}, {"byteLength", 16}, {"byteStride", 4},
         {"extensions", {{"EXT_meshopt_compression", {{"buffer", 0}, {"byteOffset", off}, {"byteLength", enc.size()},
                                                      {"byteStride", 4}, {"count", 4}, {"mode", "ATTRIBUTES"},
                                                      {"filter", "OCTAHEDRAL"}}}}}});
    f.j["accessors"].push_back({{"bufferView", 2}, {"componentType", BYTE}, {"normalized", true}, {"count", 4}, {"type", "VEC3"}});
    f.j["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
    Diagnostics d;
    Scene s = load(f.j, f.bin, d);
    const Primitive& p = s.meshes[0].primitives[0];
    ASSERT_FALSE(p.generated_normals);
    // Vertex 1's normal (0.6, 0, 0.8) through 8 bits: within a few hundredths.
    for (std::size_t i = 0; i < p.positions.size(); ++i)
        if (p.positions[i] == glm::vec3(1, 0, 0)) {
            EXPECT_NEAR(p.normals[i].x, 0.6f, 0.03f);
            EXPECT_NEAR(p.normals[i].z, 0.8f, 0.03f);
        }
}

// ---- the filters, byte for byte as the extension's reference decoder -----------------
// The expected hashes are FNV-1a 64 of what meshoptimizer 1.2's js/meshopt_decoder_reference.js
// writes for the same inputs (one xorshift32 stream); meshopt_reference_hashes.mjs beside this
// file prints them. Debian's meshoptimizer 0.18 decodes 8-bit octahedral normals within one
// step of these; ours must match them exactly.

std::uint64_t fnv1a(const std::vector<std::uint8_t>& bytes) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ull;
    return h;
}

struct Xorshift32 {
    std::uint32_t s = 2463534242u;
    std::uint32_t operator()() {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        return s;
    }
};

template <typename T>
std::vector<std::uint8_t> bytes_of(const std::vector<T>& v) {
    std::vector<std::uint8_t> b(v.size() * sizeof(T));
    std::memcpy(b.data(), v.data(), b.size());
    return b;
}

TEST(GltfMeshoptFilters, MatchTheReferenceDecoderExactly) {
    Xorshift32 rnd;
    // 8-bit octahedral: every x, y in [-127, 127], one = 127, w = 0x55 (kept).
    std::vector<std::uint8_t> oct8;
    for (int x = -127; x <= 127; ++x)
        for (int y = -127; y <= 127; ++y)
            oct8.insert(oct8.end(), {std::uint8_t(x & 255), std::uint8_t(y & 255), 127, 0x55});
    std::vector<std::uint8_t> library = oct8;
    gltf::meshopt_filter_octahedral(oct8.data(), oct8.size() / 4, 4);
    EXPECT_EQ(fnv1a(oct8), 0x4920947a9fb36abdull);
    // Debian's library agrees within one step (the reason for owning these lines).
    meshopt_decodeFilterOct(library.data(), library.size() / 4, 4);
    int differ = 0;
    for (std::size_t i = 0; i < oct8.size(); ++i) {
        int d = int(std::int8_t(oct8[i])) - int(std::int8_t(library[i]));
        EXPECT_LE(std::abs(d), 1) << i;
        differ += d != 0;
    }
    std::printf("8-bit octahedral: %d of %zu components one step from meshoptimizer %d.%d's\n", differ, oct8.size(),
                MESHOPTIMIZER_VERSION / 1000, MESHOPTIMIZER_VERSION % 1000 / 10);
    // and every decoded normal has length 127 to within rounding
    for (std::size_t i = 0; i < oct8.size(); i += 4) {
        double x = std::int8_t(oct8[i]), y = std::int8_t(oct8[i + 1]), z = std::int8_t(oct8[i + 2]);
        EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 127.0, 1.5) << i;
        EXPECT_EQ(oct8[i + 3], 0x55);
    }

    // 16-bit octahedral: one in [1, 32767], x and y in [-one, one].
    std::vector<std::int16_t> oct16;
    for (int i = 0; i < 20000; ++i) {
        int one = 1 + int(rnd() % 32767);
        int x = int(rnd() % std::uint32_t(2 * one + 1)) - one;
        int y = int(rnd() % std::uint32_t(2 * one + 1)) - one;
        int w = int(rnd() & 0x7fff);
        oct16.insert(oct16.end(), {std::int16_t(x), std::int16_t(y), std::int16_t(one), std::int16_t(w)});
    }
    auto b16 = bytes_of(oct16);
    gltf::meshopt_filter_octahedral(b16.data(), b16.size() / 8, 8);
    EXPECT_EQ(fnv1a(b16), 0x72d5ebd4aafee488ull);

    // Quaternions: any 16-bit words, hostile scales included.
    std::vector<std::uint16_t> quat;
    for (int i = 0; i < 20000 * 4; ++i) quat.push_back(std::uint16_t(rnd() & 0xffff));
    auto bq = bytes_of(quat);
    gltf::meshopt_filter_quaternion(bq.data(), bq.size() / 8, 8);
    EXPECT_EQ(fnv1a(bq), 0x80f4fa5620463639ull);

    // Exponential: any 32-bit words, three per element.
    std::vector<std::uint32_t> expo;
    for (int i = 0; i < 20000 * 3; ++i) expo.push_back(rnd());
    auto be = bytes_of(expo);
    gltf::meshopt_filter_exponential(be.data(), be.size() / 12, 12);
    EXPECT_EQ(fnv1a(be), 0x845771aa4c29c818ull);

    // Hostile 8-bit octahedral: any bytes (a zero or negative `one` gives NaN or infinities,
    // stored as 0 or wrapped, as a JavaScript Int8Array stores them).
    std::vector<std::uint8_t> any;
    for (int i = 0; i < 20000 * 4; ++i) any.push_back(std::uint8_t(rnd() & 255));
    gltf::meshopt_filter_octahedral(any.data(), any.size() / 4, 4);
    EXPECT_EQ(fnv1a(any), 0x635f62021bf5a0c1ull);
}

TEST(GltfMeshopt, EveryTruncationIsAClearError) {
    MeshoptFile f = meshopt_quad();
    for (std::size_t n = 1; n < f.vertex_bytes; ++n) {
        json j = f.j;
        meshopt_ext(j, 0)["byteLength"] = n;
        Error e = load_error(j, f.bin);
        EXPECT_EQ(e.where(), "/bufferViews/0/extensions/EXT_meshopt_compression") << n << ": " << e.what();
        EXPECT_NE(e.reason().find("EXT_meshopt_compression: "), std::string::npos) << e.what();
    }
    for (std::size_t n = 1; n < f.index_bytes; ++n) {
        json j = f.j;
        meshopt_ext(j, 1)["byteLength"] = n;
        Error e = load_error(j, f.bin);
        EXPECT_EQ(e.where().rfind("/bufferViews/1/extensions/EXT_meshopt_compression", 0), 0u) << n << ": " << e.what();
    }
}

TEST(GltfMeshopt, WrongCountsAndParametersAreErrors) {
    MeshoptFile f = meshopt_quad();
    struct Case { int view; const char* key; json value; const char* where; };
    const Case cases[] = {
        {0, "count", 1000, "/count"},                    // more elements than the view holds
        {0, "byteStride", 10, "/byteStride"},            // not a multiple of 4
        {0, "byteStride", 300, "/byteStride"},           // over 256
        {1, "count", 4, "/count"},                       // TRIANGLES need a multiple of 3
        {1, "byteStride", 3, "/byteStride"},
        {0, "mode", "STRIPS", "/mode"},
        {0, "filter", "MAGIC", "/filter"},
        {1, "filter", "OCTAHEDRAL", "/filter"},           // filters are for ATTRIBUTES
        {0, "buffer", 7, "/buffer"},
        {0, "byteOffset", 1 << 20, "/byteLength"},        // past the buffer
    };
    for (const Case& c : cases) {
        json j = f.j;
        meshopt_ext(j, c.view)[c.key] = c.value;
        Error e = load_error(j, f.bin);
        std::string want = "/bufferViews/" + std::to_string(c.view) + "/extensions/EXT_meshopt_compression" + c.where;
        EXPECT_EQ(e.where(), want) << c.key << "=" << c.value << ": " << e.what();
    }
    // A decoded size over what the stream can hold, or over the loader's limit, is refused
    // before it is allocated.
    json j = f.j;
    j["bufferViews"][0]["byteLength"] = 1ull << 40;
    Error e = load_error(j, f.bin);
    EXPECT_EQ(e.where(), "/bufferViews/0/byteLength") << e.what();
    EXPECT_NE(e.reason().find("cannot come from"), std::string::npos) << e.what();
    GltfLoadOptions small;
    small.max_total_bytes = f.j["buffers"][0]["byteLength"].get<std::size_t>() + 10;  // not the 48 decoded bytes
    Diagnostics d;
    try {
        load(f.j, f.bin, d, small);
        ADD_FAILURE();
    } catch (const Error& e2) {
        EXPECT_EQ(e2.where(), "/bufferViews/0") << e2.what();
        EXPECT_NE(e2.reason().find("limit"), std::string::npos) << e2.what();
    }
}

// ---- KHR_draco_mesh_compression ------------------------------------------------------

struct DracoFile {
    json j;
    std::vector<std::uint8_t> bin;
    std::size_t points = 0, faces = 0;
};

DracoFile draco_quad() {
    draco::TriangleSoupMeshBuilder b;
    b.Start(2);
    int pos = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    int uv = b.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    const float uvs[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int f = 0; f < 2; ++f) {
        const unsigned* t = &kQuadIndices[std::size_t(f) * 3];
        b.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &kQuad[t[0] * 3], &kQuad[t[1] * 3], &kQuad[t[2] * 3]);
        b.SetAttributeValuesForFace(uv, draco::FaceIndex(f), uvs[t[0]], uvs[t[1]], uvs[t[2]]);
    }
    auto mesh = b.Finalize();
    draco::Encoder enc;
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    draco::EncoderBuffer out;
    EXPECT_TRUE(enc.EncodeMeshToBuffer(*mesh, &out).ok());
    DracoFile f;
    f.bin.assign(out.data(), out.data() + out.size());
    // The counts the accessors must state: those of the decoded mesh.
    draco::DecoderBuffer in;
    in.Init(out.data(), out.size());
    draco::Decoder dec;
    auto decoded = dec.DecodeMeshFromBuffer(&in);
    EXPECT_TRUE(decoded.ok());
    f.points = decoded.value()->num_points();
    f.faces = decoded.value()->num_faces();
    int pos_id = int(mesh->attribute(pos)->unique_id()), uv_id = int(mesh->attribute(uv)->unique_id());
    f.j = base_doc();
    f.j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    f.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    f.j["buffers"] = {{{"byteLength", f.bin.size()}}};
    f.j["bufferViews"] = {{{"buffer", 0}, {"byteLength", f.bin.size()}}};
    f.j["accessors"] = {{{"componentType", FLOAT}, {"count", f.points}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                        {{"componentType", FLOAT}, {"count", f.points}, {"type", "VEC2"}},
                        {{"componentType", UNSIGNED_SHORT}, {"count", f.faces * 3}, {"type", "SCALAR"}}};
    json ext = {{"bufferView", 0}, {"attributes", {{"POSITION", pos_id}, {"TEXCOORD_0", uv_id}}}};
    json prim = {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}};
    prim["extensions"]["KHR_draco_mesh_compression"] = ext;
    f.j["meshes"] = json::array({{{"primitives", json::array({prim})}}});
    return f;
}

json& draco_ext(json& j) { return j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]; }
const char* kDracoPtr = "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression";

TEST(GltfDraco, DecodesPositionsTexcoordsAndIndices) {
    DracoFile f = draco_quad();
    ASSERT_EQ(f.faces, 2u);
    Diagnostics d;
    Scene s = load(f.j, f.bin, d);
    ASSERT_EQ(s.meshes[0].primitives.size(), 1u) << warnings(d);
    const Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.triangle_count(), 2u);
    ASSERT_EQ(p.uv0.size(), p.positions.size());
    // Each corner: a quad vertex (to 14-bit quantisation) with its texture coordinate.
    float area = 0;
    for (std::size_t t = 0; t < 2; ++t) {
        glm::vec3 c[3];
        for (int k = 0; k < 3; ++k) {
            std::size_t v = p.indices.empty() ? t * 3 + std::size_t(k) : p.indices[t * 3 + std::size_t(k)];
            c[k] = p.positions[v];
            EXPECT_NEAR(p.uv0[v].x, c[k].x, 1e-3) << v;
            EXPECT_NEAR(p.uv0[v].y, c[k].y, 1e-3) << v;
            EXPECT_TRUE(std::abs(c[k].x - std::round(c[k].x)) < 1e-3 && std::abs(c[k].y - std::round(c[k].y)) < 1e-3);
        }
        area += 0.5f * std::abs(glm::cross(c[1] - c[0], c[2] - c[0]).z);
    }
    EXPECT_NEAR(area, 1.0f, 1e-3);
}

TEST(GltfDraco, EveryTruncationIsAClearError) {
    DracoFile f = draco_quad();
    for (std::size_t n = 1; n < f.bin.size(); ++n) {
        json j = f.j;
        j["bufferViews"][0]["byteLength"] = n;
        Diagnostics d;
        try {
            load(j, f.bin, d);
            // Draco may still decode a mesh from a prefix; then it must be the right one.
        } catch (const Error& e) {
            EXPECT_EQ(e.where().rfind(kDracoPtr, 0), 0u) << n << ": " << e.what();
            EXPECT_NE(e.reason().find("KHR_draco_mesh_compression: "), std::string::npos) << e.what();
        }
    }
}

TEST(GltfDraco, CorruptBytesNeverCrash) {
    DracoFile f = draco_quad();
    for (std::size_t i = 0; i < f.bin.size(); ++i)
        for (std::uint8_t x : {0x01, 0x80, 0xff}) {
            auto bin = f.bin;
            bin[i] ^= x;
            Diagnostics d;
            try {
                load(f.j, bin, d);
            } catch (const Error& e) {
                EXPECT_FALSE(e.reason().empty());
            }
        }
}

TEST(GltfDraco, WrongCountsAndIdsAreErrors) {
    DracoFile f = draco_quad();
    {
        json j = f.j;
        j["accessors"][0]["count"] = f.points + 1;
        j["accessors"][1]["count"] = f.points + 1;
        Error e = load_error(j, f.bin);
        EXPECT_EQ(e.where(), kDracoPtr) << e.what();
        EXPECT_NE(e.reason().find("points"), std::string::npos) << e.what();
    }
    {
        json j = f.j;
        j["accessors"][1]["count"] = f.points + 1;  // attributes disagree with each other
        EXPECT_EQ(load_error(j, f.bin).where().rfind(std::string(kDracoPtr) + "/attributes/", 0), 0u);
    }
    {
        json j = f.j;
        j["accessors"][2]["count"] = 3;
        Error e = load_error(j, f.bin);
        EXPECT_NE(e.reason().find("triangles"), std::string::npos) << e.what();
    }
    {
        json j = f.j;
        draco_ext(j)["attributes"]["POSITION"] = 99;
        EXPECT_EQ(load_error(j, f.bin).where(), std::string(kDracoPtr) + "/attributes/POSITION");
    }
    {
        json j = f.j;
        j["accessors"][1]["type"] = "VEC3";  // the Draco attribute has 2 components
        EXPECT_EQ(load_error(j, f.bin).where(), std::string(kDracoPtr) + "/attributes/TEXCOORD_0");
    }
    {
        json j = f.j;
        draco_ext(j)["attributes"]["NORMAL"] = 0;  // not among the primitive's attributes
        EXPECT_EQ(load_error(j, f.bin).where(), std::string(kDracoPtr) + "/attributes/NORMAL");
    }
    {
        json j = f.j;
        j["accessors"][0]["count"] = 1ll << 40;  // over the vertex limit: refused before decoding
        j["accessors"][1]["count"] = 1ll << 40;
        Error e = load_error(j, f.bin);
        EXPECT_EQ(e.where(), "/accessors/0/count") << e.what();
    }
    {
        json j = f.j;
        std::vector<std::uint8_t> junk(64, 0x5a);
        j["buffers"][0]["byteLength"] = junk.size();
        j["bufferViews"][0]["byteLength"] = junk.size();
        Error e = load_error(j, junk);
        EXPECT_NE(e.reason().find("KHR_draco_mesh_compression: "), std::string::npos) << e.what();
    }
}

// The memory bomb: a stream whose own attribute headers ask for far more than the glTF
// accessors describe (an attribute of 255 components the file never names, which Draco sizes
// and zero-fills per point before reading a value). Refused by the memory budget before Draco
// allocates it; the same file decodes under a budget that holds it.
TEST(GltfDraco, TheStreamsOwnAttributesAreWithinTheBudget) {
    const int n = 24;  // an n x n grid of quads: 2 n^2 triangles
    draco::TriangleSoupMeshBuilder b;
    b.Start(2 * n * n);
    int pos = b.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    int wide = b.AddAttribute(draco::GeometryAttribute::GENERIC, 255, draco::DT_UINT8);
    std::vector<std::uint8_t> zeros(255, 0);
    int face = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float c[4][3] = {{float(x), float(y), 0}, {float(x + 1), float(y), 0}, {float(x + 1), float(y + 1), 0},
                                   {float(x), float(y + 1), 0}};
            static const int kTriangles[2][3] = {{0, 1, 2}, {0, 2, 3}};
            for (const int* t : kTriangles) {
                b.SetAttributeValuesForFace(pos, draco::FaceIndex(face), c[t[0]], c[t[1]], c[t[2]]);
                b.SetAttributeValuesForFace(wide, draco::FaceIndex(face), zeros.data(), zeros.data(), zeros.data());
                ++face;
            }
        }
    auto mesh = b.Finalize();
    ASSERT_TRUE(mesh);
    draco::Encoder enc;
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    draco::EncoderBuffer out;
    ASSERT_TRUE(enc.EncodeMeshToBuffer(*mesh, &out).ok());
    draco::DecoderBuffer in;
    in.Init(out.data(), out.size());
    auto decoded = draco::Decoder().DecodeMeshFromBuffer(&in);
    ASSERT_TRUE(decoded.ok());
    const std::size_t points = decoded.value()->num_points(), faces = decoded.value()->num_faces();
    std::vector<std::uint8_t> bin(out.data(), out.data() + out.size());
    json j = base_doc();
    j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    j["buffers"] = {{{"byteLength", bin.size()}}};
    j["bufferViews"] = {{{"buffer", 0}, {"byteLength", bin.size()}}};
    j["accessors"] = {{{"componentType", FLOAT}, {"count", points}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {n, n, 0}}},
                      {{"componentType", UNSIGNED_INT}, {"count", faces * 3}, {"type", "SCALAR"}}};
    json prim = {{"attributes", {{"POSITION", 0}}}, {"indices", 1}};
    prim["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", 0},
                                                        {"attributes", {{"POSITION", int(mesh->attribute(pos)->unique_id())}}}};
    j["meshes"] = json::array({{{"primitives", json::array({prim})}}});
    // What the accessors describe is small; the stream's 255-component attribute is not.
    const std::size_t described = points * 3 * (sizeof(double) + 4) + faces * 3 * 16;
    const std::size_t asked = points * 255 * 5;
    ASSERT_GT(asked, 8 * described) << points << " points in " << bin.size() << " bytes";
    GltfLoadOptions tight;
    tight.max_geometry_bytes = described * 4;
    Diagnostics d;
    try {
        load(j, bin, d, tight);
        ADD_FAILURE() << "decoded " << asked << " bytes of attributes under a budget of " << tight.max_geometry_bytes;
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), kDracoPtr) << e.what();
        EXPECT_NE(e.reason().find("memory budget"), std::string::npos) << e.what();
    }
    GltfLoadOptions roomy;
    roomy.max_geometry_bytes = asked * 2 + described * 4;
    Scene s = load(j, bin, d, roomy);
    EXPECT_EQ(s.meshes[0].primitives[0].triangle_count(), faces);
}

// ---- EXT_texture_webp and KHR_texture_basisu ------------------------------------------

std::vector<std::uint8_t> webp_2x2() {
    const std::uint8_t rgba[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 128, 255, 255, 255, 0};
    std::uint8_t* out = nullptr;
    std::size_t n = WebPEncodeLosslessRGBA(rgba, 2, 2, 8, &out);
    std::vector<std::uint8_t> v(out, out + n);
    WebPFree(out);
    return v;
}

json texture_doc(std::size_t image_bytes, const json& texture, const char* mime) {
    json j = base_doc();
    j["nodes"] = json::array();
    j["scenes"] = {{{"nodes", json::array()}}};
    j["buffers"] = {{{"byteLength", image_bytes}}};
    j["bufferViews"] = {{{"buffer", 0}, {"byteLength", image_bytes}}};
    j["images"] = {{{"bufferView", 0}, {"mimeType", mime}}};
    j["textures"] = {texture};
    j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    return j;
}

TEST(GltfTextureWebp, DecodesTheExtensionSource) {
    auto webp = webp_2x2();
    json j = texture_doc(webp.size(), {{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}, "image/webp");
    j["extensionsUsed"] = {"EXT_texture_webp"};
    j["extensionsRequired"] = {"EXT_texture_webp"};
    Diagnostics d;
    Scene s = load(j, webp, d);
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].image, 0);
    ASSERT_TRUE(s.images[0].valid()) << warnings(d);
    EXPECT_EQ(s.images[0].pixels.width, 2);
    const std::uint8_t* px = s.images[0].pixels.at(0, 1);
    EXPECT_EQ(px[2], 255);
    EXPECT_EQ(px[3], 128);
    EXPECT_TRUE(d.lines().empty()) << warnings(d);
}

TEST(GltfTextureWebp, CorruptOrOversizedImagesWarnAndFallBack) {
    auto webp = webp_2x2();
    json tex = {{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}};
    for (std::size_t n = 12; n < webp.size(); ++n) {
        std::vector<std::uint8_t> cut(webp.begin(), webp.begin() + std::ptrdiff_t(n));
        Diagnostics d;
        Scene s = load(texture_doc(n, tex, "image/webp"), cut, d);
        EXPECT_FALSE(s.images[0].valid()) << n;
        EXPECT_NE(warnings(d).find("EXT_texture_webp"), std::string::npos) << n << warnings(d);
    }
    GltfLoadOptions o;
    o.image_limits.max_dimension = 1;
    Diagnostics d;
    Scene s = load(texture_doc(webp.size(), tex, "image/webp"), webp, d, o);
    EXPECT_FALSE(s.images[0].valid());
    EXPECT_NE(warnings(d).find("outside"), std::string::npos) << warnings(d);
}

std::vector<std::uint8_t> shared_ktx2(const char* name) {
    const fs::path p = fs::path(FRESNEL_SHARED_DIR) / "assets" / "ktx2" / name;
    std::ifstream in(p, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

TEST(GltfTextureBasisu, DecodesTheKtx2SourceInPlaceOfTheCoreSource) {
    for (const char* file : {"kodim23_etc1s.ktx2", "kodim23_uastc_zstd_mips.ktx2"}) {
        auto ktx2 = shared_ktx2(file);
        if (ktx2.empty()) GTEST_SKIP() << "no ../shared/assets/ktx2";
        json j = texture_doc(ktx2.size(), {{"source", 1}, {"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}},
                             "image/ktx2");
        j["images"].push_back({{"uri", "fallback.png"}});  // not read: the KTX2 image decoded
        j["extensionsUsed"] = {"KHR_texture_basisu"};
        j["extensionsRequired"] = {"KHR_texture_basisu"};
        Diagnostics d;
        Scene s = load(j, ktx2, d);
        EXPECT_EQ(s.textures[0].image, 0) << file;
        ASSERT_TRUE(s.images[0].valid()) << file << warnings(d);
        EXPECT_EQ(s.images[0].pixels.width, 768);
        EXPECT_EQ(s.images[0].pixels.height, 512);
    }
}

TEST(GltfTextureBasisu, ABrokenKtx2FallsBackToTheCoreSourceWithAWarning) {
    auto webp = webp_2x2();  // the core source: any image fresnel decodes
    json j = texture_doc(webp.size(), {{"source", 0}, {"extensions", {{"KHR_texture_basisu", {{"source", 1}}}}}},
                         "image/webp");
    j["buffers"][0]["byteLength"] = webp.size() + 100;
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", webp.size()}, {"byteLength", 100}});
    j["images"].push_back({{"bufferView", 1}, {"mimeType", "image/ktx2"}});
    j["extensionsUsed"] = {"KHR_texture_basisu"};
    std::vector<std::uint8_t> bin = webp;
    const std::uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    bin.insert(bin.end(), id, id + 12);
    bin.resize(webp.size() + 100, 0);  // a KTX2 identifier, then a header of zeros
    Diagnostics d;
    Scene s = load(j, bin, d);
    EXPECT_EQ(s.textures[0].image, 0);
    EXPECT_TRUE(s.images[0].valid());
    EXPECT_NE(warnings(d).find("KHR_texture_basisu: image 1 is not usable; using the core source"), std::string::npos)
        << warnings(d);
    EXPECT_NE(warnings(d).find("width 0"), std::string::npos) << warnings(d);
    j["textures"][0].erase("source");
    Diagnostics d2;
    s = load(j, bin, d2);
    EXPECT_EQ(s.textures[0].image, 1);  // no core source: the (neutral) KTX2 image, with the decoder's warning
    EXPECT_FALSE(s.images[1].valid());
}

// ---- KHR_materials_variants ----------------------------------------------------------

TEST(GltfMaterialsVariants, MappingsAndSelection) {
    MeshoptFile f = meshopt_quad();
    json& j = f.j;
    j["extensionsUsed"].push_back("KHR_materials_variants");
    j["materials"] = {{{"name", "plain"}}, {{"name", "red"}}, {{"name", "blue"}}};
    j["extensions"] = {{"KHR_materials_variants", {{"variants", {{{"name", "Red"}}, {{"name", "Blue"}}, {{"name", "Plain"}}}}}}};
    json& prim = j["meshes"][0]["primitives"][0];
    prim["material"] = 0;
    json mappings = json::array({{{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}});
    prim["extensions"]["KHR_materials_variants"]["mappings"] = mappings;
    Diagnostics d;
    Scene s = load(j, f.bin, d);
    EXPECT_EQ(s.material_variants, (std::vector<std::string>{"Red", "Blue", "Plain"}));
    EXPECT_EQ(s.meshes[0].primitives[0].variant_materials, (std::vector<int>{1, 2, -1}));
    EXPECT_EQ(find_material_variant(s, "Blue"), 1);
    Scene blue = s;
    apply_material_variant(blue, 1);
    EXPECT_EQ(blue.meshes[0].primitives[0].material, 2);
    Scene plain = s;
    apply_material_variant(plain, 2);  // not mapped: keeps its material
    EXPECT_EQ(plain.meshes[0].primitives[0].material, 0);
    try {
        find_material_variant(s, "Green");
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(e.reason().find("'Red', 'Blue', 'Plain'"), std::string::npos) << e.what();
    }
    prim["extensions"]["KHR_materials_variants"]["mappings"][0]["variants"] = {3};
    EXPECT_EQ(load_error(j, f.bin).where(), "/meshes/0/primitives/0/extensions/KHR_materials_variants/mappings/0/variants/0");
}

TEST(GltfExtensions, SupportClasses) {
    EXPECT_EQ(gltf_extension_support("KHR_draco_mesh_compression"), GltfExtensionSupport::Supported);
    EXPECT_EQ(gltf_extension_support("EXT_meshopt_compression"), GltfExtensionSupport::Supported);
    EXPECT_EQ(gltf_extension_support("EXT_texture_webp"), GltfExtensionSupport::Supported);
    EXPECT_EQ(gltf_extension_support("KHR_materials_variants"), GltfExtensionSupport::Supported);
    EXPECT_EQ(gltf_extension_support("KHR_texture_basisu"), GltfExtensionSupport::Supported);
    EXPECT_EQ(gltf_extension_support("VENDOR_made_up"), GltfExtensionSupport::Unsupported);
}

}  // namespace
