// The glTF and OBJ writers (scene_writer.h): OBJ -> glTF -> OBJ keeps positions, normals and
// texture coordinates; .glb the same; no temporary files stay behind; the glTF files pass the
// Khronos glTF-Validator with 0 errors and 0 warnings (skips without node and the validator,
// scripts/install-test-tools.sh installs it).
#include <limits>
#include <cmath>
#include <algorithm>
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/obj_loader.h"
#include "fresnel/scene/scene_writer.h"
#include "file_size_limit.h"

using namespace fresnel;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("fresnel_scene_writer_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// A quad, a concave pentagon and a triangle with awkward decimals, two materials, one texture.
const char* kObj =
    "mtllib m.mtl\n"
    "o first\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.3 0.1\n"
    "v 0.1 0.2 0.3\nv 0.7 0.11 0.33\nv 0.123456789 1e-7 -3.3333333\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.3 0.7\nvt 0.1 0.9\nvt 0.33 0.01\nvt 0.123 0.456\n"
    "vn 0 0 1\nvn 0.6 0 0.8\nvn 0 0.6 0.8\nvn 0.267261 0.534522 0.801784\n"
    "usemtl red\n"
    "f 1/1/1 2/2/1 3/3/2 4/4/3\n"
    "f 1/5/4 5/6/1 3/7/2\n"
    "usemtl tex\n"
    "f 6/8/4 7/6/3 8/5/2\n";
const char* kMtl =
    "newmtl red\nKd 0.5 0.1 0.1\nKs 0.5 0.5 0.5\nNs 32\n"
    "newmtl tex\nKd 1 1 1\nKs 0.2 0.2 0.2\nNs 8\nmap_Kd tex.png\n";

struct Corner {
    glm::vec3 p, n;
    glm::vec2 t;
};
std::vector<Corner> corners(const Scene& s) {
    std::vector<Corner> out;
    for (const Mesh& m : s.meshes)
        for (const Primitive& p : m.primitives) {
            std::size_t count = p.indices.empty() ? p.positions.size() : p.indices.size();
            for (std::size_t i = 0; i < count; ++i) {
                std::uint32_t k = p.indices.empty() ? std::uint32_t(i) : p.indices[i];
                out.push_back({p.positions[k], p.normals[k], p.uv0.empty() ? glm::vec2(0.0f) : p.uv0[k]});
            }
        }
    return out;
}

Scene write_source(const fs::path& dir) {
    std::ofstream(dir / "in.obj") << kObj;
    std::ofstream(dir / "m.mtl") << kMtl;
    Image8 img;
    img.width = 2;
    img.height = 2;
    img.pixels = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
    write_png(dir / "tex.png", img);
    Diagnostics d;
    return load_obj(dir / "in.obj", d);
}

void expect_same_geometry(const Scene& a, const Scene& b) {
    auto ca = corners(a), cb = corners(b);
    ASSERT_EQ(ca.size(), cb.size());
    for (std::size_t i = 0; i < ca.size(); ++i) {
        EXPECT_EQ(ca[i].p, cb[i].p) << i;
        EXPECT_EQ(ca[i].n, cb[i].n) << i;
        // glTF's UV origin is top-left, OBJ's bottom-left; the flip is inverted exactly.
        EXPECT_EQ(ca[i].t, cb[i].t) << i;
    }
}

}  // namespace

TEST(SceneWriter, ObjToGltfToObjKeepsGeometry) {
    for (const char* ext : {".gltf", ".glb"}) {
        fs::path dir = temp_dir(std::string("trip") + (ext + 1));
        Scene src = write_source(dir);
        ASSERT_EQ(src.materials.size(), 2u);
        Diagnostics d;
        write_gltf(src, dir / (std::string("out") + ext), d);
        Scene mid = load_gltf(dir / (std::string("out") + ext), d);
        expect_same_geometry(src, mid);
        ASSERT_EQ(mid.images.size(), 1u);
        EXPECT_EQ(mid.images[0].pixels.pixels, src.images[0].pixels.pixels);
        write_obj(mid, dir / "back.obj", d);
        Scene back = load_obj(dir / "back.obj", d);
        expect_same_geometry(src, back);
        EXPECT_EQ(back.materials.size(), 2u);
        for (const auto& e : fs::directory_iterator(dir))
            EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
        fs::remove_all(dir);
    }
}

