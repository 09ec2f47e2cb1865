#include "details/material_uniforms.h"

#include <cmath>

#include "fresnel/gpu/resources.h"

namespace fresnel {

MaterialUniforms material_uniforms(const Material& m) {
    MaterialUniforms u;
    MaterialBlock& b = u.block;
    b.base_color_factor = m.specular_glossiness ? m.specular_glossiness->diffuse_factor : m.base_color_factor;
    b.metallic_factor = m.metallic_factor;
    b.roughness_factor = m.roughness_factor;
    b.normal_scale = m.normal_scale;
    b.occlusion_strength = m.occlusion_strength;
    b.emissive_factor = m.emissive_factor;
    b.emissive_strength = m.emissive_strength_value();
    b.alpha_cutoff = m.alpha_cutoff;
    b.ior = m.ior_value();
    if (m.specular) {
        b.specular_factor = m.specular->specular_factor;
        b.specular_color_factor = m.specular->specular_color_factor;
    }
    if (m.specular_glossiness) {
        b.sg_specular_factor = m.specular_glossiness->specular_factor;
        b.glossiness_factor = m.specular_glossiness->glossiness_factor;
    }
    if (m.has_clearcoat()) {
        b.clearcoat_factor = m.clearcoat->clearcoat_factor;
        b.clearcoat_roughness_factor = m.clearcoat->clearcoat_roughness_factor;
        b.clearcoat_normal_scale = m.clearcoat->clearcoat_normal_scale;
    }
    if (is_transmissive(m)) {
        b.transmission_factor = m.transmission->transmission_factor;
        if (m.volume) {
            b.thickness_factor = m.volume->thickness_factor;
            b.attenuation_color = m.volume->attenuation_color;
            b.attenuation_distance = std::isfinite(m.volume->attenuation_distance) ? m.volume->attenuation_distance : 0.0f;
        }
        if (m.dispersion) b.dispersion = m.dispersion->dispersion;
    }
    if (m.has_sheen()) {
        b.sheen_color_factor = m.sheen->sheen_color_factor;
        b.sheen_roughness_factor = m.sheen->sheen_roughness_factor;
    }
    if (m.has_anisotropy()) {
        b.anisotropy_strength = m.anisotropy->anisotropy_strength;
        b.anisotropy_rotation = m.anisotropy->anisotropy_rotation;
    }
    if (m.has_iridescence()) {
        b.iridescence_factor = m.iridescence->iridescence_factor;
        b.iridescence_ior = m.iridescence->iridescence_ior;
        b.iridescence_thickness_minimum = m.iridescence->iridescence_thickness_minimum;
        b.iridescence_thickness_maximum = m.iridescence->iridescence_thickness_maximum;
    }
    if (m.has_diffuse_transmission()) {
        b.diffuse_transmission_factor = m.diffuse_transmission->diffuse_transmission_factor;
        b.diffuse_transmission_color_factor = m.diffuse_transmission->diffuse_transmission_color_factor;
    }
    if (m.has_diffuse_roughness() && !m.specular_glossiness) b.diffuse_roughness_factor = m.diffuse_roughness->diffuse_roughness_factor;
    for (std::size_t i = 0; i < std::size_t(kMaterialMapCount); ++i) {
        // A map the variant reads but the material lacks is the 1x1 white texture (identity
        // transform, UV set 0: the block's defaults).
        const TextureSlot* slot = u.maps[i] = material_map(m, MaterialMap(i));
        if (!slot) continue;
        for (int c = 0; c < 3; ++c) b.maps[i].transform[std::size_t(c)] = glm::vec4(slot->transform[c], 0.0f);
        b.maps[i].uv = slot->tex_coord;
    }
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

namespace {
// "u_<map>_map" for every map, made once (the draw path builds no strings).
const std::array<std::string, kMaterialMapCount>& sampler_names() {
    static const std::array<std::string, kMaterialMapCount> names = [] {
        std::array<std::string, kMaterialMapCount> n;
        for (int i = 0; i < kMaterialMapCount; ++i)
            n[std::size_t(i)] = std::string("u_") + material_map_info(MaterialMap(i)).name + "_map";
        return n;
    }();
    return names;
}
}  // namespace

void set_material_samplers(const gpu::Program& prog, const std::array<int, kMaterialMapCount>& units) {
    const auto& names = sampler_names();
    for (std::size_t i = 0; i < std::size_t(kMaterialMapCount); ++i)
        if (units[i] >= 0) prog.set(names[i], units[i]);
}

void set_material_uniforms(const gpu::Program& prog, const MaterialUniforms& u,
                           const std::array<bool, kMaterialMapCount>& bound, gpu::UniformBuffer& buffer) {
    if (!buffer) buffer = gpu::UniformBuffer(sizeof(MaterialBlock));
    buffer.update(&u.block, sizeof u.block);
    buffer.bind(kMaterialBlockBinding);
    std::array<int, kMaterialMapCount> units{};
    for (int i = 0; i < kMaterialMapCount; ++i) units[std::size_t(i)] = bound[std::size_t(i)] ? i : -1;
    set_material_samplers(prog, units);
}

std::vector<std::pair<std::string, std::size_t>> material_block_members() {
    std::vector<std::pair<std::string, std::size_t>> m = {
        {"u_base_color_factor", offsetof(MaterialBlock, base_color_factor)},
        {"u_emissive_factor", offsetof(MaterialBlock, emissive_factor)},
        {"u_emissive_strength", offsetof(MaterialBlock, emissive_strength)},
        {"u_specular_color_factor", offsetof(MaterialBlock, specular_color_factor)},
        {"u_specular_factor", offsetof(MaterialBlock, specular_factor)},
        {"u_sg_specular_factor", offsetof(MaterialBlock, sg_specular_factor)},
        {"u_glossiness_factor", offsetof(MaterialBlock, glossiness_factor)},
        {"u_sheen_color_factor", offsetof(MaterialBlock, sheen_color_factor)},
        {"u_sheen_roughness_factor", offsetof(MaterialBlock, sheen_roughness_factor)},
        {"u_attenuation_color", offsetof(MaterialBlock, attenuation_color)},
        {"u_attenuation_distance", offsetof(MaterialBlock, attenuation_distance)},
        {"u_diffuse_transmission_color_factor", offsetof(MaterialBlock, diffuse_transmission_color_factor)},
        {"u_diffuse_transmission_factor", offsetof(MaterialBlock, diffuse_transmission_factor)},
        {"u_diffuse_roughness_factor", offsetof(MaterialBlock, diffuse_roughness_factor)},
        {"u_metallic_factor", offsetof(MaterialBlock, metallic_factor)},
        {"u_roughness_factor", offsetof(MaterialBlock, roughness_factor)},
        {"u_normal_scale", offsetof(MaterialBlock, normal_scale)},
        {"u_occlusion_strength", offsetof(MaterialBlock, occlusion_strength)},
        {"u_alpha_cutoff", offsetof(MaterialBlock, alpha_cutoff)},
        {"u_ior", offsetof(MaterialBlock, ior)},
        {"u_clearcoat_factor", offsetof(MaterialBlock, clearcoat_factor)},
        {"u_clearcoat_roughness_factor", offsetof(MaterialBlock, clearcoat_roughness_factor)},
        {"u_clearcoat_normal_scale", offsetof(MaterialBlock, clearcoat_normal_scale)},
        {"u_transmission_factor", offsetof(MaterialBlock, transmission_factor)},
        {"u_thickness_factor", offsetof(MaterialBlock, thickness_factor)},
        {"u_dispersion", offsetof(MaterialBlock, dispersion)},
        {"u_anisotropy_strength", offsetof(MaterialBlock, anisotropy_strength)},
        {"u_anisotropy_rotation", offsetof(MaterialBlock, anisotropy_rotation)},
        {"u_iridescence_factor", offsetof(MaterialBlock, iridescence_factor)},
        {"u_iridescence_ior", offsetof(MaterialBlock, iridescence_ior)},
        {"u_iridescence_thickness_minimum", offsetof(MaterialBlock, iridescence_thickness_minimum)},
        {"u_iridescence_thickness_maximum", offsetof(MaterialBlock, iridescence_thickness_maximum)},
    };
    for (int i = 0; i < kMaterialMapCount; ++i) {
        const std::string base = std::string("u_") + material_map_info(MaterialMap(i)).name;
        const std::size_t at = offsetof(MaterialBlock, maps) + std::size_t(i) * sizeof(MaterialBlock::Map);
        m.emplace_back(base + "_transform", at + offsetof(MaterialBlock::Map, transform));
        m.emplace_back(base + "_uv", at + offsetof(MaterialBlock::Map, uv));
        m.emplace_back(base + "_anisotropy", at + offsetof(MaterialBlock::Map, anisotropy));
    }
    return m;
}

std::vector<std::pair<std::string, std::size_t>> frame_block_members() {
    return {{"u_view_projection", offsetof(FrameBlock, view_projection)},
            {"u_view", offsetof(FrameBlock, view)},
            {"u_env_rotation", offsetof(FrameBlock, env_rotation)},
            {"u_camera_position", offsetof(FrameBlock, camera_position)},
            {"u_env_levels", offsetof(FrameBlock, env_levels)},
            {"u_ambient", offsetof(FrameBlock, ambient)},
            {"u_env_intensity", offsetof(FrameBlock, env_intensity)},
            {"u_debug", offsetof(FrameBlock, debug)},
            {"u_energy_compensation", offsetof(FrameBlock, energy_compensation)},
            {"u_light_count", offsetof(FrameBlock, light_count)},
            {"u_light_position_type[0]", offsetof(FrameBlock, light_position_type)},
            {"u_light_direction_range[0]", offsetof(FrameBlock, light_direction_range)},
            {"u_light_color[0]", offsetof(FrameBlock, light_color)},
            {"u_light_cone[0]", offsetof(FrameBlock, light_cone)},
            {"u_light_axis[0]", offsetof(FrameBlock, light_axis)},
            {"u_shadow_atlas_info", offsetof(FrameBlock, shadow_atlas)},
            {"u_light_shadow[0]", offsetof(FrameBlock, light_shadow)},
            {"u_shadow_matrix[0]", offsetof(FrameBlock, shadow_matrix)},
            {"u_shadow_rect[0]", offsetof(FrameBlock, shadow_rect)},
            {"u_shadow_params[0]", offsetof(FrameBlock, shadow_params)}};
}

}  // namespace fresnel
