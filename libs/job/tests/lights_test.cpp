// Lights (fresnel/job/lights.h): the --light forms and their errors, KHR_lights_punctual
// nodes placed by their world matrices, and the default pair as docs/shading.md "Lighting rules"
// states it. Pure CPU.
#include "fresnel/job/lights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/core/error.h"
#include "fresnel/job/camera.h"

using namespace fresnel;

namespace {

constexpr float kDeg = 3.14159265358979f / 180.0f;

void expect_near(glm::vec3 a, glm::vec3 b, float eps, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, eps) << what;
    EXPECT_NEAR(a.y, b.y, eps) << what;
    EXPECT_NEAR(a.z, b.z, eps) << what;
}

// The direction a light from azimuth/elevation travels, written from docs/shading.md: the
// opposite of (cos e sin a, sin e, cos e cos a).
glm::vec3 travel(float az, float el) {
    float a = az * kDeg, e = el * kDeg;
    return -glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
}

TEST(DirectionFromAngles, UsesTheOrbitCameraConvention) {
    expect_near(direction_from_angles(0, 0), {0, 0, -1}, 1e-6f, "from +Z travels -Z");
    expect_near(direction_from_angles(90, 0), {-1, 0, 0}, 1e-6f, "from +X travels -X");
    expect_near(direction_from_angles(0, 90), {0, -1, 0}, 1e-6f, "from above travels down");
    // A light from (yaw, pitch) arrives from where the orbit camera at (yaw, pitch) stands.
    Bounds b;
    b.min = glm::vec3(-1);
    b.max = glm::vec3(1);
    b.empty = false;
    for (auto [az, el] : {std::pair{30.0f, 45.0f}, std::pair{-120.0f, 15.0f}, std::pair{200.0f, -10.0f}}) {
        OrbitParams p;
        p.yaw_deg = az;
        p.pitch_deg = el;
        CameraSetup c = orbit_camera(b, p, 100, 100);
        expect_near(-direction_from_angles(az, el), glm::normalize(c.eye - c.target), 1e-5f,
                    "azimuth " + std::to_string(az) + " elevation " + std::to_string(el));
        expect_near(direction_from_angles(az, el), travel(az, el), 1e-6f, "formula");
    }
}

TEST(ParseLight, DirectionalForms) {
    LightInstance l = parse_light("dir:30,45,3");
    EXPECT_EQ(l.type, Light::Type::Directional);
    expect_near(l.direction, travel(30, 45), 1e-6f, "direction");
    expect_near(l.radiance, glm::vec3(3.0f), 1e-6f, "white, 3 lux");

    l = parse_light("dir:-90,10,2,1,0.5,0.25");
    EXPECT_EQ(l.type, Light::Type::Directional);
    expect_near(l.direction, travel(-90, 10), 1e-6f, "direction");
    expect_near(l.radiance, {2.0f, 1.0f, 0.5f}, 1e-6f, "colour times lux");
    EXPECT_FLOAT_EQ(glm::length(l.direction), 1.0f);
}

TEST(ParseLight, PointForms) {
    LightInstance l = parse_light("point:1,-2,3.5,100");
    EXPECT_EQ(l.type, Light::Type::Point);
    expect_near(l.position, {1.0f, -2.0f, 3.5f}, 1e-6f, "position");
    expect_near(l.radiance, glm::vec3(100.0f), 1e-4f, "white, 100 cd");
    EXPECT_EQ(l.range, 0.0f) << "infinite range";

    l = parse_light("point:0,0,0,8,0.5,1,0");
    expect_near(l.radiance, {4.0f, 8.0f, 0.0f}, 1e-6f, "colour times candela");
    l = parse_light("point:1e1,2E-1,-0,0");
    expect_near(l.position, {10.0f, 0.2f, 0.0f}, 1e-6f, "exponent forms");
    expect_near(l.radiance, glm::vec3(0.0f), 0.0f, "zero intensity is allowed");
}

