// `fresnel render --shading ogl1` against the real OpenGL 1 fixed-function pipeline:
// ../shared/tools/ogl1-ref renders its own scenes (make-scenes) with Mesa's fixed-function
// OpenGL, and fresnel must agree to at least 35 dB PSNR over the object (`fresnel compare
// --mask auto`, which equals compare.py's psnr_db) on every case: spheres over Ns and Ks,
// the textured sphere and cube (GL_MODULATE, separate specular), emission, two coloured
// lights with global ambient, linear / exp / exp2 fog, and the sanity scenes (colour-sum
// saturation, tilted normals, uniform texture, Ns 256 = 128). OpenGL 1 per fragment
// (ogl1-pixel) must agree too on the finely tessellated scenes, and glTF shading must NOT
// (the comparison can fail). Skips when the shared folder, or the tool's python3 with NumPy
// and Pillow, is absent. The figures are printed per case.
#include "cli_harness.h"
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

const fs::path kTool = fs::path(FRESNEL_SHARED_DIR) / "tools" / "ogl1-ref";

using fresnel::test::command_line;
using fresnel::test::TempDir;
using fresnel::test::quote;
using fresnel::test::run_captured;
using fresnel::test::show;
using fresnel::test::Result;
using fresnel::test::slurp;


std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

// One comparison: the same scene, camera and fog through both; the lights written in each
// tool's syntax (ogl1-ref: dir:AZ,EL[,R,G,B]; fresnel: dir:AZ,EL,INTENSITY[,R,G,B]).
struct Case {
    const char* name;
    const char* scene;
    const char* ref_lights;
    const char* fresnel_lights;
    const char* common;
};
const Case kCases[] = {
    {"spheres", "spheres", "", "--light dir:30,45,1", ""},
    {"spheres-2lights-ambient", "spheres", "--light dir:-60,30,1,0.85,0.7 --light dir:120,10,0.3,0.4,0.8",
     "--light dir:-60,30,1,1,0.85,0.7 --light dir:120,10,1,0.3,0.4,0.8", "--yaw 35 --pitch 10 --ambient 0.2,0.2,0.2"},
    {"spheres-fog-exp", "spheres", "", "", "--yaw 60 --fog exp:0.3 --fog-color 0.5,0.5,0.5"},
    {"spheres-fog-exp2", "spheres", "", "", "--yaw 60 --fog exp2:0.2 --background 0.2,0.3,0.4"},
    {"spheres-fog-linear", "spheres", "", "", "--yaw 60 --pitch -30 --fog linear:0,far"},
    {"textured", "textured", "", "", ""},
    {"textured-fog", "textured", "", "", "--yaw 30 --pitch 20 --fog linear:near,far --background 0.75,0.8,0.9"},
    {"emissive-side", "emissive", "--light dir:90,0", "--light dir:90,0,1", ""},
    {"sanity-sat", "sanity-sat", "", "", "--pitch 20"},
    {"sanity-plane", "sanity-plane", "", "", "--pitch 20"},
    {"sanity-tex", "sanity-tex", "", "", ""},
    {"sanity-spec256", "sanity-spec256", "", "", "--yaw 20"},
};

class Ogl1Ref : public ::testing::Test {
protected:
    static fs::path dir_;
    static inline std::unique_ptr<TempDir> scratch_;  // dir_, removed with it
    static bool usable_;
    static std::string skip_reason_;

    static Result exec(const std::string& program, const std::vector<std::string>& args) {
        return run_captured(command_line(program, args), dir_);
    }

    static void SetUpTestSuite() {
        scratch_ = std::make_unique<TempDir>("fresnel_ogl1_ref");
        dir_ = scratch_->path();
        if (!fs::exists(kTool / "render") || !fs::exists(kTool / "make-scenes")) {
            skip_reason_ = "no " + kTool.string();
            return;
        }
        Result r = exec(quote((kTool / "make-scenes").string()), {(dir_ / "scenes").string()});
        if (r.exit_code != 0 || !fs::exists(dir_ / "scenes" / "spheres.obj")) {
            skip_reason_ = "ogl1-ref/make-scenes cannot run here (python3 with NumPy and Pillow?): " + show(r);
            return;
        }
        usable_ = true;
    }
    static void TearDownTestSuite() { scratch_.reset(); }
    void SetUp() override {
        if (!usable_) GTEST_SKIP() << skip_reason_;
    }

