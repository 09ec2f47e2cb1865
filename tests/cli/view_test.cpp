// `fresnel view` end to end, in a real window under Xvfb (a server of its own per command,
// Mesa's llvmpipe through GLX): `--screenshot` writes the frame the window presents (read back from its
// back buffer before the GUI is drawn) and must equal `fresnel render` for the same flags
// (PSNR >= 40 dB over every pixel, never exact bytes); bad input exits 1 with the loader's
// error. Skips when the build has no viewer or neither Xvfb nor a DISPLAY is there.
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

#include "cli_harness.h"
#include "gltf_builders.h"
#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"

namespace fs = std::filesystem;

namespace {

const fs::path kShared = FRESNEL_SHARED_DIR;

using fresnel::test::command_line;
using fresnel::test::quote;
using fresnel::test::Result;
using fresnel::test::slurp;

// The sh function the xdotool sessions wait with: `wait_for 'CONDITION'` polls every 0.1 s up to
// `tenths` times; it gives up at once when the viewer ($pid) has gone, noting why in err.txt.
std::string wait_for_function(int tenths) {
    return "wait_for() {\n"
           "  for i in $(seq " + std::to_string(tenths) + "); do\n"
           "    eval \"$1\" && return 0\n"
           "    kill -0 $pid 2>/dev/null || { echo \"the viewer exited early (waiting for: $1)\" >>err.txt; exit 0; }\n"
           "    sleep 0.1\n"
           "  done\n"
           "  echo \"timed out: $1\" >>err.txt\n"
           "  kill $pid; wait $pid; exit 0\n"
           "}";
}

class View : public ::testing::Test {
protected:
    void SetUp() override {
#ifndef FRESNEL_HAVE_VIEWER
        GTEST_SKIP() << "this build has no viewer (GLFW or Dear ImGui missing)";
#endif
        const bool xvfb = std::system("command -v Xvfb >/dev/null 2>&1") == 0;
        if (!xvfb && !std::getenv("DISPLAY")) GTEST_SKIP() << "neither Xvfb nor a DISPLAY";
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::path(::testing::TempDir()) / (std::string("fresnel_view_") + info->name() + "_" +
                                                 std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        if (xvfb) {
            // Each windowed command gets its own Xvfb on a display the server picks itself
            // (-displayfd: no race for numbers between parallel runs), stopped afterwards.
            // Not xvfb-run: when its clean-up of the Xauthority folder fails (seen on Debian
            // 12) it exits 5 before stopping its server, leaving it running.
            fs::path wrapper = dir_ / "with_display.sh";
            std::ofstream(wrapper) << R"SH(d=$(mktemp -d)
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$d/n" 2>"$d/log" &
x=$!
i=0
while [ ! -s "$d/n" ] && [ $i -lt 400 ]; do sleep 0.05; i=$((i + 1)); done
if [ ! -s "$d/n" ]; then kill $x 2>/dev/null; cat "$d/log" >&2; rm -rf "$d"; exit 97; fi
export DISPLAY=:$(cat "$d/n")
# The number comes once the server listens; a client's first answer says it serves (CI once saw
# GLFW fail to open a display the server had just named). -noreset: without it the server resets
# when its last client leaves, and a client that connects then (the viewer, right after this
# probe) is refused: "X11: Failed to open display :0", 2 of 5 runs of the drop test here.
if command -v xdotool >/dev/null 2>&1; then
  i=0
  until xdotool getdisplaygeometry >/dev/null 2>&1; do
    i=$((i + 1))
    if [ $i -ge 200 ]; then echo "Xvfb on $DISPLAY never answered" >&2; cat "$d/log" >&2; kill $x; rm -rf "$d"; exit 97; fi
    sleep 0.05
  done
fi
"$@"
rc=$?
kill $x 2>/dev/null
wait $x 2>/dev/null
rm -rf "$d"
exit $rc
)SH";
            display_prefix_ = "sh " + quote(wrapper.string()) + " ";
        }
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }

    // Runs the program; `windowed`: on the display (a fresh Xvfb, or $DISPLAY). The exit
    // status is the program's own, written to a file.
    Result run(const std::vector<std::string>& args, bool windowed) {
        std::string inner = command_line(quote(FRESNEL_EXE), args);
        fs::path err = dir_ / "stderr.txt", rc = dir_ / "rc.txt", out = dir_ / "stdout.txt";
        fs::remove(rc);
        inner.append(" >");  // appended piece by piece: GCC 12 warns (-Wrestrict) on a + chain here
        inner.append(quote(out.string()));
        inner.append(" 2>");
        inner.append(quote(err.string()));
        inner.append(" </dev/null; echo $? >");
        inner.append(quote(rc.string()));
        std::string cmd = windowed ? display_prefix_ : std::string();
        cmd.append("sh -c ");
        cmd.append(quote(inner));
        std::system(cmd.c_str());
        Result r;
        std::istringstream(slurp(rc)) >> r.exit_code;  // -1 when the program never ran
        r.err = slurp(err);
        r.out = slurp(out);
        return r;
    }

    Result run_shell(const std::string& command) {
        fs::path err = dir_ / "shell_stderr.txt";
        std::string cmd = command;
        cmd.append(" >/dev/null 2>");
        cmd.append(quote(err.string()));
        int status = std::system(cmd.c_str());
        Result r;
        r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
        r.err = slurp(err);
        return r;
    }

    // Renders `args` with `fresnel render` and `fresnel view --screenshot`; returns the PSNR.
    double view_against_render(const std::vector<std::string>& args) {
        fs::path rendered = dir_ / "render.png", viewed = dir_ / "view.png";
        std::vector<std::string> r = {"render"}, v = {"view"};
        r.insert(r.end(), args.begin(), args.end());
        v.insert(v.end(), args.begin(), args.end());
        r.insert(r.end(), {"-o", rendered.string()});
        v.insert(v.end(), {"--screenshot", viewed.string()});
        Result rr = run(r, false);
        EXPECT_EQ(rr.exit_code, 0) << rr.err;
        Result vr = run(v, true);
        EXPECT_EQ(vr.exit_code, 0) << vr.err;
        if (rr.exit_code != 0 || vr.exit_code != 0) return 0.0;
        fresnel::Image8 a = fresnel::read_image8(rendered), b = fresnel::read_image8(viewed);
        EXPECT_EQ(a.width, b.width);
        EXPECT_EQ(a.height, b.height);
        EXPECT_EQ(a.channels, b.channels);
        if (a.width != b.width || a.height != b.height || a.channels != b.channels) return 0.0;
        // Not blank: the frame has more than its background.
        bool varied = false;
        for (std::size_t i = 3; i < b.pixels.size() && !varied; ++i) varied = b.pixels[i] != b.pixels[i % 3];
        EXPECT_TRUE(varied) << "the viewer's frame is one colour";
        fresnel::ImageMetrics m = fresnel::compare_images(a, b, /*mask_background=*/false);
        EXPECT_EQ(m.pixels, std::size_t(a.width) * std::size_t(a.height));
        std::printf("view --screenshot vs render: %.1f dB\n", m.psnr_db);
        return m.psnr_db;
    }

