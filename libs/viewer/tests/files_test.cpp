// The viewer's file handling without a window: which paths are models and environments, a
// folder's models, PageUp/PageDown stepping, and the recent-files list.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "fresnel/viewer/files.h"

namespace fresnel::viewer {
namespace {
namespace fs = std::filesystem;

// A fresh folder under the test's temporary directory, removed afterwards.
class Folder : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::path(::testing::TempDir()) / ("fresnel_viewer_files_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path touch(const fs::path& relative) {
        fs::path p = dir_ / relative;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << "x";
        return p;
    }
    std::string abs(const fs::path& relative) const { return fs::absolute(dir_ / relative).lexically_normal().string(); }
    fs::path dir_;
};

TEST(FileKinds, ModelsScenesAndEnvironmentsByName) {
    EXPECT_TRUE(is_model("a/b.GLB"));
    EXPECT_TRUE(is_model("b.gltf"));
    EXPECT_TRUE(is_model("b.obj"));
    EXPECT_TRUE(is_model("shot.fresnel.json"));
    EXPECT_FALSE(is_model("other.json"));
    EXPECT_FALSE(is_model("sky.hdr"));
    EXPECT_TRUE(is_gltf("x.Gltf"));
    EXPECT_FALSE(is_gltf("x.obj"));
    EXPECT_TRUE(is_environment("sky.HDR"));
    EXPECT_TRUE(is_environment("sky.exr"));
    EXPECT_FALSE(is_environment("sky.png"));
    EXPECT_EQ(lower_extension("A.GlB"), ".glb");
    EXPECT_EQ(lower_extension("noext"), "");
}

TEST(FileKinds, TheImageBesideASceneFile) {
    EXPECT_EQ(image_beside("out/shot.fresnel.json"), fs::path("out/shot.png"));
    EXPECT_EQ(image_beside("shot.json"), fs::path("shot.png"));
    EXPECT_EQ(image_beside("shot"), fs::path("shot.png"));
}

TEST_F(Folder, ABakedFolderIsAnEnvironmentAPlainOneIsNot) {
    touch("baked/manifest.json");
    fs::create_directories(dir_ / "plain");
    EXPECT_TRUE(is_environment(dir_ / "baked"));
    EXPECT_TRUE(is_folder(dir_ / "plain"));
    EXPECT_FALSE(is_environment(dir_ / "plain"));
    EXPECT_FALSE(is_folder(dir_ / "missing"));
}

TEST_F(Folder, ListModelsSortedAbsoluteThreeLevelsDeep) {
    touch("b.glb");
    touch("a.gltf");
    touch("notes.txt");
    touch("x/scene.fresnel.json");
    touch("x/1/2/deep.obj");      // depth 3: listed
    touch("x/1/2/3/4/deeper.obj");  // below: not
    auto models = list_models(dir_);
    std::vector<std::string> want = {abs("a.gltf"), abs("b.glb"), abs("x/1/2/deep.obj"), abs("x/scene.fresnel.json")};
    EXPECT_EQ(models, want);
}

TEST_F(Folder, SiblingsOfAModelAloneInItsFolderAreTheFolderAbove) {
    touch("Box/glTF-Binary/Box.glb");
    touch("Duck/glTF-Binary/Duck.glb");
    auto models = sibling_models((dir_ / "Box/glTF-Binary/Box.glb").string());
    std::vector<std::string> want = {abs("Box/glTF-Binary/Box.glb"), abs("Duck/glTF-Binary/Duck.glb")};
    EXPECT_EQ(models, want);
}

TEST(StepFolder, WrapsAtBothEndsAndStartsAtTheFirst) {
    const std::vector<std::string> models = {"/m/a.glb", "/m/b.glb", "/m/c.glb"};
    EXPECT_EQ(step_folder(models, "/m/c.glb", +1), "/m/a.glb");
    EXPECT_EQ(step_folder(models, "/m/a.glb", -1), "/m/c.glb");
    EXPECT_EQ(step_folder(models, "/m/a.glb", +1), "/m/b.glb");
    EXPECT_EQ(step_folder(models, "/m/./b.glb", +1), "/m/c.glb");  // any spelling of the path
    EXPECT_EQ(step_folder(models, "/elsewhere.glb", -1), "/m/a.glb");
    EXPECT_EQ(step_folder(models, "", +1), "/m/a.glb");
    EXPECT_FALSE(step_folder({}, "/m/a.glb", +1));
}

TEST_F(Folder, RecentFilesNewestFirstEachOnceAtMostTwelve) {
    RecentFiles r;
    for (int i = 0; i < 15; ++i) r.add((dir_ / ("m" + std::to_string(i) + ".glb")).string());
    ASSERT_EQ(r.paths().size(), RecentFiles::kCapacity);
    EXPECT_EQ(r.paths().front(), abs("m14.glb"));
    EXPECT_EQ(r.paths().back(), abs("m3.glb"));  // m0..m2 dropped
    r.add((dir_ / "sub/../m5.glb").string());   // again, spelt otherwise: moves to the front
    EXPECT_EQ(r.paths().size(), RecentFiles::kCapacity);
    EXPECT_EQ(r.paths().front(), abs("m5.glb"));
    EXPECT_EQ(std::count(r.paths().begin(), r.paths().end(), abs("m5.glb")), 1);
}

TEST_F(Folder, RecentFilesRoundTripThroughTheirFile) {
    const fs::path file = dir_ / "cache/fresnel/viewer-recent.txt";  // its folder is created
    RecentFiles a;
    a.add((dir_ / "one.glb").string());
    a.add((dir_ / "two.hdr").string());
    ASSERT_TRUE(a.save(file));
    RecentFiles b;
    b.load(file);
    EXPECT_EQ(b.paths(), a.paths());
    RecentFiles none;
    none.load(dir_ / "missing.txt");
    EXPECT_TRUE(none.paths().empty());
    // A hand-edited file longer than the list: blank lines skipped, the first twelve kept.
    std::ofstream(dir_ / "long.txt") << "\n/a\n\n/b\n/c\n/d\n/e\n/f\n/g\n/h\n/i\n/j\n/k\n/l\n/m\n";
    RecentFiles c;
    c.load(dir_ / "long.txt");
    ASSERT_EQ(c.paths().size(), RecentFiles::kCapacity);
    EXPECT_EQ(c.paths().front(), "/a");
    EXPECT_EQ(c.paths().back(), "/l");
}

}  // namespace
}  // namespace fresnel::viewer
