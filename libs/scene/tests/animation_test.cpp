// Animation evaluation (fresnel/scene/animation.h) and CPU posing (fresnel/scene/pose.h)
// against values worked out by hand from glTF 2.0 Appendix C.
#include "fresnel/scene/animation.h"

#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/scene/mesh_ops.h"
#include "fresnel/scene/pose.h"
#include "fresnel/core/error.h"

using namespace fresnel;

namespace {

constexpr float kPi = 3.14159265358979f;

AnimationSampler make(Interpolation i, std::vector<float> in, std::vector<float> out, int width) {
    AnimationSampler s;
    s.interpolation = i;
    s.input = std::move(in);
    s.output = std::move(out);
    s.width = width;
    return s;
}

// Unit quaternion about +Z by `deg` degrees, as glTF stores it (x, y, z, w).
std::vector<float> quat_z(float deg) {
    float h = deg * kPi / 360.0f;
    return {0.0f, 0.0f, std::sin(h), std::cos(h)};
}

// Angle (degrees) of rotation q about +Z, from where it takes +X.
float z_angle(const glm::quat& q) {
    glm::vec3 x = q * glm::vec3(1, 0, 0);
    return std::atan2(x.y, x.x) * 180.0f / kPi;
}

}  // namespace

TEST(AnimationSample, LinearTranslationClampsOutsideTheKeyframes) {
    auto s = make(Interpolation::Linear, {1, 3}, {0, 0, 0, 2, 4, 6}, 3);
    ASSERT_TRUE(s.consistent());
    auto v = sample(s, 1.5f);  // a quarter of the way
    EXPECT_NEAR(v[0], 0.5f, 1e-6f);
    EXPECT_NEAR(v[1], 1.0f, 1e-6f);
    EXPECT_NEAR(v[2], 1.5f, 1e-6f);
    EXPECT_EQ(sample(s, 0.0f), (std::vector<float>{0, 0, 0}));   // before the first: the first
    EXPECT_EQ(sample(s, 10.0f), (std::vector<float>{2, 4, 6}));  // after the last: the last
    EXPECT_EQ(sample(s, 3.0f), (std::vector<float>{2, 4, 6}));
    EXPECT_EQ(sample(s, std::nanf("")), (std::vector<float>{0, 0, 0}));
}

TEST(AnimationSample, StepHoldsThePreviousKeyframe) {
    auto s = make(Interpolation::Step, {0, 1, 2}, {10, 20, 30}, 1);
    EXPECT_EQ(sample(s, 0.99f)[0], 10.0f);
    EXPECT_EQ(sample(s, 1.0f)[0], 20.0f);  // a keyframe's own time takes its value
    EXPECT_EQ(sample(s, 1.5f)[0], 20.0f);
    EXPECT_EQ(sample(s, 5.0f)[0], 30.0f);
    EXPECT_EQ(sample(s, -1.0f)[0], 10.0f);
}

TEST(AnimationSample, CubicSplineUsesTangentsScaledByTheInterval) {
    // Keyframes at 0 and 2: v0 = 0 with out-tangent 1, v1 = 1 with in-tangent -1 (layout: in, value, out).
    auto s = make(Interpolation::CubicSpline, {0, 2}, {/*k0*/ 5, 0, 1, /*k1*/ -1, 1, 7}, 1);
    ASSERT_TRUE(s.consistent());
    // u = 0.5, dt = 2: h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125:
    // 0.125*2*1 + 0.5*1 + (-0.125)*2*(-1) = 1.0.
    EXPECT_NEAR(sample(s, 1.0f)[0], 1.0f, 1e-6f);
    // u = 0.25: h10 = 0.140625, h01 = 0.15625, h11 = -0.046875: 0.28125 + 0.15625 + 0.09375.
    EXPECT_NEAR(sample(s, 0.5f)[0], 0.53125f, 1e-6f);
    // The keyframes' own values (not the tangents) at and beyond the ends.
    EXPECT_NEAR(sample(s, 0.0f)[0], 0.0f, 1e-6f);
    EXPECT_NEAR(sample(s, 2.0f)[0], 1.0f, 1e-6f);
    EXPECT_NEAR(sample(s, 9.0f)[0], 1.0f, 1e-6f);
}

