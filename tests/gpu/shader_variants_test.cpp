// Every shader variant the renderer can ask for compiles as GLSL ES 3.00 (and every 8th
// mesh variant and every other program as GLSL 3.30 core too), checked offline with glslang
// (Debian's glslang-dev, in process, one thread per core): the mesh shaders for every
// feature set of all_feature_sets() (shader_features.h, the same enumeration the renderer's
// rules come from) and the other programs (fullscreen.vert, post.frag, sky.frag,
// brdf_probe.frag, legacy_probe.frag). pbr.frag's sources are compiled with a frame variant
// each, as the renderer compiles them (tone mapper, encoding, with or without punctual
// lights: every one of them in turn; all of them on the richest feature set).
//
// A stage's source depends only on the feature #defines it mentions, so each stage
// is compiled once per distinct set of the bits it reads (the bits it never names
// cannot change its text after preprocessing); the test finds those bits by scanning
// the assembled source, so a shader that starts reading a new bit is covered at once.
// (The anisotropy group together with the sheen or transmission group, and the diffuse
// roughness map, are compiled on a few base sets only; EveryVariantCompilesAsEs300AndGl330 says why.)
//
// Three groups are sampled instead of enumerated: the KHR_materials_iridescence bits (the film
// and its two maps), the KHR_materials_diffuse_transmission bits (the model and its two
// maps), which together would multiply the fragment shader's ~20k sources by nine, and the
// occlusion read from the metallic-roughness texture (one #if choosing where the occlusion's
// value comes from), the shared detail footprint (one #if choosing where the footprint
// comes from, and the same sample calls) and the metallic-roughness in alpha channels (#ifs
// choosing which texel's channel is metallic, roughness and occlusion). Every
// source without them compiles; of those with them, every kFilmStride-th (64th, in mask order)
// and, on top, enough that each choice of the two groups meets every other bit the stage reads
// both set and clear (pairwise coverage, asserted). Their code is a few #ifdef blocks that add
// a function or a uniform and mix the result into values every variant has.
#include <gtest/gtest.h>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "fresnel/core/color.h"
#include "fresnel/material/brdf_model.h"
#include "details/shader_features.h"
#include "details/shader_library.h"

using namespace fresnel;

namespace {

struct Job {
    std::string file;
    FeatureMask mask = 0;
    bool mesh = false;  // a pbr.* stage: compiled with feature_defines(mask)
    GlslTarget target = GlslTarget::Gl33;
    std::vector<std::string> defines = {};  // the other programs' variants
};

bool is_vertex(const std::string& file) { return file.size() > 5 && file.substr(file.size() - 5) == ".vert"; }

// True when `name` occurs in `text` as a whole identifier.
bool mentions(const std::string& text, const std::string& name) {
    auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
        bool left = at == 0 || !ident(text[at - 1]);
        bool right = at + name.size() >= text.size() || !ident(text[at + name.size()]);
        if (left && right) return true;
    }
    return false;
}

// The feature bits a stage's assembled source names.
FeatureMask bits_read_by(const std::string& file) {
    const std::string src = assemble_shader(file, {}, GlslTarget::Gl33);
    FeatureMask m = 0;
    for (const auto& f : feature_table())
        if (mentions(src, f.define)) m |= f.bit;
    return m;
}

// Compiles one stage; returns "" or the info log.
std::string compile(const Job& job) {
    std::vector<std::string> defines = job.mesh ? feature_defines(job.mask) : job.defines;
    if (job.mesh) defines.insert(defines.end(), job.defines.begin(), job.defines.end());  // its frame variant
    const std::string src = assemble_shader(job.file, defines, job.target);
    glslang::TShader shader(is_vertex(job.file) ? EShLangVertex : EShLangFragment);
    const char* text = src.c_str();
    shader.setStrings(&text, 1);
    if (shader.parse(GetDefaultResources(), 100, false, EShMsgDefault)) return "";
    return shader.getInfoLog();
}

