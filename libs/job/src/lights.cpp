#include "fresnel/job/lights.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <glm/geometric.hpp>
#include <sstream>

#include "fresnel/core/error.h"
#include "fresnel/core/float_text.h"

namespace fresnel {

glm::vec3 light_incident(const LightInstance& light, glm::vec3 position, glm::vec3& l, float& distance) {
    if (light.type == Light::Type::Directional) {
        l = -light.direction;
        distance = INFINITY;
        return light.radiance;
    }
    glm::vec3 to_light = light.position - position;
    float dist = glm::length(to_light);
    l = dist > 0.0f ? to_light / dist : glm::vec3(0.0f, 0.0f, 1.0f);
    distance = dist;
    float d2 = std::max(dist * dist, 1e-8f);
    float attenuation = 1.0f / d2;
    if (light.range > 0.0f) {
        float r = dist / light.range;
        attenuation = std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f) / d2;
    }
    glm::vec3 radiance = light.radiance * attenuation;
    if (light.is_area()) {
        // Seen as a point at its centre: luminance x projected area (a rectangle or disk seen at
        // an angle; a sphere's disk). Shading that integrates the area (ltc.h) does not use this.
        float projected = light.type == Light::Type::Sphere ? 3.14159265f * light.radius * light.radius
                          : light.type == Light::Type::Tube
                              ? 3.14159265f * light.radius * light.radius +
                                    4.0f * light.radius * glm::length(glm::cross(light.axis_u, l))  // its silhouette
                              : light.area() * std::max(glm::dot(light.direction, -l), 0.0f);
        return light.radiance * (projected / d2);
    }
    if (light.type == Light::Type::Spot) {
        // The renderer's packing (renderer.cpp, pack_frame): scale and offset of the cone.
        float scale = 1.0f / std::max(0.001f, std::cos(light.inner_cone) - std::cos(light.outer_cone));
        float offset = -std::cos(light.outer_cone) * scale;
        float a = std::clamp(glm::dot(light.direction, -l) * scale + offset, 0.0f, 1.0f);
        radiance *= a * a;
    }
    return radiance;
}

float LightInstance::area() const {
    switch (type) {
        case Light::Type::Rect: return 4.0f * glm::length(glm::cross(axis_u, axis_v));
        case Light::Type::Disk: return 3.14159265f * glm::length(glm::cross(axis_u, axis_v));
        case Light::Type::Sphere: return 4.0f * 3.14159265f * radius * radius;
        case Light::Type::Tube: return 4.0f * 3.14159265f * radius * (radius + glm::length(axis_u));  // 2 pi r 2L + 4 pi r^2
        default: return 0.0f;
    }
}

void area_light_axes(glm::vec3 direction, float width, float height, glm::vec3& axis_u, glm::vec3& axis_v) {
    glm::vec3 d = glm::normalize(direction);
    glm::vec3 up = std::abs(d.y) > 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    // u across; v = d x u, so that u x v = u x (d x u) = d (u.u) - u (u.d) = d (u is normal to d).
    glm::vec3 u = glm::normalize(glm::cross(up, d));
    glm::vec3 v = glm::cross(d, u);
    axis_u = u * (0.5f * width);
    axis_v = v * (0.5f * height);
}

