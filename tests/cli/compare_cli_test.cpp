// `fresnel compare` end to end: agreement with ../shared/tools/fidelity/compare.py on PSNR (to
// 0.01 dB, on the shared Khronos reference images and on pairs rendered by `fresnel render`),
// JSON and table output, masks, the heat map, EXR input (HDR-FLIP), and errors: mismatched
// sizes and hostile files exit 1 with a message naming the file, never a crash.
// FRESNEL_EXE is the built program; FRESNEL_SHARED_DIR the shared folder (tests needing it skip).
#include "cli_harness.h"
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fresnel/core/image.h"

namespace fs = std::filesystem;

namespace {

const fs::path kShared = FRESNEL_SHARED_DIR;

using fresnel::test::command_line;
using fresnel::test::quote;
using fresnel::test::run_captured;
using fresnel::test::show;
using fresnel::test::Result;
using fresnel::test::slurp;

class Compare : public fresnel::test::TempDirTest {
protected:
    Compare() : TempDirTest("fresnel_compare") {}

    // Runs `program args...` (the program unquoted when it is a plain command line).
    Result exec(const std::string& program, const std::vector<std::string>& args) {
        return run_captured(command_line(program, args), dir_);
    }
    Result fresnel(const std::vector<std::string>& args) { return exec(quote(FRESNEL_EXE), args); }

    nlohmann::json compare_json(const fs::path& a, const fs::path& b, const std::vector<std::string>& extra = {}) {
        std::vector<std::string> args = {"compare", a.string(), b.string(), "--json"};
        args.insert(args.end(), extra.begin(), extra.end());
        Result r = fresnel(args);
        EXPECT_EQ(r.exit_code, 0) << show(r);
        nlohmann::json j;
        EXPECT_NO_THROW(j = nlohmann::json::parse(r.out)) << show(r);
        return j;
    }

    // A python3 with NumPy and Pillow (compare.py's needs), or "".
    std::string python() {
        for (const char* p : {"/usr/bin/python3", "python3"}) {
            Result r = exec(p, {"-c", "import numpy, PIL"});
            if (r.exit_code == 0) return p;
        }
        return "";
    }
};

fresnel::Image8 gradient(int w, int h, int shift) {
    fresnel::Image8 img(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = img.at(x, y);
            const bool object = (x - w / 2) * (x - w / 2) + (y - h / 2) * (y - h / 2) < w * h / 8;
            p[0] = object ? std::uint8_t((x * 255 / w + shift) & 255) : 0;
            p[1] = object ? std::uint8_t(y * 255 / h) : 0;
            p[2] = object ? 90 : 0;
            p[3] = 255;
        }
    return img;
}

TEST_F(Compare, PsnrAgreesWithComparePy) {
    const fs::path script = kShared / "tools" / "fidelity" / "compare.py";
    if (!fs::exists(script)) GTEST_SKIP() << "shared folder not found: " << script.string() << " (FRESNEL_SHARED_DIR)";
    const std::string py = python();
    if (py.empty()) GTEST_SKIP() << "python3 with numpy and PIL not found";

    std::vector<std::pair<fs::path, fs::path>> pairs;
    const fs::path refs = kShared / "refs" / "khronos";
    for (const char* model : {"DamagedHelmet", "Duck", "TextureSettingsTest"}) {
        const fs::path a = refs / "studio" / (std::string(model) + "_front.png");
        const fs::path b = refs / "potsdamer" / (std::string(model) + "_front.png");
        const fs::path q = refs / "studio" / (std::string(model) + "_q.png");
        if (fs::exists(a) && fs::exists(b)) pairs.emplace_back(a, b);
        if (fs::exists(a) && fs::exists(q)) pairs.emplace_back(a, q);
    }
    // Pairs fresnel renders: another view, and a small exposure change (a high PSNR).
    const fs::path v0 = dir_ / "view0.png", v1 = dir_ / "view1.png", v2 = dir_ / "exposed.png";
    const std::vector<std::string> base = {"render", "--size", "96x96", "--background", "0,0,0"};
    auto render = [&](const fs::path& out, std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), {"-o", out.string()});
        args.insert(args.end(), extra.begin(), extra.end());
        Result r = fresnel(args);
        ASSERT_EQ(r.exit_code, 0) << show(r);
    };
    render(v0, {});
    render(v1, {"--yaw", "25", "--pitch", "10"});
    render(v2, {"--exposure", "0.05"});
    pairs.emplace_back(v0, v1);
    pairs.emplace_back(v0, v2);
    ASSERT_GE(pairs.size(), 2u);

    for (const auto& [a, b] : pairs) {
        Result r = exec(py, {script.string(), a.string(), b.string(), "--json"});
        ASSERT_EQ(r.exit_code, 0) << show(r);
        nlohmann::json expected = nlohmann::json::parse(r.out);
        nlohmann::json got = compare_json(a, b, {"--mask", "auto"});
        EXPECT_EQ(got.at("pixels").get<long>(), expected.at("pixels").get<long>()) << a << " vs " << b;
        EXPECT_NEAR(got.at("psnr_db").get<double>(), expected.at("psnr_db").get<double>(), 0.01) << a << " vs " << b;
        std::printf("%s vs %s: PSNR %.3f dB (compare.py %.2f), SSIM %.4f, FLIP %.4f, RMS %.2f dB\n",
                    a.filename().c_str(), b.filename().c_str(), got["psnr_db"].get<double>(),
                    expected["psnr_db"].get<double>(), got["ssim"].get<double>(), got["flip"].get<double>(),
                    got["mv_rms_db"].get<double>());
    }
}

