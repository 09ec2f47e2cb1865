#pragma once
// Area lights (rect, disk, sphere, tube: fresnel::LightInstance) as the path tracer's emitters: points
// sampled on them for next-event estimation, and the rays that meet them, with the solid-angle
// densities that multiple importance sampling weighs the two by. Rectangles and disks emit from
// the side they face (LightInstance::direction), spheres and tubes everywhere, each with the same radiance
// (nits) over its surface. Lights are not geometry: they block no ray (as in Cycles, and as the
// rasteriser draws them), and camera rays do not see them.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "fresnel/job/lights.h"

namespace fresnel::trace {

struct AreaLightSample {
    glm::vec3 l{0.0f};         // unit direction from the shaded point to the sampled point
    float distance = 0.0f;     // to the sampled point
    glm::vec3 radiance{0.0f};  // arriving along -l (0 where the point's emitting side looks away)
    float pdf = 0.0f;          // solid-angle density of l; 0: no sample (behind a one-sided light, inside a sphere)
};

// A point on `light` seen from `p`: uniform over a rectangle's or disk's area (Shirley's
// concentric map for the disk), uniform over the cone of directions a sphere subtends, uniform
// over a tube's (capsule's) area, keeping the points whose side faces p.
AreaLightSample sample_area_light(const LightInstance& light, glm::vec3 p, glm::vec2 u);

// Where the ray origin + t dir (dir unit length) first meets `light`'s emitting side with
// t in (0, tmax): its radiance and, in `pdf`, the density sample_area_light gives that direction
// from `origin`; 0 radiance and pdf when it misses.
glm::vec3 area_light_hit(const LightInstance& light, glm::vec3 origin, glm::vec3 dir, float tmax, float& pdf, float& t);

}  // namespace fresnel::trace