    // The last `fresnel render` line a session printed (Ctrl+C), or "" (a failure) when none.
    static std::string last_command_line(const std::string& out) {
        std::size_t at = out.rfind("fresnel render ");
        if (at == std::string::npos) return {};
        return out.substr(at, out.find('\n', at) - at);
    }
    // Runs a copied command line (its -o view.png) with the real program in dir_ and returns
    // its PSNR against the session's F12 screenshot (fresnel-*.png in dir_); -1 on failure.
    double copied_command_vs_f12(const std::string& line) {
        fs::path screenshot;
        for (const auto& e : fs::directory_iterator(dir_))
            if (e.path().filename().string().starts_with("fresnel-")) screenshot = e.path();
        if (screenshot.empty()) {
            ADD_FAILURE() << "no F12 screenshot in " << dir_;
            return -1.0;
        }
        std::string render = line.substr(std::string("fresnel").size());
        Result r = run_shell("cd " + quote(dir_.string()) + " && " + quote(FRESNEL_EXE) + render);
        if (r.exit_code != 0) {
            ADD_FAILURE() << r.err << line;
            return -1.0;
        }
        return fresnel::compare_images(fresnel::read_image8(dir_ / "view.png"), fresnel::read_image8(screenshot), false)
            .psnr_db;
    }
    // PSNR of two 8-bit images over every pixel (paths relative to dir_, or absolute).
    double psnr(const fs::path& a, const fs::path& b) const {
        return fresnel::compare_images(fresnel::read_image8(dir_ / a), fresnel::read_image8(dir_ / b), false).psnr_db;
    }
    std::string display_prefix_;
    fs::path dir_;
};

TEST_F(View, ScreenshotOfTheDemoEqualsRender) {
    double psnr = view_against_render({"--size", "240x180", "--yaw", "20", "--pitch", "15", "--tonemap", "aces"});
    EXPECT_GE(psnr, 40.0);
}

TEST_F(View, ScreenshotThroughOpenGlEsEqualsRender) {
    EXPECT_GE(view_against_render({"--size", "160x120", "--gl", "es3", "--pitch", "30"}), 40.0);
}

TEST_F(View, ScreenshotOfDamagedHelmetEqualsRender) {
    fs::path model = kShared / "assets/models/DamagedHelmet/DamagedHelmet.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "needs " << model;
    EXPECT_GE(view_against_render({model.string(), "--size", "256x192", "--yaw", "-35", "--pitch", "10",
                                   "--distance", "2.5", "--target", "0.1,0,0", "--exposure", "0.5"}),
              40.0);
    // A debug channel and a colour background, too.
    EXPECT_GE(view_against_render({model.string(), "--size", "200x150", "--debug", "roughness"}), 40.0);
}

TEST_F(View, ScreenshotThroughTheFilesCameraEqualsRender) {
    fs::path model = kShared / "assets/models/Cameras/Cameras.gltf";
    if (!fs::exists(model)) GTEST_SKIP() << "needs " << model;
    EXPECT_GE(view_against_render({model.string(), "--size", "160x120", "--camera", "0", "--background", "0.2,0.3,0.4"}),
              40.0);
}

TEST_F(View, GuiIsDrawnOverTheFrame) {
    fs::path plain = dir_ / "plain.png", gui = dir_ / "gui.png";
    std::vector<std::string> args = {"view", "--size", "320x240", "--exit-after", "2", "--screenshot"};
    auto a = args, b = args;
    a.push_back(plain.string());
    b.insert(b.end(), {gui.string(), "--with-gui"});
    ASSERT_EQ(run(a, true).exit_code, 0);
    ASSERT_EQ(run(b, true).exit_code, 0);
    fresnel::ImageMetrics m = fresnel::compare_images(fresnel::read_image8(plain), fresnel::read_image8(gui), false);
    // The panel covers a good part of the window's top left.
    EXPECT_LT(m.psnr_db, 25.0);
    EXPECT_GT(m.max_abs, 100.0);
}

// A person's session, played by xdotool: drag to orbit, resize, Ctrl+C copies (and prints) the
// `fresnel render` command of the view, F12 saves a screenshot, Escape quits. The command,
// run, writes the screenshot's picture.
TEST_F(View, DragCopyCommandLineAndScreenshotAgreeWithRender) {
    if (display_prefix_.empty() || std::system("command -v xdotool >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "needs Xvfb and xdotool";
    fs::path script = dir_ / "session.sh";
    std::ofstream(script) << R"SH(set -u
cd "$1"
"$2" view --size 640x360 --msaa 1 --anisotropy 1 >out.txt 2>err.txt &
pid=$!
)SH" << wait_for_function(600) << R"SH(
wait_for 'xdotool search --name "fresnel view" >/dev/null 2>&1'
# Ready when it answers: the first Ctrl+C prints the opening view.
xdotool mousemove 520 180; sleep 0.5
xdotool key ctrl+c
wait_for '[ "$(grep -c "fresnel render" out.txt)" -ge 1 ]'
sleep 0.5
xdotool mousedown 1; sleep 0.5
xdotool mousemove 540 190; sleep 0.5
xdotool mousemove 560 200; sleep 0.5
xdotool mouseup 1; sleep 1
xdotool windowsize "$(xdotool search --name "fresnel view" | head -1)" 600 340; sleep 2
xdotool mousemove 500 200; sleep 0.5
xdotool key ctrl+c
wait_for '[ "$(grep -c "fresnel render" out.txt)" -ge 2 ]'
xdotool key F12
wait_for 'ls fresnel-*.png >/dev/null 2>&1'
sleep 1
xdotool key Escape
wait $pid
echo "exit $?" >>err.txt
)SH";
    std::string cmd = display_prefix_ + "sh " + quote(script.string()) + " " + quote(dir_.string()) + " " +
                      quote(FRESNEL_EXE);
    std::system(cmd.c_str());  // checked through what it wrote
    std::string err = slurp(dir_ / "err.txt"), out = slurp(dir_ / "out.txt");
    EXPECT_NE(err.find("exit 0"), std::string::npos) << err;
    std::string line = last_command_line(out);  // the second: after the drag and the resize
    ASSERT_FALSE(line.empty()) << out << err;
    // The drag turned the camera (40 px right, 20 px down), and the window was resized. The
    // panel is docked at the left of an interactive window: the 3D view, the copied --size and
    // the F12 screenshot are the window right of it (at least 240 points, at most 45 %).
    EXPECT_NE(line.find("--yaw -12 --pitch 6"), std::string::npos) << line;
    const std::size_t at = line.find("--size ");
    ASSERT_NE(at, std::string::npos) << line;
    int w = 0, h = 0;
    ASSERT_EQ(std::sscanf(line.c_str() + at, "--size %dx%d", &w, &h), 2) << line;
    EXPECT_EQ(h, 340) << line;
    EXPECT_GE(w, 600 - 270) << line;
    EXPECT_LE(w, 600 - 240) << line;
    double psnr = copied_command_vs_f12(line);
    std::printf("copied command vs F12 screenshot: %.1f dB\n", psnr);
    EXPECT_GE(psnr, 40.0) << line << err;
}

// Drag and drop as a file manager does it (XDND, by tests/cli/xdnd_drop.cpp): a broken glTF
// (its error shown, the viewer stays), a model, then an environment dropped onto the window;
// Ctrl+C's command line names both, and F12's screenshot is what that command renders.
TEST_F(View, DroppedFilesOpenAndBrokenOnesLeaveTheViewerRunning) {
#ifndef XDND_DROP_EXE
    GTEST_SKIP() << "built without Xlib (no xdnd_drop)";
#else
    fs::path model = kShared / "assets/models/BoxTextured/BoxTextured.glb";
    fs::path env = kShared / "assets/env/studio_small_03_1k.hdr";
    if (!fs::exists(model) || !fs::exists(env)) GTEST_SKIP() << "needs the shared assets";
    if (display_prefix_.empty() || std::system("command -v xdotool >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "needs Xvfb and xdotool";
    std::ofstream(dir_ / "broken.gltf") << "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"mesh\": 7}]}";
    fs::path script = dir_ / "drop.sh";
    std::ofstream(script) << R"SH(set -u
cd "$1"
"$2" view --size 320x240 --msaa 1 --anisotropy 1 >out.txt 2>err.txt &
pid=$!
)SH" << wait_for_function(900) << R"SH(
wait_for 'xdotool search --name "fresnel view" >/dev/null 2>&1'
win=$(xdotool search --name "fresnel view" | head -1)
xdotool mousemove 160 120; sleep 0.5
xdotool key ctrl+c
wait_for '[ "$(grep -c "fresnel render" out.txt)" -ge 1 ]'
"$3" "$win" 160 120 "$PWD/broken.gltf" >>drop.txt 2>&1; echo "drop broken $?" >>drop.txt
wait_for 'grep -q "broken.gltf" err.txt'
"$3" "$win" 160 120 "$4" >>drop.txt 2>&1; echo "drop model $?" >>drop.txt
sleep 1
"$3" "$win" 160 120 "$5" >>drop.txt 2>&1; echo "drop env $?" >>drop.txt
wait_for 'grep -q "lighting ready: .*studio_small_03" err.txt'
sleep 1
xdotool mousemove 150 110; sleep 0.5
xdotool key ctrl+c
wait_for '[ "$(grep -c "fresnel render" out.txt)" -ge 2 ]'
xdotool key F12
wait_for 'ls fresnel-*.png >/dev/null 2>&1'
sleep 1
xdotool key Escape
wait $pid
echo "exit $?" >>err.txt
)SH";
    std::string cmd = display_prefix_ + "sh " + quote(script.string()) + " " + quote(dir_.string()) + " " +
                      quote(FRESNEL_EXE) + " " + quote(XDND_DROP_EXE) + " " + quote(model.string()) + " " +
                      quote(env.string());
    std::system(cmd.c_str());  // checked through what it wrote
    std::string err = slurp(dir_ / "err.txt"), out = slurp(dir_ / "out.txt"), drops = slurp(dir_ / "drop.txt");
    EXPECT_NE(drops.find("drop broken 0"), std::string::npos) << drops;
    EXPECT_NE(drops.find("drop model 0"), std::string::npos) << drops;
    EXPECT_NE(drops.find("drop env 0"), std::string::npos) << drops;
    EXPECT_NE(err.find("exit 0"), std::string::npos) << err;
    // The loader's message, naming the file and the place.
    EXPECT_NE(err.find("broken.gltf"), std::string::npos) << err;
    EXPECT_NE(err.find("/nodes/0"), std::string::npos) << err;
    std::string line = last_command_line(out);
    ASSERT_FALSE(line.empty()) << out << err;
    EXPECT_NE(line.find("BoxTextured.glb"), std::string::npos) << line;
    EXPECT_NE(line.find("studio_small_03_1k.hdr"), std::string::npos) << line;
    double psnr = copied_command_vs_f12(line);
    std::printf("after the drops, copied command vs F12 screenshot: %.1f dB\n", psnr);
    EXPECT_GE(psnr, 40.0) << line << err;
#endif
}

// --script: orbit, a broken model (reported with its line; the scene stays), a debug
// channel and a missing environment (reported; the lighting stays), each screenshot equal
// to `fresnel render` for the same view.
TEST_F(View, ScriptedSessionKeepsTheSceneOnBadFiles) {
    fs::path model = kShared / "assets/models/DamagedHelmet/DamagedHelmet.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "needs " << model;
    std::ofstream(dir_ / "broken.gltf") << "{\"asset\":";
    std::ofstream(dir_ / "session.txt") << "orbit 30 10\n"
                                           "screenshot " << (dir_ / "a.png").string() << "\n"
                                           "open " << (dir_ / "broken.gltf").string() << "\n"
                                           "screenshot " << (dir_ / "b.png").string() << "\n"
                                           "# a comment\n"
                                           "debug roughness\n"
                                           "wait 1\n"
                                           "screenshot " << (dir_ / "c.png").string() << "\n"
                                           "env " << (dir_ / "missing.hdr").string() << "\n"
                                           "wait 2\n"
                                           "screenshot " << (dir_ / "d.png").string() << "\n"
                                           "quit\n";
    Result r = run({"view", model.string(), "--size", "200x150", "--script", (dir_ / "session.txt").string()}, true);
    EXPECT_EQ(r.exit_code, 1) << r.err;  // the failed open and env
    EXPECT_NE(r.err.find("session.txt: line 3: open"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("broken.gltf: byte"), std::string::npos) << r.err;  // the loader's own message
    EXPECT_NE(r.err.find("session.txt: line 9: env"), std::string::npos) << r.err;
    Result ra = run({"render", model.string(), "--size", "200x150", "--yaw", "30", "--pitch", "10", "-o",
                     (dir_ / "ra.png").string()}, false);
    Result rc = run({"render", model.string(), "--size", "200x150", "--yaw", "30", "--pitch", "10", "--debug",
                     "roughness", "-o", (dir_ / "rc.png").string()}, false);
    ASSERT_EQ(ra.exit_code, 0) << ra.err;
    ASSERT_EQ(rc.exit_code, 0) << rc.err;
    for (const char* f : {"a.png", "b.png", "c.png", "d.png"}) ASSERT_TRUE(fs::exists(dir_ / f)) << f << r.err;
    EXPECT_GE(psnr("a.png", "ra.png"), 40.0);
    EXPECT_GE(psnr("b.png", "ra.png"), 40.0);  // the broken file left the helmet
    EXPECT_GE(psnr("c.png", "rc.png"), 40.0);
    EXPECT_GE(psnr("d.png", "rc.png"), 40.0);  // the missing environment left the lighting
    EXPECT_LT(psnr("a.png", "c.png"), 30.0);   // and the channel did change the picture
}

// Shadows toggled live by a script (`set render.shadows ...`, the settings registry's key): each
// screenshot equals `fresnel render` with the same --shadows, and turning them off changes the
// picture (the shadows on the ground go).
TEST_F(View, ShadowsToggleLive) {
    const fs::path model = fs::path(FRESNEL_SOURCE_DIR) / "tests/data/shadows/shadow-directional.gltf";
    std::ofstream(dir_ / "s.txt") << "orbit 20 30\n"
                                     "screenshot " << (dir_ / "soft.png").string() << "\n"
                                     "set render.shadows off\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "off.png").string() << "\n"
                                     "set render.shadows hard\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "hard.png").string() << "\n"
                                     "quit\n";
    Result r = run({"view", model.string(), "--size", "200x150", "--env", "none", "--script", (dir_ / "s.txt").string()},
                   true);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* mode : {"soft", "off", "hard"}) {
        const std::string rendered = std::string("r-") + mode + ".png";
        Result rr = run({"render", model.string(), "--size", "200x150", "--env", "none", "--yaw", "20", "--pitch", "30",
                         "--shadows", mode, "-o", (dir_ / rendered).string()},
                        false);
        ASSERT_EQ(rr.exit_code, 0) << rr.err;
        EXPECT_GE(psnr((std::string(mode) + ".png").c_str(), rendered.c_str()), 40.0) << mode;
    }
    EXPECT_LT(psnr("soft.png", "off.png"), 30.0);  // the shadows went
    EXPECT_GE(psnr("soft.png", "hard.png"), 30.0);  // and hard ones fall where soft ones do
}

// An area light added live by a script (`light rect:...`, as --light writes it): the screenshot
// equals `fresnel render --light` with it, with and without shadows, and each step changes the
// picture (the light, then its shadows).
TEST_F(View, AreaLightAddedLiveEqualsRender) {
    const fs::path model = fs::path(FRESNEL_SOURCE_DIR) / "tests/data/shadows/shadow-directional.gltf";
    const std::string light = "rect:0,2.5,0.5,0,70,1.5,1,6";
    std::ofstream(dir_ / "a.txt") << "orbit 20 30\n"
                                     "screenshot " << (dir_ / "plain.png").string() << "\n"
                                     "light " << light << "\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "rect.png").string() << "\n"
                                     "set render.shadows off\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "rect-off.png").string() << "\n"
                                     "quit\n";
    Result r = run({"view", model.string(), "--size", "200x150", "--env", "none", "--script", (dir_ / "a.txt").string()},
                   true);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {"plain", {}}, {"rect", {"--light", light}}, {"rect-off", {"--light", light, "--shadows", "off"}}};
    for (const auto& [name, flags] : cases) {
        std::vector<std::string> ra = {"render", model.string(), "--size", "200x150", "--env", "none", "--yaw", "20",
                                       "--pitch", "30", "-o", (dir_ / ("r-" + name + ".png")).string()};
        ra.insert(ra.end(), flags.begin(), flags.end());
        Result rr = run(ra, false);
        ASSERT_EQ(rr.exit_code, 0) << rr.err;
        EXPECT_GE(psnr((name + ".png").c_str(), ("r-" + name + ".png").c_str()), 40.0) << name;
    }
    EXPECT_LT(psnr("plain.png", "rect.png"), 30.0);     // the area light shines
    EXPECT_LT(psnr("rect.png", "rect-off.png"), 40.0);  // and casts shadows
}

// Screen-space occlusion toggled live (`set render.ao ssao`): the screenshot equals `fresnel
// render --ao ssao`, and the contacts darken.
TEST_F(View, ScreenSpaceOcclusionTogglesLive) {
    const fs::path model = fs::path(FRESNEL_SOURCE_DIR) / "tests/data/shadows/shadow-environment.gltf";
    std::ofstream(dir_ / "s.txt") << "orbit 20 30\n"
                                     "screenshot " << (dir_ / "off.png").string() << "\n"
                                     "set render.ao ssao\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "ssao.png").string() << "\n"
                                     "quit\n";
    const std::vector<std::string> common = {"--size", "200x150", "--env", "color:1,1,1"};
    std::vector<std::string> args = {"view", model.string(), "--script", (dir_ / "s.txt").string()};
    args.insert(args.end(), common.begin(), common.end());
    Result r = run(args, true);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* ao : {"off", "ssao"}) {
        std::vector<std::string> ra = {"render", model.string(), "--yaw", "20", "--pitch", "30", "--ao", ao, "-o",
                                       (dir_ / (std::string("r-") + ao + ".png")).string()};
        ra.insert(ra.end(), common.begin(), common.end());
        Result rr = run(ra, false);
        ASSERT_EQ(rr.exit_code, 0) << rr.err;
        EXPECT_GE(psnr((std::string(ao) + ".png").c_str(), (std::string("r-") + ao + ".png").c_str()), 40.0) << ao;
    }
    EXPECT_LT(psnr("off.png", "ssao.png"), 45.0);  // the contacts darkened
}

// Baked occlusion and the environment's dominant light toggled live by a script (`set render.ao
// baked`, `set render.envLight dominant`): each screenshot equals `fresnel render` with the same
// flags, and each toggle changes the picture.
TEST_F(View, OcclusionAndTheEnvironmentsLightToggleLive) {
    const fs::path model = fs::path(FRESNEL_SOURCE_DIR) / "tests/data/shadows/shadow-environment.gltf";
    fs::path env = kShared / "assets/env/studio_small_03_1k.hdr";
    if (!fs::exists(env)) GTEST_SKIP() << "needs " << env;
    std::ofstream(dir_ / "o.txt") << "orbit 20 30\n"
                                     "screenshot " << (dir_ / "plain.png").string() << "\n"
                                     "set render.ao baked\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "ao.png").string() << "\n"
                                     "set render.envLight dominant\n"
                                     "wait 30\n"
                                     "screenshot " << (dir_ / "both.png").string() << "\n"
                                     "quit\n";
    const std::vector<std::string> common = {"--size", "200x150", "--env", env.string(), "--background", "0.2,0.2,0.2"};
    std::vector<std::string> args = {"view", model.string(), "--script", (dir_ / "o.txt").string()};
    args.insert(args.end(), common.begin(), common.end());
    Result r = run(args, true);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {"plain", {}}, {"ao", {"--ao", "baked"}}, {"both", {"--ao", "baked", "--env-light", "dominant"}}};
    for (const auto& [name, flags] : cases) {
        std::vector<std::string> ra = {"render", model.string(), "--yaw", "20", "--pitch", "30", "-o",
                                       (dir_ / ("r-" + name + ".png")).string()};
        ra.insert(ra.end(), common.begin(), common.end());
        ra.insert(ra.end(), flags.begin(), flags.end());
        Result rr = run(ra, false);
        ASSERT_EQ(rr.exit_code, 0) << rr.err;
        EXPECT_GE(psnr((name + ".png").c_str(), ("r-" + name + ".png").c_str()), 40.0) << name;
    }
    EXPECT_LT(psnr("plain.png", "ao.png"), 50.0);  // the occlusion darkened the contacts
    EXPECT_LT(psnr("ao.png", "both.png"), 30.0);   // the key light's shadows fell
}

