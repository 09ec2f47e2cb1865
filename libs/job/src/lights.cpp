#include "fresnel/job/lights.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <sstream>

#include "fresnel/core/error.h"

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
    if (light.type == Light::Type::Spot) {
        // The renderer's packing (renderer.cpp, pack_frame): scale and offset of the cone.
        float scale = 1.0f / std::max(0.001f, std::cos(light.inner_cone) - std::cos(light.outer_cone));
        float offset = -std::cos(light.outer_cone) * scale;
        float a = std::clamp(glm::dot(light.direction, -l) * scale + offset, 0.0f, 1.0f);
        radiance *= a * a;
    }
    return radiance;
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
        fail("expected dir:AZIMUTH,ELEVATION,LUX[,R,G,B], point:X,Y,Z,CANDELA[,R,G,B] or "
             "spot:X,Y,Z,AZIMUTH,ELEVATION,CANDELA,INNER,OUTER[,R,G,B]");
    std::string kind = spec.substr(0, colon);
    std::vector<float> v;
    std::stringstream ss(spec.substr(colon + 1));
    std::string item;
    while (std::getline(ss, item, ',')) {
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
    } else {
        fail("unknown light type '" + kind + "' (use dir, point or spot)");
    }
    if (l.radiance.x < 0 || l.radiance.y < 0 || l.radiance.z < 0) fail("intensity and colour must not be negative");
    return l;
}

}  // namespace fresnel
