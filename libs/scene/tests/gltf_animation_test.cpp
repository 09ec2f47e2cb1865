// Tests of the glTF loader's animations (samplers, channels, KHR_animation_pointer) on
// documents built in the test, and on the shared animated models when ../shared is present.
#include "fresnel/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <limits>

#include "fresnel/scene/pose.h"
#include "gltf_test_doc.h"

using namespace fresnel;
using namespace fresnel::gltf_test;

// ---- animations ---------------------------------------------------------------------------

namespace {
// One triangle node (0) with a morph target and a TRS node (1); animation samplers are added
// by the tests.
Doc animated_doc() {
    Doc doc;
    int pos = doc.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    int delta = doc.positions({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    doc.mesh({{"attributes", {{"POSITION", pos}}}, {"targets", json::array({{{"POSITION", delta}}})}});
    doc.j["nodes"].push_back({{"translation", {1, 2, 3}}});
    doc.j["scenes"][0]["nodes"].push_back(1);
    return doc;
}
}  // namespace

TEST(GltfAnimations, SamplersAndChannelsAreRead) {
    Doc doc = animated_doc();
    int times = doc.attribute(FLOAT, "SCALAR", {0, 1, 2});
    int trans = doc.attribute(FLOAT, "VEC3", {0, 0, 0, 1, 0, 0, 2, 0, 0});
    int rot = doc.attribute(SHORT, "VEC4", {0, 0, 0, 32767, 0, 0, 32767, 0, 0, 0, 0, 32767}, true);  // normalized
    int wts = doc.attribute(FLOAT, "SCALAR", {0, 0, 0.5, 0, 1, 0, 0, 0, 0});  // cubic: 3 per key, 1 target
    doc.j["animations"] = json::array({{{"name", "walk"},
                                        {"samplers", json::array({{{"input", times}, {"output", trans}},
                                                                  {{"input", times}, {"output", rot}, {"interpolation", "STEP"}},
                                                                  {{"input", times}, {"output", wts}, {"interpolation", "CUBICSPLINE"}}})},
                                        {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}},
                                                                  {{"sampler", 1}, {"target", {{"node", 1}, {"path", "rotation"}}}},
                                                                  {{"sampler", 2}, {"target", {{"node", 0}, {"path", "weights"}}}}})}}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    EXPECT_EQ(d.lines().size(), 0u);
    ASSERT_EQ(s.animations.size(), 1u);
    const Animation& a = s.animations[0];
    EXPECT_EQ(a.name, "walk");
    EXPECT_FLOAT_EQ(a.duration(), 2.0f);
    ASSERT_EQ(a.samplers.size(), 3u);
    EXPECT_EQ(a.samplers[0].width, 3);
    EXPECT_EQ(a.samplers[1].width, 4);
    EXPECT_EQ(a.samplers[1].interpolation, Interpolation::Step);
    EXPECT_NEAR(a.samplers[1].output[6], 1.0f, 1e-6f);  // dequantised
    EXPECT_EQ(a.samplers[2].width, 1);
    EXPECT_EQ(a.samplers[2].interpolation, Interpolation::CubicSpline);
    ASSERT_EQ(a.channels.size(), 3u);
    EXPECT_EQ(a.channels[2].path, AnimationPath::Weights);
    EXPECT_EQ(a.channels[2].node, 0);
    // The rest pose keeps its TRS and morph data for animation.
    EXPECT_EQ(s.nodes[1].translation, glm::vec3(1, 2, 3));
    EXPECT_TRUE(s.nodes[1].has_trs);
    const Primitive& p = s.meshes[0].primitives[0];
    ASSERT_EQ(p.targets.size(), 1u);
    EXPECT_EQ(p.targets[0].positions[2], glm::vec3(0, 0, 1));
    EXPECT_EQ(p.applied_weights, std::vector<float>{0.0f});
}