// The OBJ's own digits come back: v values as exporters write them (up to 7 decimal places in
// [0, 1], 6 for tiling coordinates), through glTF's 1 - v and back.
// A .gltf with its .bin and images, and an OBJ with its MTL and textures, are one set: a disk
// that fills while writing it leaves every file of the old set as it was and no temporary.
TEST(SceneWriter, FileSetsAreWholeOrAbsentOnAFullDisk) {
    fs::path dir = temp_dir("full");
    Scene src = write_source(dir);
    // A big noisy texture: its PNG cannot fit under the limit below.
    Image8& img = src.images[0].pixels;
    img = Image8(256, 256, 4);
    std::uint32_t x = 12345;
    for (auto& v : img.pixels) v = std::uint8_t((x = x * 1664525u + 1013904223u) >> 24);
    for (const char* name : {"out.gltf", "out.obj"}) {
        const fs::path out = dir / name;
        Diagnostics d;
        Scene small = write_source(dir);  // the old set: a 2x2 texture
        if (out.extension() == ".gltf") write_gltf(small, out, d);
        else write_obj(small, out, d);
        std::map<std::string, std::vector<std::uint8_t>> before;
        for (const auto& e : fs::directory_iterator(dir)) before[e.path().filename().string()] = read_file_bytes(e.path(), 1 << 24);
        try {
            fresnel::test::FileSizeLimit limit(64 * 1024);
            if (out.extension() == ".gltf") write_gltf(src, out, d);
            else write_obj(src, out, d);
            ADD_FAILURE() << name << ": a write past the disk's end passed";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(std::strerror(EFBIG)), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find("partial"), std::string::npos) << "names a temporary: " << e.what();
        }
        std::map<std::string, std::vector<std::uint8_t>> after;
        for (const auto& e : fs::directory_iterator(dir)) after[e.path().filename().string()] = read_file_bytes(e.path(), 1 << 24);
        EXPECT_EQ(after.size(), before.size()) << name;
        EXPECT_TRUE(after == before) << name << ": a file of the old set changed";
        // Without the limit the new set is written whole.
        if (out.extension() == ".gltf") write_gltf(src, out, d);
        else write_obj(src, out, d);
        Diagnostics d2;
        Scene back = out.extension() == ".gltf" ? load_gltf(out, d2) : load_obj(out, d2);
        ASSERT_FALSE(back.images.empty());
        EXPECT_EQ(back.images[0].pixels.width, 256) << name;
    }
}

// Area lights go to glTF as EXT_lights_area only when asked (convert --rewrite --area-lights),
// numbered within their own list, and come back as they were; otherwise they are left out
// with a warning and the file has only the punctual lights.
TEST(SceneWriter, AreaLightsOnlyWhenAsked) {
    fs::path dir = temp_dir("area_lights");
    Scene src = write_source(dir);
    Light point, rect, sphere;
    point.type = Light::Type::Point;
    point.intensity = 3.0f;
    rect.type = Light::Type::Rect;
    rect.width = 1.5f;
    rect.height = 0.25f;
    rect.intensity = 20.0f;
    rect.name = "strip";
    sphere.type = Light::Type::Sphere;
    sphere.radius = 0.1f;
    src.lights = {rect, point, sphere};
    const int base = int(src.nodes.size());
    for (int i = 0; i < 3; ++i) {
        Node n;
        n.light = i;
        src.nodes.push_back(n);
        src.scenes[0].push_back(base + i);
    }
    Diagnostics d;
    GltfWriteOptions with;
    with.area_lights = true;
    write_gltf(src, dir / "with.gltf", d, with);
    Scene back = load_gltf(dir / "with.gltf", d);
    ASSERT_EQ(back.lights.size(), 3u);
    // The punctual light comes first on reading; the nodes still name the same lights.
    for (int i = 0; i < 3; ++i) {
        const Light& a = src.lights[std::size_t(src.nodes[std::size_t(base + i)].light)];
        const Light& b = back.lights[std::size_t(back.nodes[std::size_t(base + i)].light)];
        EXPECT_EQ(a.type, b.type) << i;
        EXPECT_FLOAT_EQ(a.intensity, b.intensity) << i;
        EXPECT_EQ(a.name, b.name) << i;
        if (a.type == Light::Type::Rect) {
            EXPECT_FLOAT_EQ(a.width, b.width);
            EXPECT_FLOAT_EQ(a.height, b.height);
        }
        if (a.type == Light::Type::Sphere) {
            EXPECT_FLOAT_EQ(a.radius, b.radius);
        }
    }
    EXPECT_EQ(d.total(), 0u);
    write_gltf(src, dir / "without.gltf", d);
    EXPECT_EQ(d.total(), 1u) << "one warning: the area lights are not written";
    std::ifstream f(dir / "without.gltf");
    const nlohmann::json j = nlohmann::json::parse(f);
    EXPECT_FALSE(j["extensions"].contains("EXT_lights_area"));
    EXPECT_EQ(j["extensions"]["KHR_lights_punctual"]["lights"].size(), 1u);
    for (const auto& e : j["extensionsUsed"]) EXPECT_NE(e.get<std::string>(), "EXT_lights_area");
    fs::remove_all(dir);
}

