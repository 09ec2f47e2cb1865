// The material property registry (fresnel/material/properties.h): the one table of the
// material's properties, its extension blocks and its textures.
#include "fresnel/material/properties.h"

#include <cstdlib>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/core/float_text.h"
#include "fresnel/core/json_text.h"

// The tables name only the fields that differ from Property's defaults (C++20 designated
// initializers); GCC would warn about every field left out.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace fresnel::material_properties {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kPi = 3.14159265f;

// ---- A field as a Value, and back ----
void to_value(float x, Value& v) { v[0] = x; }
void to_value(bool x, Value& v) { v[0] = x ? 1.0f : 0.0f; }
void to_value(AlphaMode x, Value& v) { v[0] = float(int(x)); }
template <int N>
void to_value(const glm::vec<N, float>& x, Value& v) {
    for (int i = 0; i < N; ++i) v[std::size_t(i)] = x[i];
}
void from_value(float& x, const Value& v) { x = v[0]; }
void from_value(bool& x, const Value& v) { x = v[0] != 0.0f; }
void from_value(AlphaMode& x, const Value& v) { x = AlphaMode(int(v[0])); }
template <int N>
void from_value(glm::vec<N, float>& x, const Value& v) {
    for (int i = 0; i < N; ++i) x[i] = v[std::size_t(i)];
}
float* floats_of(float& x) { return &x; }
template <int N>
float* floats_of(glm::vec<N, float>& x) {
    return &x[0];
}

// A property of the core material: a pointer to its member.
template <auto Field>
Value core_get(const Material& m) {
    Value v{};
    to_value(m.*Field, v);
    return v;
}
template <auto Field>
void core_put(Material& m, const Value& v) {
    from_value(m.*Field, v);
}
template <auto Field>
float* core_data(Material& m) {
    return floats_of(m.*Field);
}

// A property of an extension block: the block's optional member, and the field in it.
template <auto Block>
auto& block_of(Material& m) {
    auto& b = m.*Block;
    if (!b) b.emplace();
    return *b;
}
template <auto Block, auto Field>
Value ext_get(const Material& m) {
    using B = typename std::remove_cvref_t<decltype(m.*Block)>::value_type;
    Value v{};
    const auto& b = m.*Block;
    to_value(b ? (*b).*Field : B{}.*Field, v);
    return v;
}
template <auto Block, auto Field>
void ext_put(Material& m, const Value& v) {
    from_value(block_of<Block>(m).*Field, v);
}
template <auto Block, auto Field>
float* ext_data(Material& m) {
    return floats_of(block_of<Block>(m).*Field);
}

#define FRESNEL_CORE(field) .get = core_get<&Material::field>, .put = core_put<&Material::field>, .data = core_data<&Material::field>
#define FRESNEL_EXT(block, type, field)                                                              \
    .get = ext_get<&Material::block, &type::field>, .put = ext_put<&Material::block, &type::field>, \
    .data = ext_data<&Material::block, &type::field>

constexpr std::string_view kAlphaModes[] = {"OPAQUE", "MASK", "BLEND"};

