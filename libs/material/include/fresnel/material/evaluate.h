#pragma once
// fresnel::evaluate: a Material, its textures and a surface point -> the BRDF's inputs.
// Every material rule lives here and, line for line, in its GLSL twin read_material
// (shaders/material_inputs.glsl); tests/gpu/material_gpu_test.cpp keeps them equal.
// The rules (in evaluation order):
//   base colour = baseColorFactor * vertex colour * baseColorTexture (sRGB)
//   metallic, roughness = factors * metallicRoughnessTexture B, G
//   F0 colour = ior_to_f0(ior) * specularColorFactor * specularColorTexture RGB (sRGB),
//               clamped to <= 1; specular weight = specularFactor * specularTexture A
//   specular-glossiness (replaces the above): specular_glossiness_to_metallic_roughness
//   clearcoat = factor * clearcoatTexture R, roughness = factor * clearcoatRoughnessTexture G,
//               coat F0 = ior_to_f0(ior); all only when clearcoatFactor > 0
//   sheen colour = sheenColorFactor * sheenColorTexture RGB (sRGB), roughness = factor *
//               sheenRoughnessTexture A; only when the colour factor is non-zero
//   anisotropy (only with a positive strength and tangents): strength = anisotropyStrength *
//               anisotropyTexture B; direction = rotate(anisotropyRotation) * (texture RG * 2 - 1,
//               else (1, 0)), normalised ((1, 0) when 0); anisotropic t = direction.x T +
//               direction.y B of the geometric frame, b = cross(geometric normal, t)
//   iridescence = iridescenceFactor * iridescenceTexture R, film ior = iridescenceIor,
//               thickness = mix(minimum, maximum, iridescenceThicknessTexture G) nm, without
//               the texture the maximum; only when the factor is positive
//   diffuse transmission = diffuseTransmissionFactor * diffuseTransmissionTexture A, colour =
//               diffuseTransmissionColorFactor * diffuseTransmissionColorTexture RGB (sRGB); only
//               when the factor is positive (KHR_materials_diffuse_transmission)
//   diffuse roughness = diffuseRoughnessFactor * diffuseRoughnessTexture R, clamped to [0, 1];
//               only when the factor is positive and not under specular-glossiness (as
//               KHR_materials_specular; KHR_materials_diffuse_roughness: the lobe is brdf::eon_factor
//               times Lambert's)
//   occlusion = 1 + strength * (occlusionTexture R - 1)
//   emissive = emissiveFactor * emissiveStrength * emissiveTexture RGB (sRGB)
//   alpha: OPAQUE -> 1; MASK -> discard below the cutoff, else 1; BLEND -> as computed
//   transmission (KHR_materials_transmission, not with specular-glossiness or unlit):
//               factor * transmissionTexture R; with KHR_materials_volume thickness =
//               thicknessFactor * thicknessTexture G, attenuation colour and distance (infinity -> 0);
//               dispersion factor (KHR_materials_dispersion); see transmission.h
//   normal = normalize(TBN * ((map * 2 - 1) * (scale, scale, 1))) when a normal map is read,
//            else the geometric normal; the same for the clearcoat normal.
// A map is read only when the primitive can (map_usable); an unreadable map reads as
// absent, as the renderer leaves it unbound.
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/material/brdf.h"
#include "fresnel/material/brdf_model.h"
#include "fresnel/material/material.h"
#include "fresnel/material/texture.h"
#include "fresnel/material/transmission.h"

