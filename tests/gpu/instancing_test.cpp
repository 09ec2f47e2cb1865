// Instanced draws and frustum culling (RenderSettings::instancing, ::frustum_culling): a scene
// that places a few meshes many times (turned, scaled unevenly, mirrored; opaque, alpha-masked,
// blended and in a legacy shading model) draws each opaque primitive's placements with one
// instanced draw in the frame and in every shadow tile, and the picture is the one drawn a
// placement at a time; a view of part of the scene leaves the rest out, with the same picture.
// On OpenGL 3.3 and OpenGL ES 3.0 (the web page's dialect).
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"
#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/procedural.h"
#include "headless_context.h"

using namespace fresnel;

namespace {

constexpr int kGrid = 6;  // kGrid^2 opaque spheres

// Mesh 0: an opaque sphere (material 0), mesh 1: an alpha-masked one with vertex colours whose
// alpha crosses the cutoff (material 1), mesh 2: a blended one (material 2), mesh 3: a ground
// quad (material 3), mesh 4: a sphere in OpenGL 1 shading (material 4).
Scene placed_scene() {
    Scene s;
    Material opaque;
    opaque.base_color_factor = glm::vec4(0.8f, 0.5f, 0.3f, 1.0f);
    opaque.metallic_factor = 0.3f;
    opaque.roughness_factor = 0.4f;
    Material masked = opaque;
    masked.alpha_mode = AlphaMode::Mask;
    masked.alpha_cutoff = 0.5f;
    masked.double_sided = true;
    Material blended = opaque;
    blended.alpha_mode = AlphaMode::Blend;
    blended.base_color_factor = glm::vec4(0.2f, 0.4f, 0.9f, 0.5f);
    Material ground;
    ground.base_color_factor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
    ground.roughness_factor = 0.8f;
    Material legacy = opaque;  // classic Phong (an OBJ/MTL material): drawn in OpenGL 1 shading
    legacy.phong = PhongExt{};
    legacy.phong->specular = glm::vec3(0.3f);
    legacy.phong->shininess = 20.0f;
    s.materials = {opaque, masked, blended, ground, legacy};
    auto sphere = [](int material) {
        Primitive p = make_uv_sphere(24, 12);
        p.material = material;
        return p;
    };
    Primitive stripes = sphere(1);
    stripes.colors.resize(stripes.positions.size());
    for (std::size_t v = 0; v < stripes.positions.size(); ++v)
        stripes.colors[v] = glm::vec4(1.0f, 1.0f, 1.0f, std::sin(8.0f * stripes.positions[v].y) > 0.0f ? 1.0f : 0.0f);
    Primitive quad;
    quad.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    quad.normals.assign(4, glm::vec3(0, 1, 0));
    quad.indices = {0, 2, 1, 0, 3, 2};
    quad.material = 3;
    quad.bounds_min = {-1, 0, -1};
    quad.bounds_max = {1, 0, 1};
    for (Primitive p : {sphere(0), stripes, sphere(2), quad, sphere(4)}) {
        Mesh m;
        m.primitives.push_back(std::move(p));
        s.meshes.push_back(std::move(m));
    }
    std::vector<int> roots;
    auto place = [&](int mesh, glm::mat4 local) {
        Node n;
        n.mesh = mesh;
        n.local = local;
        n.has_trs = false;
        roots.push_back(int(s.nodes.size()));
        s.nodes.push_back(n);
    };
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j) {
            glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(2.5f * float(i - kGrid / 2), 1.0f, 2.5f * float(j - kGrid / 2)));
            m = glm::rotate(m, 0.3f * float(i * kGrid + j), glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
            m = glm::scale(m, glm::vec3(1.0f, 0.6f + 0.1f * float(j), 0.8f));  // uneven: the normal matrix matters
            if ((i + j) % 3 == 0) m = glm::scale(m, glm::vec3(-1.0f, 1.0f, 1.0f));  // mirrored: its own batch
            place(0, m);
        }
    for (int k = 0; k < 3; ++k) place(1, glm::translate(glm::mat4(1.0f), glm::vec3(-6.0f + 4.0f * float(k), 3.0f, 8.0f)));
    for (int k = 0; k < 2; ++k) place(2, glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f + 6.0f * float(k), 3.0f, -8.0f)));
    for (int k = 0; k < 3; ++k) place(4, glm::translate(glm::mat4(1.0f), glm::vec3(9.0f, 1.0f, -4.0f + 4.0f * float(k))));
    place(3, glm::scale(glm::mat4(1.0f), glm::vec3(12.0f, 1.0f, 12.0f)));
    s.scenes.push_back(roots);
    return s;
}

