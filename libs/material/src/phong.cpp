#include "fresnel/material/phong.h"

#include "fresnel/material/legacy_shading.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>

namespace fresnel {

float phong_shininess_to_roughness(float ns) {
    if (!(ns > 0.0f)) return 1.0f;  // also NaN
    return legacy::blinn_phong_ibl_roughness(std::min(ns, 1e30f));  // one formula for both uses
}

float roughness_to_phong_shininess(float roughness) {
    float r = std::clamp(std::isnan(roughness) ? 1.0f : roughness, 1e-3f, 1.0f);
    float r2 = r * r;
    return 2.0f / (r2 * r2) - 2.0f;
}

namespace {
float finite_or(float v, float fallback) { return std::isfinite(v) ? v : fallback; }
glm::vec3 clamp01(const glm::vec3& v) {
    return {std::clamp(finite_or(v.x, 0.0f), 0.0f, 1.0f), std::clamp(finite_or(v.y, 0.0f), 0.0f, 1.0f),
            std::clamp(finite_or(v.z, 0.0f), 0.0f, 1.0f)};
}
float clamp01(float v) { return std::clamp(finite_or(v, 0.0f), 0.0f, 1.0f); }
}  // namespace

Material phong_to_metallic_roughness(const PhongExt& p, const std::string& name) {
    Material m;
    m.name = name;
    m.double_sided = true;
    float alpha = clamp01(p.dissolve);
    m.base_color_factor = glm::vec4(clamp01(p.diffuse), alpha);
    m.base_color = p.diffuse_map.slot;
    if (alpha < 1.0f) m.alpha_mode = AlphaMode::Blend;
    m.emissive_factor = glm::max(glm::vec3(0.0f), glm::vec3(finite_or(p.emission.x, 0.0f), finite_or(p.emission.y, 0.0f),
                                                            finite_or(p.emission.z, 0.0f)));
    m.emissive = p.emission_map.slot;
    if (p.normal_map.valid()) {
        m.normal = p.normal_map.slot;
        m.normal_scale = finite_or(p.normal_map.bump_multiplier, 1.0f);
    } else if (p.bump_map.valid()) {
        m.normal = p.bump_map.slot;
        m.normal_scale = finite_or(p.bump_map.bump_multiplier, 1.0f);
    }
    if (p.illum == 0) m.unlit = UnlitExt{};
    if (p.has_pbr()) {
        m.metallic_factor = p.metallic ? clamp01(*p.metallic) : 0.0f;
        m.roughness_factor = p.roughness ? clamp01(*p.roughness) : phong_shininess_to_roughness(p.shininess);
        if (p.clearcoat && *p.clearcoat > 0.0f) {
            ClearcoatExt c;
            c.clearcoat_factor = clamp01(*p.clearcoat);
            c.clearcoat_roughness_factor = p.clearcoat_roughness ? clamp01(*p.clearcoat_roughness) : 0.0f;
            m.clearcoat = c;
        }
        if (p.sheen || p.sheen_map.valid()) {
            SheenExt s;
            s.sheen_color_factor = glm::vec3(p.sheen ? clamp01(*p.sheen) : 1.0f);
            s.sheen_color_texture = p.sheen_map.slot;
            m.sheen = s;
        }
        if (p.anisotropy && *p.anisotropy != 0.0f) {
            AnisotropyExt a;
            a.anisotropy_strength = clamp01(*p.anisotropy);
            a.anisotropy_rotation = finite_or(p.anisotropy_rotation.value_or(0.0f), 0.0f) * 6.28318531f;
            m.anisotropy = a;
        }
    } else {
        m.metallic_factor = 0.0f;
        m.roughness_factor = phong_shininess_to_roughness(p.shininess);
        glm::vec3 ks = clamp01(p.specular);
        SpecularExt s;
        bool highlight = p.illum != 0 && p.illum != 1;
        if (!highlight || (ks == glm::vec3(0.0f) && !p.specular_map.valid())) {
            s.specular_factor = 0.0f;
        } else {
            s.specular_color_factor = ks / ior_to_f0(1.5f);
            s.specular_color_texture = p.specular_map.slot;
        }
        m.specular = s;
    }
    m.phong = p;
    return m;
}

PhongExt legacy_phong(const Material& m) {
    if (m.phong) return *m.phong;
    PhongExt p;
    const glm::vec3 base = clamp01(glm::vec3(m.base_color_factor));
    const float metallic = clamp01(m.metallic_factor);
    float f0 = 0.04f;
    glm::vec3 f0_color(f0);
    if (m.specular) f0_color = glm::vec3(f0 * clamp01(m.specular->specular_factor)) * clamp01(m.specular->specular_color_factor);
    p.diffuse = base * (1.0f - metallic);
    p.ambient = p.diffuse;
    p.specular = glm::mix(f0_color, base, metallic);
    p.shininess = roughness_to_phong_shininess(clamp01(m.roughness_factor));
    float strength = m.emissive_strength ? m.emissive_strength->emissive_strength : 1.0f;
    p.emission = glm::max(glm::vec3(0.0f), m.emissive_factor * finite_or(strength, 1.0f));
    p.dissolve = clamp01(m.base_color_factor.w);
    p.diffuse_map.slot = m.base_color;
    p.emission_map.slot = m.emissive;
    return p;
}

bool is_classic_phong(const Material& m) { return m.phong && !m.phong->has_pbr(); }

legacy::BlinnPhongMaterial blinn_phong_material(const Material& m) {
    legacy::BlinnPhongMaterial b;
    if (m.phong) {
        const PhongExt& p = *m.phong;
        b.base_color = clamp01(p.diffuse);
        b.shininess = std::max(0.0f, finite_or(p.shininess, 0.0f));
        glm::vec3 ks = clamp01(p.specular);
        b.fresnel = std::max(ks.x, std::max(ks.y, ks.z));
        b.metalness = p.metallic ? clamp01(*p.metallic) : 0.0f;
        b.reflectivity = 1.0f;
        return b;
    }
    b.base_color = clamp01(glm::vec3(m.base_color_factor));
    b.shininess = roughness_to_phong_shininess(clamp01(m.roughness_factor));
    b.metalness = clamp01(m.metallic_factor);
    // The model's metal term is F base: a metal reflects its base colour at R0 = 1.
    const float f0 = m.specular ? 0.04f * clamp01(m.specular->specular_factor) : 0.04f;
    b.fresnel = f0 + (1.0f - f0) * b.metalness;
    b.reflectivity = 1.0f;
    return b;
}

}  // namespace fresnel
