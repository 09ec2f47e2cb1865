// The camera convention (docs/shading.md "Camera convention", fresnel/job/camera.h): the orbit
// camera's eye, target, orientation, fit distance and clip planes against the formulae,
// and cameras from a scene's nodes. Pure CPU, no GL context.
#include "fresnel/job/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/scene/scene.h"

using namespace fresnel;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

void expect_near(glm::vec3 a, glm::vec3 b, float eps, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, eps) << what;
    EXPECT_NEAR(a.y, b.y, eps) << what;
    EXPECT_NEAR(a.z, b.z, eps) << what;
}

glm::vec3 transform_point(const glm::mat4& m, glm::vec3 p) {
    glm::vec4 q = m * glm::vec4(p, 1.0f);
    return glm::vec3(q) / q.w;
}

Bounds box(glm::vec3 min, glm::vec3 max) {
    Bounds b;
    b.min = min;
    b.max = max;
    b.empty = false;
    return b;
}

// docs/shading.md's formulae, written out independently of camera.cpp (double precision).
struct Expected {
    glm::dvec3 eye, target;
    double D, R, znear, zfar;
};
Expected readme_orbit(const Bounds& b, double yaw_deg, double pitch_deg, std::optional<double> k, double vfov_deg, int w,
                      int h) {
    Expected e;
    glm::dvec3 mn(b.min), mx(b.max);
    e.target = (mn + mx) * 0.5;
    e.R = glm::length(mx - mn) * 0.5;
    double half = vfov_deg * kDeg * 0.5;
    double a = std::min(half, std::atan(std::tan(half) * double(w) / double(h)));
    e.D = k.value_or(1.0 / std::sin(a)) * e.R;
    double y = yaw_deg * kDeg, p = pitch_deg * kDeg;
    e.eye = e.target + e.D * glm::dvec3(std::cos(p) * std::sin(y), std::sin(p), std::cos(p) * std::cos(y));
    e.zfar = e.D + 2.0 * e.R;
    e.znear = std::max(e.D - 2.0 * e.R, e.zfar / 1000.0);
    return e;
}

const Bounds kBox = box({-1.0f, -2.0f, -3.0f}, {3.0f, 2.0f, 1.0f});  // centre (1, 0, -1), R = 2 sqrt(3)

TEST(OrbitCamera, EyeTargetAndClipPlanesFollowTheReadme) {
    struct Case {
        float yaw, pitch;
        std::optional<float> k;
        float fov;
        int w, h;
    };
    const Case cases[] = {{0, 0, {}, 45, 1024, 768},   {90, 0, {}, 45, 512, 512},    {45, 20, {}, 45, 512, 512},
                          {-30, -60, {}, 30, 300, 900}, {180, 89, 3.0f, 60, 640, 480}, {10, 5, 1.2f, 45, 100, 100},
                          {0, 90, {}, 45, 800, 600},    {270, -90, 8.0f, 20, 64, 32}};
    for (const auto& c : cases) {
        std::string what = "yaw " + std::to_string(c.yaw) + " pitch " + std::to_string(c.pitch) + " fov " +
                           std::to_string(c.fov) + " " + std::to_string(c.w) + "x" + std::to_string(c.h);
        OrbitParams p;
        p.yaw_deg = c.yaw;
        p.pitch_deg = c.pitch;
        p.distance_k = c.k;
        p.yfov_deg = c.fov;
        CameraSetup cam = orbit_camera(kBox, p, c.w, c.h);
        Expected e = readme_orbit(kBox, c.yaw, c.pitch, c.k ? std::optional<double>(*c.k) : std::nullopt, c.fov, c.w, c.h);
        float eps = 1e-4f * float(e.D);
        expect_near(cam.target, glm::vec3(e.target), eps, what + ": target");
        expect_near(cam.eye, glm::vec3(e.eye), eps, what + ": eye");
        EXPECT_NEAR(cam.zfar, e.zfar, 1e-4 * e.zfar) << what;
        EXPECT_NEAR(cam.znear, e.znear, 1e-4 * e.znear) << what;
        EXPECT_FLOAT_EQ(cam.yfov_deg, c.fov) << what;
        EXPECT_FALSE(cam.orthographic);

        // The view matrix puts the eye at the origin and the target straight ahead (-Z),
        // and keeps world +Y pointing up on screen (non-negative camera y) for |pitch| < 90.
        expect_near(transform_point(cam.view, cam.eye), glm::vec3(0.0f), eps, what + ": eye in view space");
        expect_near(transform_point(cam.view, cam.target), glm::vec3(0, 0, -float(e.D)), eps, what + ": target in view space");
        glm::vec3 up_cam = glm::mat3(cam.view) * glm::vec3(0, 1, 0);
        if (std::fabs(c.pitch) < 89.5f) {
            EXPECT_GT(up_cam.y, 0.0f) << what;
            EXPECT_NEAR(up_cam.x, 0.0f, 1e-5f) << what << ": the horizon is tilted";
        }
        // Rigid: the view's upper 3x3 is a rotation.
        glm::mat3 r(cam.view);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(glm::length(r[i]), 1.0f, 1e-5f) << what;
        EXPECT_NEAR(glm::determinant(r), 1.0f, 1e-5f) << what;

        // Projection: glm::perspective(vfov, W/H, near, far).
        glm::mat4 expected_proj = glm::perspective(float(c.fov * kDeg), float(c.w) / float(c.h), cam.znear, cam.zfar);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) EXPECT_NEAR(cam.projection[i][j], expected_proj[i][j], 1e-5f) << what;
    }
}

