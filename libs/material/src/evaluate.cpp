// The material rules, once in C++. The GLSL twin is read_material in
// shaders/material_inputs.glsl: keep the two in the same order and change them together.
#include "fresnel/material/evaluate.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace fresnel {

namespace {
constexpr MaterialMapInfo kMaps[kMaterialMapCount] = {
    {"base_color", "HAS_BASE_COLOR_MAP", true, false, true},
    {"metallic_roughness", "HAS_METALLIC_ROUGHNESS_MAP", false, false, true},
    {"normal", "HAS_NORMAL_MAP", false, true, true},
    {"occlusion", "HAS_OCCLUSION_MAP", false, false, true},
    {"emissive", "HAS_EMISSIVE_MAP", true, false, false},
    {"specular", "HAS_SPECULAR_MAP", false, false, false},
    {"specular_color", "HAS_SPECULAR_COLOR_MAP", true, false, true},
    {"specular_glossiness", "HAS_SPECULAR_GLOSSINESS_MAP", true, false, true},
    {"clearcoat", "HAS_CLEARCOAT_MAP", false, false, false},
    {"clearcoat_roughness", "HAS_CLEARCOAT_ROUGHNESS_MAP", false, false, false},
    {"clearcoat_normal", "HAS_CLEARCOAT_NORMAL_MAP", false, true, true},
    {"sheen_color", "HAS_SHEEN_COLOR_MAP", true, false, true},
    {"sheen_roughness", "HAS_SHEEN_ROUGHNESS_MAP", false, false, false},
    {"transmission", "HAS_TRANSMISSION_MAP", false, false, false},
    {"thickness", "HAS_THICKNESS_MAP", false, false, false},
    {"anisotropy", "HAS_ANISOTROPY_MAP", false, false, false},
    {"iridescence", "HAS_IRIDESCENCE_MAP", false, false, false},
    {"iridescence_thickness", "HAS_IRIDESCENCE_THICKNESS_MAP", false, false, false},
    {"diffuse_transmission", "HAS_DIFFUSE_TRANSMISSION_MAP", false, false, false},
    {"diffuse_transmission_color", "HAS_DIFFUSE_TRANSMISSION_COLOR_MAP", true, false, false},
    {"diffuse_roughness", "HAS_DIFFUSE_ROUGHNESS_MAP", false, false, false},
};

// Reads one map at the point, or nullopt when the map is absent or unreadable.
class MapReader {
public:
    MapReader(const Material& m, const TextureSource& t, const SurfacePoint& p) : m_(m), t_(t), p_(p) {}
    std::optional<glm::vec4> sample(MaterialMap map) const {
        const TextureSlot* slot = material_map(m_, map);
        if (!slot || !map_usable(*slot, map, p_.inputs)) return std::nullopt;
        const SampledTexture* tex = t_.get(slot->texture, map_srgb(m_, map));
        if (!tex) return std::nullopt;
        // map_uv in the shader: the slot's UV set through its KHR_texture_transform.
        glm::vec2 uv = slot->tex_coord == 1 ? p_.uv1 : p_.uv0;
        uv = glm::vec2(slot->transform * glm::vec3(uv, 1.0f));
        if (p_.lod) return tex->sample(uv, *p_.lod);
        // The derivatives of the transformed coordinates.
        glm::mat2 linear(slot->transform);
        glm::vec2 dx = linear * (slot->tex_coord == 1 ? p_.duv1_dx : p_.duv0_dx);
        glm::vec2 dy = linear * (slot->tex_coord == 1 ? p_.duv1_dy : p_.duv0_dy);
        glm::vec2 size(float(tex->width()), float(tex->height()));
        if (material_map_info(map).detail) {
            // sample_detail_map: the renderer's anisotropic filter.
            const TextureSampler& s = tex->sampler();
            float most = detail_anisotropy(s.mag_filter, s.mip_filter, p_.max_anisotropy);
            return tex->sample_footprint(detail_footprint(uv, dx, dy, size, most), most > 1.0f);
        }
        // texture(): λ = log2 of the larger screen-space footprint in texels (the GL spec's ρ).
        float rho = std::max(glm::length(dx * size), glm::length(dy * size));
        return tex->sample(uv, rho > 0.0f ? std::log2(rho) : -INFINITY);
    }

private:
    const Material& m_;
    const TextureSource& t_;
    const SurfacePoint& p_;
};

glm::vec3 perturb(glm::vec4 texel, float scale, const SurfacePoint& p) {
    glm::vec3 tn = glm::vec3(texel) * 2.0f - 1.0f;
    tn.x *= scale;
    tn.y *= scale;
    return glm::normalize(glm::mat3(p.tangent, p.bitangent, p.normal) * tn);
}
}  // namespace

