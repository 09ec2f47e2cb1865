// The glTF and OBJ writers (scene_writer.h): OBJ -> glTF -> OBJ keeps positions, normals and
// texture coordinates; .glb the same; no temporary files stay behind; the glTF files pass the
// Khronos glTF-Validator with 0 errors and 0 warnings (skips without node and the validator,
// scripts/install-test-tools.sh installs it).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/obj_loader.h"
#include "fresnel/scene/scene_writer.h"

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
        // glTF's UV origin is top-left, OBJ's bottom-left: each trip computes 1 - v once in
        // float, which is exact for v in [0.5, 1] and within one float step below.
        EXPECT_NEAR(ca[i].t.x, cb[i].t.x, 0.0f) << i;
        EXPECT_NEAR(ca[i].t.y, cb[i].t.y, 6e-8f) << i;
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
    std::string cmd = "node " + std::string(FRESNEL_SOURCE_DIR) + "/scripts/validate-gltf.js " + tools.string() + " " +
                      (dir / "out.gltf").string() + " " + (dir / "out.glb").string() + " > " + (dir / "report.txt").string();
    int rc = std::system(cmd.c_str());
    std::ifstream report(dir / "report.txt");
    std::string line;
    int lines = 0;
    while (std::getline(report, line)) {
        std::printf("%s\n", line.c_str());
        EXPECT_NE(line.find("\"errors\":0,\"warnings\":0"), std::string::npos) << line;
        ++lines;
    }
    EXPECT_EQ(lines, 2);
    EXPECT_EQ(rc, 0);
    fs::remove_all(dir);
}