TEST(GltfAnimations, HostileAnimationsAreDroppedWithWarnings) {
    struct Case {
        const char* what;
        std::vector<double> times;
        std::vector<double> values;
        const char* type;
        const char* interpolation;
        const char* path;
    };
    std::vector<Case> cases = {
        {"times not increasing", {0, 1, 1}, {0, 0, 0, 1, 1, 1, 2, 2, 2}, "VEC3", "LINEAR", "translation"},
        {"times decreasing", {0, 2, 1}, {0, 0, 0, 1, 1, 1, 2, 2, 2}, "VEC3", "LINEAR", "translation"},
        {"non-finite time", {0, std::numeric_limits<double>::infinity()}, {0, 0, 0, 1, 1, 1}, "VEC3", "LINEAR", "scale"},
        {"too few values", {0, 1, 2}, {0, 0, 0, 1, 1, 1}, "VEC3", "LINEAR", "translation"},
        {"cubic needs three per key", {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", "CUBICSPLINE", "translation"},
        {"non-finite value", {0, 1}, {0, 0, 0, std::nan(""), 1, 1}, "VEC3", "LINEAR", "translation"},
        {"rotation from vec3", {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", "LINEAR", "rotation"},
        {"unknown interpolation", {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", "SMOOTH", "translation"},
        {"unknown path", {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3", "LINEAR", "colour"},
        {"weights not whole", {0, 1}, {0, 1, 2}, "SCALAR", "LINEAR", "weights"},
    };
    for (const auto& c : cases) {
        Doc doc = animated_doc();
        int times = doc.attribute(FLOAT, "SCALAR", c.times);
        int values = doc.attribute(FLOAT, c.type, c.values);
        doc.j["animations"] = json::array(
            {{{"samplers", json::array({{{"input", times}, {"output", values}, {"interpolation", c.interpolation}}})},
              {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 1}, {"path", c.path}}}}})}}});
        Diagnostics d;
        Scene s;
        ASSERT_NO_THROW(s = load(doc.gltf(), d)) << c.what;
        EXPECT_TRUE(s.animations.empty()) << c.what;
        EXPECT_GE(d.lines().size(), 1u) << c.what;
        EXPECT_EQ(s.meshes.size(), 1u) << c.what;  // the rest pose still loads
    }
    // Accessor and sampler indices out of range, missing input.
    for (json bad : {json{{"samplers", json::array({{{"input", 99}, {"output", 0}}})}, {"channels", json::array()}},
                     json{{"samplers", json::array({{{"output", 0}}})}, {"channels", json::array()}},
                     json{{"samplers", json::array()}, {"channels", json::array({{{"sampler", 3}, {"target", {{"node", 1}, {"path", "scale"}}}}})}},
                     json{{"samplers", json::array()}, {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 42}, {"path", "scale"}}}}})}},
                     json("not an object")}) {
        Doc doc = animated_doc();
        doc.j["animations"] = json::array({bad});
        Diagnostics d;
        Scene s;
        ASSERT_NO_THROW(s = load(doc.gltf(), d)) << bad.dump();
        EXPECT_TRUE(s.animations.empty()) << bad.dump();
        EXPECT_GE(d.lines().size(), 1u);
    }
}

TEST(GltfAnimations, MatrixNodesAndPointerChannelsAreSkipped) {
    Doc doc = animated_doc();
    doc.j["nodes"][1].erase("translation");
    doc.j["nodes"][1]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    int times = doc.attribute(FLOAT, "SCALAR", {0, 1});
    int values = doc.attribute(FLOAT, "VEC3", {0, 0, 0, 1, 1, 1});
    doc.j["animations"] = json::array(
        {{{"samplers", json::array({{{"input", times}, {"output", values}}})},
          {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}},
                                    {{"sampler", 0}, {"target", {{"path", "pointer"}}}},
                                    {{"sampler", 0}, {"target", {{"path", "scale"}}}} /* no node: ignored */})}}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    ASSERT_EQ(s.animations.size(), 1u);
    EXPECT_TRUE(s.animations[0].channels.empty());
    EXPECT_EQ(d.lines().size(), 2u);  // the matrix node, the pointer channel
    EXPECT_FALSE(s.nodes[1].has_trs);
}

