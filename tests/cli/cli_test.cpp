// The `fresnel` executable end to end: exit codes (0 ok, 1 bad input, 2 bad usage),
// error message format, `info --json` counts and `render` output files.
// FRESNEL_EXE is the built program ($<TARGET_FILE:fresnel>).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

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

struct Result {
    int exit_code = -1;
    std::string out, err;
};

std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::path(::testing::TempDir()) / (std::string("fresnel_cli_") + info->name() + "_" +
                                                 std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    // Runs the program with `args`, capturing stdout, stderr and the exit status.
    Result run(const std::vector<std::string>& args) {
        std::string cmd = quote(FRESNEL_EXE);
        for (const auto& a : args) {
            cmd.append(" ");
            cmd.append(quote(a));
        }
        fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
        cmd.append(" >");
        cmd.append(quote(out.string()));
        cmd.append(" 2>");
        cmd.append(quote(err.string()));
        cmd.append(" </dev/null");
        int status = std::system(cmd.c_str());
        Result r;
        r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
        r.out = slurp(out);
        r.err = slurp(err);
        return r;
    }

    fs::path dir_;
};

std::string show(const Result& r) { return "exit " + std::to_string(r.exit_code) + "\nstdout:\n" + r.out + "\nstderr:\n" + r.err; }

TEST_F(Cli, HelpExitsZero) {
    Result r = run({"--help"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.out.find("render"), std::string::npos) << show(r);
    EXPECT_NE(r.out.find("info"), std::string::npos) << show(r);

    r = run({"render", "--help"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.out.find("--size"), std::string::npos) << show(r);

    r = run({"info", "--help"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.out.find("--json"), std::string::npos) << show(r);
}

TEST_F(Cli, InfoJsonCountsDamagedHelmet) {
    fs::path model = kShared / "assets" / "models" / "DamagedHelmet" / "DamagedHelmet.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "shared assets not found: " << model.string() << " (FRESNEL_SHARED_DIR)";
    Result r = run({"info", model.string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << show(r);
    EXPECT_EQ(j.at("vertices").get<long>(), 14556);
    EXPECT_EQ(j.at("triangles").get<long>(), 15452);
    EXPECT_EQ(j.at("meshes").get<long>(), 1);
    EXPECT_EQ(j.at("primitives").get<long>(), 1);
    EXPECT_TRUE(j.contains("bounds")) << show(r);
}

TEST_F(Cli, RenderDemoWritesPng) {
    fs::path png = dir_ / "demo.png";
    Result r = run({"render", "-o", png.string(), "--size", "96x64", "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    ASSERT_TRUE(fs::exists(png)) << show(r);
    fresnel::Image8 img = fresnel::read_image8(png);
    EXPECT_EQ(img.width, 96);
    EXPECT_EQ(img.height, 64);
    std::size_t lit = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const std::uint8_t* p = img.at(x, y);
            lit += p[0] > 8 || p[1] > 8 || p[2] > 8;
        }
    EXPECT_GT(lit, std::size_t(96 * 64 / 20)) << "the demo render is (nearly) blank";
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << show(r);
    EXPECT_EQ(j.at("width").get<int>(), 96);
    EXPECT_EQ(j.at("height").get<int>(), 64);
    EXPECT_EQ(j.at("model").get<std::string>(), "(demo)");
}

TEST_F(Cli, MissingModelIsBadInput) {
    fs::path missing = dir_ / "no_such_model.glb";
    fs::path png = dir_ / "out.png";
    Result r = run({"render", missing.string(), "-o", png.string(), "--size", "32x32"});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error:", 0), 0u) << show(r);
    EXPECT_FALSE(fs::exists(png)) << "an output was written for a model that does not exist";

    r = run({"info", missing.string()});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error:", 0), 0u) << show(r);
}

TEST_F(Cli, BadSizeIsUsageError) {
    fs::path png = dir_ / "out.png";
    for (const char* size : {"0x10", "10x0", "abc", "10x", "x10", "10x10x10", "10*10", "20000x10"}) {
        Result r = run({"render", "-o", png.string(), "--size", size});
        EXPECT_EQ(r.exit_code, 2) << "--size " << size << "\n" << show(r);
        EXPECT_EQ(r.err.rfind("fresnel: error: --size", 0), 0u) << "--size " << size << "\n" << show(r);
    }
    EXPECT_FALSE(fs::exists(png));
}

TEST_F(Cli, OtherUsageErrorsExitTwo) {
    EXPECT_EQ(run({}).exit_code, 2);                                              // no subcommand
    EXPECT_EQ(run({"render", "--no-such-option", "-o", "x.png"}).exit_code, 2);  // unknown option
    EXPECT_EQ(run({"render"}).exit_code, 2);                                      // -o missing
    Result r = run({"render", "-o", (dir_ / "x.png").string(), "--tonemap", "sepia"});
    EXPECT_EQ(r.exit_code, 2) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error:", 0), 0u) << show(r);
}

}  // namespace
