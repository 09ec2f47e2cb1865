// KTX2 textures and environments through the programs: glTF files built here whose texture is a
// KHR_texture_basisu KTX2 image (the real ETC1S and UASTC files of ../shared/assets/ktx2) render
// like the same file with the PNG those were encoded from, `fresnel info` calls the extension
// supported, and a UASTC HDR KTX2 lights a model as `--env`. Skips without ../shared.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_harness.h"
#include "fresnel/core/image.h"
#include "gltf_builders.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const fs::path kKtx2 = fs::path(FRESNEL_SHARED_DIR) / "assets" / "ktx2";

class Ktx2Cli : public fresnel::test::TempDirTest {
protected:
    Ktx2Cli() : TempDirTest("fresnel_ktx2_cli") {}
    fresnel::test::Result fresnel(const std::vector<std::string>& args) {
        return fresnel::test::run_captured(fresnel::test::command_line(FRESNEL_EXE, args), dir_);
    }
};

// A 3:2 quad in the XY plane facing +Z, UV (0,0) at the top left, with an unlit material whose
// base colour texture is image 0 (`uri`), or the KTX2 `ktx2` through KHR_texture_basisu with
// image 0 as the core source.
json quad_gltf(const std::string& uri, const std::string& ktx2) {
    std::vector<float> v = {-1.5f, -1, 0, 1.5f, -1, 0, 1.5f, 1, 0, -1.5f, 1, 0};
    std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    std::vector<std::uint16_t> idx = {0, 1, 2, 0, 2, 3};
    std::string bin(reinterpret_cast<const char*>(v.data()), v.size() * 4);
    bin.append(reinterpret_cast<const char*>(uv.data()), uv.size() * 4);
    bin.append(reinterpret_cast<const char*>(idx.data()), idx.size() * 2);
    json j = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"KHR_materials_unlit"}},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"buffers", {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + fresnel::test::base64(bin)}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                         {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                        {"min", {-1.5, -1, 0}}, {"max", {1.5, 1, 0}}},
                       {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                       {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
        {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                        {"extensions", {{"KHR_materials_unlit", json::object()}}}}}},
        {"images", {{{"uri", uri}}}},
        {"textures", {{{"source", 0}}}},
    };
    if (!ktx2.empty()) {
        j["extensionsUsed"].push_back("KHR_texture_basisu");
        j["extensionsRequired"] = {"KHR_texture_basisu"};
        j["images"].push_back({{"uri", ktx2}, {"mimeType", "image/ktx2"}});
        j["textures"][0]["extensions"] = {{"KHR_texture_basisu", {{"source", 1}}}};
    }
    return j;
}

void write_text(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

double psnr(const fresnel::Image8& a, const fresnel::Image8& b) {
    double se = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const double d = double(a.pixels[i]) - double(b.pixels[i]);
        se += d * d;
    }
    return se == 0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 * double(a.pixels.size()) / se);
}

TEST_F(Ktx2Cli, BasisTexturesRenderLikeTheirSourceImage) {
    if (!fs::exists(kKtx2 / "kodim23.png")) GTEST_SKIP() << "no " << kKtx2;
    for (const char* f : {"kodim23.png", "kodim23_etc1s.ktx2", "kodim23_uastc_zstd_mips.ktx2"})
        fs::copy_file(kKtx2 / f, dir_ / f);
    write_text(dir_ / "png.gltf", quad_gltf("kodim23.png", "").dump());
    auto r = fresnel({"render", (dir_ / "png.gltf").string(), "--size", "384x256", "-o", (dir_ / "png.png").string()});
    ASSERT_EQ(r.exit_code, 0) << fresnel::test::show(r);
    const fresnel::Image8 want = fresnel::read_image8(dir_ / "png.png");
    struct Case {
        const char* ktx2;
        double min_db;
    };
    // Measured: 49.3 and 59.4 dB (the texture alone: 35.3 and 45.5 dB; the frame minifies it and
    // holds background).
    for (Case c : {Case{"kodim23_etc1s.ktx2", 44.0}, Case{"kodim23_uastc_zstd_mips.ktx2", 54.0}}) {
        // The core source is a file that is not there: only the KTX2 image can give the picture.
        write_text(dir_ / "k.gltf", quad_gltf("absent.png", c.ktx2).dump());
        r = fresnel({"render", (dir_ / "k.gltf").string(), "--size", "384x256", "-o", (dir_ / "k.png").string()});
        ASSERT_EQ(r.exit_code, 0) << fresnel::test::show(r);
        // Only the absent core source is warned about; the KTX2 image decoded.
        EXPECT_EQ(r.err.find("KHR_texture_basisu"), std::string::npos) << c.ktx2 << ": " << r.err;
        EXPECT_NE(r.err.find("absent.png"), std::string::npos) << c.ktx2 << ": " << r.err;
        const double db = psnr(fresnel::read_image8(dir_ / "k.png"), want);
        EXPECT_GE(db, c.min_db) << c.ktx2;
        std::printf("%s rendered vs kodim23.png rendered: %.1f dB\n", c.ktx2, db);
    }
    r = fresnel({"info", (dir_ / "k.gltf").string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << fresnel::test::show(r);
    EXPECT_NE(r.out.find("KHR_texture_basisu"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("unsupported"), std::string::npos) << r.out;
}

TEST_F(Ktx2Cli, AnHdrKtx2IsAnEnvironment) {
    if (!fs::exists(kKtx2 / "desk_uastc_hdr_zstd.ktx2")) GTEST_SKIP() << "no " << kKtx2;
    const nlohmann::json sphere = fresnel::test::uv_sphere_gltf(48, 24, {{"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.1}}}});
    write_text(dir_ / "sphere.gltf", sphere.dump());
    auto r = fresnel({"render", (dir_ / "sphere.gltf").string(), "--size", "128x128", "--env",
                      (kKtx2 / "desk_uastc_hdr_zstd.ktx2").string(), "-o", (dir_ / "desk.png").string(), "--no-cache"});
    ASSERT_EQ(r.exit_code, 0) << fresnel::test::show(r);
    r = fresnel({"render", (dir_ / "sphere.gltf").string(), "--size", "128x128", "-o", (dir_ / "studio.png").string(),
                 "--no-cache"});
    ASSERT_EQ(r.exit_code, 0) << fresnel::test::show(r);
    // The desk's light, not the studio's: the two mirror balls differ.
    EXPECT_LT(psnr(fresnel::read_image8(dir_ / "desk.png"), fresnel::read_image8(dir_ / "studio.png")), 25.0);
}

}  // namespace