TEST(GltfAnimations, UnreadableSkinIsIgnoredWithoutPosing) {
    Doc doc = animated_doc();
    doc.j["skins"] = json::array({{{"joints", {1}}, {"inverseBindMatrices", 0}}});  // accessor 0 is VEC3
    doc.j["nodes"][0]["skin"] = 0;
    Diagnostics d;
    Scene s;
    ASSERT_NO_THROW(s = load(doc.gltf(), d));
    ASSERT_EQ(s.skins.size(), 1u);
    EXPECT_TRUE(s.skins[0].joints.empty());
    EXPECT_EQ(d.lines().size(), 1u);
    GltfLoadOptions opt;
    opt.pose_skins = true;
    Diagnostics d2;
    EXPECT_THROW(load(doc.gltf(), d2, opt), Error);
}

TEST(GltfAnimations, SharedModelsHaveTheirAnimations) {
    const fs::path root = fs::path(FRESNEL_SHARED_DIR) / "assets" / "models";
    struct Model { const char* file; std::size_t skins; bool morph; };
    int found = 0;
    for (Model m : {Model{"CesiumMan/CesiumMan.glb", 1, false}, Model{"BrainStem/BrainStem.glb", 1, false},
                    Model{"AnimatedMorphCube/AnimatedMorphCube.glb", 0, true}}) {
        fs::path path = root / m.file;
        if (!fs::exists(path)) continue;
        ++found;
        Diagnostics d;
        GltfLoadOptions opt;
        opt.decode_images = false;
        Scene s = load_gltf(path, d, opt);
        ASSERT_GE(s.animations.size(), 1u) << m.file;
        EXPECT_GT(s.animations[0].duration(), 0.0f) << m.file;
        EXPECT_GE(s.skins.size(), m.skins) << m.file;
        for (const auto& a : s.animations)
            for (const auto& smp : a.samplers) EXPECT_TRUE(smp.consistent()) << m.file;
        bool has_targets = false;
        for (const auto& mesh : s.meshes)
            for (const auto& p : mesh.primitives) has_targets = has_targets || !p.targets.empty();
        EXPECT_EQ(has_targets, m.morph) << m.file;
        EXPECT_EQ(d.lines().size(), 0u) << m.file;
    }
    if (found == 0) GTEST_SKIP() << "no animated models under " << root;
}

// ---- KHR_animation_pointer ------------------------------------------------------------------

namespace {
// animated_doc plus a textured material on the mesh, a spot light and a perspective camera.
Doc pointer_doc() {
    Doc doc = animated_doc();
    doc.j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}},
                                                                  {"baseColorTexture", {{"index", 0}}}}}}});
    doc.j["meshes"][0]["primitives"][0]["material"] = 0;
    doc.j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = doc.attribute(FLOAT, "VEC2", {0, 0, 1, 0, 0, 1});
    doc.j["images"] = json::array({{{"uri", "data:image/png;base64," + base64(make_png(2, 2))}}});
    doc.j["textures"] = json::array({{{"source", 0}}});
    doc.j["extensionsUsed"] = {"KHR_lights_punctual", "KHR_animation_pointer"};
    doc.j["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"type", "spot"}, {"intensity", 10}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}}});
    doc.j["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}});
    return doc;
}
json pointer_channel(int sampler, const std::string& pointer) {
    return {{"sampler", sampler},
            {"target", {{"path", "pointer"}, {"extensions", {{"KHR_animation_pointer", {{"pointer", pointer}}}}}}}};
}
}  // namespace