// Animation playback (issue: the viewer played no animation). A screenshot at --time T equals
// `fresnel render --time T`; a scripted session scrubs (`time`), chooses an animation, plays for
// a while, pauses, and its screenshot equals the render command line it prints (which names
// the time the playback reached), and differs from the rest pose.
TEST_F(View, AnimationPlaybackShowsWhatRenderPosesAtTheSameTime) {
    fs::path model = kShared / "assets/models/CesiumMan/CesiumMan.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "needs " << model;
    EXPECT_GE(view_against_render({model.string(), "--size", "200x150", "--yaw", "30", "--time", "1.2"}), 40.0);
    std::ofstream(dir_ / "a.txt") << "time 0.5\n"
                                     "screenshot " << (dir_ / "half.png").string() << "\n"
                                     "animation 0\n"
                                     "play\n"
                                     "wait 20\n"
                                     "pause\n"
                                     "screenshot " << (dir_ / "paused.png").string() << "\n"
                                     "print\n"
                                     "quit\n";
    Result v = run({"view", model.string(), "--size", "200x150", "--script", (dir_ / "a.txt").string()}, true);
    ASSERT_EQ(v.exit_code, 0) << v.err;
    const std::string line = last_command_line(v.out);
    ASSERT_NE(line.find("--time "), std::string::npos) << v.out;
    ASSERT_NE(line.find("--animation 0"), std::string::npos) << v.out;
    const float t = std::stof(line.substr(line.find("--time ") + 7));
    EXPECT_GT(t, 0.5f) << "the playback did not move: " << line;
    EXPECT_LE(t, 2.0f) << line;  // CesiumMan's walk lasts 2 s and loops
    std::vector<std::string> at = {"render", model.string(), "--size", "200x150", "--time", "0.5", "-o",
                                   (dir_ / "r-half.png").string()};
    ASSERT_EQ(run(at, false).exit_code, 0);
    EXPECT_GE(psnr(dir_ / "half.png", dir_ / "r-half.png"), 40.0);
    Result r = run_shell("cd " + quote(dir_.string()) + " && " + quote(FRESNEL_EXE) + line.substr(std::string("fresnel").size()));
    ASSERT_EQ(r.exit_code, 0) << r.err << line;  // its -o view.png
    const double paused = psnr(dir_ / "paused.png", dir_ / "view.png");
    std::printf("view after playback (t = %.3f) vs its printed render line: %.1f dB\n", double(t), paused);
    EXPECT_GE(paused, 40.0);
    ASSERT_EQ(run({"render", model.string(), "--size", "200x150", "-o", (dir_ / "rest.png").string()}, false).exit_code, 0);
    EXPECT_LT(psnr(dir_ / "half.png", dir_ / "rest.png"), 35.0);  // posed, not the rest pose
}