struct Frame {
    ImageF image;
    FrameStats stats;
};

Frame draw(gpu::Context& context, const Scene& scene, const CameraSetup& camera, bool instancing, bool culling) {
    RenderSettings rs;
    rs.width = 160;
    rs.height = 120;
    rs.instancing = instancing;
    rs.frustum_culling = culling;
    rs.ambient = glm::vec3(0.2f);
    Renderer renderer(context);
    renderer.set_scene(scene);
    std::vector<LightInstance> lights(1);
    lights[0].type = Light::Type::Directional;
    lights[0].direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    lights[0].radiance = glm::vec3(3.0f);
    Frame f;
    f.image = renderer.render(camera, lights, rs, &f.stats);
    return f;
}

// The largest difference of two frames' values; a frame of one colour fails (nothing to compare).
float max_difference(const ImageF& a, const ImageF& b) {
    float d = 0.0f, spread = 0.0f;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        d = std::max(d, std::abs(a.pixels[i] - b.pixels[i]));
        spread = std::max(spread, std::abs(a.pixels[i] - a.pixels[i % 4]));
    }
    EXPECT_GT(spread, 0.2f) << "a frame of one colour";
    return d;
}

void check(gpu::Api api) {
    std::string why;
    const std::unique_ptr<gpu::Context> context = test_support::try_headless_context(why, api);
    if (!context) GTEST_SKIP() << "no GL context: " << why;
    const char* dialect = gpu::api_name(api);
    const Scene scene = placed_scene();
    const CameraSetup whole = orbit_camera(scene_bounds(scene, flatten(scene)), {}, 160, 120);

    const Frame one_by_one = draw(*context, scene, whole, false, false);
    const Frame instanced = draw(*context, scene, whole, true, false);
    EXPECT_EQ(one_by_one.stats.gl_errors, "");
    EXPECT_EQ(instanced.stats.gl_errors, "");
    EXPECT_GT(one_by_one.stats.shadow_tiles_drawn, 0);
    EXPECT_EQ(one_by_one.stats.instanced_draws, 0);
    // The frame: the opaque spheres in two batches (mirrored and not), the masked ones in one;
    // the blended, legacy-shaded and ground draws alone. Every shadow tile batches the same way.
    const int tiles = instanced.stats.shadow_tiles_drawn;
    EXPECT_GE(instanced.stats.instanced_draws, 3);
    EXPECT_EQ(instanced.stats.triangles, one_by_one.stats.triangles);
    EXPECT_LT(instanced.stats.draw_calls, one_by_one.stats.draw_calls / 4);
    std::printf("%s: %d draws one by one, %d with instancing (%d instanced, %zu placements; %d shadow tiles)\n",
                dialect, one_by_one.stats.draw_calls, instanced.stats.draw_calls, instanced.stats.instanced_draws,
                instanced.stats.instances_drawn, tiles);
    const float d = max_difference(one_by_one.image, instanced.image);
    std::printf("%s: instanced against one by one: max difference %g\n", dialect, double(d));
    EXPECT_LE(d, 1e-5f) << dialect;

    // A close view of one corner: the rest is culled, the picture the same as drawing it all.
    CameraSetup corner = whole;
    corner.eye = glm::vec3(-9.0f, 4.0f, -9.0f);
    corner.view = glm::lookAt(corner.eye, glm::vec3(-5.0f, 1.0f, -5.0f), glm::vec3(0, 1, 0));
    const Frame all = draw(*context, scene, corner, true, false);
    const Frame culled = draw(*context, scene, corner, true, true);
    EXPECT_EQ(all.stats.culled_draws, 0);
    EXPECT_GE(culled.stats.culled_draws, kGrid * kGrid / 3);
    EXPECT_LT(culled.stats.instances_drawn, all.stats.instances_drawn);
    const float dc = max_difference(all.image, culled.image);
    std::printf("%s: corner view: %d draws culled, max difference %g\n", dialect, culled.stats.culled_draws, double(dc));
    EXPECT_LE(dc, 1e-5f) << dialect;
}

}  // namespace

TEST(Instancing, InstancedAndCulledFramesAreTheSameOnOpenGl33) { check(gpu::Api::OpenGL33); }
TEST(Instancing, InstancedAndCulledFramesAreTheSameOnOpenGlEs30) { check(gpu::Api::OpenGLES30); }
