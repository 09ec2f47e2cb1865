#include "fresnel/material/area_light.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "fresnel/material/brdf.h"
#include "fresnel/material/ltc.h"

namespace fresnel {

int area_light_polygon(const AreaLightGeometry& light, glm::vec3 x, glm::vec3* out) {
    const glm::vec3 c = light.center - x;
    if (light.shape == AreaShape::Rect) {
        out[0] = c - light.axis_u - light.axis_v;
        out[1] = c + light.axis_u - light.axis_v;
        out[2] = c + light.axis_u + light.axis_v;
        out[3] = c - light.axis_u + light.axis_v;
        return 4;
    }
    if (light.shape == AreaShape::Sphere) {
        const int n = ltc::sphere_polygon(c, light.radius, glm::vec3(0.0f), out, kAreaPolygonVertices);
        return n > 0 ? n : -1;  // inside: surrounded
    }
    if (light.shape == AreaShape::Tube) {
        const float half = glm::length(light.axis_u), r = light.radius;
        const glm::vec3 a = half > 0.0f ? light.axis_u / half : glm::vec3(1.0f, 0.0f, 0.0f);
        const glm::vec3 w = -c;  // from the centre towards x
        const glm::vec3 across = w - a * glm::dot(w, a);
        const float d = glm::length(across);
        if (d <= r * 1e-3f + 1e-12f) {  // on the axis, beyond an end: the end's sphere
            const glm::vec3 end = c + a * (glm::dot(w, a) > 0.0f ? half : -half);
            const int n = ltc::sphere_polygon(end, r, glm::vec3(0.0f), out, kAreaPolygonVertices);
            return n > 0 ? n : -1;
        }
        if (d <= r) return -1;  // inside: surrounded
        const glm::vec3 u = a * (half + 0.25f * brdf::kPi * r);
        const glm::vec3 v = glm::normalize(glm::cross(across, a)) * (r * d / std::sqrt((d - r) * (d + r)));  // u x v along `across`
        out[0] = c - u - v;
        out[1] = c + u - v;
        out[2] = c + u + v;
        out[3] = c - u + v;
        return 4;
    }
    // The disk's radii as the axes of a unit disk: an ellipse where they differ.
    return ltc::disk_polygon(c, light.axis_u, light.axis_v, 1.0f, out, kAreaPolygonVertices);
}

glm::vec3 shade_area_light(const EvaluatedMaterial& m, glm::vec3 v, const glm::vec3* points, int count, glm::vec3 radiance,
                           glm::vec3 toward, const AreaLightLut& lut, glm::vec3 comp_dielectric, glm::vec3 comp_metal) {
    const brdf::Surface& s = m.surface;
    const glm::vec3 n = m.normal;
    const float n_dot_v = std::clamp(glm::dot(n, v), 0.0f, 1.0f);
    const bool surrounded = count < 0;
    auto integral = [&](const glm::mat3& minv, glm::vec3 normal) {
        return surrounded ? 1.0f : ltc::polygon_integral(minv, normal, v, points, count);
    };
    const float form_factor = integral(glm::mat3(1.0f), n);
    const float specular = integral(ltc::inverse_matrix(n_dot_v, s.perceptual_roughness), n);
    const glm::vec3 f_dielectric = (s.dielectric_f0() * lut.base.x + lut.base.y) * s.specular_weight;
    const glm::vec3 f_metal = s.base_color * lut.base.x + lut.base.y;
    glm::vec3 diffuse = s.base_color * (1.0f - f_dielectric) * form_factor;
    if (m.diffuse_roughness > 0.0f) diffuse *= brdf::eon_albedo_factor(s.base_color, m.diffuse_roughness, n_dot_v);
    if (m.diffuse_transmission > 0.0f) {
        const float behind = surrounded ? 1.0f : ltc::polygon_integral(glm::mat3(1.0f), -n, v, points, count);
        diffuse = glm::mix(diffuse, m.diffuse_transmission_color * (1.0f - f_dielectric) * behind, m.diffuse_transmission);
    }
    const glm::vec3 dielectric = diffuse + f_dielectric * specular * comp_dielectric;
    const glm::vec3 metal = f_metal * specular * comp_metal;
    glm::vec3 lit = glm::mix(dielectric, metal, s.metallic);
    if (m.sheen_color != glm::vec3(0.0f)) {
        const float c = std::max({m.sheen_color.x, m.sheen_color.y, m.sheen_color.z});
        const float n_dot_l = std::clamp(glm::dot(n, toward), 0.0f, 1.0f);
        const float n_dot_h = std::clamp(glm::dot(n, glm::normalize(toward + v)), 0.0f, 1.0f);
        const glm::vec3 sheen = n_dot_l > 0.0f ? brdf::sheen_specular(m.sheen_color, m.sheen_roughness, n_dot_l, n_dot_v, n_dot_h)
                                               : glm::vec3(0.0f);
        lit = sheen * (brdf::kPi * form_factor) + lit * (1.0f - c * brdf::SheenAlbedoTable::standard()(n_dot_v, m.sheen_roughness));
    }
    if (m.clearcoat > 0.0f) {
        const glm::vec3 nc = m.clearcoat_normal;
        const float cc_n_dot_v = std::clamp(glm::dot(nc, v), 0.0f, 1.0f);
        const float coat = integral(ltc::inverse_matrix(cc_n_dot_v, m.clearcoat_roughness), nc) * (lut.coat.x + lut.coat.y);
        lit = glm::mix(lit, glm::vec3(coat), brdf::clearcoat_mix(m.clearcoat, m.clearcoat_f0, nc, v));
    }
    return radiance * lit;
}

}  // namespace fresnel