// The Features switches and the variants picker reload the scene as the job's source changes
// (a script's `set disable ...` here, as the panel's checkbox does): each screenshot equals
// `fresnel render --disable ...`, and turning clear coat off changes the picture.
TEST_F(View, SwitchingPartsOfTheFileOffEqualsRender) {
    fs::path model = kShared / "assets/models/ClearCoatTest/ClearCoatTest.gltf";
    if (!fs::exists(model)) GTEST_SKIP() << "needs " << model;
    std::ofstream(dir_ / "f.txt") << "screenshot " << (dir_ / "on.png").string() << "\n"
                                     "set disable clearcoat\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "off.png").string() << "\n"
                                     "set disable glow\n"  // not a feature: refused as the script is read
                                     "quit\n";
    // A bad feature name is refused when the script is read, naming the line.
    Result bad = run({"view", model.string(), "--size", "200x150", "--script", (dir_ / "f.txt").string()}, true);
    EXPECT_EQ(bad.exit_code, 1) << bad.err;
    EXPECT_NE(bad.err.find("line 5"), std::string::npos) << bad.err;
    std::ofstream(dir_ / "f.txt") << "screenshot " << (dir_ / "on.png").string() << "\n"
                                     "set disable clearcoat\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "off.png").string() << "\n"
                                     "quit\n";
    Result v = run({"view", model.string(), "--size", "200x150", "--script", (dir_ / "f.txt").string()}, true);
    ASSERT_EQ(v.exit_code, 0) << v.err;
    ASSERT_EQ(run({"render", model.string(), "--size", "200x150", "-o", (dir_ / "r-on.png").string()}, false).exit_code, 0);
    ASSERT_EQ(run({"render", model.string(), "--size", "200x150", "--disable", "clearcoat", "-o", (dir_ / "r-off.png").string()},
                  false).exit_code, 0);
    std::printf("clear coat off: view vs render %.1f dB, on vs off %.1f dB\n", psnr("off.png", "r-off.png"), psnr("on.png", "off.png"));
    EXPECT_GE(psnr("on.png", "r-on.png"), 40.0);
    EXPECT_GE(psnr("off.png", "r-off.png"), 40.0);
    EXPECT_LT(psnr("on.png", "off.png"), 42.0);  // the coats go (38 dB at this size: the spheres are small)
}

