// Material parameters and texture lookups: read_material is the GLSL twin of
// fresnel::evaluate (libs/material/src/evaluate.cpp); same structure, same rules, and
// tests/gpu/material_gpu_test.cpp keeps the two equal. The uniforms are the material's
// raw factors in MaterialBlock (material_block.glsl), packed by
// libs/render/src/material_uniforms.cpp. Which maps exist is
// decided per material by defines (HAS_BASE_COLOR_MAP, ...), so absent maps cost nothing.
#include "material_block.glsl"
#ifdef MATERIAL_SHEEN
#include "sheen.glsl"
#endif
#ifdef MATERIAL_IRIDESCENCE
#include "iridescence.glsl"
#endif

// Per map: its sampler (the map's transform, UV set and probes are in MaterialBlock).
#ifdef HAS_BASE_COLOR_MAP
uniform sampler2D u_base_color_map;
#endif
#if defined(HAS_METALLIC_ROUGHNESS_MAP) && !defined(METALLIC_ROUGHNESS_IN_ALPHA)
uniform sampler2D u_metallic_roughness_map;
#endif
#ifdef HAS_NORMAL_MAP
uniform sampler2D u_normal_map;
#endif
#ifdef HAS_OCCLUSION_MAP
uniform sampler2D u_occlusion_map;
#endif
#ifdef HAS_EMISSIVE_MAP
uniform sampler2D u_emissive_map;
#endif
#ifdef HAS_SPECULAR_MAP
uniform sampler2D u_specular_map;
#endif
#ifdef HAS_SPECULAR_COLOR_MAP
uniform sampler2D u_specular_color_map;
#endif
#ifdef HAS_SPECULAR_GLOSSINESS_MAP
uniform sampler2D u_specular_glossiness_map;
#endif
#ifdef HAS_CLEARCOAT_MAP
uniform sampler2D u_clearcoat_map;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
uniform sampler2D u_clearcoat_roughness_map;
#endif
#ifdef HAS_CLEARCOAT_NORMAL_MAP
uniform sampler2D u_clearcoat_normal_map;
#endif
#ifdef HAS_SHEEN_COLOR_MAP
uniform sampler2D u_sheen_color_map;
#endif
#ifdef HAS_SHEEN_ROUGHNESS_MAP
uniform sampler2D u_sheen_roughness_map;
#endif
#ifdef HAS_ANISOTROPY_MAP
uniform sampler2D u_anisotropy_map;
#endif
#ifdef HAS_IRIDESCENCE_MAP
uniform sampler2D u_iridescence_map;
#endif
#ifdef HAS_IRIDESCENCE_THICKNESS_MAP
uniform sampler2D u_iridescence_thickness_map;
#endif
#ifdef HAS_DIFFUSE_TRANSMISSION_MAP
uniform sampler2D u_diffuse_transmission_map;
#endif
#ifdef HAS_DIFFUSE_TRANSMISSION_COLOR_MAP
uniform sampler2D u_diffuse_transmission_color_map;
#endif
#ifdef HAS_DIFFUSE_ROUGHNESS_MAP
uniform sampler2D u_diffuse_roughness_map;
#endif

