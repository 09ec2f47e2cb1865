// Baked per-vertex occlusion in the rasteriser (Renderer::set_vertex_occlusion, pbr.vert's
// a_occlusion, pbr.frag): two placements of one diffuse sphere under a uniform ambient light,
// one with a visibility baked for it. The occluded one is darkened by exactly the C++
// multiple-bounce fit (fresnel::brdf::ao_multibounce, the GLSL's twin) of its visibility and
// albedo; the other is drawn as without any bake (difference 0), and is no longer batched with it
// (an occluded placement draws alone); clearing the bake gives back the first frame exactly.
// On OpenGL 3.3 and OpenGL ES 3.0 (the web page's dialect).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/gpu/context.h"
#include "fresnel/job/camera.h"
#include "fresnel/material/brdf.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/procedural.h"
#include "headless_context.h"

using namespace fresnel;

namespace {

constexpr glm::vec3 kAlbedo{0.8f, 0.5f, 0.2f};
constexpr float kVisibility = 0.3f;

Scene two_spheres() {
    Scene s;
    Material m;
    m.base_color_factor = glm::vec4(kAlbedo, 1.0f);
    m.metallic_factor = 0.0f;
    m.roughness_factor = 1.0f;
    s.materials = {m};
    Mesh mesh;
    Primitive p = make_uv_sphere(24, 12);
    p.material = 0;
    mesh.primitives.push_back(std::move(p));
    s.meshes.push_back(std::move(mesh));
    for (float x : {-1.2f, 1.2f}) {
        Node n;
        n.mesh = 0;
        n.local = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, 0.0f));
        n.has_trs = false;
        s.nodes.push_back(n);
    }
    s.scenes.push_back({0, 1});
    return s;
}

struct Frame {
    ImageF image;
    FrameStats stats;
};

Frame draw(Renderer& renderer, const CameraSetup& camera) {
    RenderSettings rs;
    rs.width = 96;
    rs.height = 48;
    rs.msaa = 1;
    rs.tone_mapper = ToneMapper::None;
    rs.encoding = std::nullopt;  // linear radiance
    rs.shadows = Shadows::Off;
    rs.ambient = glm::vec3(1.0f);
    Frame f;
    f.image = renderer.render(camera, {}, rs, &f.stats);
    return f;
}

void check(gpu::Api api) {
    std::string why;
    const std::unique_ptr<gpu::Context> context = test_support::try_headless_context(why, api);
    if (!context) GTEST_SKIP() << "no GL context: " << why;
    const char* dialect = gpu::api_name(api);
    const Scene scene = two_spheres();
    const CameraSetup camera = orbit_camera(scene_bounds(scene, flatten(scene)), {}, 96, 48);
    Renderer renderer(*context);
    renderer.set_scene(scene);
    const Frame plain = draw(renderer, camera);
    EXPECT_EQ(plain.stats.instanced_draws, 1) << dialect << ": the two placements share a draw";

    // The left sphere (node 0) baked: visibility kVisibility everywhere, no bent normal.
    VertexOcclusion occlusion;
    occlusion.nodes.resize(2);
    occlusion.nodes[0] = {std::vector<glm::vec4>(scene.meshes[0].primitives[0].positions.size(),
                                                 glm::vec4(0.0f, 0.0f, 0.0f, kVisibility))};
    renderer.set_vertex_occlusion(&occlusion);
    const Frame baked = draw(renderer, camera);
    EXPECT_EQ(baked.stats.gl_errors, "");
    EXPECT_EQ(baked.stats.instanced_draws, 0) << dialect << ": an occluded placement draws alone";
    EXPECT_EQ(baked.stats.draw_calls, 2);

    const glm::vec3 expected = brdf::ao_multibounce(kVisibility, kAlbedo);
    int left = 0, right = 0;
    float worst_ratio = 0.0f, worst_right = 0.0f;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 96; ++x) {
            const float* a = baked.image.at(x, y);
            const float* b = plain.image.at(x, y);
            if (b[3] < 1.0f || b[0] <= 0.0f) continue;  // background, or an edge
            if (x < 48) {
                ++left;
                for (int c = 0; c < 3; ++c)
                    worst_ratio = std::max(worst_ratio, std::abs(a[c] / b[c] - expected[c]) / expected[c]);
            } else {
                ++right;
                for (int c = 0; c < 3; ++c) worst_right = std::max(worst_right, std::abs(a[c] - b[c]));
            }
        }
    ASSERT_GT(left, 200);
    ASSERT_GT(right, 200);
    std::printf("%s: occluded sphere / plain = ao_multibounce(%.2f) within %.2g (relative), other sphere within %.2g\n",
                dialect, double(kVisibility), double(worst_ratio), double(worst_right));
    EXPECT_LT(worst_ratio, 2e-3f) << dialect;
    EXPECT_EQ(worst_right, 0.0f) << dialect;

    renderer.set_vertex_occlusion(nullptr);
    const Frame cleared = draw(renderer, camera);
    EXPECT_EQ(cleared.stats.instanced_draws, 1);
    float d = 0.0f;
    for (std::size_t i = 0; i < plain.image.pixels.size(); ++i) d = std::max(d, std::abs(plain.image.pixels[i] - cleared.image.pixels[i]));
    EXPECT_EQ(d, 0.0f) << dialect << ": cleared, the frame is the first one";

    // A bake whose vertex counts do not match the scene is ignored.
    VertexOcclusion wrong;
    wrong.nodes = {{std::vector<glm::vec4>(3, glm::vec4(0.0f))}};
    renderer.set_vertex_occlusion(&wrong);
    const Frame ignored = draw(renderer, camera);
    EXPECT_EQ(ignored.stats.instanced_draws, 1);
}

}  // namespace

TEST(VertexOcclusionGpu, OccludesByTheMultibounceFitOnOpenGl33) { check(gpu::Api::OpenGL33); }
TEST(VertexOcclusionGpu, OccludesByTheMultibounceFitOnOpenGlEs30) { check(gpu::Api::OpenGLES30); }