TEST(SceneWriter, ObjTextureCoordinatesComeBackAsWritten) {
    const std::vector<std::string> vs = {"0",        "1",         "0.5",      "0.000123", "0.333333", "0.1234567",
                                         "0.9999999", "0.0000001", "0.01",     "-0.25",    "2.5",      "-3.141593",
                                         "7.999999", "0.7071068", "0.4999999", "1e-05",    "0.456",    "0.9"};
    fs::path dir = temp_dir("uvdigits");
    std::string obj;
    for (std::size_t i = 0; i < vs.size(); ++i) obj += "v " + std::to_string(i) + " 0 0\n";
    for (std::size_t i = 0; i < vs.size(); ++i) obj += "vt 0.25 " + vs[i] + "\n";
    for (std::size_t i = 0; i + 2 < vs.size(); i += 3)
        obj += "f " + std::to_string(i + 1) + "/" + std::to_string(i + 1) + " " + std::to_string(i + 2) + "/" +
               std::to_string(i + 2) + " " + std::to_string(i + 3) + "/" + std::to_string(i + 3) + "\n";
    std::ofstream(dir / "in.obj") << obj;
    Diagnostics d;
    Scene src = load_obj(dir / "in.obj", d);
    write_gltf(src, dir / "mid.glb", d);
    write_obj(load_gltf(dir / "mid.glb", d), dir / "back.obj", d);
    std::ifstream back(dir / "back.obj");
    std::vector<double> got, want;
    for (std::string line; std::getline(back, line);)
        if (line.rfind("vt ", 0) == 0) got.push_back(std::strtod(line.substr(line.find(' ', 3) + 1).c_str(), nullptr));
    for (const std::string& v : vs) want.push_back(std::strtod(v.c_str(), nullptr));
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want);
    fs::remove_all(dir);
}

// Every material extension the loader keeps, and KHR_materials_variants, survive glTF -> glTF.
Scene with_every_extension(Scene s) {
    TextureSlot t;
    t.texture = 0;
    Material& m = s.materials.at(0);
    m.double_sided = false;  // the validator warns on a volume of a double-sided material
    m.sheen = SheenExt{{0.9f, 0.4f, 0.2f}, t, 0.35f, t};
    m.transmission = TransmissionExt{0.75f, t};
    m.volume = VolumeExt{0.5f, t, 2.5f, {0.8f, 0.6f, 0.4f}};
    m.dispersion = DispersionExt{0.3f};
    m.iridescence = IridescenceExt{0.8f, t, 1.45f, 120.0f, 380.0f, t};
    m.anisotropy = AnisotropyExt{0.6f, 0.7f, t};
    m.diffuse_transmission = DiffuseTransmissionExt{0.4f, t, {0.2f, 0.9f, 0.5f}, t};
    s.material_variants = {"day", "night", "dusk"};
    for (Mesh& mesh : s.meshes)
        for (Primitive& p : mesh.primitives) p.variant_materials = {1, -1, 0};
    s.nodes.push_back(Node{});  // KHR_node_visibility: a hidden (empty) root node
    s.nodes.back().name = "hidden";
    s.nodes.back().visible = false;
    s.scenes.at(0).push_back(int(s.nodes.size()) - 1);
    return s;
}