TEST(AnimationSample, CubicSplineMultiComponentWeights) {
    // Two morph weights per keyframe; zero tangents: the smoothstep 3u^2 - 2u^3 per weight.
    auto s = make(Interpolation::CubicSpline, {0, 1}, {0, 0, 0, 1, 0, 0, 0, 0, 1, 2, 0, 0}, 2);
    ASSERT_TRUE(s.consistent());
    auto v = sample(s, 0.25f);
    float h = 3 * 0.0625f - 2 * 0.015625f;  // 0.15625
    EXPECT_NEAR(v[0], h * 1.0f, 1e-6f);
    EXPECT_NEAR(v[1], 1.0f + h * (2.0f - 1.0f), 1e-6f);
}

TEST(AnimationSample, LinearWeightsAndInconsistentSamplers) {
    auto s = make(Interpolation::Linear, {0, 1}, {0, 1, 1, 0}, 2);
    auto v = sample(s, 0.25f);
    EXPECT_NEAR(v[0], 0.25f, 1e-6f);
    EXPECT_NEAR(v[1], 0.75f, 1e-6f);
    auto bad = make(Interpolation::CubicSpline, {0, 1}, {0, 1, 1, 0}, 2);  // needs 3 values per keyframe
    EXPECT_FALSE(bad.consistent());
    std::vector<float> out{42, 42};
    sample(bad, 0.5f, out);
    EXPECT_EQ(out[0], 42.0f);  // nothing written
}

TEST(AnimationRotation, LinearIsSlerpNotNlerp) {
    std::vector<float> out = quat_z(0);
    auto q90 = quat_z(90);
    out.insert(out.end(), q90.begin(), q90.end());
    auto s = make(Interpolation::Linear, {0, 1}, out, 4);
    // Slerp: a quarter of the time is a quarter of the angle, 22.5 degrees (nlerp gives 21.6).
    EXPECT_NEAR(z_angle(sample_rotation(s, 0.25f)), 22.5f, 1e-3f);
    EXPECT_NEAR(z_angle(sample_rotation(s, 0.5f)), 45.0f, 1e-3f);
    EXPECT_NEAR(glm::length(sample_rotation(s, 0.7f)), 1.0f, 1e-6f);
}

TEST(AnimationRotation, LinearTakesTheShortestPath) {
    // The second keyframe is the negated quaternion of +90 degrees: the same rotation. The
    // shorter arc goes through +45 degrees, not through -135.
    std::vector<float> out = quat_z(0);
    for (float c : quat_z(90)) out.push_back(-c);
    auto s = make(Interpolation::Linear, {0, 1}, out, 4);
    EXPECT_NEAR(z_angle(sample_rotation(s, 0.5f)), 45.0f, 1e-3f);
    // And from 170 to -170 degrees (190): through 180, 20 degrees of travel.
    std::vector<float> out2 = quat_z(170);
    for (float c : quat_z(-170)) out2.push_back(c);
    auto s2 = make(Interpolation::Linear, {0, 1}, out2, 4);
    EXPECT_NEAR(std::abs(z_angle(sample_rotation(s2, 0.5f))), 180.0f, 1e-2f);
    EXPECT_NEAR(z_angle(sample_rotation(s2, 0.25f)), 175.0f, 1e-2f);
}

