#pragma once
// The forward renderer: uploads a Scene to the GPU once, then renders frames into a
// multisampled target, each sample already exposed, tone mapped and display-encoded
// (pbr.frag, sky.frag; the background colour is cleared as given), resolves it, and runs
// the output pass (un-premultiplied alpha for transparent PNGs, NaN / Inf as magenta).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "fresnel/core/color.h"
#include "fresnel/core/image.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/material/brdf_model.h"
#include "fresnel/material/legacy_shading.h"
#include "fresnel/material/material.h"
#include "fresnel/render/camera.h"
#include "fresnel/render/lights.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

namespace gpu {
class Context;
}

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
    // Texture units a draw may use: 0 is the context's fragment limit
    // (gpu::Capabilities::max_fragment_texture_units; OpenGL 3.3 and ES 3.0 guarantee 16), a
    // smaller value (at least 16) stands in for a smaller GPU (tests). A glTF draw takes one
    // unit per map it reads and up to six for the transmitted scene, the split-sum table and
    // the environment's cubes; a material that needs more leaves its last maps (in MaterialMap
    // order: the newest extensions' first) unread and counts in FrameStats::unit_limited_draws.
    int max_texture_units = 0;
};

// Whether every skin and morphed primitive of `scene` fits RenderSettings::gpu_animation's
// limits (otherwise pose it on the CPU: fresnel::animated_scene).
bool gpu_animatable(const Scene& scene);

// Where a frame goes. Every frame is drawn into the renderer's own multisampled HDR target;
// the output pass (resolve, un-premultiply, NaN check) then writes it to the offscreen
// float image that render() reads back, to the offscreen 8-bit image that render8() reads
// back, or into the context's default framebuffer (a window's, which the caller then
// presents; a GUI can draw on top first), at a viewport origin.
struct RenderTarget {
    enum class Kind { Offscreen, Offscreen8, DefaultFramebuffer } kind = Kind::Offscreen;
    int x = 0, y = 0;  // DefaultFramebuffer: the viewport's lower-left corner (size = RenderSettings)
    // DefaultFramebuffer: when set, only the pixels of this rectangle (x, y, width, height in
    // framebuffer pixels, lower-left origin) are written; a split view draws a second frame
    // with other settings over part of the first.
    struct Rect {
        int x = 0, y = 0, width = 0, height = 0;
    };
    std::optional<Rect> scissor;
    static RenderTarget offscreen() { return {}; }
    static RenderTarget offscreen8() { return {Kind::Offscreen8, 0, 0, {}}; }
    static RenderTarget default_framebuffer(int x = 0, int y = 0) { return {Kind::DefaultFramebuffer, x, y, {}}; }
};

struct FrameStats {
    int draw_calls = 0;
    std::size_t triangles = 0;
    std::string gl_errors;  // empty when none
    // This frame (re)built its multisampled targets: a new size, sample count or frame format
    // (each format keeps its own, so frames alternating between two formats rebuild nothing).
    bool targets_rebuilt = false;
    // Draws whose detail maps shared one anisotropic footprint (RenderSettings::share_footprints).
    int shared_footprint_draws = 0;
    // Draws that read their metallic-roughness texture from alpha channels (RenderSettings::pack_channels).
    int alpha_packed_draws = 0;
    // Draws that left maps unread for want of texture units (RenderSettings::max_texture_units).
    int unit_limited_draws = 0;
};

class Renderer {
public:
    explicit Renderer(gpu::Context& context);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads meshes and textures of `scene` (index -1: its default scene). The scene
    // must outlive the renderer's use of it.
    void set_scene(const Scene& scene, int scene_index = -1);
    // Reads the scene's node transforms again (after fresnel::animate changed them in place);
    // meshes and textures stay uploaded.
    void update_transforms();

    // Renders one frame. The result: RGBA floats, rows top to bottom; display-encoded
    // values in [0,1] when settings.encoding is set, linear otherwise.
    ImageF render(const CameraSetup& camera, const std::vector<LightInstance>& lights, const RenderSettings& settings,
                  FrameStats* stats = nullptr);
    // Renders one frame into the 8-bit offscreen target (RenderTarget::offscreen8) and reads it
    // back: for display-encoded frames (PNG files, thumbnails), a quarter of render()'s bytes.
    // The GPU quantises as to_image8 does (round to nearest; values clamped to [0, 1]), so the
    // two agree to one step at rounding ties. RGBA with `alpha`, else RGB; rows top to bottom.
    Image8 render8(const CameraSetup& camera, const std::vector<LightInstance>& lights, const RenderSettings& settings,
                   bool alpha, FrameStats* stats = nullptr);

    // Draws a frame into the renderer's output target without reading it back (for
    // timing, and for windows that present it). finish() waits until the GPU is done.
    void draw(const CameraSetup& camera, const std::vector<LightInstance>& lights, const RenderSettings& settings,
              FrameStats* stats = nullptr);
    // The same, into `target` (a window's default framebuffer, to present).
    void draw(const CameraSetup& camera, const std::vector<LightInstance>& lights, const RenderSettings& settings,
              const RenderTarget& target, FrameStats* stats = nullptr);
    void finish();

    // Number of shader variants compiled so far (they are cached by feature set).
    std::size_t program_count() const;
    // Bytes of texel storage the renderer holds on the GPU: the scene's textures, the
    // environment's maps and tables, and the render targets (textures; renderbuffers aside).
    std::size_t texture_bytes() const;

    // The uploaded texture of the scene's texture `texture` (for a GUI's thumbnails): the
    // GPU layer's texture name and size; nothing when the renderer has not uploaded it. The
    // linear upload is preferred; a texture only materials read as sRGB gives that one.
    // A metallic-roughness texture and an occlusion stored together (`packed`: the occlusion's
    // R channel in the metallic-roughness texture's R) preview as that one texture; a texture
    // uploaded only with another's channel in its alpha (RenderSettings::pack_channels) previews
    // so, `packed` too, and a metallic-roughness texture spread over alphas has no preview.
    struct TexturePreview {
        unsigned id = 0;
        int width = 0, height = 0;
        bool srgb = false;
        bool packed = false;
    };
    std::optional<TexturePreview> texture_preview(int texture) const;

    // Development (`fresnel view --shaders DIR`): shader files from `folder` (a copy of
    // shaders/) instead of the embedded ones. reload_shaders() reads them again and recompiles
    // every program, all or nothing: on an error the programs stay as they were and the error
    // (file, compiler log) is returned; "" when they all compiled.
    void set_shader_folder(const std::string& folder);
    std::string reload_shaders();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Converts a rendered display-encoded image to 8-bit (RGB, or RGBA when `alpha`).
Image8 to_image8(const ImageF& image, bool alpha);

}  // namespace fresnel
