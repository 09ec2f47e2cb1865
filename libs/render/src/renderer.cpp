// The rasteriser (fresnel/render/renderer.h). Long (~1250 lines) because the frame's passes
// (shadow-free opaque, transmission's opaque copy, transparent, background, resolve) share the
// per-frame state and draw lists; the parts with a concern of their own are already apart
// (shader_features, material_uniforms, uniform_blocks, gpu_scene, environment).
#include "fresnel/render/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <cassert>
#include <tuple>

#include "fresnel/core/error.h"
#include "fresnel/core/mipmap.h"
#include "fresnel/core/parallel.h"
#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/gpu/resources.h"
#include "fresnel/material/ltc.h"
#include "fresnel/material/phong.h"
#include "fresnel/material/transmission.h"
#include "details/material_uniforms.h"
#include "details/shader_features.h"
#include "details/shader_library.h"
#include "details/shadow_maps.h"
#include "fresnel/scene/mesh_ops.h"

namespace fresnel {

namespace {
constexpr int kMaxLights = kMaxShaderLights;

// Texture units of the passes with fixed layouts: the output pass, the sky and the legacy
// models' diffuse map read one texture each from unit 0; the legacy models' image-based light
// sits at the top of the 16 units OpenGL ES 3.0 guarantees. The glTF draws pack theirs
// (draw_primitive).
enum class TextureUnit : int {
    Frame = 0,             // the output pass's frame (multisampled or resolved)
    SkyEnvironment = 0,    // the background's cube map
    LegacyDiffuseMap = 0,  // OpenGL 1 and Blinn-Phong's diffuse texture
    // The Blinn-Phong image-based light. Its shader declares the split-sum table without
    // sampling it; the unit keeps that sampler off the cube maps' units all the same.
    BrdfLut = 13,
    SpecularEnvironment = 14,
    IrradianceEnvironment = 15,
};

enum Attr : unsigned { kPosition = 0, kNormal, kTangent, kUv0, kUv1, kColor, kJoints, kWeights };  // gpu::Program's names

struct GpuPrimitive {
    gpu::VertexArray vao;
    std::vector<gpu::Buffer> buffers;
    int count = 0;
    bool indexed = false;
    Topology topology = Topology::Triangles;
    int material = -1;
    bool has_normal = false, has_tangent = false, has_uv0 = false, has_uv1 = false, has_color = false;
    glm::vec3 center{0.0f};
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  // the POSITION box (shadow maps' fit)
    std::size_t triangles = 0;
    // GPU animation inputs (used with RenderSettings::gpu_animation): JOINTS_0/WEIGHTS_0, and
    // the displacements of up to kMaxShaderMorphTargets targets (morph_texture: a layer per
    // target and attribute, vertex v at texel (v % width, v / width); the first layer of the
    // POSITION, NORMAL and TANGENT ones, -1 where no target has that attribute) with the
    // weights the vertex data holds.
    bool has_skin = false;
    int morph_targets = 0;
    // Skinned or morphed, on the GPU or on the CPU (which moves the vertices, not the box): its
    // POSITION box does not bound it, so it is never culled.
    bool deformable = false;
    std::vector<float> applied_weights;
    gpu::Texture morph_texture;
    int morph_position_layer = -1, morph_normal_layer = -1, morph_tangent_layer = -1;
    // Instanced batches' placements (Renderer::Impl::upload_instances): made by the first batch
    // drawn, the VAO's per-instance attributes pointing into it, refilled by every batch.
    mutable gpu::Buffer instance_buffer;
    mutable bool instance_attributes = false;  // the VAO's per-instance attributes point into it
    // The baked occlusion buffer the VAO's attribute gpu::kOcclusionLocation reads (a placement's,
    // Renderer::Impl::occlusion), or null with the array off (submit sets it per draw).
    mutable const gpu::Buffer* occlusion_bound = nullptr;
};

// An instanced batch's per-instance attributes (pbr.vert's a_instance_model, a_instance_normal).
struct InstanceRecord {
    glm::mat4 model;
    glm::mat3 normal;  // inverse transpose of the model's upper 3x3
};
static_assert(sizeof(InstanceRecord) == 25 * sizeof(float));
constexpr std::size_t kInstanceNormalOffset = 16 * sizeof(float);

struct Draw {
    const GpuPrimitive* prim;
    glm::mat4 model;
    float depth;  // view-space distance, for sorting blended draws
    // Skinned on the GPU by these joint matrices, which joint_texture holds this frame.
    const std::vector<glm::mat4>* joints = nullptr;
    const gpu::Texture* joint_texture = nullptr;
    // Morphed on the GPU by the weight changes from Renderer::Impl::morph_weights[morph_weights]
    // on (prim->morph_targets of them, four to a vec4); -1: not morphed.
    int morph_weights = -1;
    std::uint32_t sequence = 0;  // scene order: ties in the depth sort keep it
    bool mirrored = false;       // det(model) < 0: clockwise triangles face front
    // Posed on the CPU in world space (Node::world_space_mesh): its POSITION box, which places
    // the node's rest pose, does not bound what is drawn.
    bool posed = false;
    // An instanced batch (RenderSettings::instancing): `instances` placements of the primitive
    // (0: this draw's `model` alone), their matrices Renderer::Impl::instance_data[instance_first]
    // on; `model` is the first one's.
    int instances = 0;
    std::uint32_t instance_first = 0;
    // Baked per-vertex occlusion of this placement (Renderer::set_vertex_occlusion), or null.
    // Such draws are not batched: the values are the placement's own.
    const gpu::Buffer* occlusion = nullptr;
};

gpu::Primitive to_gpu(Topology t) {
    switch (t) {
        case Topology::Points: return gpu::Primitive::Points;
        case Topology::Lines: return gpu::Primitive::Lines;
        case Topology::LineLoop: return gpu::Primitive::LineLoop;
        case Topology::LineStrip: return gpu::Primitive::LineStrip;
        case Topology::Triangles: return gpu::Primitive::Triangles;
    }
    return gpu::Primitive::Triangles;
}
}  // namespace

struct Renderer::Impl {
    gpu::Context& context;
    gpu::Device device;
    ShaderLibrary shaders;
    // The families of defines the renderer looks programs up by (ShaderLibrary::get_keyed),
    // besides the mesh variants: no strings are built per draw.
    enum ProgramFamily { kLegacyPrograms = 1, kBrdfPrograms, kOutputPrograms, kShadowPrograms };
    std::vector<Draw> opaque_draws, blended_draws, transmissive_draws;  // a frame's, storage kept
    // The frame's opaque draws in view, batched (batch_draws), and one shadow tile's; the
    // placements of their instanced batches. Storage kept.
    std::vector<Draw> visible_draws, shadow_draws;
    std::vector<InstanceRecord> instance_data;
    SkinMatrices skin_pose;  // GPU animation's joint matrices, storage kept
    // Per skin of the scene, its joint matrices as pbr.vert reads them (joint_texture_size),
    // refreshed every frame drawn with GPU animation (upload_joints); empty past the limit.
    std::vector<gpu::Texture> joint_textures;
    std::vector<glm::vec4> morph_weights;  // the frame's draws' morph weight changes, storage kept
    const Scene* scene = nullptr;
    int scene_index = -1;
    std::vector<NodeInstance> instances;
    std::vector<std::vector<GpuPrimitive>> meshes;
    // Baked occlusion (set_vertex_occlusion): by node, then by primitive of its mesh, a vertex
    // buffer of vec4s (bent normal, visibility), or an empty buffer where none was baked.
    std::vector<std::vector<gpu::Buffer>> occlusion;
    std::size_t occlusion_draw_count = 0;  // placements with a buffer
    const gpu::Buffer* occlusion_for(int node, std::size_t primitive) const {
        if (node < 0 || std::size_t(node) >= occlusion.size()) return nullptr;
        const std::vector<gpu::Buffer>& prims = occlusion[std::size_t(node)];
        return primitive < prims.size() && prims[primitive] ? &prims[primitive] : nullptr;
    }
    // Turns every VAO's occlusion array off (before the buffers it reads go).
    void unbind_occlusion() {
        for (auto& mesh : meshes)
            for (GpuPrimitive& p : mesh)
                if (p.occlusion_bound) {
                    p.vao.disable_attribute(gpu::kOcclusionLocation);
                    p.occlusion_bound = nullptr;
                }
    }

    // The multisampled frame's targets at one size, sample count and format, rebuilt when one
    // of those changes (ensure_targets).
    struct FrameTargets {
        int w = 0, h = 0, samples = -1;
        gpu::Renderbuffer msaa_color, msaa_depth;
        gpu::Framebuffer msaa_fb;
        gpu::Texture resolved;
        gpu::Framebuffer resolved_fb;
        // Desktop GL: the MSAA colour is a multisampled texture that the output pass resolves
        // itself (texelFetch of every sample), with no blit and no resolved copy in between; on
        // llvmpipe the blit's own shader was compiled again in every process (~100 ms of a
        // first frame). ES 3.0 has no multisampled textures: a renderbuffer, blitted.
        bool shader_resolve = false;
        gpu::Texture msaa_texture;
    };
    // One set per format (index 1: RGBA8, FrameFormat::Display8; 0: half float), so frames that
    // alternate between them (the viewer's split view with a debug channel on one side) keep
    // theirs instead of rebuilding both every frame.
    std::array<FrameTargets, 2> frame_targets;
    FrameTargets* targets = &frame_targets[0];  // this frame's
    // The output pass's image (what render() reads back), rebuilt when the size changes.
    int output_w = 0, output_h = 0;
    gpu::Texture output;
    gpu::Framebuffer output_fb;

    // KHR_materials_transmission (transmission.h): the opaque scene in linear radiance, drawn
    // before the transmissive primitives, which refract it. As the Khronos Sample Viewer: a
    // square 1024^2 RGBA8 target (linear values, clamped to 1 and quantised to 8 bits as
    // there; its mip levels are the roughness blur) with the frame's own view and
    // projection, multisampled like the frame and resolved, then mip-mapped by the driver.
    int transmission_samples = -1;
    gpu::Renderbuffer transmission_msaa_color, transmission_depth;
    gpu::Framebuffer transmission_msaa_fb, transmission_fb;
    gpu::Texture transmission_texture;
    bool transmission_ready = false;  // drawn this frame
    bool linear_pass = false;         // drawing the transmission pass: linear output

    void ensure_transmission_target(int samples) {
        if (samples == transmission_samples) return;
        transmission_samples = samples;
        const int size = transmission::kFramebufferSize;
        transmission_texture = gpu::Texture::create_2d(size, size, gpu::TextureFormat::RGBA8, nullptr, true);
        gpu::SamplerState ss;
        ss.min_filter = Filter::Linear;
        ss.mipmap = MipmapMode::Linear;
        ss.mag_filter = Filter::Nearest;
        ss.wrap_s = ss.wrap_t = Wrap::ClampToEdge;
        transmission_texture.set_sampler(ss);
        transmission_fb = gpu::Framebuffer();
        transmission_fb.attach_color(transmission_texture);
        transmission_depth = gpu::Renderbuffer(size, size, gpu::RenderbufferFormat::Depth24, samples);
        if (samples > 1) {
            transmission_msaa_color = gpu::Renderbuffer(size, size, gpu::RenderbufferFormat::RGBA8, samples);
            transmission_msaa_fb = gpu::Framebuffer();
            transmission_msaa_fb.attach_color(transmission_msaa_color);
            transmission_msaa_fb.attach_depth(transmission_depth);
            transmission_msaa_fb.check();
        } else {
            transmission_msaa_color = gpu::Renderbuffer();
            transmission_msaa_fb = gpu::Framebuffer();
            transmission_fb.attach_depth(transmission_depth);
        }
        transmission_fb.check();
    }

    // Image-based light on the GPU, re-uploaded when the environment or table changes.
    // Keyed by content (BakedIbl::content_hash, image_content_hash), not by address: a new
    // object holding the same environment uploads nothing, a reused address with new data does.
    std::uint64_t uploaded_env = 0;
    gpu::Texture env_specular;
    gpu::Texture env_irradiance;
    gpu::Texture env_sheen, charlie_lut;
    gpu::Texture env_background;  // BakedIbl::background (with a dominant light taken out), else none
    std::uint64_t uploaded_lut = 0;
    gpu::Texture lut_texture;

    // Every level of `cube` as an RGBA16F cube texture; none for an empty cube.
    static gpu::Texture upload_cube(const ibl::Cubemap& cube, bool immutable) {
        if (cube.size() <= 0) return {};
        gpu::Texture t = gpu::Texture::create_cube(cube.size(), gpu::TextureFormat::RGBA16F, int(cube.levels.size()), immutable);
        for (std::size_t l = 0; l < cube.levels.size(); ++l)
            for (int f = 0; f < 6; ++f)
                t.upload_cube_face(f, int(l), cube.levels[l].size, cube.levels[l].faces[std::size_t(f)].data());
        return t;
    }

    void ensure_environment(const RenderSettings& s) {
        std::uint64_t env_id = 0;
        if (s.environment)
            env_id = s.environment->content_hash ? s.environment->content_hash : ibl::baked_content_hash(*s.environment);
        if (s.environment && env_id != uploaded_env) {
            const bool immutable = context.capabilities().texture_storage;
            env_specular = upload_cube(s.environment->specular, immutable);
            env_irradiance = upload_cube(s.environment->irradiance_map, immutable);
            env_sheen = upload_cube(s.environment->sheen, immutable);
            env_background = upload_cube(s.environment->background, immutable);
            const ImageF& cl = s.environment->charlie_lut;
            charlie_lut = {};
            if (cl.width > 0) {
                charlie_lut = gpu::Texture::create_2d(cl.width, cl.height, gpu::TextureFormat::RGBA32F, cl.pixels.data(), false);
                charlie_lut.set_sampler(gpu::SamplerState::clamped(Filter::Linear));
            }
            uploaded_env = env_id;
        }
        const ImageF* lut = s.brdf_lut ? s.brdf_lut : (s.environment ? &s.environment->lut : nullptr);
        const std::uint64_t lut_id = lut ? ibl::image_content_hash(*lut) | 1u : 0;
        if (lut && lut_id != uploaded_lut) {
            lut_texture = gpu::Texture::create_2d(lut->width, lut->height, gpu::TextureFormat::RGBA32F,
                                                  lut->pixels.data(), false);
            lut_texture.set_sampler(gpu::SamplerState::clamped(Filter::Linear));
            uploaded_lut = lut_id;
        }
    }

