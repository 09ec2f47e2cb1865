#pragma once
// The feature bits that select a variant of the mesh shaders (pbr.vert / pbr.frag), the
// rules that say which combinations exist, and the enumeration of every variant the
// renderer can ask for. One source of truth: Renderer::draw_primitive describes a draw
// by the raw bits of its primitive, material and settings and keeps canonical_features()
// of them; tests/gpu/es300_test.cpp compiles every mask all_feature_sets() lists.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fresnel/render/limits.h"

namespace fresnel {

using FeatureMask = std::uint64_t;  // bits past 31: write FeatureMask(1) << N

namespace feature {
enum : FeatureMask {
    // Vertex attributes present.
    HasNormal = 1u << 0,
    HasTangent = 1u << 1,
    HasUv0 = 1u << 2,
    HasUv1 = 1u << 3,
    HasColor = 1u << 4,
    // Material model and render settings.
    Unlit = 1u << 5,               // KHR_materials_unlit
    SpecularGlossiness = 1u << 6,  // KHR_materials_pbrSpecularGlossiness
    Clearcoat = 1u << 7,           // KHR_materials_clearcoat
    AlphaMask = 1u << 8,
    AlphaBlend = 1u << 9,
    DebugView = 1u << 10,  // RenderSettings::debug != None
    UseIbl = 1u << 11,     // an environment lights the scene
    // Texture maps bound, in fresnel::MaterialMap order (texture units 0..12).
    BaseColorMap = 1u << 12,
    MetallicRoughnessMap = 1u << 13,
    NormalMap = 1u << 14,
    OcclusionMap = 1u << 15,
    EmissiveMap = 1u << 16,
    SpecularMap = 1u << 17,             // KHR_materials_specular specularTexture
    SpecularColorMap = 1u << 18,        // KHR_materials_specular specularColorTexture
    SpecularGlossinessMap = 1u << 19,   // KHR_materials_pbrSpecularGlossiness specularGlossinessTexture
    ClearcoatMap = 1u << 20,
    ClearcoatRoughnessMap = 1u << 21,
    ClearcoatNormalMap = 1u << 22,
    SheenColorMap = 1u << 23,           // KHR_materials_sheen sheenColorTexture
    SheenRoughnessMap = 1u << 24,       // KHR_materials_sheen sheenRoughnessTexture
    // Animation on the GPU (vertex shader only; RenderSettings::gpu_animation).
    Skinned = 1u << 25,       // JOINTS_0 / WEIGHTS_0 by the joint matrices of u_joint_matrices
    MorphTargets = 1u << 26,  // the morph targets' displacements of u_morph_targets by u_morph_weights
    Sheen = 1u << 27,         // KHR_materials_sheen (Material::has_sheen)
    // KHR_materials_transmission (+ _volume, _dispersion): maps 13 and 14 (MaterialMap::Transmission,
    // ::Thickness) and the material model bit.
    TransmissionMap = 1u << 28,
    ThicknessMap = 1u << 29,
    Transmission = 1u << 30,  // MATERIAL_TRANSMISSION: refraction of the opaque scene (transmission.h)
    // KHR_materials_anisotropy (Material::has_anisotropy; needs tangents) and its map 15
    // (MaterialMap::Anisotropy).
    Anisotropy = FeatureMask(1) << 31,
    AnisotropyMap = FeatureMask(1) << 32,
    // KHR_materials_iridescence: the model bit and maps 16 and 17 (MaterialMap::Iridescence,
    // ::IridescenceThickness).
    Iridescence = FeatureMask(1) << 33,              // MATERIAL_IRIDESCENCE: the thin film (Material::has_iridescence)
    IridescenceMap = FeatureMask(1) << 34,           // iridescenceTexture
    IridescenceThicknessMap = FeatureMask(1) << 35,  // iridescenceThicknessTexture
    // KHR_materials_diffuse_transmission: the model bit and maps 18 and 19
    // (MaterialMap::DiffuseTransmission, ::DiffuseTransmissionColor).
    DiffuseTransmission = FeatureMask(1) << 36,          // MATERIAL_DIFFUSE_TRANSMISSION (Material::has_diffuse_transmission)
    DiffuseTransmissionMap = FeatureMask(1) << 37,       // diffuseTransmissionTexture
    DiffuseTransmissionColorMap = FeatureMask(1) << 38,  // diffuseTransmissionColorTexture
    // The occlusion is the R channel of the metallic-roughness texture (glTF's ORM packing, or
    // the renderer's copy of the occlusion's R into the metallic-roughness image where the two
    // maps share UV set, transform, sampler and size: Renderer's occlusion_packs): read through
    // the same probes, with no occlusion map bound. Replaces OcclusionMap.
    OcclusionInMetallicRoughness = FeatureMask(1) << 39,
    // The base colour, metallic-roughness, occlusion and normal maps of the variant (at least
    // two of them) have the same UV set, transform, level-0 size and probe limit, so one
    // anisotropic footprint (derivatives, level of detail, probe count and positions) serves
    // them all: the same probes as one footprint each, computed once (DETAIL_SHARED_FOOTPRINT,
    // material_inputs.glsl; the renderer's shares_detail_footprint).
    DetailSharedFootprint = FeatureMask(1) << 40,
    // The metallic-roughness texture's B (metallic) and G (roughness) are the alpha channels of
    // the base colour and normal textures, and with OcclusionInMetallicRoughness its R (the
    // occlusion) is the emissive texture's alpha, filtered as the emissive is (without
    // anisotropy, as the other low-frequency maps): the renderer's copies of those channels
    // into alphas that an opaque material does not read (Renderer's alpha_packs), where the
    // maps share UV set, transform, sampler and size. One texture fewer to probe per
    // fragment; no metallic-roughness map bound.
    // Needs the metallic-roughness, base colour and normal maps, an opaque metallic-roughness
    // material (no alpha mode, not specular-glossiness), no debug view, and with the occlusion
    // the emissive map (METALLIC_ROUGHNESS_IN_ALPHA, material_inputs.glsl).
    MetallicRoughnessInAlpha = FeatureMask(1) << 41,
    // KHR_materials_diffuse_roughness's map 20 (MaterialMap::DiffuseRoughness). The lobe itself
    // has no model bit: every lit variant shades it where the factor (a uniform) is positive.
    DiffuseRoughnessMap = FeatureMask(1) << 42,
    // Many placements of one primitive in one draw (INSTANCED: pbr.vert reads each instance's
    // model and normal matrices from per-instance attributes; the renderer's instanced batches,
    // RenderSettings::instancing). Not with skinning, morphing or transmission (which reads the
    // model's scale from u_model): those draw one placement at a time.
    Instanced = FeatureMask(1) << 43,
};
constexpr int kCount = 44;
constexpr int kFirstMap = 12;
constexpr int kMapCount = 21;
// Bit positions below kCount that no feature uses (none now).
constexpr FeatureMask kReserved = 0;
constexpr FeatureMask kAll = ((FeatureMask(1) << kCount) - 1) & ~kReserved;
// The bit position of each map, in fresnel::MaterialMap order: maps 0..12 are bits 12..24,
// the transmission maps (13, 14) bits 28 and 29, the anisotropy map (15) bit 32, the
// iridescence maps (16, 17) bits 34 and 35, the diffuse transmission maps (18, 19) bits 37 and
// 38, the diffuse roughness map (20) bit 42. A new map appends its position here.
constexpr int kMapBitPositions[kMapCount] = {12, 13, 14, 15, 16, 17, 18, 19, 20, 21,
                                             22, 23, 24, 28, 29, 32, 34, 35, 37, 38, 42};
// The bit of map `i` (fresnel::MaterialMap(i)).
constexpr FeatureMask map_bit(int i) { return FeatureMask(1) << kMapBitPositions[i]; }
constexpr FeatureMask all_map_bits() {
    FeatureMask m = 0;
    for (int i = 0; i < kMapCount; ++i) m |= map_bit(i);
    return m;
}
constexpr FeatureMask kMaps = all_map_bits();
}  // namespace feature

// Bound lights: the size of the shaders' light arrays (MAX_LIGHTS).
constexpr int kMaxShaderLights = kMaxFrameLights;
// GPU animation limits: a skin with more joints, or a primitive with more morph targets
// (or, morphed, more vertices), is posed on the CPU. pbr.vert reads joint matrices from a
// texture of kJointsPerRow joints a row (4 RGBA32F texels each: 1024 texels wide, 16 rows at
// the limit) and morph displacements from a 2D texture array of kMorphTextureWidth texels a
// row, one layer per target and attribute (3 x 64 = 192 of the 256 layers OpenGL ES 3.0
// guarantees); its weights are MAX_MORPH_TARGETS / 4 vec4 uniforms. 2048 is the texture size
// OpenGL ES 3.0 guarantees.
constexpr int kMaxShaderJoints = kMaxGpuSkinJoints;
constexpr int kMaxShaderMorphTargets = kMaxGpuMorphTargets;
constexpr int kJointsPerRow = 256;
constexpr int kMorphTextureWidth = 2048;
constexpr long long kMaxShaderMorphVertices = 2048LL * kMorphTextureWidth;
static_assert(kMaxShaderJoints % kJointsPerRow == 0 && kMaxShaderJoints / kJointsPerRow <= 2048);
static_assert(kMaxShaderMorphTargets % 4 == 0 && 3 * kMaxShaderMorphTargets <= 256);

struct FeatureInfo {
    FeatureMask bit;
    const char* define;  // the GLSL #define ("HAS_NORMAL", ...)
};
// Every feature bit in bit order (the bits of kAll; kReserved has none).
std::span<const FeatureInfo> feature_table();

// The #defines of a variant: one per set bit, in bit order, then "MAX_LIGHTS 16", and with
// Skinned "JOINTS_PER_ROW 256", with MorphTargets "MAX_MORPH_TARGETS 64".
std::vector<std::string> feature_defines(FeatureMask mask);

// The variant the renderer draws with when a draw's raw description is `mask` (the
// attributes the primitive has, the material's model, the maps it has, the settings).
// Each rule drops a bit that cannot change the picture or adds a map whose absence
// a 1x1 white texture stands in for exactly (x * 1.0 = x), so variants stay few:
//  - tangents without normals are ignored (glTF 2.0, meshes: "TANGENT ... ignored");
//  - every map needs UV0; normal and clearcoat-normal maps need tangents; anisotropy needs
//    tangents (its direction lies in the tangent frame; without them it is not shaded, as
//    normal maps are not), and its map the anisotropy;
//    the clearcoat maps need the clearcoat, the sheen maps the sheen; specular-glossiness reads its own map and
//    neither the metallic-roughness nor the two KHR_materials_specular maps, which
//    metallic-roughness reads instead of the specular-glossiness map;
//  - unlit without the debug view reads only the base colour (map): normals, tangents,
//    lit maps, specular-glossiness, clearcoat, sheen, anisotropy and the environment are dropped;
//  - KHR_materials_specular's two maps come together, as do the clearcoat and
//    clearcoat-roughness maps, as do the two sheen maps (the missing one is the white texture);
//  - the debug view samples every map but the normal maps and the anisotropy map (white where
//    absent; a white anisotropy texel is not the default direction (1, 0));
//  - the occlusion in the metallic-roughness texture needs that map (and metallic-roughness, not
//    specular-glossiness); it replaces the occlusion map, also under the debug view;
//  - alpha mask wins over blend (a material has one alpha mode);
//  - transmission is not shaded for unlit (without the debug view) or specular-glossiness
//    materials; with it, its two maps always come together (white stands in: factor * 1);
//  - the iridescence maps need the iridescence and come together (white stands in: factor * 1,
//    mix(minimum, maximum, 1) = maximum, the thickness without a map); unlit drops the film;
//  - the diffuse transmission maps need the diffuse transmission and come together (white stands
//    in: factor * 1, colour * 1); unlit drops it.
//  - the shared detail footprint needs two of the base colour, metallic-roughness, occlusion
//    and normal maps (after the rules above).
//  - the metallic-roughness in alpha channels needs the metallic-roughness, base colour and
//    normal maps (and the emissive map with the occlusion in the metallic-roughness texture),
//    and neither specular-glossiness, an alpha mode nor the debug view;
//  - instancing is dropped with skinning, morph targets or transmission.
// Normal maps and the anisotropy map are never stood in for: a flat normal texel is not
// exactly (0, 0, 1), a white anisotropy texel is direction (1, 1).
FeatureMask canonical_features(FeatureMask mask);

// A mask the renderer can produce: in range and canonical.
bool valid_features(FeatureMask mask);

// Every valid mask, ascending (tens of thousands; each stage source depends on fewer bits).
std::vector<FeatureMask> all_feature_sets();

// ---- The legacy shading models' variants (legacy.vert / legacy.frag) --------------------
// A separate, small set: the models of ShadingModel other than glTF share no variant with
// pbr.*, so their bits do not multiply the mesh shaders' tens of thousands of sets.
namespace legacy_feature {
enum : FeatureMask {
    Ogl1Vertex = 1u << 0,    // OpenGL 1 per vertex (Gouraud)
    Ogl1Pixel = 1u << 1,     // OpenGL 1 per fragment
    BlinnPhong = 1u << 2,    // normalized Blinn-Phong
    HasNormal = 1u << 3,
    HasUv0 = 1u << 4,
    DiffuseMap = 1u << 5,    // map_Kd (OpenGL 1: GL_MODULATE; Blinn-Phong: base colour, sRGB)
    UseIbl = 1u << 6,        // Blinn-Phong only: pre-convolved maps
    Fogged = 1u << 7,        // OpenGL 1 only: GL_FOG
};
constexpr int kCount = 8;
constexpr FeatureMask kAll = (FeatureMask(1) << kCount) - 1;
constexpr FeatureMask kModels = Ogl1Vertex | Ogl1Pixel | BlinnPhong;
}  // namespace legacy_feature

// The #defines of a legacy variant (LEGACY_OGL1_VERTEX, ..., then "MAX_LIGHTS 16").
std::vector<std::string> legacy_feature_defines(FeatureMask mask);
// The rules: exactly one model (none: nothing is drawn, so the mask is not valid); the
// diffuse map needs UV0; the environment belongs to Blinn-Phong and fog to OpenGL 1.
FeatureMask canonical_legacy_features(FeatureMask mask);
bool valid_legacy_features(FeatureMask mask);
// Every valid legacy mask, ascending (a few dozen).
std::vector<FeatureMask> all_legacy_feature_sets();

// ---- Frame variants ---------------------------------------------------------------------
// What a frame decides for every draw, compiled into the shaders that write it (pbr.frag,
// legacy.frag's Blinn-Phong, sky.frag): the tone mapper and encoding (FRAME_TONEMAP,
// FRAME_ENCODING: display_transform in tonemap.glsl) and, for pbr.frag, whether any punctual
// light shines (FRAME_NO_LIGHTS drops the light loop). A software rasteriser runs both sides
// of a branch on a uniform and a loop's body once even when it breaks at once, so a uniform
// switch or an empty light loop costs every pixel (DamagedHelmet at 1024^2 on llvmpipe with
// image-based light alone: ~20 % of the frame). A frame has one variant, so this adds one
// program per frame setting, not a factor on the feature sets.
struct FrameVariant {
    int tone_mapper = 0;  // int(fresnel::ToneMapper)
    int encoding = 0;     // int(fresnel::Encoding); -1: none (linear radiance, the transmission pass)
    bool lights = true;   // punctual lights are bound (false: FRAME_NO_LIGHTS)
    // int(fresnel::Shadows) with lights and a shadow atlas bound (FRAME_SHADOWS), 3 for soft
    // shadows with contact hardening (a light with a bulb radius), else 0
    int shadows = 0;
    bool area_lights = false;  // an area light shines (FRAME_AREA_LIGHTS: the LTC table is bound)
    bool ssao = false;         // screen-space occlusion is bound (FRAME_SSAO)
    // A small integer naming the variant (the shader caches' key).
    int key() const {
        return ((((tone_mapper * 4 + encoding + 1) * 2 + (lights ? 1 : 0)) * 4 + shadows) * 2 + (area_lights ? 1 : 0)) * 2 +
               (ssao ? 1 : 0);
    }
};
// "FRAME_TONEMAP n", "FRAME_ENCODING n", without lights "FRAME_NO_LIGHTS", with shadows
// "FRAME_SHADOWS n", with area lights "FRAME_AREA_LIGHTS", with screen-space occlusion "FRAME_SSAO".
std::vector<std::string> frame_defines(FrameVariant frame);

}  // namespace fresnel