TEST(SceneWriter, GltfToGltfKeepsMaterialExtensionsAndVariants) {
    for (const char* ext : {".gltf", ".glb"}) {
        fs::path dir = temp_dir(std::string("ext") + (ext + 1));
        Scene src = with_every_extension(write_source(dir));
        Diagnostics d;
        write_gltf(src, dir / (std::string("out") + ext), d);
        Scene a = load_gltf(dir / (std::string("out") + ext), d);
        // and once more: what was written reads back as the same material
        write_gltf(a, dir / (std::string("again") + ext), d);
        Scene b = load_gltf(dir / (std::string("again") + ext), d);
        for (const Scene* got : {&a, &b}) {
            ASSERT_EQ(got->materials.size(), src.materials.size());
            const Material& m = got->materials[0];
            ASSERT_TRUE(m.sheen && m.transmission && m.volume && m.dispersion && m.iridescence && m.anisotropy &&
                        m.diffuse_transmission);
            EXPECT_EQ(m.sheen->sheen_color_factor, glm::vec3(0.9f, 0.4f, 0.2f));
            EXPECT_EQ(m.sheen->sheen_roughness_factor, 0.35f);
            EXPECT_TRUE(m.sheen->sheen_color_texture.valid() && m.sheen->sheen_roughness_texture.valid());
            EXPECT_EQ(m.transmission->transmission_factor, 0.75f);
            EXPECT_TRUE(m.transmission->transmission_texture.valid());
            EXPECT_EQ(m.volume->thickness_factor, 0.5f);
            EXPECT_EQ(m.volume->attenuation_distance, 2.5f);
            EXPECT_EQ(m.volume->attenuation_color, glm::vec3(0.8f, 0.6f, 0.4f));
            EXPECT_TRUE(m.volume->thickness_texture.valid());
            EXPECT_EQ(m.dispersion->dispersion, 0.3f);
            EXPECT_EQ(m.iridescence->iridescence_factor, 0.8f);
            EXPECT_EQ(m.iridescence->iridescence_ior, 1.45f);
            EXPECT_EQ(m.iridescence->iridescence_thickness_minimum, 120.0f);
            EXPECT_EQ(m.iridescence->iridescence_thickness_maximum, 380.0f);
            EXPECT_TRUE(m.iridescence->iridescence_texture.valid() && m.iridescence->iridescence_thickness_texture.valid());
            EXPECT_EQ(m.anisotropy->anisotropy_strength, 0.6f);
            EXPECT_EQ(m.anisotropy->anisotropy_rotation, 0.7f);
            EXPECT_TRUE(m.anisotropy->anisotropy_texture.valid());
            EXPECT_EQ(m.diffuse_transmission->diffuse_transmission_factor, 0.4f);
            EXPECT_EQ(m.diffuse_transmission->diffuse_transmission_color_factor, glm::vec3(0.2f, 0.9f, 0.5f));
            EXPECT_TRUE(m.diffuse_transmission->diffuse_transmission_texture.valid() &&
                        m.diffuse_transmission->diffuse_transmission_color_texture.valid());
            EXPECT_FALSE(got->materials[1].sheen || got->materials[1].iridescence);  // no block appears from nothing
            EXPECT_EQ(got->material_variants, src.material_variants);
            ASSERT_FALSE(got->nodes.empty());
            EXPECT_EQ(got->nodes.back().name, "hidden");
            EXPECT_FALSE(got->nodes.back().visible);
            for (const Mesh& mesh : got->meshes)
                for (const Primitive& p : mesh.primitives) EXPECT_EQ(p.variant_materials, (std::vector<int>{1, -1, 0}));
        }
        fs::remove_all(dir);
    }
}