const MaterialMapInfo& material_map_info(MaterialMap map) { return kMaps[int(map)]; }

bool map_srgb(const Material& m, MaterialMap map) {
    if (m.specular_glossiness && m.specular_glossiness->linear_textures &&
        (map == MaterialMap::BaseColor || map == MaterialMap::SpecularGlossiness))
        return false;
    return material_map_info(map).srgb;
}

std::optional<glm::vec4> sample_material_map(const Material& material, const TextureSource& textures,
                                             const SurfacePoint& point, MaterialMap map) {
    return MapReader(material, textures, point).sample(map);
}

const TextureSlot* material_map(const Material& m, MaterialMap map) {
    const auto* sg = m.specular_glossiness ? &*m.specular_glossiness : nullptr;
    const auto* sp = m.specular ? &*m.specular : nullptr;
    const auto* cc = m.has_clearcoat() ? &*m.clearcoat : nullptr;
    const auto* sh = m.has_sheen() ? &*m.sheen : nullptr;
    const auto* an = m.has_anisotropy() ? &*m.anisotropy : nullptr;
    const auto* ir = m.has_iridescence() ? &*m.iridescence : nullptr;
    const auto* dt = m.has_diffuse_transmission() ? &*m.diffuse_transmission : nullptr;
    const auto* dr = m.has_diffuse_roughness() && !sg ? &*m.diffuse_roughness : nullptr;  // not under specular-glossiness
    const TextureSlot* slot = nullptr;
    switch (map) {
        case MaterialMap::BaseColor: slot = sg ? &sg->diffuse_texture : &m.base_color; break;
        case MaterialMap::MetallicRoughness: slot = sg ? nullptr : &m.metallic_roughness; break;
        case MaterialMap::Normal: slot = &m.normal; break;
        case MaterialMap::Occlusion: slot = &m.occlusion; break;
        case MaterialMap::Emissive: slot = &m.emissive; break;
        case MaterialMap::Specular: slot = sg || !sp ? nullptr : &sp->specular_texture; break;
        case MaterialMap::SpecularColor: slot = sg || !sp ? nullptr : &sp->specular_color_texture; break;
        case MaterialMap::SpecularGlossiness: slot = sg ? &sg->specular_glossiness_texture : nullptr; break;
        case MaterialMap::Clearcoat: slot = cc ? &cc->clearcoat_texture : nullptr; break;
        case MaterialMap::ClearcoatRoughness: slot = cc ? &cc->clearcoat_roughness_texture : nullptr; break;
        case MaterialMap::ClearcoatNormal: slot = cc ? &cc->clearcoat_normal_texture : nullptr; break;
        case MaterialMap::SheenColor: slot = sh ? &sh->sheen_color_texture : nullptr; break;
        case MaterialMap::SheenRoughness: slot = sh ? &sh->sheen_roughness_texture : nullptr; break;
        case MaterialMap::Transmission: slot = is_transmissive(m) ? &m.transmission->transmission_texture : nullptr; break;
        case MaterialMap::Thickness:
            slot = is_transmissive(m) && m.volume ? &m.volume->thickness_texture : nullptr;
            break;
        case MaterialMap::Anisotropy: slot = an ? &an->anisotropy_texture : nullptr; break;
        case MaterialMap::Iridescence: slot = ir ? &ir->iridescence_texture : nullptr; break;
        case MaterialMap::IridescenceThickness: slot = ir ? &ir->iridescence_thickness_texture : nullptr; break;
        case MaterialMap::DiffuseTransmission: slot = dt ? &dt->diffuse_transmission_texture : nullptr; break;
        case MaterialMap::DiffuseTransmissionColor: slot = dt ? &dt->diffuse_transmission_color_texture : nullptr; break;
        case MaterialMap::DiffuseRoughness: slot = dr ? &dr->diffuse_roughness_texture : nullptr; break;
    }
    return slot && slot->valid() ? slot : nullptr;
}