namespace fresnel {

// The texture maps a material can read, in the order of the material block's per-map entries
// (MaterialBlock::maps; the renderer packs the texture units per draw).
enum class MaterialMap {
    BaseColor,           // baseColorTexture, or the diffuseTexture of specular-glossiness
    MetallicRoughness,
    Normal,
    Occlusion,
    Emissive,
    Specular,            // KHR_materials_specular specularTexture
    SpecularColor,       // KHR_materials_specular specularColorTexture
    SpecularGlossiness,  // KHR_materials_pbrSpecularGlossiness specularGlossinessTexture
    Clearcoat,
    ClearcoatRoughness,
    ClearcoatNormal,
    SheenColor,          // KHR_materials_sheen sheenColorTexture
    SheenRoughness,      // KHR_materials_sheen sheenRoughnessTexture
    Transmission,        // KHR_materials_transmission transmissionTexture (R)
    Thickness,           // KHR_materials_volume thicknessTexture (G), read only with transmission
    Anisotropy,          // KHR_materials_anisotropy anisotropyTexture (RG direction, B strength), needs tangents
    Iridescence,           // KHR_materials_iridescence iridescenceTexture (R)
    IridescenceThickness,  // KHR_materials_iridescence iridescenceThicknessTexture (G)
    DiffuseTransmission,       // KHR_materials_diffuse_transmission diffuseTransmissionTexture (A)
    DiffuseTransmissionColor,  // KHR_materials_diffuse_transmission diffuseTransmissionColorTexture (RGB, sRGB)
    DiffuseRoughness,          // KHR_materials_diffuse_roughness diffuseRoughnessTexture (R)
};
inline constexpr int kMaterialMapCount = 21;

struct MaterialMapInfo {
    const char* name;    // GLSL: u_<name>_map, u_<name>_uv, u_<name>_transform
    const char* define;  // GLSL: HAS_<NAME>_MAP
    bool srgb;           // colour data, decoded by the sampler
    bool normal_map;     // needs a tangent frame
    // A detail map: read through the renderer's anisotropic filter (detail_footprint in
    // texture.h, sample_detail_map in the shader); the others are read with one lookup.
    bool detail;
};
const MaterialMapInfo& material_map_info(MaterialMap map);
// Whether material `m` reads map `map` decoded from sRGB: material_map_info(map).srgb, but
// as stored for the diffuse and specular-glossiness maps of a specular-glossiness material
// read as the Khronos Sample Renderer reads them (SpecularGlossinessExt::linear_textures).
bool map_srgb(const Material& m, MaterialMap map);

// The slot the rules read for `map`, or nullptr when this material has none there
// (specular-glossiness reads its own maps instead of the metallic-roughness ones;
// clearcoat maps only with a coat).
const TextureSlot* material_map(const Material& m, MaterialMap map);

// Which vertex attributes the primitive has.
struct VertexInputs {
    bool has_uv0 = true, has_uv1 = true, has_tangent = true;
};
// Whether a primitive with `inputs` can read `slot` for `map`: any map needs TEXCOORD_0,
// a map on TEXCOORD_1 needs it too, normal maps and the anisotropy map need tangents.
bool map_usable(const TextureSlot& slot, MaterialMap map, const VertexInputs& inputs);

// The point being shaded, as the fragment shader sees it.
struct SurfacePoint {
    glm::vec2 uv0{0.0f}, uv1{0.0f};
    glm::vec4 color{1.0f};  // COLOR_0 (1 without it)
    // Geometric frame: unit vectors, already flipped for back faces.
    glm::vec3 tangent{1, 0, 0}, bitangent{0, 1, 0}, normal{0, 0, 1};
    VertexInputs inputs;
    // Level of detail. With `lod`, every map is read at that λ (textureLod); otherwise λ
    // comes from the screen-space derivatives of each map's transformed UVs, as hardware
    // computes it (all zero: magnification, level 0).
    std::optional<float> lod;
    glm::vec2 duv0_dx{0.0f}, duv0_dy{0.0f}, duv1_dx{0.0f}, duv1_dy{0.0f};
    // Without `lod`: the most probes of the detail maps' anisotropic filter, as the renderer
    // asks for them (RenderSettings::anisotropy; 1: one probe at the GL level of detail).
    float max_anisotropy = 1.0f;
};

// evaluate's result: the BRDF's inputs plus what the shader does with the rest.
struct EvaluatedMaterial {
    brdf::Surface surface;     // base colour, metallic, roughness, F0 (specular_f0 * specular_color), weight
    float alpha = 1.0f;        // after the alpha mode
    bool discard = false;      // MASK below the cutoff
    glm::vec3 emissive{0.0f};
    float occlusion = 1.0f;
    glm::vec3 normal{0, 0, 1};            // shading normal
    float clearcoat = 0.0f;               // coat strength (0 = no coat)
    float clearcoat_roughness = 0.0f;     // perceptual
    float clearcoat_f0 = 0.04f;
    glm::vec3 clearcoat_normal{0, 0, 1};
    glm::vec3 sheen_color{0.0f};          // KHR_materials_sheen (0 = no sheen)
    float sheen_roughness = 0.0f;         // perceptual
    // KHR_materials_anisotropy (strength 0 = none): the direction in the tangent plane (unit,
    // after the rotation) and the world-space frame the lobe is stretched along.
    float anisotropy_strength = 0.0f;
    glm::vec2 anisotropy_direction{1.0f, 0.0f};
    glm::vec3 anisotropic_t{1, 0, 0}, anisotropic_b{0, 1, 0};
    float iridescence = 0.0f;             // KHR_materials_iridescence strength (0 = no film)
    float iridescence_ior = 1.3f;
    float iridescence_thickness = 0.0f;   // nm
    // KHR_materials_diffuse_transmission (factor 0 = none): the share of the diffuse lobe
    // transmitted through the surface as a Lambert lobe of this colour (brdf::diffuse_transmission_mix).
    float diffuse_transmission = 0.0f;
    glm::vec3 diffuse_transmission_color{1.0f};
    // KHR_materials_diffuse_roughness (0 = Lambert): the diffuse lobe is the energy-preserving
    // Oren-Nayar one, brdf::eon_factor times Lambert's.
    float diffuse_roughness = 0.0f;
    bool unlit = false;
    TransmissionInputs transmission;      // factor 0 without KHR_materials_transmission
};

EvaluatedMaterial evaluate(const Material& material, const TextureSource& textures, const SurfacePoint& point);

// One map's filtered, decoded texel at the point, as evaluate reads it (its UV set through its
// transform; the explicit level of detail, else the detail filter for detail maps and one
// lookup at the GL level of detail for the others), or nullopt when the material has no usable
// map there (evaluate then reads white).
std::optional<glm::vec4> sample_material_map(const Material& material, const TextureSource& textures,
                                             const SurfacePoint& point, MaterialMap map);

// KHR_materials_pbrSpecularGlossiness -> metallic-roughness at one point, the documented
// conversion (the same as in read_material):
//   base colour = diffuse (RGBA), metallic = 0, roughness = 1 - glossiness,
//   dielectric F0 colour = specular, specular weight = 1.
// It is exact: the specular-glossiness BRDF is the dielectric branch of the glTF BRDF with
// F0 = specular, which metallic-roughness + KHR_materials_specular can state. The diffuse
// is weighted only by the BRDF's own (1 - F), not by 1 - max(specular) as the extension's
// reference code does; this is how fresnel has always shaded it, and the image tests hold it.
struct MetallicRoughnessPoint {
    glm::vec4 base_color{1.0f};
    float metallic = 0.0f;
    float roughness = 1.0f;
    glm::vec3 f0{0.04f};
    float specular_weight = 1.0f;
};
MetallicRoughnessPoint specular_glossiness_to_metallic_roughness(glm::vec4 diffuse, glm::vec3 specular,
                                                                 float glossiness);

// The same conversion for a whole material, for converters that must write
// metallic-roughness (fresnel convert to OBJ/MTL and glTF). Factors convert exactly: base colour
// factor/texture = diffuse factor/texture, metallic 0, roughness 1 - glossinessFactor,
// KHR_materials_specular with specularColorFactor = specularFactor / ior_to_f0(ior) and
// specularColorTexture = the RGB of specularGlossinessTexture, ior kept. Lost: the
// glossiness channel (A) of specularGlossinessTexture, as roughness = 1 - g * A has no
// metallic-roughness form (`lost_glossiness_map` says so). A material without the block
// is returned unchanged. The renderer keeps the block and converts per point instead.
Material to_metallic_roughness(const Material& material, bool* lost_glossiness_map = nullptr);

// The thin film of `m` at the view v (KHR_materials_iridescence; factor 0 without one): the
// film shade_light and shade_light_transmission use.
brdf::IridescenceFresnel film_at(const EvaluatedMaterial& m, glm::vec3 v);

// KHR_materials_sheen and _clearcoat layering of one punctual light (pbr.frag's light loop):
//   base = (f_diffuse + f_specular_dielectric * comp_dielectric + f_specular_metal * comp_metal) n.l
//   with anisotropy the specular lobes' D and V are the anisotropic ones (brdf::apply_anisotropy)
//   with a thin film (KHR_materials_iridescence) the terms' Fresnel is mixed with the film's,
//               brdf::iridescence_at(n.v) (brdf::layer)
//   with diffuse transmission (KHR_materials_diffuse_transmission), as the Khronos viewer: the
//               diffuse lobe times its cosine is mix(f_diffuse n.l, w lambert(colour) n.(-l), factor)
//               (w: the diffuse's weight 1 - F, (1 - metallic)), so lights behind the surface light it
//   with diffuse roughness (KHR_materials_diffuse_roughness) f_diffuse is times
//               brdf::eon_factor(base colour, roughness, n.l, n.v, l.v)
//   with sheen: base = f_sheen n.l + base * sheen_albedo_scaling(colour, E(n.v), E(n.l)),
//               E from brdf::SheenAlbedoTable::standard() (the shader: the table's A channel)
//   result = radiance * mix(base, clearcoat_specular, clearcoat_mix)
// comp_* are the energy-compensation factors (1 without); `model` selects the BRDF's terms
// (brdf_model.h; the default is glTF's). The twin of shade_light in shaders/material_inputs.glsl.
glm::vec3 shade_light(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l, glm::vec3 radiance,
                      glm::vec3 comp_dielectric = glm::vec3(1.0f), glm::vec3 comp_metal = glm::vec3(1.0f),
                      const brdf::BrdfModel& model = {});

// Whether the material is shaded with KHR_materials_transmission (the block is present, even
// with factor 0, as in the Khronos viewer; not for specular-glossiness or unlit materials).
// Such materials are drawn after the opaque scene, which they refract, and are not part of it.
bool is_transmissive(const Material& material);

// The transmission term a punctual light adds to shade_light (the twin of
// shade_light_transmission in shaders/transmission.glsl): the BTDF replaces the Lambert lobe in
// proportion to the transmission factor, under the dielectric Fresnel (and a thin film's:
// brdf::film_diffuse_weight) and the coat:
//   (1 - cc_mix) (1 - metallic) (1 - F_d) T [attenuate(radiance btdf_punctual(l_transmitted)) - radiance diffuse]
// diffuse = n.l lambert (times brdf::eon_factor with diffuse roughness), or with diffuse
// transmission brdf::diffuse_transmission_mix of it.
// l: the direction to the light; l_transmitted: to the light from the point where the
// transmission ray leaves (ray_length = the ray's length, for the volume's attenuation).
glm::vec3 shade_light_transmission(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l, glm::vec3 l_transmitted,
                                   float ray_length, glm::vec3 radiance);

// The diffuse lobe the transmission takes its share of, times its cosine, at l (either side):
//   (1 - cc_mix) (1 - metallic) w_film(F_d(v.h)) T diffuse
// with `diffuse` as in shade_light_transmission (which subtracts radiance times this); 0 without
// transmission.
glm::vec3 transmission_replaced_diffuse(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l);

// The whole BSDF times |n.l| at l on either side of the surface, as the path tracer shades
// with it (fresnel/material/bsdf.h samples it): shade_light with unit radiance, less
// transmission_replaced_diffuse, plus below the surface the thin-walled transmission lobe:
//   (1 - cc_mix) (1 - metallic) w_film(F_d(v.h')) T base_colour D(n.h') V(n.l', n.v) n.l'
// (l' = l mirrored above the surface, h' = normalize(l' + v), D and V at
// transmission::apply_ior_to_roughness(alpha, ior), kept at least kMinSampledAlpha). Without
// transmission it is shade_light's value, so a tracer and a rasteriser shade one material.
// (The rasteriser's punctual transmission follows the Khronos viewer, with no cosine and a
// second 1 - F; the tracer keeps the BSDF reciprocal and energy-bounded.)
inline constexpr float kMinSampledAlpha = 9e-4f;  // perceptual roughness 0.03

// Multiple-scattering energy compensation of the specular lobes (Fdez-Aguera 2019, as Filament
// applies it; shaders/ibl.glsl's energy_compensation and pbr.frag's use of it): each lobe times
// 1 + F0 (1/E - 1), E the GGX lobe's directional albedo at (n.v, roughness) from the BRDF
// table's third channel, F0 the dielectric lobe's F0 colour times its weight and the metal's
// base colour. The rasteriser applies it to every light and the tracer to every bounce, so the
// two agree in the white furnace.
struct EnergyCompensation {
    glm::vec3 dielectric{1.0f}, metal{1.0f};
};
glm::vec3 energy_compensation(glm::vec3 f0, float e);
EnergyCompensation energy_compensation(const EvaluatedMaterial& m, float e);

glm::vec3 shade_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l, const brdf::BrdfModel& model = {},
                     const EnergyCompensation& comp = {});

}  // namespace fresnel
