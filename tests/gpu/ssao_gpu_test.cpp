// Screen-space ambient occlusion (`--ao ssao`: shaders/ssao.frag, ssao_blur.frag, pbr.frag's
// FRAME_SSAO) against a closed form: a floor in front of a long wall of height H, under a uniform
// ambient light. The cosine-weighted visibility of the floor at distance x from the wall is
// V(x) = (1 + x / sqrt(x^2 + H^2)) / 2 (the view factor of an infinite strip: 0.5 at its foot,
// towards 1 far away); the frame with occlusion over the frame without is ao_multibounce(V, albedo)
// (the C++ twin of pbr.frag's combination): measured within 0.037 from a quarter of the height
// out, 0.06 at a tenth (occlusion is found at half resolution, two slices a pixel). With a radius short of the wall, the open floor stays unoccluded
// (a plane does not occlude itself). On OpenGL 3.3 and OpenGL ES 3.0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "fresnel/gpu/context.h"
#include "fresnel/job/camera.h"
#include "fresnel/material/brdf.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/procedural.h"
#include "floor_point.h"
#include "headless_context.h"

using namespace fresnel;

namespace {

constexpr int kSize = 160;
constexpr float kWallHeight = 1.0f, kWallFace = -0.5f;  // the wall's face at z = -0.5, facing +z
constexpr glm::vec3 kAlbedo{0.6f, 0.6f, 0.6f};

// An axis-aligned box's six faces (outward normals, counter-clockwise seen from outside).
void add_box(Primitive& p, glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 n[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& f : n) {
        // Two axes spanning the face: v = f x u, so u x v = f (u is normal to f).
        const glm::vec3 u = std::abs(f.y) > 0.5f ? glm::vec3(0, 0, f.y) : glm::vec3(0, 1, 0);
        const glm::vec3 v = glm::cross(f, u);
        const glm::vec3 c = (lo + hi) * 0.5f + f * (hi - lo) * 0.5f;
        const glm::vec3 hu = u * (hi - lo) * 0.5f, hv = v * (hi - lo) * 0.5f;
        const auto base = std::uint32_t(p.positions.size());
        for (glm::vec3 q : {c - hu - hv, c + hu - hv, c + hu + hv, c - hu + hv}) {
            p.positions.push_back(q);
            p.normals.push_back(f);
        }
        // (c - u - v, c + u - v, c + u + v) runs counter-clockwise around u x v = f.
        p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
}

Scene wall_scene() {
    Material m;
    m.base_color_factor = glm::vec4(kAlbedo, 1.0f);
    m.metallic_factor = 0.0f;
    m.roughness_factor = 1.0f;
    Primitive p;
    add_box(p, {-6.0f, -0.2f, -6.0f}, {6.0f, 0.0f, 6.0f});                            // the floor's slab
    add_box(p, {-6.0f, 0.0f, kWallFace - 0.3f}, {6.0f, kWallHeight, kWallFace});  // the wall
    p.bounds_min = {-6.0f, -0.2f, -6.0f};
    p.bounds_max = {6.0f, kWallHeight, 6.0f};
    p.material = 0;
    return make_single_primitive_scene(std::move(p), {m});
}

void check(gpu::Api api) {
    std::string why;
    const std::unique_ptr<gpu::Context> context = test_support::try_headless_context(why, api);
    if (!context) GTEST_SKIP() << "no GL context: " << why;
    const char* dialect = gpu::api_name(api);
    const Scene scene = wall_scene();
    Renderer renderer(*context);
    renderer.set_scene(scene);
    const Bounds bounds = scene_bounds(scene, flatten(scene));
    const CameraSetup camera = look_at_camera(bounds, {0.0f, 2.2f, 2.6f}, {0.0f, 0.0f, 0.3f}, {0, 1, 0}, 60.0f, kSize, kSize);
    RenderSettings rs;
    rs.width = rs.height = kSize;
    rs.msaa = 1;
    rs.tone_mapper = ToneMapper::None;
    rs.encoding = std::nullopt;
    rs.shadows = Shadows::Off;
    rs.ambient = glm::vec3(1.0f);
    FrameStats stats;
    const ImageF plain = renderer.render(camera, {}, rs, &stats);
    rs.ssao = true;
    rs.ssao_radius = 4.0f;  // beyond the wall's height: the whole wall is within reach
    const ImageF occluded = renderer.render(camera, {}, rs, &stats);
    ASSERT_EQ(stats.gl_errors, "") << dialect;
    rs.ssao_radius = 0.25f;  // the open floor beyond it: nothing occludes a plane itself
    const ImageF near_only = renderer.render(camera, {}, rs, &stats);

    // The floor's point under each pixel; the mean ratio in bands at distances x from the wall.
    const float distances[] = {0.1f, 0.25f, 0.5f, 1.0f, 2.0f};
    double sum[5] = {}, open_sum = 0.0, open_worst = 0.0;
    int count[5] = {}, open_count = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const std::optional<glm::vec3> floor = test::floor_point(camera, x, y, kSize, kSize);
            if (!floor || std::abs(floor->x) > 0.6f || floor->z < kWallFace) continue;
            const glm::vec3 p = *floor;
            const double ratio = double(occluded.at(x, y)[0]) / double(plain.at(x, y)[0]);
            const float dist = p.z - kWallFace;
            for (int k = 0; k < 5; ++k)
                if (std::abs(dist - distances[k]) < 0.04f) {
                    sum[k] += ratio;
                    ++count[k];
                }
            if (dist > 0.5f) {
                const double open = double(near_only.at(x, y)[0]) / double(plain.at(x, y)[0]);
                open_sum += open;
                open_worst = std::max(open_worst, std::abs(open - 1.0));
                ++open_count;
            }
        }
    for (int k = 0; k < 5; ++k) {
        ASSERT_GT(count[k], 4) << dialect << " x = " << distances[k];
        const float xk = distances[k];
        const float v = 0.5f * (1.0f + xk / std::sqrt(xk * xk + kWallHeight * kWallHeight));
        const double expected = brdf::ao_multibounce(v, kAlbedo).x;
        const double got = sum[k] / count[k];
        std::printf("%s: x = %.2f: visibility %.3f, frame ratio %.3f, expected %.3f\n", dialect, double(xk), double(v), got,
                    expected);
        // Within two half-resolution pixels of the wall the blur and the upsampling soften the foot.
        EXPECT_NEAR(got, expected, k == 0 ? 0.07 : 0.045) << dialect << " x = " << xk;
    }
    ASSERT_GT(open_count, 50);
    std::printf("%s: open floor (radius 0.25, beyond 0.5 of the wall) ratio mean %.4f, worst %.4f\n", dialect,
                open_sum / open_count, open_worst);
    EXPECT_NEAR(open_sum / open_count, 1.0, 0.01) << dialect;  // measured 0.994: depth quantisation lifts the horizon a little
    EXPECT_LT(open_worst, 0.02) << dialect;
}

}  // namespace

TEST(SsaoGpu, FollowsTheWallsClosedFormOnOpenGl33) { check(gpu::Api::OpenGL33); }
TEST(SsaoGpu, FollowsTheWallsClosedFormOnOpenGlEs30) { check(gpu::Api::OpenGLES30); }
