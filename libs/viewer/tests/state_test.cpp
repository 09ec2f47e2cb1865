// The viewer's state without a window: the shown job, the selection, visibility, added lights
// and their drags, auto-rotation, the files it starts with and the recent list it keeps.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "fresnel/viewer/geometry.h"
#include "fresnel/viewer/state.h"
#include "viewer_test_scenes.h"

namespace fresnel::viewer {
namespace {
namespace fs = std::filesystem;

// A state showing the box-before-sphere scene as the last frame drew it, in a 200 x 100 window.
State showing_scene() {
    State s;
    s.scene = std::make_unique<Scene>(test::box_before_sphere());
    s.original_materials = s.scene->materials;
    s.resolved.instances = flatten(*s.scene);
    s.bounds = s.resolved.bounds = scene_bounds(*s.scene, s.resolved.instances);
    s.last_camera = test::camera_from_z(s.bounds);
    s.window = {200, 100};
    s.framebuffer = {400, 200};  // a high-DPI screen: two pixels a point
    return s;
}

fs::path fresh_folder(const std::string& name) {
    fs::path d = fs::path(::testing::TempDir()) / ("fresnel_viewer_state_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

TEST(State, TheShownJobHasTheFramebuffersSize) {
    State s;
    s.job.output.width = 1280;
    s.framebuffer = {640, 360};
    EXPECT_EQ(s.shown_job().output.width, 640);
    EXPECT_EQ(s.shown_job().output.height, 360);
    EXPECT_EQ(s.job.output.width, 1280);  // the job itself keeps its size
    s.framebuffer = {0, 0};               // minimised
    EXPECT_EQ(s.shown_job().output.width, 1);
    EXPECT_EQ(s.viewport().height, 1);
}

TEST(State, AClickSelectsTheNearestPrimitiveAndTheEditorFollows) {
    State s = showing_scene();
    s.pick_at({100.0f, 50.0f});
    ASSERT_TRUE(s.picked);
    EXPECT_EQ(s.picked->node, 0);
    EXPECT_EQ(s.edit_material, 0);
    s.set_node_visible(0, false);  // hiding the selected node clears the selection
    EXPECT_FALSE(s.scene->nodes[0].visible);
    EXPECT_FALSE(s.picked);
    s.resolved.instances = flatten(*s.scene);
    s.pick_at({100.0f, 50.0f});
    ASSERT_TRUE(s.picked);
    EXPECT_EQ(s.picked->node, 1);
    EXPECT_EQ(s.edit_material, 1);
    s.pick_at({1.0f, 1.0f});  // a miss clears it
    EXPECT_FALSE(s.picked);
}

TEST(State, NoPickBeforeAFrameWasDrawn) {
    State s = showing_scene();
    s.last_camera.reset();
    s.pick_at({100.0f, 50.0f});
    EXPECT_FALSE(s.picked);
}

TEST(State, SelectingANodeSelectsItsPrimitive) {
    State s = showing_scene();
    EXPECT_TRUE(s.select_primitive(1, 0));
    ASSERT_TRUE(s.picked);
    EXPECT_EQ(s.picked->node, 1);
    EXPECT_EQ(s.picked->mesh, 1);
    EXPECT_EQ(s.picked->instance, 1);
    EXPECT_EQ(s.edit_material, 1);
    EXPECT_FALSE(s.select_primitive(7, 0));  // no instance of it
    EXPECT_EQ(s.picked->node, 1);
}

TEST(State, LabelsOfNodesAndCameras) {
    State s = showing_scene();
    EXPECT_EQ(s.node_label(0), "box  [mesh 0]");
    s.scene->nodes[1].name.clear();
    s.scene->nodes[1].camera = 0;
    s.scene->cameras.resize(1);
    EXPECT_EQ(s.node_label(1), "node 1  [mesh 1]  [camera 0]");
    EXPECT_EQ(s.camera_label(0), "camera 0");
    s.scene->cameras[0].name = "front";
    EXPECT_EQ(s.camera_label(0), "camera 0: front");
}

TEST(State, AddedLightsAreSelectedAndRemovingOneClearsTheSelection) {
    State s = showing_scene();
    EXPECT_EQ(s.add_light(Light::Type::Directional), 0);
    EXPECT_EQ(s.add_light(Light::Type::Point), 1);
    EXPECT_EQ(s.selected_light, 1);
    const LightInstance& point = s.job.lights.extra[1];
    // In front of the model, on the handle sphere, towards azimuth 30 elevation 45.
    EXPECT_NEAR(glm::distance(point.position, s.bounds.center()), handle_radius(s.bounds), 1e-4f);
    EXPECT_GT(point.position.y, s.bounds.center().y);
    EXPECT_FLOAT_EQ(s.job.lights.extra[0].radiance.x, 3.0f);  // lux
    s.remove_light(0);
    ASSERT_EQ(s.job.lights.extra.size(), 1u);
    EXPECT_EQ(s.job.lights.extra[0].type, Light::Type::Point);
    EXPECT_EQ(s.selected_light, -1);
    s.remove_light(5);  // none such: nothing
    EXPECT_EQ(s.job.lights.extra.size(), 1u);
}

TEST(State, DraggingALightHandleMovesItUntilTheButtonIsReleased) {
    State s = showing_scene();
    s.add_light(Light::Type::Point);
    s.selected_light = -1;
    LightInstance& l = s.job.lights.extra[0];
    auto at = to_window(*s.last_camera, s.window, l.position);
    ASSERT_TRUE(at);
    EXPECT_TRUE(s.drag_lights(*at, /*clicked=*/true, /*down=*/true));
    EXPECT_EQ(s.dragging_light, 0);
    EXPECT_EQ(s.selected_light, 0);
    const glm::vec3 before = l.position;
    EXPECT_TRUE(s.drag_lights(*at + glm::vec2(20.0f, 0.0f), false, true));
    EXPECT_GT(l.position.x, before.x);  // right on the screen is +X from +Z
    auto now = to_window(*s.last_camera, s.window, l.position);
    ASSERT_TRUE(now);
    EXPECT_NEAR(now->x, at->x + 20.0f, 1e-2f);
    EXPECT_FALSE(s.drag_lights(*now, false, false));  // released
    EXPECT_EQ(s.dragging_light, -1);
    // A click away from every handle drags nothing (the camera turns instead).
    EXPECT_FALSE(s.drag_lights({1.0f, 1.0f}, true, true));
    // With the gizmos hidden, nothing is dragged.
    s.show_gizmos = false;
    EXPECT_FALSE(s.drag_lights(*now, true, true));
}

TEST(State, SpinTurnsTheEnvironmentTheCameraAndTheLights) {
    State s = showing_scene();
    EXPECT_FALSE(s.spinning());
    s.orbit_lights = true;
    EXPECT_FALSE(s.spinning());  // no added lights to orbit
    s.orbit_lights = false;
    s.spin_environment = true;
    s.job.environment.rotation_deg = 179.0f;
    s.job.camera.yaw_deg = 10.0f;
    EXPECT_TRUE(s.spinning());
    s.spin(0.1);  // 3 degrees, wrapping into -180..180
    EXPECT_NEAR(s.job.environment.rotation_deg, -178.0f, 1e-4f);
    EXPECT_FLOAT_EQ(s.job.camera.yaw_deg, 10.0f);
    s.spin_camera = true;
    s.spin(2.0);  // a long frame turns as a quarter second
    EXPECT_NEAR(s.job.camera.yaw_deg, 17.5f, 1e-4f);
    s.add_light(Light::Type::Directional);
    const glm::vec3 d = s.job.lights.extra[0].direction;
    s.spin_camera = s.spin_environment = false;
    s.orbit_lights = true;
    s.spin(0.1);
    const glm::vec3 e = s.job.lights.extra[0].direction;
    EXPECT_NEAR(e.y, d.y, 1e-5f);  // about +Y
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(glm::normalize(glm::vec2(d.x, d.z)), glm::normalize(glm::vec2(e.x, e.z))))),
                3.0f, 1e-2f);
}

TEST(State, OrbitingAwayFromAFilesCameraStartsWhereItLooks) {
    State s = showing_scene();
    s.job.camera.scene_camera = 0;
    s.orbit_camera_now();
    EXPECT_FALSE(s.job.camera.scene_camera);
    EXPECT_TRUE(s.job.camera.target);  // looking from (0, 0, 5) down -Z
    EXPECT_NEAR(s.job.camera.yaw_deg, 0.0f, 1e-3f);
    EXPECT_NEAR(s.job.camera.pitch_deg, 0.0f, 1e-3f);
}

TEST(State, TheDividerInFramebufferPixels) {
    State s;
    s.framebuffer = {400, 200};
    s.split_pos = 0.25f;
    EXPECT_EQ(s.divider_pixels(), 100);
    s.split_pos = 2.0f;
    EXPECT_EQ(s.divider_pixels(), 400);
}

TEST(State, StartingWithAFolderShowsItsFirstModelAndStepsThroughIt) {
    const fs::path d = fresh_folder("start");
    for (const char* name : {"b.glb", "a.gltf", "c.obj"}) std::ofstream(d / name) << "x";
    State s;
    s.start_with(d.string());
    ASSERT_EQ(s.folder_models.size(), 3u);
    EXPECT_EQ(fs::path(s.job.source.model).filename(), "a.gltf");
    EXPECT_EQ(s.opened, s.job.source.model);
    EXPECT_EQ(s.browser_dir, fs::absolute(d).lexically_normal());
    EXPECT_TRUE(s.error.empty());
    EXPECT_EQ(fs::path(*s.step_folder(-1)).filename(), "c.obj");  // wraps to the last
    EXPECT_EQ(fs::path(*s.step_folder(+1)).filename(), "b.glb");
    fs::remove_all(d);
}

TEST(State, AFolderThatStartsWithASceneFileOpensItAsOne) {
    const fs::path d = fresh_folder("scene");
    std::ofstream(d / "a.fresnel.json") << "{}";
    std::ofstream(d / "b.glb") << "x";
    State s;
    s.start_with(d.string());
    EXPECT_TRUE(s.job.source.model.empty());
    EXPECT_EQ(fs::path(s.first_scene_file).filename(), "a.fresnel.json");
    fs::remove_all(d);
}

TEST(State, AnEmptyFolderSaysSo) {
    const fs::path d = fresh_folder("empty");
    State s;
    s.start_with(d.string());
    EXPECT_TRUE(s.folder_models.empty());
    EXPECT_NE(s.error.find("no models"), std::string::npos);
    EXPECT_FALSE(s.step_folder(+1));
    fs::remove_all(d);
}

TEST(State, TheRecentListIsKeptOnlyWhenTheJobUsesTheCache) {
    const fs::path d = fresh_folder("recent");
    State s;
    s.recent_file = d / "recent.txt";
    s.open_environment((d / "sky.hdr").string());
    EXPECT_EQ(s.job.environment.kind, Job::Environment::Kind::File);
    EXPECT_EQ(s.job.environment.path, (d / "sky.hdr").string());
    ASSERT_EQ(s.recent.paths().size(), 1u);
    State again;
    again.recent_file = s.recent_file;
    again.load_recent();
    EXPECT_EQ(again.recent.paths(), s.recent.paths());

    State no_cache;
    no_cache.job.environment.use_cache = false;
    no_cache.recent_file = d / "other.txt";
    no_cache.remember((d / "m.glb").string());
    EXPECT_EQ(no_cache.recent.paths().size(), 1u);  // listed for this session
    EXPECT_FALSE(fs::exists(no_cache.recent_file));  // not written
    no_cache.recent_file = s.recent_file;
    no_cache.load_recent();
    EXPECT_EQ(no_cache.recent.paths().size(), 1u);  // not read either
    fs::remove_all(d);
}

// Playback: the time is the job's (what `print` and save-scene write, what the window poses).
TEST(State, PlaybackAdvancesTheJobsTimeAndLoopsOrStops) {
    State s;
    EXPECT_FALSE(s.animated());
    s.play(true);
    EXPECT_FALSE(s.playback.playing);  // nothing to play
    s.scene = std::make_unique<Scene>(test::animated_box_before_sphere());
    ASSERT_TRUE(s.animated());
    EXPECT_EQ(s.animation_range(), std::make_pair(0.0f, 4.0f));  // all: the union of the keyframes
    EXPECT_FALSE(s.job.source.animation.posed());                 // the rest pose until asked
    EXPECT_FALSE(s.advance(0.5));                                 // paused: nothing moves
    s.play(true);
    ASSERT_TRUE(s.playback.playing);
    EXPECT_EQ(s.job.source.animation.time, 0.0f);  // from the start
    EXPECT_TRUE(s.advance(1.5));
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 1.5f);
    s.playback.speed = 2.0f;
    s.advance(1.5);  // 1.5 + 3 = 4.5: wrapped to 0.5
    EXPECT_NEAR(*s.job.source.animation.time, 0.5f, 1e-5f);
    s.playback.speed = -1.0f;
    s.advance(1.0);  // backwards past the start: from the end
    EXPECT_NEAR(*s.job.source.animation.time, 3.5f, 1e-5f);
    s.playback.speed = 1.0f;
    s.playback.loop = false;
    s.advance(10.0);  // no loop: stops at the end
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 4.0f);
    EXPECT_FALSE(s.playback.playing);
    s.play(true);  // at the end, play starts again
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 0.0f);
}

