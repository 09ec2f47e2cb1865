#pragma once
// Lights in world space, ready for shading: from KHR_lights_punctual nodes,
// from the command line, or the default pair used when a scene has none.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "fresnel/scene/scene.h"

namespace fresnel {

struct LightInstance {
    Light::Type type = Light::Type::Directional;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the direction the light travels (spot: its axis)
    glm::vec3 radiance{1.0f};                // colour * intensity (lux or candela)
    float range = 0.0f;                      // 0 = infinite
    float inner_cone = 0.0f, outer_cone = 0.7853982f;
    bool operator==(const LightInstance&) const = default;
};

// Every KHR_lights_punctual light attached to a node of the flattened scene.
std::vector<LightInstance> scene_lights(const Scene& scene, const std::vector<NodeInstance>& instances);

// The direction a light arriving from azimuth/elevation (degrees, same convention
// as the orbit camera's yaw/pitch: 0,0 = from +Z) travels.
glm::vec3 direction_from_angles(float azimuth_deg, float elevation_deg);

// The default lighting used when a scene has no lights and none are given:
//   key:  from azimuth 30, elevation 45, 3.0 lux, white
//   fill: from azimuth -120, elevation 15, 1.0 lux, slightly cool (0.85, 0.9, 1.0)
std::vector<LightInstance> default_lights();

// The light's radiance arriving at `position` (colour * intensity, times the range window
// clamp(1 - (d/range)^4, 0, 1) / d^2 and the spot cone's smooth falloff for point and spot
// lights), the unit direction `l` towards the light and its distance (infinite for
// directional lights). The C++ twin of light_incident in shaders/lights.glsl (the path
// tracer shades punctual lights with it).
glm::vec3 light_incident(const LightInstance& light, glm::vec3 position, glm::vec3& l, float& distance);

// Parses the CLI forms "dir:AZ,EL,LUX[,R,G,B]", "point:X,Y,Z,CANDELA[,R,G,B]" and
// "spot:X,Y,Z,AZ,EL,CANDELA,INNER,OUTER[,R,G,B]" (aimed as a dir light from AZ,EL travels;
// cone half-angles in degrees, 0 <= INNER < OUTER <= 90).
// Throws fresnel::Error (file "--light") on malformed input.
LightInstance parse_light(const std::string& spec);

}  // namespace fresnel