vec2 map_uv(int set, mat3 transform) {
    vec2 uv = set == 1 ? v_uv1 : v_uv0;
    return (transform * vec3(uv, 1.0)).xy;
}
// The detail maps (base colour, metallic-roughness, normal, occlusion, specular colour,
// specular-glossiness, clearcoat normal, sheen colour) are filtered anisotropically here,
// as SwiftShader's sampler does it, the renderer of the Khronos Sample Viewer's reference
// images: per 2x2 quad (dFdx/dFdy), the anisotropy is the texel footprint's major axis over
// its parallelogram's height, at most u_<map>_anisotropy; round(it) trilinear probes spread
// evenly along the major axis, at the level of detail of the footprint's height, averaged.
// u_<map>_anisotropy 1 is one trilinear probe at the footprint's level (the renderer sets 1
// for samplers that are not trilinear). One code path: a uniform branch would cost both
// sides on a software rasteriser. Against llvmpipe's own 16x filtering this is ~1.5x faster
// and agrees better with every Khronos reference (tests/image; docs/performance.md).
#ifdef MATERIAL_EXPLICIT_LOD
// Tests: every map at one given level of detail (SurfacePoint::lod on the C++ side).
uniform float u_material_lod;
vec4 sample_map(sampler2D map, int set, mat3 transform) { return textureLod(map, map_uv(set, transform), u_material_lod); }
vec4 sample_detail_map(sampler2D map, int set, mat3 transform, float max_anisotropy) {
    return sample_map(map, set, transform);
}
#else
vec4 sample_map(sampler2D map, int set, mat3 transform) { return texture(map, map_uv(set, transform)); }
// One map's footprint: where its probes go and at which level (what sample_footprint reads).
struct DetailFootprint {
    vec2 p;      // the first probe
    vec2 delta;  // from one probe to the next
    float lod;
    int n;       // probes, >= 1
};
DetailFootprint detail_footprint(vec2 uv, vec2 size, float max_anisotropy) {
    vec2 dx = dFdx(uv), dy = dFdy(uv);
    vec2 tx = dx * size, ty = dy * size;
    float lx = dot(tx, tx), ly = dot(ty, ty);
    float major2 = max(lx, ly);
    float area = abs(tx.x * ty.y - tx.y * ty.x);
    float anisotropy = clamp(major2 / max(area, 1e-30), 1.0, max(max_anisotropy, 1.0));
    vec2 axis = lx >= ly ? dx : dy;
    DetailFootprint f;
    f.lod = 0.5 * log2(max(major2, 1e-30) / (anisotropy * anisotropy));
    // round(anisotropy) probes; a NaN footprint compares false and takes one (an integer clamp
    // here would be as safe, but costs llvmpipe its fast loop: 1.4x the frame).
    float probes = anisotropy + 0.5;
    f.n = int(probes < 17.0 ? probes : 1.0);
    f.delta = axis / float(f.n);
    f.p = uv - axis * (float(f.n - 1) / float(2 * f.n));
    return f;
}
vec4 sample_footprint(sampler2D map, DetailFootprint f) {
    // A do-while, as n >= 1: llvmpipe runs a loop's body once more than its trips (the exit
    // test at the top of the last pass is made on masked lanes that still run the body), so a
    // `for` here cost one extra probe per map (DamagedHelmet: docs/performance.md).
    vec4 sum = vec4(0.0);
    vec2 p = f.p;
    int i = 0;
    do {
        sum += textureLod(map, p, f.lod);
        p += f.delta;
    } while (++i < f.n);
    return sum / float(f.n);
}
// A map's own footprint, from its UV set, transform, size and probe limit.
DetailFootprint map_footprint(sampler2D map, int set, mat3 transform, float max_anisotropy) {
    return detail_footprint(map_uv(set, transform), vec2(textureSize(map, 0)), max_anisotropy);
}
vec4 sample_detail_map(sampler2D map, int set, mat3 transform, float max_anisotropy) {
    return sample_footprint(map, map_footprint(map, set, transform, max_anisotropy));
}
#endif

// ((ior-1)/(ior+1))^2: fresnel::ior_to_f0 in material.h.
float ior_to_f0(float ior) {
    float r = (ior - 1.0) / (ior + 1.0);
    return r * r;
}