    // The frame's punctual lights: `given`, and the environment's dominant light where its bake
    // took one out (--env-light dominant: BakedIbl::dominant_light) as a directional light, turned
    // with the environment and scaled by its intensity (the renderer's own vector: no allocation
    // once warm).
    std::vector<LightInstance> lights_with_environment;
    const std::vector<LightInstance>& frame_lights(const std::vector<LightInstance>& given, const RenderSettings& s) {
        if (!s.environment || !s.environment->dominant_light || given.size() >= std::size_t(kMaxFrameLights)) return given;
        const ibl::DominantLight& d = *s.environment->dominant_light;
        lights_with_environment.assign(given.begin(), given.end());
        LightInstance sun;
        sun.type = Light::Type::Directional;
        // env_rotation maps world directions to the environment's; its transpose maps back.
        sun.direction = -glm::normalize(glm::transpose(env_rotation(s)) * d.direction);
        sun.radiance = d.irradiance * s.env_intensity;
        // Its shadows are those of a disk as spread as the light it took out.
        sun.radius = d.angular_radius;
        lights_with_environment.push_back(sun);
        return lights_with_environment;
    }

    glm::mat3 env_rotation(const RenderSettings& s) const {
        // World -> environment: turning the environment by +angle about +Y samples it at -angle.
        float a = -s.env_rotation_deg * 3.14159265358979f / 180.0f;
        float c = std::cos(a), si = std::sin(a);
        return glm::mat3(c, 0, -si, 0, 1, 0, si, 0, c);
    }

    // What the frame compiles into its shaders (shader_features.h): the display transform,
    // none when linear (the transmission pass), and whether punctual lights are bound.
    static FrameVariant frame_variant(const RenderSettings& s, bool linear, bool lights = true) {
        if (linear) return {int(ToneMapper::None), -1, lights};
        return {int(s.tone_mapper), s.encoding ? int(*s.encoding) : -1, lights};
    }

    // linear: radiance without exposure, tone mapping or encoding (the transmission pass).
    void draw_sky(const CameraSetup& cam, const RenderSettings& s, bool linear = false) {
        gpu::PipelineState st;
        st.depth_test = false;
        st.depth_write = false;
        st.cull = gpu::Cull::None;
        device.apply(st);
        const gpu::Program& prog = shaders.get("fullscreen.vert", "sky.frag", 0, frame_variant(s, linear));
        prog.use();
        // The whole environment where the shading's cube lacks its dominant light (--env-light dominant).
        device.bind_texture(int(TextureUnit::SkyEnvironment), env_background ? env_background : env_specular);
        prog.set("u_specular_env", int(TextureUnit::SkyEnvironment));
        prog.set("u_inverse_view_projection", glm::inverse(cam.projection * cam.view));
        prog.set("u_env_rotation", env_rotation(s));
        prog.set("u_env_intensity", s.env_intensity);
        float levels = float(s.environment->specular.levels.size());
        prog.set("u_lod", s.background_mode == RenderSettings::Background::Blurred ? s.blur_roughness * (levels - 1.0f) : 0.0f);
        prog.set("u_exposure", linear ? 1.0f : exposure_scale(s.exposure_ev));
        device.draw_fullscreen();
    }

    explicit Impl(gpu::Context& c) : context(c), shaders(glsl_target(c.api())) {}

    // 1x1 white: stands in for a map a variant samples but the material lacks.
    std::unique_ptr<gpu::Texture> white_map;
    const gpu::Texture& white_texture() {
        if (!white_map) {
            const std::uint8_t px[4] = {255, 255, 255, 255};
            white_map = std::make_unique<gpu::Texture>(gpu::Texture::create_2d(1, 1, gpu::TextureFormat::RGBA8, px, false));
            gpu::SamplerState ss;
            ss.min_filter = ss.mag_filter = Filter::Nearest;
            ss.mipmap = MipmapMode::None;
            white_map->set_sampler(ss);
        }
        return *white_map;
    }

    // Where joint j's four columns lie in a skin's joint texture: texels 4 (j % kJointsPerRow)
    // to 4 (j % kJointsPerRow) + 3 of row j / kJointsPerRow (pbr.vert's joint_matrix).
    static glm::ivec2 joint_texture_size(std::size_t joints) {
        const int n = int(joints);
        return {4 * std::min(n, kJointsPerRow), (n + kJointsPerRow - 1) / kJointsPerRow};
    }
    // Writes a skin's joint matrices into its texture: whole rows, then the last one's start
    // (a glm::mat4 is its four columns, the four texels, in order). Nothing is allocated.
    static void upload_joints(gpu::Texture& texture, std::span<const glm::mat4> joints) {
        const int n = int(joints.size());
        const int rows = n / kJointsPerRow, rest = n % kJointsPerRow;
        if (rows > 0) texture.update_2d(0, 0, 4 * kJointsPerRow, rows, joints.data());
        if (rest > 0) texture.update_2d(0, rows, 4 * rest, 1, joints.data() + std::size_t(rows) * kJointsPerRow);
    }

    // A primitive's morph targets for the GPU (the layers of GpuPrimitive::morph_texture): up to
    // kMaxShaderMorphTargets targets of up to kMaxShaderMorphVertices vertices, and not where
    // flat normals were generated (they follow the faces, which only the CPU path recomputes).
    // A layer per target for each attribute some target has (zero where a target lacks it).
    // The texture itself is made by the first frame that morphs the primitive on the GPU
    // (upload_morph_texture): CPU posing, which gives the renderer every frame's posed scene,
    // and still frames never pay for it.
    static void plan_morph_targets(const Primitive& p, GpuPrimitive& g) {
        const std::size_t n = p.positions.size(), count = p.targets.size();
        if (count == 0 || count > std::size_t(kMaxShaderMorphTargets) || p.generated_normals || n == 0 ||
            n > std::size_t(kMaxShaderMorphVertices))
            return;
        using Attribute = std::vector<glm::vec3> MorphTarget::*;
        const Attribute attributes[3] = {&MorphTarget::positions, &MorphTarget::normals, &MorphTarget::tangents};
        int* firsts[3] = {&g.morph_position_layer, &g.morph_normal_layer, &g.morph_tangent_layer};
        int layers = 0;
        for (int a = 0; a < 3; ++a)
            for (const MorphTarget& t : p.targets)
                if ((t.*attributes[a]).size() == n) {
                    *firsts[a] = layers;
                    layers += int(count);
                    break;
                }
        if (layers == 0) return;  // no target moves anything
        g.morph_targets = int(count);
        g.applied_weights.assign(count, 0.0f);
        std::copy_n(p.applied_weights.begin(), std::min(count, p.applied_weights.size()), g.applied_weights.begin());
    }
    // Fills GpuPrimitive::morph_texture as plan_morph_targets laid it out (vertex v of a layer at
    // texel (v % width, v / width), width kMorphTextureWidth at most).
    static void upload_morph_texture(const Primitive& p, GpuPrimitive& g) {
        const std::size_t n = p.positions.size(), count = std::size_t(g.morph_targets);
        using Attribute = std::vector<glm::vec3> MorphTarget::*;
        const Attribute attributes[3] = {&MorphTarget::positions, &MorphTarget::normals, &MorphTarget::tangents};
        const int firsts[3] = {g.morph_position_layer, g.morph_normal_layer, g.morph_tangent_layer};
        const int layers = int(count) * int((firsts[0] >= 0) + (firsts[1] >= 0) + (firsts[2] >= 0));
        const int width = int(std::min<std::size_t>(n, kMorphTextureWidth));
        const int height = int((n + std::size_t(width) - 1) / std::size_t(width));
        const std::size_t layer_texels = std::size_t(width) * std::size_t(height);
        std::vector<float> texels(layer_texels * std::size_t(layers) * 4, 0.0f);
        for (int a = 0; a < 3; ++a) {
            if (firsts[a] < 0) continue;
            for (std::size_t k = 0; k < count && k < p.targets.size(); ++k) {
                const std::vector<glm::vec3>& d = p.targets[k].*attributes[a];
                if (d.size() != n) continue;
                float* layer = &texels[(std::size_t(firsts[a]) + k) * layer_texels * 4];
                for (std::size_t v = 0; v < n; ++v) std::copy_n(&d[v].x, 3, layer + 4 * v);
            }
        }
        g.morph_texture = gpu::Texture::create_data_2d_array(width, height, layers, texels.data());
    }

    // The units of the vertex shader's textures (the joint matrices, the morph targets): the
    // last two of the combined units, past every fragment shader's (unit_limit keeps them free).
    int joint_unit() const { return context.capabilities().max_texture_units - 1; }
    int morph_unit() const { return context.capabilities().max_texture_units - 2; }
    // Binds a draw's GPU animation inputs and sets their uniforms on `prog` (in use). After the
    // fragment's textures are bound: creating a texture (white_texture) unbinds the active unit.
    void bind_animation(const gpu::Program& prog, const Draw& d) {
        if (d.joint_texture) {
            device.bind_texture(joint_unit(), *d.joint_texture);
            prog.set("u_joint_matrices", joint_unit());
            prog.set("u_joint_count", int(d.joints->size()));
        }
        if (d.morph_weights >= 0) {
            const GpuPrimitive& p = *d.prim;
            device.bind_texture(morph_unit(), p.morph_texture);
            prog.set("u_morph_targets", morph_unit());
            prog.set("u_morph_target_count", p.morph_targets);
            prog.set("u_morph_position_layer", p.morph_position_layer);
            prog.set("u_morph_normal_layer", p.morph_normal_layer);
            prog.set("u_morph_tangent_layer", p.morph_tangent_layer);
            prog.set("u_morph_weights", std::span<const glm::vec4>(&morph_weights[std::size_t(d.morph_weights)],
                                                                   std::size_t(p.morph_targets + 3) / 4));
        }
    }

    void upload(const Scene& s) {
        meshes.clear();
        joint_textures.clear();
        for (const Skin& skin : s.skins)
            if (!skin.joints.empty() && skin.joints.size() <= std::size_t(kMaxShaderJoints)) {
                const glm::ivec2 size = joint_texture_size(skin.joints.size());
                joint_textures.push_back(gpu::Texture::create_data_2d(size.x, size.y, nullptr));
            } else {
                joint_textures.emplace_back();
            }
        textures.clear();
        material_buffers.clear();
        material_buffers.resize(s.materials.size() + 1);
        for (const auto& mesh : s.meshes) {
            std::vector<GpuPrimitive> prims;
            for (const auto& p : mesh.primitives) {
                GpuPrimitive g;
                g.topology = p.topology;
                g.material = p.material;
                g.triangles = p.triangle_count();
                g.center = (p.bounds_min + p.bounds_max) * 0.5f;
                g.bounds_min = p.bounds_min;
                g.bounds_max = p.bounds_max;
                auto add = [&](Attr slot, const void* data, std::size_t count, int comps) {
                    g.buffers.emplace_back(gpu::BufferKind::Vertex, data, count * std::size_t(comps) * sizeof(float));
                    g.vao.set_attribute(slot, g.buffers.back(), comps);
                };
                add(kPosition, p.positions.data(), p.positions.size(), 3);
                if ((g.has_normal = !p.normals.empty())) add(kNormal, p.normals.data(), p.normals.size(), 3);
                if ((g.has_tangent = !p.tangents.empty())) add(kTangent, p.tangents.data(), p.tangents.size(), 4);
                if ((g.has_uv0 = !p.uv0.empty())) add(kUv0, p.uv0.data(), p.uv0.size(), 2);
                if ((g.has_uv1 = !p.uv1.empty())) add(kUv1, p.uv1.data(), p.uv1.size(), 2);
                if ((g.has_color = !p.colors.empty())) add(kColor, p.colors.data(), p.colors.size(), 4);
                if (!p.joints.empty() && p.weights.size() == p.joints.size()) {
                    std::vector<glm::vec4> joints(p.joints.size());
                    for (std::size_t v = 0; v < joints.size(); ++v) joints[v] = glm::vec4(p.joints[v]);
                    add(kJoints, joints.data(), joints.size(), 4);
                    add(kWeights, p.weights.data(), p.weights.size(), 4);
                    g.has_skin = true;
                }
                plan_morph_targets(p, g);
                g.deformable = g.has_skin || !p.targets.empty();
                if (!p.indices.empty()) {
                    std::vector<std::uint32_t> sorted;
                    const std::vector<std::uint32_t>* indices = &p.indices;
                    if (sorts_by_uv(s, p)) {
                        sorted = p.indices;
                        sort_triangles_by_uv(sorted, p.uv0);
                        indices = &sorted;
                    }
                    g.buffers.emplace_back(gpu::BufferKind::Index, indices->data(), indices->size() * 4);
                    g.vao.set_indices(g.buffers.back());
                    g.indexed = true;
                    g.count = int(p.indices.size());
                } else {
                    g.count = int(p.positions.size());
                }
                prims.push_back(std::move(g));
            }
            meshes.push_back(std::move(prims));
        }
    }

    // Whether a primitive's triangles are drawn in UV order (sort_triangles_by_uv, mesh_ops.h):
    // indexed triangles with TEXCOORD_0 whose materials (its own and every KHR_materials_variants
    // one) read a texture and none blends, where the order is the picture's. The order is fixed
    // at set_scene: a material edited to blend afterwards (the viewer) blends in UV order.
    static bool sorts_by_uv(const Scene& s, const Primitive& p) {
        if (p.topology != Topology::Triangles || p.uv0.empty() || p.indices.size() < 6) return false;
        static const Material kDefaultMaterial{};
        bool textured = false;
        auto visit = [&](int index) {  // false: the material blends
            const Material& m = index >= 0 && std::size_t(index) < s.materials.size() ? s.materials[std::size_t(index)]
                                                                                      : kDefaultMaterial;
            if (m.alpha_mode == AlphaMode::Blend) return false;
            for (int i = 0; i < kMaterialMapCount && !textured; ++i)
                if (const TextureSlot* t = material_map(m, MaterialMap(i))) textured = t->valid();
            return true;
        };
        if (!visit(p.material)) return false;
        for (int v : p.variant_materials)
            if (v >= 0 && !visit(v)) return false;
        return textured;
    }

