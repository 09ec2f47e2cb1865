#pragma once
// Baking an environment into what the renderer samples, on disk and in a cache.
//
// A baked folder holds:
//   manifest.json      parameters, source, content hash, SH coefficients, timings, file list
//   specular.ktx2      GGX-prefiltered cube map, RGBA16F, all faces and levels
//   irradiance.ktx2    irradiance / pi as a small cube map (see BakeOptions::irradiance_samples), RGBA16F
//   irradiance_sh.json the 9 SH coefficients of irradiance / pi (RGB)
//   sheen.ktx2         KHR_materials_sheen's Charlie-prefiltered cube map (prefilter_charlie), RGBA16F
//   charlie_lut.ktx2   the sheen's Charlie table (compute_charlie_lut), RGBA16F; computed on load when absent
//   brdf_lut.ktx2      split-sum table, RGBA16F: R = A, G = B, B = A + B (directional albedo), A = sheen albedo
//   preview/           OpenEXR previews: specular_level<k>.exr and irradiance.exr (faces side by side), brdf_lut.exr
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "fresnel/core/image.h"
#include "fresnel/ibl/cubemap.h"
#include "fresnel/ibl/dominant_light.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/ibl/precompute.h"

namespace fresnel::ibl {

struct BakeOptions {
    int size = 256;          // specular level 0 face size
    int levels = 5;          // specular levels (roughness k/(levels-1))
    int samples = 1024;      // GGX samples per texel (of the same kernel whatever the count: PrefilterOptions::lod_samples)
    int lut_size = 128;
    int lut_samples = 1024;
    int irradiance_size = 16;  // face size of the irradiance cube (irradiance is smooth; sampled bilinearly)
    // Irradiance: filtered importance sampling with this many cosine samples (the Khronos
    // Sample Viewer's method and blur), or 0 for the exact brute-force convolution of the
    // 32x32 mip (sharper near small bright sources).
    int irradiance_samples = 2048;
    float lod_bias = 1.8257f;  // see PrefilterOptions::lod_bias
    unsigned threads = 0;
    bool use_lut_cache = true;  // bake(): the BRDF table through load_or_bake_lut (read from / written to cache_root())
    std::string key() const;  // the parameters as a string (cache key, manifest)
};

struct BakedIbl {
    Cubemap specular;
    Cubemap irradiance_map;  // irradiance / pi, irradiance_size^2 faces (what shading samples)
    SH9 irradiance;          // the same as SH: evaluate(n) = irradiance(n) / pi
    ImageF lut;      // lut_size^2: R = A, G = B, B = A + B, A = sheen albedo
    Cubemap sheen;       // Charlie-prefiltered (prefilter_charlie), same levels as specular
    ImageF charlie_lut;  // compute_charlie_lut(): computed on bake, stored as charlie_lut.ktx2
    std::string source;
    std::string key;
    double bake_ms = 0;
    // Where the bake's time went: cube conversion + mips, specular prefilter, irradiance, LUT.
    double cube_ms = 0, specular_ms = 0, irradiance_ms = 0, lut_ms = 0;
    bool from_cache = false;
    // Set when the source asked for it (EnvironmentSource::split_dominant_light) and the panorama
    // has one: the light taken out of the maps above, in the environment's frame.
    std::optional<DominantLight> dominant_light;
    // With a dominant light taken out: the whole panorama prefiltered as `specular` is (same size
    // and levels), which a background drawn from the environment shows (the light's region
    // included); the shading reads `specular`, without it. Empty otherwise.
    Cubemap background;
    // Identity of the baked data (specular, irradiance, table): baked_content_hash(*this),
    // set by bake() and load_baked(). Renderers key their uploads by it, not by address.
    std::uint64_t content_hash = 0;
};

// A 64-bit hash of the texels of `ibl` (its specular cube, irradiance cube and table);
// word-wise, about 2 ms for the default 256^2 bake.
std::uint64_t baked_content_hash(const BakedIbl& ibl);
// The same hash of one float image (the renderer keys its table upload by it).
std::uint64_t image_content_hash(const ImageF& image, std::uint64_t seed = 0);

// Bakes a panorama (equirect, linear).
BakedIbl bake(const ImageF& panorama, const BakeOptions& options, const Progress& progress = {});

// Only the BRDF table (for punctual-light energy compensation without an environment).
ImageF bake_lut(const BakeOptions& options);

void save_baked(const BakedIbl& ibl, const std::filesystem::path& dir, const BakeOptions& options, bool previews = true);
// Loads a folder written by save_baked; throws fresnel::Error naming the file on bad input.
BakedIbl load_baked(const std::filesystem::path& dir);
bool is_baked_dir(const std::filesystem::path& dir);

// The BRDF table alone, cached under cache_root() by its parameters; use_cache = false bakes
// it without reading or writing the cache.
ImageF load_or_bake_lut(const BakeOptions& options, bool use_cache = true);

// 64-bit FNV-1a of a byte range (cache keys).
std::uint64_t content_hash(std::span<const std::uint8_t> bytes, std::uint64_t seed = 1469598103934665603ull);

// The cache folder: $XDG_CACHE_HOME/fresnel, else $HOME/.cache/fresnel, else <temp>/fresnel-cache.
std::filesystem::path cache_root();

// The environment of `source` baked with `options`: a baked folder is loaded as is; a
// panorama is baked once and cached under cache_root() by content hash and parameters.
// use_cache = false touches no cache at all (neither the environment nor the BRDF table).
BakedIbl load_or_bake(const EnvironmentSource& source, const BakeOptions& options, const Progress& progress = {},
                      bool use_cache = true);

}  // namespace fresnel::ibl