bool map_usable(const TextureSlot& slot, MaterialMap map, const VertexInputs& inputs) {
    if (!slot.valid() || !inputs.has_uv0) return false;
    if (slot.tex_coord == 1 && !inputs.has_uv1) return false;
    if ((material_map_info(map).normal_map || map == MaterialMap::Anisotropy) && !inputs.has_tangent) return false;
    return true;
}

MetallicRoughnessPoint specular_glossiness_to_metallic_roughness(glm::vec4 diffuse, glm::vec3 specular,
                                                                 float glossiness) {
    MetallicRoughnessPoint p;
    p.base_color = diffuse;
    p.metallic = 0.0f;
    p.roughness = 1.0f - glossiness;
    p.f0 = specular;
    p.specular_weight = 1.0f;
    return p;
}

Material to_metallic_roughness(const Material& material, bool* lost_glossiness_map) {
    if (lost_glossiness_map) *lost_glossiness_map = false;
    if (!material.specular_glossiness) return material;
    const SpecularGlossinessExt& sg = *material.specular_glossiness;
    Material out = material;
    out.specular_glossiness.reset();
    MetallicRoughnessPoint p = specular_glossiness_to_metallic_roughness(sg.diffuse_factor, sg.specular_factor,
                                                                         sg.glossiness_factor);
    out.base_color_factor = p.base_color;
    out.base_color = sg.diffuse_texture;
    out.metallic_factor = p.metallic;
    out.roughness_factor = p.roughness;
    out.metallic_roughness = TextureSlot{};
    SpecularExt spec;
    spec.specular_factor = p.specular_weight;
    float f0 = ior_to_f0(material.ior_value());
    // F0 = ior_to_f0(ior) * specularColorFactor must give the specular colour; with F0 = 0
    // (ior 1) no colour can, and the ior becomes 0 (F0 = 1), which the extension allows.
    if (f0 > 0.0f) {
        spec.specular_color_factor = p.f0 / f0;
    } else {
        out.ior = IorExt{0.0f};
        spec.specular_color_factor = p.f0;
    }
    spec.specular_color_texture = sg.specular_glossiness_texture;
    out.specular = spec;
    if (lost_glossiness_map) *lost_glossiness_map = sg.specular_glossiness_texture.valid();
    return out;
}