TEST(AnimationRotation, StepAndCubicSplineAreNormalised) {
    std::vector<float> out = {0, 0, 0, 2};  // not unit: normalised to the identity
    for (float c : quat_z(90)) out.push_back(c);
    auto step = make(Interpolation::Step, {0, 1}, out, 4);
    glm::quat q = sample_rotation(step, 0.5f);
    EXPECT_NEAR(q.w, 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
    // Cubic with zero tangents at u = 0.5: (v0 + v1) / 2, normalised = 45 degrees.
    std::vector<float> cubic = {0, 0, 0, 0};
    for (float c : quat_z(0)) cubic.push_back(c);
    cubic.insert(cubic.end(), {0, 0, 0, 0, 0, 0, 0, 0});
    for (float c : quat_z(90)) cubic.push_back(c);
    cubic.insert(cubic.end(), {0, 0, 0, 0});
    auto cs = make(Interpolation::CubicSpline, {0, 1}, cubic, 4);
    ASSERT_TRUE(cs.consistent());
    glm::quat c = sample_rotation(cs, 0.5f);
    EXPECT_NEAR(glm::length(c), 1.0f, 1e-6f);
    EXPECT_NEAR(z_angle(c), 45.0f, 1e-3f);
}

TEST(AnimationClip, StartEndDuration) {
    Animation a;
    a.samplers.push_back(make(Interpolation::Linear, {0.5f, 2}, {0, 1}, 1));
    a.samplers.push_back(make(Interpolation::Step, {1, 3.5f}, {0, 1}, 1));
    EXPECT_FLOAT_EQ(a.start(), 0.5f);
    EXPECT_FLOAT_EQ(a.end(), 3.5f);
    EXPECT_FLOAT_EQ(a.duration(), 3.0f);
    EXPECT_FLOAT_EQ(Animation{}.duration(), 0.0f);
}

namespace {

// A scene with one triangle on node 0 (mesh 0, two morph targets) and a joint node 1.
Scene test_scene() {
    Scene s;
    s.source = "test";
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    MorphTarget up, right;
    up.positions = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    right.positions = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}};
    p.targets = {up, right};
    p.applied_weights = {0.0f, 0.0f};
    Mesh m;
    m.primitives.push_back(p);
    m.weights = {0.0f, 0.0f};
    s.meshes.push_back(m);
    Node n0;
    n0.mesh = 0;
    Node n1;
    s.nodes = {n0, n1};
    s.scenes = {{0, 1}};
    return s;
}

// test_scene's triangle skinned to joint node 1 (the third vertex with weight `w2`), and
// animation 0 turning the joint from 0 to 90 degrees about +Z over 2 s.
Scene skinned_scene(float w2) {
    Scene s = test_scene();
    Primitive& p = s.meshes[0].primitives[0];
    p.joints = {glm::uvec4(0), glm::uvec4(0), glm::uvec4(0)};
    p.weights = {glm::vec4(1, 0, 0, 0), glm::vec4(1, 0, 0, 0), glm::vec4(w2, 0, 0, 0)};
    s.nodes[0].skin = 0;
    Skin skin;
    skin.joints = {1};
    skin.inverse_bind = {glm::mat4(1.0f)};
    s.skins.push_back(skin);
    Animation a;
    std::vector<float> rot = quat_z(0);
    for (float c : quat_z(90)) rot.push_back(c);
    a.samplers.push_back(make(Interpolation::Linear, {0, 2}, rot, 4));
    a.channels = {{0, 1, AnimationPath::Rotation, ""}};
    s.animations.push_back(a);
    return s;
}

}  // namespace

TEST(AnimationPose, AnimateSetsTrsAndLocalMatrix) {
    Scene s = test_scene();
    Animation a;
    a.samplers.push_back(make(Interpolation::Linear, {0, 1}, {0, 0, 0, 4, 0, 0}, 3));
    std::vector<float> rot = quat_z(0);
    for (float c : quat_z(90)) rot.push_back(c);
    a.samplers.push_back(make(Interpolation::Linear, {0, 1}, rot, 4));
    a.samplers.push_back(make(Interpolation::Step, {0}, {2, 2, 2}, 3));
    a.channels = {{0, 1, AnimationPath::Translation, ""}, {1, 1, AnimationPath::Rotation, ""}, {2, 1, AnimationPath::Scale, ""},
                  {0, 7, AnimationPath::Translation, ""} /* node out of range: ignored */};
    s.animations.push_back(a);
    animate(s, 0, 0.5f);
    const Node& n = s.nodes[1];
    EXPECT_NEAR(n.translation.x, 2.0f, 1e-6f);
    EXPECT_NEAR(z_angle(n.rotation), 45.0f, 1e-3f);
    EXPECT_EQ(n.scale, glm::vec3(2.0f));
    glm::vec3 p = glm::vec3(n.local * glm::vec4(1, 0, 0, 1));  // T * R * S: scaled, turned 45, moved 2
    EXPECT_NEAR(p.x, 2.0f + 2.0f * std::cos(kPi / 4), 1e-5f);
    EXPECT_NEAR(p.y, 2.0f * std::sin(kPi / 4), 1e-5f);
    EXPECT_THROW(animate(s, 1, 0.0f), Error);
    EXPECT_NO_THROW(animate(s, -1, 0.0f));
}