const std::vector<Property>& table() {
    static const std::vector<Property> t = {
        // ---- the core material ----
        {.name = "baseColorFactor", .path = "pbrMetallicRoughness/baseColorFactor", .type = Type::Color, .width = 4,
         .fallback = {1, 1, 1, 1}, .animatable = true, .doc = "base colour (linear RGB) and alpha, times the base colour texture",
         FRESNEL_CORE(base_color_factor)},
        {.name = "metallicFactor", .path = "pbrMetallicRoughness/metallicFactor", .fallback = {1}, .animatable = true,
         .doc = "metalness, times the metallic-roughness texture's B", FRESNEL_CORE(metallic_factor)},
        {.name = "roughnessFactor", .path = "pbrMetallicRoughness/roughnessFactor", .fallback = {1}, .animatable = true,
         .doc = "perceptual roughness of the specular lobe, times the metallic-roughness texture's G",
         FRESNEL_CORE(roughness_factor)},
        {.name = "emissiveFactor", .path = "emissiveFactor", .type = Type::Color, .width = 3, .max = kInf,
         .animatable = true,
         .doc = "emitted colour (linear RGB), times the emissive texture and the emissive strength (above 1 only "
                "when animated or overridden; glTF files hold the excess as emissiveStrength)",
         FRESNEL_CORE(emissive_factor)},
        {.name = "normalScale", .path = "normalTexture/scale", .min = -kInf, .max = kInf, .slider_max = 2, .fallback = {1},
         .animatable = true, .doc = "scale of the normal texture's X and Y", FRESNEL_CORE(normal_scale)},
        {.name = "occlusionStrength", .path = "occlusionTexture/strength", .fallback = {1}, .animatable = true,
         .doc = "how much the occlusion texture darkens indirect light", FRESNEL_CORE(occlusion_strength)},
        {.name = "alphaMode", .path = "alphaMode", .type = Type::Choice, .min = 0, .max = 2, .slider_max = 2,
         .choices = kAlphaModes, .doc = "how alpha is used: ignored, a cut-out at alphaCutoff, or blended",
         .get = core_get<&Material::alpha_mode>, .put = core_put<&Material::alpha_mode>},
        {.name = "alphaCutoff", .path = "alphaCutoff", .max = kInf, .fallback = {0.5f}, .animatable = true,
         .doc = "alpha below which a MASK material is cut out", FRESNEL_CORE(alpha_cutoff)},
        {.name = "doubleSided", .path = "doubleSided", .type = Type::Bool, .max = 1, .doc = "both faces drawn and lit",
         .get = core_get<&Material::double_sided>, .put = core_put<&Material::double_sided>},
        // ---- extensions ----
        {.name = "emissiveStrength", .path = "extensions/KHR_materials_emissive_strength/emissiveStrength",
         .block = "KHR_materials_emissive_strength", .max = kInf, .slider_max = 20, .fallback = {1}, .animatable = true,
         .doc = "multiplier of the emitted colour (may exceed 1)",
         FRESNEL_EXT(emissive_strength, EmissiveStrengthExt, emissive_strength)},
        {.name = "ior", .path = "extensions/KHR_materials_ior/ior", .block = "KHR_materials_ior", .max = kInf,
         .slider_min = 1, .slider_max = 3, .fallback = {1.5f}, .animatable = true,
         .doc = "index of refraction of the dielectric (0 is allowed: F0 = 1)", FRESNEL_EXT(ior, IorExt, ior)},
        {.name = "specularFactor", .path = "extensions/KHR_materials_specular/specularFactor",
         .block = "KHR_materials_specular", .fallback = {1}, .animatable = true,
         .doc = "weight of the dielectric specular lobe", FRESNEL_EXT(specular, SpecularExt, specular_factor)},
        {.name = "specularColorFactor", .path = "extensions/KHR_materials_specular/specularColorFactor",
         .block = "KHR_materials_specular", .type = Type::Color, .width = 3, .max = kInf, .fallback = {1, 1, 1},
         .animatable = true, .doc = "tint of the dielectric F0 (may exceed 1)",
         FRESNEL_EXT(specular, SpecularExt, specular_color_factor)},
        {.name = "clearcoatFactor", .path = "extensions/KHR_materials_clearcoat/clearcoatFactor",
         .block = "KHR_materials_clearcoat", .animatable = true, .doc = "strength of the clear coat layer",
         FRESNEL_EXT(clearcoat, ClearcoatExt, clearcoat_factor)},
        {.name = "clearcoatRoughnessFactor", .path = "extensions/KHR_materials_clearcoat/clearcoatRoughnessFactor",
         .block = "KHR_materials_clearcoat", .animatable = true, .doc = "perceptual roughness of the clear coat",
         FRESNEL_EXT(clearcoat, ClearcoatExt, clearcoat_roughness_factor)},
        {.name = "clearcoatNormalScale", .path = "extensions/KHR_materials_clearcoat/clearcoatNormalTexture/scale",
         .block = "KHR_materials_clearcoat", .min = -kInf, .max = kInf, .slider_max = 2, .fallback = {1},
         .animatable = true, .doc = "scale of the clear coat normal texture's X and Y",
         FRESNEL_EXT(clearcoat, ClearcoatExt, clearcoat_normal_scale)},
        {.name = "sheenColorFactor", .path = "extensions/KHR_materials_sheen/sheenColorFactor",
         .block = "KHR_materials_sheen", .type = Type::Color, .width = 3, .animatable = true,
         .doc = "colour of the sheen (velvet) lobe; black is none", FRESNEL_EXT(sheen, SheenExt, sheen_color_factor)},
        {.name = "sheenRoughnessFactor", .path = "extensions/KHR_materials_sheen/sheenRoughnessFactor",
         .block = "KHR_materials_sheen", .animatable = true, .doc = "roughness of the sheen lobe",
         FRESNEL_EXT(sheen, SheenExt, sheen_roughness_factor)},
        {.name = "transmissionFactor", .path = "extensions/KHR_materials_transmission/transmissionFactor",
         .block = "KHR_materials_transmission", .animatable = true,
         .doc = "share of light refracted through the surface (glass)",
         FRESNEL_EXT(transmission, TransmissionExt, transmission_factor)},
        {.name = "thicknessFactor", .path = "extensions/KHR_materials_volume/thicknessFactor",
         .block = "KHR_materials_volume", .max = kInf, .slider_max = 10, .animatable = true, .unit = "model units",
         .doc = "thickness of the volume under the surface; 0 is thin-walled",
         FRESNEL_EXT(volume, VolumeExt, thickness_factor)},
        {.name = "attenuationDistance", .path = "extensions/KHR_materials_volume/attenuationDistance",
         .block = "KHR_materials_volume", .min = 1e-6f, .max = kInf, .slider_min = 0.01f, .slider_max = 10,
         .fallback = {kInf}, .animatable = true, .unit = "model units",
         .doc = "distance at which light in the volume keeps attenuationColor (inf: no absorption)",
         FRESNEL_EXT(volume, VolumeExt, attenuation_distance)},
        {.name = "attenuationColor", .path = "extensions/KHR_materials_volume/attenuationColor",
         .block = "KHR_materials_volume", .type = Type::Color, .width = 3, .fallback = {1, 1, 1}, .animatable = true,
         .doc = "colour white light becomes after attenuationDistance in the volume",
         FRESNEL_EXT(volume, VolumeExt, attenuation_color)},
        {.name = "dispersion", .path = "extensions/KHR_materials_dispersion/dispersion",
         .block = "KHR_materials_dispersion", .max = kInf, .slider_max = 2, .animatable = true,
         .doc = "spread of the ior over wavelengths (20 / Abbe number)", FRESNEL_EXT(dispersion, DispersionExt, dispersion)},
        {.name = "iridescenceFactor", .path = "extensions/KHR_materials_iridescence/iridescenceFactor",
         .block = "KHR_materials_iridescence", .animatable = true, .doc = "strength of the thin-film interference",
         FRESNEL_EXT(iridescence, IridescenceExt, iridescence_factor)},
        {.name = "iridescenceIor", .path = "extensions/KHR_materials_iridescence/iridescenceIor",
         .block = "KHR_materials_iridescence", .min = 1, .max = kInf, .slider_min = 1, .slider_max = 3,
         .fallback = {1.3f}, .animatable = true, .doc = "index of refraction of the thin film",
         FRESNEL_EXT(iridescence, IridescenceExt, iridescence_ior)},
        {.name = "iridescenceThicknessMinimum", .path = "extensions/KHR_materials_iridescence/iridescenceThicknessMinimum",
         .block = "KHR_materials_iridescence", .max = kInf, .slider_max = 1200, .fallback = {100}, .animatable = true,
         .unit = "nm", .doc = "film thickness where the thickness texture is 0",
         FRESNEL_EXT(iridescence, IridescenceExt, iridescence_thickness_minimum)},
        {.name = "iridescenceThicknessMaximum", .path = "extensions/KHR_materials_iridescence/iridescenceThicknessMaximum",
         .block = "KHR_materials_iridescence", .max = kInf, .slider_max = 1200, .fallback = {400}, .animatable = true,
         .unit = "nm", .doc = "film thickness where the thickness texture is 1 (and without one)",
         FRESNEL_EXT(iridescence, IridescenceExt, iridescence_thickness_maximum)},
        {.name = "anisotropyStrength", .path = "extensions/KHR_materials_anisotropy/anisotropyStrength",
         .block = "KHR_materials_anisotropy", .animatable = true, .doc = "stretch of the specular highlight",
         FRESNEL_EXT(anisotropy, AnisotropyExt, anisotropy_strength)},
        {.name = "anisotropyRotation", .path = "extensions/KHR_materials_anisotropy/anisotropyRotation",
         .block = "KHR_materials_anisotropy", .min = -kInf, .max = kInf, .slider_min = -kPi, .slider_max = kPi,
         .animatable = true, .unit = "radians", .doc = "rotation of the anisotropy direction from the tangent",
         FRESNEL_EXT(anisotropy, AnisotropyExt, anisotropy_rotation)},
        {.name = "diffuseTransmissionFactor",
         .path = "extensions/KHR_materials_diffuse_transmission/diffuseTransmissionFactor",
         .block = "KHR_materials_diffuse_transmission", .animatable = true,
         .doc = "share of the diffuse light scattered through the surface (leaves, paper)",
         FRESNEL_EXT(diffuse_transmission, DiffuseTransmissionExt, diffuse_transmission_factor)},
        {.name = "diffuseTransmissionColorFactor",
         .path = "extensions/KHR_materials_diffuse_transmission/diffuseTransmissionColorFactor",
         .block = "KHR_materials_diffuse_transmission", .type = Type::Color, .width = 3, .fallback = {1, 1, 1},
         .animatable = true, .doc = "colour of the diffusely transmitted light",
         FRESNEL_EXT(diffuse_transmission, DiffuseTransmissionExt, diffuse_transmission_color_factor)},
        {.name = "diffuseRoughnessFactor", .path = "extensions/KHR_materials_diffuse_roughness/diffuseRoughnessFactor",
         .block = "KHR_materials_diffuse_roughness", .animatable = true,
         .doc = "roughness of the diffuse lobe (energy-preserving Oren-Nayar; 0 is Lambert)",
         FRESNEL_EXT(diffuse_roughness, DiffuseRoughnessExt, diffuse_roughness_factor)},
    };
    return t;
}

