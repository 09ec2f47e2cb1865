// The viewer's input geometry without a window: rays through window points, picking the nearest
// primitive, the light handles and their drags, the auto-rotation's steps.
#include <gtest/gtest.h>

#include <cmath>

#include "fresnel/viewer/geometry.h"
#include "viewer_test_scenes.h"

namespace fresnel::viewer {
namespace {

const glm::ivec2 kWindow{200, 100};

struct Fixture {
    Scene scene = test::box_before_sphere();
    std::vector<NodeInstance> instances = flatten(scene);
    Bounds bounds = scene_bounds(scene, instances);
    CameraSetup camera = test::camera_from_z(bounds);
};

TEST(WindowRay, TheCentreLooksDownTheViewAxisFromTheNearPlane) {
    Fixture f;
    auto r = window_ray(f.camera, kWindow, glm::vec2(100.0f, 50.0f));
    ASSERT_TRUE(r);
    EXPECT_NEAR(r->direction.x, 0.0f, 1e-5f);
    EXPECT_NEAR(r->direction.y, 0.0f, 1e-5f);
    EXPECT_NEAR(r->direction.z, -1.0f, 1e-5f);
    EXPECT_NEAR(r->origin.z, 5.0f - f.camera.znear, 1e-3f);  // on the near plane
    EXPECT_NEAR(r->origin.x, 0.0f, 1e-5f);
}

TEST(WindowRay, ATopLeftPointLooksUpAndLeftAndProjectsBack) {
    Fixture f;
    const glm::vec2 point(20.0f, 10.0f);
    auto r = window_ray(f.camera, kWindow, point);
    ASSERT_TRUE(r);
    EXPECT_LT(r->direction.x, 0.0f);  // window x grows right, y down
    EXPECT_GT(r->direction.y, 0.0f);
    // The vertical half angle of a 60-degree camera: the window's top edge is 30 degrees up.
    auto top = window_ray(f.camera, kWindow, glm::vec2(100.0f, 0.0f));
    ASSERT_TRUE(top);
    EXPECT_NEAR(glm::degrees(std::asin(top->direction.y)), 30.0f, 1e-2f);
    // A point along the ray shows at the window point it came from.
    auto back = to_window(f.camera, kWindow, r->origin + r->direction * 3.0f);
    ASSERT_TRUE(back);
    EXPECT_NEAR(back->x, point.x, 1e-2f);
    EXPECT_NEAR(back->y, point.y, 1e-2f);
}

TEST(WindowRay, NothingForAnEmptyWindowOrBehindTheCamera) {
    Fixture f;
    EXPECT_FALSE(window_ray(f.camera, glm::ivec2(0, 100), glm::vec2(0.0f)));
    EXPECT_FALSE(to_window(f.camera, kWindow, glm::vec3(0.0f, 0.0f, 9.0f)));  // behind the eye at z = 5
}

TEST(PickAt, TheCentreHitsTheBoxFrontAtItsDistance) {
    Fixture f;
    auto r = window_ray(f.camera, kWindow, glm::vec2(100.0f, 50.0f));
    ASSERT_TRUE(r);
    auto hit = pick_at(f.scene, f.instances, f.camera, kWindow, glm::vec2(100.0f, 50.0f));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->node, 0);  // the box, nearer than the sphere behind it
    EXPECT_EQ(hit->mesh, 0);
    EXPECT_EQ(hit->primitive, 0);
    EXPECT_NEAR(hit->distance, r->origin.z - 0.5f, 1e-4f);
    EXPECT_NEAR(hit->point.z, 0.5f, 1e-4f);
}

TEST(PickAt, AHiddenBoxLetsTheRayReachTheSphere) {
    Fixture f;
    f.scene.nodes[0].visible = false;
    f.instances = flatten(f.scene);
    auto r = window_ray(f.camera, kWindow, glm::vec2(100.0f, 50.0f));
    ASSERT_TRUE(r);
    auto hit = pick_at(f.scene, f.instances, f.camera, kWindow, glm::vec2(100.0f, 50.0f));
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->node, 1);
    // The unit sphere centred at z = -3 is met at z = -2 (within its tessellation's flattening).
    EXPECT_NEAR(hit->distance, r->origin.z + 2.0f, 1e-2f);
}

TEST(PickAt, AMissPicksNothing) {
    Fixture f;
    EXPECT_FALSE(pick_at(f.scene, f.instances, f.camera, kWindow, glm::vec2(2.0f, 2.0f)));  // the top-left corner
}