TEST(SceneWriter, GltfPassesTheKhronosValidator) {
    const fs::path tools = FRESNEL_NODE_TOOLS;
    if (std::system("node --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "node not found";
    if (!fs::exists(tools / "node_modules" / "gltf-validator"))
        GTEST_SKIP() << "gltf-validator not installed (scripts/install-test-tools.sh)";
    fs::path dir = temp_dir("validator");
    Scene src = write_source(dir);
    Diagnostics d;
    write_gltf(src, dir / "out.gltf", d);
    write_gltf(src, dir / "out.glb", d);
    write_gltf(with_every_extension(src), dir / "extensions.gltf", d);
    std::string cmd = "node " + std::string(FRESNEL_SOURCE_DIR) + "/scripts/validate-gltf.js " + tools.string() + " " +
                      (dir / "out.gltf").string() + " " + (dir / "out.glb").string() + " " +
                      (dir / "extensions.gltf").string() + " > " + (dir / "report.txt").string();
    int rc = std::system(cmd.c_str());
    std::ifstream report(dir / "report.txt");
    std::string line;
    int lines = 0;
    while (std::getline(report, line)) {
        std::printf("%s\n", line.c_str());
        EXPECT_NE(line.find("\"errors\":0,\"warnings\":0"), std::string::npos) << line;
        ++lines;
    }
    EXPECT_EQ(lines, 3);
    EXPECT_EQ(rc, 0);
    fs::remove_all(dir);
}

// --- material edits saved back (save_gltf_material_edits) -----------------------------------

namespace {

using ojson = nlohmann::ordered_json;

std::vector<std::uint8_t> bytes_of(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A triangle with two materials, an unknown extension (required nowhere, used), extras at
// several levels, names, and its data in a .bin file: what the writer does not understand.
ojson edit_model(std::string& bin) {
    const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::uint16_t idx[] = {0, 1, 2, 0};
    bin.assign(reinterpret_cast<const char*>(pos), sizeof pos);
    bin.append(reinterpret_cast<const char*>(idx), sizeof idx);
    return ojson::parse(R"({
      "asset": {"version": "2.0", "generator": "a tool", "extras": {"note": "keep me"}},
      "extensionsUsed": ["VENDOR_unknown_thing"],
      "scene": 0, "scenes": [{"nodes": [0], "name": "the scene"}],
      "nodes": [{"mesh": 0, "name": "tri", "extras": {"id": 7}}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 1}]}],
      "materials": [
        {"name": "first", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.7, 0.6, 1.0], "metallicFactor": 0.0},
         "extensions": {"VENDOR_unknown_thing": {"level": 3, "tags": ["a", "b"]}}, "extras": {"kept": true}},
        {"name": "second", "pbrMetallicRoughness": {"roughnessFactor": 0.9}, "zeta": 1, "alpha": 2}
      ],
      "buffers": [{"uri": "tri.bin", "byteLength": 44}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 8}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
      ]
    })");
}

void put32(std::string& s, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) s += char(v >> (8 * i));
}
void write_glb(const fs::path& path, ojson doc, const std::string& bin) {
    doc["buffers"][0].erase("uri");
    std::string j = doc.dump(), b = bin;
    while (j.size() % 4) j += ' ';
    while (b.size() % 4) b += '\0';
    std::string out;
    put32(out, 0x46546C67);
    put32(out, 2);
    put32(out, std::uint32_t(12 + 8 + j.size() + 8 + b.size()));
    put32(out, std::uint32_t(j.size()));
    put32(out, 0x4E4F534A);
    out += j;
    put32(out, std::uint32_t(b.size()));
    put32(out, 0x004E4942);
    out += b;
    std::ofstream(path, std::ios::binary) << out;
}
ojson glb_json(const fs::path& path) {
    auto b = bytes_of(path);
    std::uint32_t n = std::uint32_t(b[12]) | std::uint32_t(b[13]) << 8 | std::uint32_t(b[14]) << 16 | std::uint32_t(b[15]) << 24;
    return ojson::parse(b.begin() + 20, b.begin() + 20 + n);
}
std::vector<std::uint8_t> glb_rest(const fs::path& path) {  // everything after the JSON chunk
    auto b = bytes_of(path);
    std::uint32_t n = std::uint32_t(b[12]) | std::uint32_t(b[13]) << 8 | std::uint32_t(b[14]) << 16 | std::uint32_t(b[15]) << 24;
    return std::vector<std::uint8_t>(b.begin() + 20 + n, b.end());
}

}  // namespace