TEST_F(Compare, JsonTableAndMasks) {
    const fs::path a = dir_ / "a.png", b = dir_ / "b.png";
    fresnel::write_png(a, gradient(64, 48, 0));
    fresnel::write_png(b, gradient(64, 48, 12));
    nlohmann::json all = compare_json(a, b);
    for (const char* k : {"psnr_db", "ssim", "ssim_pixels", "flip", "flip_pixels_per_degree", "mv_rms_db", "pixels",
                          "total_pixels", "width", "height", "mask"})
        EXPECT_TRUE(all.contains(k)) << k << "\n" << all.dump(2);
    EXPECT_EQ(all["pixels"].get<long>(), 64 * 48);
    EXPECT_EQ(all["mask"], "none");
    EXPECT_TRUE(all["hdr_flip"].is_null());  // PNGs: LDR only
    nlohmann::json masked = compare_json(a, b, {"--mask", "auto"});
    const long object = masked["pixels"].get<long>();
    EXPECT_GT(object, 64 * 48 / 4);
    EXPECT_LT(object, 64 * 48);
    // The same error over fewer pixels: lower PSNR, higher mean FLIP.
    EXPECT_LT(masked["psnr_db"].get<double>(), all["psnr_db"].get<double>());
    EXPECT_GT(masked["flip"].get<double>(), all["flip"].get<double>());

    // A mask image selecting the same object gives the same numbers.
    fresnel::Image8 m(64, 48, 3);
    fresnel::Image8 ga = gradient(64, 48, 0);
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            const std::uint8_t* p = ga.at(x, y);
            const std::uint8_t v = (p[0] | p[1] | p[2]) ? 255 : 0;
            m.at(x, y)[0] = m.at(x, y)[1] = m.at(x, y)[2] = v;
        }
    const fs::path mask = dir_ / "mask.png";
    fresnel::write_png(mask, m);
    nlohmann::json file = compare_json(a, b, {"--mask", mask.string()});
    EXPECT_EQ(file["pixels"].get<long>(), object);
    EXPECT_NEAR(file["psnr_db"].get<double>(), masked["psnr_db"].get<double>(), 1e-9);

    // Identical: compare.py's sentinels.
    nlohmann::json same = compare_json(a, a);
    EXPECT_EQ(same["psnr_db"].get<double>(), 99.0);
    EXPECT_EQ(same["mv_rms_db"].get<double>(), -99.0);
    EXPECT_EQ(same["flip"].get<double>(), 0.0);
    EXPECT_EQ(same["ssim"].get<double>(), 1.0);

    Result table = fresnel({"compare", a.string(), b.string()});
    ASSERT_EQ(table.exit_code, 0) << show(table);
    for (const char* row : {"PSNR", "SSIM", "LDR-FLIP", "RMS", "mask"})
        EXPECT_NE(table.out.find(row), std::string::npos) << row << "\n" << show(table);
}