EvaluatedMaterial evaluate(const Material& material, const TextureSource& textures, const SurfacePoint& point) {
    const Material& m = material;
    MapReader maps(m, textures, point);
    EvaluatedMaterial e;
    brdf::Surface& s = e.surface;
    e.unlit = m.unlit.has_value();

    glm::vec4 base_color;
    float metallic, roughness;
    glm::vec3 f0;
    float specular_weight;
    glm::vec4 diffuse = m.specular_glossiness ? m.specular_glossiness->diffuse_factor : m.base_color_factor;
    base_color = diffuse * point.color;
    if (auto t = maps.sample(MaterialMap::BaseColor)) base_color *= *t;
    if (m.specular_glossiness) {
        const SpecularGlossinessExt& sg = *m.specular_glossiness;
        glm::vec3 specular = sg.specular_factor;
        float glossiness = sg.glossiness_factor;
        if (auto t = maps.sample(MaterialMap::SpecularGlossiness)) {
            specular *= glm::vec3(*t);
            glossiness *= t->w;
        }
        MetallicRoughnessPoint p = specular_glossiness_to_metallic_roughness(base_color, specular, glossiness);
        metallic = p.metallic;
        roughness = p.roughness;
        f0 = p.f0;
        specular_weight = p.specular_weight;
    } else {
        metallic = m.metallic_factor;
        roughness = m.roughness_factor;
        if (auto t = maps.sample(MaterialMap::MetallicRoughness)) {
            metallic *= t->z;
            roughness *= t->y;
        }
        glm::vec3 specular_color = m.specular ? m.specular->specular_color_factor : glm::vec3(1.0f);
        if (auto t = maps.sample(MaterialMap::SpecularColor)) specular_color *= glm::vec3(*t);
        f0 = ior_to_f0(m.ior_value()) * specular_color;
        specular_weight = m.specular ? m.specular->specular_factor : 1.0f;
        if (auto t = maps.sample(MaterialMap::Specular)) specular_weight *= t->w;
    }
    f0 = glm::min(f0, glm::vec3(1.0f));
    s.base_color = glm::vec3(base_color);
    s.metallic = std::clamp(metallic, 0.0f, 1.0f);
    s.perceptual_roughness = std::clamp(roughness, 0.0f, 1.0f);
    // brdf::Surface states F0 as specular_f0 * specular_color: the colour carries it all.
    s.specular_f0 = 1.0f;
    s.specular_color = f0;
    s.specular_weight = specular_weight;

    e.clearcoat_f0 = ior_to_f0(m.ior_value());
    if (m.has_clearcoat()) {
        const ClearcoatExt& cc = *m.clearcoat;
        e.clearcoat = cc.clearcoat_factor;
        e.clearcoat_roughness = cc.clearcoat_roughness_factor;
        if (auto t = maps.sample(MaterialMap::Clearcoat)) e.clearcoat *= t->x;
        if (auto t = maps.sample(MaterialMap::ClearcoatRoughness)) e.clearcoat_roughness *= t->y;
        e.clearcoat = std::clamp(e.clearcoat, 0.0f, 1.0f);
        e.clearcoat_roughness = std::clamp(e.clearcoat_roughness, 0.0f, 1.0f);
    }
    if (m.has_sheen()) {
        const SheenExt& sh = *m.sheen;
        e.sheen_color = sh.sheen_color_factor;
        e.sheen_roughness = sh.sheen_roughness_factor;
        if (auto t = maps.sample(MaterialMap::SheenColor)) e.sheen_color *= glm::vec3(*t);
        if (auto t = maps.sample(MaterialMap::SheenRoughness)) e.sheen_roughness *= t->w;
        e.sheen_color = glm::max(e.sheen_color, glm::vec3(0.0f));
        e.sheen_roughness = std::clamp(e.sheen_roughness, 0.0f, 1.0f);
    }
    if (m.has_anisotropy() && point.inputs.has_tangent) {
        // KHR_materials_anisotropy, as the Khronos viewer: the direction in the geometric
        // tangent frame, the bitangent from the geometric normal.
        const AnisotropyExt& an = *m.anisotropy;
        glm::vec2 dir(1.0f, 0.0f);
        float strength = an.anisotropy_strength;
        if (auto t = maps.sample(MaterialMap::Anisotropy)) {
            dir = glm::vec2(t->x, t->y) * 2.0f - 1.0f;
            strength *= t->z;
        }
        float c = std::cos(an.anisotropy_rotation), sn = std::sin(an.anisotropy_rotation);
        dir = glm::vec2(c * dir.x - sn * dir.y, sn * dir.x + c * dir.y);
        float len = glm::length(dir);
        dir = len > 0.0f ? dir / len : glm::vec2(1.0f, 0.0f);
        e.anisotropy_strength = std::clamp(strength, 0.0f, 1.0f);
        e.anisotropy_direction = dir;
        e.anisotropic_t = dir.x * point.tangent + dir.y * point.bitangent;
        e.anisotropic_b = glm::cross(point.normal, e.anisotropic_t);
    }
    if (m.has_iridescence()) {
        const IridescenceExt& ir = *m.iridescence;
        e.iridescence = ir.iridescence_factor;
        if (auto t = maps.sample(MaterialMap::Iridescence)) e.iridescence *= t->x;
        e.iridescence = std::clamp(e.iridescence, 0.0f, 1.0f);
        e.iridescence_ior = ir.iridescence_ior;
        e.iridescence_thickness = ir.iridescence_thickness_maximum;
        // mix(minimum, maximum, G), written so that G = 1 gives the maximum exactly (the white
        // texture stands in for an absent map).
        if (auto t = maps.sample(MaterialMap::IridescenceThickness))
            e.iridescence_thickness = ir.iridescence_thickness_minimum * (1.0f - t->y) + ir.iridescence_thickness_maximum * t->y;
    }
    if (m.has_diffuse_transmission()) {
        const DiffuseTransmissionExt& dt = *m.diffuse_transmission;
        e.diffuse_transmission = dt.diffuse_transmission_factor;
        if (auto t = maps.sample(MaterialMap::DiffuseTransmission)) e.diffuse_transmission *= t->w;
        e.diffuse_transmission = std::clamp(e.diffuse_transmission, 0.0f, 1.0f);
        e.diffuse_transmission_color = dt.diffuse_transmission_color_factor;
        if (auto t = maps.sample(MaterialMap::DiffuseTransmissionColor)) e.diffuse_transmission_color *= glm::vec3(*t);
        e.diffuse_transmission_color = glm::max(e.diffuse_transmission_color, glm::vec3(0.0f));
    }
    if (m.has_diffuse_roughness() && !m.specular_glossiness) {
        e.diffuse_roughness = m.diffuse_roughness->diffuse_roughness_factor;
        if (auto t = maps.sample(MaterialMap::DiffuseRoughness)) e.diffuse_roughness *= t->x;
        e.diffuse_roughness = std::clamp(e.diffuse_roughness, 0.0f, 1.0f);
    }
    if (auto t = maps.sample(MaterialMap::Occlusion)) e.occlusion = 1.0f + m.occlusion_strength * (t->x - 1.0f);
    e.emissive = m.emissive_factor * m.emissive_strength_value();
    if (auto t = maps.sample(MaterialMap::Emissive)) e.emissive *= glm::vec3(*t);

    e.alpha = base_color.w;
    if (m.alpha_mode == AlphaMode::Mask) {
        e.discard = base_color.w < m.alpha_cutoff;
        e.alpha = 1.0f;
    } else if (m.alpha_mode == AlphaMode::Opaque) {
        e.alpha = 1.0f;
    }
    e.normal = point.normal;
    if (auto t = maps.sample(MaterialMap::Normal)) e.normal = perturb(*t, m.normal_scale, point);
    e.clearcoat_normal = point.normal;
    if (auto t = maps.sample(MaterialMap::ClearcoatNormal))
        e.clearcoat_normal = perturb(*t, m.clearcoat->clearcoat_normal_scale, point);
    if (is_transmissive(m)) {
        TransmissionInputs& tr = e.transmission;
        tr.factor = m.transmission->transmission_factor;
        if (auto t = maps.sample(MaterialMap::Transmission)) tr.factor *= t->x;
        tr.ior = m.ior_value();
        if (m.volume) {
            tr.thickness = m.volume->thickness_factor;
            if (auto t = maps.sample(MaterialMap::Thickness)) tr.thickness *= t->y;
            tr.attenuation_color = m.volume->attenuation_color;
            float d = m.volume->attenuation_distance;
            tr.attenuation_distance = std::isfinite(d) ? d : 0.0f;
        }
        if (m.dispersion) tr.dispersion = m.dispersion->dispersion;
    }
    return e;
}