// The variants picker's way (the job's variant changed, the scene loaded again): a script's
// `set variant blue` shows what `render --variant blue` renders, and another picture than the
// default materials; a variant the file lacks is reported and the scene stays.
TEST_F(View, VariantsSwitchAsRenderShowsThem) {
    nlohmann::json doc = fresnel::test::uv_sphere_gltf(32, 16, {{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.1, 0.1, 1}}}}});
    doc["materials"].push_back({{"name", "blue"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.2, 0.9, 1}}}}});
    doc["extensionsUsed"] = {"KHR_materials_variants"};
    doc["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "red"}}, {{"name", "blue"}}};
    doc["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
        {{"material", 1}, {"variants", {1}}}};
    const fs::path model = dir_ / "variants.gltf";
    std::ofstream(model) << doc.dump();
    std::ofstream(dir_ / "v.txt") << "screenshot " << (dir_ / "default.png").string() << "\n"
                                     "set variant blue\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "blue.png").string() << "\n"
                                     "set variant green\n"
                                     "wait 1\n"
                                     "screenshot " << (dir_ / "still.png").string() << "\n"
                                     "print\n"
                                     "quit\n";
    Result v = run({"view", model.string(), "--size", "160x120", "--script", (dir_ / "v.txt").string()}, true);
    EXPECT_EQ(v.exit_code, 1) << v.err;  // the variant that did not load
    EXPECT_NE(v.err.find("green"), std::string::npos) << v.err;  // the loader's message names it
    ASSERT_EQ(run({"render", model.string(), "--size", "160x120", "--variant", "blue", "-o", (dir_ / "r-blue.png").string()}, false)
                  .exit_code,
              0);
    std::printf("variant blue: view vs render %.1f dB, against the default %.1f dB\n", psnr("blue.png", "r-blue.png"),
                psnr("blue.png", "default.png"));
    EXPECT_GE(psnr("blue.png", "r-blue.png"), 40.0);
    EXPECT_LT(psnr("blue.png", "default.png"), 25.0);
    EXPECT_GE(psnr("still.png", "blue.png"), 60.0) << "a variant the file lacks leaves the scene as it was";
    EXPECT_NE(last_command_line(v.out).find("--variant blue"), std::string::npos) << v.out;
}

