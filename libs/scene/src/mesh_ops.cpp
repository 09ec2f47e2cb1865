#include "fresnel/scene/mesh_ops.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace fresnel {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

template <class T>
void remap_array(std::vector<T>& a, std::span<const std::uint32_t> remap) {
    if (a.empty()) return;
    std::vector<T> out(remap.size());
    for (std::size_t i = 0; i < remap.size(); ++i) out[i] = a[remap[i]];
    a.swap(out);
}

// Unit face normal of a triangle, +Z when it has no area (or is not finite).
glm::vec3 face_normal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    glm::vec3 n = glm::cross(b - a, c - a);
    float len = glm::length(n);
    return len > 0 && std::isfinite(len) ? n / len : glm::vec3(0, 0, 1);
}

}  // namespace

std::vector<std::uint32_t> strip_to_triangles(std::span<const std::uint32_t> strip) {
    std::vector<std::uint32_t> list;
    if (strip.size() < 3) return list;
    list.reserve((strip.size() - 2) * 3);
    for (std::size_t i = 2; i < strip.size(); ++i) {
        if (i % 2 == 0) list.insert(list.end(), {strip[i - 2], strip[i - 1], strip[i]});
        else list.insert(list.end(), {strip[i - 1], strip[i - 2], strip[i]});
    }
    return list;
}

std::vector<std::uint32_t> fan_to_triangles(std::span<const std::uint32_t> fan) {
    std::vector<std::uint32_t> list;
    if (fan.size() < 3) return list;
    list.reserve((fan.size() - 2) * 3);
    for (std::size_t i = 2; i < fan.size(); ++i) list.insert(list.end(), {fan[0], fan[i - 1], fan[i]});
    return list;
}

std::vector<std::uint32_t> line_strip_to_lines(std::span<const std::uint32_t> strip) {
    std::vector<std::uint32_t> list;
    if (strip.size() < 2) return list;
    list.reserve((strip.size() - 1) * 2);
    for (std::size_t i = 1; i < strip.size(); ++i) list.insert(list.end(), {strip[i - 1], strip[i]});
    return list;
}

std::vector<std::uint32_t> line_loop_to_lines(std::span<const std::uint32_t> loop) {
    std::vector<std::uint32_t> list = line_strip_to_lines(loop);
    if (loop.size() >= 3) list.insert(list.end(), {loop.back(), loop.front()});
    return list;
}

std::vector<std::uint32_t> index_list(const Primitive& p) {
    if (!p.indices.empty()) return p.indices;
    std::vector<std::uint32_t> out(p.positions.size());
    std::iota(out.begin(), out.end(), 0u);
    return out;
}

std::size_t repair_normals(std::span<const glm::vec3> positions, std::span<const std::uint32_t> triangles,
                           std::span<glm::vec3> normals) {
    std::vector<glm::vec3> smooth;  // area-weighted vertex normals, computed on the first bad normal
    std::size_t bad = 0;
    for (std::size_t v = 0; v < normals.size(); ++v) {
        glm::vec3& n = normals[v];
        float len = finite(n) ? glm::length(n) : 0.0f;
        if (len > 1e-20f && std::isfinite(len)) {
            // Unit to the digits a file carries (6 decimals: |len - 1| ~ 1e-6) is kept as written,
            // so converters keep normals bit for bit; anything further off is normalised.
            if (std::fabs(len - 1.0f) > 1e-5f) n /= len;
            continue;
        }
        if (smooth.empty()) {
            smooth.assign(positions.size(), glm::vec3(0.0f));
            for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
                glm::vec3 fn = glm::cross(positions[triangles[t + 1]] - positions[triangles[t]],
                                          positions[triangles[t + 2]] - positions[triangles[t]]);
                if (!finite(fn)) continue;
                for (std::size_t k = 0; k < 3; ++k) smooth[triangles[t + k]] += fn;
            }
        }
        float sl = v < smooth.size() ? glm::length(smooth[v]) : 0.0f;
        n = sl > 0 && std::isfinite(sl) ? smooth[v] / sl : glm::vec3(0, 0, 1);
        ++bad;
    }
    return bad;
}

std::size_t repair_normals(Primitive& p) {
    if (p.topology != Topology::Triangles || p.normals.empty()) return 0;
    return repair_normals(p.positions, index_list(p), p.normals);
}

void generate_flat_normals(Primitive& p) {
    if (p.topology != Topology::Triangles) return;
    std::vector<std::uint32_t> corners = index_list(p);
    corners.resize(corners.size() / 3 * 3);
    remap_vertices(p, corners);
    p.indices.clear();
    p.normals.resize(p.positions.size());
    for (std::size_t t = 0; t < p.positions.size(); t += 3)
        p.normals[t] = p.normals[t + 1] = p.normals[t + 2] =
            face_normal(p.positions[t], p.positions[t + 1], p.positions[t + 2]);
    p.generated_normals = true;
}