std::vector<LightInstance> scene_lights(const Scene& scene, const std::vector<NodeInstance>& instances) {
    std::vector<LightInstance> out;
    for (const auto& inst : instances) {
        const Node& node = scene.nodes[std::size_t(inst.node)];
        if (node.light < 0 || !inst.visible) continue;
        const Light& l = scene.lights[std::size_t(node.light)];
        LightInstance li;
        li.type = l.type;
        li.position = glm::vec3(inst.world[3]);
        glm::vec3 d = -glm::vec3(inst.world[2]);  // lights point down their local -Z
        float len = glm::length(d);
        li.direction = len > 0 ? d / len : glm::vec3(0, 0, -1);
        li.radiance = l.color * l.intensity;
        li.range = l.range;
        li.inner_cone = l.inner_cone_angle;
        li.outer_cone = l.outer_cone_angle;
        // Area lights: the node's X and Y axes (scale included) span the rectangle or disk; a
        // sphere takes the largest scale.
        glm::vec3 x = glm::vec3(inst.world[0]), y = glm::vec3(inst.world[1]), z = glm::vec3(inst.world[2]);
        if (l.type == Light::Type::Rect) {
            li.axis_u = x * (0.5f * l.width);
            li.axis_v = y * (0.5f * l.height);
        } else if (l.type == Light::Type::Disk) {
            li.axis_u = x * l.radius;
            li.axis_v = y * l.radius;
        } else if (l.type == Light::Type::Sphere) {
            li.radius = l.radius * std::max({glm::length(x), glm::length(y), glm::length(z)});
        } else if (l.type == Light::Type::Tube) {  // along the node's X; the radius by the larger of the others
            li.axis_u = x * (0.5f * l.length);
            li.axis_v = glm::vec3(0.0f);
            li.radius = l.radius * std::max(glm::length(y), glm::length(z));
            if (glm::length(x) > 0.0f) li.direction = glm::normalize(x);
        }
        // u x v faces where the light emits (the node's X x Y is its +Z, away from it; a
        // mirroring transform turns that too).
        if ((li.type == Light::Type::Rect || li.type == Light::Type::Disk) &&
            glm::dot(glm::cross(li.axis_u, li.axis_v), li.direction) < 0.0f)
            li.axis_v = -li.axis_v;
        out.push_back(li);
    }
    return out;
}

