// A warm renderer draws a frame without allocating: the frame's shared values and each material live in
// uniform buffers (uniform_blocks.h), uniform locations are read once per program, program
// lookups build no strings, and the draw lists keep their storage. Counted here by
// replacing the global operator new for this test program (the driver's own C allocations
// are its business). Frames with GPU animation too: the joint matrices live in kept storage.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/procedural.h"
#include "headless_context.h"

namespace {
std::atomic<long> g_allocations{0};
std::atomic<bool> g_counting{false};
}  // namespace

// The replacements pair malloc with free on purpose; GCC, seeing an inlined vector's `new`
// reach this `free`, takes them for a mismatch.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t n) {
    if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace fresnel;

namespace {
// The allocations `f` makes.
template <class F>
long allocations_in(F&& f) {
    g_allocations = 0;
    g_counting = true;
    f();
    g_counting = false;
    return g_allocations.load();
}
}  // namespace

TEST(FrameAllocations, AWarmFrameAllocatesNothing) {
    std::string why;
    auto context = test_support::try_headless_context(why);
    if (!context) GTEST_SKIP() << "no headless OpenGL context: " << why;
    Scene scene = make_demo_scene();
    ASSERT_GE(scene.materials.size(), 3u);
    scene.materials[1].alpha_mode = AlphaMode::Blend;  // the depth-sorted list too
    scene.materials[1].base_color_factor.w = 0.5f;
    scene.materials[2].alpha_mode = AlphaMode::Blend;
    scene.materials[2].base_color_factor.w = 0.5f;
    // A small uniform environment (baked in a moment).
    ImageF sky(16, 8);
    for (std::size_t i = 0; i < sky.pixels.size(); i += 4)
        sky.pixels[i] = 0.6f, sky.pixels[i + 1] = 0.7f, sky.pixels[i + 2] = 0.8f, sky.pixels[i + 3] = 1.0f;
    ibl::BakeOptions bo;
    bo.size = 16;
    bo.levels = 3;
    bo.use_lut_cache = false;
    bo.lut_size = 16;
    bo.lut_samples = 64;
    ibl::BakedIbl env = ibl::bake(sky, bo);

    Renderer renderer(*context);
    renderer.set_scene(scene);
    RenderSettings rs;
    rs.width = 96;
    rs.height = 64;
    rs.environment = &env;
    rs.background_mode = RenderSettings::Background::Environment;
    const CameraSetup cam = orbit_camera(scene_bounds(scene, flatten(scene)), {}, rs.width, rs.height);
    const std::vector<LightInstance> lights = default_lights();
    for (int i = 0; i < 2; ++i) {  // warm: programs, textures, targets, buffers
        renderer.draw(cam, lights, rs);
        renderer.finish();
    }
    FrameStats stats;
    const long warm = allocations_in([&] {
        for (int i = 0; i < 3; ++i) {
            renderer.draw(cam, lights, rs, &stats);
            renderer.finish();
        }
    });
    EXPECT_GT(stats.draw_calls, 40);
    EXPECT_TRUE(stats.gl_errors.empty()) << stats.gl_errors;
    EXPECT_EQ(warm, 0) << "allocations in three warm frames";
    // The control: render() returns a new image, and the counter sees it.
    ImageF image;
    EXPECT_GE(allocations_in([&] { image = renderer.render(cam, lights, rs); }), 1);
    EXPECT_EQ(image.width, rs.width);
}

// The viewer's loop with GPU skinning: the joints move between frames (as fresnel::animate
// moves them) and the joint matrices are computed again into the renderer's kept storage.
TEST(FrameAllocations, AWarmAnimatedFrameAllocatesNothing) {
    std::string why;
    auto context = test_support::try_headless_context(why);
    if (!context) GTEST_SKIP() << "no headless OpenGL context: " << why;
    Primitive p = make_uv_sphere(16, 8);
    for (const glm::vec3& v : p.positions) {
        const float w = std::clamp(0.5f + 0.5f * v.y, 0.0f, 1.0f);  // the top follows joint 1
        p.joints.push_back(glm::uvec4(0, 1, 0, 0));
        p.weights.push_back(glm::vec4(1.0f - w, w, 0.0f, 0.0f));
    }
    p.material = 0;
    Scene scene = make_single_primitive_scene(std::move(p), {Material{}});
    const int first_joint = int(scene.nodes.size());
    scene.nodes.push_back(Node{});
    scene.nodes.push_back(Node{});
    scene.nodes[std::size_t(first_joint)].children = {first_joint + 1};
    scene.nodes[0].skin = 0;
    Skin skin;
    skin.joints = {first_joint, first_joint + 1};
    skin.inverse_bind = {glm::mat4(1.0f), glm::mat4(1.0f)};
    scene.skins.push_back(skin);
    ASSERT_TRUE(gpu_animatable(scene));

    Renderer renderer(*context);
    renderer.set_scene(scene);
    RenderSettings rs;
    rs.width = 64;
    rs.height = 64;
    rs.gpu_animation = true;
    const CameraSetup cam = orbit_camera(scene_bounds(scene, flatten(scene)), {}, rs.width, rs.height);
    const std::vector<LightInstance> lights = default_lights();
    Node& moving = scene.nodes[std::size_t(first_joint + 1)];
    auto frame = [&](int i, FrameStats* stats) {
        moving.local = glm::rotate(glm::mat4(1.0f), 0.2f * float(i), glm::vec3(0, 0, 1));
        renderer.draw(cam, lights, rs, stats);
        renderer.finish();
    };
    for (int i = 0; i < 2; ++i) frame(i, nullptr);
    FrameStats stats;
    const long warm = allocations_in([&] {
        for (int i = 2; i < 5; ++i) frame(i, &stats);
    });
    EXPECT_GE(stats.draw_calls, 1);
    EXPECT_TRUE(stats.gl_errors.empty()) << stats.gl_errors;
    EXPECT_EQ(warm, 0) << "allocations in three warm animated frames";
}