TEST(ParseLight, SpotForms) {
    // Above the origin, shining straight down (as a dir light from elevation 90 travels).
    LightInstance l = parse_light("spot:0,2,0,0,90,50,10,30");
    EXPECT_EQ(l.type, Light::Type::Spot);
    expect_near(l.position, {0.0f, 2.0f, 0.0f}, 1e-6f, "position");
    expect_near(l.direction, {0.0f, -1.0f, 0.0f}, 1e-6f, "aimed down");
    EXPECT_NEAR(l.inner_cone, 10.0f * 3.14159265f / 180.0f, 1e-6f);
    EXPECT_NEAR(l.outer_cone, 30.0f * 3.14159265f / 180.0f, 1e-6f);
    expect_near(l.radiance, glm::vec3(50.0f), 1e-5f, "white, 50 cd");
    l = parse_light("spot:1,2,3,-90,10,4,0,45,1,0.5,0");
    expect_near(l.direction, travel(-90, 10), 1e-6f, "direction as dir: travels");
    expect_near(l.radiance, {4.0f, 2.0f, 0.0f}, 1e-6f, "colour times candela");
}

// A point or spot light's bulb (the last item radius=R): its soft shadows' size (the
// rasteriser's contact hardening, the tracer's sphere), read back by light_spec; none by default.
TEST(ParseLight, BulbRadiusOfPointAndSpotLights) {
    LightInstance l = parse_light("point:1,2,3,40,radius=0.25");
    EXPECT_EQ(l.type, Light::Type::Point);
    EXPECT_FLOAT_EQ(l.radius, 0.25f);
    expect_near(l.radiance, glm::vec3(40.0f), 1e-6f, "white, 40 cd");
    EXPECT_EQ(light_spec(l), "point:1,2,3,40,radius=0.25");
    EXPECT_EQ(parse_light(light_spec(l)), l);
    l = parse_light("spot:0,3,0,0,90,60,20,34,1,0.5,0,radius=0.1");
    EXPECT_EQ(l.type, Light::Type::Spot);
    EXPECT_FLOAT_EQ(l.radius, 0.1f);
    expect_near(l.radiance, {60.0f, 30.0f, 0.0f}, 1e-5f, "colour times candela");
    EXPECT_EQ(parse_light(light_spec(l)).radius, 0.1f);
    EXPECT_EQ(parse_light("point:1,2,3,40").radius, 0.0f);
    EXPECT_EQ(light_spec(parse_light("point:1,2,3,40")), "point:1,2,3,40");
    // A dir light's angular radius, in degrees (radians in LightInstance::radius).
    l = parse_light("dir:30,45,3,angle=0.5");
    EXPECT_NEAR(l.radius, 0.5f * 3.14159265f / 180.0f, 1e-7f);
    EXPECT_NEAR(parse_light(light_spec(l)).radius, l.radius, 1e-7f);
    EXPECT_NE(light_spec(l).find(",angle="), std::string::npos) << light_spec(l);
}

TEST(ParseLight, ErrorsNameTheOptionTheSpecAndTheReason) {
    struct Case {
        const char* spec;
        const char* reason;  // a part of the message
    };
    const Case cases[] = {
        {"", "expected dir:AZIMUTH,ELEVATION,LUX[,R,G,B], point:X,Y,Z,CANDELA[,R,G,B], spot:"},
        {"dir", "expected dir:"},
        {"30,45,3", "expected dir:"},
        {"dir:", "dir: needs AZIMUTH,ELEVATION,LUX[,R,G,B]"},
        {"dir:30,45", "dir: needs AZIMUTH,ELEVATION,LUX[,R,G,B]"},
        {"dir:30,45,3,1", "dir: needs"},
        {"dir:30,45,3,1,1", "dir: needs"},
        {"dir:30,45,3,1,1,1,1", "dir: needs"},
        {"point:1,2,3", "point: needs X,Y,Z,CANDELA[,R,G,B]"},
        {"point:1,2,3,4,5", "point: needs"},
        {"point:1,2,3,4,5,6,7,8", "point: needs"},
        {"spot:1,2,3,4", "spot: needs X,Y,Z,AZIMUTH,ELEVATION,CANDELA,INNER,OUTER[,R,G,B]"},
        {"spot:0,1,0,0,90,5,30,20", "0 <= INNER < OUTER <= 90"},
        {"spot:0,1,0,0,90,5,10,95", "0 <= INNER < OUTER <= 90"},
        {"cone:1,2,3,4", "unknown light type 'cone' (use dir, point, spot, rect, disk, sphere or tube)"},
        {"DIR:30,45,3", "unknown light type 'DIR'"},
        {"dir:a,45,3", "'a' is not a number"},
        {"dir:30,45,3x", "'3x' is not a number"},
        {"dir:30,,3", "'' is not a number"},
        {"dir:30,45,inf", "'inf' is not a number"},
        {"dir:30,45,nan", "'nan' is not a number"},
        {"dir:30,45,1e99", "'1e99' is not a number"},
        {"dir:30,45,-3", "must not be negative"},
        {"point:0,0,0,1,1,-0.5,1", "must not be negative"},
        {"point:0,1,0,10,radius=-0.1", "radius: '-0.1' is not a length >= 0"},
        {"point:0,1,0,10,radius=x", "radius: 'x' is not a number"},
        {"point:0,1,0,10,radius=0.1,1,1,1", "radius=R or angle=A comes last"},
        {"dir:30,45,3,radius=0.1", "radius=R is for point and spot lights"},
        {"point:0,1,0,10,angle=1", "angle=A is for dir lights"},
        {"dir:30,45,3,angle=30", "angle: '30' is not an angle in [0, 20] degrees"},
        {"sphere:0,1,0,0.2,5,radius=0.1", "radius=R is for point and spot lights"},
    };
    for (const auto& c : cases) {
        try {
            parse_light(c.spec);
            ADD_FAILURE() << "'" << c.spec << "' was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), "--light") << c.spec;
            EXPECT_EQ(e.where(), c.spec);
            EXPECT_NE(e.reason().find(c.reason), std::string::npos) << "'" << c.spec << "': " << e.reason();
            EXPECT_NE(std::string(e.what()).find(c.reason), std::string::npos) << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << "'" << c.spec << "' threw something other than fresnel::Error: " << e.what();
        }
    }
}

