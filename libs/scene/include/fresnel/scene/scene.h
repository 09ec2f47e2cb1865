#pragma once
// The in-memory scene every loader produces and every renderer consumes.
// Geometry is already decoded to float arrays, triangle strips/fans are
// converted to lists, and missing normals/tangents are generated, so
// consumers never see raw glTF accessors.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec4.hpp>
#include <glm/ext/vector_uint4.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/core/image.h"
#include "fresnel/core/sampler.h"
#include "fresnel/material/material.h"
#include "fresnel/scene/animation.h"

namespace fresnel {

// Material, TextureSlot (TextureRef) and AlphaMode come from libs/material: the material
// model is not the scene's; loaders translate files into it.

// How a texture is sampled. The default is glTF's when a texture has no sampler:
// trilinear (linear filters, linear between mip levels), repeating.
struct Sampler {
    Filter mag_filter = Filter::Linear;
    Filter min_filter = Filter::Linear;        // within a mip level
    MipmapMode mipmap = MipmapMode::Linear;    // minification across mip levels
    Wrap wrap_s = Wrap::Repeat;
    Wrap wrap_t = Wrap::Repeat;
    bool uses_mipmaps() const { return mipmap != MipmapMode::None; }
    bool operator==(const Sampler&) const = default;
};

struct Texture {
    int image = -1;  // index into Scene::images; -1 = missing (renderers use a neutral fallback)
    Sampler sampler;
};

struct SceneImage {
    std::string name;  // URI or "image N" for diagnostics
    Image8 pixels;     // RGBA8; empty when the image could not be decoded (a warning was issued)
    // What the file holds, from the encoded image's header (set when the loader read its bytes):
    // format and size (peek_image_header), and its encoded size.
    ImageHeader header;
    std::size_t encoded_bytes = 0;
    // The file's bytes, kept when the loader was asked to (GltfLoadOptions::keep_encoded_images):
    // then `pixels.pixels` may be released once the image is on the GPU (width and height stay,
    // released() says so) and decode_again gives the pixels back. Shared: copies of a scene
    // share the bytes, not the decoded pixels.
    std::shared_ptr<const std::vector<std::uint8_t>> encoded;
    SceneImage() = default;
    SceneImage(std::string image_name, Image8 image) : name(std::move(image_name)), pixels(std::move(image)) {}
    bool valid() const { return pixels.width > 0; }
    // Whether the decoded pixels were let go (release_pixels): read them with decode_again.
    bool released() const { return valid() && pixels.pixels.empty(); }
    // Frees the decoded pixels where the encoded bytes can give them back; false (nothing freed)
    // where they cannot.
    bool release_pixels();
};

// A released image's pixels decoded again from its encoded bytes, as the loader decoded them
// (8-bit RGBA; WebP, PNG, JPEG, KTX2). Throws fresnel::Error naming the image when it holds no
// encoded bytes or they no longer decode to its size.
Image8 decode_again(const SceneImage& image);

enum class Topology { Points, Lines, LineLoop, LineStrip, Triangles };

// A morph target's displacements (glTF `targets`): each array empty or one per vertex.
struct MorphTarget {
    std::vector<glm::vec3> positions, normals, tangents;
};

struct Primitive {
    Topology topology = Topology::Triangles;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;    // always present for triangles (generated flat when absent)
    std::vector<glm::vec4> tangents;   // present when given, or generated when a normal map is used
    std::vector<glm::vec2> uv0, uv1;
    std::vector<glm::vec4> colors;     // COLOR_0 as RGBA (alpha 1 for vec3)
    std::vector<std::uint32_t> indices;  // empty = non-indexed
    // Skinning inputs (JOINTS_0 / WEIGHTS_0); the loader poses skinned meshes at rest only
    // with GltfLoadOptions::pose_skins (default: the bind pose).
    std::vector<glm::uvec4> joints;
    std::vector<glm::vec4> weights;
    // Morph targets, kept for animation; positions, normals and tangents above already hold
    // them at `applied_weights` (the mesh's default weights, the rest pose).
    std::vector<MorphTarget> targets;
    std::vector<float> applied_weights;
    int material = -1;                   // -1 = the glTF default material
    // The POSITION accessor's min/max (used by the camera convention); falls back to the data.
    glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};
    std::size_t source_vertex_count = 0;  // the POSITION accessor's count, before any re-indexing
    // KHR_materials_variants: the material of each of Scene::material_variants for this
    // primitive (-1: none mapped, keep `material`); empty when the primitive has no mappings.
    std::vector<int> variant_materials;
    bool generated_normals = false;
    bool generated_tangents = false;
    std::size_t vertex_count() const { return positions.size(); }
    std::size_t triangle_count() const;
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
    std::vector<float> weights;  // default morph weights (glTF mesh.weights)
};

// glTF skin: joint nodes and their inverse bind matrices (identity where the file has none).
struct Skin {
    std::string name;
    std::vector<int> joints;
    std::vector<glm::mat4> inverse_bind;  // one per joint
};

struct Camera {
    enum class Type { Perspective, Orthographic } type = Type::Perspective;
    std::string name;
    float yfov = 0.8f;                 // radians
    std::optional<float> aspect_ratio;
    float znear = 0.01f;
    std::optional<float> zfar;         // perspective: absent = infinite
    float xmag = 1.0f, ymag = 1.0f;    // orthographic half extents
};