#undef FRESNEL_CORE
#undef FRESNEL_EXT

template <auto B>
bool block_present(const Material& m) {
    return bool(m.*B);
}
template <auto B>
void block_add(Material& m) {
    if (!(m.*B)) (m.*B).emplace();
}
template <auto B>
void block_remove(Material& m) {
    (m.*B).reset();
}
#define FRESNEL_BLOCK(member, ext, text) \
    {ext, text, block_present<&Material::member>, block_add<&Material::member>, block_remove<&Material::member>}

const std::vector<Block>& block_table() {
    static const std::vector<Block> t = {
        FRESNEL_BLOCK(emissive_strength, "KHR_materials_emissive_strength", "emission brighter than 1"),
        FRESNEL_BLOCK(ior, "KHR_materials_ior", "the dielectric's index of refraction"),
        FRESNEL_BLOCK(specular, "KHR_materials_specular", "strength and colour of the dielectric specular"),
        FRESNEL_BLOCK(clearcoat, "KHR_materials_clearcoat", "a clear coat layer over the material"),
        FRESNEL_BLOCK(sheen, "KHR_materials_sheen", "a velvet-like sheen lobe"),
        FRESNEL_BLOCK(transmission, "KHR_materials_transmission", "light refracted through the surface"),
        FRESNEL_BLOCK(volume, "KHR_materials_volume", "thickness and absorption of a transmitting volume"),
        FRESNEL_BLOCK(dispersion, "KHR_materials_dispersion", "ior varying with wavelength"),
        FRESNEL_BLOCK(iridescence, "KHR_materials_iridescence", "thin-film interference"),
        FRESNEL_BLOCK(anisotropy, "KHR_materials_anisotropy", "a stretched specular highlight"),
        FRESNEL_BLOCK(diffuse_transmission, "KHR_materials_diffuse_transmission", "diffuse light through thin surfaces"),
        FRESNEL_BLOCK(diffuse_roughness, "KHR_materials_diffuse_roughness", "a rough (Oren-Nayar) diffuse lobe"),
        FRESNEL_BLOCK(unlit, "KHR_materials_unlit", "the base colour shown as it is, without light"),
    };
    return t;
}
#undef FRESNEL_BLOCK