std::string describe(const Job& job) {
    std::string s = job.file + (job.target == GlslTarget::Es30 ? " (300 es)" : " (330 core)");
    if (job.mesh) {
        s += ":";
        for (const auto& d : feature_defines(job.mask)) s += " " + d;
    }  // then the frame variant, below
    for (const auto& d : job.defines) s += " " + d;
    return s;
}

// The sampled group (see the top) and the share of its sources compiled besides the
// pairwise cover.
constexpr FeatureMask kSampledGroup = feature::Iridescence | feature::IridescenceMap | feature::IridescenceThicknessMap |
                                   feature::DiffuseTransmission | feature::DiffuseTransmissionMap |
                                   feature::DiffuseTransmissionColorMap | feature::OcclusionInMetallicRoughness |
                                   feature::DetailSharedFootprint | feature::MetallicRoughnessInAlpha;
constexpr std::size_t kFilmStride = 64;
// The share of the mesh stages' sources compiled as GLSL 330 core too (all compile as 300 es).
constexpr std::size_t kDesktopStride = 8;

// The sources of one stage to compile, from its distinct masks: all without the film group,
// a stride of those with it, and a pairwise cover of the film's choices with every other bit
// in `read` (each choice with each bit set and clear, where such a source exists).
std::vector<FeatureMask> sources_to_compile(const std::set<FeatureMask>& distinct, FeatureMask read) {
    std::vector<FeatureMask> out, filmed;
    for (FeatureMask m : distinct) (m & kSampledGroup ? filmed : out).push_back(m);
    std::set<std::pair<FeatureMask, int>> need;  // (group choice, bit index * 2 + value)
    for (FeatureMask m : filmed)
        for (int b = 0; b < 64; ++b)
            if ((read & ~kSampledGroup) >> b & 1) need.insert({m & kSampledGroup, b * 2 + int(m >> b & 1)});
    auto take = [&](FeatureMask m) {
        out.push_back(m);
        for (int b = 0; b < 64; ++b) need.erase({m & kSampledGroup, b * 2 + int(m >> b & 1)});
    };
    std::vector<bool> taken(filmed.size(), false);
    for (std::size_t i = 0; i < filmed.size(); i += kFilmStride) taken[i] = true, take(filmed[i]);
    for (std::size_t i = 0; i < filmed.size() && !need.empty(); ++i) {
        if (taken[i]) continue;
        const FeatureMask m = filmed[i];
        bool useful = false;
        for (int b = 0; b < 64 && !useful; ++b) useful = need.count({m & kSampledGroup, b * 2 + int(m >> b & 1)}) > 0;
        if (useful) taken[i] = true, take(m);
    }
    EXPECT_TRUE(need.empty()) << need.size() << " (group choice, bit value) pairs not covered";
    return out;
}

struct GlslangProcess {
    GlslangProcess() { glslang::InitializeProcess(); }
    ~GlslangProcess() { glslang::FinalizeProcess(); }
};

}  // namespace

