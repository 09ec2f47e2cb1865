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
#include <functional>
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

}  // namespace fresnel::trace