template <auto Slot>
const TextureSlot* core_texture(const Material& m) {
    return &(m.*Slot);
}
template <auto Slot>
TextureSlot* core_texture_slot(Material& m) {
    return &(m.*Slot);
}
template <auto Block, auto Slot>
const TextureSlot* ext_texture(const Material& m) {
    const auto& b = m.*Block;
    return b ? &((*b).*Slot) : nullptr;
}
template <auto Block, auto Slot>
TextureSlot* ext_texture_slot(Material& m) {
    return &(block_of<Block>(m).*Slot);
}
#define FRESNEL_CORE_TEX(name, path, channels, slot) \
    {name, path, "", channels, core_texture<&Material::slot>, core_texture_slot<&Material::slot>}
#define FRESNEL_EXT_TEX(name, ext, channels, block, type, slot)                                       \
    {name, "extensions/" ext "/" name, ext, channels, ext_texture<&Material::block, &type::slot>, \
     ext_texture_slot<&Material::block, &type::slot>}

const std::vector<Texture>& texture_table() {
    static const std::vector<Texture> t = {
        FRESNEL_CORE_TEX("baseColorTexture", "pbrMetallicRoughness/baseColorTexture", "RGBA sRGB", base_color),
        FRESNEL_CORE_TEX("metallicRoughnessTexture", "pbrMetallicRoughness/metallicRoughnessTexture",
                         "G roughness, B metallic", metallic_roughness),
        FRESNEL_CORE_TEX("normalTexture", "normalTexture", "RGB tangent-space normal", normal),
        FRESNEL_CORE_TEX("occlusionTexture", "occlusionTexture", "R", occlusion),
        FRESNEL_CORE_TEX("emissiveTexture", "emissiveTexture", "RGB sRGB", emissive),
        FRESNEL_EXT_TEX("clearcoatTexture", "KHR_materials_clearcoat", "R", clearcoat, ClearcoatExt, clearcoat_texture),
        FRESNEL_EXT_TEX("clearcoatRoughnessTexture", "KHR_materials_clearcoat", "G", clearcoat, ClearcoatExt,
                        clearcoat_roughness_texture),
        FRESNEL_EXT_TEX("clearcoatNormalTexture", "KHR_materials_clearcoat", "RGB tangent-space normal", clearcoat,
                        ClearcoatExt, clearcoat_normal_texture),
        FRESNEL_EXT_TEX("specularTexture", "KHR_materials_specular", "A", specular, SpecularExt, specular_texture),
        FRESNEL_EXT_TEX("specularColorTexture", "KHR_materials_specular", "RGB sRGB", specular, SpecularExt,
                        specular_color_texture),
        FRESNEL_EXT_TEX("sheenColorTexture", "KHR_materials_sheen", "RGB sRGB", sheen, SheenExt, sheen_color_texture),
        FRESNEL_EXT_TEX("sheenRoughnessTexture", "KHR_materials_sheen", "A", sheen, SheenExt, sheen_roughness_texture),
        FRESNEL_EXT_TEX("transmissionTexture", "KHR_materials_transmission", "R", transmission, TransmissionExt,
                        transmission_texture),
        FRESNEL_EXT_TEX("thicknessTexture", "KHR_materials_volume", "G", volume, VolumeExt, thickness_texture),
        FRESNEL_EXT_TEX("iridescenceTexture", "KHR_materials_iridescence", "R", iridescence, IridescenceExt,
                        iridescence_texture),
        FRESNEL_EXT_TEX("iridescenceThicknessTexture", "KHR_materials_iridescence", "G", iridescence, IridescenceExt,
                        iridescence_thickness_texture),
        FRESNEL_EXT_TEX("anisotropyTexture", "KHR_materials_anisotropy", "RG direction, B strength", anisotropy,
                        AnisotropyExt, anisotropy_texture),
        FRESNEL_EXT_TEX("diffuseTransmissionTexture", "KHR_materials_diffuse_transmission", "A", diffuse_transmission,
                        DiffuseTransmissionExt, diffuse_transmission_texture),
        FRESNEL_EXT_TEX("diffuseTransmissionColorTexture", "KHR_materials_diffuse_transmission", "RGB sRGB",
                        diffuse_transmission, DiffuseTransmissionExt, diffuse_transmission_color_texture),
        FRESNEL_EXT_TEX("diffuseRoughnessTexture", "KHR_materials_diffuse_roughness", "R", diffuse_roughness,
                        DiffuseRoughnessExt, diffuse_roughness_texture),
    };
    return t;
}
#undef FRESNEL_CORE_TEX
#undef FRESNEL_EXT_TEX

