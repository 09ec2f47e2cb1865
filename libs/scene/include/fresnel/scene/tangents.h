#pragma once
// MikkTSpace-compatible per-vertex tangent generation (glTF 2.0 requires MikkTSpace
// tangents when a primitive with a normal map has no TANGENT attribute).
//
// Convention: glTF texture coordinates have their origin at the top-left of the image
// (v runs down) and normal textures are "+Y up". MikkTSpace (as in Blender) assumes v runs
// up, so tangents are evaluated on (u, 1 - v); this leaves the tangent direction unchanged
// and gives the sign w such that bitangent = w * cross(normal, tangent.xyz) points up the
// image (towards decreasing glTF v). This equals the output of MikkTSpace on the raw UVs
// with w negated, as Blender's glTF exporter and three.js's computeMikkTSpaceTangents do.
#include <cstdint>
#include <span>
#include <vector>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
namespace fresnel {
// Result of tangent generation: a re-indexed triangle list. Vertices are split
// where MikkTSpace would give one input vertex different tangents (e.g. at UV
// mirroring seams), so output vertex count >= number of distinct input vertices used.
struct TangentMesh {
    std::vector<std::uint32_t> remap;    // for each output vertex, the input vertex it came from
    std::vector<glm::vec4> tangents;     // per output vertex: xyz unit tangent orthogonal to the normal, w = +1 or -1 (bitangent = w * cross(normal, tangent.xyz))
    std::vector<std::uint32_t> indices;  // 3 per triangle, into the output vertices, same triangle order as input
};
// positions/normals/uvs are per input vertex; indices are a triangle list (size % 3 == 0,
// every value < positions.size(); the caller has validated this). Normals are assumed unit length
// (degenerate ones are tolerated). Never produces NaN: degenerate UVs or triangles get a
// tangent built from any vector orthogonal to the normal, w = +1.
TangentMesh generate_tangents(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                              std::span<const glm::vec2> uvs, std::span<const std::uint32_t> indices);
}