    // A GL texture: a scene texture's image as stored (source -1), or with its channel `to`
    // replaced by channel `from` of texture `source`'s image of the same size: the occlusion's R
    // in a metallic-roughness texture's R (occlusion_packs), the metallic-roughness channels in
    // alphas (alpha_packs).
    struct TextureKey {
        int texture = -1;
        bool srgb = false;
        int source = -1;
        int from = 0, to = 0;
        auto operator<=>(const TextureKey&) const = default;
        bool packed() const { return source >= 0; }
    };
    struct GpuTexture {
        gpu::Texture texture;
        bool mipmapped = false;
        float anisotropy = -1.0f;  // applied sampler anisotropy; -1 = sampler not set yet
        bool linear_min = false;   // minification forced to linear (shader anisotropy)
    };
    std::map<TextureKey, GpuTexture> textures;

    bool usable(const TextureSlot& ref) const {
        if (!ref.valid() || !scene || std::size_t(ref.texture) >= scene->textures.size()) return false;
        const Texture& tex = scene->textures[std::size_t(ref.texture)];
        return tex.image >= 0 && std::size_t(tex.image) < scene->images.size() &&
               scene->images[std::size_t(tex.image)].valid();
    }
    static bool wants_mipmaps(const Sampler& s) { return s.uses_mipmaps(); }

    // Whether material `m`'s occlusion can be read from the R channel of its metallic-roughness
    // texture (feature::OcclusionInMetallicRoughness): both maps usable, on the same UV set
    // through the same transform, textures with the same sampler and images of the same size.
    // Then the probes that read metallic and roughness read the occlusion's texels too: for
    // glTF's ORM packing (one texture) as they are, for two images once the occlusion's R
    // channel is copied into the metallic-roughness image (its R is unused), whose mip chain
    // (built per channel) then holds the occlusion's own levels. The occlusion texture to pack,
    // or -1.
    int occlusion_packs(const Material& m) const {
        if (m.specular_glossiness) return -1;
        const TextureSlot& mr = m.metallic_roughness;
        const TextureSlot& ao = m.occlusion;
        if (mr.texture == ao.texture && usable(mr) && mr.tex_coord == ao.tex_coord && mr.transform == ao.transform)
            return ao.texture;  // glTF's ORM packing: one texture already
        return stored_alike(mr, ao) ? ao.texture : -1;
    }
    // A texture's image as stored (its size; its pixels may have been released: pixels_of).
    const Image8& image_of(int texture) const {
        return scene->images[std::size_t(scene->textures[std::size_t(texture)].image)].pixels;
    }
    // A texture's image with its pixels: as loaded, or decoded again where set_scene released
    // them (ImageResidency::GpuOnly) and a texture not made then is asked for (kept until the
    // next set_scene).
    const Image8& pixels_of(int texture) const {
        const int image = scene->textures[std::size_t(texture)].image;
        const SceneImage& im = scene->images[std::size_t(image)];
        if (!im.released()) return im.pixels;
        std::lock_guard lock(redecode_mutex);
        auto it = redecoded.find(image);
        if (it == redecoded.end()) it = redecoded.emplace(image, decode_again(im)).first;
        return it->second;
    }
    mutable std::mutex redecode_mutex;
    mutable std::map<int, Image8> redecoded;  // image index -> its pixels decoded again
    Scene* releasing = nullptr;  // set_scene with ImageResidency::GpuOnly: the scene whose images upload_textures releases
    // Whether the texels of maps `a` and `b` can share one texture, channel by channel (the
    // renderer's packings, occlusion_packs and alpha_packs): both usable, on one UV set through
    // one transform, textures with one sampler and RGBA images of one size.
    bool stored_alike(const TextureSlot& a, const TextureSlot& b) const {
        if (!usable(a) || !usable(b) || a.tex_coord != b.tex_coord || a.transform != b.transform) return false;
        const Image8& ia = image_of(a.texture);
        const Image8& ib = image_of(b.texture);
        return scene->textures[std::size_t(a.texture)].sampler == scene->textures[std::size_t(b.texture)].sampler &&
               ia.channels == 4 && ib.channels == 4 && ia.width == ib.width && ia.height == ib.height;
    }
    // The level-0 image of a packed key: the texture's image with the source's channel copied in.
    Image8 packed_image(const TextureKey& key) const {
        Image8 out = pixels_of(key.texture);
        pack_into(out, key);
        return out;
    }
    // The source's channel copied into `out` (the texture's image, or a copy of it).
    void pack_into(Image8& out, const TextureKey& key) const {
        const Image8& src = pixels_of(key.source);
        for (std::size_t i = 0, n = std::size_t(out.width) * std::size_t(out.height); i < n; ++i)
            out.pixels[i * 4 + std::size_t(key.to)] = src.pixels[i * 4 + std::size_t(key.from)];
    }

    // Where an opaque metallic-roughness material's metallic-roughness texture can live in
    // alpha channels the material does not read (feature::MetallicRoughnessInAlpha): its B
    // (metallic) in the base colour texture's alpha, its G (roughness) in the normal texture's,
    // and, when the occlusion is packed with it (`occlusion`: occlusion_packs' texture, whose
    // R is the occlusion; -1 when it is not), the occlusion in the emissive texture's alpha.
    // All of those maps stored alike (stored_alike; the occlusion is, by occlusion_packs). The mip chains are built per channel and the alpha
    // linearly in sRGB textures too (build_mip_chain), so every level holds the metallic-
    // roughness texture's own texels: the probes of the base colour and normal maps read what
    // the metallic-roughness probes read, one texture fewer. The occlusion in the emissive is
    // filtered as the emissive (not a detail map: without anisotropy, as a low-frequency map).
    // The keys of the textures then bound, or nothing.
    struct AlphaPacking {
        TextureKey base_color, normal, emissive;  // emissive: with the occlusion only
    };
    std::optional<AlphaPacking> alpha_packs(const Material& m, int occlusion) const {
        if (m.specular_glossiness || m.alpha_mode != AlphaMode::Opaque) return std::nullopt;
        const TextureSlot& mr = m.metallic_roughness;
        if (!stored_alike(mr, m.base_color) || !stored_alike(mr, m.normal) ||
            (occlusion >= 0 && !stored_alike(mr, m.emissive)))
            return std::nullopt;
        AlphaPacking p;
        p.base_color = {m.base_color.texture, true, mr.texture, 2, 3};
        p.normal = {m.normal.texture, false, mr.texture, 1, 3};
        if (occlusion >= 0) p.emissive = {m.emissive.texture, true, occlusion, 0, 3};
        return p;
    }
    // The texture a material's map `map` (its `slot`) binds under the packings in force:
    // `occlusion`, the occlusion packed into the metallic-roughness texture (occlusion_packs)
    // or -1; `alpha`, the metallic-roughness texture in alpha channels (alpha_packs) or null,
    // under which the metallic-roughness map binds nothing.
    static TextureKey map_key(const Material& m, const TextureSlot& slot, MaterialMap map, int occlusion,
                              const AlphaPacking* alpha) {
        if (alpha && map == MaterialMap::BaseColor) return alpha->base_color;
        if (alpha && map == MaterialMap::Normal) return alpha->normal;
        if (alpha && occlusion >= 0 && map == MaterialMap::Emissive) return alpha->emissive;
        if (map == MaterialMap::MetallicRoughness)  // with the occlusion's R unless one texture has both
            return {slot.texture, false, occlusion >= 0 && occlusion != slot.texture ? occlusion : -1};
        return {slot.texture, map_srgb(m, map)};
    }

    // Creates the GL texture for `key` from the image and its CPU-built mip chain.
    // `packed`: the level-0 image when the key packs an occlusion (packed_image), else null.
    GpuTexture make_texture(const TextureKey& key, const std::vector<Image8>* chain, const Image8* packed = nullptr) {
        const Texture& tex = scene->textures[std::size_t(key.texture)];
        Image8 local_packed;
        if (key.packed() && !packed) {
            local_packed = packed_image(key);
            packed = &local_packed;
        }
        const Image8& img = packed ? *packed : pixels_of(key.texture);
        auto format = key.srgb ? gpu::TextureFormat::SRGB8_ALPHA8 : gpu::TextureFormat::RGBA8;
        GpuTexture g;
        g.mipmapped = wants_mipmaps(tex.sampler);
        std::vector<Image8> local;
        if (g.mipmapped && !chain) {
            local = build_mip_chain(img, key.srgb);
            chain = &local;
        }
        std::vector<gpu::MipLevel> levels{{img.width, img.height, img.pixels.data()}};
        if (g.mipmapped)
            for (const auto& l : *chain) levels.push_back({l.width, l.height, l.pixels.data()});
        g.texture = gpu::Texture::create_2d_levels(format, levels, context.capabilities().texture_storage);
        return g;
    }

    // Uploads every texture the scene's materials use, their mip chains built in
    // parallel on the CPU first.
    void upload_textures() {
        std::vector<TextureKey> keys;
        for (const auto& m : scene->materials) {
            const int packed = occlusion_packs(m);
            // As draw_primitive packs (the debug view, or a mesh without tangents for the normal
            // map, reads the textures as stored: those are uploaded when first drawn).
            const std::optional<AlphaPacking> alpha = alpha_packs(m, packed);
            for (int i = 0; i < kMaterialMapCount; ++i) {
                const MaterialMap map = MaterialMap(i);
                const TextureSlot* slot = material_map(m, map);
                if (!slot || !usable(*slot) || (packed >= 0 && map == MaterialMap::Occlusion)) continue;
                if (alpha && map == MaterialMap::MetallicRoughness) continue;
                keys.push_back(map_key(m, *slot, map, packed, alpha ? &*alpha : nullptr));
            }
        }
        std::sort(keys.begin(), keys.end());
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
        // A releasing set_scene (ImageResidency::GpuOnly) frees each image once nothing left
        // to upload reads it, so that the driver's copies reuse its memory: an image that one
        // packed key alone reads becomes that key's packed image in place (no copy: decode_again
        // gives the stored one back); the images only packed copies read, before the first
        // upload; the others after the last key that uploads them.
        auto image_of_key = [&](int texture) { return scene->textures[std::size_t(texture)].image; };
        std::map<int, int> readers;  // image -> keys that read it
        for (const TextureKey& k : keys) {
            ++readers[image_of_key(k.texture)];
            if (k.packed()) ++readers[image_of_key(k.source)];
        }
        std::vector<Image8*> in_place(keys.size(), nullptr);  // the scene's image packed in place
        std::map<int, std::size_t> release_after;  // image -> how many keys are uploaded when it goes
        if (releasing)
            for (std::size_t i = 0; i < keys.size(); ++i) {
                const int image = image_of_key(keys[i].texture);
                SceneImage& stored = releasing->images[std::size_t(image)];
                const bool own = keys[i].packed() && readers[image] == 1 && !stored.released() && stored.encoded;
                if (own) in_place[i] = &stored.pixels;
                std::size_t& after = release_after[image];
                if (!keys[i].packed() || own) after = std::max(after, i + 1);
                if (keys[i].packed()) release_after.try_emplace(image_of_key(keys[i].source), 0);
            }
        std::vector<std::vector<Image8>> chains(keys.size());
        std::vector<Image8> packed(keys.size());
        parallel_for(keys.size(), [&](std::size_t i) {
            const Texture& tex = scene->textures[std::size_t(keys[i].texture)];
            if (in_place[i]) pack_into(*in_place[i], keys[i]);
            else if (keys[i].packed()) packed[i] = packed_image(keys[i]);
            const Image8& img = in_place[i] ? *in_place[i] : keys[i].packed() ? packed[i] : pixels_of(keys[i].texture);
            if (wants_mipmaps(tex.sampler)) chains[i] = build_mip_chain(img, keys[i].srgb);
        });
        auto release = [&](std::size_t uploaded) {
            for (const auto& [image, after] : release_after)
                if (after == uploaded) releasing->images[std::size_t(image)].release_pixels();
        };
        if (releasing) release(0);
        for (std::size_t i = 0; i < keys.size(); ++i) {
            const Image8* level0 = in_place[i] ? in_place[i] : keys[i].packed() ? &packed[i] : nullptr;
            textures.emplace(keys[i], make_texture(keys[i], &chains[i], level0));
            chains[i] = {};
            packed[i] = {};
            if (releasing) release(i + 1);
        }
    }

    // Anisotropic filtering is a property of the map: it is what agrees with the Khronos
    // Sample Viewer's texture filtering on the detail maps, and each anisotropic lookup costs
    // a software rasteriser more probes, so the low-frequency maps (emissive, the scalar
    // extension maps) go without: measured over the Khronos reference views, that moves
    // agreement by <= 0.16 dB. The occlusion is filtered as the metallic-roughness map is,
    // since it is usually read from the same texels (occlusion_packs), unless it is read from
    // the emissive's (alpha_packs). The detail maps (MaterialMapInfo::detail) are filtered in the
    // shader (sample_detail_map, shaders/material_inputs.glsl; fresnel::evaluate's twin:
    // detail_footprint in material/texture.h).
    //
    // How a slot's texture is filtered anisotropically: not at all, by the sampler (GL's
    // TEXTURE_MAX_ANISOTROPY), or in the shader (sample_detail_map in material_inputs.glsl).
    enum class Anisotropic { Off, Sampler, Shader };