TEST(DefaultLights, AreTheReadmesKeyAndFill) {
    auto lights = default_lights();
    ASSERT_EQ(lights.size(), 2u);
    const LightInstance& key = lights[0];
    const LightInstance& fill = lights[1];
    EXPECT_EQ(key.type, Light::Type::Directional);
    EXPECT_EQ(fill.type, Light::Type::Directional);
    // key: from azimuth 30, elevation 45, 3 lux, white.
    expect_near(key.direction, travel(30, 45), 1e-6f, "key direction");
    expect_near(key.radiance, glm::vec3(3.0f), 1e-6f, "key");
    // fill: from azimuth -120, elevation 15, 1 lux, slightly cool.
    expect_near(fill.direction, travel(-120, 15), 1e-6f, "fill direction");
    EXPECT_NEAR(std::max({fill.radiance.x, fill.radiance.y, fill.radiance.z}), 1.0f, 1e-6f) << "1 lux";
    EXPECT_LT(fill.radiance.x, fill.radiance.z) << "cool: more blue than red";
    expect_near(fill.radiance, {0.85f, 0.9f, 1.0f}, 1e-6f, "fill colour (lights.h)");
    // Both arrive from above the horizon.
    EXPECT_LT(key.direction.y, 0.0f);
    EXPECT_LT(fill.direction.y, 0.0f);
}

// Node 0: translated (1, 2, 3), turned 90 degrees about +X, scaled by 3; its child node 1
// carries a spot light, node 2 (a root) a point light, node 3 a directional one; node 4
// has a light but belongs to scene 1 only, node 5 has none.
Scene light_scene() {
    Scene s;
    Light spot;
    spot.type = Light::Type::Spot;
    spot.color = {1.0f, 0.5f, 0.25f};
    spot.intensity = 40.0f;
    spot.range = 12.0f;
    spot.inner_cone_angle = 0.2f;
    spot.outer_cone_angle = 0.5f;
    Light point;
    point.type = Light::Type::Point;
    point.intensity = 7.0f;
    Light sun;
    sun.type = Light::Type::Directional;
    sun.intensity = 2.0f;
    sun.color = {0.5f, 0.5f, 1.0f};
    s.lights = {spot, point, sun};
    Node parent, spot_node, point_node, sun_node, other, plain;
    parent.local = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3)), 90.0f * kDeg,
                                          glm::vec3(1, 0, 0)),
                              glm::vec3(3.0f));
    parent.children = {1};
    spot_node.light = 0;
    spot_node.local = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
    point_node.light = 1;
    point_node.local = glm::translate(glm::mat4(1.0f), glm::vec3(-5, 0, 0));
    sun_node.light = 2;
    sun_node.local = glm::rotate(glm::mat4(1.0f), -90.0f * kDeg, glm::vec3(1, 0, 0));  // -Z turned to -Y
    other.light = 1;
    s.nodes = {parent, spot_node, point_node, sun_node, other, plain};
    s.scenes = {{0, 2, 3, 5}, {4}};
    return s;
}