    // PSNR of fresnel's image against ogl1-ref's over the object, in dB.
    double psnr(const Case& c, const std::string& shading, const std::string& extra = "") {
        const fs::path scene = dir_ / "scenes" / (std::string(c.scene) + ".obj");
        const fs::path ref = dir_ / (std::string(c.name) + ".ref.png");
        const fs::path ours = dir_ / (std::string(c.name) + "." + shading + ".png");
        std::vector<std::string> common = split(c.common), e = split(extra);
        if (!fs::exists(ref)) {
            std::vector<std::string> args = {scene.string(), "-o", ref.string(), "--size", "192x192"};
            for (const auto& a : split(c.ref_lights)) args.push_back(a);
            args.insert(args.end(), common.begin(), common.end());
            args.insert(args.end(), e.begin(), e.end());
            Result r = exec(quote((kTool / "render").string()), args);
            EXPECT_EQ(r.exit_code, 0) << show(r);
            if (r.exit_code != 0) return 0.0;
        }
        std::vector<std::string> args = {"render", scene.string(), "-o", ours.string(), "--size", "192x192",
                                         "--shading", shading};
        // No --msaa: --shading ogl1 defaults to none, as ogl1-ref (the issue's exact command line).
        for (const auto& a : split(c.fresnel_lights)) args.push_back(a);
        args.insert(args.end(), common.begin(), common.end());
        args.insert(args.end(), e.begin(), e.end());
        Result r = exec(quote(FRESNEL_EXE), args);
        EXPECT_EQ(r.exit_code, 0) << show(r);
        if (r.exit_code != 0) return 0.0;
        r = exec(quote(FRESNEL_EXE), {"compare", ours.string(), ref.string(), "--mask", "auto", "--json"});
        EXPECT_EQ(r.exit_code, 0) << show(r);
        nlohmann::json j;
        EXPECT_NO_THROW(j = nlohmann::json::parse(r.out)) << show(r);
        return j.value("psnr_db", 0.0);
    }
};
fs::path Ogl1Ref::dir_;
bool Ogl1Ref::usable_ = false;
std::string Ogl1Ref::skip_reason_;

}  // namespace

TEST_F(Ogl1Ref, PerVertexMatchesTheFixedFunctionPipeline) {
    for (const Case& c : kCases) {
        double db = psnr(c, "ogl1");
        std::printf("ogl1 %-26s %6.2f dB\n", c.name, db);
        EXPECT_GE(db, 35.0) << c.name;
    }
}

// Files of the shared OBJ cases the reference tool reads fully (no normals, no smoothing
// groups, quads; not concave_polygon.obj, which ogl1-ref fans across its hole while fresnel
// ear-clips it), by the issue's exact command lines: `fresnel render S.obj
// --shading ogl1 --light dir:30,45,1` against `ogl1-ref/render S.obj --light dir:30,45` (no
// --msaa: both none; missing normals: both smooth per position, as OpenGL 1 viewers make them).
TEST_F(Ogl1Ref, SharedObjCasesByTheIssuesCommandLines) {
    const fs::path obj = fs::path(FRESNEL_SHARED_DIR) / "assets" / "obj";
    if (!fs::exists(obj / "box.obj")) GTEST_SKIP() << "needs " << obj;
    for (const char* name : {"box", "regr01", "cube_usemtl"})
        for (const char* view : {"", "--yaw 40 --pitch 25"}) {
            const std::string tag = std::string(name) + (view[0] ? "_q" : "_front");
            const fs::path ref = dir_ / (tag + ".ref.png"), ours = dir_ / (tag + ".png");
            std::vector<std::string> ra = {(obj / (std::string(name) + ".obj")).string(), "-o", ref.string(), "--size",
                                           "192x192", "--light", "dir:30,45"};
            std::vector<std::string> fa = {"render", (obj / (std::string(name) + ".obj")).string(), "-o", ours.string(),
                                           "--size", "192x192", "--shading", "ogl1", "--light", "dir:30,45,1"};
            for (const auto& a : split(view)) ra.push_back(a), fa.push_back(a);
            Result r = exec(quote((kTool / "render").string()), ra);
            ASSERT_EQ(r.exit_code, 0) << show(r);
            r = exec(quote(FRESNEL_EXE), fa);
            ASSERT_EQ(r.exit_code, 0) << show(r);
            r = exec(quote(FRESNEL_EXE), {"compare", ours.string(), ref.string(), "--mask", "auto", "--json"});
            ASSERT_EQ(r.exit_code, 0) << show(r);
            const double db = nlohmann::json::parse(r.out).value("psnr_db", 0.0);
            std::printf("ogl1 shared %-24s %6.2f dB\n", tag.c_str(), db);
            EXPECT_GE(db, 35.0) << tag;
        }
}

TEST_F(Ogl1Ref, MsaaMatchesMultisampledReference) {
    // fresnel's default 4x MSAA against ogl1-ref --msaa 4 (both resolve box-filtered samples).
    const Case c{"spheres-msaa4", "spheres", "", "", "--yaw 20 --pitch 15"};
    double db = psnr(c, "ogl1", "--msaa 4");
    std::printf("ogl1 %-26s %6.2f dB\n", c.name, db);
    EXPECT_GE(db, 35.0);
}

TEST_F(Ogl1Ref, PerFragmentAgreesAndGltfDoesNot) {
    for (const Case& c : {kCases[0], kCases[5]}) {
        double db = psnr(c, "ogl1-pixel");
        std::printf("ogl1-pixel %-20s %6.2f dB\n", c.name, db);
        EXPECT_GE(db, 35.0) << c.name;
    }
    // The check can fail: the glTF BRDF with tone mapping is a different picture.
    double gltf = psnr(kCases[0], "gltf");
    std::printf("gltf %-26s %6.2f dB\n", kCases[0].name, gltf);
    EXPECT_LT(gltf, 30.0);
}