    // The GL texture for a material's slot with its sampler state, or nullptr when it has
    // no usable image. `anisotropy` applies to trilinear samplers with a linear magnification
    // filter; `shader_anisotropy` (if given) receives what the shader should apply (1: none).
    // In the shader, the probes are bilinear within a level whatever the sampler's minification
    // filter, as in SwiftShader (the Khronos references), so such samplers minify linearly.
    // `key`: the texture to bind when it is not (ref.texture, srgb) as stored (a packed one).
    const gpu::Texture* texture_for(const TextureSlot& ref, bool srgb, Anisotropic mode, float anisotropy,
                                    float* shader_anisotropy = nullptr, std::optional<TextureKey> packed_key = {}) {
        if (shader_anisotropy) *shader_anisotropy = 1.0f;
        if (!usable(ref)) return nullptr;
        TextureKey key = packed_key ? *packed_key : TextureKey{ref.texture, srgb};
        auto it = textures.find(key);
        if (it == textures.end()) it = textures.emplace(key, make_texture(key, nullptr)).first;
        GpuTexture& g = it->second;
        const Sampler& sampler = scene->textures[std::size_t(ref.texture)].sampler;
        float level = mode != Anisotropic::Off ? detail_anisotropy(sampler.mag_filter, sampler.mipmap, anisotropy) : 1.0f;
        float want = mode == Anisotropic::Sampler ? level : 1.0f;
        bool linear_min = mode == Anisotropic::Shader && level > 1.0f;
        if (shader_anisotropy && mode == Anisotropic::Shader) *shader_anisotropy = level;
        if (g.anisotropy != want || g.linear_min != linear_min) {
            gpu::SamplerState ss;
            ss.min_filter = linear_min ? Filter::Linear : sampler.min_filter;
            ss.mipmap = sampler.mipmap;
            ss.mag_filter = sampler.mag_filter;
            ss.wrap_s = sampler.wrap_s;
            ss.wrap_t = sampler.wrap_t;
            ss.max_anisotropy = want;
            g.texture.set_sampler(ss);
            g.anisotropy = want;
            g.linear_min = linear_min;
        }
        return &g.texture;
    }

    // Whether the base colour, metallic-roughness, occlusion and normal maps that `features`
    // reads (at least two of them) are the material's own textures, of one level-0 size, read
    // through one UV set and transform with one probe limit: then one footprint serves them
    // all (feature::DetailSharedFootprint) and the probes are those of one footprint each.
    // With the metallic-roughness in alpha channels (feature::MetallicRoughnessInAlpha) it has
    // no texture of its own.
    bool shares_detail_footprint(FeatureMask features, const gpu::Texture* const* bound, const MaterialUniforms& mu) {
        const MaterialBlock::Map* first = nullptr;
        const gpu::Texture* first_texture = nullptr;
        int count = 0;
        const bool in_alpha = features & feature::MetallicRoughnessInAlpha;
        for (MaterialMap map : {MaterialMap::BaseColor, MaterialMap::MetallicRoughness, MaterialMap::Occlusion,
                                MaterialMap::Normal}) {
            const int i = int(map);
            if (!(features & feature::map_bit(i))) continue;
            if (in_alpha && map == MaterialMap::MetallicRoughness) continue;
            if (!bound[i] || bound[i] == &white_texture()) return false;  // a stand-in: not worth a variant
            const MaterialBlock::Map& b = mu.block.maps[std::size_t(i)];
            if (first && (b.uv != first->uv || b.transform != first->transform || b.anisotropy != first->anisotropy ||
                          bound[i]->width() != first_texture->width() || bound[i]->height() != first_texture->height()))
                return false;
            if (!first) {
                first = &b;
                first_texture = bound[i];
            }
            ++count;
        }
        return count >= 2;
    }

    // Whether it (re)built the targets.
    bool ensure_targets(int w, int h, int samples, bool display8) {
        targets = &frame_targets[display8 ? 1 : 0];
        ensure_output(w, h);
        FrameTargets& t = *targets;
        if (w == t.w && h == t.h && samples == t.samples) return false;
        t.w = w;
        t.h = h;
        t.samples = samples;
        // HDR targets: float where the context renders to float (always on GL 3.3; on ES 3.0
        // with EXT_color_buffer_float, half float alone with EXT_color_buffer_half_float,
        // else 8-bit; the context logged the fallback when it was made). A Display8 frame
        // is 8-bit by choice.
        const gpu::Capabilities& caps = context.capabilities();
        const bool half = caps.half_float_color_targets && !display8;
        t.shader_resolve = caps.multisample_textures && samples > 1 && samples <= caps.max_color_texture_samples;
        t.msaa_depth = gpu::Renderbuffer(w, h, gpu::RenderbufferFormat::Depth24, samples);
        t.msaa_fb = gpu::Framebuffer();
        if (t.shader_resolve) {
            t.msaa_texture = gpu::Texture::create_2d_multisample(
                w, h, half ? gpu::TextureFormat::RGBA16F : gpu::TextureFormat::RGBA8, samples);
            t.msaa_fb.attach_color(t.msaa_texture);
            t.msaa_color = gpu::Renderbuffer();
            t.resolved_fb = gpu::Framebuffer();
            t.resolved = gpu::Texture();
        } else {
            t.msaa_color = gpu::Renderbuffer(w, h, half ? gpu::RenderbufferFormat::RGBA16F : gpu::RenderbufferFormat::RGBA8,
                                             samples);
            t.msaa_fb.attach_color(t.msaa_color);
            t.msaa_texture = gpu::Texture();
            t.resolved = gpu::Texture::create_2d(w, h, half ? gpu::TextureFormat::RGBA16F : gpu::TextureFormat::RGBA8,
                                                 nullptr, false);
            t.resolved.set_sampler(gpu::SamplerState::clamped(Filter::Nearest));
            t.resolved_fb = gpu::Framebuffer();
            t.resolved_fb.attach_color(t.resolved);
            t.resolved_fb.check();
        }
        t.msaa_fb.attach_depth(t.msaa_depth);
        t.msaa_fb.check();
        return true;
    }

    // The texture units a draw may use (RenderSettings::max_texture_units).
    // Two of the combined units stay for the vertex shader's textures (joint_unit, morph_unit).
    int unit_limit(const RenderSettings& settings) const {
        const gpu::Capabilities& caps = context.capabilities();
        const int limit = std::min(caps.max_fragment_texture_units, caps.max_texture_units - 2);
        return settings.max_texture_units > 0 ? std::clamp(settings.max_texture_units, 16, limit) : limit;
    }
    // The units a glTF draw of `features` takes besides its maps, as draw_primitive packs them:
    // the transmitted scene, the split-sum table, the environment's two cubes, sheen's cube and table.
    int fixed_units(FeatureMask features, const RenderSettings& settings) const {
        const bool env = settings.environment != nullptr;
        return ((features & feature::Transmission) ? 1 : 0) + 1 + (env ? 2 : 0) +
               ((features & feature::Sheen) && env && env_sheen && charlie_lut ? 2 : 0) + (frame_shadows > 0 ? 1 : 0) +
               (frame_shadows == kContactHardeningShadows ? 1 : 0) +
               (frame_area_lights ? 1 : 0) + (frame_ssao ? 1 : 0);
    }

    // Adds the GL errors raised since the last look to `stats` (if given).
    void note_errors(FrameStats* stats) {
        std::string errors = device.take_errors();
        if (stats && !errors.empty()) stats->gl_errors += (stats->gl_errors.empty() ? "" : ", ") + errors;
    }

    // The 8-bit output (RenderTarget::offscreen8), made on first use.
    gpu::Texture output8;
    gpu::Framebuffer output8_fb;
    int output8_w = 0, output8_h = 0;
    void ensure_output8(int w, int h) {
        if (w == output8_w && h == output8_h) return;
        output8_w = w;
        output8_h = h;
        output8 = gpu::Texture::create_2d(w, h, gpu::TextureFormat::RGBA8, nullptr, false);
        output8_fb = gpu::Framebuffer();
        output8_fb.attach_color(output8);
        output8_fb.check();
    }

    void ensure_output(int w, int h) {
        if (w == output_w && h == output_h) return;
        output_w = w;
        output_h = h;
        const gpu::Capabilities& caps = context.capabilities();
        output = gpu::Texture::create_2d(w, h,
                                         caps.float_color_targets         ? gpu::TextureFormat::RGBA32F
                                         : caps.half_float_color_targets ? gpu::TextureFormat::RGBA16F
                                                                         : gpu::TextureFormat::RGBA8,
                                         nullptr, false);
        output_fb = gpu::Framebuffer();
        output_fb.attach_color(output);
        output_fb.check();
    }

    // What every draw of the frame shares as FrameBlock (frame_block.glsl, uniform_blocks.h):
    // camera, environment placement, debug channel, ambient, energy compensation and the
    // packed lights; filled and uploaded once per frame, bound at kFrameBlockBinding.
    FrameBlock frame_block;
    gpu::UniformBuffer frame_buffer;
    void pack_frame(const CameraSetup& cam, const std::vector<LightInstance>& lights, const RenderSettings& s) {
        FrameBlock& p = frame_block;
        p.view_projection = cam.projection * cam.view;
        p.view = cam.view;
        const glm::mat3 rotation = env_rotation(s);
        for (int c = 0; c < 3; ++c) p.env_rotation[std::size_t(c)] = glm::vec4(rotation[c], 0.0f);
        p.camera_position = cam.eye;
        p.env_levels = s.environment ? float(s.environment->specular.levels.size()) : 1.0f;
        p.ambient = s.ambient;
        p.env_intensity = s.env_intensity;
        p.debug = int(s.debug);
        p.energy_compensation = s.energy_compensation && lut_texture && uploaded_lut != 0 ? 1 : 0;
        p.light_count = std::min<int>(int(lights.size()), kMaxLights);
        frame_area_lights = std::any_of(lights.begin(), lights.begin() + p.light_count, [](const LightInstance& l) { return l.is_area(); });
        if (frame_area_lights && !ltc_texture) {
            // The GGX lobe's linearly transformed cosines (fresnel/material/ltc.h), made once.
            ltc_texture = gpu::Texture::create_2d(ltc::kTableSize, ltc::kTableSize, gpu::TextureFormat::RGBA16F,
                                                  ltc::table_data(), false);
            ltc_texture.set_sampler(gpu::SamplerState::clamped(Filter::Linear));
        }
        for (int i = 0; i < p.light_count; ++i) {
            const LightInstance& l = lights[std::size_t(i)];
            p.light_position_type[std::size_t(i)] = glm::vec4(l.position, float(int(l.type)));  // Light::Type's order
            p.light_direction_range[std::size_t(i)] = glm::vec4(l.direction, l.range);
            p.light_color[std::size_t(i)] = glm::vec4(l.radiance, 0.0f);
            if (l.is_area()) {
                p.light_cone[std::size_t(i)] = glm::vec4(l.axis_u, l.radius);
                p.light_axis[std::size_t(i)] = glm::vec4(l.axis_v, 0.0f);
            } else {
                float scale = 1.0f / std::max(0.001f, std::cos(l.inner_cone) - std::cos(l.outer_cone));
                p.light_cone[std::size_t(i)] = glm::vec4(scale, -std::cos(l.outer_cone) * scale, 0, 0);
                p.light_axis[std::size_t(i)] = glm::vec4(0.0f);
            }
        }
        for (int i = p.light_count; i < kMaxLights; ++i)
            p.light_position_type[std::size_t(i)] = p.light_direction_range[std::size_t(i)] =
                p.light_color[std::size_t(i)] = p.light_cone[std::size_t(i)] = p.light_axis[std::size_t(i)] = glm::vec4(0.0f);
        p.shadow_atlas = glm::vec4(0.0f);
        for (auto& v : p.light_shadow) v = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
        if (frame_shadows > 0) {
            const ShadowPlan& plan = shadow_plan;
            p.shadow_atlas = glm::vec4(1.0f / float(plan.atlas_width), 1.0f / float(plan.atlas_height),
                                       kSoftShadowRadius, 0.0f);
            for (std::size_t i = 0; i < plan.lights.size() && i < p.light_shadow.size(); ++i)
                p.light_shadow[i] = glm::vec4(float(plan.lights[i].first_tile), float(plan.lights[i].tiles),
                                              i < lights.size() ? shadow_source_size(lights[i]) : 0.0f, 0);
            for (std::size_t t = 0; t < plan.tiles.size(); ++t) {
                const ShadowTile& tile = plan.tiles[t];
                p.shadow_matrix[t] = tile_lookup_matrix(tile);
                p.shadow_rect[t] = glm::vec4(float(tile.rect.x) / float(plan.atlas_width),
                                             float(tile.rect.y) / float(plan.atlas_height),
                                             float(tile.rect.z) / float(plan.atlas_width),
                                             float(tile.rect.w) / float(plan.atlas_height));
                p.shadow_params[t] =
                    glm::vec4(tile.texel_world, float(ShadowPlan::kMarginTexels) / float(tile.rect.z), tile.near, tile.far);
            }
        }
        if (!frame_buffer) frame_buffer = gpu::UniformBuffer(sizeof(FrameBlock));
        frame_buffer.update(&p, sizeof p);
        frame_buffer.bind(kFrameBlockBinding);
    }

    bool frame_area_lights = false;  // this frame's FRAME_AREA_LIGHTS
    gpu::Texture ltc_texture;         // ltc::table_data(), bound for frames with area lights

    // ---- Shadows (details/shadow_maps.h, shaders/shadows.glsl) ----
    static constexpr float kSoftShadowRadius = 1.5f;  // the soft filter's disk, in texels
    // FRAME_SHADOWS 3: soft shadows whose lights include one with a size (an area light;
    // LightInstance::radius: a point or spot light's bulb, a directional light's angular
    // radius): contact-hardening (PCSS) for those, shadows.glsl.
    static constexpr int kContactHardeningShadows = 3;
    // The size a light's shadows come from, as shadows.glsl's contact_hardening reads it: a point
    // or spot light's bulb radius (metres), an area light's half extent (its shadows those of a
    // sphere as wide), the tangent of a directional light's angular radius; 0: a point (the soft
    // filter alone).
    static float shadow_source_size(const LightInstance& l) {
        if (l.is_area()) return std::max({glm::length(l.axis_u), glm::length(l.axis_v), l.radius});
        if (!(l.radius > 0.0f)) return 0.0f;
        if (l.type == Light::Type::Point || l.type == Light::Type::Spot) return l.radius;
        if (l.type == Light::Type::Directional) return std::tan(std::min(l.radius, 0.5f));
        return 0.0f;
    }
    gpu::SamplerObject shadow_depth_sampler;  // the atlas read as depths (the blocker search)
    ShadowPlan shadow_plan;  // this frame's
    int frame_shadows = 0;   // this frame's FRAME_SHADOWS: int(Shadows) when its maps are drawn, else 0
    gpu::Texture shadow_atlas;
    gpu::Framebuffer shadow_fb;
    int shadow_atlas_w = 0, shadow_atlas_h = 0;

