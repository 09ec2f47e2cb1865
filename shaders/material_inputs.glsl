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

// Per map: sampler, UV set (0/1) and the KHR_texture_transform matrix.
#define DECLARE_MAP(name) uniform sampler2D u_##name##_map; uniform int u_##name##_uv; uniform mat3 u_##name##_transform;
#ifdef HAS_BASE_COLOR_MAP
DECLARE_MAP(base_color)
#endif
#ifdef HAS_METALLIC_ROUGHNESS_MAP
DECLARE_MAP(metallic_roughness)
#endif
#ifdef HAS_NORMAL_MAP
DECLARE_MAP(normal)
#endif
#ifdef HAS_OCCLUSION_MAP
DECLARE_MAP(occlusion)
#endif
#ifdef HAS_EMISSIVE_MAP
DECLARE_MAP(emissive)
#endif
#ifdef HAS_SPECULAR_MAP
DECLARE_MAP(specular)
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
DECLARE_MAP(specular_color)
#endif
#ifdef HAS_CLEARCOAT_MAP
DECLARE_MAP(clearcoat)
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
DECLARE_MAP(clearcoat_roughness)
#endif
#ifdef HAS_CLEARCOAT_NORMAL_MAP
DECLARE_MAP(clearcoat_normal)
#endif

vec2 map_uv(int set, mat3 transform) {
    vec2 uv = set == 1 ? v_uv1 : v_uv0;
    return (transform * vec3(uv, 1.0)).xy;
}
#define SAMPLE_MAP(name) texture(u_##name##_map, map_uv(u_##name##_uv, u_##name##_transform))
// Normal maps are read one mip level sharper than the other maps. Why: the Khronos Sample
// Viewer's images (its reference renderer, WebGL on SwiftShader) resolve normal-map detail
// that much more sharply than llvmpipe's filtering of the same mip chain, and reflections
// amplify the difference; with the bias our images agree with them better in every one of
// 20 normal-mapped views over four environments (+0.6 dB mean, up to +2.2 dB), with no
// change elsewhere. Colour maps stay unbiased: biasing them lowers the agreement.
const float NORMAL_MAP_LOD_BIAS = -1.0;
#define SAMPLE_NORMAL_MAP(name) texture(u_##name##_map, map_uv(u_##name##_uv, u_##name##_transform), NORMAL_MAP_LOD_BIAS)

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
    m.base_color *= SAMPLE_MAP(base_color);  // an SRGB8_ALPHA8 texture: decoded by the sampler
#endif
    m.metallic = u_metallic_factor;
    m.roughness = u_roughness_factor;
#ifdef HAS_METALLIC_ROUGHNESS_MAP
    vec4 mr = SAMPLE_MAP(metallic_roughness);
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
    vec4 sg = SAMPLE_MAP(specular_color);
    m.f0_dielectric *= sg.rgb;
    m.roughness *= sg.a;
#endif
    m.roughness = 1.0 - m.roughness;
#else
#ifdef HAS_SPECULAR_MAP
    m.specular_weight *= SAMPLE_MAP(specular).a;
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
    m.f0_dielectric *= SAMPLE_MAP(specular_color).rgb;
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
    m.clearcoat *= SAMPLE_MAP(clearcoat).r;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
    m.clearcoat_roughness *= SAMPLE_MAP(clearcoat_roughness).g;
#endif
    m.clearcoat = clamp(m.clearcoat, 0.0, 1.0);
    m.clearcoat_roughness = clamp(m.clearcoat_roughness, 0.0, 1.0);
#endif
    m.occlusion = 1.0;
#ifdef HAS_OCCLUSION_MAP
    m.occlusion = 1.0 + u_occlusion_strength * (SAMPLE_MAP(occlusion).r - 1.0);
#endif
    m.emissive = u_emissive;
#ifdef HAS_EMISSIVE_MAP
    m.emissive *= SAMPLE_MAP(emissive).rgb;
#endif
    return m;
}
