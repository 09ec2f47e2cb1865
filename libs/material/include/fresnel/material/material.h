#pragma once
// The material model: what a surface is made of, as loaders read it from files.
//
// A Material is the glTF 2.0 metallic-roughness core plus one optional block per
// extension, holding the extension's values as written in the file (defaults of the
// specification where a value is absent). Loaders only translate into this; the rules
// that turn a material and its textures into shading inputs live in ONE C++ function,
// fresnel::evaluate (evaluate.h), and in its GLSL twin read_material
// (shaders/material_inputs.glsl). tests/gpu/material_gpu_test.cpp keeps the two equal.
//
// Blocks marked "kept, not shaded" are parsed with the specification's defaults and
// carried (for `fresnel info`, and converters), but neither evaluate
// nor the shader reads them yet.
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace fresnel {

enum class AlphaMode { Opaque, Mask, Blend };

// KHR_texture_transform as written in the file; matrix() is the form samplers use.
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians, counter-clockwise rotation of the UVs
    glm::vec2 scale{1.0f};
    // uv' = (matrix() * vec3(uv, 1)).xy = T * R * S * uv (the extension's definition).
    glm::mat3 matrix() const {
        float c = std::cos(rotation), s = std::sin(rotation);
        glm::mat3 t(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
        glm::mat3 r(c, -s, 0, s, c, 0, 0, 0, 1);
        glm::mat3 m(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
        return t * r * m;
    }
};

// A material's reference to a texture. `texture` indexes the scene's textures (each of
// which names an image and a sampler); tex_coord selects TEXCOORD_0 or _1 (after
// KHR_texture_transform's texCoord override). `transform` is the matrix of
// `transform_params` (identity without the extension).
struct TextureSlot {
    int texture = -1;  // -1 = none
    int tex_coord = 0;
    bool has_transform = false;
    TextureTransform transform_params;
    glm::mat3 transform{1.0f};
    bool valid() const { return texture >= 0; }
    void set_transform(const TextureTransform& t) {
        transform_params = t;
        transform = t.matrix();
        has_transform = true;
    }
};
using TextureRef = TextureSlot;  // the former name (the glTF loader and its tests still say it)

// ---- Extension blocks (glTF names in comments; defaults are the specification's) ----

struct IorExt {            // KHR_materials_ior
    float ior = 1.5f;      // 0 is allowed by the extension (F0 = 1)
};
struct SpecularExt {                       // KHR_materials_specular
    float specular_factor = 1.0f;          // specularFactor: weight of the dielectric lobe
    TextureSlot specular_texture;          // specularTexture: A channel, linear
    glm::vec3 specular_color_factor{1.0f}; // specularColorFactor: tints F0 (may exceed 1)
    TextureSlot specular_color_texture;    // specularColorTexture: RGB, sRGB
};
struct ClearcoatExt {                      // KHR_materials_clearcoat
    float clearcoat_factor = 0.0f;
    TextureSlot clearcoat_texture;         // R, linear
    float clearcoat_roughness_factor = 0.0f;
    TextureSlot clearcoat_roughness_texture;  // G, linear
    TextureSlot clearcoat_normal_texture;  // tangent space; the geometric normal without one
    float clearcoat_normal_scale = 1.0f;
};
struct EmissiveStrengthExt {               // KHR_materials_emissive_strength
    float emissive_strength = 1.0f;
};
struct UnlitExt {};                        // KHR_materials_unlit
// KHR_materials_pbrSpecularGlossiness, as read from the file. Shaded through
// specular_glossiness_to_metallic_roughness (evaluate.h), the documented conversion.
struct SpecularGlossinessExt {
    glm::vec4 diffuse_factor{1.0f};
    TextureSlot diffuse_texture;           // sRGB RGBA
    glm::vec3 specular_factor{1.0f};
    float glossiness_factor = 1.0f;
    TextureSlot specular_glossiness_texture;  // RGB specular (sRGB), A glossiness (linear)
    // Read the two textures' RGB as stored, without sRGB decoding, as the Khronos Sample
    // Renderer (1.1.0) does, against the extension's text (map_srgb in evaluate.h; the job's
    // specularGlossinessTextures setting).
    bool linear_textures = false;
};

// Shaded (transmission.h): KHR_materials_transmission, _volume, _dispersion; (evaluate.h)
// KHR_materials_sheen, _iridescence, _anisotropy, _diffuse_transmission, _diffuse_roughness.
struct SheenExt {                          // KHR_materials_sheen (shaded: evaluate.h)
    glm::vec3 sheen_color_factor{0.0f};
    TextureSlot sheen_color_texture;       // RGB, sRGB
    float sheen_roughness_factor = 0.0f;
    TextureSlot sheen_roughness_texture;   // A
};
struct TransmissionExt {                   // KHR_materials_transmission
    float transmission_factor = 0.0f;
    TextureSlot transmission_texture;      // R
};
struct VolumeExt {                         // KHR_materials_volume
    float thickness_factor = 0.0f;
    TextureSlot thickness_texture;         // G
    float attenuation_distance = std::numeric_limits<float>::infinity();
    glm::vec3 attenuation_color{1.0f};
};
struct IridescenceExt {                    // KHR_materials_iridescence (shaded: evaluate.h)
    float iridescence_factor = 0.0f;
    TextureSlot iridescence_texture;       // R
    float iridescence_ior = 1.3f;
    float iridescence_thickness_minimum = 100.0f;  // nm
    float iridescence_thickness_maximum = 400.0f;  // nm
    TextureSlot iridescence_thickness_texture;     // G
};
struct AnisotropyExt {                     // KHR_materials_anisotropy (shaded: evaluate.h)
    float anisotropy_strength = 0.0f;
    float anisotropy_rotation = 0.0f;      // radians
    TextureSlot anisotropy_texture;        // RG direction, B strength
};
struct DispersionExt {                     // KHR_materials_dispersion
    float dispersion = 0.0f;
};
struct DiffuseTransmissionExt {            // KHR_materials_diffuse_transmission (shaded: evaluate.h)
    float diffuse_transmission_factor = 0.0f;
    TextureSlot diffuse_transmission_texture;        // A
    glm::vec3 diffuse_transmission_color_factor{1.0f};
    TextureSlot diffuse_transmission_color_texture;  // RGB, sRGB
};
// KHR_materials_diffuse_roughness (shaded: evaluate.h): the roughness of the diffuse lobe,
// shaded with the energy-preserving Oren-Nayar model (EON, brdf.h); 0 is Lambert.
struct DiffuseRoughnessExt {
    float diffuse_roughness_factor = 0.0f;
    TextureSlot diffuse_roughness_texture;  // R, linear
};

// Wavefront MTL, as read from the file: the classic (Phong-era) keys and the PBR
// extension's. The OBJ loader fills it and converts it to the metallic-roughness core by
// phong_to_metallic_roughness (phong.h); the block keeps the original values for a Phong
// shading model and a fitted conversion. Kept, not shaded. Absent keys take OpenGL 1's
// glMaterial defaults (Ka 0.2, Kd 0.8, Ks 0, Ke 0, Ns 0, d 1), as an OpenGL 1 viewer shows them.
enum class MtlChannel { R, G, B, Matte, Luminance };  // -imfchan r|g|b|m|l (m = alpha)
struct MtlMap {
    TextureSlot slot;                       // -o/-s become slot's transform (in glTF's UV space)
    MtlChannel channel = MtlChannel::R;     // which channel a scalar map uses
    float bump_multiplier = 1.0f;           // -bm (bump and normal maps)
    bool valid() const { return slot.valid(); }
};
struct PhongExt {
    glm::vec3 ambient{0.2f};                // Ka
    glm::vec3 diffuse{0.8f};                // Kd
    glm::vec3 specular{0.0f};               // Ks
    glm::vec3 emission{0.0f};               // Ke
    float shininess = 0.0f;                 // Ns: Blinn-Phong exponent (as written; OpenGL 1 clamps to 128)
    float optical_density = 1.0f;           // Ni
    float dissolve = 1.0f;                  // d, or 1 - Tr when the file has no d
    glm::vec3 transmission_filter{1.0f};    // Tf
    int illum = 2;                          // illumination model 0..10
    MtlMap ambient_map, diffuse_map, specular_map, shininess_map, dissolve_map, emission_map;  // map_Ka Kd Ks Ns d Ke
    MtlMap bump_map;                        // bump / map_bump (-bm)
    // The PBR extension (absent: not written in the file).
    std::optional<float> roughness, metallic, sheen;           // Pr, Pm, Ps
    std::optional<float> clearcoat, clearcoat_roughness;       // Pc, Pcr
    std::optional<float> anisotropy, anisotropy_rotation;      // aniso, anisor (fraction of a turn)
    MtlMap roughness_map, metallic_map, sheen_map, normal_map; // map_Pr map_Pm map_Ps norm
    bool has_pbr() const { return roughness || metallic || roughness_map.valid() || metallic_map.valid(); }
};

// glTF metallic-roughness material with its extension blocks.
struct Material {
    std::string name;
    glm::vec4 base_color_factor{1.0f};
    TextureSlot base_color;            // sRGB
    float metallic_factor = 1.0f;
    float roughness_factor = 1.0f;
    TextureSlot metallic_roughness;    // B = metallic, G = roughness, linear
    TextureSlot normal;                // tangent space, linear
    float normal_scale = 1.0f;
    TextureSlot occlusion;             // R, linear
    float occlusion_strength = 1.0f;
    TextureSlot emissive;              // sRGB
    glm::vec3 emissive_factor{0.0f};
    AlphaMode alpha_mode = AlphaMode::Opaque;
    float alpha_cutoff = 0.5f;
    bool double_sided = false;

    std::optional<IorExt> ior;
    std::optional<SpecularExt> specular;
    std::optional<ClearcoatExt> clearcoat;
    std::optional<EmissiveStrengthExt> emissive_strength;
    std::optional<UnlitExt> unlit;
    std::optional<SpecularGlossinessExt> specular_glossiness;
    std::optional<SheenExt> sheen;
    std::optional<TransmissionExt> transmission;
    std::optional<VolumeExt> volume;
    std::optional<IridescenceExt> iridescence;
    std::optional<AnisotropyExt> anisotropy;
    std::optional<DispersionExt> dispersion;
    std::optional<DiffuseTransmissionExt> diffuse_transmission;
    std::optional<DiffuseRoughnessExt> diffuse_roughness;
    std::optional<PhongExt> phong;  // Wavefront MTL source values (OBJ files)

    // The values that hold without a block (the extensions' defaults).
    float ior_value() const { return ior ? ior->ior : 1.5f; }
    float emissive_strength_value() const { return emissive_strength ? emissive_strength->emissive_strength : 1.0f; }
    // A coat is shaded only with a positive factor (the extension's default 0 means none).
    bool has_clearcoat() const { return clearcoat && clearcoat->clearcoat_factor > 0.0f; }
    // Sheen is shaded only with a non-zero colour factor (the default 0 is no sheen, as the
    // colour is factor * texture).
    bool has_sheen() const {
        return sheen && (sheen->sheen_color_factor.x > 0.0f || sheen->sheen_color_factor.y > 0.0f ||
                         sheen->sheen_color_factor.z > 0.0f);
    }
    // Anisotropy is shaded only with a positive strength (strength = factor * texture B; at 0
    // the lobe is the isotropic one).
    bool has_anisotropy() const { return anisotropy && anisotropy->anisotropy_strength > 0.0f; }
    // The thin film is shaded only with a positive factor (the default 0 is none, as the
    // strength is factor * texture).
    bool has_iridescence() const { return iridescence && iridescence->iridescence_factor > 0.0f; }
    // Diffuse transmission is shaded only with a positive factor (the default 0 is none, as the
    // share transmitted is factor * texture A; the Khronos viewer's mix(..., 0) is the same).
    bool has_diffuse_transmission() const {
        return diffuse_transmission && diffuse_transmission->diffuse_transmission_factor > 0.0f;
    }
    // The diffuse lobe is rough (EON) only with a positive factor (0, the default, is Lambert).
    bool has_diffuse_roughness() const {
        return diffuse_roughness && diffuse_roughness->diffuse_roughness_factor > 0.0f;
    }
};

// Dielectric reflectance at normal incidence of an ior against air: ((ior-1)/(ior+1))^2
// (0.04 at 1.5). The same as ior_to_f0 in shaders/material_inputs.glsl.
inline float ior_to_f0(float ior) {
    float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

}  // namespace fresnel
