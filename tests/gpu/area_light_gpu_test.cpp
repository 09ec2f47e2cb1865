// Area lights in the rasteriser (shaders/area_lights.glsl, ltc.glsl; FRAME_AREA_LIGHTS) against
// their C++ twin (fresnel::shade_area_light, fresnel/material/area_light.h; fresnel::ltc): a
// floor of one material under one rect, disk or sphere light, drawn in linear radiance without
// shadows, tone mapping or environment; each pixel against shade_area_light at the point of the
// floor its centre sees, with the split-sum table read as the shader reads it. The GPU's table is
// RGBA16F read through the driver's filter (llvmpipe: 8-bit weights), the C++ one float and exact,
// and the frame is half floats: measured on llvmpipe within 0.16 % (mean 0.04 %) for every
// light and material here, on both dialects; the test allows 0.5 % (mean 0.1 %). A light moved behind the floor
// lights nothing. On OpenGL 3.3 and OpenGL ES 3.0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/gpu/context.h"
#include "fresnel/ibl/precompute.h"
#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/material/area_light.h"
#include "fresnel/material/ltc.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/procedural.h"
#include "floor_point.h"
#include "headless_context.h"

using namespace fresnel;

namespace {

constexpr int kSize = 64;

Scene floor_scene(const Material& m) {
    Primitive p;
    p.positions = {{-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2}};
    p.normals = std::vector<glm::vec3>(4, glm::vec3(0, 1, 0));
    p.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from above
    p.bounds_min = {-2, 0, -2};
    p.bounds_max = {2, 0, 2};
    p.material = 0;
    return make_single_primitive_scene(std::move(p), {m});
}

AreaLightGeometry geometry(const LightInstance& l) {
    AreaLightGeometry g;
    g.shape = l.type == Light::Type::Rect   ? AreaShape::Rect
              : l.type == Light::Type::Disk ? AreaShape::Disk
              : l.type == Light::Type::Tube ? AreaShape::Tube
                                            : AreaShape::Sphere;
    g.center = l.position;
    g.axis_u = l.axis_u;
    g.axis_v = l.axis_v;
    g.radius = l.radius;
    return g;
}

struct Case {
    const char* name;
    glm::vec3 base;
    float metallic, roughness;
};

void check(gpu::Api api) {
    std::string why;
    const std::unique_ptr<gpu::Context> context = test_support::try_headless_context(why, api);
    if (!context) GTEST_SKIP() << "no GL context: " << why;
    const char* dialect = gpu::api_name(api);
    const ImageF lut = ibl::compute_brdf_lut(32, 128);
    const Case cases[] = {{"rough dielectric", {0.8f, 0.5f, 0.3f}, 0.0f, 0.8f},
                          {"glossy dielectric", {0.2f, 0.4f, 0.7f}, 0.0f, 0.3f},
                          {"metal", {0.9f, 0.7f, 0.4f}, 1.0f, 0.45f}};
    const char* lights[] = {"rect:0.3,1.2,-0.4,30,60,1.2,0.6,5", "disk:-0.5,0.8,0.2,-40,50,0.4,8", "sphere:0.4,0.6,0.5,0.25,6",
                            "tube:0.2,0.7,-0.3,70,10,1.2,0.06,30"};
    Renderer renderer(*context);
    for (const Case& c : cases) {
        Material m;
        m.base_color_factor = glm::vec4(c.base, 1.0f);
        m.metallic_factor = c.metallic;
        m.roughness_factor = c.roughness;
        const Scene scene = floor_scene(m);
        renderer.set_scene(scene);
        const Bounds bounds = scene_bounds(scene, flatten(scene));
        const CameraSetup camera = look_at_camera(bounds, {0.3f, 1.5f, 1.8f}, {0, 0, 0}, {0, 1, 0}, 50.0f, kSize, kSize);
        EvaluatedMaterial em;
        em.surface.base_color = c.base;
        em.surface.metallic = c.metallic;
        em.surface.perceptual_roughness = c.roughness;
        em.normal = glm::vec3(0, 1, 0);
        for (const char* spec : lights) {
            const LightInstance light = parse_light(spec);
            RenderSettings rs;
            rs.width = rs.height = kSize;
            rs.msaa = 1;
            rs.tone_mapper = ToneMapper::None;
            rs.encoding = std::nullopt;
            rs.shadows = Shadows::Off;
            rs.energy_compensation = false;
            rs.brdf_lut = &lut;
            FrameStats stats;
            const ImageF image = renderer.render(camera, {light}, rs, &stats);
            ASSERT_EQ(stats.gl_errors, "") << dialect;
            const AreaLightGeometry g = geometry(light);
            double worst = 0.0, sum = 0.0, peak = 0.0;
            int lit = 0;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const std::optional<glm::vec3> floor = test::floor_point(camera, x, y, kSize, kSize);
                    if (!floor || std::abs(floor->x) > 1.95f || std::abs(floor->z) > 1.95f) continue;
                    const glm::vec3 p = *floor;
                    glm::vec3 pts[ltc::kMaxPolygon + 1];
                    const int count = area_light_polygon(g, p, pts);
                    const glm::vec3 v = glm::normalize(camera.eye - p);
                    const glm::vec3 toward = glm::normalize(light.position - p);
                    AreaLightLut l;
                    const glm::vec4 ab = ibl::sample_brdf_lut(lut, std::max(v.y, 0.0f), c.roughness);
                    l.base = {ab.x, ab.y};
                    const glm::vec3 want = shade_area_light(em, v, pts, count, light.radiance, toward, l);
                    const float* got = image.at(x, y);
                    for (int k = 0; k < 3; ++k) {
                        peak = std::max(peak, double(want[k]));
                        const double e = std::abs(double(got[k]) - double(want[k])) / std::max(double(want[k]), 0.02);
                        worst = std::max(worst, e);
                        sum += e;
                    }
                    ++lit;
                }
            ASSERT_GT(lit, kSize * kSize / 4) << dialect;
            std::printf("%s, %s, %s: worst %.3g, mean %.3g (relative, floor 0.02; peak %.3g)\n", dialect, c.name, spec,
                        worst, sum / (3.0 * lit), peak);
            EXPECT_GT(peak, 0.05) << spec << ": the light shows";
            EXPECT_LT(worst, 0.005) << dialect << ", " << c.name << ", " << spec;
            EXPECT_LT(sum / (3.0 * lit), 0.001) << dialect << ", " << c.name << ", " << spec;

            // Under the floor, facing down, it lights nothing.
            LightInstance below = light;
            below.position.y = -below.position.y;
            const ImageF dark = renderer.render(camera, {below}, rs, &stats);
            float most = 0.0f;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x)
                    if (dark.at(x, y)[3] > 0.0f) most = std::max({most, dark.at(x, y)[0], dark.at(x, y)[1], dark.at(x, y)[2]});
            if (light.type != Light::Type::Sphere && light.type != Light::Type::Tube) {  // (those still reach past the horizon)
                EXPECT_EQ(most, 0.0f) << dialect << ", " << spec << " moved under the floor";
            }
        }
    }
}

}  // namespace

TEST(AreaLightGpu, MatchesTheCppTwinOnOpenGl33) { check(gpu::Api::OpenGL33); }
TEST(AreaLightGpu, MatchesTheCppTwinOnOpenGlEs30) { check(gpu::Api::OpenGLES30); }
