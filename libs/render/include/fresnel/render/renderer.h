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

#include "fresnel/core/image.h"
#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/job/render_settings.h"
#include "fresnel/render/limits.h"
#include "fresnel/scene/scene.h"
#include "fresnel/scene/vertex_occlusion.h"

namespace fresnel {

namespace gpu {
class Context;
}



// Whether every skin and morphed primitive of `scene` fits RenderSettings::gpu_animation's
// limits (kMaxGpuSkinJoints, kMaxGpuMorphTargets: fresnel/render/limits.h); otherwise pose it
// on the CPU (fresnel::animated_scene), and `why` (if given) names the first that does not.
bool gpu_animatable(const Scene& scene, std::string* why = nullptr);

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
    // Shadow maps drawn this frame (RenderSettings::shadows): 0 when the frame has none or kept
    // the last frame's, whose lights, casters and view gave the same maps.
    int shadow_tiles_drawn = 0;
    // Primitives skinned and morphed by the vertex shader this frame (RenderSettings::gpu_animation;
    // a scene past gpu_animatable's limits is drawn as uploaded, to be posed on the CPU).
    int gpu_skinned_draws = 0;
    int gpu_morphed_draws = 0;
    // Instanced draws this frame (RenderSettings::instancing; the frame's and the shadow maps')
    // and the placements they drew; placements left out of the frame because their boxes lie
    // outside the view (RenderSettings::frustum_culling).
    int instanced_draws = 0;
    std::size_t instances_drawn = 0;
    int culled_draws = 0;
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
    // What set_scene does with the scene's decoded images once their textures are on the GPU.
    enum class ImageResidency {
        Keep,     // nothing: the scene stays as loaded (the viewer, batch, Python)
        // Each image whose encoded bytes the loader kept (SceneImage::encoded) is released
        // (SceneImage::release_pixels) as soon as the textures made from it are uploaded, so the
        // GPU driver's copies reuse its memory (a one-shot render: llvmpipe's texture storage is
        // process memory). A later texture that needs a released image (a frame with other
        // settings: a debug view, another shading model) decodes it again (decode_again).
        GpuOnly,
    };
    void set_scene(Scene& scene, int scene_index, ImageResidency residency);
    // Baked visibility of the environment per vertex (`--ao baked`: trace::bake_vertex_occlusion
    // of the scene set_scene uploaded, in its current pose), copied to the GPU: image-based and
    // ambient light at those vertices is occluded by it (with the material's occlusion texture,
    // the smaller of the two; pbr.frag). Placements with values draw one at a time (not
    // instanced). Null clears it; set_scene clears it too. Values for a primitive whose vertex
    // count differs are ignored.
    void set_vertex_occlusion(const VertexOcclusion* occlusion);
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
    // Bytes of texel storage the renderer holds on the GPU: the scene's textures (and its
    // joint and morph target tables), the environment's maps and tables, and the render
    // targets (textures; renderbuffers aside).
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
