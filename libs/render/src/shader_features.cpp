#include "details/shader_features.h"

#include <algorithm>
#include <bit>

namespace fresnel {

namespace {
using namespace feature;
constexpr FeatureInfo kFeatures[] = {
    {HasNormal, "HAS_NORMAL"},
    {HasTangent, "HAS_TANGENT"},
    {HasUv0, "HAS_UV0"},
    {HasUv1, "HAS_UV1"},
    {HasColor, "HAS_COLOR"},
    {Unlit, "UNLIT"},
    {SpecularGlossiness, "SPECULAR_GLOSSINESS"},
    {Clearcoat, "MATERIAL_CLEARCOAT"},
    {AlphaMask, "ALPHA_MASK"},
    {AlphaBlend, "ALPHA_BLEND"},
    {DebugView, "DEBUG_VIEW"},
    {UseIbl, "USE_IBL"},
    {BaseColorMap, "HAS_BASE_COLOR_MAP"},
    {MetallicRoughnessMap, "HAS_METALLIC_ROUGHNESS_MAP"},
    {NormalMap, "HAS_NORMAL_MAP"},
    {OcclusionMap, "HAS_OCCLUSION_MAP"},
    {EmissiveMap, "HAS_EMISSIVE_MAP"},
    {SpecularMap, "HAS_SPECULAR_MAP"},
    {SpecularColorMap, "HAS_SPECULAR_COLOR_MAP"},
    {SpecularGlossinessMap, "HAS_SPECULAR_GLOSSINESS_MAP"},
    {ClearcoatMap, "HAS_CLEARCOAT_MAP"},
    {ClearcoatRoughnessMap, "HAS_CLEARCOAT_ROUGHNESS_MAP"},
    {ClearcoatNormalMap, "HAS_CLEARCOAT_NORMAL_MAP"},
    {SheenColorMap, "HAS_SHEEN_COLOR_MAP"},
    {SheenRoughnessMap, "HAS_SHEEN_ROUGHNESS_MAP"},
    {Skinned, "SKINNED"},
    {MorphTargets, "MORPH_TARGETS"},
    {Sheen, "MATERIAL_SHEEN"},
    {TransmissionMap, "HAS_TRANSMISSION_MAP"},
    {ThicknessMap, "HAS_THICKNESS_MAP"},
    {Transmission, "MATERIAL_TRANSMISSION"},
    {Anisotropy, "MATERIAL_ANISOTROPY"},
    {AnisotropyMap, "HAS_ANISOTROPY_MAP"},
    {Iridescence, "MATERIAL_IRIDESCENCE"},
    {IridescenceMap, "HAS_IRIDESCENCE_MAP"},
    {IridescenceThicknessMap, "HAS_IRIDESCENCE_THICKNESS_MAP"},
    {DiffuseTransmission, "MATERIAL_DIFFUSE_TRANSMISSION"},
    {DiffuseTransmissionMap, "HAS_DIFFUSE_TRANSMISSION_MAP"},
    {DiffuseTransmissionColorMap, "HAS_DIFFUSE_TRANSMISSION_COLOR_MAP"},
    {OcclusionInMetallicRoughness, "OCCLUSION_IN_METALLIC_ROUGHNESS"},
    {DetailSharedFootprint, "DETAIL_SHARED_FOOTPRINT"},
    {MetallicRoughnessInAlpha, "METALLIC_ROUGHNESS_IN_ALPHA"},
    {DiffuseRoughnessMap, "HAS_DIFFUSE_ROUGHNESS_MAP"},
    {Instanced, "INSTANCED"},
};
constexpr bool table_is_kall_in_bit_order() {
    FeatureMask seen = 0;
    for (const FeatureInfo& f : kFeatures) {
        if ((f.bit & (f.bit - 1)) != 0 || f.bit <= seen) return false;  // one bit each, ascending
        seen |= f.bit;
    }
    return seen == kAll;
}
static_assert(table_is_kall_in_bit_order(), "kFeatures lists the bits of kAll, one each, in bit order");

// The maps DetailSharedFootprint lets share one footprint.
constexpr FeatureMask kSharedFootprintMaps = BaseColorMap | MetallicRoughnessMap | OcclusionMap | NormalMap;

// The maps a draw with these attributes and this material model may bind.
FeatureMask allowed_maps(FeatureMask m) {
    if (!(m & HasUv0)) return 0;
    if ((m & Unlit) && !(m & DebugView)) return BaseColorMap;
    FeatureMask maps = BaseColorMap | OcclusionMap | EmissiveMap;
    if (m & SpecularGlossiness) maps |= SpecularGlossinessMap;
    else maps |= MetallicRoughnessMap | SpecularMap | SpecularColorMap | DiffuseRoughnessMap;
    if (m & HasTangent) maps |= NormalMap;
    if (m & Clearcoat) {
        maps |= ClearcoatMap | ClearcoatRoughnessMap;
        if (m & HasTangent) maps |= ClearcoatNormalMap;
    }
    if (m & Transmission) maps |= TransmissionMap | ThicknessMap;
    if (m & Sheen) maps |= SheenColorMap | SheenRoughnessMap;
    if (m & Anisotropy) maps |= AnisotropyMap;
    if (m & Iridescence) maps |= IridescenceMap | IridescenceThicknessMap;
    if (m & DiffuseTransmission) maps |= DiffuseTransmissionMap | DiffuseTransmissionColorMap;
    return maps;
}
}  // namespace

std::span<const FeatureInfo> feature_table() { return kFeatures; }

std::vector<std::string> frame_defines(FrameVariant frame) {
    std::vector<std::string> out{"FRAME_TONEMAP " + std::to_string(frame.tone_mapper),
                                 "FRAME_ENCODING " + std::to_string(frame.encoding)};
    if (!frame.lights) out.emplace_back("FRAME_NO_LIGHTS");
    else if (frame.shadows > 0) out.push_back("FRAME_SHADOWS " + std::to_string(frame.shadows));
    if (frame.lights && frame.area_lights) out.emplace_back("FRAME_AREA_LIGHTS");
    if (frame.ssao) out.emplace_back("FRAME_SSAO");
    return out;
}

std::vector<std::string> feature_defines(FeatureMask mask) {
    std::vector<std::string> out;
    for (const auto& f : kFeatures)
        if (mask & f.bit) out.emplace_back(f.define);
    out.push_back("MAX_LIGHTS " + std::to_string(kMaxShaderLights));
    if (mask & Skinned) out.push_back("JOINTS_PER_ROW " + std::to_string(kJointsPerRow));
    if (mask & MorphTargets) out.push_back("MAX_MORPH_TARGETS " + std::to_string(kMaxShaderMorphTargets));
    return out;
}

FeatureMask canonical_features(FeatureMask m) {
    m &= kAll;
    if (!(m & HasNormal)) m &= ~HasTangent;
    if (m & AlphaMask) m &= ~AlphaBlend;
    if ((m & Unlit) && !(m & DebugView))
        m &= ~(HasNormal | HasTangent | SpecularGlossiness | Clearcoat | Sheen | UseIbl | Transmission | Anisotropy |
               Iridescence | DiffuseTransmission);
    if (m & SpecularGlossiness) m &= ~Transmission;
    if (!(m & HasTangent)) m &= ~Anisotropy;
    const FeatureMask allowed = allowed_maps(m);
    m = (m & ~kMaps) | (m & allowed);
    if (!(m & SpecularGlossiness) && (m & (SpecularMap | SpecularColorMap))) m |= SpecularMap | SpecularColorMap;
    if (m & (ClearcoatMap | ClearcoatRoughnessMap)) m |= ClearcoatMap | ClearcoatRoughnessMap;
    if (m & Transmission) m |= allowed & (TransmissionMap | ThicknessMap);
    if (m & (SheenColorMap | SheenRoughnessMap)) m |= SheenColorMap | SheenRoughnessMap;
    if (m & (IridescenceMap | IridescenceThicknessMap)) m |= IridescenceMap | IridescenceThicknessMap;
    if (m & (DiffuseTransmissionMap | DiffuseTransmissionColorMap))
        m |= DiffuseTransmissionMap | DiffuseTransmissionColorMap;
    if (m & OcclusionInMetallicRoughness) {
        if ((m & MetallicRoughnessMap) && !(m & SpecularGlossiness)) m &= ~OcclusionMap;
        else m &= ~OcclusionInMetallicRoughness;
    }
    if (m & DebugView)
        m |= allowed & ~(NormalMap | ClearcoatNormalMap | AnisotropyMap |
                         (m & OcclusionInMetallicRoughness ? OcclusionMap : FeatureMask(0)));
    if (std::popcount(m & kSharedFootprintMaps) < 2) m &= ~DetailSharedFootprint;
    if (m & MetallicRoughnessInAlpha) {
        const FeatureMask needs = MetallicRoughnessMap | BaseColorMap | NormalMap |
                                  (m & OcclusionInMetallicRoughness ? EmissiveMap : FeatureMask(0));
        if ((m & needs) != needs || (m & (SpecularGlossiness | AlphaMask | AlphaBlend | DebugView)))
            m &= ~MetallicRoughnessInAlpha;
    }
    if (m & (Skinned | MorphTargets | Transmission)) m &= ~Instanced;
    return m;
}

bool valid_features(FeatureMask mask) { return (mask & ~kAll) == 0 && canonical_features(mask) == mask; }

std::vector<FeatureMask> all_feature_sets() {
    // Bits 23..38 (the sheen, transmission, anisotropy, iridescence and diffuse transmission maps and model bits,
    // skinning, morphing) come in groups that no rule on bits 0..22 looks at, except that unlit,
    // specular-glossiness and missing tangents drop some and the debug view turns the maps on:
    // so every valid mask is a valid mask of bits 0..22 plus one choice per group (the diffuse
    // roughness map, bit 42, is one more), kept when canonical. 2^23 masks (eight times: bits
    // 39, 40 and 41, below) instead of 2^43.
    std::vector<FeatureMask> out;
    constexpr FeatureMask kLow = (FeatureMask(1) << 23) - 1;
    // Instancing (bit 43) excludes skinning and morphing: one more choice of that group.
    const FeatureMask animation[] = {0, Skinned, MorphTargets, Skinned | MorphTargets, Instanced};
    const FeatureMask sheen[] = {0, Sheen, Sheen | SheenColorMap | SheenRoughnessMap};
    const FeatureMask transmission[] = {0, Transmission, Transmission | TransmissionMap | ThicknessMap};
    const FeatureMask anisotropy[] = {0, Anisotropy, Anisotropy | AnisotropyMap};
    const FeatureMask iridescence[] = {0, Iridescence, Iridescence | IridescenceMap | IridescenceThicknessMap};
    const FeatureMask diffuse_transmission[] = {0, DiffuseTransmission,
                                                DiffuseTransmission | DiffuseTransmissionMap | DiffuseTransmissionColorMap};
    const FeatureMask diffuse_roughness[] = {0, DiffuseRoughnessMap};
    // The debug view turns the diffuse roughness map on (bit 42, outside the low bits): the low
    // bits' own rules are checked without it, the whole mask's below.
    const auto canonical_low = [](FeatureMask m) { return canonical_features(m) & ~DiffuseRoughnessMap; };
    for (FeatureMask low = 0; low <= kLow; ++low) {
        if (canonical_low(low) != low) continue;
        // The occlusion in the metallic-roughness texture (bit 39) replaces the occlusion map:
        // the low bits of a valid mask with it are canonical alone, or with the occlusion map
        // added (the debug view adds it where allowed). Both ways can give one mask: deduplicated.
        // The shared detail footprint (bit 40) needs two of four low map bits: the same masks
        // with it, where canonical; so is the metallic-roughness in alpha channels (bit 41).
        const FeatureMask occlusion_in_mr = (low & ~OcclusionMap) | OcclusionInMetallicRoughness;
        for (FeatureMask m : {low, occlusion_in_mr, low | DetailSharedFootprint, occlusion_in_mr | DetailSharedFootprint,
                              low | MetallicRoughnessInAlpha, occlusion_in_mr | MetallicRoughnessInAlpha,
                              low | DetailSharedFootprint | MetallicRoughnessInAlpha,
                              occlusion_in_mr | DetailSharedFootprint | MetallicRoughnessInAlpha}) {
            if (m != low && canonical_low(m) != m) continue;
            for (FeatureMask a : animation)
                for (FeatureMask s : sheen)
                    for (FeatureMask t : transmission)
                        for (FeatureMask an : anisotropy)
                            for (FeatureMask i : iridescence)
                                for (FeatureMask dt : diffuse_transmission)
                                    for (FeatureMask dr : diffuse_roughness) {
                                        const FeatureMask x = m | a | s | t | an | i | dt | dr;
                                        if (canonical_features(x) == x) out.push_back(x);
                                    }
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

namespace {
constexpr FeatureInfo kLegacyFeatures[legacy_feature::kCount] = {
    {legacy_feature::Ogl1Vertex, "LEGACY_OGL1_VERTEX"}, {legacy_feature::Ogl1Pixel, "LEGACY_OGL1_PIXEL"},
    {legacy_feature::BlinnPhong, "LEGACY_BLINN_PHONG"}, {legacy_feature::HasNormal, "HAS_NORMAL"},
    {legacy_feature::HasUv0, "HAS_UV0"},                {legacy_feature::DiffuseMap, "HAS_DIFFUSE_MAP"},
    {legacy_feature::UseIbl, "USE_IBL"},                {legacy_feature::Fogged, "LEGACY_FOG"},
};
}  // namespace

std::vector<std::string> legacy_feature_defines(FeatureMask mask) {
    std::vector<std::string> out;
    for (const auto& f : kLegacyFeatures)
        if (mask & f.bit) out.emplace_back(f.define);
    out.push_back("MAX_LIGHTS " + std::to_string(kMaxShaderLights));
    return out;
}

FeatureMask canonical_legacy_features(FeatureMask m) {
    namespace lf = legacy_feature;
    m &= lf::kAll;
    if (m & lf::Ogl1Vertex) m &= ~FeatureMask(lf::Ogl1Pixel | lf::BlinnPhong);
    else if (m & lf::Ogl1Pixel) m &= ~FeatureMask(lf::BlinnPhong);
    if (!(m & lf::HasUv0)) m &= ~FeatureMask(lf::DiffuseMap);
    if (!(m & lf::BlinnPhong)) m &= ~FeatureMask(lf::UseIbl);
    else m &= ~FeatureMask(lf::Fogged);
    return m;
}

bool valid_legacy_features(FeatureMask mask) {
    return (mask & legacy_feature::kModels) != 0 && canonical_legacy_features(mask) == mask;
}

std::vector<FeatureMask> all_legacy_feature_sets() {
    std::vector<FeatureMask> out;
    for (FeatureMask m = 0; m <= legacy_feature::kAll; ++m)
        if (valid_legacy_features(m)) out.push_back(m);
    return out;
}

}  // namespace fresnel
