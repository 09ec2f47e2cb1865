#pragma once
// Writers for converters (`fresnel convert`): a Scene as glTF 2.0 (.gltf with one .bin and
// PNG images beside it, or a single .glb with everything embedded) and as Wavefront OBJ/MTL.
// Both write every file to a temporary name in the destination folder and rename it into
// place, so a reader never sees half a file.
//
// glTF: nodes (as matrices), meshes (POSITION, NORMAL, TANGENT, TEXCOORD_0/1, COLOR_0,
// 32-bit indices; triangles, lines, points), materials with KHR_materials_specular, _ior,
// _emissive_strength, _unlit, _clearcoat and KHR_texture_transform, textures (images
// re-encoded as PNG from the decoded pixels), samplers, cameras, KHR_lights_punctual (and area lights as EXT_lights_area when asked).
// Not written: skins and animations (the Scene holds no animations; joints and weights are
// dropped), the kept-but-unshaded extension blocks (sheen, transmission, ...) and unknown
// extensions and extras (the glTF loader does not keep them; save_gltf_material_edits below
// keeps them, for edits of a file's materials).
//
// OBJ: one `o` per mesh instance, with its node's world transform applied to positions
// and normals (identity for scenes from OBJ files, so the numbers round-trip), `vt` with
// glTF's top-left UV origin flipped back, `vn`, faces v/vt/vn, `usemtl` per primitive;
// MTL from each Material's `phong` block (Ka Kd Ks Ke Ns d illum, and the PBR extension
// keys Pr Pm when `pbr_keys`), map_Kd / map_Ks / map_Ke / norm as PNG files beside it.
// Floats are written with 9 significant digits, which reads back to the same float.
#include <filesystem>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

// `.glb` writes a binary container; anything else a .gltf with `<stem>.bin` and
// `<stem>_imageN.png` beside it. Every writer here returns the files it wrote (one set,
// committed together).
struct GltfWriteOptions {
    // Area lights as EXT_lights_area (fresnel's extension; other viewers ignore it). Off: they
    // are left out with a warning, and the file uses only ratified extensions.
    bool area_lights = false;
};
std::vector<std::filesystem::path> write_gltf(const Scene& scene, const std::filesystem::path& path, Diagnostics& diagnostics,
                                              const GltfWriteOptions& options = {});

// glTF -> glTF as the file is, in the container `dest` names (.gltf or .glb): the JSON key by
// key (animations, skins, morph targets, cameras, lights, extras, every name, unknown
// extensions with a warning that they are carried blind, asset with its copyright; a
// generator added when there is none) and the binary data and images byte for byte (their
// original encoding and MIME type). Only the container changes: the buffers are merged into
// one (inside a .glb, or `<stem>.bin` beside a .gltf), images go into a .glb's buffer or stay
// files beside a .gltf (copied when the folder changes). Converting the result again gives
// the same JSON and bytes. The source is loaded first (what the loader refuses is refused);
// the new files are one set, committed together. Throws fresnel::Error.
std::vector<std::filesystem::path> copy_gltf(const std::filesystem::path& source, const std::filesystem::path& dest,
                                             Diagnostics& diagnostics, bool allow_external_files = false);

struct ObjWriteOptions {
    bool pbr_keys = true;  // Pr/Pm from the metallic-roughness factors, beside the Phong keys
};
// Writes path (.obj), `<stem>.mtl` and `<stem>_imageN.png` beside it. Materials without a
// `phong` block get the naive Kd = base colour, Ks 0.04 (converters fill `phong` first).
std::vector<std::filesystem::path> write_obj(const Scene& scene, const std::filesystem::path& path, Diagnostics& diagnostics,
                                             const ObjWriteOptions& options = {});

// Material edits written back into the glTF file they came from, losslessly: `source`
// (.gltf or .glb) is written to `dest` (the same container; may be `source` itself) with the
// values that differ between `original` (the materials as loaded from `source`, in file order)
// and `edited` replaced, and nothing else changed. The JSON is parsed and written back with its
// keys in order, so unknown extensions, extras, names and other materials stay; a .glb's BIN
// chunk (and any other chunk) is copied byte for byte; a .gltf's .bin and image files are not
// touched (copied beside `dest` when it is in another folder). Values written: baseColorFactor,
// metallicFactor, roughnessFactor, emissiveFactor, alphaMode, alphaCutoff, doubleSided,
// normalTexture.scale, occlusionTexture.strength, KHR_materials_emissive_strength, _ior,
// _specular (specularFactor, specularColorFactor), _clearcoat (clearcoatFactor,
// clearcoatRoughnessFactor); a new extension block is added to extensionsUsed. Atomic: a
// failed write leaves `dest` as it was. Returns how many values were written; throws
// fresnel::Error (file, reason); what cannot be written goes to `diagnostics`.
int save_gltf_material_edits(const std::filesystem::path& source, const std::filesystem::path& dest,
                             const std::vector<Material>& original, const std::vector<Material>& edited,
                             Diagnostics& diagnostics);

}  // namespace fresnel