bool is_transmissive(const Material& m) { return m.transmission && !m.specular_glossiness && !m.unlit; }

brdf::IridescenceFresnel film_at(const EvaluatedMaterial& m, glm::vec3 v) {
    if (!(m.iridescence > 0.0f)) return {};
    return brdf::iridescence_at(m.iridescence, m.iridescence_ior, m.iridescence_thickness,
                                std::clamp(glm::dot(m.normal, v), 0.0f, 1.0f), m.surface.dielectric_f0(),
                                m.surface.base_color);
}

namespace {
// What the transmission's two parts share at l: the dielectric Fresnel's weight (a thin film's:
// brdf::film_diffuse_weight) times 1 - metallic and 1 - the coat's mix.
glm::vec3 transmission_weight(const EvaluatedMaterial& m, glm::vec3 v, const brdf::Cosines& c) {
    const brdf::Surface& s = m.surface;
    glm::vec3 f_dielectric = brdf::f_schlick(s.dielectric_f0() * s.specular_weight, glm::vec3(s.specular_weight), c.v_dot_h);
    glm::vec3 w = (1.0f - s.metallic) * brdf::film_diffuse_weight(f_dielectric, film_at(m, v));
    if (m.clearcoat > 0.0f) w *= 1.0f - brdf::clearcoat_mix(m.clearcoat, m.clearcoat_f0, m.clearcoat_normal, v);
    return w;
}
// The Lambert (or EON) lobe times its cosine, mixed with the diffuse transmission's: what the
// transmission replaces in proportion to its factor.
glm::vec3 diffuse_cos(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l, const brdf::Cosines& c) {
    const brdf::Surface& s = m.surface;
    float n_dot_minus_l = std::clamp(-glm::dot(m.normal, l), 0.0f, 1.0f);
    glm::vec3 lambert = brdf::lambert(s.base_color) *
                        brdf::eon_factor(s.base_color, m.diffuse_roughness, c.n_dot_l, c.n_dot_v, glm::dot(l, v));
    return brdf::diffuse_transmission_mix(c.n_dot_l * lambert, n_dot_minus_l, m.diffuse_transmission,
                                          m.diffuse_transmission_color);
}
}  // namespace

