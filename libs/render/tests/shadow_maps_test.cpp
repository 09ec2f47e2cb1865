// Shadow map planning (details/shadow_maps.h), no GL: the atlas layout, each light's tiles,
// and that every tile sees the scene's box from its light (cascades hold the slices they were
// fitted to; cube faces cover every direction; nothing of the box falls outside a map's depth).
#include "details/shadow_maps.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

using namespace fresnel;

namespace {

Bounds box(glm::vec3 lo, glm::vec3 hi) {
    Bounds b;
    b.extend(glm::mat4(1.0f), lo, hi);
    return b;
}

CameraSetup camera_at(glm::vec3 eye, glm::vec3 target) {
    CameraSetup c;
    c.eye = eye;
    c.target = target;
    c.view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    c.znear = 0.1f;
    c.zfar = 100.0f;
    c.projection = glm::perspective(glm::radians(45.0f), 1.0f, c.znear, c.zfar);
    return c;
}

LightInstance directional(glm::vec3 dir) {
    LightInstance l;
    l.type = Light::Type::Directional;
    l.direction = glm::normalize(dir);
    return l;
}

// p in the tile's lookup space: (u, v, depth).
glm::vec3 lookup(const ShadowTile& t, glm::vec3 p) {
    glm::vec4 q = tile_lookup_matrix(t) * glm::vec4(p, 1.0f);
    return glm::vec3(q) / q.w;
}

bool inside(glm::vec3 s, float margin = 0.0f) {
    return s.x >= margin && s.y >= margin && s.x <= 1.0f - margin && s.y <= 1.0f - margin && s.z >= 0.0f &&
           s.z <= 1.0f;
}

}  // namespace

TEST(ShadowMaps, NothingWithoutSceneOrLights) {
    const CameraSetup cam = camera_at({0, 0, 5}, {0, 0, 0});
    EXPECT_TRUE(plan_shadows({directional({0, -1, 0})}, 1, cam, Bounds{}, 1024, 2, 16384).empty());
    EXPECT_TRUE(plan_shadows({}, 0, cam, box({-1, -1, -1}, {1, 1, 1}), 1024, 2, 16384).empty());
}

TEST(ShadowMaps, TilesPerLightAndAtlasLayout) {
    const CameraSetup cam = camera_at({0, 2, 6}, {0, 0, 0});
    LightInstance point;
    point.type = Light::Type::Point;
    point.position = {0, 3, 0};
    LightInstance spot;
    spot.type = Light::Type::Spot;
    spot.position = {2, 3, 0};
    spot.direction = glm::normalize(glm::vec3(-2, -3, 0));
    const std::vector<LightInstance> lights = {directional({1, -2, -1}), point, spot};
    const ShadowPlan plan = plan_shadows(lights, 3, cam, box({-2, -0.1f, -2}, {2, 1, 2}), 1024, 3, 16384);
    ASSERT_EQ(plan.lights.size(), 3u);
    EXPECT_EQ(plan.lights[0].first_tile, 0);
    EXPECT_EQ(plan.lights[0].tiles, 3);
    EXPECT_EQ(plan.lights[1].first_tile, 3);
    EXPECT_EQ(plan.lights[1].tiles, 6);
    EXPECT_EQ(plan.lights[2].first_tile, 9);
    EXPECT_EQ(plan.lights[2].tiles, 1);
    ASSERT_EQ(plan.tiles.size(), 10u);
    // 10 tiles: 4 x 3, within 4096^2 texels in all, so smaller than asked.
    EXPECT_EQ(plan.atlas_width, 4 * plan.tile_size);
    EXPECT_EQ(plan.atlas_height, 3 * plan.tile_size);
    EXPECT_LE(double(plan.tile_size) * plan.tile_size * 10, 4096.0 * 4096.0);
    EXPECT_GT(plan.tile_size, 1000 * 1000 / 1024);
    // Tiles do not overlap and lie inside the atlas.
    for (std::size_t a = 0; a < plan.tiles.size(); ++a) {
        const glm::ivec4 r = plan.tiles[a].rect;
        EXPECT_GE(r.x, 0);
        EXPECT_GE(r.y, 0);
        EXPECT_LE(r.x + r.z, plan.atlas_width);
        EXPECT_LE(r.y + r.w, plan.atlas_height);
        for (std::size_t b = a + 1; b < plan.tiles.size(); ++b) {
            const glm::ivec4 o = plan.tiles[b].rect;
            EXPECT_TRUE(r.x + r.z <= o.x || o.x + o.z <= r.x || r.y + r.w <= o.y || o.y + o.w <= r.y) << a << " " << b;
        }
    }
}

TEST(ShadowMaps, AtlasRespectsTheGpusTextureSize) {
    const CameraSetup cam = camera_at({0, 2, 6}, {0, 0, 0});
    const ShadowPlan plan =
        plan_shadows({directional({0, -1, 0})}, 1, cam, box({-1, 0, -1}, {1, 1, 1}), 4096, 4, 2048);
    EXPECT_LE(plan.atlas_width, 2048);
    EXPECT_LE(plan.atlas_height, 2048);
}