TEST(MaterialEdits, GltfKeepsEverythingButTheEdit) {
    fs::path dir = temp_dir("edits_gltf");
    std::string bin;
    ojson doc = edit_model(bin);
    std::ofstream(dir / "tri.gltf") << doc.dump(2);
    std::ofstream(dir / "tri.bin", std::ios::binary) << bin;
    Diagnostics diag;
    Scene scene = load_gltf(dir / "tri.gltf", diag);
    ASSERT_EQ(scene.materials.size(), 2u);

    // No edit: the same JSON (keys in order), the .bin untouched.
    EXPECT_EQ(save_gltf_material_edits(dir / "tri.gltf", dir / "same.gltf", scene.materials, scene.materials, diag), 0);
    EXPECT_EQ(ojson::parse(std::ifstream(dir / "same.gltf")), doc);

    // One edit, saved into another folder: that value changes, nothing else; the .bin is copied.
    std::vector<Material> edited = scene.materials;
    edited[1].roughness_factor = 0.2f;
    fs::create_directories(dir / "out");
    EXPECT_EQ(save_gltf_material_edits(dir / "tri.gltf", dir / "out" / "tri.gltf", scene.materials, edited, diag), 1);
    ojson saved = ojson::parse(std::ifstream(dir / "out" / "tri.gltf"));
    EXPECT_EQ(saved["materials"][1]["pbrMetallicRoughness"]["roughnessFactor"].dump(), "0.2");
    ojson expect = doc;
    expect["materials"][1]["pbrMetallicRoughness"]["roughnessFactor"] = 0.2;
    EXPECT_EQ(saved, expect);
    EXPECT_EQ(saved["materials"][0]["extensions"], doc["materials"][0]["extensions"]);
    EXPECT_EQ(saved["materials"][1].begin().key(), "name");  // keys keep their order
    EXPECT_EQ(bytes_of(dir / "out" / "tri.bin"), bytes_of(dir / "tri.bin"));
    Scene back = load_gltf(dir / "out" / "tri.gltf", diag);
    ASSERT_EQ(back.materials.size(), 2u);
    EXPECT_EQ(back.materials[1].roughness_factor, 0.2f);
    EXPECT_EQ(back.materials[0].base_color_factor, scene.materials[0].base_color_factor);
    ASSERT_EQ(back.meshes.size(), scene.meshes.size());
    EXPECT_EQ(back.meshes[0].primitives[0].positions.size(), scene.meshes[0].primitives[0].positions.size());
    EXPECT_EQ(back.meshes[0].primitives[0].indices, scene.meshes[0].primitives[0].indices);

    // A new extension block is declared in extensionsUsed.
    edited = scene.materials;
    edited[0].emissive_strength = EmissiveStrengthExt{4.0f};
    save_gltf_material_edits(dir / "tri.gltf", dir / "tri.gltf", scene.materials, edited, diag);  // in place
    saved = ojson::parse(std::ifstream(dir / "tri.gltf"));
    EXPECT_EQ(saved["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"], 4.0);
    EXPECT_EQ(saved["materials"][0]["extensions"]["VENDOR_unknown_thing"], doc["materials"][0]["extensions"]["VENDOR_unknown_thing"]);
    EXPECT_EQ(saved["extensionsUsed"], ojson::parse(R"(["VENDOR_unknown_thing", "KHR_materials_emissive_strength"])"));
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    fs::remove_all(dir);
}