glm::vec3 transmission_replaced_diffuse(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l) {
    if (!(m.transmission.factor > 0.0f)) return glm::vec3(0.0f);
    const brdf::Cosines c = brdf::cosines(m.normal, v, l);
    return m.transmission.factor * transmission_weight(m, v, c) * diffuse_cos(m, v, l, c);
}

glm::vec3 shade_light_transmission(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l, glm::vec3 l_transmitted,
                                   float ray_length, glm::vec3 radiance) {
    const TransmissionInputs& tr = m.transmission;
    const brdf::Surface& s = m.surface;
    const brdf::Cosines c = brdf::cosines(m.normal, v, l);
    glm::vec3 btdf = transmission::btdf_punctual(m.normal, v, l_transmitted,
                                                 brdf::alpha_from_roughness(s.perceptual_roughness), s.dielectric_f0(),
                                                 glm::vec3(1.0f), s.base_color, tr.ior);
    glm::vec3 transmitted = transmission::volume_attenuation(radiance * btdf, ray_length, tr.attenuation_color,
                                                             tr.attenuation_distance);
    return transmission_weight(m, v, c) * tr.factor * (transmitted - radiance * diffuse_cos(m, v, l, c));
}

glm::vec3 energy_compensation(glm::vec3 f0, float e) { return 1.0f + f0 * (1.0f / std::max(e, 1e-4f) - 1.0f); }

EnergyCompensation energy_compensation(const EvaluatedMaterial& m, float e) {
    EnergyCompensation c;
    c.dielectric = energy_compensation(m.surface.dielectric_f0() * m.surface.specular_weight, e);
    c.metal = energy_compensation(m.surface.base_color, e);
    return c;
}

glm::vec3 shade_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l, const brdf::BrdfModel& model,
                     const EnergyCompensation& comp) {
    // With KHR_materials_diffuse_transmission, shade_light has the transmitted Lambert lobe below.
    glm::vec3 f = shade_light(m, v, l, glm::vec3(1.0f), comp.dielectric, comp.metal, model);
    const TransmissionInputs& tr = m.transmission;
    if (!(tr.factor > 0.0f)) return f;
    const float n_dot_l = glm::dot(m.normal, l);
    if (n_dot_l >= 0.0f || m.diffuse_transmission > 0.0f) f = glm::max(f - transmission_replaced_diffuse(m, v, l), glm::vec3(0.0f));
    else f = glm::vec3(0.0f);
    if (n_dot_l >= 0.0f) return f;
    // The thin-walled transmission lobe: the reflection lobe's GGX mirrored through the surface.
    const brdf::Surface& s = m.surface;
    const glm::vec3 n = m.normal;
    const glm::vec3 lm = l - 2.0f * n_dot_l * n;
    const brdf::Cosines c = brdf::cosines(n, v, lm);  // h' = normalize(l' + v)
    const float n_dot_lm = -n_dot_l;
    const float a = std::max(transmission::apply_ior_to_roughness(brdf::alpha_from_roughness(s.perceptual_roughness), tr.ior),
                             kMinSampledAlpha);
    const float dv = brdf::d_ggx(c.n_dot_h, a) * brdf::v_smith_ggx_correlated(n_dot_lm, c.n_dot_v, a);
    return f + transmission_weight(m, v, c) * tr.factor * s.base_color * dv * n_dot_lm;
}

