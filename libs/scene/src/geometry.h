#pragma once
// Turns a glTF mesh primitive into a fresnel::Primitive: decodes and checks the
// attributes, indices and morph targets; the processing after that (strips and fans
// to lists, normal repair, flat normals, MikkTSpace tangents) is fresnel/scene/mesh_ops.h.
#include <optional>
#include <vector>

#include "accessor.h"
#include "fresnel/scene/scene.h"

namespace fresnel::gltf {

// Returns nullopt (after a warning) for primitives that cannot be drawn but do
// not make the file unusable; throws for structural errors. `mesh_quantization`:
// the file uses KHR_mesh_quantization (integer TEXCOORD/NORMAL/TANGENT allowed).
std::optional<Primitive> build_primitive(const JsonReader& r, const json& prim, const std::string& ptr,
                                         const AccessorDecoder& accessors, const std::vector<Material>& materials,
                                         std::size_t max_vertices, bool mesh_quantization,
                                         const std::vector<float>& morph_weights, Diagnostics& diag);

}  // namespace fresnel::gltf