// Every extension factor the material editor edits is saved and reads back; a value not
// edited inside a block that was edited is left alone.
TEST(MaterialEdits, ExtensionFactorsSaveAndReadBack) {
    fs::path dir = temp_dir("edits_ext");
    std::string bin;
    ojson doc = edit_model(bin);
    doc["materials"][1]["extensions"] = ojson::parse(R"({
      "KHR_materials_sheen": {"sheenColorFactor": [0.1, 0.2, 0.3], "sheenRoughnessFactor": 0.5},
      "KHR_materials_volume": {"thicknessFactor": 0.5, "attenuationDistance": 2.0}
    })");
    doc["extensionsUsed"].push_back("KHR_materials_sheen");
    doc["extensionsUsed"].push_back("KHR_materials_volume");
    std::ofstream(dir / "tri.gltf") << doc.dump(2);
    std::ofstream(dir / "tri.bin", std::ios::binary) << bin;
    Diagnostics diag;
    Scene scene = load_gltf(dir / "tri.gltf", diag);
    ASSERT_EQ(scene.materials.size(), 2u);
    std::vector<Material> edited = scene.materials;
    Material& m = edited[1];
    m.sheen->sheen_roughness_factor = 0.25f;
    m.volume->attenuation_distance = std::numeric_limits<float>::infinity();  // back to the default
    m.volume->attenuation_color = {0.5f, 0.75f, 1.0f};
    m.transmission = TransmissionExt{};
    m.transmission->transmission_factor = 0.5f;
    m.dispersion = DispersionExt{0.25f};
    m.iridescence = IridescenceExt{};
    m.iridescence->iridescence_factor = 1.0f;
    m.iridescence->iridescence_thickness_maximum = 500.0f;
    m.anisotropy = AnisotropyExt{};
    m.anisotropy->anisotropy_strength = 0.5f;
    m.anisotropy->anisotropy_rotation = 1.0f;
    m.diffuse_transmission = DiffuseTransmissionExt{};
    m.diffuse_transmission->diffuse_transmission_factor = 0.75f;
    m.diffuse_transmission->diffuse_transmission_color_factor = {1.0f, 0.5f, 0.25f};
    EXPECT_GT(save_gltf_material_edits(dir / "tri.gltf", dir / "tri.gltf", scene.materials, edited, diag), 0);
    ojson saved = ojson::parse(std::ifstream(dir / "tri.gltf"));
    const ojson& x = saved["materials"][1]["extensions"];
    EXPECT_EQ(x["KHR_materials_sheen"]["sheenColorFactor"], doc["materials"][1]["extensions"]["KHR_materials_sheen"]["sheenColorFactor"]);
    EXPECT_EQ(x["KHR_materials_sheen"]["sheenRoughnessFactor"], 0.25);
    EXPECT_FALSE(x["KHR_materials_volume"].contains("attenuationDistance"));
    EXPECT_EQ(x["KHR_materials_volume"]["thicknessFactor"], 0.5);
    Scene back = load_gltf(dir / "tri.gltf", diag);
    ASSERT_EQ(back.materials.size(), 2u);
    const Material& b = back.materials[1];
    ASSERT_TRUE(b.sheen && b.volume && b.transmission && b.dispersion && b.iridescence && b.anisotropy &&
                b.diffuse_transmission);
    EXPECT_EQ(b.sheen->sheen_roughness_factor, 0.25f);
    EXPECT_TRUE(std::isinf(b.volume->attenuation_distance));
    EXPECT_EQ(b.volume->attenuation_color, m.volume->attenuation_color);
    EXPECT_EQ(b.transmission->transmission_factor, 0.5f);
    EXPECT_EQ(b.dispersion->dispersion, 0.25f);
    EXPECT_EQ(b.iridescence->iridescence_factor, 1.0f);
    EXPECT_EQ(b.iridescence->iridescence_thickness_maximum, 500.0f);
    EXPECT_EQ(b.anisotropy->anisotropy_strength, 0.5f);
    EXPECT_EQ(b.anisotropy->anisotropy_rotation, 1.0f);
    EXPECT_EQ(b.diffuse_transmission->diffuse_transmission_factor, 0.75f);
    EXPECT_EQ(b.diffuse_transmission->diffuse_transmission_color_factor, m.diffuse_transmission->diffuse_transmission_color_factor);
    for (const char* e : {"KHR_materials_transmission", "KHR_materials_dispersion", "KHR_materials_iridescence",
                          "KHR_materials_anisotropy", "KHR_materials_diffuse_transmission"})
        EXPECT_NE(std::find(saved["extensionsUsed"].begin(), saved["extensionsUsed"].end(), e),
                  saved["extensionsUsed"].end())
            << e;
    // Saving the read-back materials over themselves changes nothing.
    EXPECT_EQ(save_gltf_material_edits(dir / "tri.gltf", dir / "again.gltf", back.materials, back.materials, diag), 0);
    fs::remove_all(dir);
}

