#include "fresnel/job/render_settings.h"

#include <utility>

#include "fresnel/material/phong.h"

namespace fresnel {

namespace {
struct NamedChannel {
    const char* name;
    DebugChannel channel;
};
constexpr NamedChannel kChannels[] = {
    {"basecolor", DebugChannel::BaseColor}, {"metallic", DebugChannel::Metallic},
    {"roughness", DebugChannel::Roughness}, {"normal", DebugChannel::Normal},
    {"geometry-normal", DebugChannel::GeometryNormal}, {"tangent", DebugChannel::Tangent},
    {"bitangent", DebugChannel::Bitangent}, {"occlusion", DebugChannel::Occlusion},
    {"emissive", DebugChannel::Emissive}, {"alpha", DebugChannel::Alpha}, {"uv0", DebugChannel::Uv0},
    {"uv1", DebugChannel::Uv1}, {"D", DebugChannel::D}, {"G", DebugChannel::G}, {"F", DebugChannel::F},
    {"diffuse", DebugChannel::Diffuse}, {"specular", DebugChannel::Specular},
    {"irradiance", DebugChannel::Irradiance}, {"prefiltered", DebugChannel::Prefiltered},
    {"ibl-diffuse", DebugChannel::IblDiffuse}, {"ibl-specular", DebugChannel::IblSpecular},
    {"transmission", DebugChannel::Transmission}, {"thickness", DebugChannel::Thickness},
    {"sheen", DebugChannel::Sheen}, {"sheen-roughness", DebugChannel::SheenRoughness},
    {"anisotropy", DebugChannel::Anisotropy}, {"anisotropy-direction", DebugChannel::AnisotropyDirection},
    {"iridescence", DebugChannel::Iridescence}, {"iridescence-thickness", DebugChannel::IridescenceThickness},
    {"diffuse-transmission", DebugChannel::DiffuseTransmission},
    {"diffuse-transmission-color", DebugChannel::DiffuseTransmissionColor},
    {"diffuse-roughness", DebugChannel::DiffuseRoughness},
};
}  // namespace

std::optional<DebugChannel> parse_debug_channel(const std::string& name) {
    if (name == "none") return DebugChannel::None;
    for (const auto& c : kChannels)
        if (name == c.name) return c.channel;
    return std::nullopt;
}
namespace {
struct NamedModel {
    const char* name;
    ShadingModel model;
};
constexpr NamedModel kModels[] = {
    {"auto", ShadingModel::Auto}, {"gltf", ShadingModel::Gltf}, {"ogl1", ShadingModel::Ogl1},
    {"ogl1-pixel", ShadingModel::Ogl1Pixel}, {"blinn-phong-normalized", ShadingModel::BlinnPhongNormalized},
};
}  // namespace

std::optional<ShadingModel> parse_shading_model(const std::string& name) {
    for (const auto& m : kModels)
        if (name == m.name) return m.model;
    return std::nullopt;
}
const char* shading_model_name(ShadingModel model) {
    for (const auto& m : kModels)
        if (model == m.model) return m.name;
    return "auto";
}
namespace {
constexpr std::pair<const char*, Shadows> kShadows[] = {
    {"off", Shadows::Off}, {"hard", Shadows::Hard}, {"soft", Shadows::Soft}};
}
std::optional<Shadows> parse_shadows(const std::string& name) {
    for (const auto& [n, s] : kShadows)
        if (name == n) return s;
    return std::nullopt;
}
const char* shadows_name(Shadows shadows) {
    for (const auto& [n, s] : kShadows)
        if (shadows == s) return n;
    return "soft";
}

std::optional<AmbientOcclusion> parse_ambient_occlusion(const std::string& name) {
    if (name == "off") return AmbientOcclusion::Off;
    if (name == "baked") return AmbientOcclusion::Baked;
    if (name == "ssao") return AmbientOcclusion::ScreenSpace;
    return std::nullopt;
}
const char* ambient_occlusion_name(AmbientOcclusion ao) {
    return ao == AmbientOcclusion::Baked ? "baked" : ao == AmbientOcclusion::ScreenSpace ? "ssao" : "off";
}
std::optional<EnvLight> parse_env_light(const std::string& name) {
    if (name == "off") return EnvLight::Off;
    if (name == "dominant") return EnvLight::Dominant;
    return std::nullopt;
}
const char* env_light_name(EnvLight e) { return e == EnvLight::Dominant ? "dominant" : "off"; }

ShadingModel material_shading(ShadingModel frame, const Material& material) {
    if (frame != ShadingModel::Auto) return frame;
    return is_classic_phong(material) ? ShadingModel::Ogl1 : ShadingModel::Gltf;
}

std::vector<std::string> debug_channel_names() {
    std::vector<std::string> out;
    for (const auto& c : kChannels) out.push_back(c.name);
    return out;
}

}  // namespace fresnel