TEST(State, ChoosingAnAnimationTakesItsRange) {
    State s;
    s.scene = std::make_unique<Scene>(test::animated_box_before_sphere());
    s.set_time(3.0f);
    s.set_animation(0);  // paused: the time shown, clamped to [0, 2]
    EXPECT_EQ(s.animation_range(), std::make_pair(0.0f, 2.0f));
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 2.0f);
    s.play(true);
    s.set_animation(1);  // playing: from the start of [1, 4]
    EXPECT_EQ(s.job.source.animation.index, 1);
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 1.0f);
    s.advance(0.25);
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 1.25f);
    s.set_animation(-1);
    EXPECT_EQ(s.animation_range(), std::make_pair(0.0f, 4.0f));
    s.set_time(std::nanf(""));  // ignored
    EXPECT_FLOAT_EQ(*s.job.source.animation.time, 0.0f);
}

TEST(State, EnvironmentPresetsAreTheStudioTheFilesBesideTheModelAndTheRecentOnes) {
    const fs::path d = fresh_folder("presets");
    for (const char* f : {"b.hdr", "a.exr", "model.glb", "notes.txt"}) std::ofstream(d / f) << "x";
    fs::create_directories(d / "sky.baked");
    std::ofstream(d / "sky.baked" / "manifest.json") << "{}";
    State s;
    s.job.source.model = (d / "model.glb").string();
    s.recent.add("/elsewhere/night.exr");
    s.recent.add((d / "b.hdr").string());  // beside the model too: listed once
    s.recent.add("/elsewhere/car.glb");    // a model, not an environment
    const std::vector<std::string> want = {"studio", (d / "a.exr").string(), (d / "b.hdr").string(),
                                           (d / "sky.baked").string(), "/elsewhere/night.exr"};
    EXPECT_EQ(s.environment_presets(), want);
    State demo;  // the built-in demo: the studio and the recent ones
    EXPECT_EQ(demo.environment_presets(), std::vector<std::string>{"studio"});
    fs::remove_all(d);
}

}  // namespace
}  // namespace fresnel::viewer