TEST(MaterialEdits, GlbKeepsItsBinaryChunkByteForByte) {
    fs::path dir = temp_dir("edits_glb");
    std::string bin;
    ojson doc = edit_model(bin);
    write_glb(dir / "tri.glb", doc, bin);
    Diagnostics diag;
    Scene scene = load_gltf(dir / "tri.glb", diag);
    std::vector<Material> edited = scene.materials;
    edited[0].base_color_factor = {1, 0, 0, 1};
    EXPECT_EQ(save_gltf_material_edits(dir / "tri.glb", dir / "red.glb", scene.materials, edited, diag), 1);
    EXPECT_EQ(glb_rest(dir / "red.glb"), glb_rest(dir / "tri.glb"));
    ojson expect = glb_json(dir / "tri.glb");
    expect["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = ojson::parse("[1, 0, 0, 1]");
    ojson saved = glb_json(dir / "red.glb");
    EXPECT_EQ(saved, expect);
    Scene back = load_gltf(dir / "red.glb", diag);
    EXPECT_EQ(back.materials[0].base_color_factor, glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(bytes_of(dir / "red.glb").size() % 4, 0u);
    // Containers are kept; a failed write leaves the file as it was.
    EXPECT_THROW(save_gltf_material_edits(dir / "tri.glb", dir / "x.gltf", scene.materials, edited, diag), Error);
    auto before = bytes_of(dir / "red.glb");
    fs::create_directories(dir / "busy.glb" / "inside");
    EXPECT_THROW(save_gltf_material_edits(dir / "tri.glb", dir / "busy.glb", scene.materials, edited, diag), Error);
    EXPECT_THROW(save_gltf_material_edits(dir / "tri.glb", dir / "no" / "dir" / "a.glb", scene.materials, edited, diag), Error);
    EXPECT_EQ(bytes_of(dir / "red.glb"), before);
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    fs::remove_all(dir);
}

// --- glTF -> glTF as the file is (copy_gltf) ------------------------------------------------

// The triangle above with an animation, a copyright, an image file and an unknown extension,
// copied into a .glb, from it into a .gltf in another folder and back into a .glb: everything
// is kept (JSON key by key, the image's bytes and MIME type), and the second .glb is the first
// byte for byte.
TEST(CopyGltf, KeepsEverythingAndIsIdempotent) {
    fs::path dir = temp_dir("copy");
    std::string bin;
    ojson doc = edit_model(bin);
    const float times[] = {0, 1}, moves[] = {0, 0, 0, 1, 2, 3};
    bin.append(reinterpret_cast<const char*>(times), sizeof times);
    bin.append(reinterpret_cast<const char*>(moves), sizeof moves);
    doc["buffers"][0]["byteLength"] = bin.size();
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 44}, {"byteLength", 8}});
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 52}, {"byteLength", 24}});
    doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 2}, {"type", "SCALAR"},
                                {"min", {0}}, {"max", {1}}});
    doc["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
    doc["animations"] = ojson::parse(R"([{"name": "move", "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
                                          "samplers": [{"input": 2, "output": 3}]}])");
    doc["asset"]["copyright"] = "CC-BY 4.0 the test";
    Image8 img(4, 4, 4);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = std::uint8_t(i * 13);
    write_png(dir / "tex.png", img);
    doc["images"] = ojson::parse(R"([{"uri": "tex.png", "name": "the texture"}])");
    doc["textures"] = ojson::parse(R"([{"source": 0}])");
    doc["materials"][1]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    std::ofstream(dir / "tri.gltf") << doc.dump(2);
    std::ofstream(dir / "tri.bin", std::ios::binary) << bin;

    Diagnostics d;
    copy_gltf(dir / "tri.gltf", dir / "a.glb", d);
    ojson a = glb_json(dir / "a.glb");
    EXPECT_EQ(a["animations"], doc["animations"]);
    EXPECT_EQ(a["asset"]["copyright"], "CC-BY 4.0 the test");
    EXPECT_EQ(a["asset"]["generator"], "a tool");
    EXPECT_EQ(a["asset"]["extras"], doc["asset"]["extras"]);
    EXPECT_EQ(a["nodes"], doc["nodes"]);
    EXPECT_EQ(a["materials"], doc["materials"]);
    EXPECT_EQ(a["scenes"], doc["scenes"]);
    EXPECT_EQ(a["accessors"], doc["accessors"]);
    EXPECT_EQ(a["images"][0]["name"], "the texture");
    EXPECT_EQ(a["images"][0]["mimeType"], "image/png");
    ASSERT_TRUE(a["images"][0].contains("bufferView"));
    // The image's bytes, as the file had them, inside the BIN chunk.
    const auto glb = bytes_of(dir / "a.glb");
    const std::size_t json_len = std::size_t(glb[12]) | std::size_t(glb[13]) << 8 | std::size_t(glb[14]) << 16;
    const std::size_t bin_at = 20 + json_len + 8;
    const ojson& view = a["bufferViews"][a["images"][0]["bufferView"].get<std::size_t>()];
    const auto png = bytes_of(dir / "tex.png");
    ASSERT_EQ(view["byteLength"].get<std::size_t>(), png.size());
    EXPECT_TRUE(std::equal(png.begin(), png.end(), glb.begin() + std::ptrdiff_t(bin_at + view["byteOffset"].get<std::size_t>())));
    bool carried = false;
    for (const auto& l : d.lines()) carried |= l.find("VENDOR_unknown_thing is not read by fresnel: carried") != std::string::npos;
    EXPECT_TRUE(carried);

    fs::create_directories(dir / "b");
    copy_gltf(dir / "a.glb", dir / "b" / "b.gltf", d);
    Diagnostics d2;
    Scene back = load_gltf(dir / "b" / "b.gltf", d2);
    EXPECT_EQ(back.animations.size(), 1u);
    ASSERT_EQ(back.images.size(), 1u);
    EXPECT_EQ(back.images[0].pixels.pixels, img.pixels);
    copy_gltf(dir / "b" / "b.gltf", dir / "c.glb", d);
    EXPECT_EQ(bytes_of(dir / "c.glb"), glb) << "converting the result again gives the same bytes";
    copy_gltf(dir / "c.glb", dir / "c.glb", d);  // onto itself
    EXPECT_EQ(bytes_of(dir / "c.glb"), glb);
    fs::remove_all(dir);
}