std::string range_text(const Property& p) {
    bool lo = std::isfinite(p.min), hi = std::isfinite(p.max);
    if (lo && hi) return " in [" + shortest_text(p.min) + ", " + shortest_text(p.max) + "]";
    if (lo) return " >= " + shortest_text(p.min);
    if (hi) return " <= " + shortest_text(p.max);
    return "";
}

bool parse_number(std::string_view t, float& out) {
    while (!t.empty() && t.front() == ' ') t.remove_prefix(1);
    while (!t.empty() && t.back() == ' ') t.remove_suffix(1);
    if (t.empty()) return false;
    // strtof, not std::from_chars: Emscripten's libc++ (the web page's) has no float overload.
    const std::string text(t);
    char* end = nullptr;
    out = std::strtof(text.c_str(), &end);
    return end == text.c_str() + text.size() && !std::isnan(out);
}

}  // namespace

std::span<const Property> all() { return table(); }
std::span<const Block> blocks() { return block_table(); }
std::span<const Texture> textures() { return texture_table(); }

namespace {
// The entry of `table` whose `member` is `key`, or nullptr.
template <class T>
const T* lookup(const std::vector<T>& table, std::string_view T::*member, std::string_view key) {
    for (const T& e : table)
        if (e.*member == key) return &e;
    return nullptr;
}
}  // namespace