    // Plans this frame's maps around the boxes of its draws (plan_shadows); frame_shadows
    // says whether there are any. Debug views show no shadows (they show a channel).
    void plan_frame_shadows(const CameraSetup& cam, const std::vector<LightInstance>& lights, const RenderSettings& s) {
        frame_shadows = 0;
        shadow_plan.tiles.clear();
        shadow_plan.lights.clear();
        if (s.shadows == Shadows::Off || lights.empty() || s.debug != DebugChannel::None) return;
        Bounds scene_box;
        for (const std::vector<Draw>* list : {&opaque_draws, &blended_draws, &transmissive_draws})
            for (const Draw& d : *list) scene_box.extend(d.model, d.prim->bounds_min, d.prim->bounds_max);
        if (scene_box.empty) return;
        // Skinned and morphed draws move off their boxes: a margin keeps their casters inside.
        const glm::vec3 pad(0.05f * glm::length(scene_box.max - scene_box.min) + 1e-4f);
        scene_box.min -= pad;
        scene_box.max += pad;
        plan_shadows(lights, std::min<int>(int(lights.size()), kMaxLights), cam, scene_box, s.shadow_map_size,
                     s.shadow_cascades, context.capabilities().max_texture_size, shadow_plan);
        if (shadow_plan.empty()) return;
        frame_shadows = int(s.shadows);
        if (s.shadows == Shadows::Soft)
            for (std::size_t i = 0; i < shadow_plan.lights.size() && i < lights.size(); ++i)
                if (shadow_plan.lights[i].first_tile >= 0 && shadow_source_size(lights[i]) > 0.0f)
                    frame_shadows = kContactHardeningShadows;
    }

    // What the maps were last drawn from (shadow_inputs_key): a frame with the same plan, draws
    // and casting materials keeps them (the viewer redrawing a still scene, a turntable's
    // environment spin, batch jobs on one scene draw them once).
    std::uint64_t shadow_key = 0;
    std::uint64_t shadow_inputs_key() const {
        std::uint64_t h = 1469598103934665603ull;
        auto mix = [&h](const void* data, std::size_t bytes) {
            const auto* b = static_cast<const unsigned char*>(data);
            for (std::size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
        };
        mix(&shadow_plan.atlas_width, sizeof(int));
        mix(&shadow_plan.atlas_height, sizeof(int));
        for (const ShadowTile& t : shadow_plan.tiles) {
            mix(&t.view_projection, sizeof t.view_projection);
            mix(&t.rect, sizeof t.rect);
        }
        mix(&scene, sizeof scene);
        for (const Draw& d : opaque_draws) {
            mix(&d.prim, sizeof d.prim);
            mix(&d.model, sizeof d.model);
            if (d.morph_weights >= 0)
                mix(&morph_weights[std::size_t(d.morph_weights)],
                    std::size_t(d.prim->morph_targets + 3) / 4 * sizeof(glm::vec4));
            if (d.joints) mix(d.joints->data(), d.joints->size() * sizeof(glm::mat4));
            if (d.prim->material >= 0) {  // what a masked material casts (the viewer edits materials)
                const Material& m = scene->materials[std::size_t(d.prim->material)];
                mix(&m.alpha_mode, sizeof m.alpha_mode);
                if (m.alpha_mode == AlphaMode::Mask) {
                    mix(&m.alpha_cutoff, sizeof m.alpha_cutoff);
                    mix(&m.base_color_factor.w, sizeof(float));
                    mix(&m.base_color.texture, sizeof(int));
                    mix(&m.base_color.transform, sizeof m.base_color.transform);
                }
            }
        }
        return h;
    }

    // Whether a draw's box (its model's POSITION box) can touch a tile: not when all eight
    // corners lie beyond one of the tile's clip planes. Skinned draws always can (joints move them).
    static bool may_cast(const Draw& d, const ShadowTile& tile) {
        return d.joints || d.posed || d.prim->deformable || !box_outside(tile.view_projection * d.model, d.prim->bounds_min, d.prim->bounds_max);
    }
    // Whether the box [lo, hi] lies outside the clip volume of `m` (clip space from the box's
    // space): all eight corners beyond one of its planes.
    static bool box_outside(const glm::mat4& m, glm::vec3 lo, glm::vec3 hi) {
        int outside[6] = {0, 0, 0, 0, 0, 0};
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
            const glm::vec4 c = m * glm::vec4(p, 1.0f);
            outside[0] += c.x < -c.w;
            outside[1] += c.x > c.w;
            outside[2] += c.y < -c.w;
            outside[3] += c.y > c.w;
            outside[4] += c.z < -c.w;
            outside[5] += c.z > c.w;
        }
        for (int k = 0; k < 6; ++k)
            if (outside[k] == 8) return true;
        return false;
    }

    // Whether a draw may share an instanced draw with other placements of its primitive: one
    // placement, not skinned or morphed, a glTF-shaded material that neither blends (blended
    // draws go far to near) nor transmits (transmission reads the model's scale from u_model).
    bool batchable(const Draw& d, const RenderSettings& s) const {
        if (d.joints || d.morph_weights >= 0 || d.instances > 0 || d.occlusion) return false;
        static const Material kDefaultMaterial{};
        const Material& m = d.prim->material >= 0 ? scene->materials[std::size_t(d.prim->material)] : kDefaultMaterial;
        return m.alpha_mode != AlphaMode::Blend && !is_transmissive(m) &&
               material_shading(s.shading, m) == ShadingModel::Gltf;
    }
    // `out` (emptied first): the draws of `in` that `keep` accepts, in material, primitive and
    // scene order, and with RenderSettings::instancing the placements of one primitive that
    // can share a draw (batchable, one handedness) as one instanced draw, their matrices
    // appended to instance_data.
    template <class Keep>
    void batch_draws(const std::vector<Draw>& in, Keep keep, const RenderSettings& s, std::vector<Draw>& out) {
        out.clear();
        for (const Draw& d : in)
            if (keep(d)) out.push_back(d);
        std::sort(out.begin(), out.end(), [](const Draw& a, const Draw& b) {
            if (a.prim->material != b.prim->material) return a.prim->material < b.prim->material;
            if (a.prim != b.prim) return std::less<const GpuPrimitive*>()(a.prim, b.prim);
            if (a.mirrored != b.mirrored) return b.mirrored;
            return a.sequence < b.sequence;
        });
        if (!s.instancing) return;
        std::size_t w = 0;
        for (std::size_t i = 0; i < out.size();) {
            std::size_t j = i + 1;
            if (batchable(out[i], s))
                while (j < out.size() && out[j].prim == out[i].prim && out[j].mirrored == out[i].mirrored &&
                       batchable(out[j], s))
                    ++j;
            Draw d = out[i];
            if (j - i >= 2) {
                d.instances = int(j - i);
                d.instance_first = std::uint32_t(instance_data.size());
                for (std::size_t k = i; k < j; ++k)
                    instance_data.push_back({out[k].model, glm::inverseTranspose(glm::mat3(out[k].model))});
            }
            out[w++] = d;
            i = j;
        }
        out.resize(w);
    }
    // Fills the primitive's instance buffer with an instanced draw's placements (made, and the
    // VAO's per-instance attributes set, on the first).
    void upload_instances(const Draw& d) {
        const GpuPrimitive& p = *d.prim;
        const void* data = &instance_data[d.instance_first];
        const std::size_t bytes = std::size_t(d.instances) * sizeof(InstanceRecord);
        if (p.instance_attributes) {
            p.instance_buffer.replace(data, bytes);
            return;
        }
        p.instance_buffer = gpu::Buffer(gpu::BufferKind::Vertex, data, bytes);
        gpu::VertexArray& vao = const_cast<gpu::VertexArray&>(p.vao);  // the renderer's own (meshes)
        for (unsigned c = 0; c < 4; ++c)
            vao.set_instance_attribute(gpu::kInstanceModelLocation + c, p.instance_buffer, 4, sizeof(InstanceRecord),
                                       c * 4 * sizeof(float));
        for (unsigned c = 0; c < 3; ++c)
            vao.set_instance_attribute(gpu::kInstanceNormalLocation + c, p.instance_buffer, 3, sizeof(InstanceRecord),
                                       kInstanceNormalOffset + c * 3 * sizeof(float));
        p.instance_attributes = true;
    }

    // Draws the planned maps: every opaque and alpha-masked draw's depth into each tile
    // (blended and transmissive ones cast none, as they let light through), both faces, with a
    // slope-scaled bias. After pack_frame: pbr.vert's frame block must be bound.
    void draw_shadow_maps(const RenderSettings& settings, FrameStats& stats) {
        const ShadowPlan& plan = shadow_plan;
        if (plan.atlas_width != shadow_atlas_w || plan.atlas_height != shadow_atlas_h) {
            shadow_atlas = gpu::Texture::create_depth_2d(plan.atlas_width, plan.atlas_height);
            shadow_fb = gpu::Framebuffer();
            shadow_fb.attach_depth(shadow_atlas);
            shadow_fb.check();
            shadow_atlas_w = plan.atlas_width;
            shadow_atlas_h = plan.atlas_height;
        }
        device.bind_framebuffer(&shadow_fb);
        device.no_scissor();
        device.viewport(0, 0, plan.atlas_width, plan.atlas_height);
        device.clear(glm::vec4(0.0f), true);  // (clear() turns depth writes on itself)
        gpu::PipelineState state;
        state.cull = gpu::Cull::None;
        state.offset_factor = 1.5f;
        state.offset_units = 2.0f;
        device.apply(state);
        stats.shadow_tiles_drawn = int(plan.tiles.size());
        for (const ShadowTile& tile : plan.tiles) {
            device.viewport(tile.rect.x, tile.rect.y, tile.rect.z, tile.rect.w);
            batch_draws(
                opaque_draws,
                [&](const Draw& d) { return d.prim->topology == Topology::Triangles && may_cast(d, tile); }, settings,
                shadow_draws);
            draw_depth(shadow_draws, tile.view_projection, stats);
        }
    }

    // Depth only, seen through `view_projection` (shadow.frag: masked materials discard by their
    // base colour's alpha): the shadow maps' tiles and screen-space occlusion's depth pass.
    void draw_depth(const std::vector<Draw>& draws, const glm::mat4& view_projection, FrameStats& stats) {
        static const Material kDefaultMaterial{};
        for (const Draw& d : draws) {
            const GpuPrimitive& p = *d.prim;
            const Material& m = p.material >= 0 ? scene->materials[std::size_t(p.material)] : kDefaultMaterial;
            FeatureMask features = 0;
            const gpu::Texture* base = nullptr;
            if (m.alpha_mode == AlphaMode::Mask) {
                features |= feature::AlphaMask;
                if (p.has_color) features |= feature::HasColor;
                const TextureSlot& slot = m.base_color;
                if (p.has_uv0 && slot.tex_coord == 0 && slot.texture >= 0)
                    base = texture_for(slot, true, Anisotropic::Off, 1.0f);
                if (base) features |= feature::HasUv0 | feature::BaseColorMap;
            }
            if (d.joints) features |= feature::Skinned;
            if (d.morph_weights >= 0) features |= feature::MorphTargets;
            if (d.instances > 0) features |= feature::Instanced;
            const gpu::Program& prog =
                shaders.get_keyed("pbr.vert", "shadow.frag", {kShadowPrograms, features, -1, 0}, [&] {
                    std::vector<std::string> defines = feature_defines(features);
                    defines.emplace_back("SHADOW_PASS");
                    return defines;
                });
            prog.use();
            prog.set("u_light_view_projection", view_projection);
            if (d.instances == 0) {
                prog.set("u_model", d.model);
                prog.set("u_normal_matrix", glm::inverseTranspose(glm::mat3(d.model)));
            }
            prog.set("u_handedness", 1.0f);
            prog.set("u_point_size", 1.0f);
            if (features & feature::AlphaMask) {
                prog.set("u_base_color_factor", m.base_color_factor);
                prog.set("u_alpha_cutoff", m.alpha_cutoff);
                if (base) {
                    device.bind_texture(0, *base);
                    prog.set("u_base_color_map", 0);
                    prog.set("u_base_color_transform", m.base_color.transform);
                }
            }
            bind_animation(prog, d);
            if (d.instances > 0) {
                upload_instances(d);
                device.draw_instanced(p.vao, gpu::Primitive::Triangles, p.count, p.indexed, d.instances);
                ++stats.instanced_draws;
                stats.instances_drawn += std::size_t(d.instances);
            } else {
                device.draw(p.vao, gpu::Primitive::Triangles, p.count, p.indexed);
            }
            ++stats.draw_calls;
        }
    }

    // ---- Screen-space ambient occlusion (--ao ssao: shaders/ssao.frag, ssao_blur.frag) ----
    bool frame_ssao = false;  // this frame's FRAME_SSAO: ssao_texture holds its visibility
    gpu::Texture ssao_depth, ssao_raw, ssao_texture;
    gpu::Framebuffer ssao_depth_fb, ssao_raw_fb, ssao_fb;
    int ssao_w = 0, ssao_h = 0;