TEST(GltfAnimationPointer, MaterialLightCameraAndNodePropertiesAreAnimated) {
    Doc doc = pointer_doc();
    int times = doc.attribute(FLOAT, "SCALAR", {0, 2});
    int colour = doc.attribute(FLOAT, "VEC4", {1, 1, 1, 1, 0, 0.5, 1, 0.5});
    int rgb = doc.attribute(FLOAT, "VEC3", {0, 0, 0, 4, 2, 0});
    int scalar = doc.attribute(FLOAT, "SCALAR", {0, 1});
    int intensity = doc.attribute(FLOAT, "SCALAR", {10, 30});
    int yfov = doc.attribute(FLOAT, "SCALAR", {0.8, 0.4});
    int offset = doc.attribute(FLOAT, "VEC2", {0, 0, 1, 0.5});
    int trans = doc.attribute(FLOAT, "VEC3", {0, 0, 0, 2, 4, 6});
    auto smp = [&](int output) { return json{{"input", times}, {"output", output}}; };
    doc.j["animations"] = json::array(
        {{{"samplers", json::array({smp(colour), smp(rgb), smp(scalar), smp(intensity), smp(yfov), smp(offset), smp(trans)})},
          {"channels", json::array({pointer_channel(0, "/materials/0/pbrMetallicRoughness/baseColorFactor"),
                                    pointer_channel(1, "/materials/0/emissiveFactor"),
                                    pointer_channel(2, "/materials/0/extensions/KHR_materials_clearcoat/clearcoatFactor"),
                                    pointer_channel(3, "/extensions/KHR_lights_punctual/lights/0/intensity"),
                                    pointer_channel(4, "/cameras/0/perspective/yfov"),
                                    pointer_channel(5, "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/"
                                                       "KHR_texture_transform/offset"),
                                    pointer_channel(6, "/nodes/1/translation")})}}});
    Diagnostics d;
    Scene s = load(doc.gltf(), d);
    EXPECT_EQ(d.lines().size(), 0u) << all_warnings(d);
    ASSERT_EQ(s.animations.size(), 1u);
    const Animation& a = s.animations[0];
    ASSERT_EQ(a.channels.size(), 7u);
    EXPECT_EQ(a.channels[0].path, AnimationPath::Pointer);
    EXPECT_EQ(a.channels[6].path, AnimationPath::Translation);  // a node's TRS: an ordinary channel
    EXPECT_EQ(a.channels[6].node, 1);
    // The rest pose is untouched: no clearcoat block was added by the loader's checks.
    EXPECT_FALSE(s.materials[0].clearcoat.has_value());
    EXPECT_FALSE(s.materials[0].base_color.has_transform);

    animate(s, 0, 1.0f);  // half way
    const Material& m = s.materials[0];
    EXPECT_NEAR(m.base_color_factor.y, 0.75f, 1e-6f);
    EXPECT_NEAR(m.base_color_factor.w, 0.75f, 1e-6f);
    EXPECT_NEAR(m.emissive_factor.x, 2.0f, 1e-6f);  // not clamped above 1
    ASSERT_TRUE(m.clearcoat.has_value());          // added with the extension's defaults, then animated
    EXPECT_NEAR(m.clearcoat->clearcoat_factor, 0.5f, 1e-6f);
    EXPECT_TRUE(m.has_clearcoat());
    EXPECT_NEAR(s.lights[0].intensity, 20.0f, 1e-5f);
    EXPECT_NEAR(s.cameras[0].yfov, 0.6f, 1e-6f);
    ASSERT_TRUE(m.base_color.has_transform);
    EXPECT_NEAR(m.base_color.transform_params.offset.x, 0.5f, 1e-6f);
    EXPECT_NEAR(m.base_color.transform[2][0], 0.5f, 1e-6f);  // the matrix follows the parameters
    EXPECT_NEAR(s.nodes[1].translation.y, 2.0f, 1e-6f);

    animate(s, 0, 5.0f);  // past the end: the last keyframe
    EXPECT_NEAR(s.materials[0].base_color_factor.x, 0.0f, 1e-6f);
    EXPECT_NEAR(s.lights[0].intensity, 30.0f, 1e-5f);
}