TEST(OrbitCamera, YawAndPitchLookFromTheStatedSides) {
    Bounds unit = box(glm::vec3(-1.0f), glm::vec3(1.0f));
    auto eye_dir = [&](float yaw, float pitch) {
        OrbitParams p;
        p.yaw_deg = yaw;
        p.pitch_deg = pitch;
        CameraSetup c = orbit_camera(unit, p, 100, 100);
        return glm::normalize(c.eye - c.target);
    };
    expect_near(eye_dir(0, 0), {0, 0, 1}, 1e-6f, "yaw 0, pitch 0 looks from +Z");
    expect_near(eye_dir(90, 0), {1, 0, 0}, 1e-6f, "yaw 90 looks from +X");
    expect_near(eye_dir(-90, 0), {-1, 0, 0}, 1e-6f, "yaw -90 looks from -X");
    expect_near(eye_dir(180, 0), {0, 0, -1}, 1e-6f, "yaw 180 looks from -Z");
    expect_near(eye_dir(0, 90), {0, 1, 0}, 1e-6f, "pitch 90 looks from above");
    expect_near(eye_dir(0, -90), {0, -1, 0}, 1e-6f, "pitch -90 looks from below");
}

TEST(OrbitCamera, DefaultDistanceFitsTheBoundingSphere) {
    // With K = 1/sin(a) the sphere (target, R) touches the narrower pair of frustum planes:
    // the tangent point at angle a off the view axis projects onto the image edge.
    for (auto [w, h] : {std::pair{1024, 768}, std::pair{400, 800}, std::pair{512, 512}}) {
        OrbitParams p;
        p.yaw_deg = 30;
        p.pitch_deg = 10;
        CameraSetup c = orbit_camera(kBox, p, w, h);
        float R = kBox.radius(), D = glm::length(c.eye - c.target);
        float a = std::asin(R / D);  // half the angle the sphere subtends
        float s = std::sqrt(D * D - R * R);
        bool narrow_horizontally = w < h;
        glm::vec3 tangent = narrow_horizontally ? glm::vec3(s * std::sin(a), 0, -s * std::cos(a))
                                                : glm::vec3(0, s * std::sin(a), -s * std::cos(a));
        glm::vec3 ndc = transform_point(c.projection, tangent);
        std::string what = std::to_string(w) + "x" + std::to_string(h);
        EXPECT_NEAR(narrow_horizontally ? ndc.x : ndc.y, 1.0f, 1e-4f) << what;
        EXPECT_LE(std::fabs(narrow_horizontally ? ndc.y : ndc.x), 1.0f) << what;
        // The whole box lies inside the frustum and the clip range.
        for (int k = 0; k < 8; ++k) {
            glm::vec3 corner((k & 1) ? kBox.max.x : kBox.min.x, (k & 2) ? kBox.max.y : kBox.min.y,
                             (k & 4) ? kBox.max.z : kBox.min.z);
            glm::vec3 q = transform_point(c.projection * c.view, corner);
            EXPECT_LE(std::fabs(q.x), 1.0f + 1e-5f) << what << " corner " << k;
            EXPECT_LE(std::fabs(q.y), 1.0f + 1e-5f) << what << " corner " << k;
            EXPECT_LE(std::fabs(q.z), 1.0f + 1e-5f) << what << " corner " << k;
        }
    }
}