// A soak: 100 models opened in a row in one session; resident memory after the 100th is
// within 10 % (+ 8 MiB) of what it was after the 20th, and every open worked.
TEST_F(View, HundredOpensKeepResidentMemoryFlat) {
    std::vector<std::string> models;
    for (const char* m : {"BoxTextured/BoxTextured.glb", "BoxInterleaved/BoxInterleaved.glb",
                          "BoxVertexColors/BoxVertexColors.glb", "AnimatedMorphCube/AnimatedMorphCube.glb",
                          "Duck/Duck.glb"})
        if (fs::exists(kShared / "assets/models" / m)) models.push_back((kShared / "assets/models" / m).string());
    if (models.size() < 2) GTEST_SKIP() << "needs the shared models";
    {
        // The first screenshot waits for the lighting (a cold cache bakes it), so that both
        // counts are taken with every target made and a frame drawn after the open.
        std::ofstream script(dir_ / "soak.txt");
        for (int i = 0; i < 100; ++i) {
            script << "open " << models[std::size_t(i) % models.size()] << "\n";
            if (i == 0) script << "screenshot " << (dir_ / "first.png").string() << "\n";
            if (i == 19) script << "wait 2\nstats\n";
        }
        script << "wait 2\nstats\nquit\n";
    }
    fs::path out = dir_ / "stats.txt";
    std::string cmd = display_prefix_ + "sh -c " +
                      quote(quote(FRESNEL_EXE) + " view --size 160x120 --msaa 1 --script " +
                            quote((dir_ / "soak.txt").string()) + " >" + quote(out.string()) + " 2>" +
                            quote((dir_ / "err.txt").string()));
    std::system(cmd.c_str());  // checked through what it wrote
    std::string err = slurp(dir_ / "err.txt"), stats = slurp(out);
    EXPECT_EQ(err.find("error"), std::string::npos) << err;
    std::vector<long> rss;
    for (std::size_t at = stats.find("\"rss_kb\":"); at != std::string::npos; at = stats.find("\"rss_kb\":", at + 1))
        rss.push_back(std::atol(stats.c_str() + at + 9));
    ASSERT_EQ(rss.size(), 2u) << stats << err;
    std::printf("resident memory after 20 opens %ld kB, after 100 %ld kB\n", rss[0], rss[1]);
    EXPECT_GT(rss[0], 0);
    EXPECT_LE(double(rss[1]), double(rss[0]) * 1.10 + 8192.0);
    // The GL objects alive (the driver's count) after the 20th and the 100th open: the same
    // models were open both times, so any difference is a leak. Programs may still be added
    // (a variant first needed later), nothing else.
    auto field = [&](const std::string& key) {
        std::vector<long> v;
        std::string pat = "\"" + key + "\":";
        for (std::size_t at = stats.find("\"gl_objects\""); at != std::string::npos;
             at = stats.find("\"gl_objects\"", at + 1)) {
            std::size_t k = stats.find(pat, at);
            if (k != std::string::npos) v.push_back(std::atol(stats.c_str() + k + pat.size()));
        }
        return v;
    };
    for (const char* key : {"buffers", "vertex_arrays", "textures", "renderbuffers", "framebuffers"}) {
        std::vector<long> n = field(key);
        ASSERT_EQ(n.size(), 2u) << key << ": " << stats;
        std::printf("live GL %s after 20 opens %ld, after 100 %ld\n", key, n[0], n[1]);
        EXPECT_GT(n[0], 0) << key;
        EXPECT_EQ(n[1], n[0]) << key;
    }
    std::vector<long> tex;
    for (std::size_t at = stats.find("\"texture_bytes\":"); at != std::string::npos;
         at = stats.find("\"texture_bytes\":", at + 1))
        tex.push_back(std::atol(stats.c_str() + at + 16));
    ASSERT_EQ(tex.size(), 2u) << stats;
    std::printf("texture memory after 20 opens %ld bytes, after 100 %ld\n", tex[0], tex[1]);
    EXPECT_GT(tex[0], 0);
    EXPECT_EQ(tex[1], tex[0]);
    std::vector<long> programs = field("programs");
    ASSERT_EQ(programs.size(), 2u);
    EXPECT_LE(programs[1], programs[0] + 8);
}

// `set material`: a red base colour factor reddens the helmet (and nothing else: the
// background stays), setting it back gives `fresnel render`'s picture again.
TEST_F(View, MaterialEditIsLiveAndRevertsExactly) {
    fs::path model = kShared / "assets/models/DamagedHelmet/DamagedHelmet.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "needs " << model;
    std::ofstream(dir_ / "m.txt") << "set material 0 baseColorFactor 1 0.1 0.1 1\n"
                                     "screenshot " << (dir_ / "red.png").string() << "\n"
                                     "set material 0 baseColorFactor 1 1 1 1\n"
                                     "screenshot " << (dir_ / "back.png").string() << "\n"
                                     "set material 3 roughnessFactor 0.5\n"
                                     "quit\n";
    Result r = run({"view", model.string(), "--size", "200x150", "--script", (dir_ / "m.txt").string()}, true);
    EXPECT_EQ(r.exit_code, 1) << r.err;  // material 3 does not exist
    EXPECT_NE(r.err.find("m.txt: line 5: set material: no material 3 (the scene has 1)"), std::string::npos) << r.err;
    Result rr = run({"render", model.string(), "--size", "200x150", "-o", (dir_ / "render.png").string()}, false);
    ASSERT_EQ(rr.exit_code, 0) << rr.err;
    fresnel::Image8 red = fresnel::read_image8(dir_ / "red.png"), back = fresnel::read_image8(dir_ / "back.png"),
                    ref = fresnel::read_image8(dir_ / "render.png");
    EXPECT_GE(fresnel::compare_images(back, ref, false).psnr_db, 40.0);
    // Red minus green over the image: the edit raises it; the corner (background) keeps its colour.
    auto redness = [](const fresnel::Image8& im) {
        double sum = 0;
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x) sum += double(im.at(x, y)[0]) - double(im.at(x, y)[1]);
        return sum / double(im.width * im.height);
    };
    EXPECT_GT(redness(red), redness(ref) + 5.0);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(red.at(2, 2)[c], ref.at(2, 2)[c]) << c;
}

// The scene tree, picking and the lights panel's script twins: a click on the helmet selects
// its one primitive (and a click on the background nothing); an added light changes the frame
// as `render --light` would and removing it gives the first frame back; hiding node 0 (the
// helmet) leaves the background, showing it restores the frame.
TEST_F(View, PickingLightsAndNodeVisibility) {
    fs::path model = kShared / "assets/models/DamagedHelmet/DamagedHelmet.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "needs " << model;
    const std::string light = "spot:0,0,3,0,0,40,10,25,1,0.6,0.3";
    auto shot = [&](const char* name) { return "screenshot " + (dir_ / name).string() + "\n"; };
    std::ofstream(dir_ / "p.txt") << shot("first.png") << "pick 100 75\npick 3 3\n"
                                  << "light " << light << "\n" << shot("lit.png") << "light-remove 0\n"
                                  << shot("unlit.png") << "hide 0\n" << shot("hidden.png") << "show 0\n"
                                  << shot("shown.png") << "quit\n";
    Result r = run({"view", model.string(), "--size", "200x150", "--script", (dir_ / "p.txt").string()}, true);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("{\"node\":0,\"mesh\":0,\"primitive\":0,\"material\":0,"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("{\"node\":null}"), std::string::npos) << r.out;
    Result rr = run({"render", model.string(), "--size", "200x150", "--light", light, "-o", (dir_ / "render_lit.png").string()},
                    false);
    ASSERT_EQ(rr.exit_code, 0) << rr.err;
    auto img = [&](const char* name) { return fresnel::read_image8(dir_ / name); };
    const fresnel::Image8 first = img("first.png"), lit = img("lit.png");
    EXPECT_GE(fresnel::compare_images(lit, img("render_lit.png"), false).psnr_db, 40.0);
    EXPECT_LT(fresnel::compare_images(lit, first, false).psnr_db, 30.0);  // the light changed the frame
    EXPECT_GE(fresnel::compare_images(img("unlit.png"), first, false).psnr_db, 60.0);
    EXPECT_GE(fresnel::compare_images(img("shown.png"), first, false).psnr_db, 60.0);
    // Hidden: the centre shows the grey studio background instead of the helmet.
    const fresnel::Image8 hidden = img("hidden.png");
    const std::uint8_t* h = hidden.at(100, 75);
    EXPECT_LE(std::abs(int(h[0]) - int(h[1])) + std::abs(int(h[1]) - int(h[2])), 8) << int(h[0]) << " " << int(h[1]) << " " << int(h[2]);
    int moved = 0;
    for (int c = 0; c < 3; ++c) moved = std::max(moved, std::abs(int(h[c]) - int(first.at(100, 75)[c])));
    EXPECT_GT(moved, 20);
    EXPECT_LT(fresnel::compare_images(hidden, first, false).psnr_db, 25.0);
}