TEST(ShaderFeatures, RulesAreCanonicalAndEnumerated) {
    using namespace feature;
    const std::vector<FeatureMask> all = all_feature_sets();
    // Ascending and distinct, so a binary search finds a mask (millions of masks: no std::set).
    ASSERT_TRUE(std::adjacent_find(all.begin(), all.end(), std::greater_equal<FeatureMask>()) == all.end());
    const auto enumerated = [&](FeatureMask m) { return std::binary_search(all.begin(), all.end(), m); };
    // canonical_features is idempotent, and everything it returns is enumerated.
    std::uint64_t state = 0x9e3779b97f4a7c15ull;  // splitmix64: 4M raw masks spread over all bits
    for (int i = 0; i < (1 << 22); ++i) {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        const FeatureMask m = (z ^ (z >> 31)) & kAll;
        FeatureMask c = canonical_features(m);
        ASSERT_EQ(canonical_features(c), c) << std::hex << m;
        ASSERT_TRUE(enumerated(c)) << std::hex << m;
    }
    for (FeatureMask m : all) EXPECT_TRUE(valid_features(m));
    // The rules the renderer relies on.
    EXPECT_FALSE(valid_features(HasUv0 | HasNormal | NormalMap));  // normal maps need tangents
    EXPECT_FALSE(valid_features(HasNormal | BaseColorMap));        // maps need UV0
    EXPECT_FALSE(valid_features(HasUv0 | HasNormal | ClearcoatMap | ClearcoatRoughnessMap));  // need the clearcoat
    EXPECT_FALSE(valid_features(AlphaMask | AlphaBlend));
    EXPECT_FALSE(valid_features(HasUv0 | HasNormal | SpecularMap));  // the specular pair comes together
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | Unlit | UseIbl | MetallicRoughnessMap | BaseColorMap),
              HasUv0 | Unlit | BaseColorMap);
    // KHR_materials_anisotropy needs tangents; its map needs it and is never stood in for.
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | Anisotropy | AnisotropyMap), HasUv0 | HasNormal);
    EXPECT_TRUE(valid_features(HasUv0 | HasNormal | HasTangent | Anisotropy | AnisotropyMap));
    EXPECT_FALSE(valid_features(HasUv0 | HasNormal | HasTangent | AnisotropyMap));
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | HasTangent | Anisotropy | DebugView) & AnisotropyMap, 0u);
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | HasTangent | Anisotropy | Unlit), HasUv0 | Unlit);
    // KHR_materials_diffuse_transmission's maps need it and come together; unlit drops it.
    EXPECT_FALSE(valid_features(HasUv0 | HasNormal | DiffuseTransmissionMap | DiffuseTransmissionColorMap));
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | DiffuseTransmission | DiffuseTransmissionColorMap),
              HasUv0 | HasNormal | DiffuseTransmission | DiffuseTransmissionMap | DiffuseTransmissionColorMap);
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | DiffuseTransmission | Unlit), HasUv0 | Unlit);
    // The occlusion in the metallic-roughness texture replaces the occlusion map (also under the
    // debug view) and needs that map and metallic-roughness.
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | MetallicRoughnessMap | OcclusionMap | OcclusionInMetallicRoughness),
              HasUv0 | HasNormal | MetallicRoughnessMap | OcclusionInMetallicRoughness);
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | OcclusionMap | OcclusionInMetallicRoughness),
              HasUv0 | HasNormal | OcclusionMap);
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | SpecularGlossiness | MetallicRoughnessMap | OcclusionInMetallicRoughness),
              HasUv0 | HasNormal | SpecularGlossiness);
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | MetallicRoughnessMap | OcclusionInMetallicRoughness | DebugView) &
                  (OcclusionMap | OcclusionInMetallicRoughness),
              OcclusionInMetallicRoughness);
    EXPECT_TRUE(valid_features(HasNormal | HasTangent | HasUv0 | UseIbl | BaseColorMap | MetallicRoughnessMap |
                               NormalMap | OcclusionInMetallicRoughness | EmissiveMap));
    // The shared detail footprint needs two of the base colour, metallic-roughness, occlusion and
    // normal maps (the occlusion packed into metallic-roughness counts as that map).
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | BaseColorMap | EmissiveMap | DetailSharedFootprint),
              HasUv0 | HasNormal | BaseColorMap | EmissiveMap);
    EXPECT_TRUE(valid_features(HasUv0 | HasNormal | BaseColorMap | OcclusionMap | DetailSharedFootprint));
    EXPECT_TRUE(valid_features(HasNormal | HasTangent | HasUv0 | MetallicRoughnessMap | NormalMap | DetailSharedFootprint));
    EXPECT_EQ(canonical_features(HasUv0 | HasNormal | Unlit | BaseColorMap | MetallicRoughnessMap | DetailSharedFootprint),
              HasUv0 | Unlit | BaseColorMap);
    EXPECT_TRUE(valid_features(HasNormal | HasTangent | HasUv0 | UseIbl | BaseColorMap | MetallicRoughnessMap | NormalMap |
                               OcclusionInMetallicRoughness | EmissiveMap | DetailSharedFootprint));
    // The metallic-roughness in alpha channels needs the metallic-roughness, base colour and normal
    // maps, the emissive map with the occlusion in the metallic-roughness texture, an opaque
    // metallic-roughness material and no debug view.
    const FeatureMask in_alpha = HasNormal | HasTangent | HasUv0 | UseIbl | BaseColorMap | MetallicRoughnessMap |
                                 NormalMap | MetallicRoughnessInAlpha;
    EXPECT_TRUE(valid_features(in_alpha));
    EXPECT_TRUE(valid_features(in_alpha | OcclusionInMetallicRoughness | EmissiveMap | DetailSharedFootprint));
    EXPECT_TRUE(valid_features(in_alpha | OcclusionMap | DetailSharedFootprint));  // an occlusion of its own
    EXPECT_EQ(canonical_features(in_alpha | OcclusionInMetallicRoughness), (in_alpha | OcclusionInMetallicRoughness) &
                                                                                ~MetallicRoughnessInAlpha);
    for (FeatureMask map : {BaseColorMap, MetallicRoughnessMap, NormalMap})
        EXPECT_EQ(canonical_features(in_alpha & ~map) & MetallicRoughnessInAlpha, 0u) << std::hex << map;
    for (FeatureMask other : {FeatureMask(AlphaMask), FeatureMask(AlphaBlend), FeatureMask(DebugView),
                              FeatureMask(SpecularGlossiness), FeatureMask(0)})
        EXPECT_EQ(canonical_features(in_alpha | other) & MetallicRoughnessInAlpha,
                  other ? FeatureMask(0) : FeatureMask(MetallicRoughnessInAlpha)) << std::hex << other;
    EXPECT_EQ(canonical_features(in_alpha & ~HasTangent) & MetallicRoughnessInAlpha, 0u);  // no normal map
    // DamagedHelmet's variant exists unchanged.
    const FeatureMask helmet = HasNormal | HasTangent | HasUv0 | UseIbl | BaseColorMap | MetallicRoughnessMap |
                               NormalMap | OcclusionMap | EmissiveMap;
    EXPECT_EQ(canonical_features(helmet), helmet);
    EXPECT_GT(all.size(), 1000u);
    std::printf("feature sets: %zu\n", all.size());
}

