// GPU skinning and morph targets (RenderSettings::gpu_animation, pbr.vert's SKINNED and
// MORPH_TARGETS) against the CPU reference (fresnel::animated_scene), on a scene built here:
// a sphere skinned to two joints (one animated by rotation, its parent by translation),
// with weights that do not all sum to 1, and one morph target animated by its weight.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/core/error.h"
#include "fresnel/core/metrics.h"
#include "fresnel/gpu/context.h"
#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/pose.h"
#include "fresnel/scene/procedural.h"

using namespace fresnel;

namespace {

AnimationSampler linear(std::vector<float> in, std::vector<float> out, int width) {
    AnimationSampler s;
    s.input = std::move(in);
    s.output = std::move(out);
    s.width = width;
    return s;
}

Scene skinned_scene() {
    Scene s;
    s.source = "animation_gpu_test";
    Primitive p = make_uv_sphere(48, 24);
    std::size_t n = p.positions.size();
    p.joints.assign(n, glm::uvec4(0, 1, 0, 0));
    p.weights.resize(n);
    MorphTarget bulge;
    bulge.positions.resize(n);
    bulge.normals.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
        float y = p.positions[v].y;
        float w1 = glm::smoothstep(-0.3f, 0.6f, y);
        float scale = p.positions[v].x > 0.5f ? 0.8f : 1.0f;  // some weights sum to 0.8
        p.weights[v] = glm::vec4((1.0f - w1) * scale, w1 * scale, 0, 0);
        bool front = p.positions[v].z > 0.0f;
        bulge.positions[v] = front ? p.normals[v] * 0.35f : glm::vec3(0.0f);
        bulge.normals[v] = front ? glm::vec3(0.0f, 0.3f, 0.0f) : glm::vec3(0.0f);
    }
    p.targets = {bulge};
    p.applied_weights = {0.0f};
    Mesh mesh;
    mesh.primitives.push_back(std::move(p));
    mesh.weights = {0.0f};
    s.meshes.push_back(std::move(mesh));
    Material m;
    s.materials.push_back(m);
    s.meshes[0].primitives[0].material = 0;

    Node body;
    body.mesh = 0;
    body.skin = 0;
    Node root;
    root.children = {2};
    Node upper;
    upper.translation = glm::vec3(0.0f, 0.2f, 0.0f);
    upper.local = trs_matrix(upper.translation, upper.rotation, upper.scale);
    s.nodes = {body, root, upper};
    s.scenes = {{0, 1}};
    Skin skin;
    skin.joints = {1, 2};
    skin.inverse_bind = {glm::mat4(1.0f), glm::inverse(upper.local)};
    s.skins.push_back(skin);

    Animation a;
    float h = glm::radians(60.0f) / 2.0f;
    a.samplers.push_back(linear({0, 1}, {0, 0, 0, 1, 0, 0, std::sin(h), std::cos(h)}, 4));  // 0 -> 60 degrees about z
    a.samplers.push_back(linear({0, 1}, {0, 0, 0, 0.1f, -0.2f, 0.3f}, 3));
    a.samplers.push_back(linear({0, 1}, {0, 1}, 1));
    a.channels = {{0, 2, AnimationPath::Rotation, ""}, {1, 1, AnimationPath::Translation, ""}, {2, 0, AnimationPath::Weights, ""}};
    s.animations.push_back(a);
    return s;
}

}  // namespace

TEST(AnimationGpu, SkinningAndMorphingAgreeWithTheCpuReference) {
    std::unique_ptr<gpu::Context> context;
    try {
        context = gpu::create_headless_context({});
    } catch (const Error& e) {
        GTEST_SKIP() << "no GL context: " << e.what();
    }
    const Scene rest = skinned_scene();
    ASSERT_TRUE(gpu_animatable(rest));
    RenderSettings rs;
    rs.width = 160;
    rs.height = 160;
    auto instances = flatten(rest);
    Bounds b = scene_bounds(rest, instances);
    OrbitParams op;
    op.yaw_deg = 20.0f;
    op.distance_k = 3.0f;  // the posed sphere moves out of its rest box
    CameraSetup cam = orbit_camera(b, op, rs.width, rs.height);
    auto lights = default_lights();
    Renderer renderer(*context);

    renderer.set_scene(rest);
    Image8 bind = to_image8(renderer.render(cam, lights, rs), false);
    for (float t : {0.3f, 0.8f}) {
        SCOPED_TRACE("t = " + std::to_string(t));
        Scene cpu = animated_scene(rest, 0, t);
        renderer.set_scene(cpu);
        FrameStats cs;
        Image8 cpu_image = to_image8(renderer.render(cam, lights, rs, &cs), false);

        Scene gpu = rest;
        renderer.set_scene(gpu);
        animate(gpu, 0, t);
        renderer.update_transforms();
        RenderSettings grs = rs;
        grs.gpu_animation = true;
        FrameStats gs;
        Image8 gpu_image = to_image8(renderer.render(cam, lights, grs, &gs), false);
        EXPECT_EQ(gs.gl_errors, "");
        EXPECT_EQ(gs.triangles, cs.triangles);

        ImageMetrics agree = compare_images(gpu_image, cpu_image, false);
        ImageMetrics moved = compare_images(gpu_image, bind, false);
        std::printf("t=%.1f: GPU vs CPU posing %.1f dB; GPU vs bind pose %.1f dB\n", t, agree.psnr_db, moved.psnr_db);
        EXPECT_GE(agree.psnr_db, 45.0);
        EXPECT_LT(moved.psnr_db, 30.0) << "the animation did not move the mesh";
    }
    // Without gpu_animation the same scene draws in its bind pose, as before.
    Scene gpu = rest;
    renderer.set_scene(gpu);
    animate(gpu, 0, 0.8f);
    renderer.update_transforms();
    Image8 off = to_image8(renderer.render(cam, lights, rs), false);
    EXPECT_GE(compare_images(off, bind, false).psnr_db, 60.0);
}