TEST(SceneLights, PlacedByTheirNodesWorldMatrices) {
    Scene s = light_scene();
    auto lights = scene_lights(s, flatten(s, 0));
    ASSERT_EQ(lights.size(), 3u) << "the spot, point and directional light of scene 0";
    const LightInstance& spot = lights[0];
    EXPECT_EQ(spot.type, Light::Type::Spot);
    // (1,2,3) + R_x(90) * 3 * (0,1,0) = (1,2,3) + (0,0,3).
    expect_near(spot.position, {1, 2, 6}, 1e-5f, "spot position");
    // Lights shine down their local -Z: R_x(90) * (0,0,-1) = (0,1,0), unit length despite the scale.
    expect_near(spot.direction, {0, 1, 0}, 1e-5f, "spot direction");
    expect_near(spot.radiance, {40.0f, 20.0f, 10.0f}, 1e-5f, "colour times intensity");
    EXPECT_FLOAT_EQ(spot.range, 12.0f);
    EXPECT_FLOAT_EQ(spot.inner_cone, 0.2f);
    EXPECT_FLOAT_EQ(spot.outer_cone, 0.5f);

    const LightInstance& point = lights[1];
    EXPECT_EQ(point.type, Light::Type::Point);
    expect_near(point.position, {-5, 0, 0}, 1e-6f, "point position");
    expect_near(point.radiance, glm::vec3(7.0f), 1e-6f, "point");

    const LightInstance& sun = lights[2];
    EXPECT_EQ(sun.type, Light::Type::Directional);
    expect_near(sun.direction, {0, -1, 0}, 1e-5f, "sun shines down");
    expect_near(sun.radiance, {1.0f, 1.0f, 2.0f}, 1e-6f, "sun");

    auto other = scene_lights(s, flatten(s, 1));
    ASSERT_EQ(other.size(), 1u);
    EXPECT_EQ(other[0].type, Light::Type::Point);
    EXPECT_TRUE(scene_lights(s, {}).empty());
}

// Area lights from the command line: placed, facing as a spot light aims, sized, wound so that
// u x v faces where they emit; light_spec writes what parse_light reads back.
TEST(ParseLight, AreaForms) {
    LightInstance r = parse_light("rect:1,2,3,30,45,2,0.5,10,1,0.5,0.25");
    EXPECT_EQ(r.type, Light::Type::Rect);
    EXPECT_TRUE(r.is_area());
    expect_near(r.position, {1, 2, 3}, 1e-6f, "rect position");
    expect_near(r.direction, travel(30, 45), 1e-5f, "rect faces as a spot aims");
    EXPECT_NEAR(glm::length(r.axis_u), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(r.axis_v), 0.25f, 1e-5f);
    EXPECT_NEAR(glm::dot(r.axis_u, r.direction), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(r.axis_v, r.direction), 0.0f, 1e-5f);
    EXPECT_NEAR(r.axis_u.y, 0.0f, 1e-5f) << "the width runs horizontally";
    expect_near(glm::normalize(glm::cross(r.axis_u, r.axis_v)), r.direction, 1e-5f, "u x v faces the lit side");
    EXPECT_NEAR(r.area(), 1.0f, 1e-5f);
    expect_near(r.radiance, {10.0f, 5.0f, 2.5f}, 1e-5f, "nits times colour");

    LightInstance d = parse_light("disk:0,3,0,0,90,0.5,4");
    EXPECT_EQ(d.type, Light::Type::Disk);
    expect_near(d.direction, {0, -1, 0}, 1e-5f, "from straight above it faces down");
    EXPECT_NEAR(d.area(), 3.14159265f * 0.25f, 1e-5f);
    expect_near(glm::normalize(glm::cross(d.axis_u, d.axis_v)), d.direction, 1e-5f, "u x v faces the lit side");

    LightInstance sp = parse_light("sphere:0,1,0,0.1,100");
    EXPECT_EQ(sp.type, Light::Type::Sphere);
    EXPECT_FLOAT_EQ(sp.radius, 0.1f);
    EXPECT_NEAR(sp.area(), 4.0f * 3.14159265f * 0.01f, 1e-6f);

    LightInstance tube = parse_light("tube:0,2,0,90,0,1.5,0.05,30");
    EXPECT_EQ(tube.type, Light::Type::Tube);
    expect_near(tube.direction, {1, 0, 0}, 1e-5f, "its axis points towards azimuth 90");
    EXPECT_NEAR(glm::length(tube.axis_u), 0.75f, 1e-6f);
    EXPECT_FLOAT_EQ(tube.radius, 0.05f);
    EXPECT_NEAR(tube.area(), 2.0f * 3.14159265f * 0.05f * 1.5f + 4.0f * 3.14159265f * 0.0025f, 1e-5f);

    for (const LightInstance& l : {r, d, sp, tube}) {
        LightInstance back = parse_light(light_spec(l));
        EXPECT_EQ(back.type, l.type) << light_spec(l);
        expect_near(back.position, l.position, 1e-5f, light_spec(l));
        expect_near(back.direction, l.direction, 1e-5f, light_spec(l));
        expect_near(back.axis_u, l.axis_u, 1e-5f, light_spec(l));
        expect_near(back.axis_v, l.axis_v, 1e-5f, light_spec(l));
        EXPECT_NEAR(back.radius, l.radius, 1e-6f);
        expect_near(back.radiance, l.radiance, 1e-4f, light_spec(l));
    }
    for (const char* bad : {"rect:0,0,0,0,0,1,1", "rect:0,0,0,0,0,-1,1,5", "disk:0,0,0,0,0,0,5", "sphere:0,0,0,0,5",
                            "sphere:0,0,0,1", "tube:0,0,0,1,1", "tube:0,0,0,0,0,1,0,5", "cone:0,0,0"}) {
        try {
            parse_light(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), "--light") << bad;
        }
    }
}