const TextureSlot* tangent_source(const Material& m) {
    if (m.normal.valid()) return &m.normal;
    if (m.clearcoat && m.clearcoat->clearcoat_normal_texture.valid()) return &m.clearcoat->clearcoat_normal_texture;
    if (m.has_anisotropy()) return &m.anisotropy->anisotropy_texture;
    return nullptr;
}

bool generate_tangents(Primitive& p, int tex_coord) {
    const auto& uv = tex_coord == 1 ? p.uv1 : p.uv0;
    if (p.topology != Topology::Triangles || p.normals.empty() || uv.empty()) return false;
    std::vector<std::uint32_t> corners = index_list(p);
    corners.resize(corners.size() / 3 * 3);
    TangentMesh tm = generate_tangents(p.positions, p.normals, uv, corners);
    remap_vertices(p, tm.remap);
    p.tangents = std::move(tm.tangents);
    p.indices = std::move(tm.indices);
    p.generated_tangents = true;
    return true;
}

void repair_tangents(std::span<glm::vec4> tangents) {
    for (auto& t : tangents) {
        glm::vec3 v(t);
        float len = finite(v) ? glm::length(v) : 0.0f;
        if (!(len > 0) || !std::isfinite(len)) t = glm::vec4(1, 0, 0, 1);
        else t = glm::vec4(v / len, t.w < 0 ? -1.0f : 1.0f);
    }
}

void remap_vertices(Primitive& p, std::span<const std::uint32_t> remap) {
    remap_array(p.positions, remap);
    remap_array(p.normals, remap);
    remap_array(p.tangents, remap);
    remap_array(p.uv0, remap);
    remap_array(p.uv1, remap);
    remap_array(p.colors, remap);
    remap_array(p.joints, remap);
    remap_array(p.weights, remap);
    for (auto& t : p.targets) {
        remap_array(t.positions, remap);
        remap_array(t.normals, remap);
        remap_array(t.tangents, remap);
    }
}

bool drop_identity_indices(Primitive& p) {
    if (p.indices.empty() || p.indices.size() != p.positions.size()) return false;
    for (std::size_t i = 0; i < p.indices.size(); ++i)
        if (p.indices[i] != i) return false;
    p.indices.clear();
    return true;
}

std::vector<std::uint32_t> compact_vertices(Primitive& p) {
    if (p.indices.empty()) return index_list(p);
    constexpr std::uint32_t kUnused = 0xffffffffu;
    std::vector<std::uint32_t> new_index(p.positions.size(), kUnused);
    for (std::uint32_t i : p.indices) new_index[i] = 0;
    std::vector<std::uint32_t> remap;
    for (std::size_t v = 0; v < new_index.size(); ++v)
        if (new_index[v] != kUnused) {
            new_index[v] = std::uint32_t(remap.size());
            remap.push_back(std::uint32_t(v));
        }
    if (remap.size() != p.positions.size()) remap_vertices(p, remap);
    for (auto& i : p.indices) i = new_index[i];
    drop_identity_indices(p);
    return remap;
}

namespace {
// world_matrices into `world`, with the workspace's storage.
void world_matrices_into(std::span<const Node> nodes, SkinMatrices& ws) {
    std::vector<glm::mat4>& world = ws.world;
    world.resize(nodes.size());
    ws.has_parent.assign(nodes.size(), 0);
    ws.done.assign(nodes.size(), 0);
    ws.stack.clear();
    for (const Node& n : nodes)
        for (int c : n.children)
            if (c >= 0 && std::size_t(c) < nodes.size()) ws.has_parent[std::size_t(c)] = 1;
    for (std::size_t root = 0; root < nodes.size(); ++root) {
        if (ws.has_parent[root]) continue;
        world[root] = nodes[root].local;
        ws.done[root] = 1;
        ws.stack.push_back(root);
        while (!ws.stack.empty()) {
            std::size_t n = ws.stack.back();
            ws.stack.pop_back();
            for (int c : nodes[n].children) {
                if (c < 0 || std::size_t(c) >= nodes.size() || ws.done[std::size_t(c)]) continue;
                world[std::size_t(c)] = world[n] * nodes[std::size_t(c)].local;
                ws.done[std::size_t(c)] = 1;
                ws.stack.push_back(std::size_t(c));
            }
        }
    }
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (!ws.done[i]) world[i] = nodes[i].local;
}

void joint_matrices_into(std::span<const glm::mat4> world, std::span<const int> joints,
                         std::span<const glm::mat4> inverse_bind, std::vector<glm::mat4>& out) {
    out.clear();
    for (std::size_t j = 0; j < joints.size(); ++j)
        out.push_back(world[std::size_t(joints[j])] * (j < inverse_bind.size() ? inverse_bind[j] : glm::mat4(1.0f)));
}
}  // namespace

std::vector<glm::mat4> world_matrices(std::span<const Node> nodes) {
    SkinMatrices ws;
    world_matrices_into(nodes, ws);
    return std::move(ws.world);
}

