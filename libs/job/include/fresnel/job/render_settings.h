#pragma once
// What a frame looks like, independent of the renderer that draws it: the size, the samples,
// exposure and tone mapping, the background, the shading model, the debug channel, fog and
// the environment's use. The rasteriser (fresnel/render/renderer.h) draws a frame with these;
// the path tracer (fresnel/trace) writes its output through the same tone mapping and encoding.
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/core/color.h"
#include "fresnel/core/image.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/material/brdf_model.h"
#include "fresnel/material/legacy_shading.h"
#include "fresnel/material/material.h"

namespace fresnel {

enum class DebugChannel {
    None = 0, BaseColor, Metallic, Roughness, Normal, GeometryNormal, Tangent, Bitangent, Occlusion, Emissive,
    Alpha, Uv0, Uv1, D, G, F, Diffuse, Specular, Irradiance, Prefiltered, IblDiffuse, IblSpecular,
    Transmission, Thickness,  // KHR_materials_transmission factor, KHR_materials_volume thickness (0..1)
    Sheen, SheenRoughness,  // KHR_materials_sheen: colour (sRGB), roughness (grey)
    Anisotropy, AnisotropyDirection,  // KHR_materials_anisotropy: strength (grey), direction (RG = xy * 0.5 + 0.5)
    Iridescence = 28,      // KHR_materials_iridescence strength (grey)
    IridescenceThickness,  // the film's thickness in micrometres (grey, 1 = 1000 nm and above)
    DiffuseTransmission = 30,  // KHR_materials_diffuse_transmission factor (grey)
    DiffuseTransmissionColor,  // its colour (sRGB)
    DiffuseRoughness = 32,     // KHR_materials_diffuse_roughness (grey; 0: Lambert)
};
std::optional<DebugChannel> parse_debug_channel(const std::string& name);
std::vector<std::string> debug_channel_names();

// The shading model (`fresnel render --shading`), for the whole frame or per material:
//   Gltf: the glTF specification's BRDF (pbr.frag), tone mapped and display-encoded.
//   Ogl1: OpenGL 1's fixed-function lighting exactly, per vertex (Gouraud), with texture
//     modulation (texels as stored) and fog, written straight to the display (no tone
//     mapping, no encoding); a light of intensity I acts as an OpenGL light of colour I.
//   Ogl1Pixel: the same per fragment.
//   BlinnPhongNormalized: the normalized Blinn-Phong microfacet model (legacy_shading.h)
//     with its image-based path, tone mapped and encoded like Gltf.
//   Auto: per material, Ogl1 for classic Phong (MTL) materials, Gltf for the rest.
// The legacy models (legacy.vert / legacy.frag) take their inputs from legacy_phong() and
// blinn_phong_material() (fresnel/material/phong.h).
enum class ShadingModel { Auto = 0, Gltf, Ogl1, Ogl1Pixel, BlinnPhongNormalized };
std::optional<ShadingModel> parse_shading_model(const std::string& name);
const char* shading_model_name(ShadingModel model);
// The model a material is drawn with when the frame asks for `frame`.
ShadingModel material_shading(ShadingModel frame, const Material& material);
inline bool is_ogl1(ShadingModel m) { return m == ShadingModel::Ogl1 || m == ShadingModel::Ogl1Pixel; }

// OpenGL 1 fog (GL_FOG on the eye-plane distance |z_eye|, legacy_shading.h), drawn by the
// Ogl1 models only. start/end unset: the camera's near/far clip distances.
struct Fog {
    legacy::FogMode mode = legacy::FogMode::None;
    std::optional<float> start, end;  // linear
    float density = 1.0f;             // exp, exp2
    glm::vec3 color{0.0f};            // display-referred, as written
    bool operator==(const Fog&) const = default;
};

// The default most probes of the detail maps' anisotropic filter (RenderSettings::anisotropy).
// The Khronos Sample Viewer asks for 16, but on a software rasteriser every probe is paid for
// by a whole pixel vector, and past 6 the probes changed no Khronos reference view by more
// than 0.01 dB (34 views, 4 to 16 probes) while costing DamagedHelmet's 1024^2 frame 7-16 %
// (docs/performance.md).
inline constexpr float kDefaultAnisotropy = 6.0f;

// Shadows of punctual lights in the rasteriser (`--shadows`): none, hard (one bilinear
// depth comparison per light, the hardware's 2x2 filter) or soft (four comparisons on a disk
// turned per pixel, a few texels wide: the edge of a point light's shadow anti-aliased, not
// widened). Directional lights use cascaded maps fitted to the view, spot lights a
// perspective map, point lights six (a cube), all tiles of one depth atlas (shadows.h).
enum class Shadows { Off = 0, Hard, Soft };
std::optional<Shadows> parse_shadows(const std::string& name);
const char* shadows_name(Shadows s);

// Occlusion of the environment's and the ambient light (`--ao`): off, baked per vertex with the
// tracer's rays once per scene (fresnel/trace/vertex_occlusion.h), or screen-space (ground-truth
// ambient occlusion from the frame's depth, every frame: shaders/ssao.frag).
enum class AmbientOcclusion { Off = 0, Baked, ScreenSpace };
// The environment's dominant light (`--env-light`): part of the image-based light (off), or taken
// out of it and drawn as a directional light with shadows (dominant; fresnel/ibl/dominant_light.h).
enum class EnvLight { Off = 0, Dominant };
std::optional<EnvLight> parse_env_light(const std::string& name);
const char* env_light_name(EnvLight e);
std::optional<AmbientOcclusion> parse_ambient_occlusion(const std::string& name);
const char* ambient_occlusion_name(AmbientOcclusion ao);

struct RenderSettings {
    int width = 1024, height = 768;
    int msaa = 4;
    // Anisotropic filtering of the detail maps (base colour, metallic-roughness, normal,
    // specular colour, clearcoat normal, sheen colour) with trilinear samplers: at most this
    // many probes along the footprint's major axis; 1 = off.
    float anisotropy = kDefaultAnisotropy;
    float exposure_ev = 0.0f;
    ToneMapper tone_mapper = ToneMapper::Neutral;
    // Display encoding; nullopt = none (float output: exposure and tone map only).
    std::optional<Encoding> encoding = Encoding::Srgb;
    glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};  // display-referred RGB; a = 0: transparent
    bool straight_alpha = true;  // transparent frames: un-premultiply (PNG); false keeps premultiplied (EXR)
    // Storage of the multisampled frame. Float (the default): half float, so render() reads
    // back the display values (or, without an encoding, the radiance) unquantised. Display8:
    // 8 bits a channel, as a display's canvas (the Khronos Sample Viewer's WebGL canvas), for
    // frames that end as 8-bit display values (a PNG, a window): half the memory of Float and
    // faster on a software rasteriser (fewer bytes written per sample). Each sample is then
    // clamped to [0, 1] and quantised before the MSAA resolve averages them, so a resolved
    // pixel is within 1/255 of the Float frame's. Used only where the frame has a display
    // encoding, is opaque and shows no debug channel; otherwise the frame is Float.
    enum class FrameFormat { Float, Display8 } frame_format = FrameFormat::Float;
    DebugChannel debug = DebugChannel::None;
    glm::vec3 ambient{0.0f};  // uniform ambient radiance added to diffuse (default none); Ogl1: GL_LIGHT_MODEL_AMBIENT
    ShadingModel shading = ShadingModel::Auto;
    Fog fog;  // Ogl1 models only
    // The glTF model's BRDF terms for punctual lights (`--brdf`; brdf_model.h). The default
    // is the specification's; image-based light always uses the split sum of the default.
    brdf::BrdfModel brdf;