glm::vec3 direction_from_angles(float azimuth_deg, float elevation_deg) {
    const float deg = 3.14159265358979f / 180.0f;
    float a = azimuth_deg * deg, e = elevation_deg * deg;
    glm::vec3 from(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
    return -from;
}

std::vector<LightInstance> default_lights() {
    LightInstance key, fill;
    key.direction = direction_from_angles(30.0f, 45.0f);
    key.radiance = glm::vec3(3.0f);
    fill.direction = direction_from_angles(-120.0f, 15.0f);
    fill.radiance = glm::vec3(0.85f, 0.9f, 1.0f) * 1.0f;
    return {key, fill};
}

LightInstance parse_light(const std::string& spec) {
    auto colon = spec.find(':');
    auto fail = [&](const std::string& why) -> void { throw Error("--light", spec, why); };
    if (colon == std::string::npos)
        fail("expected dir:AZIMUTH,ELEVATION,LUX[,R,G,B], point:X,Y,Z,CANDELA[,R,G,B], "
             "spot:X,Y,Z,AZIMUTH,ELEVATION,CANDELA,INNER,OUTER[,R,G,B], rect:X,Y,Z,AZIMUTH,ELEVATION,WIDTH,HEIGHT,NITS[,R,G,B], "
             "disk:X,Y,Z,AZIMUTH,ELEVATION,RADIUS,NITS[,R,G,B], sphere:X,Y,Z,RADIUS,NITS[,R,G,B] or "
             "tube:X,Y,Z,AZIMUTH,ELEVATION,LENGTH,RADIUS,NITS[,R,G,B]");
    std::string kind = spec.substr(0, colon);
    std::vector<float> v;
    std::stringstream ss(spec.substr(colon + 1));
    std::string item;
    // The size its shadows come from, a last item: radius=R (point and spot lights: the bulb,
    // metres) or angle=A (directional lights: the angular radius, degrees).
    std::optional<float> bulb, angle;
    while (std::getline(ss, item, ',')) {
        if (bulb || angle) fail("radius=R or angle=A comes last");
        const bool is_radius = item.rfind("radius=", 0) == 0, is_angle = item.rfind("angle=", 0) == 0;
        if (is_radius || is_angle) {
            const std::string key = is_radius ? "radius" : "angle", value = item.substr(key.size() + 1);
            try {
                std::size_t used = 0;
                float f = std::stof(value, &used);
                if (used != value.size() || !std::isfinite(f) || f < 0.0f || (is_angle && f > 20.0f))
                    fail(key + ": '" + value + (is_angle ? "' is not an angle in [0, 20] degrees" : "' is not a length >= 0"));
                (is_radius ? bulb : angle) = f;
            } catch (const std::logic_error&) {
                fail(key + ": '" + value + "' is not a number");
            }
            continue;
        }
        try {
            std::size_t used = 0;
            float f = std::stof(item, &used);
            if (used != item.size() || !std::isfinite(f)) fail("'" + item + "' is not a number");
            v.push_back(f);
        } catch (const std::logic_error&) {
            fail("'" + item + "' is not a number");
        }
    }
    LightInstance l;
    glm::vec3 color(1.0f);
    if (kind == "dir") {
        if (v.size() != 3 && v.size() != 6) fail("dir: needs AZIMUTH,ELEVATION,LUX[,R,G,B]");
        l.type = Light::Type::Directional;
        l.direction = direction_from_angles(v[0], v[1]);
        if (v.size() == 6) color = {v[3], v[4], v[5]};
        l.radiance = color * v[2];
    } else if (kind == "point") {
        if (v.size() != 4 && v.size() != 7) fail("point: needs X,Y,Z,CANDELA[,R,G,B]");
        l.type = Light::Type::Point;
        l.position = {v[0], v[1], v[2]};
        if (v.size() == 7) color = {v[4], v[5], v[6]};
        l.radiance = color * v[3];
    } else if (kind == "spot") {
        if (v.size() != 8 && v.size() != 11) fail("spot: needs X,Y,Z,AZIMUTH,ELEVATION,CANDELA,INNER,OUTER[,R,G,B]");
        l.type = Light::Type::Spot;
        l.position = {v[0], v[1], v[2]};
        l.direction = direction_from_angles(v[3], v[4]);  // it shines as a dir light from AZIMUTH,ELEVATION would
        const float deg = 3.14159265358979f / 180.0f;
        l.inner_cone = v[6] * deg;
        l.outer_cone = v[7] * deg;
        // KHR_lights_punctual's ranges: 0 <= inner < outer <= pi/2.
        if (!(v[6] >= 0.0f && v[6] < v[7] && v[7] <= 90.0f)) fail("spot cone angles need 0 <= INNER < OUTER <= 90 degrees");
        if (v.size() == 11) color = {v[8], v[9], v[10]};
        l.radiance = color * v[5];
    } else if (kind == "rect" || kind == "disk") {
        const bool rect = kind == "rect";
        const std::size_t n = rect ? 8 : 7;
        if (v.size() != n && v.size() != n + 3)
            fail(rect ? "rect: needs X,Y,Z,AZIMUTH,ELEVATION,WIDTH,HEIGHT,NITS[,R,G,B]" : "disk: needs X,Y,Z,AZIMUTH,ELEVATION,RADIUS,NITS[,R,G,B]");
        l.type = rect ? Light::Type::Rect : Light::Type::Disk;
        l.position = {v[0], v[1], v[2]};
        l.direction = direction_from_angles(v[3], v[4]);  // it faces as a spot light from AZIMUTH,ELEVATION aims
        float w = v[5], h = rect ? v[6] : v[5];
        if (!(w > 0.0f && h > 0.0f)) fail(rect ? "WIDTH and HEIGHT must be positive" : "RADIUS must be positive");
        area_light_axes(l.direction, rect ? w : 2.0f * w, rect ? h : 2.0f * h, l.axis_u, l.axis_v);
        if (v.size() == n + 3) color = {v[n], v[n + 1], v[n + 2]};
        l.radiance = color * v[n - 1];
    } else if (kind == "tube") {
        if (v.size() != 8 && v.size() != 11) fail("tube: needs X,Y,Z,AZIMUTH,ELEVATION,LENGTH,RADIUS,NITS[,R,G,B]");
        l.type = Light::Type::Tube;
        l.position = {v[0], v[1], v[2]};
        l.direction = -direction_from_angles(v[3], v[4]);  // its axis points towards AZIMUTH,ELEVATION
        if (!(v[5] > 0.0f && v[6] > 0.0f)) fail("LENGTH and RADIUS must be positive");
        l.axis_u = l.direction * (0.5f * v[5]);
        l.axis_v = glm::vec3(0.0f);
        l.radius = v[6];
        if (v.size() == 11) color = {v[8], v[9], v[10]};
        l.radiance = color * v[7];
    } else if (kind == "sphere") {
        if (v.size() != 5 && v.size() != 8) fail("sphere: needs X,Y,Z,RADIUS,NITS[,R,G,B]");
        l.type = Light::Type::Sphere;
        l.position = {v[0], v[1], v[2]};
        if (!(v[3] > 0.0f)) fail("RADIUS must be positive");
        l.radius = v[3];
        if (v.size() == 8) color = {v[5], v[6], v[7]};
        l.radiance = color * v[4];
    } else {
        fail("unknown light type '" + kind + "' (use dir, point, spot, rect, disk, sphere or tube)");
    }
    if (l.radiance.x < 0 || l.radiance.y < 0 || l.radiance.z < 0) fail("intensity and colour must not be negative");
    if (bulb) {
        if (l.type != Light::Type::Point && l.type != Light::Type::Spot)
            fail("radius=R is for point and spot lights (the bulb their soft shadows come from)");
        l.radius = *bulb;
    }
    if (angle) {
        if (l.type != Light::Type::Directional) fail("angle=A is for dir lights (the angular radius their soft shadows come from)");
        l.radius = *angle * 3.14159265358979f / 180.0f;
    }
    return l;
}

std::string light_spec(const LightInstance& l) {
    auto nums = [](std::initializer_list<float> v) {  // the shortest forms that read back as the same floats
        std::string out;
        for (float f : v) out += (out.empty() ? "" : ",") + shortest_text(f);
        return out;
    };
    const float lum = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
    const glm::vec3 color = lum > 0 ? l.radiance / lum : glm::vec3(1.0f);
    const std::string rgb = color == glm::vec3(1.0f) ? "" : "," + nums({color.x, color.y, color.z});
    const float deg = 180.0f / 3.14159265358979f;
    const glm::vec3 from = -l.direction;
    const float el = std::asin(std::clamp(from.y, -1.0f, 1.0f)) * deg, az = std::atan2(from.x, from.z) * deg;
    const glm::vec3 p = l.position;
    const std::string bulb = l.radius > 0.0f ? ",radius=" + shortest_text(l.radius) : "";
    switch (l.type) {
        case Light::Type::Directional:
            return "dir:" + nums({az, el, lum}) + rgb + (l.radius > 0.0f ? ",angle=" + shortest_text(l.radius * deg) : "");
        case Light::Type::Point: return "point:" + nums({p.x, p.y, p.z, lum}) + rgb + bulb;
        case Light::Type::Spot:
            return "spot:" + nums({p.x, p.y, p.z, az, el, lum, l.inner_cone * deg, l.outer_cone * deg}) + rgb + bulb;
        case Light::Type::Rect:
            return "rect:" + nums({p.x, p.y, p.z, az, el, 2.0f * glm::length(l.axis_u), 2.0f * glm::length(l.axis_v), lum}) + rgb;
        case Light::Type::Disk: return "disk:" + nums({p.x, p.y, p.z, az, el, glm::length(l.axis_u), lum}) + rgb;
        case Light::Type::Sphere: return "sphere:" + nums({p.x, p.y, p.z, l.radius, lum}) + rgb;
        case Light::Type::Tube: {
            const glm::vec3 axis = glm::length(l.axis_u) > 0.0f ? glm::normalize(l.axis_u) : glm::vec3(1, 0, 0);
            const float tel = std::asin(std::clamp(axis.y, -1.0f, 1.0f)) * deg, taz = std::atan2(axis.x, axis.z) * deg;
            return "tube:" + nums({p.x, p.y, p.z, taz, tel, 2.0f * glm::length(l.axis_u), l.radius, lum}) + rgb;
        }
    }
    return "";
}

}  // namespace fresnel
