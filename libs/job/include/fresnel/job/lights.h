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
    // Area lights (radiance in nits): a rectangle's half extents, a disk's radii (both in the
    // plane the light faces out of, along `direction`; u x v = direction, so the corners p - u - v,
    // p + u - v, p + u + v, p - u + v run counter-clockwise seen from the lit side, as
    // fresnel/material/ltc.h wants them); a sphere's radius; a tube's half length along axis_u
    // (its `direction` the axis's) and its radius. A point or spot light's radius: its bulb,
    // which only its shadows see (contact-hardening in the rasteriser, a sphere's shadow in the
    // tracer); a directional light's: its angular radius in radians, the same for its cone of
    // directions; 0: a point, one direction.
    glm::vec3 axis_u{0.5f, 0.0f, 0.0f}, axis_v{0.0f, 0.5f, 0.0f};
    float radius = 0.0f;
    bool operator==(const LightInstance&) const = default;
    bool is_area() const { return is_area_light(type); }
    float area() const;  // of the emitting surface (m^2); 0 for punctual lights
};

// The half-extent axes of an area light facing along `direction` (the way it emits), `width`
// across (horizontal where the light does not face straight up or down) and `height` along
// the other axis, with u x v = direction.
void area_light_axes(glm::vec3 direction, float width, float height, glm::vec3& axis_u, glm::vec3& axis_v);

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
// tracer shades punctual lights with it). Area lights come back as a point at their centre of
// luminance x projected area (the OpenGL 1 shading's view of them); the PBR shading and the
// tracer integrate their area instead.
glm::vec3 light_incident(const LightInstance& light, glm::vec3 position, glm::vec3& l, float& distance);

// Parses the CLI forms "dir:AZ,EL,LUX[,R,G,B]", "point:X,Y,Z,CANDELA[,R,G,B]",
// "spot:X,Y,Z,AZ,EL,CANDELA,INNER,OUTER[,R,G,B]" (aimed as a dir light from AZ,EL travels;
// cone half-angles in degrees, 0 <= INNER < OUTER <= 90) and the area lights
// "rect:X,Y,Z,AZ,EL,WIDTH,HEIGHT,NITS[,R,G,B]", "disk:X,Y,Z,AZ,EL,RADIUS,NITS[,R,G,B]" (facing
// as a spot light aims), "sphere:X,Y,Z,RADIUS,NITS[,R,G,B]" and
// "tube:X,Y,Z,AZ,EL,LENGTH,RADIUS,NITS[,R,G,B]" (its axis pointing towards AZ,EL). Point and
// spot lights take a last item "radius=R": their bulb's radius (LightInstance::radius), which
// softens their shadows (contact hardening) and leaves their shading a point's; dir lights
// "angle=A": their angular radius in degrees (at most 20; the sun's is about 0.27).
// Throws fresnel::Error (file "--light") on malformed input.
LightInstance parse_light(const std::string& spec);

// The light as parse_light reads it back ("dir:...", "rect:...": a range is not part of that
// syntax; a rectangle's or disk's turn about its facing is the one area_light_axes gives).
std::string light_spec(const LightInstance& light);


}  // namespace fresnel
