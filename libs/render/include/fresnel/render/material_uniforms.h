#pragma once
// Material -> shader uniforms, in one place. The values are the material's raw factors;
// the shader (read_material in shaders/material_inputs.glsl) applies the rules, exactly
// as fresnel::evaluate does on the CPU, so nothing here computes F0 or weights.
#include <array>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/material/evaluate.h"
#include "fresnel/material/material.h"
#include "fresnel/render/shader_features.h"
#include "fresnel/render/uniform_blocks.h"

namespace fresnel {
namespace gpu {
class Program;
class UniformBuffer;
}

// The values one material uploads (MaterialBlock members in material_block.glsl: u_<field>).
struct MaterialUniforms {
    glm::vec4 base_color_factor{1.0f};  // baseColorFactor, or diffuseFactor with specular-glossiness
    float metallic_factor = 1.0f;
    float roughness_factor = 1.0f;
    float normal_scale = 1.0f;
    float occlusion_strength = 1.0f;
    glm::vec3 emissive_factor{0.0f};
    float emissive_strength = 1.0f;
    float alpha_cutoff = 0.5f;
    float ior = 1.5f;
    float specular_factor = 1.0f;
    glm::vec3 specular_color_factor{1.0f};
    glm::vec3 sg_specular_factor{1.0f};  // specular-glossiness only
    float glossiness_factor = 1.0f;      // specular-glossiness only
    float clearcoat_factor = 0.0f;       // with MATERIAL_CLEARCOAT only
    float clearcoat_roughness_factor = 0.0f;
    float clearcoat_normal_scale = 1.0f;
    // KHR_materials_transmission / _volume / _dispersion (with MATERIAL_TRANSMISSION only).
    float transmission_factor = 0.0f;
    float thickness_factor = 0.0f;
    glm::vec3 attenuation_color{1.0f};
    float attenuation_distance = 0.0f;  // 0 = infinite (transmission.h)
    float dispersion = 0.0f;
    glm::vec3 sheen_color_factor{0.0f};  // with MATERIAL_SHEEN only
    float sheen_roughness_factor = 0.0f;
    float anisotropy_strength = 0.0f;    // with MATERIAL_ANISOTROPY only
    float anisotropy_rotation = 0.0f;    // radians
    float iridescence_factor = 0.0f;  // with MATERIAL_IRIDESCENCE only
    float iridescence_ior = 1.3f;
    float iridescence_thickness_minimum = 100.0f;  // nm
    float iridescence_thickness_maximum = 400.0f;
    float diffuse_transmission_factor = 0.0f;  // with MATERIAL_DIFFUSE_TRANSMISSION only
    glm::vec3 diffuse_transmission_color_factor{1.0f};
    // The slot each map reads (material_map), nullptr for none; index = MaterialMap.
    std::array<const TextureSlot*, kMaterialMapCount> maps{};
    // The most probes of the shader's anisotropic filter per map (u_<map>_anisotropy, read by
    // sample_detail_map in material_inputs.glsl for the detail maps): 1 here, one trilinear
    // probe; the renderer raises it where the map's sampler and --anisotropy allow.
    std::array<float, kMaterialMapCount> anisotropy = [] {
        std::array<float, kMaterialMapCount> a{};
        a.fill(1.0f);
        return a;
    }();
};

MaterialUniforms material_uniforms(const Material& m);

// The shader feature bits (shader_features.h) of the material model: unlit,
// specular-glossiness, clearcoat, sheen, transmission, anisotropy, iridescence, diffuse transmission, alpha mode (feature_defines() spells them as #defines).
FeatureMask material_features(const Material& m);

// The uniform block of the values (std140, shaders/material_block.glsl).
MaterialBlock material_block(const MaterialUniforms& u);

// The samplers of `program` (in use): units[i] is the texture unit map i is bound to (-1: none).
// The renderer packs the maps a variant reads into consecutive units, so that with the
// image-based light's textures they stay within the 16 units OpenGL ES 3.0 guarantees.
void set_material_samplers(const gpu::Program& program, const std::array<int, kMaterialMapCount>& units);

// Tests: the values into `buffer` (made when empty) bound at kMaterialBlockBinding, and map i
// on unit i where bound[i].
void set_material_uniforms(const gpu::Program& program, const MaterialUniforms& u,
                           const std::array<bool, kMaterialMapCount>& bound, gpu::UniformBuffer& buffer);

}  // namespace fresnel
