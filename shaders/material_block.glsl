// The material's factors and per-map parameters as one std140 uniform block: the layout of
// fresnel::MaterialBlock (libs/render/include/fresnel/render/uniform_blocks.h), which
// tests/gpu/material_gpu_test.cpp checks member by member against the driver's offsets.
// The renderer keeps one buffer per material and binds it per draw; only the samplers
// (u_<map>_map) stay plain uniforms. Every member exists in every variant (a fixed layout);
// the defines decide which the shader reads. The per-map members follow MaterialMap order.
layout(std140) uniform MaterialBlock {
    vec4 u_base_color_factor;  // baseColorFactor, or diffuseFactor (specular-glossiness)
    vec3 u_emissive_factor;
    float u_emissive_strength;  // KHR_materials_emissive_strength (1 without)
    vec3 u_specular_color_factor;  // KHR_materials_specular (1 without)
    float u_specular_factor;       // KHR_materials_specular (1 without)
    vec3 u_sg_specular_factor;  // KHR_materials_pbrSpecularGlossiness specularFactor
    float u_glossiness_factor;
    vec3 u_sheen_color_factor;  // KHR_materials_sheen
    float u_sheen_roughness_factor;
    vec3 u_attenuation_color;  // KHR_materials_volume
    float u_attenuation_distance;  // 0 = infinite
    vec3 u_diffuse_transmission_color_factor;  // KHR_materials_diffuse_transmission
    float u_diffuse_transmission_factor;
    float u_metallic_factor;
    float u_roughness_factor;
    float u_normal_scale;
    float u_occlusion_strength;
    float u_alpha_cutoff;
    float u_ior;  // KHR_materials_ior (1.5 without)
    float u_clearcoat_factor;  // KHR_materials_clearcoat
    float u_clearcoat_roughness_factor;
    float u_clearcoat_normal_scale;
    float u_transmission_factor;  // KHR_materials_transmission
    float u_thickness_factor;     // KHR_materials_volume
    float u_dispersion;           // KHR_materials_dispersion
    float u_anisotropy_strength;  // KHR_materials_anisotropy
    float u_anisotropy_rotation;  // radians
    float u_iridescence_factor;   // KHR_materials_iridescence
    float u_iridescence_ior;
    float u_iridescence_thickness_minimum;  // nm
    float u_iridescence_thickness_maximum;
    float u_diffuse_roughness_factor;  // KHR_materials_diffuse_roughness (0 without)
    // Per map: the KHR_texture_transform matrix, the UV set (0/1), the most probes of
    // sample_detail_map (read for the detail maps only). Spelled out: GLSL ES 3.00 has no
    // token pasting.
    mat3 u_base_color_transform; int u_base_color_uv; float u_base_color_anisotropy;
    mat3 u_metallic_roughness_transform; int u_metallic_roughness_uv; float u_metallic_roughness_anisotropy;
    mat3 u_normal_transform; int u_normal_uv; float u_normal_anisotropy;
    mat3 u_occlusion_transform; int u_occlusion_uv; float u_occlusion_anisotropy;
    mat3 u_emissive_transform; int u_emissive_uv; float u_emissive_anisotropy;
    mat3 u_specular_transform; int u_specular_uv; float u_specular_anisotropy;
    mat3 u_specular_color_transform; int u_specular_color_uv; float u_specular_color_anisotropy;
    mat3 u_specular_glossiness_transform; int u_specular_glossiness_uv; float u_specular_glossiness_anisotropy;
    mat3 u_clearcoat_transform; int u_clearcoat_uv; float u_clearcoat_anisotropy;
    mat3 u_clearcoat_roughness_transform; int u_clearcoat_roughness_uv; float u_clearcoat_roughness_anisotropy;
    mat3 u_clearcoat_normal_transform; int u_clearcoat_normal_uv; float u_clearcoat_normal_anisotropy;
    mat3 u_sheen_color_transform; int u_sheen_color_uv; float u_sheen_color_anisotropy;
    mat3 u_sheen_roughness_transform; int u_sheen_roughness_uv; float u_sheen_roughness_anisotropy;
    mat3 u_transmission_transform; int u_transmission_uv; float u_transmission_anisotropy;
    mat3 u_thickness_transform; int u_thickness_uv; float u_thickness_anisotropy;
    mat3 u_anisotropy_transform; int u_anisotropy_uv; float u_anisotropy_anisotropy;
    mat3 u_iridescence_transform; int u_iridescence_uv; float u_iridescence_anisotropy;
    mat3 u_iridescence_thickness_transform; int u_iridescence_thickness_uv; float u_iridescence_thickness_anisotropy;
    mat3 u_diffuse_transmission_transform; int u_diffuse_transmission_uv; float u_diffuse_transmission_anisotropy;
    mat3 u_diffuse_transmission_color_transform; int u_diffuse_transmission_color_uv; float u_diffuse_transmission_color_anisotropy;
    mat3 u_diffuse_roughness_transform; int u_diffuse_roughness_uv; float u_diffuse_roughness_anisotropy;
};