    // Image-based light (nullptr = none). Baked by libs/ibl; must outlive the call.
    const ibl::BakedIbl* environment = nullptr;
    float env_intensity = 1.0f;
    float env_rotation_deg = 0.0f;  // turns the environment about +Y
    // Background: the colour above, or the environment (sharp, or blurred = a prefiltered level).
    enum class Background { Color, Environment, Blurred } background_mode = Background::Color;
    float blur_roughness = 0.6f;  // the prefiltered level shown as the blurred background
    // The split-sum table (for energy compensation of punctual lights); when null the
    // environment's table is used, else compensation is off.
    const ImageF* brdf_lut = nullptr;
    bool energy_compensation = true;
    // Shadows of punctual lights: the filter, each map's size (texels a side; the atlas shrinks
    // tiles that would not fit the GPU's texture size) and a directional light's cascades.
    Shadows shadows = Shadows::Soft;
    // Screen-space ambient occlusion (--ao ssao): its radius in world units (0: a quarter of
    // the scene's bounding radius).
    bool ssao = false;
    float ssao_radius = 0.0f;
    int shadow_map_size = 2048;
    int shadow_cascades = 2;
    // Skin and morph on the GPU, from the scene's current nodes (fresnel::animate, then
    // Renderer::update_transforms): skinned meshes by their joints' world matrices times the
    // inverse bind matrices (skins of at most kMaxShaderJoints joints), morph targets (at most
    // kMaxShaderMorphTargets per primitive) at the node's weights. Off (the default): meshes
    // are drawn as uploaded, skins in their bind pose (the Khronos reference images'
    // convention) or as posed on the CPU (fresnel/scene/pose.h). gpu_animatable() says
    // whether a scene fits the limits.
    bool gpu_animation = false;
    // Detail maps that share UV set, transform, size and probe limit read their anisotropic
    // probes through one footprint computed once (feature::DetailSharedFootprint): the same
    // image, faster. false computes one per map (tests compare the two).
    bool share_footprints = true;
    // An opaque material's metallic-roughness texture read from alpha channels it does not
    // read, where its maps share UV set, transform, sampler and size
    // (feature::MetallicRoughnessInAlpha): metallic in the base colour texture's alpha,
    // roughness in the normal texture's, and an occlusion packed with them in the emissive
    // texture's. One texture fewer for every fragment to probe (DamagedHelmet: ~15 % of the
    // frame). The same image, except that an occlusion in the emissive's alpha is filtered as
    // the emissive is, without anisotropy (the rule for low-frequency maps; DamagedHelmet
    // agrees with the Khronos references as well on average, docs/performance.md). false
    // reads the textures as stored (tests compare the two).
    bool pack_channels = true;
    // Placements of one primitive with one material (repeated meshes of the scene graph,
    // EXT_mesh_gpu_instancing's instances) drawn by one instanced draw, their model matrices as
    // per-instance attributes (feature::Instanced), in the frame and in each shadow map; skinned,
    // morphed, blended, transmissive and legacy-shaded draws go one at a time. The same image.
    // false draws every placement on its own (tests compare the two).
    bool instancing = true;
    // Draws whose box lies outside the view (all eight corners beyond one clip plane) are not
    // submitted; shadow maps still see them. false submits every draw (tests compare).
    bool frustum_culling = true;
    // Texture units a draw may use: 0 is the context's fragment limit
    // (gpu::Capabilities::max_fragment_texture_units; OpenGL 3.3 and ES 3.0 guarantee 16), a
    // smaller value (at least 16) stands in for a smaller GPU (tests). A glTF draw takes one
    // unit per map it reads and up to six for the transmitted scene, the split-sum table and
    // the environment's cubes; a material that needs more leaves its last maps (in MaterialMap
    // order: the newest extensions' first) unread and counts in FrameStats::unit_limited_draws.
    int max_texture_units = 0;
};

}  // namespace fresnel