const Property* find(std::string_view name) { return lookup(table(), &Property::name, name); }
const Property* find_path(std::string_view path) { return lookup(table(), &Property::path, path); }
const Block* find_block(std::string_view name) { return lookup(block_table(), &Block::name, name); }
const Texture* find_texture_path(std::string_view path) { return lookup(texture_table(), &Texture::path, path); }

bool present(const Property& p, const Material& m) {
    if (p.block.empty()) return true;
    const Block* b = find_block(p.block);
    return b && b->present(m);
}

bool changed(const Property& p, const Material& was, const Material& now) {
    return present(p, now) && (!present(p, was) || !same(p, p.get(now), p.get(was)));
}

bool editable(const Property& p, const Material& m) {
    if (!present(p, m)) return false;
    std::size_t slash = p.path.rfind('/');
    if (slash == std::string_view::npos) return true;
    const Texture* t = find_texture_path(p.path.substr(0, slash));
    return !t || (t->get(m) && t->get(m)->valid());
}

std::string expected(const Property& p) {
    switch (p.type) {
        case Type::Bool: return "true or false";
        case Type::Choice: {
            std::string s;
            for (std::size_t i = 0; i < p.choices.size(); ++i)
                s += std::string(i == 0 ? "" : i + 1 == p.choices.size() ? " or " : ", ") + std::string(p.choices[i]);
            return s;
        }
        case Type::Color:
            return std::string(p.width == 4 ? "R,G,B,A" : "R,G,B") + range_text(p);
        case Type::Number:
            return (p.width == 1 ? std::string("a number") : std::to_string(p.width) + " numbers") + range_text(p) +
                   (p.unit.empty() ? "" : " (" + std::string(p.unit) + ")");
    }
    return "";
}

std::string check(const Property& p, const Value& v) {
    for (int i = 0; i < p.width; ++i) {
        float x = v[std::size_t(i)];
        if (std::isnan(x)) return expected(p);
        if (p.type == Type::Bool && x != 0.0f && x != 1.0f) return expected(p);
        if (p.type == Type::Choice && (x != std::floor(x) || x < 0 || x >= float(p.choices.size()))) return expected(p);
        // Infinity only where it is the default (attenuationDistance: no absorption).
        if (std::isinf(x) && x != p.fallback[std::size_t(i)]) return expected(p);
        if (x < p.min || x > p.max) return expected(p);
    }
    return "";
}

Value from_floats(const Property& p, std::span<const float> values, const std::string& where) {
    Value v{};
    std::string got;
    for (std::size_t i = 0; i < values.size(); ++i) got += (i ? "," : "") + shortest_text(values[i]);
    if (int(values.size()) != p.width) throw Error(where, "", "expected " + expected(p) + ", got '" + got + "'");
    for (std::size_t i = 0; i < values.size(); ++i) v[i] = values[i];
    if (!check(p, v).empty()) throw Error(where, "", "expected " + expected(p) + ", got '" + got + "'");
    return v;
}