TEST_F(Compare, HeatmapIsWrittenWithLegend) {
    const fs::path a = dir_ / "a.png", b = dir_ / "b.png", heat = dir_ / "heat.png";
    fresnel::write_png(a, gradient(240, 120, 0));
    fresnel::write_png(b, gradient(240, 120, 40));
    Result r = fresnel({"compare", a.string(), b.string(), "--heatmap", heat.string()});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    fresnel::Image8 img = fresnel::read_image8(heat);
    EXPECT_EQ(img.width, 240);
    EXPECT_GT(img.height, 120 + 30);  // the legend band
    // Nothing but the heat map is left in the folder (written through a temporary, renamed).
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir_)) files += e.path().filename().string().find("heat") == 0;
    EXPECT_EQ(files, 1);
    // Error-free background is magma's darkest colour; the shifted object is brighter.
    const std::uint8_t* corner = img.at(2, 2);
    EXPECT_LT(corner[0] + corner[1] + corner[2], 20);

    // An unwritable destination fails cleanly.
    r = fresnel({"compare", a.string(), b.string(), "--heatmap", (dir_ / "no_such_dir" / "h.png").string()});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error:", 0), 0u) << show(r);
    r = fresnel({"compare", a.string(), b.string(), "--heatmap", (dir_ / "h.jpg").string()});
    EXPECT_EQ(r.exit_code, 2) << show(r);
}

TEST_F(Compare, ExrInputsGiveHdrFlip) {
    fresnel::ImageF x(40, 30), y(40, 30);
    for (int j = 0; j < 30; ++j)
        for (int i = 0; i < 40; ++i) {
            float* p = x.at(i, j);
            float* q = y.at(i, j);
            p[0] = 0.1f + 4.0f * float(i) / 40.0f, p[1] = 0.5f, p[2] = float(j) / 30.0f, p[3] = 1;
            for (int c = 0; c < 3; ++c) q[c] = p[c] * (i > 20 ? 1.5f : 1.0f);
            q[3] = 1;
        }
    const fs::path a = dir_ / "a.exr", b = dir_ / "b.hdr";
    fresnel::write_exr(a, y);
    fresnel::write_hdr(b, x);
    nlohmann::json j = compare_json(a, b);
    ASSERT_FALSE(j["hdr_flip"].is_null()) << j.dump(2);
    EXPECT_GT(j["hdr_flip"].get<double>(), 0.0);
    EXPECT_GE(j["hdr_flip_exposures"]["count"].get<int>(), 1);
    EXPECT_GT(j["flip"].get<double>(), 0.0);
}

TEST_F(Compare, MismatchedSizesAndHostileFilesAreErrors) {
    const fs::path a = dir_ / "a.png", b = dir_ / "b.png";
    fresnel::write_png(a, gradient(64, 48, 0));
    fresnel::write_png(b, gradient(48, 64, 0));
    Result r = fresnel({"compare", a.string(), b.string()});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error: " + a.string(), 0), 0u) << show(r);
    EXPECT_NE(r.err.find(b.string()), std::string::npos) << "the message names both files\n" << show(r);
    EXPECT_NE(r.err.find("64x48"), std::string::npos) << show(r);

    r = fresnel({"compare", a.string(), a.string(), "--mask", b.string()});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error: " + b.string(), 0), 0u) << show(r);

    // Not images, cut short, lying headers, missing, a folder.
    const std::string png = slurp(a);
    std::vector<std::pair<std::string, std::string>> hostile = {
        {"text.png", "this is not an image\n"},
        {"empty.png", ""},
        {"cut.png", png.substr(0, png.size() / 2)},
        {"huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n"},
        {"cut.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 4\n\x02\x02"},
        {"bad.exr", std::string("\x76\x2f\x31\x01", 4) + std::string(64, '\xff')},
    };
    for (const auto& [name, bytes] : hostile) {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << bytes;
        for (const auto& args : {std::vector<std::string>{"compare", p.string(), a.string()},
                                 std::vector<std::string>{"compare", a.string(), p.string()}}) {
            r = fresnel(args);
            EXPECT_EQ(r.exit_code, 1) << name << "\n" << show(r);
            EXPECT_EQ(r.err.rfind("fresnel: error: " + p.string(), 0), 0u) << name << "\n" << show(r);
        }
    }
    r = fresnel({"compare", (dir_ / "missing.png").string(), a.string()});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    r = fresnel({"compare", dir_.string(), a.string()});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    r = fresnel({"compare", a.string()});  // B missing
    EXPECT_EQ(r.exit_code, 2) << show(r);
}

}  // namespace