// "Save scene": a scripted session moves the camera, the environment and the tone mapping,
// edits two materials and saves the view as a scene file; `fresnel render SCENE` renders the
// frame the window showed (>= 40 dB), and `fresnel view SCENE` opens on it again.
TEST_F(View, SavedSceneRendersWhatTheWindowShowed) {
    fs::path scene = dir_ / "shots" / "shot.fresnel.json", scene2 = dir_ / "shots" / "normals.fresnel.json";
    fs::create_directories(dir_ / "shots");
    std::ofstream(dir_ / "s.txt") << "orbit 40 -15\npan 10 5\ndolly 0.8\nenv-rotation 70\nexposure 0.5\ntonemap aces\n"
                                     "set material 3 baseColorFactor 1 0.2 0.1 1\n"
                                     "set material 5 roughnessFactor 0.05\n"
                                     "screenshot " << (dir_ / "window.png").string() << "\n"
                                     "save-scene " << scene.string() << "\n"
                                     "debug normal\n"
                                     "screenshot " << (dir_ / "window2.png").string() << "\n"
                                     "save-scene " << scene2.string() << "\n"
                                     "quit\n";
    Result v = run({"view", "--size", "200x150", "--light", "dir:30,45,2", "--script", (dir_ / "s.txt").string()}, true);
    ASSERT_EQ(v.exit_code, 0) << v.err;
    const std::string text = slurp(scene);
    EXPECT_NE(text.find("\"materials\""), std::string::npos) << text;  // the edits, as overrides
    EXPECT_NE(text.find("\"directional\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"aces\""), std::string::npos) << text;
    EXPECT_NE(slurp(scene2).find("\"normal\""), std::string::npos);
    // `render SCENE` writes the file's "output", shot.png beside it.
    Result r = run({"render", scene.string()}, false);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    Result r2 = run({"render", scene2.string(), "-o", (dir_ / "render2.png").string()}, false);
    ASSERT_EQ(r2.exit_code, 0) << r2.err;
    auto psnr = [&](const fs::path& x, const fs::path& y) {
        fresnel::Image8 a = fresnel::read_image8(x), b = fresnel::read_image8(y);
        EXPECT_EQ(a.width, b.width);
        EXPECT_EQ(a.height, b.height);
        if (a.width != b.width || a.height != b.height) return 0.0;
        return fresnel::compare_images(a, b, false).psnr_db;
    };
    const double shaded = psnr(dir_ / "shots" / "shot.png", dir_ / "window.png");
    const double normals = psnr(dir_ / "render2.png", dir_ / "window2.png");
    std::printf("saved scene rendered vs the window: %.1f dB shaded, %.1f dB normals\n", shaded, normals);
    EXPECT_GE(shaded, 40.0);
    EXPECT_GE(normals, 40.0);
    // The same scene without the material overrides is another picture: the edits were saved.
    nlohmann::json doc = nlohmann::json::parse(text);
    ASSERT_TRUE(doc.contains("models")) << text;
    doc.erase("models");
    doc["model"] = "demo";
    std::ofstream(dir_ / "shots" / "plain.fresnel.json") << doc.dump();
    ASSERT_EQ(run({"render", (dir_ / "shots" / "plain.fresnel.json").string(), "-o", (dir_ / "plain.png").string()},
                  false).exit_code, 0);
    EXPECT_LT(psnr(dir_ / "plain.png", dir_ / "window.png"), 38.0);
    // The viewer opens the scene file on the same frame.
    Result o = run({"view", scene.string(), "--screenshot", (dir_ / "reopened.png").string()}, true);
    ASSERT_EQ(o.exit_code, 0) << o.err;
    EXPECT_GE(psnr(dir_ / "reopened.png", dir_ / "window.png"), 40.0);
}

// "Save" of material edits: the edited factor is written into a copy of the glTF file and
// nothing else changes: unknown extensions, extras, other materials, key order, accessors, and
// the .bin file byte for byte. A save into a folder that does not exist fails, naming the line.
TEST_F(View, MaterialSaveChangesTheFactorAndNothingElse) {
    const float pos[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const std::uint16_t idx[] = {0, 1, 2, 0, 2, 3};
    {
        std::ofstream bin(dir_ / "quad.bin", std::ios::binary);
        bin.write(reinterpret_cast<const char*>(pos), sizeof pos);
        bin.write(reinterpret_cast<const char*>(idx), sizeof idx);
    }
    const std::string gltf = R"({
  "asset": {"version": "2.0", "extras": {"author": "someone"}},
  "extensionsUsed": ["VENDOR_thing"],
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "extras": {"tag": [1, 2, 3]}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "materials": [
    {"name": "edited", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "roughnessFactor": 0.8},
     "extensions": {"VENDOR_thing": {"x": 1}}},
    {"name": "other", "extras": {"keep": "me"}, "pbrMetallicRoughness": {"metallicFactor": 0.25}}
  ],
  "buffers": [{"uri": "quad.bin", "byteLength": 60}],
  "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ]
})";
    std::ofstream(dir_ / "quad.gltf") << gltf;
    fs::create_directories(dir_ / "saved");
    std::ofstream(dir_ / "e.txt") << "set material 0 roughnessFactor 0.2\n"
                                     "save " << (dir_ / "saved" / "quad.gltf").string() << "\n"
                                     "save " << (dir_ / "no" / "such" / "folder.gltf").string() << "\n"
                                     "quit\n";
    Result v = run({"view", (dir_ / "quad.gltf").string(), "--size", "64x64", "--script", (dir_ / "e.txt").string()}, true);
    EXPECT_EQ(v.exit_code, 1) << v.err;  // the second save
    EXPECT_NE(v.err.find("e.txt: line 3: save"), std::string::npos) << v.err;
    using ojson = nlohmann::ordered_json;
    ojson before = ojson::parse(gltf), after = ojson::parse(slurp(dir_ / "saved" / "quad.gltf"));
    EXPECT_EQ(after["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"], 0.2);
    before["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"] = 0.2;
    EXPECT_EQ(after, before);  // everything else as it was, keys in their order
    EXPECT_EQ(slurp(dir_ / "saved" / "quad.bin"), slurp(dir_ / "quad.bin"));
    EXPECT_FALSE(fs::exists(dir_ / "no"));
    // The saved file renders.
    EXPECT_EQ(run({"render", (dir_ / "saved" / "quad.gltf").string(), "--size", "32x32", "-o",
                   (dir_ / "q.png").string()}, false).exit_code, 0);
}

