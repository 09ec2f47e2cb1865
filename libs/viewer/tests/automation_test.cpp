// Scripts (`fresnel view --script`) run by the automation engine against the viewer's state and
// a recording host in place of the window: which commands change the state, which go to the
// host, when the engine waits for a drawn frame, and how failures are reported.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "fresnel/core/error.h"
#include "fresnel/viewer/automation.h"
#include "fresnel/viewer/script.h"
#include "viewer_test_scenes.h"

namespace fresnel::viewer {
namespace {

// Records what the engine asks of the window; `open`, `save...` and `screenshot` fail on request.
class RecordingHost : public AutomationHost {
public:
    std::vector<std::string> calls, printed, errors;
    bool open_works = true, screenshot_works = true;
    State* state = nullptr;  // where a failed open leaves its error

    void screenshot(const std::string& path) override {
        calls.push_back("screenshot " + path);
        if (!screenshot_works) throw std::runtime_error(path + ": cannot write");
    }
    bool open(const std::string& path) override {
        calls.push_back("open " + path);
        if (!open_works && state) state->error = "not a model";
        return open_works;
    }
    bool save_model(const std::string& path) override { return calls.push_back("save " + path), true; }
    bool save_scene(const std::string& path) override { return calls.push_back("save-scene " + path), true; }
    bool reload_shaders(const std::string& folder) override { return calls.push_back("reload-shaders " + folder), true; }
    void set_material_field(Material& m, const std::string& field, const std::vector<float>& values) override {
        calls.push_back("set-material " + m.name + " " + field + " " + std::to_string(values.size()));
        if (field == "roughnessFactor" && values.size() == 1) m.roughness_factor = values[0];
    }
    void node_visibility_changed() override { calls.push_back("visibility"); }
    std::string stats() override { return "{\"frame_ms\":1}"; }
    std::string render_command_line(const Job& job) override {
        return "fresnel render --size " + std::to_string(job.output.width) + "x" + std::to_string(job.output.height);
    }
    void print(const std::string& line) override { printed.push_back(line); }
    void report_error(const std::string& message) override { errors.push_back(message); }
};

Command cmd(int line, std::string name, std::vector<std::string> args = {}) {
    Command c;
    c.line = line;
    c.name = std::move(name);
    c.args = std::move(args);
    return c;
}

// The state of a drawn frame of the box-before-sphere scene in a 200 x 100 window.
State drawn_scene() {
    State s;
    s.scene = std::make_unique<Scene>(test::box_before_sphere());
    s.resolved.instances = flatten(*s.scene);
    s.bounds = scene_bounds(*s.scene, s.resolved.instances);
    s.last_camera = test::camera_from_z(s.bounds);
    s.window = {200, 100};
    s.framebuffer = {200, 100};
    return s;
}

TEST(Command, NumbersOfItsArguments) {
    Command c = cmd(1, "orbit", {"12.5", "-3", "x"});
    EXPECT_FLOAT_EQ(c.number(0), 12.5f);
    EXPECT_FLOAT_EQ(c.number(1), -3.0f);
    EXPECT_FLOAT_EQ(c.number(2), 0.0f);
}

TEST(Automation, OneChangeAFrameThenQuit) {
    State s;
    s.job.camera.yaw_deg = 0.0f;
    s.job.camera.pitch_deg = 0.0f;
    RecordingHost host;
    Automation a({cmd(1, "orbit", {"10", "5"}), cmd(2, "set", {"render.exposure", "1.5"}), cmd(3, "quit")}, "s.txt");
    EXPECT_TRUE(a.pending());
    EXPECT_FALSE(a.step(s, host, false));  // the orbit; the next frame shows it
    EXPECT_FLOAT_EQ(s.job.camera.yaw_deg, 10.0f);
    EXPECT_FLOAT_EQ(s.job.camera.pitch_deg, 5.0f);
    EXPECT_FLOAT_EQ(s.job.output.exposure_ev, 0.0f);
    EXPECT_FALSE(a.step(s, host, false));
    EXPECT_FLOAT_EQ(s.job.output.exposure_ev, 1.5f);
    EXPECT_TRUE(a.step(s, host, false));  // quit
    EXPECT_FALSE(a.pending());
    EXPECT_FALSE(a.failed());
    EXPECT_TRUE(host.errors.empty());
}

TEST(Automation, CameraCommands) {
    State s;
    s.framebuffer = {100, 100};
    s.initial_camera.yaw_deg = 33.0f;
    RecordingHost host;
    Automation a({cmd(1, "dolly", {"0.5"}), cmd(2, "reset"), cmd(3, "camera", {"2"}), cmd(4, "frame")}, "s.txt");
    const float k = distance_k(s.job.camera, 100, 100);
    a.step(s, host, false);
    ASSERT_TRUE(s.job.camera.distance_k);
    EXPECT_NEAR(*s.job.camera.distance_k, 0.5f * k, 1e-4f);
    a.step(s, host, false);
    EXPECT_FLOAT_EQ(s.job.camera.yaw_deg, 33.0f);
    a.step(s, host, false);
    EXPECT_EQ(s.job.camera.scene_camera, 2);
    s.job.camera.target = glm::vec3(1.0f);
    a.step(s, host, false);
    EXPECT_FALSE(s.job.camera.target);  // frame: the bounds' centre again
}

TEST(Automation, WaitLetsFramesPass) {
    State s;
    RecordingHost host;
    Automation a({cmd(1, "wait", {"2"}), cmd(2, "print")}, "s.txt");
    a.step(s, host, false);  // wait 2
    a.step(s, host, false);
    a.step(s, host, false);
    EXPECT_TRUE(host.printed.empty());
    a.step(s, host, false);
    EXPECT_EQ(host.printed.size(), 1u);
}

TEST(Automation, PrintAndStatsRunInTheSameFrame) {
    State s;
    s.framebuffer = {640, 480};
    RecordingHost host;
    Automation a({cmd(1, "print"), cmd(2, "stats"), cmd(3, "quit")}, "s.txt");
    EXPECT_TRUE(a.step(s, host, false));  // neither changes the frame: on to quit
    ASSERT_EQ(host.printed.size(), 2u);
    EXPECT_EQ(host.printed[0], "fresnel render --size 640x480");  // the shown job
    EXPECT_EQ(host.printed[1], "{\"frame_ms\":1}");
}

TEST(Automation, ScreenshotAndPickWaitForADrawnFrame) {
    State s = drawn_scene();
    RecordingHost host;
    Automation a({cmd(1, "screenshot", {"a.png"}), cmd(2, "pick", {"100", "50"}), cmd(3, "pick", {"1", "1"})}, "s.txt");
    EXPECT_FALSE(a.step(s, host, /*ready=*/false));
    EXPECT_TRUE(host.calls.empty());
    EXPECT_FALSE(a.step(s, host, true));  // the screenshot, then the pick
    ASSERT_EQ(host.calls.size(), 1u);
    EXPECT_EQ(host.calls[0], "screenshot a.png");
    ASSERT_EQ(host.printed.size(), 1u);
    EXPECT_EQ(host.printed[0].rfind("{\"node\":0,\"mesh\":0,\"primitive\":0,\"material\":0,\"distance\":", 0), 0u) << host.printed[0];
    ASSERT_TRUE(s.picked);
    EXPECT_FALSE(a.step(s, host, false));  // the second pick waits again
    EXPECT_EQ(host.printed.size(), 1u);
    EXPECT_TRUE(a.pending());
    EXPECT_FALSE(a.step(s, host, true));
    EXPECT_EQ(host.printed.back(), "{\"node\":null}");
    EXPECT_FALSE(s.picked);
    EXPECT_FALSE(a.pending());
}

TEST(Automation, FailuresAreReportedWithTheLineAndTheScriptGoesOn) {
    State s;
    RecordingHost host;
    host.state = &s;
    host.open_works = false;
    host.screenshot_works = false;
    s.scene = std::make_unique<Scene>(test::box_before_sphere());
    Automation a({cmd(4, "open", {"x.glb"}), cmd(5, "screenshot", {"/no/such/a.png"}), cmd(6, "light-remove", {"0"}),
                  cmd(7, "set", {"material", "9", "roughnessFactor", "0.5"}), cmd(8, "select", {"5"}), cmd(9, "quit")},
                 "script.txt");
    while (!a.step(s, host, true)) {
    }
    EXPECT_TRUE(a.failed());
    const std::vector<std::string> want = {
        "script.txt: line 4: open x.glb: not a model",
        "script.txt: line 5: /no/such/a.png: cannot write",
        "script.txt: line 6: light-remove: no added light 0",
        "script.txt: line 7: set material: no material 9 (the scene has 2)",
        "script.txt: line 8: select: node 5 has no mesh",
    };
    EXPECT_EQ(host.errors, want);
}

TEST(Automation, MaterialEditsGoThroughTheHostAndAreMarked) {
    State s = drawn_scene();
    RecordingHost host;
    Automation a({cmd(1, "set", {"material", "1", "roughnessFactor", "0.25"})}, "s.txt");
    a.step(s, host, false);
    ASSERT_EQ(host.calls.size(), 1u);
    EXPECT_EQ(host.calls[0], "set-material ball roughnessFactor 1");
    EXPECT_FLOAT_EQ(s.scene->materials[1].roughness_factor, 0.25f);
    EXPECT_TRUE(s.materials_edited);
}

TEST(Automation, LightsSelectionAndVisibility) {
    State s = drawn_scene();
    RecordingHost host;
    Automation a({cmd(1, "light", {"point:0,2,0,10"}), cmd(2, "orbit-lights", {"on"}), cmd(3, "select", {"1"}),
                  cmd(4, "hide", {"1"}), cmd(5, "show", {"1"}), cmd(6, "light-remove", {"0"})},
                 "s.txt");
    a.step(s, host, false);
    ASSERT_EQ(s.job.lights.extra.size(), 1u);
    EXPECT_EQ(s.job.lights.extra[0].type, Light::Type::Point);
    a.step(s, host, false);
    EXPECT_TRUE(s.orbit_lights);
    a.step(s, host, false);
    ASSERT_TRUE(s.picked);
    EXPECT_EQ(s.picked->node, 1);
    a.step(s, host, false);
    EXPECT_FALSE(s.scene->nodes[1].visible);
    EXPECT_FALSE(s.picked);
    a.step(s, host, false);
    EXPECT_TRUE(s.scene->nodes[1].visible);
    EXPECT_EQ(host.calls, (std::vector<std::string>{"visibility", "visibility"}));
    a.step(s, host, false);
    EXPECT_TRUE(s.job.lights.extra.empty());
    EXPECT_TRUE(host.errors.empty());
}

TEST(Automation, SplitViewAndAutoRotate) {
    State s;
    s.job.output.exposure_ev = 2.0f;
    RecordingHost host;
    Automation a({cmd(1, "split", {"normal", "0.25"}), cmd(2, "auto-rotate", {"env", "on"}), cmd(3, "auto-rotate", {"camera", "on"}),
                  cmd(4, "split", {"off"})},
                 "s.txt");
    a.step(s, host, false);
    EXPECT_TRUE(s.split);
    EXPECT_EQ(s.split_output.debug, DebugChannel::Normal);
    EXPECT_FLOAT_EQ(s.split_output.exposure_ev, 2.0f);  // the rest as the left side's
    EXPECT_FLOAT_EQ(s.split_pos, 0.25f);
    a.step(s, host, false);
    EXPECT_TRUE(s.spin_environment);
    EXPECT_FALSE(s.spin_camera);
    a.step(s, host, false);
    EXPECT_TRUE(s.spin_camera);
    a.step(s, host, false);
    EXPECT_FALSE(s.split);
}

TEST(Automation, EnvironmentsByNameOrFile) {
    State s;
    s.job.environment.use_cache = false;  // the recent list stays in memory
    RecordingHost host;
    Automation a({cmd(3, "env", {"studio"}), cmd(4, "set", {"environment", "sky.hdr"}), cmd(5, "env", {"color:0.5,0.25,1"})},
                 "s.txt");
    a.step(s, host, false);
    EXPECT_EQ(s.job.environment.kind, Job::Environment::Kind::Studio);
    EXPECT_EQ(a.env_line(), 3);
    a.step(s, host, false);
    EXPECT_EQ(s.job.environment.kind, Job::Environment::Kind::File);
    EXPECT_EQ(s.job.environment.path, "sky.hdr");
    EXPECT_EQ(a.env_line(), 4);
    ASSERT_EQ(s.recent.paths().size(), 1u);  // a file opened goes on the recent list
    a.step(s, host, false);
    EXPECT_EQ(s.job.environment.kind, Job::Environment::Kind::Color);
    EXPECT_FLOAT_EQ(s.job.environment.color.y, 0.25f);
}

TEST(Automation, FilesAndShadersGoToTheHost) {
    State s;
    RecordingHost host;
    Automation a({cmd(1, "open", {"m.glb"}), cmd(2, "save", {"e.glb"}), cmd(3, "save-scene", {"v.fresnel.json"}),
                  cmd(4, "reload-shaders")},
                 "s.txt");
    a.step(s, host, false);  // open: the next frame shows it
    a.step(s, host, false);  // save and save-scene change nothing drawn: on to reload-shaders
    const std::vector<std::string> want = {"open m.glb", "save e.glb", "save-scene v.fresnel.json", "reload-shaders "};
    EXPECT_EQ(host.calls, want);
    EXPECT_FALSE(a.pending());
}

TEST(Automation, ABakeFailureIsReportedAtTheEnvLine) {
    State s;
    RecordingHost host;
    Automation a({cmd(7, "env", {"broken.hdr"})}, "s.txt");
    a.step(s, host, false);
    EXPECT_FALSE(a.failed());
    a.fail(host, a.env_line(), "env failed");
    EXPECT_TRUE(a.failed());
    EXPECT_EQ(host.errors, (std::vector<std::string>{"s.txt: line 7: env failed"}));
}

TEST(Automation, PlaybackCommands) {
    State s;
    s.scene = std::make_unique<Scene>(test::animated_box_before_sphere());
    RecordingHost host;
    Automation a({cmd(1, "time", {"1.25"}), cmd(2, "animation", {"1"}), cmd(3, "speed", {"-2"}), cmd(4, "loop", {"off"}),
                  cmd(5, "play"), cmd(6, "pause"), cmd(7, "animation", {"5"}), cmd(8, "animation", {"all"}),
                  cmd(9, "quit")},
                 "s.txt");
    a.step(s, host, true);  // time
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 1.25f);
    a.step(s, host, true);  // animation 1, paused: the time stays within [1, 4]
    EXPECT_EQ(s.job.source.animation.index, 1);
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 1.25f);
    a.step(s, host, true);  // speed and loop change nothing drawn; play does
    EXPECT_FLOAT_EQ(s.playback.speed, -2.0f);
    EXPECT_FALSE(s.playback.loop);
    EXPECT_TRUE(s.playback.playing);
    a.step(s, host, true);  // pause
    EXPECT_FALSE(s.playback.playing);
    a.step(s, host, true);  // animation 5: the scene has 2
    EXPECT_TRUE(a.failed());
    ASSERT_EQ(host.errors.size(), 1u);
    EXPECT_EQ(host.errors[0], "s.txt: line 7: animation: no animation 5 (the scene has 2)");
    EXPECT_EQ(s.job.source.animation.index, 1);
    a.step(s, host, true);  // animation all
    EXPECT_EQ(s.job.source.animation.index, -1);
    EXPECT_TRUE(a.step(s, host, true));  // quit
}