// KHR_lights_punctual and fresnel's area lights (EXT_lights_area in glTF files). Intensity:
// directional in lux, point and spot in candela, area lights in nits (cd/m^2: the luminance of
// the emitting surface, the same everywhere on it and in every direction it emits).
struct Light {
    // The order is the shaders' light type code (frame_block.glsl).
    enum class Type { Directional, Point, Spot, Rect, Disk, Sphere, Tube } type = Type::Directional;
    std::string name;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;                 // 0 = infinite
    float inner_cone_angle = 0.0f;      // radians
    float outer_cone_angle = 0.7853982f;
    // Area lights, in the node's space: a rectangle width x height (along its X and Y) or a disk
    // of `radius` in the node's XY plane, emitting from the side its -Z faces (as spot lights
    // point); a sphere of `radius` emitting everywhere; a tube (a capsule: a cylinder of
    // `radius` with round ends) `length` long along the node's X, emitting everywhere. Metres.
    float width = 1.0f, height = 1.0f, radius = 0.5f, length = 1.0f;
};

// Rectangle, disk, sphere and tube lights (the rest are punctual).
inline bool is_area_light(Light::Type t) {
    return t == Light::Type::Rect || t == Light::Type::Disk || t == Light::Type::Sphere || t == Light::Type::Tube;
}

// "directional", "point", "spot", "rect", "disk", "sphere", "tube": the names glTF files
// (KHR_lights_punctual, EXT_lights_area) and scene files give the types.
inline const char* light_type_name(Light::Type type) {
    switch (type) {
        case Light::Type::Directional: return "directional";
        case Light::Type::Point: return "point";
        case Light::Type::Spot: return "spot";
        case Light::Type::Rect: return "rect";
        case Light::Type::Disk: return "disk";
        case Light::Type::Sphere: return "sphere";
        case Light::Type::Tube: return "tube";
    }
    return "directional";
}

struct Node {
    std::string name;
    glm::mat4 local{1.0f};
    int mesh = -1, camera = -1, light = -1;
    int skin = -1;  // index into Scene::skins
    std::vector<int> children;
    // The local transform as T * R * S (what animations drive); has_trs is false when the
    // file gave a matrix (animations then cannot target the node). `local` is their product.
    glm::vec3 translation{0.0f}, scale{1.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    bool has_trs = true;
    std::vector<float> weights;  // morph weights set by an animation (empty: the mesh's)
    // The node's mesh is skinned and already posed in world space (rest pose): draw it with
    // the identity, not the node's world matrix (which still places its bounds, as the
    // camera convention uses the POSITION accessor's box).
    bool world_space_mesh = false;
    // KHR_node_visibility: false hides the node and every node below it (their meshes and
    // lights are not drawn; cameras still work). NodeInstance::visible holds the result.
    bool visible = true;
};

// World-space axis-aligned bounds following the camera convention: the 8 corners
// of each primitive's POSITION min/max box transformed by its node's world matrix.
struct Bounds {
    glm::vec3 min{0.0f}, max{0.0f};
    bool empty = true;
    glm::vec3 center() const { return (min + max) * 0.5f; }
    float radius() const;  // half the diagonal
    // Grows to hold the box [box_min, box_max] after `transform` (its eight corners).
    void extend(const glm::mat4& transform, const glm::vec3& box_min, const glm::vec3& box_max);
};

struct Scene {
    std::string source;  // file it came from
    std::vector<Node> nodes;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<SceneImage> images;
    std::vector<Camera> cameras;
    std::vector<Light> lights;
    std::vector<Skin> skins;
    std::vector<Animation> animations;
    std::vector<std::vector<int>> scenes;  // root nodes of each scene
    int default_scene = 0;                 // the file's `scene`, else 0
    std::vector<std::string> extensions_used, extensions_required;
    // Set when several models were merged into this scene (append_model, fresnel/scene/merge.h):
    // one entry per model, in order, saying where its nodes, cameras and materials start.
    struct Part {
        std::string source;
        int root = -1;  // the node holding the model's transform; its children are the model's roots
        int first_camera = 0, camera_count = 0;
        int first_material = 0, material_count = 0;
    };
    std::vector<Part> parts;
    std::vector<std::string> material_variants;  // KHR_materials_variants names, in file order
    // The bounds a camera is fitted to, per scene index + 1 (entry 0: the default scene), kept
    // from the rest pose when the scene is first posed (fresnel::animate), so that every frame
    // of an animation, and a single frame at a time T, share the rest pose's camera. Empty:
    // the scene's own bounds (framing_bounds).
    std::vector<Bounds> framing;
};

// KHR_materials_variants. The index of the variant called `name`; throws fresnel::Error
// (file: scene.source) listing the known variants when there is none of that name.
int find_material_variant(const Scene& scene, const std::string& name);
// Gives every primitive the material variant `variant` maps it to (others keep theirs),
// generating tangents where the new material's normal map needs them. Not undoable:
// keep a copy of the scene to switch back.
void apply_material_variant(Scene& scene, int variant);

// A node instance in the scene graph with its world matrix (rest pose).
struct NodeInstance {
    int node = -1;
    glm::mat4 world{1.0f};
    bool visible = true;  // the node and all its ancestors are visible (Node::visible)
};

// Flattens the scene graph of scene `index` (-1 = default scene) into node instances.
std::vector<NodeInstance> flatten(const Scene& scene, int index = -1);

Bounds scene_bounds(const Scene& scene, const std::vector<NodeInstance>& instances);
// The bounds a camera of scene `index` (-1: the default) fits: Scene::framing's when the scene
// was posed, else scene_bounds(scene, instances) (`instances`: flatten(scene, index)).
Bounds framing_bounds(const Scene& scene, int index, const std::vector<NodeInstance>& instances);
// Scene::framing from the scene as it is now (animate() calls it on a rest pose).
void keep_framing(Scene& scene);

}  // namespace fresnel
