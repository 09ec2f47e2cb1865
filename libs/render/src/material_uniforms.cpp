#include "fresnel/render/material_uniforms.h"

#include <cmath>

#include "fresnel/gpu/resources.h"

namespace fresnel {

MaterialUniforms material_uniforms(const Material& m) {
    MaterialUniforms u;
    u.base_color_factor = m.specular_glossiness ? m.specular_glossiness->diffuse_factor : m.base_color_factor;
    u.metallic_factor = m.metallic_factor;
    u.roughness_factor = m.roughness_factor;
    u.normal_scale = m.normal_scale;
    u.occlusion_strength = m.occlusion_strength;
    u.emissive_factor = m.emissive_factor;
    u.emissive_strength = m.emissive_strength_value();
    u.alpha_cutoff = m.alpha_cutoff;
    u.ior = m.ior_value();
    if (m.specular) {
        u.specular_factor = m.specular->specular_factor;
        u.specular_color_factor = m.specular->specular_color_factor;
    }
    if (m.specular_glossiness) {
        u.sg_specular_factor = m.specular_glossiness->specular_factor;
        u.glossiness_factor = m.specular_glossiness->glossiness_factor;
    }
    if (m.has_clearcoat()) {
        u.clearcoat_factor = m.clearcoat->clearcoat_factor;
        u.clearcoat_roughness_factor = m.clearcoat->clearcoat_roughness_factor;
        u.clearcoat_normal_scale = m.clearcoat->clearcoat_normal_scale;
    }
    if (is_transmissive(m)) {
        u.transmission_factor = m.transmission->transmission_factor;
        if (m.volume) {
            u.thickness_factor = m.volume->thickness_factor;
            u.attenuation_color = m.volume->attenuation_color;
            u.attenuation_distance = std::isfinite(m.volume->attenuation_distance) ? m.volume->attenuation_distance : 0.0f;
        }
        if (m.dispersion) u.dispersion = m.dispersion->dispersion;
    }
    if (m.has_sheen()) {
        u.sheen_color_factor = m.sheen->sheen_color_factor;
        u.sheen_roughness_factor = m.sheen->sheen_roughness_factor;
    }
    if (m.has_anisotropy()) {
        u.anisotropy_strength = m.anisotropy->anisotropy_strength;
        u.anisotropy_rotation = m.anisotropy->anisotropy_rotation;
    }
    if (m.has_iridescence()) {
        u.iridescence_factor = m.iridescence->iridescence_factor;
        u.iridescence_ior = m.iridescence->iridescence_ior;
        u.iridescence_thickness_minimum = m.iridescence->iridescence_thickness_minimum;
        u.iridescence_thickness_maximum = m.iridescence->iridescence_thickness_maximum;
    }
    if (m.has_diffuse_transmission()) {
        u.diffuse_transmission_factor = m.diffuse_transmission->diffuse_transmission_factor;
        u.diffuse_transmission_color_factor = m.diffuse_transmission->diffuse_transmission_color_factor;
    }
    for (int i = 0; i < kMaterialMapCount; ++i) u.maps[std::size_t(i)] = material_map(m, MaterialMap(i));
    return u;
}

FeatureMask material_features(const Material& m) {
    FeatureMask f = 0;
    if (m.unlit) f |= feature::Unlit;
    if (m.specular_glossiness) f |= feature::SpecularGlossiness;
    if (m.has_clearcoat()) f |= feature::Clearcoat;
    if (is_transmissive(m)) f |= feature::Transmission;
    if (m.has_sheen()) f |= feature::Sheen;
    if (m.has_anisotropy()) f |= feature::Anisotropy;
    if (m.has_iridescence()) f |= feature::Iridescence;
    if (m.has_diffuse_transmission()) f |= feature::DiffuseTransmission;
    if (m.alpha_mode == AlphaMode::Mask) f |= feature::AlphaMask;
    if (m.alpha_mode == AlphaMode::Blend) f |= feature::AlphaBlend;
    return f;
}

void set_material_uniforms(const gpu::Program& prog, const MaterialUniforms& u,
                           const std::array<bool, kMaterialMapCount>& bound) {
    std::array<int, kMaterialMapCount> units{};
    for (int i = 0; i < kMaterialMapCount; ++i) units[std::size_t(i)] = bound[std::size_t(i)] ? i : -1;
    set_material_uniforms(prog, u, units);
}

void set_material_uniforms(const gpu::Program& prog, const MaterialUniforms& u,
                           const std::array<int, kMaterialMapCount>& units) {
    prog.set("u_base_color_factor", u.base_color_factor);
    prog.set("u_metallic_factor", u.metallic_factor);
    prog.set("u_roughness_factor", u.roughness_factor);
    prog.set("u_normal_scale", u.normal_scale);
    prog.set("u_occlusion_strength", u.occlusion_strength);
    prog.set("u_emissive_factor", u.emissive_factor);
    prog.set("u_emissive_strength", u.emissive_strength);
    prog.set("u_alpha_cutoff", u.alpha_cutoff);
    prog.set("u_ior", u.ior);
    prog.set("u_specular_factor", u.specular_factor);
    prog.set("u_specular_color_factor", u.specular_color_factor);
    prog.set("u_sg_specular_factor", u.sg_specular_factor);
    prog.set("u_glossiness_factor", u.glossiness_factor);
    prog.set("u_clearcoat_factor", u.clearcoat_factor);
    prog.set("u_clearcoat_roughness_factor", u.clearcoat_roughness_factor);
    prog.set("u_clearcoat_normal_scale", u.clearcoat_normal_scale);
    prog.set("u_transmission_factor", u.transmission_factor);
    prog.set("u_thickness_factor", u.thickness_factor);
    prog.set("u_attenuation_color", u.attenuation_color);
    prog.set("u_attenuation_distance", u.attenuation_distance);
    prog.set("u_dispersion", u.dispersion);
    prog.set("u_sheen_color_factor", u.sheen_color_factor);
    prog.set("u_sheen_roughness_factor", u.sheen_roughness_factor);
    prog.set("u_anisotropy_strength", u.anisotropy_strength);
    prog.set("u_anisotropy_rotation", u.anisotropy_rotation);
    prog.set("u_iridescence_factor", u.iridescence_factor);
    prog.set("u_iridescence_ior", u.iridescence_ior);
    prog.set("u_iridescence_thickness_minimum", u.iridescence_thickness_minimum);
    prog.set("u_iridescence_thickness_maximum", u.iridescence_thickness_maximum);
    prog.set("u_diffuse_transmission_factor", u.diffuse_transmission_factor);
    prog.set("u_diffuse_transmission_color_factor", u.diffuse_transmission_color_factor);
    for (int i = 0; i < kMaterialMapCount; ++i) {
        if (units[std::size_t(i)] < 0) continue;
        std::string base = std::string("u_") + material_map_info(MaterialMap(i)).name;
        prog.set(base + "_map", units[std::size_t(i)]);
        // A map the variant reads but the material lacks is the 1x1 white texture.
        const TextureSlot* slot = u.maps[std::size_t(i)];
        prog.set(base + "_uv", slot ? slot->tex_coord : 0);
        prog.set(base + "_transform", slot ? slot->transform : glm::mat3(1.0f));
        prog.set(base + "_anisotropy", slot ? u.anisotropy[std::size_t(i)] : 1.0f);  // detail maps only declare it
    }
}

}  // namespace fresnel