    // The frame's opaque, triangle draws in depth, the horizon search, the 4x4 blur, at half the
    // frame's resolution each way (a quarter of the cost; occlusion varies slowly): the
    // visibility pbr.frag reads at gl_FragCoord / 2.
    void draw_ssao(const CameraSetup& cam, const RenderSettings& s, const std::vector<Draw>& draws, FrameStats& stats) {
        const int w = (s.width + 1) / 2, h = (s.height + 1) / 2;
        if (w != ssao_w || h != ssao_h || !ssao_texture) {
            ssao_depth = gpu::Texture::create_depth_2d(w, h, false);
            ssao_depth_fb = gpu::Framebuffer();
            ssao_depth_fb.attach_depth(ssao_depth);
            ssao_depth_fb.check();
            for (auto [texture, fb] : {std::pair{&ssao_raw, &ssao_raw_fb}, std::pair{&ssao_texture, &ssao_fb}}) {
                *texture = gpu::Texture::create_2d(w, h, gpu::TextureFormat::R8, nullptr, false);
                texture->set_sampler(gpu::SamplerState::clamped(Filter::Nearest));
                *fb = gpu::Framebuffer();
                fb->attach_color(*texture);
                fb->check();
            }
            ssao_w = w;
            ssao_h = h;
        }
        device.bind_framebuffer(&ssao_depth_fb);
        device.no_scissor();
        device.viewport(0, 0, w, h);
        device.clear(glm::vec4(0.0f), true);
        gpu::PipelineState state;
        state.cull = gpu::Cull::None;
        device.apply(state);
        ssao_draws.clear();
        for (const Draw& d : draws)
            if (d.prim->topology == Topology::Triangles) ssao_draws.push_back(d);
        draw_depth(ssao_draws, cam.projection * cam.view, stats);

        gpu::PipelineState flat;
        flat.depth_test = false;
        flat.depth_write = false;
        flat.cull = gpu::Cull::None;
        device.apply(flat);
        const glm::mat4& P = cam.projection;
        const bool orthographic = P[2][3] == 0.0f;
        const glm::vec4 projection(P[0][0], P[1][1], P[2][2], P[3][2]);
        const glm::vec2 projection_offset = orthographic ? glm::vec2(P[3][0], P[3][1]) : glm::vec2(P[2][0], P[2][1]);
        const std::vector<std::string> defines = orthographic ? std::vector<std::string>{"SSAO_ORTHOGRAPHIC"}
                                                              : std::vector<std::string>{};
        const glm::vec2 texel(1.0f / float(w), 1.0f / float(h));
        Bounds b;  // the frame's opaque draws: the default radius (a quarter of theirs) follows the scene's size
        for (const Draw& d : opaque_draws) b.extend(d.model, d.prim->bounds_min, d.prim->bounds_max);
        const float radius = s.ssao_radius > 0.0f ? s.ssao_radius : std::max(b.empty ? 1.0f : b.radius(), 1e-4f) * 0.25f;
        device.bind_framebuffer(&ssao_raw_fb);
        const gpu::Program& horizon = shaders.get("fullscreen.vert", "ssao.frag", defines);
        horizon.use();
        device.bind_texture(0, ssao_depth);
        horizon.set("u_depth", 0);
        horizon.set("u_projection", projection);
        horizon.set("u_projection_offset", projection_offset);
        horizon.set("u_texel", texel);
        horizon.set("u_radius", radius);
        horizon.set("u_pixels_per_unit", cam.projection[1][1] * 0.5f * float(h));
        device.draw_fullscreen();
        device.bind_framebuffer(&ssao_fb);
        const gpu::Program& blur = shaders.get("fullscreen.vert", "ssao_blur.frag", defines);
        blur.use();
        device.bind_texture(0, ssao_depth);
        blur.set("u_depth", 0);
        device.bind_texture(1, ssao_raw);
        blur.set("u_occlusion", 1);
        blur.set("u_texel", texel);
        blur.set("u_projection", projection);
        device.draw_fullscreen();
        frame_ssao = true;
    }
    std::vector<Draw> ssao_draws;  // the frame's (storage kept)

    // One uniform buffer per material (index + 1; 0: the glTF default material), refilled
    // only when the material's block changes (an edit in the viewer, another --anisotropy).
    struct MaterialBuffer {
        gpu::UniformBuffer buffer;
        MaterialBlock block;
        bool filled = false;
    };
    std::vector<MaterialBuffer> material_buffers;
    void bind_material_block(int material, const MaterialUniforms& mu) {
        const std::size_t slot = material >= 0 ? std::size_t(material) + 1 : 0;
        if (slot >= material_buffers.size()) material_buffers.resize(slot + 1);
        MaterialBuffer& mb = material_buffers[slot];
        const MaterialBlock& block = mu.block;
        if (!mb.buffer) mb.buffer = gpu::UniformBuffer(sizeof(MaterialBlock));
        if (!mb.filled || std::memcmp(&mb.block, &block, sizeof block) != 0) {
            mb.buffer.update(&block, sizeof block);
            mb.block = block;
            mb.filled = true;
        }
        mb.buffer.bind(kMaterialBlockBinding);
    }

    // Draws a primitive whose program and material are bound: culling by the material's sides
    // and the winding that the model matrix's determinant `det` keeps or mirrors, blending for
    // BLEND materials (no depth writes), and the frame's counts.
    void submit(const Draw& d, const Material& m, float det, FrameStats& stats) {
        const GpuPrimitive& p = *d.prim;
        gpu::PipelineState state;
        state.cull = m.double_sided ? gpu::Cull::None : gpu::Cull::Back;
        state.front_ccw = det >= 0;
        if (m.alpha_mode == AlphaMode::Blend) {
            state.blend = gpu::Blend::AlphaOver;
            state.depth_write = false;
        }
        device.apply(state);
        if (d.occlusion != p.occlusion_bound) {
            gpu::VertexArray& vao = const_cast<gpu::VertexArray&>(p.vao);  // the renderer's own (meshes)
            if (d.occlusion) vao.set_attribute(gpu::kOcclusionLocation, *d.occlusion, 4);
            else vao.disable_attribute(gpu::kOcclusionLocation);
            p.occlusion_bound = d.occlusion;
        }
        if (d.instances > 0) {
            upload_instances(d);
            device.draw_instanced(p.vao, to_gpu(p.topology), p.count, p.indexed, d.instances);
            ++stats.instanced_draws;
            stats.instances_drawn += std::size_t(d.instances);
        } else {
            device.draw(p.vao, to_gpu(p.topology), p.count, p.indexed);
        }
        ++stats.draw_calls;
        stats.triangles += p.triangles * std::size_t(std::max(1, d.instances));
    }

    // One primitive in a legacy model (legacy.vert / legacy.frag, ShadingModel in renderer.h)
    // with the material's Phong values (legacy_phong, blinn_phong_material in phong.h).
    void draw_legacy(const Draw& d, const CameraSetup& cam, const RenderSettings& settings, const Material& m,
                     ShadingModel model, FrameStats& stats) {
        namespace lf = legacy_feature;
        const GpuPrimitive& p = *d.prim;
        const PhongExt ph = legacy_phong(m);
        const bool blinn = model == ShadingModel::BlinnPhongNormalized;
        FeatureMask raw = model == ShadingModel::Ogl1        ? lf::Ogl1Vertex
                          : model == ShadingModel::Ogl1Pixel ? lf::Ogl1Pixel
                                                             : lf::BlinnPhong;
        if (p.has_normal) raw |= lf::HasNormal;
        if (p.has_uv0) raw |= lf::HasUv0;
        if (settings.environment) raw |= lf::UseIbl;
        if (settings.fog.mode != legacy::FogMode::None) raw |= lf::Fogged;
        // OpenGL 1 modulates by the texels as stored (no sRGB decode, no anisotropic
        // filtering); Blinn-Phong reads map_Kd as the base colour, sRGB.
        const gpu::Texture* map = nullptr;
        const TextureSlot& slot = ph.diffuse_map.slot;
        if (p.has_uv0 && slot.tex_coord == 0) map = texture_for(slot, blinn, blinn ? Anisotropic::Sampler : Anisotropic::Off, settings.anisotropy);
        if (map) raw |= lf::DiffuseMap;
        const FeatureMask features = canonical_legacy_features(raw);
        // The OpenGL 1 models write their colour as they compute it: no frame variant.
        const int frame = blinn ? frame_variant(settings, false).key() : -1;
        const gpu::Program& prog =
            shaders.get_keyed("legacy.vert", "legacy.frag", {kLegacyPrograms, features, frame, 0}, [&] {
                std::vector<std::string> defines = legacy_feature_defines(features);
                if (blinn)
                    for (auto& d : frame_defines(frame_variant(settings, false))) defines.push_back(std::move(d));
                return defines;
            });
        prog.use();
        prog.set("u_model", d.model);
        prog.set("u_normal_matrix", glm::inverseTranspose(glm::mat3(d.model)));
        prog.set("u_point_size", 1.0f);  // the camera and the lights: FrameBlock (pack_frame)
        prog.set("u_ka", ph.ambient);
        prog.set("u_kd", glm::vec4(ph.diffuse, std::clamp(ph.dissolve, 0.0f, 1.0f)));
        prog.set("u_ks", ph.specular);
        prog.set("u_ke", ph.emission);
        prog.set("u_shininess", legacy::ogl1_shininess(ph.shininess));
        prog.set("u_separate_specular", map ? 1 : 0);  // as rgl: separate specular for textured materials
        if (map) {
            device.bind_texture(int(TextureUnit::LegacyDiffuseMap), *map);
            prog.set("u_diffuse_map", int(TextureUnit::LegacyDiffuseMap));
            prog.set("u_diffuse_transform", slot.transform);
        }
        if (features & lf::Fogged) {
            const fresnel::Fog& f = settings.fog;
            prog.set("u_fog_mode", int(f.mode));
            prog.set("u_fog", glm::vec4(f.start.value_or(cam.znear), f.end.value_or(cam.zfar), f.density, 0.0f));
            prog.set("u_fog_color", f.color);
        }
        if (blinn) {
            const legacy::BlinnPhongMaterial bp = blinn_phong_material(m);
            prog.set("u_bp_base_color", bp.base_color);
            prog.set("u_bp_shininess", bp.shininess);
            prog.set("u_bp_fresnel", bp.fresnel);
            prog.set("u_bp_metalness", bp.metalness);
            prog.set("u_bp_reflectivity", bp.reflectivity);
            prog.set("u_exposure", exposure_scale(settings.exposure_ev));
            prog.set("u_brdf_lut", int(TextureUnit::BrdfLut));
            if (settings.environment) {
                device.bind_texture(int(TextureUnit::SpecularEnvironment), env_specular);
                prog.set("u_specular_env", int(TextureUnit::SpecularEnvironment));
                device.bind_texture(int(TextureUnit::IrradianceEnvironment), env_irradiance);
                prog.set("u_irradiance_env", int(TextureUnit::IrradianceEnvironment));
            }
        }
        assert(d.instances == 0);  // batch_draws batches glTF-shaded draws only
        submit(d, m, glm::determinant(glm::mat3(d.model)), stats);
    }

