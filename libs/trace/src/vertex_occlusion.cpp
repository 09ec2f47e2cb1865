#include "fresnel/trace/vertex_occlusion.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <span>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/error.h"
#include "fresnel/core/parallel.h"
#include "fresnel/ibl/bake.h"
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

// ---------------------------------------------------------------------------------------------
// The cache.

namespace fresnel::trace {

namespace {

constexpr char kMagic[8] = {'F', 'R', 'A', 'O', 'C', 'C', '0', '1'};

// Word-wise hashing of plain data (the key): SplitMix64 over each 64-bit word.
struct KeyHash {
    std::uint64_t h = 0x6A09E667F3BCC909ull;
    void word(std::uint64_t w) { h = splitmix64(h ^ w); }
    void bytes(const void* data, std::size_t n) {
        const auto* p = static_cast<const std::uint8_t*>(data);
        std::size_t i = 0;
        for (; i + 8 <= n; i += 8) {
            std::uint64_t w;
            std::memcpy(&w, p + i, 8);
            word(w);
        }
        std::uint64_t tail = 0;
        std::memcpy(&tail, p + i, n - i);
        word(tail ^ (std::uint64_t(n) << 56));
    }
    template <class T>
    void vec(const std::vector<T>& v) {
        word(v.size());
        if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
    }
    void f(float x) {
        std::uint32_t b;
        std::memcpy(&b, &x, 4);
        word(b);
    }
};

void put(std::vector<std::uint8_t>& out, const void* data, std::size_t n) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    out.insert(out.end(), p, p + n);
}

}  // namespace

std::uint64_t vertex_occlusion_key(const Scene& scene, const std::vector<NodeInstance>& instances,
                                   const VertexOcclusionOptions& options) {
    KeyHash k;
    k.word(0x6F63636C75736931ull);  // "occlusi1": the format of the values
    k.word(std::uint64_t(std::max(1, options.rays)));
    k.f(options.max_distance);
    k.word(options.seed);
    k.word(scene.nodes.size());
    for (const NodeInstance& inst : instances) {
        if (inst.node < 0 || std::size_t(inst.node) >= scene.nodes.size() || !inst.visible) continue;
        const Node& node = scene.nodes[std::size_t(inst.node)];
        if (node.mesh < 0 || std::size_t(node.mesh) >= scene.meshes.size()) continue;
        k.word(std::uint64_t(inst.node));
        k.word(node.world_space_mesh);
        k.bytes(&inst.world[0][0], sizeof(inst.world));
        for (const Primitive& p : scene.meshes[std::size_t(node.mesh)].primitives) {
            k.word(std::uint64_t(p.topology));
            k.vec(p.positions);
            k.vec(p.normals);
            k.vec(p.indices);
            k.word((p.joints.empty() ? 0u : 1u) | (p.targets.empty() ? 0u : 2u));
            k.vec(p.uv0);
            if (p.material < 0 || std::size_t(p.material) >= scene.materials.size()) {
                k.word(~0ull);
                continue;
            }
            const Material& m = scene.materials[std::size_t(p.material)];
            k.word(std::uint64_t(m.alpha_mode));
            k.f(m.alpha_cutoff);
            k.word(m.double_sided);
            k.f(m.base_color_factor.w);
            if (m.alpha_mode != AlphaMode::Opaque && m.base_color.valid() &&
                std::size_t(m.base_color.texture) < scene.textures.size()) {
                const int image = scene.textures[std::size_t(m.base_color.texture)].image;
                if (image >= 0 && std::size_t(image) < scene.images.size()) k.vec(scene.images[std::size_t(image)].pixels.pixels);
            }
        }
    }
    return k.h;
}

void write_vertex_occlusion(const std::filesystem::path& path, const VertexOcclusion& occ, std::uint64_t key) {
    std::vector<std::uint8_t> out;
    put(out, kMagic, 8);
    put(out, &key, 8);
    const std::uint32_t rays = std::uint32_t(occ.rays_per_vertex), nodes = std::uint32_t(occ.nodes.size());
    put(out, &rays, 4);
    put(out, &nodes, 4);
    for (const auto& prims : occ.nodes) {
        const std::uint32_t n = std::uint32_t(prims.size());
        put(out, &n, 4);
        for (const auto& values : prims) {
            const std::uint64_t count = values.size();
            put(out, &count, 8);
            if (count) put(out, values.data(), values.size() * sizeof(glm::vec4));
        }
    }
    write_file_atomically(path, std::span<const std::uint8_t>(out));
}