TEST(Automation, PlayWithoutAnimationsFails) {
    State s = drawn_scene();
    RecordingHost host;
    Automation a({cmd(3, "play")}, "s.txt");
    a.step(s, host, true);
    EXPECT_FALSE(s.playback.playing);
    EXPECT_EQ(host.errors, (std::vector<std::string>{"s.txt: line 3: play: the scene has no animations"}));
}

TEST(Script, PlaybackCommandsAreChecked) {
    const std::string path = ::testing::TempDir() + "fresnel_playback_script.txt";
    auto read = [&](const std::string& text) {
        std::ofstream(path) << text;
        return read_view_script(path);
    };
    std::vector<Command> ok = read("play\npause\ntime 1.5\nanimation 2\nanimation all\nspeed -0.5\nloop off\n");
    ASSERT_EQ(ok.size(), 7u);
    EXPECT_FLOAT_EQ(ok[2].number(0), 1.5f);
    for (const char* bad : {"time x\n", "time\n", "animation -1\n", "animation 1.5\n", "loop maybe\n", "speed 1000\n", "play 2\n"}) {
        try {
            read(bad);
            ADD_FAILURE() << bad;
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), "line 1") << bad;
        }
    }
    std::remove(path.c_str());
}

}  // namespace
}  // namespace fresnel::viewer