TEST(OrbitCamera, NearPlaneIsClampedToAThousandthOfFar) {
    OrbitParams close;
    close.distance_k = 1.5f;  // D < 2R: D - 2R is negative
    CameraSetup c = orbit_camera(kBox, close, 100, 100);
    EXPECT_NEAR(c.znear, c.zfar / 1000.0f, 1e-6f * c.zfar);
    OrbitParams far;
    far.distance_k = 5.0f;
    c = orbit_camera(kBox, far, 100, 100);
    EXPECT_NEAR(c.znear, 3.0f * kBox.radius(), 1e-4f);
    EXPECT_NEAR(c.zfar, 7.0f * kBox.radius(), 1e-4f);
}

TEST(OrbitCamera, EmptyBoundsUseTheUnitSphereAtTheOrigin) {
    Bounds empty;
    CameraSetup c = orbit_camera(empty, OrbitParams{}, 100, 100);
    expect_near(c.target, glm::vec3(0.0f), 1e-6f, "target");
    float D = 1.0f / std::sin(float(22.5 * kDeg));
    expect_near(c.eye, {0, 0, D}, 1e-5f, "eye");
}

// A scene whose node 1 (child of node 0) carries a camera; node 0 is translated, turned
// 90 degrees about +Y and scaled by 2 (the scale must not reach the view matrix).
Scene camera_scene(const Camera& cam) {
    Scene s;
    s.cameras = {Camera{}, cam};
    Node parent, child;
    parent.local = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)), float(90 * kDeg),
                                          glm::vec3(0, 1, 0)),
                              glm::vec3(2.0f));
    parent.children = {1};
    child.local = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 1));
    child.camera = 1;
    s.nodes = {parent, child};
    s.scenes = {{0}};
    return s;
}

TEST(SceneCamera, PerspectiveFromANode) {
    Camera cam;
    cam.type = Camera::Type::Perspective;
    cam.yfov = 0.6f;
    cam.znear = 0.05f;
    cam.zfar = 50.0f;
    Scene s = camera_scene(cam);
    auto inst = flatten(s);
    auto c = scene_camera(s, inst, 1, 640, 480);
    ASSERT_TRUE(c.has_value());
    // World position: parent (1,2,3) + R_y(90) * 2 * (0,0,1) = (1,2,3) + (2,0,0).
    expect_near(c->eye, {3, 2, 3}, 1e-5f, "eye");
    // The camera looks down its local -Z: R_y(90) * (0,0,-1) = (-1,0,0).
    expect_near(glm::normalize(c->target - c->eye), {-1, 0, 0}, 1e-5f, "view direction");
    expect_near(transform_point(c->view, c->eye), glm::vec3(0.0f), 1e-5f, "eye in view space");
    expect_near(transform_point(c->view, c->eye + glm::vec3(-4, 0, 0)), {0, 0, -4}, 1e-5f, "a point ahead, unscaled");
    expect_near(glm::mat3(c->view) * glm::vec3(0, 1, 0), {0, 1, 0}, 1e-5f, "up");
    EXPECT_FLOAT_EQ(c->znear, 0.05f);
    EXPECT_FLOAT_EQ(c->zfar, 50.0f);
    EXPECT_NEAR(c->yfov_deg, 0.6 / kDeg, 1e-3);
    EXPECT_FALSE(c->orthographic);
    glm::mat4 p = glm::perspective(0.6f, 640.0f / 480.0f, 0.05f, 50.0f);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(c->projection[i][j], p[i][j], 1e-5f);
}

