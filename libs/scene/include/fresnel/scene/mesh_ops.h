#pragma once
// Mesh operations every loader needs once its file is decoded to plain arrays: index
// conversion (strips, fans, loops to lists), normal and tangent repair and generation,
// vertex compaction, node world matrices and skin posing at the rest pose.
//
// They take plain vectors or a fresnel::Primitive, never a file's accessors, so the glTF
// loader and any other loader (OBJ, ...) share them. Conventions:
//  - A Primitive's `indices` empty means non-indexed (vertex i is index i). Every index must
//    be < vertex_count() and every per-vertex array empty or vertex_count() long; the loaders
//    check this before calling (the functions here do not validate, except where stated).
//  - "Triangle list" means three indices per triangle, counter-clockwise front faces.
//  - The repair and generation functions never produce NaN or infinity: zero-length normals
//    and tangents get documented fallbacks. The transforms assume invertible matrices.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "fresnel/scene/scene.h"
#include "fresnel/scene/tangents.h"

namespace fresnel {

// ---- Index conversion -----------------------------------------------------------------

// Triangle strip to triangle list, keeping every triangle's winding: triangle k (k = 0 ..
// n - 3) is (k, k+1, k+2) for even k and (k+1, k, k+2) for odd k, as glTF and OpenGL
// define strips. Fewer than three indices give an empty list.
std::vector<std::uint32_t> strip_to_triangles(std::span<const std::uint32_t> strip);

// Triangle fan to triangle list: triangle k is (0, k+1, k+2), the fan's winding.
std::vector<std::uint32_t> fan_to_triangles(std::span<const std::uint32_t> fan);

// Line strip to line list: segments (k, k+1). Fewer than two indices give an empty list.
std::vector<std::uint32_t> line_strip_to_lines(std::span<const std::uint32_t> strip);

// Line loop to line list: the strip's segments plus the closing one (n-1, 0) when the loop
// has at least three indices (two indices give one segment, not the same one twice).
std::vector<std::uint32_t> line_loop_to_lines(std::span<const std::uint32_t> loop);

// The primitive's index list: `indices`, or 0 .. vertex_count()-1 when it is non-indexed.
std::vector<std::uint32_t> index_list(const Primitive& p);

// ---- Normals and tangents ---------------------------------------------------------------

// Renormalises every normal. A normal that is zero (length <= 1e-20), infinite or NaN is
// replaced by the area-weighted average of the faces of the triangles around its vertex
// (`triangles`: a triangle list into `positions`), or by +Z when those faces have no area.
// Returns how many normals were replaced (renormalised ones are not counted; normals within
// 1e-5 of unit length are kept as they are).
std::size_t repair_normals(std::span<const glm::vec3> positions, std::span<const std::uint32_t> triangles,
                           std::span<glm::vec3> normals);
// The same on a triangle primitive with normals (returns 0 for other primitives).
std::size_t repair_normals(Primitive& p);

// Flat normals for a triangle primitive: every triangle gets three vertices of its own (all
// attributes are copied through the index list, so unreferenced vertices are dropped) with
// the unit face normal (+Z for a triangle without area). The result is non-indexed and has
// generated_normals set. Does nothing for primitives that are not triangles.
void generate_flat_normals(Primitive& p);

// MikkTSpace tangents (fresnel::generate_tangents in tangents.h) for a triangle primitive
// with normals, from TEXCOORD_`tex_coord` (0 or 1). Vertices are split where MikkTSpace
// gives one vertex several tangents; every attribute follows and generated_tangents is set.
// Returns false (and changes nothing) when the primitive is not triangles or has no normals
// or no such texture coordinates.
bool generate_tangents(Primitive& p, int tex_coord);
// The slot whose UV set a primitive of material `m` without tangents generates them from: the
// normal map, else the clearcoat normal map, else (KHR_materials_anisotropy, whose direction lies
// in the tangent frame) the anisotropy texture, TEXCOORD_0 without one; nullptr when nothing
// needs tangents.
const TextureSlot* tangent_source(const Material& m);

// Makes every tangent a unit xyz with w = +1 or -1 (w < 0 becomes -1, anything else +1);
// a zero, infinite or NaN xyz becomes (1, 0, 0, 1).
void repair_tangents(std::span<glm::vec4> tangents);

// ---- Vertices and indices ---------------------------------------------------------------

// Rebuilds every per-vertex array of `p` (positions, normals, tangents, uvs, colours,
// joints, weights) so that output vertex i is input vertex remap[i]. Indices are untouched.
void remap_vertices(Primitive& p, std::span<const std::uint32_t> remap);

// Drops the index buffer when it is the identity 0, 1, ..., vertex_count()-1 (the primitive
// then draws the same without it). Returns whether it was dropped.
bool drop_identity_indices(Primitive& p);

// Removes the vertices no index refers to, keeping the others in their order, and renumbers
// the indices; then drops an identity index buffer. Non-indexed primitives are unchanged.
// Returns the remap (new vertex -> old vertex).
std::vector<std::uint32_t> compact_vertices(Primitive& p);

// Reorders the triangles of a triangle list (three indices each, every index < uv.size())
// so that triangles whose UV centroids are near each other come one after another: Morton
// (Z) order of the centroid's fractional part, 16 bits an axis, ties in the old order. Each
// triangle keeps its indices and winding. A rasteriser that shades a screen tile's triangles
// in submission order then reads the textures of one region at a time (llvmpipe:
// DamagedHelmet's frame ~5-8 % faster; a random order made it 13-22 % slower). For opaque
// geometry the picture is the same except where coplanar triangles overlap (depth ties);
// the order of blended triangles is the blend's order, so callers keep theirs. Does nothing
// when the list is not whole triangles or an index is out of range.
void sort_triangles_by_uv(std::vector<std::uint32_t>& triangles, std::span<const glm::vec2> uv);

// ---- Transforms and skinning ------------------------------------------------------------

// World matrix of every node: the product of the local matrices from its root down
// (world = parent's world * local). The nodes are expected to form a forest (one parent at
// most, no cycles). Bad input cannot make it loop: children out of range are ignored, a
// node with several parents takes the first one reached, and a node reachable only
// through a cycle keeps its local matrix.
std::vector<glm::mat4> world_matrices(std::span<const Node> nodes);

// A skin's joint matrices: world[joints[j]] * inverse_bind[j] (identity where inverse_bind
// has no entry j). Joint node indices must be < world.size().
std::vector<glm::mat4> joint_matrices(std::span<const glm::mat4> world, std::span<const int> joints,
                                      std::span<const glm::mat4> inverse_bind);

// Every skin's joint matrices at the nodes' current matrices, in storage that is kept from one
// call to the next (a viewer poses every frame: a warm call allocates nothing). The loader's
// posing, fresnel::pose_meshes and the renderer's GPU skinning all take them from here.
struct SkinMatrices {
    std::vector<glm::mat4> world;                // every node's world matrix (world_matrices)
    std::vector<std::vector<glm::mat4>> skins;   // per skin; empty where the skin cannot be posed
    // world_matrices' workspace.
    std::vector<std::uint8_t> has_parent, done;
    std::vector<std::size_t> stack;
};
// Fills `out` for `skins` over `nodes`. A skin without joints, with a joint index out of range
// or with more than `max_joints` joints (the renderer's shader limit) gets no matrices.
void skin_matrices(std::span<const Node> nodes, std::span<const Skin> skins, SkinMatrices& out,
                   std::size_t max_joints = std::size_t(-1));

// The first vertex of a skinned primitive that gives weight to a joint >= joint_count.
struct InvalidJoint {
    std::size_t vertex = 0;
    std::uint32_t joint = 0;
};
std::optional<InvalidJoint> find_invalid_joint(const Primitive& p, std::size_t joint_count);

// Transforms positions by m, normals by its inverse transpose and tangents by its upper 3x3
// (w kept); normals and tangents are renormalised.
void transform_primitive(Primitive& p, const glm::mat4& m);

// Poses a primitive at its skin's pose (glTF 2.0 linear blend skinning): each vertex is moved
// by sum_c weights[c] * joint_matrices[joints[c]], normals and tangents as in
// transform_primitive. Vertices with no weight follow `node_world`; a primitive without
// JOINTS_0 is transformed by `node_world` as a whole. The result is in world space. Weighted
// joints out of range (see find_invalid_joint) are ignored.
// SkinWeights::Homogeneous divides each position by the blended matrix's w (the sum of the
// weights), as the Khronos Sample Viewer's vertex shader does through the perspective divide:
// weights that do not sum to 1 then act normalised (animated poses use it, fresnel/scene/pose.h).
enum class SkinWeights { AsGiven, Homogeneous };
void pose_skinned(Primitive& p, std::span<const glm::mat4> joint_matrices, const glm::mat4& node_world,
                  SkinWeights mode = SkinWeights::AsGiven);

}  // namespace fresnel
