#pragma once
// Ambient occlusion baked with the tracer's rays (`--ao baked`): at every vertex of every
// placed primitive, cosine-distributed rays over the hemisphere of its normal ask the
// TraceScene whether anything stands in the way. The fraction that escape is the vertex's
// visibility of the environment (the factor a uniform environment's diffuse light loses
// there), their mean direction its bent normal. The rasteriser interpolates both
// (Renderer::set_vertex_occlusion).
//
// Static geometry only: skinned and morphed primitives (unless posed on the CPU, when their
// vertices are world positions), points and lines, primitives without normals and hidden
// nodes get no values. The samples are a Hammersley set rotated per vertex (Cranley-Patterson,
// from a hash of node, primitive and vertex): the same inputs give the same values on any
// number of threads.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

#include "fresnel/scene/scene.h"
#include "fresnel/scene/vertex_occlusion.h"
#include "fresnel/trace/tracer.h"

namespace fresnel::trace {

struct VertexOcclusionOptions {
    int rays = 128;            // per vertex
    float max_distance = 0.0f; // > 0: hits farther than this do not occlude (0: any distance)
    unsigned threads = 0;      // 0: all cores
    std::uint64_t seed = 0;
};

// Called with the fraction of vertices done (from worker threads).
using OcclusionProgress = std::function<void(double fraction)>;

// `tscene` must hold `scene` placed by `instances` (the same flatten() the renderer draws).
VertexOcclusion bake_vertex_occlusion(const TraceScene& tscene, const Scene& scene,
                                      const std::vector<NodeInstance>& instances,
                                      const VertexOcclusionOptions& options = {},
                                      const OcclusionProgress& progress = {});

// A 64-bit key of everything a bake's values depend on: the options, and every placed primitive
// (node, world matrix, positions, normals, indices, whether it deforms) with what decides whether
// rays pass its surfaces (alpha mode, cutoff, sidedness, base colour alpha and, for MASK and BLEND,
// the base colour image's texels).
std::uint64_t vertex_occlusion_key(const Scene& scene, const std::vector<NodeInstance>& instances,
                                   const VertexOcclusionOptions& options);

// The bake of `scene` as `instances` place it, from the cache under ibl::cache_root()/occlusion
// (by vertex_occlusion_key) when `use_cache` and an entry fits the scene, else baked (a
// TraceScene built for it, TraceSceneOptions::instancing = `instancing`) and, with `use_cache`,
// stored there (whole or absent; a cache that cannot be written is skipped). A cached result has
// bake_ms the time to read it and from_cache set.
VertexOcclusion load_or_bake_vertex_occlusion(const Scene& scene, const std::vector<NodeInstance>& instances,
                                              const VertexOcclusionOptions& options, bool use_cache,
                                              bool instancing = true, const OcclusionProgress& progress = {});

// The cache file's reader and writer (a small binary format: magic, key, rays, then per node and
// primitive a count and that many vec4s). read_vertex_occlusion treats the file as untrusted:
// nothing (not an error) when it is not one, is cut short, or does not fit `scene`.
void write_vertex_occlusion(const std::filesystem::path& path, const VertexOcclusion& occlusion, std::uint64_t key);
std::optional<VertexOcclusion> read_vertex_occlusion(const std::filesystem::path& path, const Scene& scene,
                                                     std::uint64_t key);

}  // namespace fresnel::trace