TEST(AnimationPose, MorphWeightsOnTheCpu) {
    Scene s = test_scene();
    Animation a;
    a.samplers.push_back(make(Interpolation::Linear, {0, 1}, {0, 0, 1, 0.5f}, 2));
    a.channels = {{0, 0, AnimationPath::Weights, ""}};
    s.animations.push_back(a);
    Scene posed = animated_scene(s, 0, 0.5f);  // weights (0.5, 0.25)
    const Node& n = posed.nodes[0];
    ASSERT_EQ(n.weights.size(), 2u);
    EXPECT_FLOAT_EQ(n.weights[0], 0.5f);
    EXPECT_FLOAT_EQ(n.weights[1], 0.25f);
    ASSERT_NE(n.mesh, 0);  // a posed copy; the rest mesh is untouched
    EXPECT_FALSE(n.world_space_mesh);
    const Primitive& p = posed.meshes[std::size_t(n.mesh)].primitives[0];
    EXPECT_NEAR(p.positions[1].x, 1.25f, 1e-6f);
    EXPECT_NEAR(p.positions[1].z, 0.5f, 1e-6f);
    EXPECT_EQ(posed.meshes[0].primitives[0].positions[1], glm::vec3(1, 0, 0));
    // Moving from one set of weights to another is the same as from zero.
    Primitive q = p;
    apply_morph_weights(q, std::vector<float>{1.0f, 0.0f});
    EXPECT_NEAR(q.positions[1].x, 1.0f, 1e-6f);
    EXPECT_NEAR(q.positions[1].z, 1.0f, 1e-6f);
    EXPECT_EQ(q.applied_weights, (std::vector<float>{1.0f, 0.0f}));
    // At the rest weights nothing is copied.
    Scene rest = animated_scene(test_scene(), -1, 0.0f);
    EXPECT_EQ(rest.nodes[0].mesh, 0);
}

TEST(AnimationPose, MorphRenormalisesNormalsAndRegeneratesFlatOnes) {
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    p.generated_normals = true;
    MorphTarget t;
    t.positions = {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}};  // tilt the triangle about x
    p.targets = {t};
    apply_morph_weights(p, std::vector<float>{1.0f});
    glm::vec3 expected = glm::normalize(glm::vec3(0, -1, 1));
    for (const auto& n : p.normals) {
        EXPECT_NEAR(n.x, expected.x, 1e-6f);
        EXPECT_NEAR(n.y, expected.y, 1e-6f);
        EXPECT_NEAR(n.z, expected.z, 1e-6f);
    }
    Primitive q;
    q.positions = {{0, 0, 0}};
    q.normals = {{0, 0, 1}};
    q.tangents = {{1, 0, 0, -1}};
    MorphTarget u;
    u.normals = {{1, 0, -1}};
    u.tangents = {{-1, 1, 0}};
    q.targets = {u};
    apply_morph_weights(q, std::vector<float>{1.0f});
    EXPECT_NEAR(q.normals[0].x, 1.0f, 1e-6f);  // (1, 0, 0) after renormalising
    EXPECT_NEAR(q.tangents[0].y, 1.0f, 1e-6f);
    EXPECT_EQ(q.tangents[0].w, -1.0f);
}

TEST(AnimationPose, SkinFollowsTheAnimatedJoint) {
    Scene s = skinned_scene(0.5f);
    Scene posed = animated_scene(s, 0, 2.0f);  // the joint turned 90 degrees about +Z
    const Node& n = posed.nodes[0];
    ASSERT_TRUE(n.world_space_mesh);
    const Primitive& q = posed.meshes[std::size_t(n.mesh)].primitives[0];
    EXPECT_NEAR(q.positions[1].x, 0.0f, 1e-6f);  // (1, 0, 0) -> (0, 1, 0)
    EXPECT_NEAR(q.positions[1].y, 1.0f, 1e-6f);
    // Weight 0.5 alone (glTF weights should sum to 1): divided by the blended w, as the
    // Khronos viewer's perspective divide does, it acts as 1: R * (0, 1, 0) = (-1, 0, 0).
    EXPECT_NEAR(q.positions[2].x, -1.0f, 1e-6f);
    EXPECT_NEAR(q.normals[0].z, 1.0f, 1e-6f);
    // Same as pose_skinned with the joint matrices of the animated world matrices.
    std::vector<glm::mat4> world = world_matrices(posed.nodes);
    auto mats = joint_matrices(world, posed.skins[0].joints, posed.skins[0].inverse_bind);
    Primitive r = s.meshes[0].primitives[0];
    pose_skinned(r, mats, world[0], SkinWeights::Homogeneous);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(glm::length(r.positions[i] - q.positions[i]), 0.0f, 1e-6f);
}