struct MaterialInputs {
    vec4 base_color;      // linear, alpha in .a (after the alpha mode)
    bool discard_fragment;  // ALPHA_MASK below the cutoff
    float metallic;
    float roughness;      // perceptual
    float occlusion;
    vec3 emissive;
    vec3 f0_dielectric;     // dielectric F0 colour
    float specular_weight;  // dielectric specular weight (F0 and F90)
    vec3 normal;            // shading normal
    float clearcoat;            // KHR_materials_clearcoat strength (0 = no coat)
    float clearcoat_roughness;  // perceptual
    float clearcoat_f0;
    vec3 clearcoat_normal;
    vec3 sheen_color;       // KHR_materials_sheen (0 = no sheen)
    float sheen_roughness;  // perceptual
    float anisotropy_strength;  // KHR_materials_anisotropy (0 = none)
    vec2 anisotropy_direction;  // in the tangent plane, unit, after the rotation
    vec3 anisotropic_t;         // the world-space direction the lobe is stretched along
    vec3 anisotropic_b;         // cross(ng, anisotropic_t)
    float iridescence;            // KHR_materials_iridescence strength (0 = no film)
    float iridescence_ior;
    float iridescence_thickness;  // nm
    float diffuse_transmission;        // KHR_materials_diffuse_transmission factor (0 = none)
    vec3 diffuse_transmission_color;
    float diffuse_roughness;           // KHR_materials_diffuse_roughness (0 = Lambert)
};

// The base colour, metallic-roughness, occlusion and normal maps through one footprint where the
// renderer found them alike (DETAIL_SHARED_FOOTPRINT: same UV set, transform, size and probe
// limit; feature::DetailSharedFootprint): the same probes as one footprint each, computed once,
// from the first of them the variant reads (the renderer asks for two or more).
#if defined(DETAIL_SHARED_FOOTPRINT) && !defined(MATERIAL_EXPLICIT_LOD)
#if defined(HAS_BASE_COLOR_MAP)
#define SHARED_FOOTPRINT map_footprint(u_base_color_map, u_base_color_uv, u_base_color_transform, u_base_color_anisotropy)
#elif defined(HAS_METALLIC_ROUGHNESS_MAP) && !defined(METALLIC_ROUGHNESS_IN_ALPHA)
#define SHARED_FOOTPRINT map_footprint(u_metallic_roughness_map, u_metallic_roughness_uv, u_metallic_roughness_transform, u_metallic_roughness_anisotropy)
#else
#define SHARED_FOOTPRINT map_footprint(u_occlusion_map, u_occlusion_uv, u_occlusion_transform, u_occlusion_anisotropy)
#endif
#define SAMPLE_SHARED_DETAIL(map, set, transform, anisotropy) sample_footprint(map, shared_footprint)
#else
#define SAMPLE_SHARED_DETAIL(map, set, transform, anisotropy) sample_detail_map(map, set, transform, anisotropy)
#endif