TEST(ShadowMaps, TooManyTilesLeaveTheLastLightsUnshadowed) {
    const CameraSetup cam = camera_at({0, 2, 6}, {0, 0, 0});
    LightInstance point;
    point.type = Light::Type::Point;
    point.position = {0, 3, 0};
    const std::vector<LightInstance> lights(5, point);  // 30 tiles asked, 24 allowed
    const ShadowPlan plan = plan_shadows(lights, 5, cam, box({-1, 0, -1}, {1, 1, 1}), 512, 2, 16384);
    EXPECT_EQ(plan.tiles.size(), 24u);
    EXPECT_EQ(plan.lights[3].tiles, 6);
    EXPECT_EQ(plan.lights[4].first_tile, -1);
}

TEST(ShadowMaps, EveryCornerOfTheSceneIsInsideSomeCascade) {
    const Bounds scene = box({-3, 0, -3}, {3, 2, 3});
    const CameraSetup cam = camera_at({0, 3, 8}, {0, 1, 0});
    const ShadowPlan plan = plan_shadows({directional({0.3f, -1, -0.2f})}, 1, cam, scene, 1024, 3, 16384);
    ASSERT_EQ(plan.tiles.size(), 3u);
    const float margin = float(ShadowPlan::kMarginTexels) / float(plan.tile_size);
    // Points of the scene the camera sees, on a grid: each inside one cascade with its margin.
    for (float x = -3; x <= 3; x += 0.5f)
        for (float z = -3; z <= 3; z += 0.5f)
            for (float y : {0.0f, 1.0f, 2.0f}) {
                glm::vec3 p(x, y, z);
                glm::vec4 c = cam.projection * cam.view * glm::vec4(p, 1.0f);
                if (c.w <= 0 || std::abs(c.x) > c.w || std::abs(c.y) > c.w) continue;  // off screen
                bool held = false;
                for (const ShadowTile& t : plan.tiles) held = held || inside(lookup(t, p), margin);
                EXPECT_TRUE(held) << x << "," << y << "," << z;
            }
    // Cascades get finer towards the camera.
    EXPECT_LE(plan.tiles[0].texel_world, plan.tiles[1].texel_world);
    EXPECT_LE(plan.tiles[1].texel_world, plan.tiles[2].texel_world);
}

TEST(ShadowMaps, CascadesHoldStillForSmallCameraMoves) {
    // A cascade fitted to the box is the same map wherever the camera looks from.
    const Bounds scene = box({-1, 0, -1}, {1, 1, 1});
    const ShadowPlan a = plan_shadows({directional({0, -1, 0.3f})}, 1, camera_at({0, 1, 4}, {0, 0.5f, 0}), scene,
                                      1024, 1, 16384);
    const ShadowPlan b = plan_shadows({directional({0, -1, 0.3f})}, 1, camera_at({0.05f, 1, 4}, {0, 0.5f, 0}), scene,
                                      1024, 1, 16384);
    ASSERT_EQ(a.tiles.size(), 1u);
    ASSERT_EQ(b.tiles.size(), 1u);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_FLOAT_EQ(a.tiles[0].view_projection[c][r], b.tiles[0].view_projection[c][r]);
}

TEST(ShadowMaps, PointLightFacesCoverEveryDirection) {
    const Bounds scene = box({-2, -2, -2}, {2, 2, 2});
    LightInstance point;
    point.type = Light::Type::Point;
    point.position = {0.2f, 0.1f, -0.3f};
    const ShadowPlan plan = plan_shadows({point}, 1, camera_at({0, 0, 6}, {0, 0, 0}), scene, 512, 1, 16384);
    ASSERT_EQ(plan.tiles.size(), 6u);
    const float margin = float(ShadowPlan::kMarginTexels) / 512.0f;
    // A point in each direction is inside the face its major axis names (shadows.glsl's choice).
    for (float x = -1.5f; x <= 1.5f; x += 0.75f)
        for (float y = -1.5f; y <= 1.5f; y += 0.75f)
            for (float z = -1.5f; z <= 1.5f; z += 0.75f) {
                const glm::vec3 d = glm::vec3(x, y, z) - point.position;
                const glm::vec3 a = glm::abs(d);
                if (glm::length(d) < 0.2f) continue;
                const int face = a.x >= a.y && a.x >= a.z ? (d.x < 0 ? 1 : 0)
                                 : a.y >= a.z             ? (d.y < 0 ? 3 : 2)
                                                          : (d.z < 0 ? 5 : 4);
                EXPECT_TRUE(inside(lookup(plan.tiles[std::size_t(face)], glm::vec3(x, y, z)), margin * 0.99f))
                    << x << "," << y << "," << z << " face " << face;
            }
}

TEST(ShadowMaps, SpotLightMapHoldsItsCone) {
    LightInstance spot;
    spot.type = Light::Type::Spot;
    spot.position = {0, 4, 0};
    spot.direction = {0, -1, 0};
    spot.outer_cone = glm::radians(30.0f);
    const ShadowPlan plan =
        plan_shadows({spot}, 1, camera_at({0, 2, 6}, {0, 0, 0}), box({-3, 0, -3}, {3, 1, 3}), 1024, 2, 16384);
    ASSERT_EQ(plan.tiles.size(), 1u);
    const float margin = float(ShadowPlan::kMarginTexels) / 1024.0f;
    // A point on the floor just inside the cone's edge.
    const float r = 4.0f * std::tan(glm::radians(29.5f));
    EXPECT_TRUE(inside(lookup(plan.tiles[0], {r, 0, 0}), margin));
    EXPECT_TRUE(inside(lookup(plan.tiles[0], {0, 0.5f, -r * 0.8f}), margin));
}