    void draw_primitive(const Draw& d, const CameraSetup& cam, const std::vector<LightInstance>& lights,
                        const RenderSettings& settings, FrameStats& stats) {
        static const Material kDefaultMaterial{};
        const GpuPrimitive& p = *d.prim;
        const Material& m = p.material >= 0 ? scene->materials[std::size_t(p.material)] : kDefaultMaterial;
        // The legacy models draw with their own shaders (the debug view shows glTF's channels).
        const ShadingModel model = material_shading(settings.shading, m);
        if (model != ShadingModel::Gltf && settings.debug == DebugChannel::None) {
            draw_legacy(d, cam, settings, m, model, stats);
            return;
        }
        // The draw's raw features; canonical_features() turns them into the variant (shader_features.h).
        MaterialUniforms mu = material_uniforms(m);
        FeatureMask raw = material_features(m);
        if (p.has_normal) raw |= feature::HasNormal;
        if (p.has_tangent) raw |= feature::HasTangent;
        if (p.has_uv0) raw |= feature::HasUv0;
        if (p.has_uv1) raw |= feature::HasUv1;
        if (p.has_color) raw |= feature::HasColor;
        if (settings.debug != DebugChannel::None) raw |= feature::DebugView;
        if (settings.environment) raw |= feature::UseIbl;
        if (d.joints) raw |= feature::Skinned;
        if (d.morph_weights >= 0) raw |= feature::MorphTargets;
        if (d.instances > 0) raw |= feature::Instanced;

        // Texture units are packed per draw: the maps the variant reads take units 0, 1, ... in
        // MaterialMap order, then the opaque scene (transmission), the split-sum table, the
        // environment's two cubes and sheen's cube and table follow; a draw that would need more
        // than the limit leaves its last maps unread (below: unit_limit).
        static_assert(kMaterialMapCount == feature::kMapCount);
        const gpu::Texture* bound[kMaterialMapCount] = {};
        const VertexInputs vertex{p.has_uv0, p.has_uv1, p.has_tangent};
        for (int i = 0; i < kMaterialMapCount; ++i) {
            const TextureSlot* slot = mu.maps[std::size_t(i)];
            if (slot && map_usable(*slot, MaterialMap(i), vertex)) raw |= feature::map_bit(i);
        }
        // The occlusion read with the metallic-roughness probes from one texture where it can be.
        const int packed = occlusion_packs(m);
        constexpr FeatureMask kMr = feature::map_bit(int(MaterialMap::MetallicRoughness));
        constexpr FeatureMask kAo = feature::map_bit(int(MaterialMap::Occlusion));
        if (packed >= 0 && (raw & kMr) && (raw & kAo)) raw = (raw & ~kAo) | feature::OcclusionInMetallicRoughness;
        // And the metallic-roughness texture in the other maps' alphas where it can be (the
        // canonical rules drop the bit where the variant cannot read it so).
        const std::optional<AlphaPacking> alpha =
            settings.pack_channels ? alpha_packs(m, (raw & feature::OcclusionInMetallicRoughness) ? packed : -1)
                                   : std::nullopt;
        if (alpha) raw |= feature::MetallicRoughnessInAlpha;
        // Upload the maps the variant reads; one without a usable image counts as absent.
        FeatureMask features = canonical_features(raw);
        const bool in_alpha = features & feature::MetallicRoughnessInAlpha;
        for (int i = 0; i < kMaterialMapCount; ++i) {
            if (!(features & raw & feature::map_bit(i))) continue;
            const MaterialMap map = MaterialMap(i);
            const MaterialMapInfo& info = material_map_info(map);
            if (map == MaterialMap::MetallicRoughness && in_alpha) continue;  // no texture of its own
            const TextureKey key =
                map_key(m, *mu.maps[std::size_t(i)], map, (features & feature::OcclusionInMetallicRoughness) ? packed : -1,
                        in_alpha ? &*alpha : nullptr);
            bound[i] = texture_for(*mu.maps[std::size_t(i)], key.srgb,
                                   info.detail ? Anisotropic::Shader : Anisotropic::Off,
                                   settings.anisotropy, &mu.block.maps[std::size_t(i)].anisotropy, key);
            if (!bound[i]) raw &= ~feature::map_bit(i);
        }
        features = canonical_features(raw);
        // alpha_packs found every texture it names usable, so none went missing above.
        assert(in_alpha == bool(features & feature::MetallicRoughnessInAlpha));
        // batch_draws batches what the variant can draw instanced.
        assert(d.instances == 0 || (features & feature::Instanced));
        auto settle_maps = [&] {
            for (int i = 0; i < kMaterialMapCount; ++i) {
                // A map the variant samples but the material lacks reads the white texture: x * 1.0 = x.
                if (!(features & feature::map_bit(i)) || (in_alpha && MaterialMap(i) == MaterialMap::MetallicRoughness))
                    bound[i] = nullptr;
                else if (!bound[i]) bound[i] = &white_texture();
            }
        };
        settle_maps();
        // The texture units (the packing below): the maps take what the transmitted scene, the
        // split-sum table and the environment's cubes leave; past the limit the last maps go
        // unread (RenderSettings::max_texture_units). 16 units hold 10 maps with everything else.
        // Maps the variants read in pairs (clearcoat's, sheen's, ...: canonical_features) go in pairs.
        {
            auto units_for = [&](FeatureMask f) {
                int units = fixed_units(f, settings);
                for (int i = 0; i < kMaterialMapCount; ++i)
                    units += (f & feature::map_bit(i)) && !(in_alpha && MaterialMap(i) == MaterialMap::MetallicRoughness);
                return units;
            };
            const int limit = unit_limit(settings);
            FeatureMask trial = features;
            for (int i = kMaterialMapCount - 1; i >= 0 && units_for(canonical_features(trial)) > limit; --i)
                trial &= ~feature::map_bit(i);
            if (trial != features) {
                features = canonical_features(trial);
                settle_maps();
                ++stats.unit_limited_draws;
            }
        }
        // One anisotropic footprint for the detail maps that agree (DetailSharedFootprint).
        const bool shared_footprint = settings.share_footprints && shares_detail_footprint(features, bound, mu);
        if (shared_footprint) features = canonical_features(features | feature::DetailSharedFootprint);

        // Alternative BRDF terms are defines on top of the feature set (rare: a string-keyed variant).
        const gpu::Program& prog = [&]() -> const gpu::Program& {
            FrameVariant output = frame_variant(settings, linear_pass, !lights.empty());
            if (output.lights) output.shadows = frame_shadows;
            output.area_lights = output.lights && frame_area_lights;
            output.ssao = frame_ssao && !linear_pass;  // (the transmission pass has its own size)
            if (settings.brdf.is_default()) return shaders.get("pbr.vert", "pbr.frag", features, output);
            const brdf::BrdfModel& b = settings.brdf;
            const std::uint32_t terms = std::uint32_t(b.d) | std::uint32_t(b.g) << 6 | std::uint32_t(b.f) << 12 |
                                        std::uint32_t(b.diffuse) << 18 | std::uint32_t(b.conductor) << 24;
            return shaders.get_keyed("pbr.vert", "pbr.frag", {kBrdfPrograms, features, output.key(), terms}, [&] {
                std::vector<std::string> defines = feature_defines(features);
                for (auto& d : frame_defines(output)) defines.push_back(std::move(d));
                for (auto& d : brdf::brdf_model_defines(settings.brdf)) defines.push_back(std::move(d));
                return defines;
            });
        }();
        prog.use();
        if (d.instances == 0) {
            prog.set("u_model", d.model);
            prog.set("u_normal_matrix", glm::inverseTranspose(glm::mat3(d.model)));
        }
        float det = glm::determinant(glm::mat3(d.model));
        prog.set("u_handedness", det < 0 ? -1.0f : 1.0f);
        prog.set("u_point_size", 1.0f);
        // The transmission pass writes linear radiance (Khronos' LINEAR_OUTPUT: no exposure either;
        // the tone mapper and encoding are the frame variant's).
        prog.set("u_exposure", linear_pass ? 1.0f : exposure_scale(settings.exposure_ev));
        // Created (and so bound to the active unit) before any unit is filled, not in between.
        const gpu::Texture& white = white_texture();
        std::array<int, kMaterialMapCount> map_units{};
        int next_unit = 0;
        for (int i = 0; i < kMaterialMapCount; ++i) {
            map_units[std::size_t(i)] = bound[i] ? next_unit++ : -1;
            if (bound[i]) device.bind_texture(map_units[std::size_t(i)], *bound[i]);
        }
        if (features & feature::Transmission) {
            const int kUnit = next_unit++;
            device.bind_texture(kUnit, transmission_ready ? transmission_texture : white);
            prog.set("u_transmission_framebuffer", kUnit);
            prog.set("u_transmission_framebuffer_size", float(transmission::kFramebufferSize));
        }
        // The split-sum table, the prefiltered environment, the irradiance.
        bool have_lut = lut_texture && uploaded_lut != 0;
        const int kLutUnit = next_unit++;
        if (have_lut) device.bind_texture(kLutUnit, lut_texture);
        prog.set("u_brdf_lut", kLutUnit);
        if (settings.environment) {
            const int kSpecularUnit = next_unit++, kIrradianceUnit = next_unit++;
            device.bind_texture(kSpecularUnit, env_specular);
            prog.set("u_specular_env", kSpecularUnit);
            device.bind_texture(kIrradianceUnit, env_irradiance);
            prog.set("u_irradiance_env", kIrradianceUnit);
            if ((features & feature::Sheen) && env_sheen && charlie_lut) {
                const int kSheenUnit = next_unit++, kCharlieUnit = next_unit++;
                device.bind_texture(kSheenUnit, env_sheen);
                prog.set("u_sheen_env", kSheenUnit);
                device.bind_texture(kCharlieUnit, charlie_lut);
                prog.set("u_charlie_lut", kCharlieUnit);
            }
        }
        if (frame_ssao && !linear_pass) {
            const int kSsaoUnit = next_unit++;
            device.bind_texture(kSsaoUnit, ssao_texture);
            prog.set("u_ssao", kSsaoUnit);
        }
        if (frame_area_lights && !lights.empty()) {
            const int kLtcUnit = next_unit++;
            device.bind_texture(kLtcUnit, ltc_texture);
            prog.set("u_ltc_table", kLtcUnit);
        }
        if (frame_shadows > 0) {
            const int kShadowUnit = next_unit++;
            device.bind_texture(kShadowUnit, shadow_atlas);
            prog.set("u_shadow_atlas", kShadowUnit);
            if (frame_shadows == kContactHardeningShadows) {
                if (!shadow_depth_sampler) shadow_depth_sampler = gpu::SamplerObject::depth_values();
                const int kShadowDepthUnit = next_unit++;
                device.bind_texture(kShadowDepthUnit, shadow_atlas, &shadow_depth_sampler);
                prog.set("u_shadow_depth", kShadowDepthUnit);
            }
        }
        assert(next_unit <= unit_limit(settings));  // fixed_units counts what this packs
        bind_material_block(p.material, mu);
        set_material_samplers(prog, map_units);
        bind_animation(prog, d);

        submit(d, m, det, stats);
        if (shared_footprint) ++stats.shared_footprint_draws;
        if (in_alpha) ++stats.alpha_packed_draws;
    }
};

Renderer::Renderer(gpu::Context& context) : impl_(std::make_unique<Impl>(context)) {}
Renderer::~Renderer() = default;

void Renderer::set_scene(Scene& scene, int scene_index, ImageResidency residency) {
    impl_->releasing = residency == ImageResidency::GpuOnly ? &scene : nullptr;
    set_scene(static_cast<const Scene&>(scene), scene_index);
    impl_->releasing = nullptr;
}

void Renderer::set_scene(const Scene& scene, int scene_index) {
    impl_->redecoded.clear();
    impl_->unbind_occlusion();
    impl_->occlusion.clear();
    impl_->occlusion_draw_count = 0;
    impl_->scene = &scene;
    impl_->scene_index = scene_index;
    impl_->shadow_key = 0;  // new primitives may sit where the old ones were
    impl_->instances = flatten(scene, scene_index);
    impl_->upload(scene);
    impl_->upload_textures();
}

void Renderer::set_vertex_occlusion(const VertexOcclusion* occlusion) {
    Impl& r = *impl_;
    r.unbind_occlusion();
    r.occlusion.clear();
    r.occlusion_draw_count = 0;
    if (!occlusion || !r.scene) return;
    r.occlusion.resize(std::min(occlusion->nodes.size(), r.scene->nodes.size()));
    for (std::size_t n = 0; n < r.occlusion.size(); ++n) {
        const int mesh = r.scene->nodes[n].mesh;
        if (mesh < 0 || std::size_t(mesh) >= r.meshes.size()) continue;
        const std::vector<GpuPrimitive>& prims = r.meshes[std::size_t(mesh)];
        const Mesh& m = r.scene->meshes[std::size_t(mesh)];
        r.occlusion[n].resize(prims.size());
        for (std::size_t k = 0; k < prims.size(); ++k) {
            const std::vector<glm::vec4>* values = occlusion->find(int(n), k);
            // Values for every vertex the primitive has, or none (a bake of another scene).
            if (!values || values->size() != m.primitives[k].positions.size()) continue;
            r.occlusion[n][k] = gpu::Buffer(gpu::BufferKind::Vertex, values->data(), values->size() * sizeof(glm::vec4));
            ++r.occlusion_draw_count;
        }
    }
}

void Renderer::update_transforms() {
    if (impl_->scene) impl_->instances = flatten(*impl_->scene, impl_->scene_index);
}

bool gpu_animatable(const Scene& scene, std::string* why) {
    auto no = [why](std::string reason) {
        if (why) *why = std::move(reason);
        return false;
    };
    for (std::size_t i = 0; i < scene.skins.size(); ++i)
        if (scene.skins[i].joints.size() > std::size_t(kMaxShaderJoints))
            return no("skin " + std::to_string(i) + " has " + std::to_string(scene.skins[i].joints.size()) +
                      " joints (the GPU poses up to " + std::to_string(kMaxShaderJoints) + ")");
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (std::size_t k = 0; k < scene.meshes[m].primitives.size(); ++k) {
            const Primitive& p = scene.meshes[m].primitives[k];
            if (p.targets.empty()) continue;
            const std::string name = "mesh " + std::to_string(m) + " primitive " + std::to_string(k);
            if (p.targets.size() > std::size_t(kMaxShaderMorphTargets))
                return no(name + " has " + std::to_string(p.targets.size()) + " morph targets (the GPU poses up to " +
                          std::to_string(kMaxShaderMorphTargets) + ")");
            if (p.positions.size() > std::size_t(kMaxShaderMorphVertices))
                return no(name + " has morph targets and " + std::to_string(p.positions.size()) +
                          " vertices (the GPU morphs up to " + std::to_string(kMaxShaderMorphVertices) + ")");
            if (p.generated_normals)
                return no(name + " has morph targets and generated flat normals (which follow the morphed faces)");
        }
    return true;
}

std::size_t Renderer::program_count() const { return impl_->shaders.size(); }
std::size_t Renderer::texture_bytes() const {
    const Impl& m = *impl_;
    std::size_t n = 0;
    for (const auto& [key, t] : m.textures) n += t.texture.bytes();
    for (const auto& t : m.frame_targets) n += t.resolved.bytes() + t.msaa_texture.bytes();
    for (const gpu::Texture* t : {&m.output, &m.output8, &m.transmission_texture, &m.env_specular, &m.env_irradiance, &m.env_sheen,
                                  &m.charlie_lut, &m.lut_texture})
        n += t->bytes();
    if (m.white_map) n += m.white_map->bytes();
    for (const gpu::Texture& t : m.joint_textures) n += t.bytes();
    for (const auto& mesh : m.meshes)
        for (const GpuPrimitive& p : mesh) n += p.morph_texture.bytes();
    return n;
}
void Renderer::set_shader_folder(const std::string& folder) { impl_->shaders.set_source_folder(folder); }
std::string Renderer::reload_shaders() { return impl_->shaders.reload(); }

ImageF Renderer::render(const CameraSetup& cam, const std::vector<LightInstance>& lights,
                        const RenderSettings& settings, FrameStats* stats_out) {
    draw(cam, lights, settings, stats_out);
    Impl& r = *impl_;
    int w = settings.width, h = settings.height;
    std::vector<float> px = r.device.read_rgba32f(r.output_fb, w, h);
    ImageF img(w, h);
    for (int y = 0; y < h; ++y)  // GL rows are bottom to top
        std::copy_n(&px[std::size_t(h - 1 - y) * std::size_t(w) * 4], std::size_t(w) * 4, img.at(0, y));
    r.note_errors(stats_out);
    return img;
}

Image8 Renderer::render8(const CameraSetup& cam, const std::vector<LightInstance>& lights,
                         const RenderSettings& settings, bool alpha, FrameStats* stats_out) {
    draw(cam, lights, settings, RenderTarget::offscreen8(), stats_out);
    Impl& r = *impl_;
    const int w = settings.width, h = settings.height;
    const std::vector<std::uint8_t> px = r.device.read_rgba8(r.output8_fb, w, h);
    Image8 img(w, h, alpha ? 4 : 3);
    for (int y = 0; y < h; ++y) {  // GL rows are bottom to top
        const std::uint8_t* src = &px[std::size_t(h - 1 - y) * std::size_t(w) * 4];
        std::uint8_t* dst = img.at(0, y);
        if (alpha) {
            std::copy_n(src, std::size_t(w) * 4, dst);
        } else {
            for (int x = 0; x < w; ++x, src += 4, dst += 3) dst[0] = src[0], dst[1] = src[1], dst[2] = src[2];
        }
    }
    r.note_errors(stats_out);
    return img;
}

std::optional<Renderer::TexturePreview> Renderer::texture_preview(int texture) const {
    for (bool srgb : {false, true}) {
        auto it = impl_->textures.find({texture, srgb});
        if (it != impl_->textures.end() && it->second.texture)
            return TexturePreview{it->second.texture.id(), it->second.texture.width(), it->second.texture.height(), srgb};
    }
    // A texture uploaded only with another's channel in it, or a metallic-roughness texture and
    // an occlusion packed together (occlusion_packs: the one texture shows both). A
    // metallic-roughness texture spread over alpha channels (alpha_packs) has no texture of its own.
    for (const auto& [key, g] : impl_->textures)
        if (g.texture && key.packed() && (key.texture == texture || (key.source == texture && key.to == 0)))
            return TexturePreview{g.texture.id(), g.texture.width(), g.texture.height(), key.srgb, true};
    return std::nullopt;
}

void Renderer::draw(const CameraSetup& cam, const std::vector<LightInstance>& lights, const RenderSettings& settings,
                    FrameStats* stats_out) {
    draw(cam, lights, settings, RenderTarget::offscreen(), stats_out);
}

void Renderer::draw(const CameraSetup& cam, const std::vector<LightInstance>& given_lights, const RenderSettings& settings,
                    const RenderTarget& target, FrameStats* stats_out) {
    Impl& r = *impl_;
    const std::vector<LightInstance>& lights = r.frame_lights(given_lights, settings);
    FrameStats stats;
    int w = settings.width, h = settings.height;
    int samples = std::clamp(settings.msaa, 1, std::max(1, r.context.capabilities().max_samples_float));
    if (samples == 1) samples = 0;
    const bool sky = settings.environment && settings.background_mode != RenderSettings::Background::Color &&
                     settings.debug == DebugChannel::None;
    // A transparent frame is one whose background is transparent and not covered by the sky.
    const bool transparent = settings.background.w == 0.0f && !sky;
    const bool display8 = settings.frame_format == RenderSettings::FrameFormat::Display8 && settings.encoding &&
                          settings.debug == DebugChannel::None && !transparent;
    stats.targets_rebuilt = r.ensure_targets(w, h, samples, display8);

    r.device.bind_framebuffer(&r.targets->msaa_fb);
    r.device.viewport(0, 0, w, h);
    // The background is display-referred and written as-is (like the Khronos Sample Viewer's clear colour).
    r.device.clear(settings.background.w == 0.0f ? glm::vec4(0.0f) : glm::vec4(glm::vec3(settings.background), 1.0f),
                   true);
    r.ensure_environment(settings);
    if (sky) r.draw_sky(cam, settings);

    if (r.scene) {
        // The frame's draw lists: the renderer's own vectors, emptied (their storage stays).
        std::vector<Draw>& opaque = r.opaque_draws;
        std::vector<Draw>& blended = r.blended_draws;
        std::vector<Draw>& transmissive = r.transmissive_draws;
        opaque.clear();
        blended.clear();
        transmissive.clear();
        // GPU animation: joint matrices from the nodes' current world matrices (storage kept),
        // written into each skin's texture.
        r.morph_weights.clear();
        if (settings.gpu_animation) {
            skin_matrices(r.scene->nodes, r.scene->skins, r.skin_pose, kMaxShaderJoints);
            for (std::size_t i = 0; i < r.skin_pose.skins.size() && i < r.joint_textures.size(); ++i) {
                const std::vector<glm::mat4>& joints = r.skin_pose.skins[i];
                gpu::Texture& texture = r.joint_textures[i];
                if (!joints.empty() && texture &&
                    Impl::joint_texture_size(joints.size()) == glm::ivec2(texture.width(), texture.height()))
                    Impl::upload_joints(texture, joints);
                else r.skin_pose.skins[i].clear();  // a skin edited since set_scene: drawn unskinned
            }
        }
        const std::vector<std::vector<glm::mat4>>& skins = r.skin_pose.skins;
        for (const auto& inst : r.instances) {
            const Node& node = r.scene->nodes[std::size_t(inst.node)];
            if (node.mesh < 0 || !inst.visible) continue;
            const Mesh& mesh = r.scene->meshes[std::size_t(node.mesh)];
            std::vector<GpuPrimitive>& gpu_mesh = r.meshes[std::size_t(node.mesh)];
            for (std::size_t k = 0; k < gpu_mesh.size(); ++k) {
                GpuPrimitive& p = gpu_mesh[k];
                glm::mat4 model = node.world_space_mesh ? glm::mat4(1.0f) : inst.world;
                glm::vec4 c = cam.view * model * glm::vec4(p.center, 1.0f);
                Draw d{&p, model, std::isnan(c.z) ? 0.0f : -c.z};  // a NaN would break the sort's ordering
                d.sequence = std::uint32_t(opaque.size() + blended.size() + transmissive.size());
                d.mirrored = glm::determinant(glm::mat3(model)) < 0.0f;
                d.posed = node.world_space_mesh;
                d.occlusion = r.occlusion_for(inst.node, k);
                if (settings.gpu_animation && !node.world_space_mesh) {
                    if (p.has_skin && node.skin >= 0 && std::size_t(node.skin) < skins.size() &&
                        !skins[std::size_t(node.skin)].empty()) {
                        d.joints = &skins[std::size_t(node.skin)];
                        d.joint_texture = &r.joint_textures[std::size_t(node.skin)];
                    }
                    // The weight changes, four to a vec4, appended to the frame's list where one is not zero.
                    const std::vector<float>& weights = node.weights.empty() ? mesh.weights : node.weights;
                    const std::size_t first = r.morph_weights.size();
                    bool morphed = false;
                    for (int k = 0; k < p.morph_targets; ++k) {
                        const float w = std::size_t(k) < weights.size() ? weights[std::size_t(k)] : 0.0f;
                        const float change = w - p.applied_weights[std::size_t(k)];
                        if (k % 4 == 0) r.morph_weights.emplace_back(0.0f);
                        r.morph_weights.back()[k % 4] = change;
                        morphed = morphed || change != 0.0f;
                    }
                    if (morphed && !p.morph_texture && k < mesh.primitives.size())
                        Impl::upload_morph_texture(mesh.primitives[k], p);  // the first frame that morphs it
                    if (morphed && p.morph_texture) d.morph_weights = int(first);
                    else r.morph_weights.resize(first);
                    stats.gpu_skinned_draws += d.joints != nullptr;
                    stats.gpu_morphed_draws += d.morph_weights >= 0;
                }
                const Material* m = p.material >= 0 ? &r.scene->materials[std::size_t(p.material)] : nullptr;
                if (m && is_transmissive(*m) && material_shading(settings.shading, *m) == ShadingModel::Gltf)
                    transmissive.push_back(d);
                else if (m && m->alpha_mode == AlphaMode::Blend) blended.push_back(d);
                else opaque.push_back(d);
            }
        }
        // Blended primitives last, far to near; transmissive ones (KHR_materials_transmission)
        // between the opaque and the blended ones, far to near, as the Khronos Sample Viewer.
        // (std::sort with the scene order as tie-break: stable_sort would allocate a buffer each frame.)
        auto far_to_near = [](const Draw& a, const Draw& b) {
            return a.depth != b.depth ? a.depth > b.depth : a.sequence < b.sequence;
        };
        std::sort(blended.begin(), blended.end(), far_to_near);
        std::sort(transmissive.begin(), transmissive.end(), far_to_near);
        r.plan_frame_shadows(cam, lights, settings);
        r.pack_frame(cam, lights, settings);
        const std::uint64_t shadow_key = r.frame_shadows > 0 ? r.shadow_inputs_key() : 0;
        r.instance_data.clear();
        if (r.frame_shadows > 0 && (shadow_key != r.shadow_key || !r.shadow_atlas)) {
            r.draw_shadow_maps(settings, stats);
            r.shadow_key = shadow_key;
            r.device.bind_framebuffer(&r.targets->msaa_fb);
            r.device.viewport(0, 0, w, h);
        }
        // The frame draws what its view sees (the shadow maps above saw every caster): the opaque
        // draws batched (batch_draws), the blended and transmissive ones in their order.
        const glm::mat4 view_projection = cam.projection * cam.view;
        auto in_view = [&](const Draw& d) {
            // Skinned, morphed and CPU-posed draws move off their boxes: always drawn.
            const bool seen = !settings.frustum_culling || d.joints || d.morph_weights >= 0 || d.posed || d.prim->deformable ||
                              !Impl::box_outside(view_projection * d.model, d.prim->bounds_min, d.prim->bounds_max);
            stats.culled_draws += !seen;
            return seen;
        };
        r.batch_draws(opaque, in_view, settings, r.visible_draws);
        const std::vector<Draw>& opaque_visible = r.visible_draws;
        r.frame_ssao = false;
        if (settings.ssao && settings.debug == DebugChannel::None) {
            r.draw_ssao(cam, settings, opaque_visible, stats);
            r.device.bind_framebuffer(&r.targets->msaa_fb);
            r.device.viewport(0, 0, w, h);
        }
        std::erase_if(blended, [&](const Draw& d) { return !in_view(d); });
        std::erase_if(transmissive, [&](const Draw& d) { return !in_view(d); });
        r.transmission_ready = false;
        if (!transmissive.empty() && settings.debug == DebugChannel::None) {
            // The transmission pass: what the transmissive primitives refract (everything else,
            // with the environment background when the frame shows one), in linear radiance.
            const int size = transmission::kFramebufferSize;
            r.ensure_transmission_target(samples);
            r.device.bind_framebuffer(samples > 1 ? &r.transmission_msaa_fb : &r.transmission_fb);
            r.device.viewport(0, 0, size, size);
            r.device.clear(transparent ? glm::vec4(0.0f) : glm::vec4(glm::vec3(settings.background), 1.0f), true);
            if (settings.environment && settings.background_mode != RenderSettings::Background::Color)
                r.draw_sky(cam, settings, true);
            r.linear_pass = true;
            for (const auto& d : opaque_visible) r.draw_primitive(d, cam, lights, settings, stats);
            for (const auto& d : blended) r.draw_primitive(d, cam, lights, settings, stats);
            r.linear_pass = false;
            if (samples > 1) r.device.blit_color(r.transmission_msaa_fb, r.transmission_fb, size, size);
            r.transmission_texture.generate_mipmaps();
            r.transmission_ready = true;
            r.device.bind_framebuffer(&r.targets->msaa_fb);
            r.device.viewport(0, 0, w, h);
        }
        for (const auto& d : opaque_visible) r.draw_primitive(d, cam, lights, settings, stats);
        for (const auto& d : transmissive) r.draw_primitive(d, cam, lights, settings, stats);
        for (const auto& d : blended) r.draw_primitive(d, cam, lights, settings, stats);
    }

    const Impl::FrameTargets& ft = *r.targets;
    if (!ft.shader_resolve) r.device.blit_color(ft.msaa_fb, ft.resolved_fb, w, h);

    // Output pass, into the offscreen image or the default framebuffer.
    const bool to_default = target.kind == RenderTarget::Kind::DefaultFramebuffer;
    if (target.kind == RenderTarget::Kind::Offscreen8) r.ensure_output8(w, h);
    r.device.bind_framebuffer(to_default                                       ? nullptr
                              : target.kind == RenderTarget::Kind::Offscreen8 ? &r.output8_fb
                                                                               : &r.output_fb);
    if (to_default) r.device.viewport(target.x, target.y, w, h);
    else r.device.viewport(0, 0, w, h);
    gpu::PipelineState post;
    post.depth_test = false;
    post.depth_write = false;
    post.cull = gpu::Cull::None;
    r.device.apply(post);
    const bool unpremultiply = transparent && settings.straight_alpha;
    const int resolve_samples = ft.shader_resolve ? ft.samples : 0;
    const gpu::Program& prog = r.shaders.get_keyed(
        "fullscreen.vert", "post.frag",
        {Impl::kOutputPrograms, 0, -1, std::uint32_t(resolve_samples) << 1 | (unpremultiply ? 1u : 0u)}, [&] {
            std::vector<std::string> defines{std::string("STRAIGHT_ALPHA ") + (unpremultiply ? "1" : "0")};
            if (ft.shader_resolve) {
                defines.emplace_back("MSAA_RESOLVE");
                defines.push_back("MSAA_SAMPLES " + std::to_string(resolve_samples));
            }
            return defines;
        });
    prog.use();
    if (ft.shader_resolve) {
        r.device.bind_texture(int(TextureUnit::Frame), ft.msaa_texture);
        prog.set("u_frame_ms", int(TextureUnit::Frame));  // the sample count and the alpha choice are compiled in
    } else {
        r.device.bind_texture(int(TextureUnit::Frame), ft.resolved);
        prog.set("u_frame", int(TextureUnit::Frame));
    }
    const bool scissored = to_default && target.scissor;
    if (scissored) r.device.scissor(target.scissor->x, target.scissor->y, target.scissor->width, target.scissor->height);
    r.device.draw_fullscreen();
    if (scissored) r.device.no_scissor();
    stats.gl_errors = r.device.take_errors();
    if (stats_out) *stats_out = stats;
}

void Renderer::finish() { impl_->device.finish(); }

Image8 to_image8(const ImageF& image, bool alpha) {
    Image8 out(image.width, image.height, alpha ? 4 : 3);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float* s = image.at(x, y);
            std::uint8_t* d = out.at(x, y);
            for (int c = 0; c < out.channels; ++c) {
                float v = std::isfinite(s[c]) ? std::clamp(s[c], 0.0f, 1.0f) : 0.0f;
                // lround(v * 255) for v >= 0, without a libm call per channel (exact in double).
                d[c] = std::uint8_t(double(v * 255.0f) + 0.5);
            }
        }
    return out;
}

}  // namespace fresnel