TEST(GltfAnimationPointer, ValuesStayInTheirValidRange) {
    Scene s;
    s.materials.resize(1);
    s.lights.resize(1);
    s.lights[0].type = Light::Type::Spot;
    s.lights[0].inner_cone_angle = 0.2f;
    s.lights[0].outer_cone_angle = 0.5f;
    const float four[4] = {-1, 2, 0.5f, 3};
    EXPECT_TRUE(write_animation_pointer(s, "/materials/0/pbrMetallicRoughness/baseColorFactor", four));
    EXPECT_EQ(s.materials[0].base_color_factor, glm::vec4(0, 1, 0.5f, 1));
    const float big[1] = {7.0f};
    EXPECT_TRUE(write_animation_pointer(s, "/materials/0/pbrMetallicRoughness/roughnessFactor", big));
    EXPECT_EQ(s.materials[0].roughness_factor, 1.0f);
    const float negative[1] = {-3.0f};
    EXPECT_TRUE(write_animation_pointer(s, "/extensions/KHR_lights_punctual/lights/0/intensity", negative));
    EXPECT_EQ(s.lights[0].intensity, 0.0f);
    const float narrow[1] = {0.1f};  // outer below inner: inner follows
    EXPECT_TRUE(write_animation_pointer(s, "/extensions/KHR_lights_punctual/lights/0/spot/outerConeAngle", narrow));
    EXPECT_LT(s.lights[0].inner_cone_angle, s.lights[0].outer_cone_angle);
    const float nan[1] = {std::numeric_limits<float>::quiet_NaN()};
    EXPECT_TRUE(write_animation_pointer(s, "/materials/0/pbrMetallicRoughness/metallicFactor", nan));
    EXPECT_EQ(s.materials[0].metallic_factor, 1.0f);  // unchanged
    EXPECT_FALSE(write_animation_pointer(s, "/materials/0/pbrMetallicRoughness/metallicFactor", {}));
}

TEST(GltfAnimationPointer, HostilePointersAreIgnoredWithWarnings) {
    const std::vector<std::string> bad = {
        "",
        "materials/0/emissiveFactor",                       // not absolute
        "/materials/1/emissiveFactor",                      // no material 1
        "/materials/-1/emissiveFactor",
        "/materials/00/emissiveFactor",                     // leading zero
        "/materials/99999999999999999999/emissiveFactor",
        "/materials/0/emissiveFactor/",                     // empty token
        "/materials/0//emissiveFactor",
        "/materials/0/emissive~1Factor",                    // escapes
        "/materials/0/unknownFactor",
        "/materials/0/normalTexture/extensions/KHR_texture_transform/texCoord",
        "/materials/0/extensions/KHR_materials_foo/bar",
        "/extensions/KHR_lights_punctual/lights/3/color",
        "/extensions/KHR_lights_punctual/lights/0/range/x",
        "/cameras/0/orthographic/xmag",                     // the camera is perspective
        "/cameras/0/perspective",
        "/nodes/0/matrix",
        "/nodes/7/translation",
        "/meshes/0/weights",
        "/",
        std::string(5000, '/'),
    };
    for (const auto& pointer : bad) {
        Doc doc = pointer_doc();
        int times = doc.attribute(FLOAT, "SCALAR", {0, 1});
        int values = doc.attribute(FLOAT, "VEC3", {0, 0, 0, 1, 1, 1});
        doc.j["animations"] = json::array({{{"samplers", json::array({{{"input", times}, {"output", values}}})},
                                            {"channels", json::array({pointer_channel(0, pointer)})}}});
        Diagnostics d;
        Scene s;
        ASSERT_NO_THROW(s = load(doc.gltf(), d)) << pointer;
        ASSERT_EQ(s.animations.size(), 1u) << pointer;
        EXPECT_TRUE(s.animations[0].channels.empty()) << pointer;
        EXPECT_EQ(d.lines().size(), 1u) << pointer << all_warnings(d);
        ASSERT_NO_THROW(animate(s, 0, 0.5f)) << pointer;
    }
    // A sampler whose values do not fit the property: VEC3 into a VEC4 colour, VEC3 into a scalar.
    for (const char* pointer : {"/materials/0/pbrMetallicRoughness/baseColorFactor", "/cameras/0/perspective/yfov"}) {
        Doc doc = pointer_doc();
        int times = doc.attribute(FLOAT, "SCALAR", {0, 1});
        int values = doc.attribute(FLOAT, "VEC3", {0, 0, 0, 1, 1, 1});
        doc.j["animations"] = json::array({{{"samplers", json::array({{{"input", times}, {"output", values}}})},
                                            {"channels", json::array({pointer_channel(0, pointer)})}}});
        Diagnostics d;
        Scene s = load(doc.gltf(), d);
        EXPECT_TRUE(s.animations.at(0).channels.empty()) << pointer;
        EXPECT_TRUE(has_warning(d, "/animations/0/channels/0/sampler", "do not fit")) << pointer << all_warnings(d);
    }
}
