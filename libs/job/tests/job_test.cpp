// Tests of resolve(): the lighting, background and camera rules of docs/shading.md applied to
// a Job, on scenes built in code (no GL, no files).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/core/error.h"
#include "fresnel/job/features.h"
#include "fresnel/job/job.h"
#include "fresnel/job/settings.h"
#include "fresnel/scene/pose.h"
#include "fresnel/scene/procedural.h"

using namespace fresnel;

namespace {

using EnvKind = Job::Environment::Kind;
using Mode = Job::Background::Mode;
using Bg = RenderSettings::Background;

// One unit sphere (no lights, no cameras).
Scene sphere_scene() {
    Primitive p = make_uv_sphere(16, 8);
    p.bounds_min = glm::vec3(-1.0f);
    p.bounds_max = glm::vec3(1.0f);
    return make_single_primitive_scene(std::move(p));
}

// The sphere plus a KHR_lights_punctual point light node.
Scene lit_scene() {
    Scene s = sphere_scene();
    Light l;
    l.type = Light::Type::Point;
    l.intensity = 20.0f;
    l.color = glm::vec3(1.0f, 0.5f, 0.25f);
    s.lights.push_back(l);
    Node n;
    n.light = 0;
    n.local = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 3.0f, 0.0f));
    s.nodes.push_back(n);
    s.scenes[0].push_back(int(s.nodes.size()) - 1);
    return s;
}

// The sphere plus two cameras, only camera 1 used by a node (at z = 5, looking down -Z);
// and a second scene (index 1) that holds only the sphere.
Scene camera_scene() {
    Scene s = sphere_scene();
    Camera c;
    c.yfov = 0.5f;
    c.znear = 0.1f;
    c.zfar = 50.0f;
    s.cameras.push_back(c);
    s.cameras.push_back(c);
    Node n;
    n.camera = 1;
    n.local = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 5.0f));
    s.nodes.push_back(n);
    s.scenes[0].push_back(int(s.nodes.size()) - 1);
    s.scenes.push_back({0});
    return s;
}

LightInstance extra_light() {
    LightInstance l;
    l.type = Light::Type::Directional;
    l.direction = direction_from_angles(10.0f, 20.0f);
    l.radiance = glm::vec3(3.0f);
    return l;
}

