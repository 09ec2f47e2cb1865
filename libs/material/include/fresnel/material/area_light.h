#pragma once
// Area lights (rectangles, disks, spheres of uniform luminance) on the material, as the
// rasteriser shades them: the twin of shaders/area_lights.glsl. The diffuse lobe gets the
// light's exact form factor and the GGX lobes (base and clearcoat) linearly transformed cosines
// (fresnel/material/ltc.h) weighted by the split-sum table's Fresnel scale and bias; sheen is
// taken at the direction of the light's centre with the diffuse's irradiance. Lights are one
// polygon: a rectangle its four corners, a disk (an ellipse under a stretching transform) a
// 12-gon of its area, a sphere the 12-gon of the disk covering the same cone of directions, a
// tube (a capsule) the rectangle through its axis facing the point that covers the cylinder's
// silhouette (half width r d / sqrt(d^2 - r^2) at distance d from the axis), lengthened by pi r / 4
// at each end for the round ends' area (seen along its axis: the sphere of its end).
// Not modelled for area lights: anisotropy (the isotropic lobe), the thin film's Fresnel,
// KHR_materials_transmission's BTDF. The path tracer integrates the lights exactly instead
// (fresnel/trace/area_lights.h); fidelity tests compare the two.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "fresnel/material/evaluate.h"

namespace fresnel {

enum class AreaShape { Rect, Disk, Sphere, Tube };

struct AreaLightGeometry {
    AreaShape shape = AreaShape::Rect;
    glm::vec3 center{0.0f};
    // Rect: half extents; disk: radii; u x v the side it lights (ltc.h's winding). Tube: axis_u
    // its half length along its axis.
    glm::vec3 axis_u{0.5f, 0.0f, 0.0f}, axis_v{0.0f, 0.5f, 0.0f};
    float radius = 0.5f;  // sphere, tube
};

inline constexpr int kAreaPolygonVertices = 12;  // a disk's and a sphere's polygon

// The light's polygon seen from x, relative to x (out: at least ltc::kMaxPolygon + 1 points).
// Returns the vertex count; -1 when x is inside a sphere light (surrounded: every integral 1).
int area_light_polygon(const AreaLightGeometry& light, glm::vec3 x, glm::vec3* out);

// What shade_area_light reads from the split-sum table (fresnel::ibl's BRDF LUT: scale A,
// bias B of F0) at (n.v, roughness) and at the coat's (n_c.v, clearcoat roughness).
struct AreaLightLut {
    glm::vec2 base{1.0f, 0.0f}, coat{1.0f, 0.0f};
};

// Light reflected towards v from the polygon (area_light_polygon's, relative to the shaded
// point) of radiance `radiance`:
//   spec_d = F_d (F0 A + F90 B) ltc(n.v, r) comp_d,  F0 = dielectric F0 x weight, F90 = weight
//   spec_m = (base A + B) ltc(n.v, r) comp_m
//   diffuse = base (1 - F0 A - F90 B) form_factor (x eon_albedo_factor with diffuse roughness;
//             with diffuse transmission mixed with its colour x the form factor seen from -n)
//   base_lobes = mix(diffuse + spec_d, spec_m, metallic)
//   sheen: f_sheen(toward) pi form_factor + base_lobes (1 - max(c) E_sheen(n.v))
//   coat:  mix(that, (A_c + B_c) ltc(n_c.v, r_c), clearcoat_mix)
// times radiance. `toward`: the unit direction to the light's centre.
glm::vec3 shade_area_light(const EvaluatedMaterial& m, glm::vec3 v, const glm::vec3* points, int count, glm::vec3 radiance,
                           glm::vec3 toward, const AreaLightLut& lut, glm::vec3 comp_dielectric = glm::vec3(1.0f),
                           glm::vec3 comp_metal = glm::vec3(1.0f));

}  // namespace fresnel
