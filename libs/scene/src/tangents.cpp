// MikkTSpace-compatible tangent generation (our own implementation of the published algorithm).
//
// Outline, following MikkTSpace's default behaviour for triangle lists:
//  1. Weld corners by value (position + normal + uv), not by index.
//  2. Per triangle: the unit tangent direction dP/du (sign-corrected by the triangle's UV
//     orientation) and its handedness. Triangles with zero UV area or a vanishing tangent or
//     bitangent are "group with any": they contribute nothing and take the handedness of the
//     first group that reaches them. Triangles with two corners on the same welded vertex are
//     degenerate: they take no part in grouping and copy their tangents afterwards.
//  3. Triangles are connected across shared edges (welded indices, consistent winding).
//  4. For every corner, a group is grown around its welded vertex through edge-connected
//     triangles of the same handedness. Each group yields one tangent: the sum over its corners
//     of the triangle tangent projected onto the vertex normal's plane, weighted by the corner
//     angle (measured in that plane), then normalised.
//  5. Output vertices are (input vertex, tangent) pairs, so an input vertex is only split where
//     its corners end up with different tangents.
// Deliberate simplification: MikkTSpace further splits a group into "subgroups" whose projected
// tangents are exactly antiparallel (cos == -1 with the default 180 degree threshold); we keep
// one tangent per group. All arithmetic is guarded so that no NaN or infinity can escape.
#include "fresnel/scene/tangents.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace fresnel {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

// Unit vector in the direction of v, or zero when v is zero or not finite.
glm::vec3 safe_normalize(const glm::vec3& v) {
    const double x = v.x, y = v.y, z = v.z;
    const double len = std::sqrt(x * x + y * y + z * z);
    if (!(len > 0.0) || !std::isfinite(len)) return glm::vec3(0.0f);
    return glm::vec3(float(x / len), float(y / len), float(z / len));
}
glm::vec3 safe_normalize(const glm::dvec3& v) {
    const double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(len > 0.0) || !std::isfinite(len)) return glm::vec3(0.0f);
    return glm::vec3(float(v.x / len), float(v.y / len), float(v.z / len));
}
bool is_zero(const glm::vec3& v) { return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f; }

// Removes the component along unit (or zero) n.
glm::vec3 project(const glm::vec3& v, const glm::vec3& n) { return v - n * glm::dot(n, v); }

// Some unit vector orthogonal to unit n (any unit vector when n is zero). Deterministic in n,
// so every corner of a vertex gets the same fallback and no split is introduced.
glm::vec3 fallback_tangent(const glm::vec3& n) {
    const glm::vec3 axis = std::fabs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 t = safe_normalize(project(axis, n));
    return is_zero(t) ? glm::vec3(1.0f, 0.0f, 0.0f) : t;
}

// Welding key: position, normal, uv compared by value (-0 == +0); NaN keys are never welded.
struct WeldKey {
    std::array<float, 8> v;
    bool operator==(const WeldKey& o) const { return v == o.v; }
};
struct WeldHash {
    std::size_t operator()(const WeldKey& k) const {
        std::uint64_t h = 0xcbf29ce484222325ull;
        for (float f : k.v) {
            const float c = f == 0.0f ? 0.0f : f;  // -0 and +0 compare equal, so hash them alike
            std::uint32_t bits = 0;  // std::bit_cast, which the web build's libc++ lacks
            std::memcpy(&bits, &c, sizeof bits);
            h = (h ^ bits) * 0x100000001b3ull;
        }
        h ^= h >> 29;
        h *= 0xbf58476d1ce4e5b9ull;
        h ^= h >> 32;
        return std::size_t(h);
    }
};

struct Triangle {
    glm::vec3 tangent{0.0f};  // unit dP/du, zero when undefined
    bool orient = false;      // UV orientation preserving (in MikkTSpace's v-up space)
    bool any = true;          // "group with any": no usable tangent frame
    bool degenerate = false;  // two corners share a welded vertex
};

