// The viewer's camera control (fresnel/job/orbit_controller.h) against the camera
// convention: pan keeps the point under the cursor under it, dolly scales the eye's
// distance, frame all gives `render`'s default camera back, and a file camera converts to
// an orbit camera with the same eye and view direction. Pure CPU, no window.
#include "fresnel/job/orbit_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

using namespace fresnel;

namespace {

Bounds box(glm::vec3 min, glm::vec3 max) {
    Bounds b;
    b.min = min;
    b.max = max;
    b.empty = false;
    return b;
}

CameraSetup setup(const Job::Camera& c, const OrbitViewport& v) {
    OrbitParams p;
    p.yaw_deg = c.yaw_deg;
    p.pitch_deg = c.pitch_deg;
    p.distance_k = c.distance_k;
    p.yfov_deg = c.yfov_deg;
    p.target = c.target;
    return orbit_camera(v.bounds, p, v.width, v.height);
}

// Window coordinates (x right, y down, pixels) of a world point.
glm::vec2 to_pixels(const CameraSetup& s, const OrbitViewport& v, glm::vec3 p) {
    glm::vec4 q = s.projection * s.view * glm::vec4(p, 1.0f);
    glm::vec2 ndc = glm::vec2(q) / q.w;
    return {(ndc.x * 0.5f + 0.5f) * float(v.width), (0.5f - ndc.y * 0.5f) * float(v.height)};
}

const OrbitViewport kView{box({-1, -2, -0.5f}, {3, 1, 0.5f}), 800, 600};

}  // namespace

TEST(OrbitController, OrbitTurnsYawAndPitchAndClampsPitch) {
    Job::Camera c;
    c.scene_camera = 2;
    Job::Camera o = orbit(c, 10.0f, -20.0f, 0.5f);
    EXPECT_FALSE(o.scene_camera);
    EXPECT_FLOAT_EQ(o.yaw_deg, -5.0f);
    EXPECT_FLOAT_EQ(o.pitch_deg, -10.0f);
    EXPECT_FLOAT_EQ(orbit(c, 0.0f, 1e4f).pitch_deg, 89.9f);
    EXPECT_FLOAT_EQ(orbit(c, 0.0f, -1e4f).pitch_deg, -89.9f);
    // Yaw stays within [-180, 180].
    EXPECT_NEAR(orbit(c, -1300.0f, 0.0f, 1.0f).yaw_deg, 1300.0f - 4 * 360.0f, 1e-3f);
}

TEST(OrbitController, PanKeepsThePointUnderTheCursor) {
    for (float yaw : {0.0f, 45.0f, -120.0f})
        for (float pitch : {0.0f, 30.0f, -60.0f}) {
            Job::Camera c;
            c.yaw_deg = yaw;
            c.pitch_deg = pitch;
            CameraSetup before = setup(c, kView);
            glm::vec2 p0 = to_pixels(before, kView, before.target);
            Job::Camera moved = pan(c, kView, 37.0f, -21.0f);
            ASSERT_TRUE(moved.target);
            glm::vec2 p1 = to_pixels(setup(moved, kView), kView, before.target);
            EXPECT_NEAR(p1.x - p0.x, 37.0f, 0.05f) << yaw << " " << pitch;
            EXPECT_NEAR(p1.y - p0.y, -21.0f, 0.05f) << yaw << " " << pitch;
            // The distance and direction do not change.
            CameraSetup after = setup(moved, kView);
            EXPECT_NEAR(glm::length(after.eye - after.target), glm::length(before.eye - before.target), 1e-4f);
        }
}

TEST(OrbitController, DollyScalesTheDistanceFromTheFit) {
    Job::Camera c;
    CameraSetup fit = setup(c, kView);
    float d0 = glm::length(fit.eye - fit.target);
    EXPECT_NEAR(d0, fit_distance_k(45.0f, 800, 600) * kView.bounds.radius(), 1e-4f);
    Job::Camera closer = dolly(c, kView, dolly_factor(2.0f));
    ASSERT_TRUE(closer.distance_k);
    CameraSetup s = setup(closer, kView);
    EXPECT_NEAR(glm::length(s.eye - s.target), d0 * 0.81f, 1e-4f);
    EXPECT_FLOAT_EQ(*dolly(c, kView, 1e-9f).distance_k, 0.01f);
    EXPECT_FLOAT_EQ(*dolly(c, kView, 1e9f).distance_k, 1e4f);
}

TEST(OrbitController, FrameAllGivesTheDefaultCameraBack) {
    Job::Camera c;
    c.yaw_deg = 30.0f;
    c.pitch_deg = 10.0f;
    Job::Camera moved = dolly(pan(c, kView, 100.0f, 50.0f), kView, 0.5f);
    EXPECT_NE(moved, c);
    EXPECT_EQ(frame_all(moved), c);
}

TEST(OrbitController, FileCameraBecomesAnOrbitCameraWithTheSameView) {
    Job::Camera c;
    c.yaw_deg = -70.0f;
    c.pitch_deg = 25.0f;
    c.distance_k = 3.0f;
    c.target = glm::vec3(0.5f, -0.25f, 0.1f);
    CameraSetup s = setup(c, kView);
    Job::Camera back = orbit_from_setup(s, kView.bounds, 45.0f);
    CameraSetup t = setup(back, kView);
    EXPECT_NEAR(glm::length(t.eye - s.eye), 0.0f, 1e-4f);
    glm::vec3 f0 = glm::normalize(s.target - s.eye), f1 = glm::normalize(t.target - t.eye);
    EXPECT_GT(glm::dot(f0, f1), 0.99999f);
    EXPECT_NEAR(back.yaw_deg, -70.0f, 1e-3f);
    EXPECT_NEAR(back.pitch_deg, 25.0f, 1e-3f);
}