// A skinned, morphing, moving scene posed again and again in place (ScenePoser) is at every
// time what animated_scene makes from the rest pose, and goes back to the rest pose exactly.
TEST(ScenePoser, PosesInPlaceAsAnimatedSceneDoesAndRestsAgain) {
    Scene s = skinned_scene(1.0f);  // animation 0 turns the joint; animation 1 morphs the triangle
    Animation morph;
    morph.samplers.push_back(make(Interpolation::Linear, {0, 1}, {0, 0, 1, 0.5f}, 2));
    morph.channels = {{0, 0, AnimationPath::Weights, ""}};
    s.animations.push_back(morph);
    const Scene rest = s;
    ScenePoser poser(s);
    for (int index : {-1, 0, 1, -1})
        for (float t : {0.3f, 1.7f, 0.9f}) {
            poser.pose(index, t, true);
            const Scene want = animated_scene(rest, index, t);
            ASSERT_EQ(s.meshes.size(), want.meshes.size()) << index << " " << t;
            for (std::size_t n = 0; n < s.nodes.size(); ++n) {
                EXPECT_EQ(s.nodes[n].local, want.nodes[n].local);
                EXPECT_EQ(s.nodes[n].mesh, want.nodes[n].mesh);
                EXPECT_EQ(s.nodes[n].weights, want.nodes[n].weights);
            }
            for (std::size_t m = 0; m < s.meshes.size(); ++m)
                EXPECT_EQ(s.meshes[m].primitives[0].positions, want.meshes[m].primitives[0].positions) << index << " " << t;
        }
    s.nodes[1].visible = false;  // not something animations change: kept across poses
    poser.pose(0, 1.0f, false);   // the GPU's way: the nodes move, the meshes stay as loaded
    EXPECT_EQ(s.meshes.size(), rest.meshes.size());
    EXPECT_FALSE(s.nodes[1].visible);
    EXPECT_NEAR(z_angle(s.nodes[1].rotation), 45.0f, 1e-3f);
    EXPECT_THROW(poser.pose(2, 0.0f, true), Error);
    poser.rest();
    ASSERT_EQ(s.meshes.size(), rest.meshes.size());
    EXPECT_EQ(s.meshes[0].primitives[0].positions, rest.meshes[0].primitives[0].positions);
    for (std::size_t n = 0; n < s.nodes.size(); ++n) {
        EXPECT_EQ(s.nodes[n].local, rest.nodes[n].local);
        EXPECT_EQ(s.nodes[n].mesh, rest.nodes[n].mesh);
        EXPECT_FALSE(s.nodes[n].world_space_mesh);
    }
}

// A posed scene keeps the rest pose's bounds for cameras (Scene::framing), so that frames of an
// animation, and a single frame at some time, are fitted alike.
TEST(ScenePoser, ThePosedSceneKeepsTheRestPosesFraming) {
    Scene s = test_scene();
    Animation slide;
    slide.samplers.push_back(make(Interpolation::Linear, {0, 1}, {0, 0, 0, 10, 0, 0}, 3));
    slide.channels = {{0, 0, AnimationPath::Translation, ""}};
    s.animations.push_back(slide);
    const Bounds rest = scene_bounds(s, flatten(s));
    Scene posed = animated_scene(s, 0, 1.0f);
    const std::vector<NodeInstance> moved = flatten(posed);
    EXPECT_NEAR(scene_bounds(posed, moved).min.x, 10.0f, 1e-6f);  // the triangle moved
    const Bounds framed = framing_bounds(posed, -1, moved);
    EXPECT_EQ(framed.min, rest.min);
    EXPECT_EQ(framed.max, rest.max);
    EXPECT_EQ(framing_bounds(posed, 0, moved).max, rest.max);
    EXPECT_EQ(framing_bounds(s, -1, flatten(s)).max, rest.max);  // never posed: its own bounds
}