// The statistics' GPU time comes from a timer query on OpenGL 3.3, and is null (not made up)
// on OpenGL ES 3.0, which has none.
TEST_F(View, GpuTimeOnlyWhereTimerQueriesExist) {
    std::ofstream(dir_ / "t.txt") << "screenshot " << (dir_ / "t.png").string() << "\nstats\nquit\n";  // after a frame
    for (const char* api : {"gl33", "es3"}) {
        fs::path out = dir_ / (std::string(api) + ".txt");
        std::string cmd = display_prefix_ + "sh -c " +
                          quote(quote(FRESNEL_EXE) + " view --size 96x64 --gl " + api + " --script " +
                                quote((dir_ / "t.txt").string()) + " >" + quote(out.string()) + " 2>/dev/null");
        std::system(cmd.c_str());  // checked through what it wrote
        nlohmann::json stats = nlohmann::json::parse(slurp(out), nullptr, false);
        ASSERT_TRUE(stats.is_object() && stats.contains("gpu_ms")) << api << ": " << slurp(out);
        if (std::string(api) == "gl33") {
            ASSERT_TRUE(stats["gpu_ms"].is_number()) << stats.dump();
            EXPECT_GT(stats["gpu_ms"].get<double>(), 0.0);
            std::printf("GPU time of a 96x64 demo frame (llvmpipe): %.2f ms, CPU %.2f ms\n",
                        stats["gpu_ms"].get<double>(), stats["frame_ms"].get<double>());
        } else {
            EXPECT_TRUE(stats["gpu_ms"].is_null()) << stats.dump();
        }
    }
}

// Shader reload (F5, the script's reload-shaders): a folder whose post pass fails to compile
// is reported and the frame stays as it was; a folder whose post pass inverts the colours
// shows the inverted frame.
TEST_F(View, ShaderReloadKeepsTheShadersOnErrorsAndShowsTheNewOnes) {
    const fs::path src = fs::path(FRESNEL_SOURCE_DIR) / "shaders";
    for (const char* d : {"bad", "inverted"}) fs::copy(src, dir_ / d, fs::copy_options::recursive);
    std::ofstream(dir_ / "bad" / "post.frag", std::ios::app) << "\nthis is not GLSL\n";
    std::string post = slurp(src / "post.frag");
    const std::string from = "frag_color = c;";
    ASSERT_NE(post.find(from), std::string::npos) << "post.frag changed: update this test";
    post.replace(post.find(from), from.size(), "frag_color = vec4(1.0 - c.rgb, c.a);");
    std::ofstream(dir_ / "inverted" / "post.frag") << post;
    std::ofstream(dir_ / "r.txt") << "screenshot " << (dir_ / "a.png").string() << "\n"
                                  << "reload-shaders " << (dir_ / "bad").string() << "\n"
                                  << "screenshot " << (dir_ / "b.png").string() << "\n"
                                  << "reload-shaders " << (dir_ / "inverted").string() << "\n"
                                  << "screenshot " << (dir_ / "c.png").string() << "\nquit\n";
    Result r = run({"view", "--size", "96x64", "--msaa", "1", "--script", (dir_ / "r.txt").string()}, true);
    EXPECT_EQ(r.exit_code, 1) << r.err;  // the bad folder
    EXPECT_NE(r.err.find("r.txt: line 2: reload-shaders"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("post.frag"), std::string::npos) << r.err;  // the compiler's log names the file
    for (const char* f : {"a.png", "b.png", "c.png"}) ASSERT_TRUE(fs::exists(dir_ / f)) << f << "\n" << r.err;
    fresnel::Image8 a = fresnel::read_image8(dir_ / "a.png"), b = fresnel::read_image8(dir_ / "b.png"),
                    c = fresnel::read_image8(dir_ / "c.png");
    EXPECT_GE(fresnel::compare_images(a, b, false).psnr_db, 50.0);
    ASSERT_EQ(a.pixels.size(), c.pixels.size());
    int worst = 0;
    std::size_t at = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (a.channels == 4 && i % 4 == 3) continue;  // alpha is 255 in both
        int d = std::abs(255 - int(a.pixels[i]) - int(c.pixels[i]));
        if (d > worst) worst = d, at = i;
    }
    EXPECT_LE(worst, 2) << "byte " << at << ": " << int(a.pixels[at]) << " and " << int(c.pixels[at]);  // 8-bit rounding
}

// The split view: left of the divider `render`'s shaded frame, right of it its roughness channel.
TEST_F(View, SplitViewShowsBothSettings) {
    std::ofstream(dir_ / "s.txt") << "split roughness 0.5\nscreenshot " << (dir_ / "split.png").string() << "\nquit\n";
    Result r = run({"view", "--size", "200x150", "--script", (dir_ / "s.txt").string()}, true);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(run({"render", "--size", "200x150", "-o", (dir_ / "a.png").string()}, false).exit_code, 0);
    ASSERT_EQ(run({"render", "--size", "200x150", "--debug", "roughness", "-o", (dir_ / "b.png").string()}, false)
                  .exit_code, 0);
    fresnel::Image8 split = fresnel::read_image8(dir_ / "split.png"), a = fresnel::read_image8(dir_ / "a.png"),
                    b = fresnel::read_image8(dir_ / "b.png");
    auto crop = [](const fresnel::Image8& im, int x0, int x1) {
        fresnel::Image8 out(x1 - x0, im.height, 3);
        for (int y = 0; y < im.height; ++y)
            for (int x = x0; x < x1; ++x)
                for (int c = 0; c < 3; ++c) out.at(x - x0, y)[c] = im.at(x, y)[c];
        return out;
    };
    EXPECT_GE(fresnel::compare_images(crop(split, 0, 100), crop(a, 0, 100), false).psnr_db, 40.0);
    EXPECT_GE(fresnel::compare_images(crop(split, 100, 200), crop(b, 100, 200), false).psnr_db, 40.0);
    EXPECT_LT(fresnel::compare_images(crop(a, 100, 200), crop(b, 100, 200), false).psnr_db, 30.0);
}

TEST_F(View, MalformedScriptNamesTheLineBeforeOpeningAWindow) {
    std::ofstream(dir_ / "bad.txt") << "orbit 10 0\n\nzoom 2\n";
    Result r = run({"view", "--script", (dir_ / "bad.txt").string()}, false);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("bad.txt: line 3: unknown command 'zoom'"), std::string::npos) << r.err;
    std::ofstream(dir_ / "bad2.txt") << "dolly -1\n";
    r = run({"view", "--script", (dir_ / "bad2.txt").string()}, false);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("bad2.txt: line 1: dolly"), std::string::npos) << r.err;
}

TEST_F(View, BadModelExitsOneWithTheLoadersError) {
    fs::path bad = dir_ / "broken.gltf";
    std::ofstream(bad) << "{ \"asset\": { \"version\": \"2.0\" }, \"buffers\": [ { \"byteLength\": -4 } ] ";
    Result r = run({"view", bad.string(), "--size", "64x48", "--screenshot", (dir_ / "x.png").string()}, true);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("fresnel: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("broken.gltf"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

TEST_F(View, BadEnvironmentExitsOne) {
    fs::path bad = dir_ / "sky.hdr";
    std::ofstream(bad) << "not a radiance file";
    Result r = run({"view", "--env", bad.string(), "--size", "64x48", "--exit-after", "1"}, true);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("sky.hdr"), std::string::npos) << r.err;
}

TEST_F(View, FolderOpensItsFirstModel) {
    fs::path folder = kShared / "assets/models";
    if (!fs::exists(folder)) GTEST_SKIP() << "needs " << folder;
    Result r = run({"view", folder.string(), "--size", "64x48", "--exit-after", "1", "--no-ibl"}, true);
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(View, UsageErrorsExitTwoBeforeOpeningAWindow) {
    Result r = run({"view", "--size", "12x", "--exit-after", "1"}, false);  // no display needed
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
}

}  // namespace