TEST(ShaderFeatures, LegacyRules) {
    using namespace legacy_feature;
    const std::vector<FeatureMask> all = all_legacy_feature_sets();
    for (FeatureMask m = 0; m <= kAll; ++m) {
        FeatureMask c = canonical_legacy_features(m);
        EXPECT_EQ(canonical_legacy_features(c), c) << m;
        if (m & kModels) {
            EXPECT_TRUE(valid_legacy_features(c)) << m;
        }
    }
    for (FeatureMask m : all) EXPECT_EQ(__builtin_popcount(m & kModels), 1) << m;  // exactly one model
    EXPECT_FALSE(valid_legacy_features(HasNormal));                     // no model
    EXPECT_FALSE(valid_legacy_features(Ogl1Vertex | DiffuseMap));       // the map needs UV0
    EXPECT_FALSE(valid_legacy_features(Ogl1Pixel | UseIbl));            // OpenGL 1 has no image-based light
    EXPECT_FALSE(valid_legacy_features(BlinnPhong | Fogged));           // fog is OpenGL 1's
    EXPECT_TRUE(valid_legacy_features(Ogl1Vertex | HasNormal | HasUv0 | DiffuseMap | Fogged));
    EXPECT_TRUE(valid_legacy_features(BlinnPhong | HasNormal | HasUv0 | DiffuseMap | UseIbl));
}