TEST(LightHandles, DirectionalOnTheSphereAroundTheModelPointOnesAtTheirPosition) {
    Bounds b;
    b.empty = false;
    b.min = glm::vec3(-1.0f);
    b.max = glm::vec3(1.0f);
    EXPECT_NEAR(handle_radius(b), 1.25f * std::sqrt(3.0f), 1e-5f);
    EXPECT_EQ(handle_radius(Bounds{}), 1.0f);
    LightInstance sun;
    sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);  // shining down: the handle sits above
    glm::vec3 h = light_handle(sun, b);
    EXPECT_NEAR(h.y, handle_radius(b), 1e-5f);
    LightInstance lamp;
    lamp.type = Light::Type::Point;
    lamp.position = glm::vec3(3.0f, 2.0f, 1.0f);
    EXPECT_EQ(light_handle(lamp, b), lamp.position);
}

TEST(LightHandles, TheNearestHandleWithinTenPoints) {
    Fixture f;
    std::vector<LightInstance> lights(2);
    lights[0].type = lights[1].type = Light::Type::Point;
    lights[0].position = glm::vec3(0.0f);
    lights[1].position = glm::vec3(0.5f, 0.0f, 0.0f);
    auto s1 = to_window(f.camera, kWindow, lights[1].position);
    ASSERT_TRUE(s1);
    EXPECT_EQ(nearest_handle(lights, f.bounds, f.camera, kWindow, *s1 + glm::vec2(3.0f, 0.0f)), 1);
    EXPECT_EQ(nearest_handle(lights, f.bounds, f.camera, kWindow, glm::vec2(100.0f, 50.0f)), 0);
    EXPECT_EQ(nearest_handle(lights, f.bounds, f.camera, kWindow, glm::vec2(5.0f, 5.0f)), -1);
}

TEST(DragLight, ADirectionalLightShinesFromWhereTheRayMeetsItsSphere) {
    Fixture f;
    LightInstance sun;
    sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
    auto r = window_ray(f.camera, kWindow, glm::vec2(100.0f, 50.0f));
    ASSERT_TRUE(r);
    drag_light(sun, *r, f.bounds, f.camera);
    // The ray down the view axis meets the sphere about the centre on its near (+Z) side:
    // the light now shines along -Z, from the camera's side.
    EXPECT_NEAR(sun.direction.z, -1.0f, 1e-4f);
    EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-5f);
}

TEST(DragLight, APointLightMovesInThePlaneFacingTheCamera) {
    Fixture f;
    LightInstance lamp;
    lamp.type = Light::Type::Point;
    lamp.position = glm::vec3(0.0f, 0.0f, 1.0f);
    auto r = window_ray(f.camera, kWindow, glm::vec2(150.0f, 25.0f));
    ASSERT_TRUE(r);
    drag_light(lamp, *r, f.bounds, f.camera);
    EXPECT_NEAR(lamp.position.z, 1.0f, 1e-4f);  // the plane z = 1 faces the camera on +Z
    EXPECT_GT(lamp.position.x, 0.0f);
    EXPECT_GT(lamp.position.y, 0.0f);
    auto s = to_window(f.camera, kWindow, lamp.position);  // under the cursor
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->x, 150.0f, 1e-2f);
    EXPECT_NEAR(s->y, 25.0f, 1e-2f);
}

TEST(OrbitLights, AQuarterTurnAboutPlusYThroughTheCentre) {
    Bounds b;
    b.empty = false;
    b.min = glm::vec3(1.0f, 0.0f, 1.0f);
    b.max = glm::vec3(3.0f, 2.0f, 3.0f);  // centre (2, 1, 2)
    std::vector<LightInstance> lights(1);
    lights[0].direction = glm::vec3(0.0f, 0.0f, -1.0f);
    lights[0].position = glm::vec3(3.0f, 1.0f, 2.0f);  // +X of the centre
    orbit_lights(lights, b, 90.0f);
    EXPECT_NEAR(lights[0].direction.x, -1.0f, 1e-5f);
    EXPECT_NEAR(lights[0].direction.z, 0.0f, 1e-5f);
    EXPECT_NEAR(lights[0].position.x, 2.0f, 1e-5f);
    EXPECT_NEAR(lights[0].position.y, 1.0f, 1e-5f);
    EXPECT_NEAR(lights[0].position.z, 1.0f, 1e-5f);  // +X turned to -Z
    orbit_lights(lights, b, 270.0f);  // the rest of the way round
    EXPECT_NEAR(lights[0].position.x, 3.0f, 1e-4f);
    EXPECT_NEAR(lights[0].direction.z, -1.0f, 1e-4f);
}

TEST(Spin, ThirtyDegreesASecondAtMostAQuarterSecondAFrame) {
    EXPECT_FLOAT_EQ(spin_degrees(0.0), 0.0f);
    EXPECT_FLOAT_EQ(spin_degrees(0.1), 3.0f);
    EXPECT_FLOAT_EQ(spin_degrees(5.0), 7.5f);
}

}  // namespace
}  // namespace fresnel::viewer