// t, b, ng: the geometric frame (unit, flipped for back faces), as evaluate's SurfacePoint.
MaterialInputs read_material(vec3 t, vec3 b, vec3 ng) {
    MaterialInputs m;
#ifdef SHARED_FOOTPRINT
    DetailFootprint shared_footprint = SHARED_FOOTPRINT;
#endif
    m.base_color = u_base_color_factor * v_color;
#ifdef HAS_BASE_COLOR_MAP
    // An SRGB8_ALPHA8 texture: decoded by the sampler (the alpha is linear).
    vec4 base_texel = SAMPLE_SHARED_DETAIL(u_base_color_map, u_base_color_uv, u_base_color_transform, u_base_color_anisotropy);
    m.base_color *= base_texel;
#endif
#ifdef METALLIC_ROUGHNESS_IN_ALPHA
    // The metallic-roughness texture's channels in the alphas of the base colour (B, metallic),
    // normal (G, roughness) and, with the occlusion, emissive (R) textures, which an opaque
    // material does not read (feature::MetallicRoughnessInAlpha): metallic and roughness are
    // the same texels through the same probes, one texture fewer to probe. The occlusion is
    // then filtered as the emissive is, without anisotropy (the renderer's rule for the
    // low-frequency maps). The base colour's alpha is set to 1 below (opaque).
    vec4 normal_texel = SAMPLE_SHARED_DETAIL(u_normal_map, u_normal_uv, u_normal_transform, u_normal_anisotropy);
#ifdef OCCLUSION_IN_METALLIC_ROUGHNESS
    vec4 emissive_texel = sample_map(u_emissive_map, u_emissive_uv, u_emissive_transform);
    vec4 mr = vec4(emissive_texel.a, normal_texel.a, base_texel.a, 1.0);
#else
    vec4 mr = vec4(1.0, normal_texel.a, base_texel.a, 1.0);
#endif
#endif
#ifdef SPECULAR_GLOSSINESS
    // KHR_materials_pbrSpecularGlossiness: base colour is the diffuse colour, the specular
    // map (sRGB RGB, linear A) gives F0 and glossiness; the conversion of
    // specular_glossiness_to_metallic_roughness (evaluate.h).
    vec3 sg_specular = u_sg_specular_factor;
    float glossiness = u_glossiness_factor;
#ifdef HAS_SPECULAR_GLOSSINESS_MAP
    vec4 sg = sample_detail_map(u_specular_glossiness_map, u_specular_glossiness_uv, u_specular_glossiness_transform, u_specular_glossiness_anisotropy);
    sg_specular *= sg.rgb;
    glossiness *= sg.a;
#endif
    m.metallic = 0.0;
    m.roughness = 1.0 - glossiness;
    m.f0_dielectric = sg_specular;
    m.specular_weight = 1.0;
#else
    m.metallic = u_metallic_factor;
    m.roughness = u_roughness_factor;
#ifdef HAS_METALLIC_ROUGHNESS_MAP
#ifndef METALLIC_ROUGHNESS_IN_ALPHA
    vec4 mr = SAMPLE_SHARED_DETAIL(u_metallic_roughness_map, u_metallic_roughness_uv, u_metallic_roughness_transform, u_metallic_roughness_anisotropy);
#endif
    m.metallic *= mr.b;
    m.roughness *= mr.g;
#endif
    vec3 specular_color = u_specular_color_factor;
#ifdef HAS_SPECULAR_COLOR_MAP
    specular_color *= sample_detail_map(u_specular_color_map, u_specular_color_uv, u_specular_color_transform, u_specular_color_anisotropy).rgb;
#endif
    m.f0_dielectric = ior_to_f0(u_ior) * specular_color;
    m.specular_weight = u_specular_factor;
#ifdef HAS_SPECULAR_MAP
    m.specular_weight *= sample_map(u_specular_map, u_specular_uv, u_specular_transform).a;
#endif
#endif
    m.f0_dielectric = min(m.f0_dielectric, vec3(1.0));
    m.metallic = clamp(m.metallic, 0.0, 1.0);
    m.roughness = clamp(m.roughness, 0.0, 1.0);
    m.clearcoat = 0.0;
    m.clearcoat_roughness = 0.0;
    m.clearcoat_f0 = ior_to_f0(u_ior);
#ifdef MATERIAL_CLEARCOAT
    m.clearcoat = u_clearcoat_factor;
    m.clearcoat_roughness = u_clearcoat_roughness_factor;
#ifdef HAS_CLEARCOAT_MAP
    m.clearcoat *= sample_map(u_clearcoat_map, u_clearcoat_uv, u_clearcoat_transform).r;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_MAP
    m.clearcoat_roughness *= sample_map(u_clearcoat_roughness_map, u_clearcoat_roughness_uv, u_clearcoat_roughness_transform).g;
#endif
    m.clearcoat = clamp(m.clearcoat, 0.0, 1.0);
    m.clearcoat_roughness = clamp(m.clearcoat_roughness, 0.0, 1.0);
#endif
    m.sheen_color = vec3(0.0);
    m.sheen_roughness = 0.0;
#ifdef MATERIAL_SHEEN
    m.sheen_color = u_sheen_color_factor;
    m.sheen_roughness = u_sheen_roughness_factor;
#ifdef HAS_SHEEN_COLOR_MAP
    m.sheen_color *= sample_detail_map(u_sheen_color_map, u_sheen_color_uv, u_sheen_color_transform, u_sheen_color_anisotropy).rgb;
#endif
#ifdef HAS_SHEEN_ROUGHNESS_MAP
    m.sheen_roughness *= sample_map(u_sheen_roughness_map, u_sheen_roughness_uv, u_sheen_roughness_transform).a;
#endif
    m.sheen_color = max(m.sheen_color, vec3(0.0));
    m.sheen_roughness = clamp(m.sheen_roughness, 0.0, 1.0);
#endif
    m.anisotropy_strength = 0.0;
    m.anisotropy_direction = vec2(1.0, 0.0);
    m.anisotropic_t = vec3(1.0, 0.0, 0.0);
    m.anisotropic_b = vec3(0.0, 1.0, 0.0);
#ifdef MATERIAL_ANISOTROPY
    // The direction in the geometric tangent frame, the bitangent from the geometric normal
    // (as the Khronos viewer; fresnel::evaluate).
    vec2 an_dir = vec2(1.0, 0.0);
    float an_strength = u_anisotropy_strength;
#ifdef HAS_ANISOTROPY_MAP
    vec3 an = sample_map(u_anisotropy_map, u_anisotropy_uv, u_anisotropy_transform).rgb;
    an_dir = an.xy * 2.0 - 1.0;
    an_strength *= an.z;
#endif
    float an_c = cos(u_anisotropy_rotation), an_s = sin(u_anisotropy_rotation);
    an_dir = vec2(an_c * an_dir.x - an_s * an_dir.y, an_s * an_dir.x + an_c * an_dir.y);
    float an_len = length(an_dir);
    an_dir = an_len > 0.0 ? an_dir / an_len : vec2(1.0, 0.0);
    m.anisotropy_strength = clamp(an_strength, 0.0, 1.0);
    m.anisotropy_direction = an_dir;
    m.anisotropic_t = an_dir.x * t + an_dir.y * b;
    m.anisotropic_b = cross(ng, m.anisotropic_t);
#endif
    m.iridescence = 0.0;
    m.iridescence_ior = 1.3;
    m.iridescence_thickness = 0.0;
#ifdef MATERIAL_IRIDESCENCE
    m.iridescence = u_iridescence_factor;
#ifdef HAS_IRIDESCENCE_MAP
    m.iridescence *= sample_map(u_iridescence_map, u_iridescence_uv, u_iridescence_transform).r;
#endif
    m.iridescence = clamp(m.iridescence, 0.0, 1.0);
    m.iridescence_ior = u_iridescence_ior;
    m.iridescence_thickness = u_iridescence_thickness_maximum;
#ifdef HAS_IRIDESCENCE_THICKNESS_MAP
    // mix(minimum, maximum, G), exactly the maximum at G = 1 (the white stand-in).
    float film_g = sample_map(u_iridescence_thickness_map, u_iridescence_thickness_uv, u_iridescence_thickness_transform).g;
    m.iridescence_thickness = u_iridescence_thickness_minimum * (1.0 - film_g) + u_iridescence_thickness_maximum * film_g;
#endif
#endif
    m.diffuse_transmission = 0.0;
    m.diffuse_transmission_color = vec3(1.0);
#ifdef MATERIAL_DIFFUSE_TRANSMISSION
    m.diffuse_transmission = u_diffuse_transmission_factor;
#ifdef HAS_DIFFUSE_TRANSMISSION_MAP
    m.diffuse_transmission *= sample_map(u_diffuse_transmission_map, u_diffuse_transmission_uv, u_diffuse_transmission_transform).a;
#endif
    m.diffuse_transmission = clamp(m.diffuse_transmission, 0.0, 1.0);
    m.diffuse_transmission_color = u_diffuse_transmission_color_factor;
#ifdef HAS_DIFFUSE_TRANSMISSION_COLOR_MAP
    m.diffuse_transmission_color *= sample_map(u_diffuse_transmission_color_map, u_diffuse_transmission_color_uv,
                                               u_diffuse_transmission_color_transform).rgb;  // sRGB, decoded by the sampler
#endif
    m.diffuse_transmission_color = max(m.diffuse_transmission_color, vec3(0.0));
#endif
    m.diffuse_roughness = 0.0;
    m.diffuse_roughness = u_diffuse_roughness_factor;  // KHR_materials_diffuse_roughness (0 without)
#ifdef HAS_DIFFUSE_ROUGHNESS_MAP
    m.diffuse_roughness *= sample_map(u_diffuse_roughness_map, u_diffuse_roughness_uv, u_diffuse_roughness_transform).r;
#endif
    m.diffuse_roughness = clamp(m.diffuse_roughness, 0.0, 1.0);
    m.occlusion = 1.0;
#if defined(OCCLUSION_IN_METALLIC_ROUGHNESS)
    // The R channel of the metallic-roughness texture (glTF's ORM packing, or the renderer's
    // packing of the two images): the same texels through the same probes, one lookup fewer
    // (with METALLIC_ROUGHNESS_IN_ALPHA, the emissive texture's alpha: mr above).
    m.occlusion = 1.0 + u_occlusion_strength * (mr.r - 1.0);
#elif defined(HAS_OCCLUSION_MAP)
    m.occlusion = 1.0 + u_occlusion_strength * (SAMPLE_SHARED_DETAIL(u_occlusion_map, u_occlusion_uv, u_occlusion_transform, u_occlusion_anisotropy).r - 1.0);
#endif
    m.emissive = u_emissive_factor * u_emissive_strength;
#if defined(METALLIC_ROUGHNESS_IN_ALPHA) && defined(OCCLUSION_IN_METALLIC_ROUGHNESS)
    m.emissive *= emissive_texel.rgb;  // read with the occlusion
#elif defined(HAS_EMISSIVE_MAP)
    m.emissive *= sample_map(u_emissive_map, u_emissive_uv, u_emissive_transform).rgb;
#endif
    m.discard_fragment = false;
#ifdef ALPHA_MASK
    m.discard_fragment = m.base_color.a < u_alpha_cutoff;
    m.base_color.a = 1.0;
#endif
#if !defined(ALPHA_BLEND) && !defined(ALPHA_MASK)
    m.base_color.a = 1.0;
#endif
    m.normal = ng;
#ifdef HAS_NORMAL_MAP
#ifndef METALLIC_ROUGHNESS_IN_ALPHA
    vec4 normal_texel = SAMPLE_SHARED_DETAIL(u_normal_map, u_normal_uv, u_normal_transform, u_normal_anisotropy);
#endif
    vec3 tn = normal_texel.rgb * 2.0 - 1.0;
    tn.xy *= u_normal_scale;
    m.normal = normalize(mat3(t, b, ng) * tn);
#endif
    m.clearcoat_normal = ng;
#ifdef HAS_CLEARCOAT_NORMAL_MAP
    vec3 tc = sample_detail_map(u_clearcoat_normal_map, u_clearcoat_normal_uv, u_clearcoat_normal_transform, u_clearcoat_normal_anisotropy).rgb * 2.0 - 1.0;
    tc.xy *= u_clearcoat_normal_scale;
    m.clearcoat_normal = normalize(mat3(t, b, ng) * tc);
#endif
    return m;
}