std::string error_of(const Job& job, const Scene& scene) {
    try {
        resolve(job, scene);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(JobTest, IsARegularValueType) {
    Job a;
    Job b = a;
    EXPECT_EQ(a, b);
    b.lights.extra.push_back(extra_light());
    EXPECT_NE(a, b);
    a = b;
    EXPECT_EQ(a, b);
    b.environment.color.y = 0.5f;
    EXPECT_NE(a, b);
    b = a;
    b.camera.distance_k = 2.0f;
    EXPECT_NE(a, b);
    // The defaults are the CLI's.
    Job d;
    EXPECT_EQ(d.output.width, 1024);
    EXPECT_EQ(d.output.height, 768);
    EXPECT_EQ(d.output.msaa, 0);  // automatic: 4, 1 with OpenGL 1 shading
    EXPECT_EQ(resolve(d, sphere_scene()).settings.msaa, 4);
    d.output.shading = ShadingModel::Ogl1;
    EXPECT_EQ(resolve(d, sphere_scene()).settings.msaa, 1);
    d.output.shading = ShadingModel::Ogl1Pixel;
    EXPECT_EQ(resolve(d, sphere_scene()).settings.msaa, 1);
    d.output.msaa = 8;
    EXPECT_EQ(resolve(d, sphere_scene()).settings.msaa, 8);
    d = Job{};
    EXPECT_EQ(d.output.tone_mapper, ToneMapper::Neutral);
    EXPECT_EQ(d.environment.kind, EnvKind::Automatic);
    EXPECT_EQ(d.background.mode, Mode::Automatic);
    EXPECT_TRUE(d.lights.scene_lights);
    EXPECT_EQ(d.source.scene, -1);
}

TEST(JobTest, StudioWhenNothingLightsTheScene) {
    ResolvedJob r = resolve(Job{}, sphere_scene());
    ASSERT_TRUE(r.environment);
    EXPECT_EQ(r.environment->kind, ibl::EnvironmentSource::Kind::Studio);
    EXPECT_TRUE(r.lights.empty());
    EXPECT_FALSE(r.default_lights);
    EXPECT_FALSE(r.needs_brdf_lut);  // the environment brings its own table
    EXPECT_EQ(r.settings.background_mode, Bg::Blurred);
    EXPECT_EQ(r.settings.environment, nullptr);  // attached by JobLighting::settings()
}

TEST(JobTest, SceneLightsReplaceTheStudio) {
    ResolvedJob r = resolve(Job{}, lit_scene());
    EXPECT_FALSE(r.environment);
    ASSERT_EQ(r.lights.size(), 1u);
    EXPECT_EQ(r.lights[0].type, Light::Type::Point);
    EXPECT_NEAR(r.lights[0].position.y, 3.0f, 1e-6f);
    EXPECT_NEAR(r.lights[0].radiance.x, 20.0f, 1e-5f);
    EXPECT_NEAR(r.lights[0].radiance.z, 5.0f, 1e-5f);
    EXPECT_FALSE(r.default_lights);
    EXPECT_TRUE(r.needs_brdf_lut);  // energy compensation without an environment
    EXPECT_EQ(r.settings.background_mode, Bg::Color);
    EXPECT_EQ(r.settings.background, glm::vec4(0, 0, 0, 1));
}

TEST(JobTest, ExtraLightsReplaceTheStudioAndFollowTheScenes) {
    Job job;
    job.lights.extra.push_back(extra_light());
    ResolvedJob r = resolve(job, sphere_scene());
    EXPECT_FALSE(r.environment);
    ASSERT_EQ(r.lights.size(), 1u);
    EXPECT_EQ(r.lights[0], extra_light());

    r = resolve(job, lit_scene());
    ASSERT_EQ(r.lights.size(), 2u);
    EXPECT_EQ(r.lights[0].type, Light::Type::Point);  // the scene's first
    EXPECT_EQ(r.lights[1], extra_light());
}

TEST(JobTest, GivenEnvironmentLightsTogetherWithSceneLights) {
    Job job;
    job.environment.kind = EnvKind::Studio;
    ResolvedJob r = resolve(job, lit_scene());
    ASSERT_TRUE(r.environment);
    EXPECT_EQ(r.environment->kind, ibl::EnvironmentSource::Kind::Studio);
    EXPECT_EQ(r.lights.size(), 1u);
    EXPECT_FALSE(r.default_lights);

    job.environment.kind = EnvKind::File;
    job.environment.path = "sky.hdr";
    r = resolve(job, lit_scene());
    ASSERT_TRUE(r.environment);
    EXPECT_EQ(r.environment->kind, ibl::EnvironmentSource::Kind::File);
    EXPECT_EQ(r.environment->path, "sky.hdr");

    job.environment.kind = EnvKind::Color;
    job.environment.color = glm::vec3(0.25f, 0.5f, 1.0f);
    job.environment.bake_samples = 64;
    job.environment.bake_size = 32;
    job.environment.use_cache = false;
    job.environment.rotation_deg = 90.0f;
    job.environment.intensity = 2.0f;
    r = resolve(job, sphere_scene());
    ASSERT_TRUE(r.environment);
    EXPECT_EQ(r.environment->kind, ibl::EnvironmentSource::Kind::Uniform);
    EXPECT_EQ(r.environment->color, glm::vec3(0.25f, 0.5f, 1.0f));
    EXPECT_EQ(r.bake_options.samples, 64);
    EXPECT_EQ(r.bake_options.size, 32);
    EXPECT_FALSE(r.use_cache);
    EXPECT_EQ(r.settings.env_rotation_deg, 90.0f);
    EXPECT_EQ(r.settings.env_intensity, 2.0f);
}

TEST(JobTest, DefaultLightsOnlyWhenNothingElseLights) {
    Job job;
    job.environment.kind = EnvKind::None;  // --no-ibl
    ResolvedJob r = resolve(job, sphere_scene());
    EXPECT_FALSE(r.environment);
    EXPECT_TRUE(r.default_lights);
    EXPECT_EQ(r.lights, default_lights());
    EXPECT_TRUE(r.needs_brdf_lut);

    // Scene lights, extra lights or an environment each keep the default pair away.
    EXPECT_FALSE(resolve(job, lit_scene()).default_lights);
    Job with_light = job;
    with_light.lights.extra.push_back(extra_light());
    EXPECT_FALSE(resolve(with_light, sphere_scene()).default_lights);
    EXPECT_FALSE(resolve(Job{}, sphere_scene()).default_lights);

    // Ignoring the scene's lights with no environment brings the default pair back.
    Job no_scene_lights = job;
    no_scene_lights.lights.scene_lights = false;
    r = resolve(no_scene_lights, lit_scene());
    EXPECT_TRUE(r.default_lights);
    EXPECT_EQ(r.lights.size(), 2u);
    // ... and with the automatic environment, the studio.
    no_scene_lights.environment.kind = EnvKind::Automatic;
    r = resolve(no_scene_lights, lit_scene());
    EXPECT_TRUE(r.environment);
    EXPECT_TRUE(r.lights.empty());
}

TEST(JobTest, NoIblWinsOverAGivenEnvironment) {
    Job job;
    job.environment.kind = EnvKind::None;
    job.environment.path = "sky.hdr";  // ignored
    ResolvedJob r = resolve(job, lit_scene());
    EXPECT_FALSE(r.environment);
    EXPECT_EQ(r.lights.size(), 1u);
    EXPECT_FALSE(r.default_lights);
    job.output.energy_compensation = false;
    EXPECT_FALSE(resolve(job, lit_scene()).needs_brdf_lut);
    EXPECT_FALSE(resolve(job, lit_scene()).settings.energy_compensation);
}

TEST(JobTest, BackgroundRules) {
    auto mode = [](Mode m, EnvKind env) {
        Job job;
        job.background.mode = m;
        job.background.color = glm::vec3(0.2f, 0.3f, 0.4f);
        job.environment.kind = env;
        return resolve(job, sphere_scene()).settings;
    };
    // With an environment: blurred by default, sharp when asked, the colour when given.
    EXPECT_EQ(mode(Mode::Automatic, EnvKind::Studio).background_mode, Bg::Blurred);
    EXPECT_EQ(mode(Mode::Blurred, EnvKind::Studio).background_mode, Bg::Blurred);
    EXPECT_EQ(mode(Mode::Environment, EnvKind::Studio).background_mode, Bg::Environment);
    RenderSettings c = mode(Mode::Color, EnvKind::Studio);
    EXPECT_EQ(c.background_mode, Bg::Color);
    EXPECT_EQ(c.background, glm::vec4(0.2f, 0.3f, 0.4f, 1.0f));
    RenderSettings t = mode(Mode::Transparent, EnvKind::Studio);
    EXPECT_EQ(t.background_mode, Bg::Color);
    EXPECT_EQ(t.background.w, 0.0f);
    // Without one, every mode shows a colour; transparent stays transparent.
    for (Mode m : {Mode::Automatic, Mode::Blurred, Mode::Environment, Mode::Color})
        EXPECT_EQ(mode(m, EnvKind::None).background_mode, Bg::Color);
    EXPECT_EQ(mode(Mode::Color, EnvKind::None).background, glm::vec4(0.2f, 0.3f, 0.4f, 1.0f));
    EXPECT_EQ(mode(Mode::Transparent, EnvKind::None).background.w, 0.0f);
    Job job;
    job.background.mode = Mode::Transparent;
    EXPECT_TRUE(resolve(job, sphere_scene()).transparent());
    EXPECT_FALSE(resolve(Job{}, sphere_scene()).transparent());
    // The automatic background without an environment is black and opaque.
    job.background.mode = Mode::Automatic;
    job.environment.kind = EnvKind::None;
    EXPECT_EQ(resolve(job, sphere_scene()).settings.background, glm::vec4(0, 0, 0, 1));
}

TEST(JobTest, OutputSettings) {
    Job job;
    job.output.width = 320;
    job.output.height = 200;
    job.output.msaa = 1;
    job.output.tone_mapper = ToneMapper::Agx;
    job.output.exposure_ev = -1.5f;
    job.output.encoding = Encoding::Gamma22;
    job.output.debug = DebugChannel::Normal;
    RenderSettings rs = resolve(job, sphere_scene()).settings;
    EXPECT_EQ(rs.width, 320);
    EXPECT_EQ(rs.height, 200);
    EXPECT_EQ(rs.msaa, 1);
    EXPECT_EQ(rs.tone_mapper, ToneMapper::Agx);
    EXPECT_EQ(rs.exposure_ev, -1.5f);
    EXPECT_EQ(rs.encoding, Encoding::Gamma22);
    EXPECT_TRUE(rs.straight_alpha);
    EXPECT_EQ(rs.debug, DebugChannel::Normal);
    job.output.float_output = true;  // EXR, HDR: linear, premultiplied
    rs = resolve(job, sphere_scene()).settings;
    EXPECT_FALSE(rs.encoding);
    EXPECT_FALSE(rs.straight_alpha);
}

TEST(JobTest, OrbitCameraFollowsTheConvention) {
    Job job;
    job.output.width = job.output.height = 100;
    job.camera.yaw_deg = 90.0f;
    job.camera.distance_k = 3.0f;
    ResolvedJob r = resolve(job, sphere_scene());
    float R = std::sqrt(3.0f);  // half the diagonal of the [-1,1]^3 box
    EXPECT_NEAR(r.bounds.radius(), R, 1e-5f);
    EXPECT_NEAR(r.camera.eye.x, 3.0f * R, 1e-4f);  // yaw 90: from +X
    EXPECT_NEAR(r.camera.eye.z, 0.0f, 1e-4f);
    EXPECT_NEAR(r.camera.zfar, 5.0f * R, 1e-4f);
    EXPECT_EQ(r.camera.yfov_deg, 45.0f);
    EXPECT_EQ(r.instances.size(), 1u);
}

TEST(JobTest, SceneCameraAndItsErrors) {
    Scene s = camera_scene();
    Job job;
    job.source.model = "cams.gltf";
    job.camera.scene_camera = 1;
    job.camera.yaw_deg = 90.0f;  // unused with a scene camera
    ResolvedJob r = resolve(job, s);
    EXPECT_NEAR(r.camera.eye.z, 5.0f, 1e-5f);
    EXPECT_NEAR(r.camera.eye.x, 0.0f, 1e-5f);
    EXPECT_NEAR(r.camera.zfar, 50.0f, 1e-4f);
    EXPECT_NEAR(r.camera.yfov_deg, 0.5f * 180.0f / 3.14159265f, 1e-3f);

    job.camera.scene_camera = 0;  // in the file, but no node uses it
    EXPECT_EQ(error_of(job, s), "cams.gltf: --camera 0: no node of the scene uses camera 0 (the file has 2)");
    job.camera.scene_camera = 7;
    EXPECT_EQ(error_of(job, s), "cams.gltf: --camera 7: no node of the scene uses camera 7 (the file has 2)");
    job.source.model.clear();
    EXPECT_EQ(error_of(job, s), "demo: --camera 7: no node of the scene uses camera 7 (the file has 2)");

    // Scene 1 holds only the sphere: camera 1 is not in it.
    job.source.model = "cams.gltf";
    job.source.scene = 1;
    job.camera.scene_camera = 1;
    EXPECT_EQ(error_of(job, s), "cams.gltf: --camera 1: no node of the scene uses camera 1 (the file has 2)");
    job.camera.scene_camera.reset();
    r = resolve(job, s);
    EXPECT_EQ(r.scene_index, 1);
    EXPECT_EQ(r.instances.size(), 1u);
    job.source.scene = 2;
    EXPECT_EQ(error_of(job, s), "cams.gltf: --scene 2: the file has 2 scenes");
}

TEST(JobTest, LightingSettingsPointAtTheLoadedData) {
    Job job;
    job.environment.kind = EnvKind::None;
    job.output.energy_compensation = false;
    ResolvedJob r = resolve(job, sphere_scene());
    JobLighting none = load_lighting(r);  // nothing to load
    EXPECT_FALSE(none.environment);
    EXPECT_EQ(none.brdf_lut.width, 0);
    EXPECT_EQ(none.settings(r).environment, nullptr);
    EXPECT_EQ(none.settings(r).brdf_lut, nullptr);

    JobLighting lut;
    lut.brdf_lut = ImageF(4, 4);
    EXPECT_EQ(lut.settings(r).brdf_lut, &lut.brdf_lut);

    // A uniform environment bakes in closed form: cheap enough for a unit test.
    job.environment.kind = EnvKind::Color;
    job.environment.color = glm::vec3(0.5f);
    job.environment.bake_size = 32;
    job.environment.use_cache = false;
    r = resolve(job, sphere_scene());
    JobLighting l = load_lighting(r);
    ASSERT_TRUE(l.environment);
    EXPECT_FALSE(l.environment->from_cache);
    EXPECT_EQ(l.environment->source, r.environment->describe());
    EXPECT_NEAR(l.environment->irradiance.evaluate(glm::vec3(0, 1, 0)).y, 0.5f, 1e-3f);
    EXPECT_EQ(l.brdf_lut.width, 0);
    RenderSettings rs = l.settings(r);
    EXPECT_EQ(rs.environment, &*l.environment);
    EXPECT_EQ(rs.brdf_lut, nullptr);
    EXPECT_EQ(rs.background_mode, Bg::Blurred);
}

// The legacy shading rules: a frame drawn all in OpenGL 1's model (classic MTL materials under
// --shading auto, or any material under ogl1) has no automatic environment and ogl1-ref's
// default light; glTF materials under auto keep the glTF rules; fog takes the background colour.
TEST(JobTest, OpenGl1FramesTakeTheReferenceDefaults) {
    Scene s = sphere_scene();
    s.materials.push_back(Material{});  // a glTF material
    Job job;
    ResolvedJob r = resolve(job, s);
    EXPECT_FALSE(r.ogl1_frame);
    EXPECT_TRUE(r.environment.has_value());  // the studio, as before

    job.output.shading = ShadingModel::Ogl1Pixel;
    job.background.mode = Mode::Color;
    job.background.color = glm::vec3(0.2f, 0.3f, 0.4f);
    r = resolve(job, s);
    EXPECT_TRUE(r.ogl1_frame);
    EXPECT_FALSE(r.environment.has_value());
    EXPECT_FALSE(r.needs_brdf_lut);
    ASSERT_EQ(r.lights.size(), 1u);
    EXPECT_TRUE(r.default_lights);
    EXPECT_EQ(r.lights[0].radiance, glm::vec3(1.0f));
    EXPECT_NEAR(glm::dot(-r.lights[0].direction, direction_from_angles(30.0f, 45.0f)), -1.0f, 1e-6f);
    EXPECT_EQ(r.settings.shading, ShadingModel::Ogl1Pixel);
    EXPECT_EQ(r.settings.fog.color, glm::vec3(0.2f, 0.3f, 0.4f));

    // Auto: an MTL material without the PBR extension is OpenGL 1's, one with Pm is glTF's.
    job = Job{};
    s.materials[0].phong = PhongExt{};
    r = resolve(job, s);
    EXPECT_TRUE(r.ogl1_frame);
    EXPECT_EQ(material_shading(ShadingModel::Auto, s.materials[0]), ShadingModel::Ogl1);
    s.materials[0].phong->metallic = 0.5f;
    EXPECT_EQ(material_shading(ShadingModel::Auto, s.materials[0]), ShadingModel::Gltf);
    EXPECT_FALSE(resolve(job, s).ogl1_frame);
    // A given environment stays; lights given stay.
    s.materials[0].phong->metallic.reset();
    job.lights.extra.push_back(parse_light("dir:0,0,2"));
    r = resolve(job, s);
    ASSERT_EQ(r.lights.size(), 1u);
    EXPECT_EQ(r.lights[0].radiance, glm::vec3(2.0f));
    EXPECT_FALSE(r.default_lights);
}

TEST(JobTest, ShadingModelNames) {
    for (ShadingModel m : {ShadingModel::Auto, ShadingModel::Gltf, ShadingModel::Ogl1, ShadingModel::Ogl1Pixel,
                           ShadingModel::BlinnPhongNormalized})
        EXPECT_EQ(parse_shading_model(shading_model_name(m)), m);
    EXPECT_EQ(parse_shading_model("ogl1-pixel"), ShadingModel::Ogl1Pixel);
    EXPECT_FALSE(parse_shading_model("phong").has_value());
}

// Parts of a file turned off (fresnel/job/features.h, the setting `disable`): what a scene holds,
// how each is removed, and the setting's one spelling.
TEST(Features, WhatASceneHoldsAndTurningItOff) {
    Scene s = sphere_scene();
    Primitive& p = s.meshes[0].primitives[0];
    MorphTarget up;
    up.positions.assign(p.positions.size(), glm::vec3(0.0f, 1.0f, 0.0f));
    p.targets = {up};
    const glm::vec3 base = p.positions[0];
    s.meshes[0].weights = {0.5f};
    apply_morph_weights(p, s.meshes[0].weights);  // as the loader applies the mesh's weights
    s.skins.push_back(Skin{});
    s.nodes[0].skin = 0;
    Material m;
    m.occlusion.texture = 0;
    m.clearcoat.emplace();
    s.materials = {m, Material{}};
    s.extensions_used = {"KHR_materials_sheen", "KHR_texture_transform"};  // used by the file, held by no material
    EXPECT_EQ(scene_features(s), (std::vector<std::string>{"skinning", "morphing", "occlusion", "KHR_materials_clearcoat",
                                                            "KHR_materials_sheen"}));
    disable_features(s, {"skinning", "morphing", "occlusion", "KHR_materials_clearcoat"});
    EXPECT_EQ(s.nodes[0].skin, -1);
    EXPECT_TRUE(p.targets.empty());
    EXPECT_EQ(p.positions[0], base) << "back to the base shape";
    EXPECT_FALSE(s.materials[0].occlusion.valid());
    EXPECT_FALSE(s.materials[0].clearcoat.has_value());
    EXPECT_EQ(scene_features(s), (std::vector<std::string>{"KHR_materials_sheen"}));
    EXPECT_EQ(feature_name("clearcoat"), "KHR_materials_clearcoat");
    EXPECT_EQ(feature_name("KHR_materials_unlit"), "KHR_materials_unlit");
    EXPECT_EQ(feature_name("materials_clearcoat"), "");
    EXPECT_EQ(feature_name("morphing"), "morphing");
}

TEST(Features, TheDisableSettingHasOneSpelling) {
    Job job;
    settings::set(job, "disable", "clearcoat,skinning,clearcoat", "--disable");
    EXPECT_EQ(job.source.disabled, (std::vector<std::string>{"skinning", "KHR_materials_clearcoat"}));
    EXPECT_EQ(settings::get(job, "disable"), "skinning,KHR_materials_clearcoat");
    settings::set(job, "disable", "none", "--disable");
    EXPECT_TRUE(job.source.disabled.empty());
    try {
        settings::set(job, "disable", "skinning,glow", "--disable");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'glow' is not one of"), std::string::npos) << e.what();
    }
}

// A choice a front end cannot carry out is the registry's to say (the page draws no baked
// occlusion: it has no tracer), and its JSON says it to the page.
TEST(Settings, ChoicesNotOfferedToAFrontEnd) {
    const fresnel::settings::Setting& ao = fresnel::settings::at("render.ao");
    EXPECT_TRUE(ao.offered(fresnel::settings::kWeb));
    EXPECT_FALSE(ao.choice_offered("baked", fresnel::settings::kWeb));
    EXPECT_TRUE(ao.choice_offered("baked", fresnel::settings::kCli));
    EXPECT_TRUE(ao.choice_offered("ssao", fresnel::settings::kWeb));
    EXPECT_NE(fresnel::settings::describe_json().find(R"("choicesNotOffered":[{"choice":"baked","frontEnds":["web"]}])"),
              std::string::npos);
}