TEST(SceneCamera, InfinitePerspectiveWithoutZfar) {
    Camera cam;
    cam.yfov = 0.8f;
    cam.znear = 0.1f;
    Scene s = camera_scene(cam);
    auto c = scene_camera(s, flatten(s), 1, 100, 100);
    ASSERT_TRUE(c.has_value());
    EXPECT_FLOAT_EQ(c->zfar, 0.1f * 1e6f);
    // Points far beyond any finite plane still land inside the depth range.
    glm::vec3 ndc = transform_point(c->projection, {0, 0, -2.0f * c->zfar});
    EXPECT_LT(ndc.z, 1.0f);
    EXPECT_GT(ndc.z, -1.0f);
    EXPECT_NEAR(transform_point(c->projection, {0, 0, -0.1f}).z, -1.0f, 1e-4f) << "znear maps to -1";
}

TEST(SceneCamera, OrthographicKeepsYmagAndFitsXToTheImage) {
    Camera cam;
    cam.type = Camera::Type::Orthographic;
    cam.xmag = 5.0f;  // ignored: x follows the image's aspect
    cam.ymag = 2.0f;
    cam.znear = 0.5f;
    cam.zfar = 20.0f;
    Scene s = camera_scene(cam);
    auto c = scene_camera(s, flatten(s), 1, 300, 100);
    ASSERT_TRUE(c.has_value());
    EXPECT_TRUE(c->orthographic);
    EXPECT_FLOAT_EQ(c->zfar, 20.0f);
    expect_near(transform_point(c->projection, {6.0f, 2.0f, -0.5f}), {1, 1, -1}, 1e-5f, "corner at znear");
    expect_near(transform_point(c->projection, {-6.0f, -2.0f, -20.0f}), {-1, -1, 1}, 1e-5f, "corner at zfar");
}

TEST(SceneCamera, NoNodeUsesTheCamera) {
    Camera cam;
    Scene s = camera_scene(cam);
    auto inst = flatten(s);
    EXPECT_FALSE(scene_camera(s, inst, 0, 100, 100).has_value()) << "camera 0 is in the file but on no node";
    EXPECT_FALSE(scene_camera(s, inst, 2, 100, 100).has_value()) << "there is no camera 2";
    EXPECT_FALSE(scene_camera(s, {}, 1, 100, 100).has_value()) << "no instances: the scene is empty";
}

TEST(SceneBounds, CornersOfEachBoxTransformedAndBoxedAgain) {
    // docs/shading.md: the 8 corners of each POSITION box, through its node's world matrix, boxed again.
    Scene s;
    Primitive prim;
    prim.bounds_min = glm::vec3(-1.0f);
    prim.bounds_max = glm::vec3(1.0f);
    s.meshes.push_back(Mesh{"cube", {prim}, {}});
    Node a, b;
    a.mesh = 0;
    a.local = glm::rotate(glm::mat4(1.0f), float(45 * kDeg), glm::vec3(0, 1, 0));
    b.mesh = 0;
    b.local = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0));
    s.nodes = {a, b};
    s.scenes = {{0, 1}};
    Bounds bb = scene_bounds(s, flatten(s));
    ASSERT_FALSE(bb.empty);
    float r2 = std::sqrt(2.0f);
    expect_near(bb.min, {-r2, -1, -r2}, 1e-5f, "min");
    expect_near(bb.max, {11, 1, r2}, 1e-5f, "max");
    EXPECT_NEAR(bb.radius(), 0.5f * glm::length(glm::vec3(11 + r2, 2, 2 * r2)), 1e-5f);
}

}  // namespace
