// Scene files (*.fresnel.json) read onto a Job: every key of docs/scene.schema.json, the
// broken files (wrong types, missing files, paths outside the folder, hostile JSON), unknown
// keys as warnings with their pointer, and several models merged into one scene.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fresnel/core/error.h"
#include "fresnel/job/job.h"
#include "fresnel/job/scene_file.h"
#include "gltf_builders.h"

using namespace fresnel;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

using fresnel::test::base64;


// A unit quad in z = 0 from (0,0) to (1,1) with one named material and one camera node.
void write_quad(const fs::path& path, const std::string& material) {
    const float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::uint16_t idx[] = {0, 1, 2, 0, 2, 3};
    std::string buf(reinterpret_cast<const char*>(pos), sizeof pos);
    buf.append(reinterpret_cast<const char*>(idx), sizeof idx);
    json j = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0, 1}}}}},
        {"nodes", {{{"mesh", 0}}, {{"camera", 0}, {"translation", {0.5, 0.5, 3}}}}},
        {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
        {"materials", {{{"name", material}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}}}},
        {"buffers", {{{"byteLength", buf.size()}, {"uri", "data:application/octet-stream;base64," + base64(buf)}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", sizeof pos}},
                         {{"buffer", 0}, {"byteOffset", sizeof pos}, {"byteLength", sizeof idx}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                        {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                       {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
    };
    std::ofstream(path) << j.dump();
}

class SceneFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::path(::testing::TempDir()) / ("fresnel_scenefile_" + std::string(info->name()) + "_" +
                                                 std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "models");
        write_quad(dir_ / "models" / "a.gltf", "Red");
        write_quad(dir_ / "models" / "b.gltf", "Blue");
        std::ofstream(dir_ / "sky.hdr") << "not read by the parser";
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    fs::path write(const std::string& text, const std::string& name = "scene.fresnel.json") {
        fs::path p = dir_ / name;
        std::ofstream(p) << text;
        return p;
    }
    SceneFile load(const json& doc) { return load_scene_file(write(doc.dump()), Job{}, diag_); }
    // The error of loading `text`; fails the test when it loads.
    Error error_of(const std::string& text) {
        try {
            load_scene_file(write(text), Job{}, diag_);
        } catch (const Error& e) {
            return e;
        }
        ADD_FAILURE() << "loaded without error: " << text.substr(0, 200);
        return Error("", "", "");
    }
    fs::path dir_;
    Diagnostics diag_;
};

TEST_F(SceneFileTest, EveryKeyReachesTheJob) {
    json doc = {
        {"fresnel", 1},
        {"models",
         {{{"path", "models/a.gltf"}, {"translation", {1, 2, 3}}, {"scale", {2, 2, 2}},
           {"materials", {{{"name", "Red"}, {"baseColorFactor", {1, 0, 0, 1}}, {"roughnessFactor", 0.25}}}}},
          {{"path", "models/b.gltf"}, {"visible", false}}}},
        {"camera", {{"type", "lookAt"}, {"eye", {0, 1, 5}}, {"target", {0, 0, 0}}, {"fov", 30}}},
        {"lights",
         {{{"type", "directional"}, {"azimuth", 30}, {"elevation", 45}, {"intensity", 3}},
          {{"type", "point"}, {"position", {1, 2, 3}}, {"intensity", 50}, {"color", {1, 0.5, 0.25}}, {"range", 10}},
          {{"type", "spot"}, {"position", {0, 4, 0}}, {"target", {0, 0, 0}}, {"innerConeAngle", 0.1},
           {"outerConeAngle", 0.5}, {"intensity", 100}}}},
        {"sceneLights", false},
        {"environment", {{"file", "sky.hdr"}, {"rotation", 90}, {"intensity", 0.5}, {"bakeSize", 64}}},
        {"background", {{"type", "color"}, {"color", {0.1, 0.2, 0.3}}}},
        {"render", {{"size", {320, 200}}, {"msaa", 2}, {"toneMapping", "aces"}, {"exposure", -1}, {"encoding", "gamma2.2"},
                    {"debug", "normal"}, {"anisotropy", 4}, {"energyCompensation", false}}},
        {"output", "out/frame.exr"},
    };
    SceneFile sf = load(doc);
    const Job& job = sf.job;
    ASSERT_EQ(job.source.models.size(), 2u);
    EXPECT_EQ(fs::path(job.source.models[0].path).filename(), "a.gltf");
    EXPECT_TRUE(fs::path(job.source.models[0].path).is_absolute()) << "paths resolve against the file's folder";
    EXPECT_FLOAT_EQ(job.source.models[0].transform[3][0], 1.0f);
    EXPECT_FLOAT_EQ(job.source.models[0].transform[0][0], 2.0f);
    ASSERT_EQ(job.source.models[0].materials.size(), 1u);
    EXPECT_EQ(job.source.models[0].materials[0].name, std::optional<std::string>("Red"));
    ASSERT_EQ(job.source.models[0].materials[0].values.count("roughnessFactor"), 1u);
    EXPECT_EQ(job.source.models[0].materials[0].values.at("roughnessFactor")[0], 0.25f);
    EXPECT_FALSE(job.source.models[1].visible);
    ASSERT_TRUE(job.camera.look_at);
    EXPECT_EQ(job.camera.look_at->eye, glm::vec3(0, 1, 5));
    EXPECT_FLOAT_EQ(job.camera.yfov_deg, 30.0f);
    ASSERT_EQ(job.lights.extra.size(), 3u);
    EXPECT_EQ(job.lights.extra[0], parse_light("dir:30,45,3")) << "directional azimuth/elevation as --light dir:";
    EXPECT_EQ(job.lights.extra[1].type, Light::Type::Point);
    EXPECT_EQ(job.lights.extra[1].radiance, glm::vec3(50, 25, 12.5));
    EXPECT_FLOAT_EQ(job.lights.extra[1].range, 10.0f);
    EXPECT_EQ(job.lights.extra[2].type, Light::Type::Spot);
    EXPECT_NEAR(job.lights.extra[2].direction.y, -1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(job.lights.extra[2].outer_cone, 0.5f);
    EXPECT_FALSE(job.lights.scene_lights);
    EXPECT_EQ(job.environment.kind, Job::Environment::Kind::File);
    EXPECT_EQ(fs::path(job.environment.path).filename(), "sky.hdr");
    EXPECT_FLOAT_EQ(job.environment.rotation_deg, 90.0f);
    EXPECT_FLOAT_EQ(job.environment.intensity, 0.5f);
    EXPECT_EQ(job.environment.bake_size, 64);
    EXPECT_EQ(job.background.mode, Job::Background::Mode::Color);
    EXPECT_EQ(job.background.color, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(job.output.width, 320);
    EXPECT_EQ(job.output.height, 200);
    EXPECT_EQ(job.output.msaa, 2);
    EXPECT_EQ(job.output.tone_mapper, ToneMapper::Aces);
    EXPECT_FLOAT_EQ(job.output.exposure_ev, -1.0f);
    EXPECT_EQ(job.output.encoding, Encoding::Gamma22);
    EXPECT_EQ(job.output.debug, DebugChannel::Normal);
    EXPECT_FLOAT_EQ(job.output.anisotropy, 4.0f);
    EXPECT_FALSE(job.output.energy_compensation);
    EXPECT_TRUE(job.output.float_output);
    ASSERT_TRUE(sf.output);
    EXPECT_EQ(sf.output->filename(), "frame.exr");
    EXPECT_EQ(diag_.total(), 0u) << diag_.lines().front();
}

// Keys absent keep the job the file is read onto (flags as batch defaults); one model at
// the origin is the plain one-model job.
TEST_F(SceneFileTest, AbsentKeysKeepTheDefaults) {
    Job defaults;
    defaults.output.width = 77;
    defaults.camera.yaw_deg = 12;
    defaults.environment.kind = Job::Environment::Kind::Studio;
    SceneFile sf = load_scene_file(write(R"({"fresnel": 1, "model": "models/a.gltf", "camera": {"pitch": 10}})"),
                                   defaults, diag_);
    EXPECT_EQ(sf.job.output.width, 77);
    EXPECT_FLOAT_EQ(sf.job.camera.yaw_deg, 12.0f);
    EXPECT_FLOAT_EQ(sf.job.camera.pitch_deg, 10.0f);
    EXPECT_EQ(sf.job.environment.kind, Job::Environment::Kind::Studio);
    EXPECT_TRUE(sf.job.source.models.empty());
    EXPECT_EQ(fs::path(sf.job.source.model).filename(), "a.gltf");
    EXPECT_FALSE(sf.output);
}

TEST_F(SceneFileTest, UnknownKeysWarnWithTheirPointer) {
    load(json{{"fresnel", 1}, {"colour", 1}, {"camera", {{"yaw", 10}, {"yawn", 3}}},
              {"models", {{{"path", "models/a.gltf"}, {"translate", {1, 2, 3}}}}}});
    std::string all;
    for (const auto& l : diag_.lines()) all += l + "\n";
    EXPECT_EQ(diag_.total(), 3u) << all;
    EXPECT_NE(all.find("/colour"), std::string::npos) << all;
    EXPECT_NE(all.find("/camera/yawn"), std::string::npos) << all;
    EXPECT_NE(all.find("/models/0/translate"), std::string::npos) << all;
    EXPECT_NE(all.find("scene.fresnel.json"), std::string::npos) << "warnings name the file: " << all;
}

// A key the chosen camera does not use is reported, not silently dropped (a sweep of yaw on
// a lookAt camera would otherwise render one picture N times).
TEST_F(SceneFileTest, KeysTheCameraDoesNotUseWarn) {
    load(json{{"fresnel", 1}, {"camera", {{"eye", {0, 0, 5}}, {"target", {0, 0, 0}}, {"yaw", 30}}}});
    ASSERT_EQ(diag_.total(), 1u);
    EXPECT_NE(diag_.lines().front().find("/camera/yaw"), std::string::npos) << diag_.lines().front();
}

TEST_F(SceneFileTest, WrongTypesNameFileAndPointer) {
    struct Case {
        const char* text;
        const char* pointer;
    };
    const Case cases[] = {
        {R"({"fresnel": 1, "camera": {"yaw": "ten"}})", "/camera/yaw"},
        {R"({"fresnel": 1, "models": [{"path": 3}]})", "/models/0/path"},
        {R"({"fresnel": 1, "models": {"path": "models/a.gltf"}})", "/models"},
        {R"({"fresnel": 1, "models": [{"path": "models/a.gltf", "translation": [1, 2]}]})", "/models/0/translation"},
        {R"({"fresnel": 1, "models": [{"path": "models/a.gltf", "matrix": [1, 0, 0]}]})", "/models/0/matrix"},
        {R"({"fresnel": 1, "lights": [{"type": "area"}]})", "/lights/0/type"},
        {R"({"fresnel": 1, "lights": [{"type": "point", "position": [0, 0, 0], "intensity": -1}]})", "/lights/0/intensity"},
        {R"({"fresnel": 1, "render": {"size": [0, 10]}})", "/render/size/0"},
        {R"({"fresnel": 1, "render": {"size": [1e300, 10]}})", "/render/size/0"},
        {R"({"fresnel": 1, "render": {"msaa": 2.5}})", "/render/msaa"},
        {R"({"fresnel": 1, "render": {"toneMapping": "sepia"}})", "/render/toneMapping"},
        {R"({"fresnel": 1, "environment": {"type": "file"}})", "/environment"},
        {R"({"fresnel": 1, "environment": {"color": [1, 1]}})", "/environment/color"},
        {R"({"fresnel": 1, "background": 7})", "/background"},
        {R"({"fresnel": 1, "camera": {"type": "lookAt", "eye": [1, 1, 1], "target": [1, 1, 1]}})", "/camera"},
        {R"({"fresnel": "1"})", "/fresnel"},
        {R"({"fresnel": 2})", "/fresnel"},
        {R"({"model": "models/a.gltf"})", "/fresnel"},
        {R"({"fresnel": 1, "output": "x.jpg"})", "/output"},
    };
    for (const Case& c : cases) {
        Error e = error_of(c.text);
        EXPECT_EQ(e.where(), c.pointer) << c.text << "\n" << e.what();
        EXPECT_NE(e.file().find("scene.fresnel.json"), std::string::npos) << e.what();
    }
}

TEST_F(SceneFileTest, MissingFilesAndPathsOutsideTheFolder) {
    Error e = error_of(R"({"fresnel": 1, "model": "models/missing.glb"})");
    EXPECT_EQ(e.where(), "/model");
    EXPECT_NE(e.reason().find("does not exist"), std::string::npos) << e.what();

    e = error_of(R"({"fresnel": 1, "environment": "nowhere.hdr"})");
    EXPECT_EQ(e.where(), "/environment");

    fs::create_directories(dir_ / "sub");
    write_quad(dir_ / "outside.gltf", "X");
    for (const char* path : {"../outside.gltf", "/etc/passwd", "http://example.com/a.glb", "file:///etc/passwd"}) {
        std::string text = std::string(R"({"fresnel": 1, "models": [{"path": ")") + path + R"("}]})";
        fs::path p = dir_ / "sub" / "scene.fresnel.json";
        std::ofstream(p) << text;
        try {
            load_scene_file(p, Job{}, diag_);
            ADD_FAILURE() << path << " was accepted";
        } catch (const Error& err) {
            EXPECT_EQ(err.where(), "/models/0/path") << err.what();
        }
    }
    // ... unless external files are allowed.
    SceneFileOptions o;
    o.allow_external_files = true;
    fs::path p = dir_ / "sub" / "scene.fresnel.json";
    std::ofstream(p) << R"({"fresnel": 1, "model": "../outside.gltf"})";
    EXPECT_NO_THROW(load_scene_file(p, Job{}, diag_, o));

    e = error_of(R"({"fresnel": 1, "output": "../../escape.png"})");
    EXPECT_EQ(e.where(), "/output");
    EXPECT_THROW(load_scene_file(dir_ / "none.fresnel.json", Job{}, diag_), Error);
    EXPECT_THROW(load_scene_file(dir_, Job{}, diag_), Error);
}

// Hostile JSON: broken syntax, deep nesting, a huge file, huge arrays; errors, never a crash.
TEST_F(SceneFileTest, HostileJsonIsAnErrorNotACrash) {
    for (std::string text : {std::string("{"), std::string(""), std::string("[1, 2]"), std::string("null"),
                             std::string("{\"fresnel\": 1,}"), std::string("\xff\xfe")}) {
        Error e = error_of(text);
        EXPECT_FALSE(std::string(e.what()).empty());
    }
    Error overflow = error_of(R"({"fresnel": 1, "render": {"exposure": 1e999}})");
    EXPECT_NE(overflow.reason().find("overflow"), std::string::npos) << overflow.what();
    Error deep = error_of("{\"fresnel\": 1, \"x\": " + std::string(100000, '[') + std::string(100000, ']') + "}");
    EXPECT_NE(deep.reason().find("deeper"), std::string::npos) << deep.what();

    SceneFileOptions small;
    small.max_bytes = 64;
    fs::path p = write("{\"fresnel\": 1, \"description\": \"" + std::string(100, 'x') + "\"}");
    EXPECT_THROW(load_scene_file(p, Job{}, diag_, small), Error);

    json many = {{"fresnel", 1}, {"lights", json::array()}};
    for (int i = 0; i < 5000; ++i) many["lights"].push_back({{"type", "point"}, {"position", {0, 0, 0}}});
    EXPECT_EQ(error_of(many.dump()).where(), "/lights");
}

TEST_F(SceneFileTest, ModelsMergeUnderTheirTransforms) {
    SceneFile sf = load(json{
        {"fresnel", 1},
        {"models",
         {{{"path", "models/a.gltf"}},
          {{"path", "models/b.gltf"}, {"translation", {3, 0, 0}},
           {"materials", {{{"index", 0}, {"baseColorFactor", {0, 0, 1, 1}}, {"doubleSided", true}}}}},
          {{"path", "models/a.gltf"}, {"visible", false}}}},
        {"camera", {{"type", "model"}, {"model", 1}, {"index", 0}}},
    });
    Diagnostics d;
    Scene scene = load_scene(sf.job, d);
    ASSERT_EQ(scene.parts.size(), 2u) << "the invisible model is not loaded";
    EXPECT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.materials[1].name, "Blue");
    EXPECT_EQ(scene.materials[1].base_color_factor, glm::vec4(0, 0, 1, 1));
    EXPECT_TRUE(scene.materials[1].double_sided);
    EXPECT_FALSE(scene.materials[0].double_sided) << "the override reaches only its model";
    EXPECT_EQ(scene.meshes[1].primitives[0].material, 1) << "material indices are offset";
    ResolvedJob r = resolve(sf.job, scene);
    EXPECT_NEAR(r.bounds.min.x, 0.0f, 1e-6f);
    EXPECT_NEAR(r.bounds.max.x, 4.0f, 1e-6f) << "the second quad moved by its translation";
    // Model 1's camera: at (0.5, 0.5, 3) in its file, moved by the model's translation.
    EXPECT_NEAR(r.camera.eye.x, 3.5f, 1e-5f);
    EXPECT_NEAR(r.camera.eye.z, 3.0f, 1e-5f);

    sf.job.camera.scene_camera_model = 5;
    EXPECT_THROW(resolve(sf.job, scene), Error);
}

// A model named several times with the same overrides is loaded once and placed again: its
// meshes, materials and images are held once, each placement is its own part and node tree.
TEST_F(SceneFileTest, RepeatedModelsAreLoadedOnce) {
    SceneFile sf = load(json{
        {"fresnel", 1},
        {"models",
         {{{"path", "models/a.gltf"}},
          {{"path", "models/a.gltf"}, {"translation", {3, 0, 0}}},
          {{"path", "models/a.gltf"}, {"translation", {6, 0, 0}}},
          {{"path", "models/a.gltf"}, {"translation", {9, 0, 0}},
           {"materials", {{{"index", 0}, {"baseColorFactor", {0, 0, 1, 1}}}}}}}},
    });
    Diagnostics d;
    Scene scene = load_scene(sf.job, d);
    ASSERT_EQ(scene.parts.size(), 4u);
    EXPECT_EQ(scene.meshes.size(), 2u) << "the three equal placements share one copy; the overridden one has its own";
    EXPECT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.parts[1].first_material, scene.parts[0].first_material);
    EXPECT_EQ(scene.parts[3].first_material, 1);
    EXPECT_EQ(scene.materials[1].base_color_factor, glm::vec4(0, 0, 1, 1));
    const ResolvedJob r = resolve(sf.job, scene);
    int drawn = 0;
    for (const NodeInstance& n : r.instances) drawn += scene.nodes[std::size_t(n.node)].mesh >= 0;
    EXPECT_EQ(drawn, 4);
    EXPECT_NEAR(r.bounds.min.x, 0.0f, 1e-6f);
    EXPECT_NEAR(r.bounds.max.x, 10.0f, 1e-6f) << "every placement at its own translation";
}

TEST_F(SceneFileTest, OverrideOfAMissingMaterialWarnsAndIndexOutOfRangeFails) {
    SceneFile sf = load(json{{"fresnel", 1},
                             {"models", {{{"path", "models/a.gltf"}, {"materials", {{{"name", "Green"}, {"metallicFactor", 1}}}}}}}});
    Diagnostics d;
    load_scene(sf.job, d);
    ASSERT_EQ(d.total(), 1u);
    EXPECT_NE(d.lines().front().find("Green"), std::string::npos);

    sf = load(json{{"fresnel", 1}, {"models", {{{"path", "models/a.gltf"}, {"materials", {{{"index", 4}, {"metallicFactor", 1}}}}}}}});
    EXPECT_THROW(load_scene(sf.job, d), Error);
}

TEST_F(SceneFileTest, LookAtCameraLooksAtTheTarget) {
    SceneFile sf = load(json{{"fresnel", 1}, {"model", "models/a.gltf"},
                             {"camera", {{"eye", {0.5, 0.5, 4}}, {"target", {0.5, 0.5, 0}}, {"fov", 40}}}});
    Diagnostics d;
    Scene scene = load_scene(sf.job, d);
    ResolvedJob r = resolve(sf.job, scene);
    glm::vec4 centre = r.camera.projection * r.camera.view * glm::vec4(0.5f, 0.5f, 0.0f, 1.0f);
    EXPECT_NEAR(centre.x / centre.w, 0.0f, 1e-5f);
    EXPECT_NEAR(centre.y / centre.w, 0.0f, 1e-5f);
    EXPECT_GT(r.camera.znear, 0.0f);
    EXPECT_LT(r.camera.znear, 4.0f);
    EXPECT_GT(r.camera.zfar, 4.0f);
}

}  // namespace

namespace {

// The example of docs/scene-file.md reads without a warning (the docs keep up with the parser).
// The way back (the viewer's "save scene"): a job written as a scene file reads back to the
// same job, every field a scene file holds, floats exactly (lights within rounding: the
// reader normalises directions).
TEST_F(SceneFileTest, SavedJobReadsBackTheSame) {
    Job job;
    Job::Source::Model a, b;
    a.path = fs::weakly_canonical(dir_ / "models" / "a.gltf").string();
    a.transform = glm::mat4(1.0f);
    a.transform[3] = glm::vec4(0.1f, -2.5f, 3.3f, 1.0f);
    a.transform[0][0] = 0.7f;
    Job::Source::MaterialOverride mo;
    mo.index = 0;
    // Every property of the material property registry, at a value other than its default.
    for (const auto& p : material_properties::all()) {
        material_properties::Value v{};
        for (int k = 0; k < p.width; ++k)
            v[std::size_t(k)] = p.type == material_properties::Type::Bool     ? 1.0f - p.fallback[0]
                                : p.type == material_properties::Type::Choice ? 1.0f
                                                                              : p.slider_min + (0.37f + 0.1f * float(k)) *
                                                                                                   (p.slider_max - p.slider_min);
        ASSERT_EQ(material_properties::check(p, v), "") << p.name;
        mo.values[std::string(p.name)] = v;
    }
    a.materials.push_back(mo);
    b.path = fs::weakly_canonical(dir_ / "models" / "b.gltf").string();
    b.visible = false;
    b.scene = 0;
    job.source.models = {a, b};
    job.source.variant = "night";
    job.source.pose_skins = true;
    job.camera.yaw_deg = 123.456f;
    job.camera.pitch_deg = -33.3f;
    job.camera.distance_k = 1.7f;
    job.camera.yfov_deg = 38.5f;
    job.camera.target = glm::vec3(0.1f, 0.2f, -0.3f);
    job.lights.extra = {parse_light("dir:30,45,3,1,0.5,0.25"), parse_light("point:1,2,-3,40")};
    LightInstance spot;
    spot.type = Light::Type::Spot;
    spot.position = {0, 3, 2};
    spot.direction = glm::normalize(glm::vec3(0, -3, -2));
    spot.radiance = {200, 100, 50};
    spot.range = 12.0f;
    spot.inner_cone = 0.2f;
    spot.outer_cone = 0.5f;
    job.lights.extra.push_back(spot);
    job.lights.scene_lights = false;
    job.environment.kind = Job::Environment::Kind::File;
    job.environment.path = fs::weakly_canonical(dir_ / "sky.hdr").string();
    job.environment.rotation_deg = 33.3f;
    job.environment.intensity = 0.7f;
    job.environment.bake_samples = 64;
    job.environment.bake_size = 128;
    job.background.mode = Job::Background::Mode::Color;
    job.background.color = {0.1f, 0.2f, 0.3f};
    job.output.width = 640;
    job.output.height = 360;
    job.output.msaa = 2;
    job.output.anisotropy = 4.0f;
    job.output.tone_mapper = ToneMapper::AcesHill;
    job.output.exposure_ev = -1.25f;
    job.output.encoding = Encoding::Gamma22;
    job.output.debug = DebugChannel::Roughness;
    job.output.energy_compensation = false;
    job.output.shading = ShadingModel::Gltf;
    job.output.brdf = *fresnel::brdf::parse_brdf_model("D=beckmann,F=exact:gold");

    fs::path saved = dir_ / "saved.fresnel.json";
    Diagnostics wd;
    save_scene_file(saved, job, wd, dir_ / "out.png");
    EXPECT_EQ(wd.total(), 0u) << (wd.lines().empty() ? "" : wd.lines().front());
    // The paths are relative to the file's folder (the file can move with its folder).
    json doc = json::parse(std::ifstream(saved));
    EXPECT_EQ(doc["models"][0]["path"], "models/a.gltf");
    EXPECT_EQ(doc["environment"]["file"], "sky.hdr");
    EXPECT_EQ(doc["camera"]["pitch"].dump(), "-33.3");  // floats in their shortest form
    EXPECT_EQ(doc["render"]["brdf"], "D=beckmann,G=smith-height-correlated,F=exact:gold,diffuse=lambert");

    SceneFile back = load_scene_file(saved, Job{}, diag_);
    EXPECT_EQ(diag_.total(), 0u) << (diag_.lines().empty() ? "" : diag_.lines().front());
    EXPECT_EQ(back.job.source, job.source);
    EXPECT_EQ(back.job.camera, job.camera);
    EXPECT_EQ(back.job.environment, job.environment);
    EXPECT_EQ(back.job.background, job.background);
    Job::Output want = job.output;
    want.float_output = false;  // out.png
    EXPECT_EQ(back.job.output, want);
    ASSERT_TRUE(back.output);
    EXPECT_EQ(back.output->filename(), "out.png");
    EXPECT_EQ(back.job.lights.scene_lights, false);
    ASSERT_EQ(back.job.lights.extra.size(), job.lights.extra.size());
    for (std::size_t i = 0; i < job.lights.extra.size(); ++i) {
        const LightInstance &x = job.lights.extra[i], &y = back.job.lights.extra[i];
        EXPECT_EQ(x.type, y.type) << i;
        EXPECT_LT(glm::length(x.position - y.position), 1e-6f) << i;
        EXPECT_LT(glm::length(x.radiance - y.radiance), 1e-4f) << i;
        EXPECT_EQ(x.range, y.range) << i;
        EXPECT_EQ(x.inner_cone, y.inner_cone) << i;
        EXPECT_EQ(x.outer_cone, y.outer_cone) << i;
        if (x.type != Light::Type::Point) {
            EXPECT_LT(glm::length(x.direction - y.direction), 1e-6f) << i;
        }
    }
}

TEST_F(SceneFileTest, SavedFormsReadBack) {
    // One model at the origin is a plain "model"; the file's camera; a look-at camera; the other
    // environment and background kinds.
    Job job;
    job.source.model = fs::weakly_canonical(dir_ / "models" / "a.gltf").string();
    job.camera.scene_camera = 0;
    job.environment.kind = Job::Environment::Kind::Color;
    job.environment.color = {0.5f, 0.25f, 2.0f};
    job.background.mode = Job::Background::Mode::Transparent;
    fs::path saved = dir_ / "one.fresnel.json";
    Diagnostics wd;
    save_scene_file(saved, job, wd);
    json doc = json::parse(std::ifstream(saved));
    EXPECT_EQ(doc["model"], "models/a.gltf");
    SceneFile back = load_scene_file(saved, Job{}, diag_);
    EXPECT_EQ(back.job, job);
    EXPECT_FALSE(back.output);

    job.camera = Job::Camera{};
    job.camera.look_at = Job::Camera::LookAt{{1, 2, 3}, {0, 0.5f, 0}, {0, 1, 0}};
    job.camera.yfov_deg = 30.0f;
    job.environment = Job::Environment{};
    job.environment.kind = Job::Environment::Kind::None;
    job.background.mode = Job::Background::Mode::Blurred;
    job.source.model.clear();  // the demo
    save_scene_file(saved, job, wd);
    EXPECT_EQ(json::parse(std::ifstream(saved))["model"], "demo");
    EXPECT_EQ(load_scene_file(saved, Job{}, diag_).job, job);
    for (auto kind : {Job::Environment::Kind::Studio, Job::Environment::Kind::Automatic}) {
        job.environment.kind = kind;
        job.background.mode = Job::Background::Mode::Environment;
        save_scene_file(saved, job, wd);
        EXPECT_EQ(load_scene_file(saved, Job{}, diag_).job, job);
    }
    EXPECT_EQ(wd.total(), 0u);
}

// Area lights in a scene file: rect (width, height), disk and sphere (radius), placed and aimed
// as spot lights are; saved and read back; sizes on the wrong type are errors with their pointer.
TEST_F(SceneFileTest, AreaLightsReadAndSaveBack) {
    json doc = {{"fresnel", 1},
                {"model", "models/a.gltf"},
                {"lights",
                 {{{"type", "rect"}, {"position", {0, 3, 0}}, {"target", {0, 0, 0}}, {"width", 2}, {"height", 0.5}, {"intensity", 40}},
                  {{"type", "disk"}, {"position", {1, 2, 0}}, {"azimuth", 90}, {"elevation", 30}, {"radius", 0.3}},
                  {{"type", "sphere"}, {"position", {0, 1, 1}}, {"radius", 0.1}, {"color", {1, 0.5, 0.5}}, {"intensity", 8}},
                  {{"type", "tube"}, {"position", {0, 2, 0}}, {"direction", {1, 0, 0}}, {"length", 1.5}, {"radius", 0.04}}}}};
    SceneFile sf = load(doc);
    const std::vector<LightInstance>& l = sf.job.lights.extra;
    ASSERT_EQ(l.size(), 4u);
    EXPECT_EQ(l[0].type, Light::Type::Rect);
    EXPECT_NEAR(l[0].direction.y, -1.0f, 1e-6f) << "aimed at its target";
    EXPECT_NEAR(l[0].area(), 1.0f, 1e-5f);
    EXPECT_EQ(l[1].type, Light::Type::Disk);
    EXPECT_NEAR(glm::length(l[1].axis_u), 0.3f, 1e-6f);
    EXPECT_EQ(l[2].type, Light::Type::Sphere);
    EXPECT_FLOAT_EQ(l[2].radius, 0.1f);
    EXPECT_EQ(l[2].radiance, glm::vec3(8, 4, 4));
    EXPECT_EQ(l[3].type, Light::Type::Tube);
    EXPECT_NEAR(l[3].axis_u.x, 0.75f, 1e-6f);
    EXPECT_FLOAT_EQ(l[3].radius, 0.04f);
    fs::path saved = dir_ / "area.fresnel.json";
    Diagnostics wd;
    save_scene_file(saved, sf.job, wd);
    SceneFile back = load_scene_file(saved, Job{}, diag_);
    ASSERT_EQ(back.job.lights.extra.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        const LightInstance& a = l[i];
        const LightInstance& b = back.job.lights.extra[i];
        EXPECT_EQ(a.type, b.type) << i;
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(a.position[k], b.position[k], 1e-5f) << i;
            EXPECT_NEAR(a.axis_u[k], b.axis_u[k], 1e-5f) << i;
            EXPECT_NEAR(a.axis_v[k], b.axis_v[k], 1e-5f) << i;
            EXPECT_NEAR(a.radiance[k], b.radiance[k], 1e-4f) << i;
        }
        EXPECT_NEAR(a.radius, b.radius, 1e-6f) << i;
    }
    for (const auto& [text, pointer] : std::vector<std::pair<std::string, std::string>>{
             {R"({"fresnel": 1, "lights": [{"type": "sphere", "position": [0, 0, 0], "width": 1}]})", "/lights/0/width"},
             {R"({"fresnel": 1, "lights": [{"type": "rect", "position": [0, 0, 0], "azimuth": 0, "radius": 1}]})", "/lights/0/radius"},
             {R"({"fresnel": 1, "lights": [{"type": "rect", "position": [0, 0, 0], "azimuth": 0, "width": 0}]})", "/lights/0/width"},
             {R"({"fresnel": 1, "lights": [{"type": "disk", "position": [0, 0, 0]}]})", "/lights/0"},
             {R"({"fresnel": 1, "lights": [{"type": "sphere", "position": [0, 0, 0], "length": 1}]})", "/lights/0/length"},
         }) {
        Error e = error_of(text);
        EXPECT_EQ(e.where(), pointer) << text << "\n" << e.what();
    }
}

// A point or spot light's "radius" is its bulb (contact-hardening shadows; LightInstance::radius),
// a directional light's "angularRadius" its angular size (degrees), each written back when set;
// 0 or absent is a point; out of range or on another type is refused naming the key.
TEST_F(SceneFileTest, LightsTakeTheSizeTheirShadowsComeFrom) {
    json doc = {{"fresnel", 1},
                {"lights",
                 {{{"type", "point"}, {"position", {0, 2, 0}}, {"intensity", 40}, {"radius", 0.2}},
                  {{"type", "spot"}, {"position", {0, 3, 0}}, {"target", {0, 0, 0}}, {"intensity", 60}, {"radius", 0.05}},
                  {{"type", "point"}, {"position", {1, 2, 0}}},
                  {{"type", "directional"}, {"azimuth", 30}, {"elevation", 40}, {"angularRadius", 2}}}}};
    SceneFile sf = load(doc);
    const auto& l = sf.job.lights.extra;
    ASSERT_EQ(l.size(), 4u);
    EXPECT_FLOAT_EQ(l[0].radius, 0.2f);
    EXPECT_FLOAT_EQ(l[1].radius, 0.05f);
    EXPECT_EQ(l[2].radius, 0.0f);
    EXPECT_NEAR(l[3].radius, 2.0f * 3.14159265f / 180.0f, 1e-7f);  // degrees in the file, radians in the light
    fs::path saved = dir_ / "bulbs.fresnel.json";
    Diagnostics wd;
    save_scene_file(saved, sf.job, wd);
    const json written = json::parse(std::ifstream(saved));
    EXPECT_EQ(written["lights"][0]["radius"], 0.2);
    EXPECT_FALSE(written["lights"][2].contains("radius")) << written.dump();
    EXPECT_NEAR(written["lights"][3]["angularRadius"].get<double>(), 2.0, 1e-5);
    SceneFile back = load_scene_file(saved, Job{}, diag_);
    ASSERT_EQ(back.job.lights.extra.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(back.job.lights.extra[i].radius, l[i].radius, 1e-7f) << i;
    Error e = error_of(R"({"fresnel": 1, "lights": [{"type": "point", "position": [0, 0, 0], "radius": -1}]})");
    EXPECT_EQ(e.where(), "/lights/0/radius") << e.what();
    e = error_of(R"({"fresnel": 1, "lights": [{"type": "directional", "azimuth": 0, "radius": 1}]})");
    EXPECT_EQ(e.where(), "/lights/0/radius") << e.what();
    e = error_of(R"({"fresnel": 1, "lights": [{"type": "point", "position": [0, 0, 0], "angularRadius": 1}]})");
    EXPECT_EQ(e.where(), "/lights/0/angularRadius") << e.what();
    e = error_of(R"({"fresnel": 1, "lights": [{"type": "directional", "azimuth": 0, "angularRadius": 45}]})");
    EXPECT_EQ(e.where(), "/lights/0/angularRadius") << e.what();
}

// Files outside the scene file's folder are written with "..", and reported: the reader
// refuses them unless external files are allowed.
TEST_F(SceneFileTest, SavedPathsOutsideTheFolderWarn) {
    fs::create_directories(dir_ / "shots");
    Job job;
    job.source.model = fs::weakly_canonical(dir_ / "models" / "a.gltf").string();
    fs::path saved = dir_ / "shots" / "s.fresnel.json";
    Diagnostics wd;
    save_scene_file(saved, job, wd);
    ASSERT_EQ(wd.total(), 1u);
    EXPECT_NE(wd.lines().front().find("--allow-external-files"), std::string::npos) << wd.lines().front();
    EXPECT_EQ(json::parse(std::ifstream(saved))["model"], "../models/a.gltf");
    EXPECT_THROW(load_scene_file(saved, Job{}, diag_), Error);
    SceneFileOptions allow;
    allow.allow_external_files = true;
    EXPECT_EQ(load_scene_file(saved, Job{}, diag_, allow).job.source.model, job.source.model);
}

// A write that cannot complete leaves what was there and no temporary file behind.
TEST_F(SceneFileTest, SaveIsAtomic) {
    Job job;
    fs::path saved = dir_ / "keep.fresnel.json";
    Diagnostics wd;
    save_scene_file(saved, job, wd);
    const std::string before = [&] { std::stringstream ss; ss << std::ifstream(saved).rdbuf(); return ss.str(); }();
    // The target is a folder that is not empty: the rename fails, the folder stays.
    fs::create_directories(dir_ / "busy.fresnel.json" / "inside");
    EXPECT_THROW(save_scene_file(dir_ / "busy.fresnel.json", job, wd), Error);
    EXPECT_TRUE(fs::is_directory(dir_ / "busy.fresnel.json" / "inside"));
    EXPECT_THROW(save_scene_file(dir_ / "no" / "such" / "folder.fresnel.json", job, wd), Error);
    for (const auto& e : fs::directory_iterator(dir_))
        EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos) << e.path();
    // Saving again over a file replaces it whole.
    job.camera.yaw_deg = 10.0f;
    save_scene_file(saved, job, wd);
    EXPECT_EQ(load_scene_file(saved, Job{}, diag_).job.camera.yaw_deg, 10.0f);
    EXPECT_NE(before.size(), 0u);
}

TEST(SceneFileDocs, ExampleReadsCleanly) {
    fs::path example = fs::path(FRESNEL_SOURCE_DIR) / "docs" / "examples" / "demo.fresnel.json";
    Diagnostics diag;
    SceneFile sf = load_scene_file(example, Job{}, diag);
    EXPECT_EQ(diag.total(), 0u) << (diag.lines().empty() ? "" : diag.lines().front());
    EXPECT_EQ(sf.job.source.models.size(), 2u);
    EXPECT_EQ(sf.job.lights.extra.size(), 2u);
    EXPECT_EQ(sf.job.environment.kind, Job::Environment::Kind::Studio);
    ASSERT_TRUE(sf.output);
    Scene scene = load_scene(sf.job, diag);
    EXPECT_EQ(scene.parts.size(), 2u);
}

}  // namespace