TEST(ShaderVariants, EveryVariantCompilesAsEs300AndGl330) {
    GlslangProcess process;
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<FeatureMask> all = all_feature_sets();
    std::vector<Job> jobs;
    std::size_t per_target = 0;
    // KHR_materials_anisotropy's code (under MATERIAL_ANISOTROPY / HAS_ANISOTROPY_MAP) and the
    // sheen and transmission code name none of each other's identifiers, so a variant with the
    // anisotropy group on and one of those groups on can fail only in ways the two show apart:
    // such variants are compiled on a few base sets (bits 0..22: the bare tangent frame,
    // DamagedHelmet's, its debug view and the richest), every other variant in full. The full
    // cross product would be 2.5x the pbr.frag sources of the set without anisotropy; this is 1.3x.
    using namespace feature;
    constexpr FeatureMask kLow = (FeatureMask(1) << 23) - 1;
    // The diffuse roughness map (HAS_DIFFUSE_ROUGHNESS_MAP) reads one sampler into one float
    // and names no other group's identifiers: its variants are compiled on the base sets too.
    const auto crossed = [](FeatureMask m) {
        return ((m & (Anisotropy | AnisotropyMap)) != 0 && (m & (Sheen | Transmission)) != 0) ||
               (m & DiffuseRoughnessMap) != 0;
    };
    std::set<FeatureMask> bases;
    {
        const FeatureMask helmet = HasNormal | HasTangent | HasUv0 | UseIbl | BaseColorMap | MetallicRoughnessMap |
                                   NormalMap | OcclusionMap | EmissiveMap;
        bases = {HasNormal | HasTangent, helmet, canonical_features(helmet | DebugView) & kLow};
        FeatureMask richest = 0;
        for (FeatureMask m : all)
            if (crossed(m) && __builtin_popcountll(m & kLow) > __builtin_popcountll(richest)) richest = m & kLow;
        bases.insert(richest);
    }
    for (const char* file : {"pbr.vert", "pbr.frag"}) {
        const FeatureMask read = bits_read_by(file);
        EXPECT_NE(read, 0u) << file << " reads no feature bit: the scan is broken";
        std::set<FeatureMask> distinct;
        std::size_t crossed_kept = 0;
        for (FeatureMask m : all) {
            if (crossed(m) && !bases.count(m & kLow)) continue;
            if (crossed(m)) ++crossed_kept;
            distinct.insert(m & read);
        }
        const std::vector<FeatureMask> sources = sources_to_compile(distinct, read);
        std::printf("%s: %zu distinct sources over %zu feature sets (%zu of them with anisotropy and sheen or "
                    "transmission or the diffuse roughness map, on %zu base sets), %zu compiled (the film and diffuse transmission groups sampled)\n",
                    file, distinct.size(), all.size(), crossed_kept, bases.size(), sources.size());
        per_target += sources.size();
        // GLSL ES 3.00 is the stricter dialect and the two sources differ only in the header
        // (#version, precision statements), so every source compiles as 300 es and every
        // kDesktopStride-th (in mask order) as 330 core as well, which keeps this test's share
        // of CI's two cores near half of what compiling all twice cost (~580 s there).
        // The renderer compiles pbr.frag with a frame variant always (frame_defines: tone mapper,
        // encoding, with or without punctual lights); the sources take them in turn, so each
        // variant is compiled with some thousand feature sets, and FRAME_NO_LIGHTS (which removes
        // the light loop) meets every bit the stage reads both set and clear (asserted below).
        std::vector<FrameVariant> frames;
        for (int t = 0; t <= int(ToneMapper::None); ++t)
            for (int e : {-1, 0, 1})
                for (bool lights : {true, false}) frames.push_back({t, e, lights});
        const bool fragment = std::string(file) == "pbr.frag";
        FeatureMask set_lit = 0, set_unlit = 0, clear_lit = 0, clear_unlit = 0;
        for (std::size_t k = 0; k < sources.size(); ++k) {
            // Consecutive variants alternate the lights, and the turn shifts by one every round
            // (k / frames.size()), so that a bit that alternates with k meets both choices.
            const FrameVariant& frame = frames[(k + k / frames.size()) % frames.size()];
            const std::vector<std::string> fd = fragment ? frame_defines(frame) : std::vector<std::string>{};
            if (fragment) {
                (frame.lights ? set_lit : set_unlit) |= sources[k];
                (frame.lights ? clear_lit : clear_unlit) |= ~sources[k] & read;
            }
            jobs.push_back({file, sources[k], true, GlslTarget::Es30, fd});
            if (k % kDesktopStride == 0) jobs.push_back({file, sources[k], true, GlslTarget::Gl33, fd});
        }
        if (fragment) {
            for (FeatureMask bits : {set_lit, set_unlit, clear_lit, clear_unlit}) {
                EXPECT_EQ(bits & read, read) << "a bit pbr.frag reads never meets one of the light choices";
            }
        }
    }
    // The legacy models' shaders (legacy.vert / legacy.frag): every legacy feature set.
    const std::vector<FeatureMask> legacy = all_legacy_feature_sets();
    EXPECT_GT(legacy.size(), 10u);
    for (const char* file : {"legacy.vert", "legacy.frag"}) {
        per_target += legacy.size();
        for (GlslTarget t : {GlslTarget::Es30, GlslTarget::Gl33})
            for (FeatureMask m : legacy) jobs.push_back({file, 0, false, t, legacy_feature_defines(m)});
    }
    for (const char* file : {"fullscreen.vert", "post.frag", "sky.frag", "brdf_probe.frag", "legacy_probe.frag"}) {
        ++per_target;
        for (GlslTarget t : {GlslTarget::Es30, GlslTarget::Gl33}) jobs.push_back({file, 0, false, t});
    }
    // The alternative BRDF terms (`--brdf`, BRDF_* defines) on the richest feature set and in
    // the probe shader: every value of every term, and all of them at once.
    {
        FeatureMask richest = *std::max_element(all.begin(), all.end(), [](FeatureMask a, FeatureMask b) {
            return __builtin_popcountll(a) < __builtin_popcountll(b);
        });
        std::vector<fresnel::brdf::BrdfModel> models;
        for (int i = 1; i < 3; ++i) models.push_back({fresnel::brdf::Distribution(i), {}, {}, {}});
        for (int i = 1; i < 5; ++i) models.push_back({{}, fresnel::brdf::Geometry(i), {}, {}});
        for (int i = 1; i < 4; ++i) models.push_back({{}, {}, fresnel::brdf::Fresnel(i), {}});
        models.push_back({{}, {}, fresnel::brdf::Fresnel::Exact, {}, fresnel::brdf::Conductor::Copper});
        for (int i = 1; i < 3; ++i) models.push_back({{}, {}, {}, fresnel::brdf::Diffuse(i)});
        models.push_back({fresnel::brdf::Distribution::Beckmann, fresnel::brdf::Geometry::Kelemen,
                          fresnel::brdf::Fresnel::ExactDielectric, fresnel::brdf::Diffuse::OrenNayar});
        for (const auto& model : models) {
            std::vector<std::string> defines = feature_defines(richest);
            for (const auto& d : fresnel::brdf::brdf_model_defines(model)) defines.push_back(d);
            per_target += 2;
            for (GlslTarget t : {GlslTarget::Es30, GlslTarget::Gl33}) {
                jobs.push_back({"pbr.frag", 0, false, t, defines});
                jobs.push_back({"brdf_probe.frag", 0, false, t, fresnel::brdf::brdf_model_defines(model)});
            }
        }
    }
    // The frame variants (frame_defines: every tone mapper with each encoding, the transmission
    // pass's linear output, with and without punctual lights) in the three shaders that write a
    // frame, on the richest mesh feature set, a Blinn-Phong legacy set and the sky.
    {
        FeatureMask richest = *std::max_element(all.begin(), all.end(), [](FeatureMask a, FeatureMask b) {
            return __builtin_popcountll(a) < __builtin_popcountll(b);
        });
        std::vector<fresnel::FrameVariant> outputs;
        for (int t = 0; t <= int(fresnel::ToneMapper::None); ++t)
            for (int e : {-1, 0, 1}) outputs.push_back({t, e, t % 2 == 0});  // with and without lights
        const FeatureMask blinn = fresnel::legacy_feature::BlinnPhong | fresnel::legacy_feature::HasNormal |
                                  fresnel::legacy_feature::HasUv0 | fresnel::legacy_feature::DiffuseMap |
                                  fresnel::legacy_feature::UseIbl;
        for (const auto& out : outputs) {
            const std::vector<std::string> od = frame_defines(out);
            std::vector<std::string> mesh = feature_defines(richest), legacy = legacy_feature_defines(blinn);
            mesh.insert(mesh.end(), od.begin(), od.end());
            legacy.insert(legacy.end(), od.begin(), od.end());
            per_target += 3;
            for (GlslTarget t : {GlslTarget::Es30, GlslTarget::Gl33}) {
                jobs.push_back({"pbr.frag", 0, false, t, mesh});
                jobs.push_back({"legacy.frag", 0, false, t, legacy});
                jobs.push_back({"sky.frag", 0, false, t, od});
            }
        }
    }
    // The output pass that resolves the multisampled frame itself: desktop GL only (GLSL ES
    // 3.00 has no sampler2DMS; the renderer blits there).
    jobs.push_back({"post.frag", 0, false, GlslTarget::Gl33, {"MSAA_RESOLVE"}});
    // The output pass as the renderer compiles it: the sample count and the alpha choice defined.
    for (const char* alpha : {"STRAIGHT_ALPHA 0", "STRAIGHT_ALPHA 1"}) {
        for (GlslTarget t : {GlslTarget::Es30, GlslTarget::Gl33}) jobs.push_back({"post.frag", 0, false, t, {alpha}});
        for (const char* samples : {"MSAA_SAMPLES 2", "MSAA_SAMPLES 4", "MSAA_SAMPLES 8"})
            jobs.push_back({"post.frag", 0, false, GlslTarget::Gl33, {"MSAA_RESOLVE", samples, alpha}});
    }

    std::atomic<std::size_t> next{0}, compiled{0};
    std::mutex mutex;
    std::vector<std::string> failures;
    auto worker = [&] {
        for (std::size_t i = next++; i < jobs.size(); i = next++) {
            std::string log = compile(jobs[i]);
            ++compiled;
            if (log.empty()) continue;
            std::lock_guard<std::mutex> lock(mutex);
            failures.push_back(describe(jobs[i]) + "\n" + log);
        }
    };
    const unsigned n = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> threads;
    for (unsigned i = 0; i < n; ++i) threads.emplace_back(worker);
    for (auto& t : threads) t.join();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("compiled %zu stage sources (%zu as 300 es, every %zuth mesh source and all others as 330 core too, "
                "and the desktop-only MSAA resolve) on %u threads in %.1f s\n",
                compiled.load(), per_target, kDesktopStride, n, seconds);
    EXPECT_EQ(compiled.load(), jobs.size());
    EXPECT_TRUE(failures.empty()) << failures.size() << " of " << jobs.size() << " failed; first:\n"
                                  << (failures.empty() ? "" : failures.front());
}

TEST(ShaderVariants, CompilerRejectsBadSource) {
    // The check can fail: GLSL ES rejects an implicit int -> float conversion that 330 core accepts.
    GlslangProcess process;
    auto parse = [](const char* src) {
        glslang::TShader shader(EShLangFragment);
        shader.setStrings(&src, 1);
        return shader.parse(GetDefaultResources(), 100, false, EShMsgDefault);
    };
    EXPECT_FALSE(parse("#version 300 es\nprecision highp float;\nout vec4 c;\nvoid main() { float x = 1; c = vec4(x); }\n"));
    EXPECT_TRUE(parse("#version 330 core\nout vec4 c;\nvoid main() { float x = 1; c = vec4(x); }\n"));
}