std::vector<glm::mat4> joint_matrices(std::span<const glm::mat4> world, std::span<const int> joints,
                                      std::span<const glm::mat4> inverse_bind) {
    std::vector<glm::mat4> out;
    out.reserve(joints.size());
    joint_matrices_into(world, joints, inverse_bind, out);
    return out;
}

void skin_matrices(std::span<const Node> nodes, std::span<const Skin> skins, SkinMatrices& out, std::size_t max_joints) {
    world_matrices_into(nodes, out);
    out.skins.resize(skins.size());
    for (std::size_t k = 0; k < skins.size(); ++k) {
        const Skin& s = skins[k];
        bool ok = !s.joints.empty() && s.joints.size() <= max_joints;
        for (int j : s.joints) ok = ok && j >= 0 && std::size_t(j) < out.world.size();
        if (ok) joint_matrices_into(out.world, s.joints, s.inverse_bind, out.skins[k]);
        else out.skins[k].clear();
    }
}

std::optional<InvalidJoint> find_invalid_joint(const Primitive& p, std::size_t joint_count) {
    for (std::size_t v = 0; v < p.joints.size() && v < p.weights.size(); ++v)
        for (int c = 0; c < 4; ++c)
            if (p.weights[v][c] != 0.0f && p.joints[v][c] >= joint_count) return InvalidJoint{v, p.joints[v][c]};
    return std::nullopt;
}

void transform_primitive(Primitive& p, const glm::mat4& m) {
    for (auto& v : p.positions) v = glm::vec3(m * glm::vec4(v, 1.0f));
    glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(m)));
    for (auto& n : p.normals) n = glm::normalize(nm * n);
    for (auto& t : p.tangents) t = glm::vec4(glm::normalize(glm::mat3(m) * glm::vec3(t)), t.w);
}

void pose_skinned(Primitive& p, std::span<const glm::mat4> joint_matrices, const glm::mat4& node_world,
                  SkinWeights mode) {
    if (p.joints.empty()) {
        transform_primitive(p, node_world);
        return;
    }
    for (std::size_t v = 0; v < p.positions.size(); ++v) {
        glm::mat4 m(0.0f);
        float wsum = 0.0f;
        for (int c = 0; c < 4; ++c) {
            if (v >= p.joints.size() || v >= p.weights.size()) break;
            float w = p.weights[v][c];
            std::uint32_t j = p.joints[v][c];
            if (w == 0.0f || j >= joint_matrices.size()) continue;
            m += w * joint_matrices[j];
            wsum += w;
        }
        if (wsum <= 0.0f) m = node_world;  // unweighted vertices follow the node
        glm::vec4 h = m * glm::vec4(p.positions[v], 1.0f);
        p.positions[v] = mode == SkinWeights::Homogeneous && h.w != 0.0f ? glm::vec3(h) / h.w : glm::vec3(h);
        glm::mat3 m3(m);
        if (v < p.normals.size()) p.normals[v] = glm::normalize(glm::transpose(glm::inverse(m3)) * p.normals[v]);
        if (v < p.tangents.size()) p.tangents[v] = glm::vec4(glm::normalize(m3 * glm::vec3(p.tangents[v])), p.tangents[v].w);
    }
}

void sort_triangles_by_uv(std::vector<std::uint32_t>& triangles, std::span<const glm::vec2> uv) {
    if (triangles.size() % 3 != 0 || triangles.size() < 6) return;
    for (std::uint32_t v : triangles)
        if (v >= uv.size()) return;
    // 16 bits of x and y interleaved (x in the even bits).
    auto spread = [](std::uint32_t v) {
        v &= 0xFFFFu;
        v = (v | (v << 8)) & 0x00FF00FFu;
        v = (v | (v << 4)) & 0x0F0F0F0Fu;
        v = (v | (v << 2)) & 0x33333333u;
        v = (v | (v << 1)) & 0x55555555u;
        return v;
    };
    auto quantise = [](float c) {
        float f = c - std::floor(c);  // repeating UVs: the position within the tile
        return std::isfinite(f) ? std::uint32_t(std::clamp(f, 0.0f, 1.0f) * 65535.0f) : 0u;
    };
    const std::size_t count = triangles.size() / 3;
    std::vector<std::uint64_t> keys(count);  // Morton code << 32 | triangle: sorted, ties keep the order
    for (std::size_t t = 0; t < count; ++t) {
        glm::vec2 c = (uv[triangles[t * 3]] + uv[triangles[t * 3 + 1]] + uv[triangles[t * 3 + 2]]) / 3.0f;
        keys[t] = std::uint64_t(spread(quantise(c.x)) | spread(quantise(c.y)) << 1) << 32 | std::uint64_t(t);
    }
    std::sort(keys.begin(), keys.end());
    std::vector<std::uint32_t> out(triangles.size());
    for (std::size_t t = 0; t < count; ++t) {
        const std::size_t from = std::size_t(keys[t] & 0xFFFFFFFFu) * 3;
        std::copy_n(triangles.begin() + std::ptrdiff_t(from), 3, out.begin() + std::ptrdiff_t(t * 3));
    }
    triangles = std::move(out);
}

}  // namespace fresnel
