#pragma once
// Wavefront OBJ/MTL loader. The file is treated as hostile, as the glTF loader treats
// its input: sizes and counts are capped, every index is checked, non-finite numbers are
// refused or repaired, and mtllib/texture paths may not leave the model's folder. Errors
// read FILE: line N: WHAT (fresnel::Error with where = "line N").
//
// What becomes of the file:
//  - one Mesh (and one root Node) per object/group (`o`, `g`; faces before either go to a
//    mesh named after the file), one Primitive per material used in it (`usemtl`); points
//    (`p`) and lines (`l`) become Points/Lines primitives of their own;
//  - polygons are triangulated by ear clipping in the polygon's plane (concave ones
//    correctly); degenerate or over-budget ones become fans (with a warning);
//  - indices may be negative (relative to the vertices read so far); `v x y z r g b` gives
//    vertex colours; `vt` v is flipped (glTF's UV origin is the top left);
//  - corners without `vn` get normals from the smoothing groups (`s N`: the area-weighted
//    average over the group's faces around each position; `s off`/`s 0`, the default:
//    the face's own normal);
//  - MTL materials become fresnel::Material by phong_to_metallic_roughness
//    (fresnel/material/phong.h), with the file's values kept in Material::phong; texture
//    paths are relative to the MTL file; scalar maps (map_d, map_Pr, map_Pm, map_Ns) are
//    packed into the glTF channels they feed. Faces without a known material use MTL's
//    defaults (OpenGL 1's: Kd 0.8, Ka 0.2).
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/material/material.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

struct ObjLoadOptions {
    // Allow mtllib and texture paths outside the model's folder (absolute paths, ".."
    // escapes). Never the network.
    bool allow_external_files = false;
    std::size_t max_file_bytes = std::size_t(2) << 30;      // the .obj and each .mtl
    // all texture files together: 8 GiB, or all of a 32-bit address space (the web build)
    std::size_t max_total_bytes = std::size_t(std::min<std::uint64_t>(std::uint64_t(8) << 30, SIZE_MAX));
    std::size_t max_elements = std::size_t(200) << 20;      // v + vt + vn + face corners
    std::size_t max_polygon_vertices = std::size_t(1) << 20;
    std::size_t max_materials = std::size_t(1) << 20;       // per MTL file
    std::size_t max_mtl_files = 256;
    // Work allowed for ear clipping over the whole file (vertex tests); past it, polygons
    // are fanned (with a warning), so a hostile file cannot make triangulation quadratic.
    std::size_t triangulation_budget = std::size_t(1) << 28;
    // Give corners without `vn` a smooth normal per position even without `s` statements
    // (what most viewers do; the OBJ specification's default is smoothing off).
    bool smooth_without_groups = false;
    ImageLimits image_limits{};
    bool decode_images = true;  // false: skip texture decoding (fresnel info)
    // With decode_images false: still read each image's bytes for its header (SceneImage::header,
    // encoded_bytes), as fresnel info lists formats and sizes.
    bool read_image_headers = false;
    unsigned threads = 0;       // image decoding threads, 0 = hardware concurrency
};

// Loads an OBJ file and its MTL files; throws fresnel::Error (file, "line N", reason) on
// bad input. Recoverable problems (a missing MTL or texture, an unknown statement, a
// non-finite normal, ...) become warnings.
Scene load_obj(const std::filesystem::path& path, Diagnostics& diagnostics, const ObjLoadOptions& options = {});

// Same, from memory (`name` is used in messages; mtllib paths resolve against `base_dir`).
Scene load_obj_from_memory(std::span<const std::uint8_t> bytes, const std::string& name,
                           const std::filesystem::path& base_dir, Diagnostics& diagnostics,
                           const ObjLoadOptions& options = {});

// One MTL material as parsed, with its texture paths as written (resolved by the loader).
struct MtlTextureRef {
    std::string path;          // as written, backslashes turned into '/'
    int line = 0;              // where in the MTL file
    bool clamp = false;        // -clamp on
    TextureTransform transform;  // -o / -s, converted to glTF's UV space
    bool has_transform = false;
};
struct MtlMaterialSource {
    std::string name;
    int line = 0;
    PhongExt phong;  // factors; the maps' slots are left empty
    // Paths of the maps, by the PhongExt member they feed (empty path = none).
    MtlTextureRef ambient, diffuse, specular, shininess, dissolve, emission, bump, roughness, metallic, sheen, normal;
};

// Parses MTL text (for the loader and tests). `name` is used in messages.
std::vector<MtlMaterialSource> parse_mtl(std::string_view text, const std::string& name, Diagnostics& diagnostics,
                                         std::size_t max_materials = std::size_t(1) << 20);

// True for paths the scene loaders read as OBJ (".obj", any case).
bool is_obj_path(const std::filesystem::path& path);

}  // namespace fresnel