// The thin film at the view (KHR_materials_iridescence; no film without MATERIAL_IRIDESCENCE).
IridescenceFresnel material_film(MaterialInputs m, vec3 v) {
#ifdef MATERIAL_IRIDESCENCE
    if (m.iridescence > 0.0)
        return iridescence_at(m.iridescence, m.iridescence_ior, m.iridescence_thickness, clamped_dot(m.normal, v),
                              m.f0_dielectric, m.base_color.rgb);
#endif
    return no_film();
}

// One punctual light on the material, with KHR_materials_clearcoat layering: the twin of
// fresnel::shade_light (evaluate.h). comp_*: energy compensation of the specular lobes.
vec3 shade_light(MaterialInputs m, vec3 v, vec3 l, vec3 radiance, vec3 comp_dielectric, vec3 comp_metal) {
    float n_dot_l = clamped_dot(m.normal, l);
    // KHR_materials_diffuse_transmission: a light behind the surface lights its transmitted lobe.
    float n_dot_minus_l = m.diffuse_transmission > 0.0 ? clamped_dot(-m.normal, l) : 0.0;
    vec3 lit = vec3(0.0);
    if (n_dot_l > 0.0 || n_dot_minus_l > 0.0) {
        BrdfTerms t = brdf_terms_film(m.base_color.rgb, m.metallic, m.roughness, m.f0_dielectric, m.specular_weight,
                                      m.normal, v, l, material_film(m, v));
        if (m.diffuse_roughness > 0.0)  // KHR_materials_diffuse_roughness: the EON lobe
            t.diffuse *= eon_factor(m.base_color.rgb, m.diffuse_roughness, n_dot_l, clamped_dot(m.normal, v), dot(l, v));
#ifdef MATERIAL_ANISOTROPY
        if (m.anisotropy_strength > 0.0)
            apply_anisotropy(t, m.metallic, m.roughness, m.normal, v, l, m.anisotropic_t, m.anisotropic_b, m.anisotropy_strength);
#endif
        vec3 specular = t.specular_dielectric * comp_dielectric + t.specular_metal * comp_metal;
        vec3 base = t.diffuse + specular;
        vec3 sheen = vec3(0.0);
        float scaling = 1.0;
#ifdef MATERIAL_SHEEN
        // The Charlie lobe over the base, which keeps 1 - max(c) E (fresnel::shade_light).
        if (m.sheen_color != vec3(0.0)) {
            float n_dot_v = clamped_dot(m.normal, v);
            float n_dot_h = clamped_dot(m.normal, normalize(l + v));
            float c = max3(m.sheen_color);
            scaling = min(1.0 - c * sheen_albedo(n_dot_v, m.sheen_roughness), 1.0 - c * sheen_albedo(n_dot_l, m.sheen_roughness));
            if (n_dot_l > 0.0) sheen = sheen_specular(m.sheen_color, m.sheen_roughness, n_dot_l, n_dot_v, n_dot_h);
        }
#endif
        if (m.diffuse_transmission > 0.0) {
            // The diffuse lobe times its cosine, the reflected and the transmitted lobe mixed; the
            // transmitted one takes the diffuse's weight (w lambert(c) = lambert(w c)).
            vec3 diffuse = diffuse_transmission_mix(n_dot_l * t.diffuse, n_dot_minus_l, m.diffuse_transmission,
                                                    t.diffuse_weight * m.diffuse_transmission_color);
            vec3 specular_cos = n_dot_l > 0.0 ? n_dot_l * (sheen + specular * scaling) : vec3(0.0);
            lit = radiance * (specular_cos + diffuse * scaling);
        } else {
            lit = radiance * n_dot_l * (sheen + base * scaling);
        }
    }
#ifdef MATERIAL_CLEARCOAT
    // mix(base, coat, clearcoat * Fc), Fc the Schlick Fresnel of the coat at its normal
    // and the view (the extension's fresnel_coat; brdf::clearcoat_mix).
    float cc_mix = m.clearcoat * f_schlick(m.clearcoat_f0, 1.0, clamped_dot(m.clearcoat_normal, v));
    vec3 coat = radiance * clearcoat_specular(m.clearcoat_normal, v, l, alpha_from_roughness(m.clearcoat_roughness));
    lit = mix(lit, coat, cc_mix);
#endif
    return lit;
}