Value parse(const Property& p, std::string_view text, const std::string& where) {
    auto fail = [&]() -> Value {
        throw Error(where, "", "expected " + expected(p) + ", got '" + std::string(text) + "'");
    };
    Value v{};
    if (p.type == Type::Bool) {
        if (text == "true" || text == "1" || text == "on") v[0] = 1;
        else if (text == "false" || text == "0" || text == "off") v[0] = 0;
        else return fail();
        return v;
    }
    if (p.type == Type::Choice) {
        for (std::size_t i = 0; i < p.choices.size(); ++i)
            if (p.choices[i] == text) {
                v[0] = float(i);
                return v;
            }
        return fail();
    }
    std::vector<float> numbers;
    std::size_t at = 0;
    while (at <= text.size()) {
        std::size_t next = text.find_first_of(", ", at);
        std::string_view token = text.substr(at, next == std::string_view::npos ? std::string_view::npos : next - at);
        if (!token.empty()) {
            float x = 0;
            if (!parse_number(token, x) || numbers.size() >= 4) return fail();
            numbers.push_back(x);
        }
        if (next == std::string_view::npos) break;
        at = next + 1;
    }
    if (int(numbers.size()) != p.width) return fail();
    for (std::size_t i = 0; i < numbers.size(); ++i) v[i] = numbers[i];
    if (!check(p, v).empty()) return fail();
    return v;
}

std::string format(const Property& p, const Value& v) {
    if (p.type == Type::Bool) return v[0] != 0.0f ? "true" : "false";
    if (p.type == Type::Choice) {
        std::size_t i = std::size_t(std::max(0.0f, v[0]));
        return i < p.choices.size() ? std::string(p.choices[i]) : std::string("?");
    }
    std::string s;
    for (int i = 0; i < p.width; ++i) s += (i ? "," : "") + shortest_text(v[std::size_t(i)]);
    return s;
}

bool same(const Property& p, const Value& a, const Value& b) {
    for (int i = 0; i < p.width; ++i)
        if (a[std::size_t(i)] != b[std::size_t(i)]) return false;
    return true;
}

void set(Material& m, std::string_view name, std::string_view text, const std::string& where) {
    const Property* p = find(name);
    if (!p) throw Error(where, "", "unknown material property '" + std::string(name) + "' (fresnel settings lists them)");
    p->put(m, parse(*p, text, where + " " + std::string(name)));
}

namespace {
std::string json_number(float v) { return std::isfinite(v) ? shortest_text(v) : "null"; }
const char* type_name(Type t) {
    switch (t) {
        case Type::Number: return "number";
        case Type::Color: return "color";
        case Type::Bool: return "bool";
        case Type::Choice: return "choice";
    }
    return "";
}
}  // namespace

std::string describe_json() {
    std::string out = "{\"properties\":[";
    for (const Property& p : table()) {
        if (&p != &table().front()) out += ",";
        out += "\n{\"name\":" + json_string(p.name) + ",\"path\":" + json_string(p.path) + ",\"block\":" + json_string(p.block) +
               ",\"type\":\"" + type_name(p.type) + "\",\"width\":" + std::to_string(p.width) +
               ",\"min\":" + json_number(p.min) + ",\"max\":" + json_number(p.max) +
               ",\"sliderMin\":" + json_number(p.slider_min) + ",\"sliderMax\":" + json_number(p.slider_max) +
               ",\"default\":" + json_string(format(p, p.fallback)) + ",\"animatable\":" + (p.animatable ? "true" : "false") +
               ",\"unit\":" + json_string(p.unit) + ",\"choices\":[";
        for (std::size_t i = 0; i < p.choices.size(); ++i) out += (i ? "," : "") + json_string(p.choices[i]);
        out += "],\"expected\":" + json_string(expected(p)) + ",\"doc\":" + json_string(p.doc) + "}";
    }
    out += "\n],\"blocks\":[";
    for (const Block& b : block_table())
        out += std::string(&b == &block_table().front() ? "" : ",") + "\n{\"name\":" + json_string(b.name) +
               ",\"doc\":" + json_string(b.doc) + "}";
    return out + "\n]}\n";
}

}  // namespace fresnel::material_properties
