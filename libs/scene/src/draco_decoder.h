#pragma once
// KHR_draco_mesh_compression: a primitive whose attributes and indices are one Draco
// mesh in a bufferView. The primitive's accessors give count, type and componentType
// (they have no bufferView); the decoded mesh must agree with them.
#include <map>
#include <string>

#include "accessor.h"

namespace fresnel::gltf {

// Decodes the primitive's extension object `ext` (at JSON pointer `ptr`) into the values
// of the accessors it replaces: accessor index -> data, for each attribute it names and
// for the primitive's `indices`. Accessor counts are checked against `max_vertices`
// before decoding, and the decoded mesh against the accessors before values are copied.
// Throws fresnel::Error ("KHR_draco_mesh_compression: ...") on any mismatch.
std::map<int, AccessorData> decode_draco_primitive(const JsonReader& r, const json& prim, const json& ext,
                                                   const std::string& ptr, const AccessorDecoder& accessors,
                                                   std::size_t max_vertices);

}  // namespace fresnel::gltf
