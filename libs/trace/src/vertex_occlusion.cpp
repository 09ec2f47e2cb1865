#include "fresnel/trace/vertex_occlusion.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "fresnel/core/parallel.h"
#include "fresnel/material/sampling.h"
#include "splitmix.h"

namespace fresnel::trace {

namespace {

// One placed primitive to bake.
struct Task {
    int node = -1;
    std::size_t primitive = 0;
    const Primitive* prim = nullptr;
    glm::mat4 world{1.0f};
    glm::mat3 normal_matrix{1.0f};
};

constexpr std::size_t kChunk = 256;  // vertices per unit of parallel work

}  // namespace

VertexOcclusion bake_vertex_occlusion(const TraceScene& tscene, const Scene& scene,
                                      const std::vector<NodeInstance>& instances,
                                      const VertexOcclusionOptions& options, const OcclusionProgress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    VertexOcclusion out;
    out.rays_per_vertex = std::max(1, options.rays);
    out.nodes.resize(scene.nodes.size());
    std::vector<Task> tasks;
    for (const NodeInstance& inst : instances) {
        if (inst.node < 0 || std::size_t(inst.node) >= scene.nodes.size() || !inst.visible) continue;
        const Node& node = scene.nodes[std::size_t(inst.node)];
        if (node.mesh < 0 || std::size_t(node.mesh) >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[std::size_t(node.mesh)];
        out.nodes[std::size_t(inst.node)].resize(mesh.primitives.size());
        for (std::size_t k = 0; k < mesh.primitives.size(); ++k) {
            const Primitive& p = mesh.primitives[k];
            const bool deformable = !p.joints.empty() || !p.targets.empty();
            if (p.topology != Topology::Triangles || p.positions.empty() || p.normals.size() != p.positions.size() ||
                (deformable && !node.world_space_mesh))
                continue;
            Task t;
            t.node = inst.node;
            t.primitive = k;
            t.prim = &p;
            t.world = node.world_space_mesh ? glm::mat4(1.0f) : inst.world;
            t.normal_matrix = glm::transpose(glm::inverse(glm::mat3(t.world)));
            out.nodes[std::size_t(inst.node)][k].resize(p.positions.size());
            tasks.push_back(t);
        }
    }
    // Chunks of kChunk vertices over every task, so that one big primitive spreads over every core.
    struct Chunk {
        std::size_t task, first, last;
    };
    std::vector<Chunk> chunks;
    for (std::size_t i = 0; i < tasks.size(); ++i) {
        const std::size_t n = tasks[i].prim->positions.size();
        out.vertices += n;
        for (std::size_t first = 0; first < n; first += kChunk) chunks.push_back({i, first, std::min(n, first + kChunk)});
    }
    const auto rays = std::uint32_t(out.rays_per_vertex);
    const float tfar = options.max_distance > 0.0f ? options.max_distance : INFINITY;
    std::atomic<std::size_t> done{0};
    parallel_for(
        chunks.size(),
        [&](std::size_t c) {
            const Chunk& chunk = chunks[c];
            const Task& t = tasks[chunk.task];
            std::vector<glm::vec4>& values = out.nodes[std::size_t(t.node)][t.primitive];
            for (std::size_t v = chunk.first; v < chunk.last; ++v) {
                const glm::vec3 p(t.world * glm::vec4(t.prim->positions[v], 1.0f));
                glm::vec3 n = t.normal_matrix * t.prim->normals[v];
                const float len = glm::length(n);
                if (!(len > 0.0f) || !std::isfinite(p.x + p.y + p.z)) {
                    values[v] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);  // no direction to look in: unoccluded
                    continue;
                }
                n /= len;
                glm::vec3 tx, ty;
                sampling::basis(n, tx, ty);
                const std::uint64_t key =
                    splitmix64(options.seed ^ splitmix64((std::uint64_t(std::uint32_t(t.node)) << 32) ^ (t.primitive << 24) ^ v));
                // Cranley-Patterson rotation of the Hammersley set, per vertex.
                const glm::vec2 shift(float(key >> 40) * 0x1p-24f, float((key >> 16) & 0xFFFFFF) * 0x1p-24f);
                int open = 0;
                glm::vec3 bent(0.0f);
                for (std::uint32_t s = 0; s < rays; ++s) {
                    glm::vec2 u = sampling::hammersley(s, rays) + shift;
                    u -= glm::floor(u);
                    const glm::vec3 l = sampling::sample_cosine(u);
                    const glm::vec3 d = glm::normalize(l.x * tx + l.y * ty + l.z * n);
                    if (!tscene.occluded(p, n, d, tfar, key + s)) {
                        ++open;
                        bent += d;
                    }
                }
                const float bl = glm::length(bent);
                values[v] = glm::vec4(bl > 0.0f ? bent / bl : glm::vec3(0.0f), float(open) / float(rays));
            }
            const std::size_t finished = done.fetch_add(chunk.last - chunk.first) + (chunk.last - chunk.first);
            if (progress && out.vertices > 0) progress(double(finished) / double(out.vertices));
        },
        options.threads);
    out.bake_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace fresnel::trace