glm::vec3 shade_light(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l, glm::vec3 radiance,
                      glm::vec3 comp_dielectric, glm::vec3 comp_metal, const brdf::BrdfModel& model) {
    float n_dot_l = std::clamp(glm::dot(m.normal, l), 0.0f, 1.0f);
    // KHR_materials_diffuse_transmission: a light behind the surface lights its transmitted lobe.
    float n_dot_minus_l = m.diffuse_transmission > 0.0f ? std::clamp(-glm::dot(m.normal, l), 0.0f, 1.0f) : 0.0f;
    glm::vec3 lit(0.0f);
    if (n_dot_l > 0.0f || n_dot_minus_l > 0.0f) {
        brdf::Terms t = brdf::evaluate_terms(m.surface, m.normal, v, l, model, film_at(m, v));
        if (m.diffuse_roughness > 0.0f)  // KHR_materials_diffuse_roughness: the EON lobe
            t.diffuse *= brdf::eon_factor(m.surface.base_color, m.diffuse_roughness, n_dot_l,
                                          std::clamp(glm::dot(m.normal, v), 0.0f, 1.0f), glm::dot(l, v));
        if (m.anisotropy_strength > 0.0f)
            brdf::apply_anisotropy(t, m.surface, m.normal, v, l, m.anisotropic_t, m.anisotropic_b, m.anisotropy_strength);
        glm::vec3 specular = t.specular_dielectric * comp_dielectric + t.specular_metal * comp_metal;
        glm::vec3 base = t.diffuse + specular;
        glm::vec3 sheen(0.0f);
        float scaling = 1.0f;
        if (m.sheen_color != glm::vec3(0.0f)) {
            // KHR_materials_sheen: the Charlie lobe over the base, which keeps 1 - max(c) E.
            float n_dot_v = std::clamp(glm::dot(m.normal, v), 0.0f, 1.0f);
            glm::vec3 h = glm::normalize(l + v);
            float n_dot_h = std::clamp(glm::dot(m.normal, h), 0.0f, 1.0f);
            const brdf::SheenAlbedoTable& e = brdf::SheenAlbedoTable::standard();
            scaling = brdf::sheen_albedo_scaling(m.sheen_color, e(n_dot_v, m.sheen_roughness),
                                                 e(n_dot_l, m.sheen_roughness));
            if (n_dot_l > 0.0f) sheen = brdf::sheen_specular(m.sheen_color, m.sheen_roughness, n_dot_l, n_dot_v, n_dot_h);
        }
        if (m.diffuse_transmission > 0.0f) {
            // The diffuse lobe times its cosine: the reflected and the transmitted lobe mixed.
            // The transmitted lobe takes the diffuse's weight: w lambert(c) = lambert(w c).
            glm::vec3 diffuse = brdf::diffuse_transmission_mix(n_dot_l * t.diffuse, n_dot_minus_l, m.diffuse_transmission,
                                                               t.diffuse_weight * m.diffuse_transmission_color);
            glm::vec3 specular_cos = n_dot_l > 0.0f ? n_dot_l * (sheen + specular * scaling) : glm::vec3(0.0f);
            lit = radiance * (specular_cos + diffuse * scaling);
        } else {
            lit = radiance * n_dot_l * (sheen + base * scaling);
        }
    }
    if (m.clearcoat > 0.0f) {
        float cc_mix = brdf::clearcoat_mix(m.clearcoat, m.clearcoat_f0, m.clearcoat_normal, v);
        glm::vec3 coat = radiance * brdf::clearcoat_specular(m.clearcoat_normal, v, l,
                                                             brdf::alpha_from_roughness(m.clearcoat_roughness));
        lit = glm::mix(lit, coat, cc_mix);
    }
    return lit;
}

}  // namespace fresnel