struct Group {
    std::uint32_t vertex;  // welded vertex the group sits on
    std::uint32_t input;   // an input vertex with that value
    bool orient;
};

}  // namespace

TangentMesh generate_tangents(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                              std::span<const glm::vec2> uvs, std::span<const std::uint32_t> indices) {
    TangentMesh out;
    const std::size_t nc = indices.size() - indices.size() % 3;  // corners
    const std::size_t nt = nc / 3;                                // triangles
    if (nt == 0) return out;

    auto pos = [&](std::uint32_t i) { return positions[i]; };
    auto nrm = [&](std::uint32_t i) { return i < normals.size() ? normals[i] : glm::vec3(0.0f); };
    auto uv = [&](std::uint32_t i) { return i < uvs.size() ? uvs[i] : glm::vec2(0.0f); };
    // Unit normal of an input vertex (zero for degenerate normals).
    auto unit_normal = [&](std::uint32_t i) { return safe_normalize(nrm(i)); };

    // 1. Weld by value.
    std::vector<std::uint32_t> weld_of_input(positions.size(), kNone);
    std::vector<std::uint32_t> welded(nc);
    {
        std::unordered_map<WeldKey, std::uint32_t, WeldHash> map;
        map.reserve(std::min(nc, positions.size()));
        std::uint32_t next = 0;
        for (std::size_t k = 0; k < nc; ++k) {
            const std::uint32_t idx = indices[k];
            if (weld_of_input[idx] == kNone) {
                const glm::vec3 p = pos(idx), n = nrm(idx);
                const glm::vec2 t = uv(idx);
                WeldKey key{{p.x, p.y, p.z, n.x, n.y, n.z, t.x, t.y}};
                bool has_nan = false;
                for (float& f : key.v) {
                    if (f != f) has_nan = true;
                    if (f == 0.0f) f = 0.0f;
                }
                if (has_nan) {
                    weld_of_input[idx] = next++;
                } else {
                    auto [it, inserted] = map.try_emplace(key, next);
                    if (inserted) ++next;
                    weld_of_input[idx] = it->second;
                }
            }
            welded[k] = weld_of_input[idx];
        }
    }

    // 2. Per-triangle tangent direction and handedness.
    std::vector<Triangle> tris(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        Triangle& tri = tris[t];
        const std::uint32_t* w = &welded[3 * t];
        if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) {
            tri.degenerate = true;
            continue;
        }
        const std::uint32_t i0 = indices[3 * t], i1 = indices[3 * t + 1], i2 = indices[3 * t + 2];
        const glm::vec3 d1 = pos(i1) - pos(i0), d2 = pos(i2) - pos(i0);
        // MikkTSpace's v runs up the image; glTF's runs down: use -v (differences equal 1 - v's).
        const glm::vec2 uv0 = uv(i0), uv1 = uv(i1), uv2 = uv(i2);
        const float s1 = uv1.x - uv0.x, t1 = -(uv1.y - uv0.y);
        const float s2 = uv2.x - uv0.x, t2 = -(uv2.y - uv0.y);
        const float area = s1 * t2 - t1 * s2;  // twice the signed UV area
        tri.orient = area > 0.0f;
        const float sign = tri.orient ? 1.0f : -1.0f;
        const glm::vec3 os = (t2 * d1 - t1 * d2) * sign;   // dP/du * |area|
        const glm::vec3 ot = (s1 * d2 - s2 * d1) * sign;   // dP/dv * |area|
        tri.tangent = safe_normalize(os);
        const glm::vec3 bitangent = safe_normalize(ot);
        if (std::fabs(area) > FLT_MIN && std::isfinite(area) && !is_zero(tri.tangent) && !is_zero(bitangent)) {
            // MikkTSpace: usable when both |os|/|area| and |ot|/|area| are non-zero.
            const glm::dvec3 os_d(os), ot_d(ot);
            const double a = std::fabs(double(area));
            const double mag_s = glm::length(os_d) / a, mag_t = glm::length(ot_d) / a;
            tri.any = !(mag_s > FLT_MIN && mag_t > FLT_MIN);
        }
        if (tri.any) tri.tangent = glm::vec3(0.0f);
    }

    // 3. Edge adjacency: corner k's edge runs from welded[k] to the next corner of its triangle;
    //    it is matched with an edge running the other way (k-th forward with k-th reverse).
    std::vector<std::uint32_t> neighbor(nc, kNone);  // triangle across corner k's edge
    {
        struct Edge {
            std::uint64_t key;
            std::uint32_t corner;
        };
        std::vector<Edge> edges;
        edges.reserve(nc);
        for (std::size_t t = 0; t < nt; ++t) {
            if (tris[t].degenerate) continue;
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t a = welded[3 * t + c], b = welded[3 * t + (c + 1) % 3];
                const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
                edges.push_back({key, std::uint32_t(3 * t + c)});
            }
        }
        std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
            return x.key != y.key ? x.key < y.key : x.corner < y.corner;
        });
        std::vector<std::uint32_t> fwd, rev;
        for (std::size_t i = 0; i < edges.size();) {
            std::size_t j = i;
            while (j < edges.size() && edges[j].key == edges[i].key) ++j;
            if (j - i >= 2) {
                fwd.clear();
                rev.clear();
                for (std::size_t e = i; e < j; ++e) {
                    const std::uint32_t k = edges[e].corner;
                    const bool ascending = welded[k] < welded[k - k % 3 + (k % 3 + 1) % 3];
                    (ascending ? fwd : rev).push_back(k);
                }
                for (std::size_t m = 0; m < std::min(fwd.size(), rev.size()); ++m) {
                    neighbor[fwd[m]] = rev[m] / 3;
                    neighbor[rev[m]] = fwd[m] / 3;
                }
            }
            i = j;
        }
    }

    // 4. Groups: per corner, the edge-connected fan of same-handedness triangles around its
    //    welded vertex. Seeds are usable triangles in order; "any" triangles adopt the
    //    handedness of the first group that reaches them.
    std::vector<std::uint32_t> group(nc, kNone);
    std::vector<Group> groups;
    {
        std::vector<std::uint32_t> stack;
        for (std::size_t t0 = 0; t0 < nt; ++t0) {
            if (tris[t0].degenerate || tris[t0].any) continue;
            for (int c0 = 0; c0 < 3; ++c0) {
                if (group[3 * t0 + c0] != kNone) continue;
                const auto g = std::uint32_t(groups.size());
                const Group grp{welded[3 * t0 + c0], indices[3 * t0 + c0], tris[t0].orient};
                groups.push_back(grp);
                stack.assign(1, std::uint32_t(t0));
                while (!stack.empty()) {
                    const std::uint32_t t = stack.back();
                    stack.pop_back();
                    const std::uint32_t base = 3 * t;
                    int c = 0;
                    while (c < 3 && welded[base + c] != grp.vertex) ++c;
                    if (c == 3 || group[base + c] != kNone) continue;
                    Triangle& tri = tris[t];
                    if (tri.any && group[base] == kNone && group[base + 1] == kNone && group[base + 2] == kNone)
                        tri.orient = grp.orient;
                    if (tri.orient != grp.orient) continue;
                    group[base + c] = g;
                    // Both edges touching the corner; the "next" edge is explored first.
                    const std::uint32_t prev_edge = neighbor[base + (c + 2) % 3], next_edge = neighbor[base + c];
                    if (prev_edge != kNone) stack.push_back(prev_edge);
                    if (next_edge != kNone) stack.push_back(next_edge);
                }
            }
        }
    }

    // 5. One tangent per group: angle-weighted sum of the projected triangle tangents.
    std::vector<glm::dvec3> sum(groups.size(), glm::dvec3(0.0));
    for (std::size_t t = 0; t < nt; ++t) {
        const Triangle& tri = tris[t];
        if (tri.degenerate || tri.any) continue;
        for (int c = 0; c < 3; ++c) {
            const std::size_t k = 3 * t + c;
            const std::uint32_t g = group[k];
            if (g == kNone) continue;  // cannot happen for usable triangles; be safe anyway
            const glm::vec3 n = unit_normal(groups[g].input);
            const glm::vec3 dir = safe_normalize(project(tri.tangent, n));
            if (is_zero(dir)) continue;
            const glm::vec3 p = pos(indices[k]);
            const glm::vec3 e_prev = safe_normalize(project(pos(indices[3 * t + (c + 2) % 3]) - p, n));
            const glm::vec3 e_next = safe_normalize(project(pos(indices[3 * t + (c + 1) % 3]) - p, n));
            const float cosine = std::clamp(glm::dot(e_prev, e_next), -1.0f, 1.0f);
            const double angle = std::acos(double(cosine));
            sum[g] += angle * glm::dvec3(dir);
        }
    }
    std::vector<glm::vec4> group_tangent(groups.size());
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const glm::vec3 n = unit_normal(groups[g].input);
        glm::vec3 tangent = safe_normalize(sum[g]);
        if (!is_zero(tangent)) tangent = safe_normalize(project(tangent, n));  // scrub rounding
        if (is_zero(tangent)) tangent = fallback_tangent(n);
        group_tangent[g] = glm::vec4(tangent, groups[g].orient ? 1.0f : -1.0f);
    }

    // Per-corner result. Corners outside any group get the fallback with w = +1; degenerate
    // triangles copy from the first usable corner on the same welded vertex.
    std::vector<glm::vec4> corner_tangent(nc);
    std::vector<std::uint32_t> first_corner_of_welded;
    bool any_degenerate = false;
    for (std::size_t t = 0; t < nt; ++t) {
        if (tris[t].degenerate) {
            any_degenerate = true;
            continue;
        }
        for (int c = 0; c < 3; ++c) {
            const std::size_t k = 3 * t + c;
            corner_tangent[k] = group[k] != kNone ? group_tangent[group[k]]
                                                  : glm::vec4(fallback_tangent(unit_normal(indices[k])), 1.0f);
        }
    }
    if (any_degenerate) {
        first_corner_of_welded.assign(nc, kNone);  // welded ids are < nc
        for (std::size_t k = 0; k < nc; ++k)
            if (!tris[k / 3].degenerate && first_corner_of_welded[welded[k]] == kNone)
                first_corner_of_welded[welded[k]] = std::uint32_t(k);
        for (std::size_t k = 0; k < nc; ++k) {
            if (!tris[k / 3].degenerate) continue;
            const std::uint32_t src = first_corner_of_welded[welded[k]];
            corner_tangent[k] = src != kNone ? corner_tangent[src]
                                             : glm::vec4(fallback_tangent(unit_normal(indices[k])), 1.0f);
        }
    }

    // 6. Output vertices: one per distinct (input vertex, tangent) pair, in first-use order.
    std::vector<std::uint32_t> head(positions.size(), kNone);  // first output of an input vertex
    std::vector<std::uint32_t> next_same_input;                 // chain of outputs per input vertex
    out.indices.resize(nc);
    out.remap.reserve(std::min(nc, positions.size()));
    out.tangents.reserve(std::min(nc, positions.size()));
    for (std::size_t k = 0; k < nc; ++k) {
        const std::uint32_t idx = indices[k];
        const glm::vec4& tan = corner_tangent[k];
        std::uint32_t o = head[idx];
        while (o != kNone && out.tangents[o] != tan) o = next_same_input[o];
        if (o == kNone) {
            o = std::uint32_t(out.remap.size());
            out.remap.push_back(idx);
            out.tangents.push_back(tan);
            next_same_input.push_back(head[idx]);
            head[idx] = o;
        }
        out.indices[k] = o;
    }
    return out;
}

}  // namespace fresnel