// Seen from far away an area light is a point light of luminance x projected area (what the
// OpenGL 1 shading takes; light_incident's view of it).
TEST(LightIncident, AreaLightsFromAfarAreLuminanceTimesProjectedArea) {
    LightInstance r = parse_light("rect:0,10,0,0,90,2,1,3");  // facing down, 2 m^2
    glm::vec3 l;
    float dist = 0;
    glm::vec3 e = light_incident(r, {0, 0, 0}, l, dist);
    expect_near(l, {0, 1, 0}, 1e-6f, "towards the centre");
    EXPECT_NEAR(dist, 10.0f, 1e-5f);
    EXPECT_NEAR(e.x, 3.0f * 2.0f / 100.0f, 1e-6f);
    e = light_incident(r, {0, 20, 0}, l, dist);
    EXPECT_EQ(e.x, 0.0f) << "behind a one-sided light";
    LightInstance sp = parse_light("sphere:0,0,5,0.5,8");
    e = light_incident(sp, {0, 0, 0}, l, dist);
    EXPECT_NEAR(e.x, 8.0f * 3.14159265f * 0.25f / 25.0f, 1e-6f);
}

// glTF area lights (EXT_lights_area) on nodes: the node's X and Y axes (scale included) span
// the rectangle or disk, which emits down its -Z; a sphere takes the largest scale.
TEST(SceneLights, AreaLightsPlacedByTheirNodes) {
    Scene s;
    Light rect;
    rect.type = Light::Type::Rect;
    rect.width = 2.0f;
    rect.height = 1.0f;
    rect.intensity = 5.0f;
    Light sphere;
    sphere.type = Light::Type::Sphere;
    sphere.radius = 0.25f;
    s.lights = {rect, sphere};
    Node a, b;
    a.light = 0;
    a.local = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 3, 0)), -90.0f * kDeg, glm::vec3(1, 0, 0)),
                         glm::vec3(2.0f, 1.0f, 1.0f));
    b.light = 1;
    b.local = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 4.0f, 2.0f));
    s.nodes = {a, b};
    s.scenes = {{0, 1}};
    auto lights = scene_lights(s, flatten(s, 0));
    ASSERT_EQ(lights.size(), 2u);
    const LightInstance& r = lights[0];
    expect_near(r.direction, {0, -1, 0}, 1e-5f, "-Z turned down");
    EXPECT_NEAR(r.area(), 4.0f, 1e-4f) << "2 x 1 scaled by 2 along its width";
    expect_near(glm::normalize(glm::cross(r.axis_u, r.axis_v)), r.direction, 1e-5f, "u x v faces the lit side");
    EXPECT_NEAR(lights[1].radius, 1.0f, 1e-6f) << "the largest scale";
}

}  // namespace