std::optional<VertexOcclusion> read_vertex_occlusion(const std::filesystem::path& path, const Scene& scene,
                                                     std::uint64_t key) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    // The largest file the scene could have: a vec4 per vertex of every node's mesh, plus headers.
    std::uint64_t limit = 24;
    for (const Node& n : scene.nodes) {
        limit += 4;
        if (n.mesh >= 0 && std::size_t(n.mesh) < scene.meshes.size())
            for (const Primitive& p : scene.meshes[std::size_t(n.mesh)].primitives) limit += 8 + 16 * p.positions.size();
    }
    if (ec || size < 24 || size > limit) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size))) return std::nullopt;
    std::size_t at = 0;
    auto take = [&](void* dst, std::size_t n) {
        if (bytes.size() - at < n) return false;
        std::memcpy(dst, bytes.data() + at, n);
        at += n;
        return true;
    };
    char magic[8];
    std::uint64_t file_key = 0;
    std::uint32_t rays = 0, nodes = 0;
    if (!take(magic, 8) || std::memcmp(magic, kMagic, 8) != 0 || !take(&file_key, 8) || file_key != key ||
        !take(&rays, 4) || !take(&nodes, 4) || nodes != scene.nodes.size() || rays == 0 || rays > (1u << 20))
        return std::nullopt;
    VertexOcclusion occ;
    occ.rays_per_vertex = int(rays);
    occ.nodes.resize(nodes);
    for (std::uint32_t n = 0; n < nodes; ++n) {
        std::uint32_t prims = 0;
        if (!take(&prims, 4)) return std::nullopt;
        const Node& node = scene.nodes[n];
        const Mesh* mesh = node.mesh >= 0 && std::size_t(node.mesh) < scene.meshes.size() ? &scene.meshes[std::size_t(node.mesh)] : nullptr;
        if (prims != 0 && (!mesh || prims != mesh->primitives.size())) return std::nullopt;
        occ.nodes[n].resize(prims);
        for (std::uint32_t k = 0; k < prims; ++k) {
            std::uint64_t count = 0;
            if (!take(&count, 8)) return std::nullopt;
            if (count == 0) continue;
            if (count != mesh->primitives[k].positions.size() || (bytes.size() - at) / sizeof(glm::vec4) < count)
                return std::nullopt;
            std::vector<glm::vec4>& values = occ.nodes[n][k];
            values.resize(static_cast<std::size_t>(count));
            take(values.data(), values.size() * sizeof(glm::vec4));
            for (const glm::vec4& v : values)
                if (!std::isfinite(v.x + v.y + v.z + v.w) || v.w < 0.0f || v.w > 1.0f) return std::nullopt;
            occ.vertices += values.size();
        }
    }
    if (at != bytes.size()) return std::nullopt;
    return occ;
}

VertexOcclusion load_or_bake_vertex_occlusion(const Scene& scene, const std::vector<NodeInstance>& instances,
                                              const VertexOcclusionOptions& options, bool use_cache, bool instancing,
                                              const OcclusionProgress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::uint64_t key = vertex_occlusion_key(scene, instances, options);
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.ao", static_cast<unsigned long long>(key));
    const std::filesystem::path path = ibl::cache_root() / "occlusion" / name;
    if (use_cache)
        if (std::optional<VertexOcclusion> cached = read_vertex_occlusion(path, scene, key)) {
            cached->bake_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            cached->from_cache = true;
            if (progress) progress(1.0);
            return std::move(*cached);
        }
    TraceSceneOptions to;
    to.instancing = instancing;
    const TraceScene tscene(scene, instances, to);
    VertexOcclusion out = bake_vertex_occlusion(tscene, scene, instances, options, progress);
    out.bake_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (use_cache) {
        try {
            std::error_code ec;
            std::filesystem::create_directories(path.parent_path(), ec);
            write_vertex_occlusion(path, out, key);
        } catch (const Error&) {
            // caching is best effort; the render goes on
        }
    }
    return out;
}

}  // namespace fresnel::trace
