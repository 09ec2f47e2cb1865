#include "fresnel/scene/tangents.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>
#include <set>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

using namespace fresnel;

namespace {

constexpr float kPi = 3.14159265358979f;

struct Mesh {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<std::uint32_t> indices;
    TangentMesh run() const { return generate_tangents(positions, normals, uvs, indices); }
};

bool finite(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// Invariants every result must satisfy: consistent re-indexing and unit tangents orthogonal
// to the (unit) normals with w = +-1.
void check_invariants(const Mesh& m, const TangentMesh& r, bool check_orthogonal = true) {
    ASSERT_EQ(r.indices.size(), m.indices.size());
    ASSERT_EQ(r.remap.size(), r.tangents.size());
    for (std::size_t k = 0; k < m.indices.size(); ++k) {
        ASSERT_LT(r.indices[k], r.remap.size());
        EXPECT_EQ(r.remap[r.indices[k]], m.indices[k]) << "corner " << k;
    }
    std::set<std::uint32_t> used(m.indices.begin(), m.indices.end());
    EXPECT_GE(r.remap.size(), used.size());
    for (std::size_t o = 0; o < r.tangents.size(); ++o) {
        const glm::vec4 t = r.tangents[o];
        ASSERT_TRUE(finite(t)) << "output vertex " << o;
        EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-5f) << "output vertex " << o;
        EXPECT_TRUE(t.w == 1.0f || t.w == -1.0f) << "output vertex " << o;
        if (check_orthogonal) {
            const glm::vec3 n = m.normals[r.remap[o]];
            if (std::isfinite(glm::length(n)) && glm::length(n) > 0.5f) {
                EXPECT_NEAR(glm::dot(glm::normalize(n), glm::vec3(t)), 0.0f, 1e-5f) << "output vertex " << o;
            }
        }
    }
}

glm::vec3 bitangent(const glm::vec3& n, const glm::vec4& t) { return t.w * glm::cross(n, glm::vec3(t)); }

void expect_vec_near(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

// Unit quad in the XY plane facing +Z (counter-clockwise seen from +Z), drawn "upright":
// u grows along +X and glTF's v grows along -Y, i.e. the image's top row (v = 0) is at y = 1.
Mesh upright_quad() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.normals.assign(4, {0, 0, 1});
    m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

// (n+1) x (n+1) vertex grid over [0,1]^2, CCW from +Z, standard upright glTF UVs. When
// `curved`, the surface is a smooth height field with analytic normals.
Mesh grid(int n, bool curved) {
    Mesh m;
    auto height = [](float x, float y) { return 0.3f * std::sin(3.0f * x) * std::cos(2.0f * y); };
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const float x = float(i) / float(n), y = float(j) / float(n);
            if (curved) {
                const float dzdx = 0.9f * std::cos(3.0f * x) * std::cos(2.0f * y);
                const float dzdy = -0.6f * std::sin(3.0f * x) * std::sin(2.0f * y);
                m.positions.push_back({x, y, height(x, y)});
                m.normals.push_back(glm::normalize(glm::vec3(-dzdx, -dzdy, 1.0f)));
            } else {
                m.positions.push_back({x, y, 0.0f});
                m.normals.push_back({0, 0, 1});
            }
            m.uvs.push_back({x, 1.0f - y});
        }
    }
    const auto at = [n](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    return m;
}

}  // namespace

// glTF: texture coordinate (0,0) is the image's top-left, so v runs down the image; the normal
// texture is "+Y up"; bitangent = cross(normal, tangent.xyz) * tangent.w. Hence for an upright
// mapping the tangent is +X and the bitangent must point up the image (+Y here, the direction
// of decreasing v), i.e. w = +1. This matches Blender's MikkTSpace (which works with v up).
TEST(Tangents, UprightQuadFollowsGltfConvention) {
    const Mesh m = upright_quad();
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), 4u);  // nothing to split
    for (std::size_t o = 0; o < r.tangents.size(); ++o) {
        expect_vec_near(glm::vec3(r.tangents[o]), {1, 0, 0});
        EXPECT_EQ(r.tangents[o].w, 1.0f);
        expect_vec_near(bitangent(m.normals[r.remap[o]], r.tangents[o]), {0, 1, 0});
    }
}

// Flipping v (v now grows along +Y, a mirrored image) keeps the tangent and flips w: the
// bitangent again points towards decreasing v, now -Y.
TEST(Tangents, FlippedVGivesNegativeW) {
    Mesh m = upright_quad();
    for (auto& uv : m.uvs) uv.y = 1.0f - uv.y;
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), 4u);
    for (std::size_t o = 0; o < r.tangents.size(); ++o) {
        expect_vec_near(glm::vec3(r.tangents[o]), {1, 0, 0});
        EXPECT_EQ(r.tangents[o].w, -1.0f);
        expect_vec_near(bitangent(m.normals[r.remap[o]], r.tangents[o]), {0, -1, 0});
    }
}

// A rotated UV mapping (u along +Y, v along +X) is not mirrored: w = +1, tangent follows u.
TEST(Tangents, RotatedUvsFollowU) {
    Mesh m = upright_quad();
    for (std::size_t i = 0; i < m.positions.size(); ++i) m.uvs[i] = {m.positions[i].y, m.positions[i].x};
    const TangentMesh r = m.run();
    check_invariants(m, r);
    for (const auto& t : r.tangents) {
        expect_vec_near(glm::vec3(t), {0, 1, 0});
        EXPECT_EQ(t.w, 1.0f);
    }
}

// Two quads side by side sharing the x = 1 column; the right one's texture is mirrored
// (u = 2 - x). The shared vertices have the same position/normal/uv but opposite handedness
// on either side, so each is split in two.
TEST(Tangents, MirroredUvsSplitSeamVertices) {
    Mesh m;
    for (int y = 0; y <= 1; ++y) {
        for (int x = 0; x <= 2; ++x) {
            m.positions.push_back({float(x), float(y), 0.0f});
            m.normals.push_back({0, 0, 1});
            m.uvs.push_back({x <= 1 ? float(x) : 2.0f - float(x), 1.0f - float(y)});
        }
    }
    // Vertex (x, y) = 3y + x.
    m.indices = {0, 1, 4, 0, 4, 3,   // left quad
                 1, 2, 5, 1, 5, 4};  // right quad (mirrored UVs)
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), 8u);  // 6 inputs + the 2 seam vertices split
    EXPECT_EQ(std::count(r.remap.begin(), r.remap.end(), 1u), 2);
    EXPECT_EQ(std::count(r.remap.begin(), r.remap.end(), 4u), 2);
    for (std::size_t k = 0; k < m.indices.size(); ++k) {
        const glm::vec4 t = r.tangents[r.indices[k]];
        const bool left = k < 6;
        EXPECT_EQ(t.w, left ? 1.0f : -1.0f) << "corner " << k;
        expect_vec_near(glm::vec3(t), left ? glm::vec3(1, 0, 0) : glm::vec3(-1, 0, 0));
        // The bitangent points up the image on both sides.
        expect_vec_near(bitangent({0, 0, 1}, t), {0, 1, 0});
    }
    // The two sides' seam corners use different output vertices.
    EXPECT_NE(r.indices[1], r.indices[6]);   // input 1: left vs right
    EXPECT_NE(r.indices[2], r.indices[11]);  // input 4: left vs right
}

TEST(Tangents, SmoothGridKeepsVerticesShared) {
    const Mesh m = grid(8, true);
    const TangentMesh r = m.run();
    check_invariants(m, r);
    ASSERT_EQ(r.remap.size(), m.positions.size());  // no needless splitting
    std::vector<std::uint32_t> sorted = r.remap;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) EXPECT_EQ(sorted[i], i);
    for (std::size_t o = 0; o < r.tangents.size(); ++o) {
        EXPECT_EQ(r.tangents[o].w, 1.0f);
        // u grows along +X: the tangent leans towards +X and the bitangent towards +Y.
        EXPECT_GT(r.tangents[o].x, 0.7f);
        EXPECT_GT(bitangent(m.normals[r.remap[o]], r.tangents[o]).y, 0.7f);
    }
}

// A flat grid must give exactly the analytic frame everywhere.
TEST(Tangents, FlatGridExact) {
    const Mesh m = grid(5, false);
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), m.positions.size());
    for (const auto& t : r.tangents) {
        expect_vec_near(glm::vec3(t), {1, 0, 0}, 1e-6f);
        EXPECT_EQ(t.w, 1.0f);
    }
}

// MikkTSpace welds by value: a triangle soup (no shared indices) gives the same per-corner
// tangents as the indexed mesh, and no vertex is split.
TEST(Tangents, WeldsByValueNotIndex) {
    const Mesh indexed = grid(6, true);
    Mesh soup;
    for (std::uint32_t i : indexed.indices) {
        soup.indices.push_back(std::uint32_t(soup.positions.size()));
        soup.positions.push_back(indexed.positions[i]);
        soup.normals.push_back(indexed.normals[i]);
        soup.uvs.push_back(indexed.uvs[i]);
    }
    const TangentMesh a = indexed.run(), b = soup.run();
    check_invariants(indexed, a);
    check_invariants(soup, b);
    EXPECT_EQ(b.remap.size(), soup.positions.size());
    for (std::size_t k = 0; k < indexed.indices.size(); ++k) {
        const glm::vec4 ta = a.tangents[a.indices[k]], tb = b.tangents[b.indices[k]];
        expect_vec_near(glm::vec3(ta), glm::vec3(tb), 1e-6f);
        EXPECT_EQ(ta.w, tb.w);
    }
}

// UV sphere with a seam column and one vertex per pole per segment; the pole rows include the
// zero-area triangles (two corners at the pole). u runs east, glTF v runs from north to south.
TEST(Tangents, SphereTangentsAreUnitOrthogonalFinite) {
    Mesh m;
    const int stacks = 24, slices = 48;
    for (int i = 0; i <= stacks; ++i) {
        const float v = float(i) / float(stacks), theta = v * kPi;
        for (int j = 0; j <= slices; ++j) {
            const float u = float(j) / float(slices), phi = 2.0f * kPi * u;
            const glm::vec3 p(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
            m.positions.push_back(p);
            m.normals.push_back(i == 0 ? glm::vec3(0, 1, 0) : i == stacks ? glm::vec3(0, -1, 0) : glm::normalize(p));
            m.uvs.push_back({u, v});
        }
    }
    const auto at = [&](int i, int j) { return std::uint32_t(i * (slices + 1) + j); };
    for (int i = 0; i < stacks; ++i) {
        for (int j = 0; j < slices; ++j) {
            m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    // Sanity: the winding faces outwards.
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
        const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        if (glm::length(n) > 1e-6f) {
            ASSERT_GT(glm::dot(n, a + b + c), 0.0f);
        }
    }
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), m.positions.size());  // nothing mirrored, nothing to split
    for (std::size_t o = 0; o < r.tangents.size(); ++o) {
        const glm::vec4 t = r.tangents[o];
        EXPECT_EQ(t.w, 1.0f);
        const glm::vec3 p = m.positions[r.remap[o]];
        const float ring = std::sqrt(p.x * p.x + p.z * p.z);
        if (ring > 0.2f) {  // away from the poles the tangent points east (increasing u)
            const glm::vec3 east = glm::normalize(glm::vec3(p.z, 0.0f, -p.x));
            EXPECT_GT(glm::dot(glm::vec3(t), east), 0.99f) << "output vertex " << o;
            // and the bitangent points north (up the image, decreasing v)
            EXPECT_GT(bitangent(m.normals[r.remap[o]], t).y, 0.0f) << "output vertex " << o;
        }
    }
}

TEST(Tangents, DegenerateUvsGiveFiniteOrthonormalTangents) {
    Mesh m = grid(4, true);
    std::fill(m.uvs.begin(), m.uvs.end(), glm::vec2(0.0f));
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), m.positions.size());
    for (const auto& t : r.tangents) EXPECT_EQ(t.w, 1.0f);
}

TEST(Tangents, DegenerateNormalsTolerated) {
    Mesh m = upright_quad();
    m.normals[0] = {0, 0, 0};
    m.normals[2] = {std::nanf(""), 0, 0};
    m.normals[3] = {0, 0, 5};  // not unit: still projected correctly
    const TangentMesh r = m.run();
    check_invariants(m, r, false);
    for (std::size_t o = 0; o < r.tangents.size(); ++o) {
        if (r.remap[o] == 3) {
            EXPECT_NEAR(r.tangents[o].z, 0.0f, 1e-6f);
        }
    }
}

// Degenerate triangles take no part and must not change their neighbours' tangents; their
// own corners copy the tangents of the welded vertex.
TEST(Tangents, DegenerateTrianglesDoNotPoisonNeighbours) {
    const Mesh clean = grid(6, true);
    Mesh dirty = clean;
    // Index-degenerate triangle.
    dirty.indices.insert(dirty.indices.end(), {10, 10, 11});
    // Value-degenerate triangle: a duplicate of vertex 20 welds onto it.
    const auto dup = std::uint32_t(dirty.positions.size());
    dirty.positions.push_back(dirty.positions[20]);
    dirty.normals.push_back(dirty.normals[20]);
    dirty.uvs.push_back(dirty.uvs[20]);
    dirty.indices.insert(dirty.indices.end(), {20, dup, 21});
    // Zero-UV-area sliver along the first row (collinear UVs).
    dirty.indices.insert(dirty.indices.end(), {2, 1, 0});
    // Triangle whose positions coincide but whose UVs differ.
    const auto p0 = std::uint32_t(dirty.positions.size());
    for (int i = 0; i < 3; ++i) {
        dirty.positions.push_back(dirty.positions[30]);
        dirty.normals.push_back(dirty.normals[30]);
        dirty.uvs.push_back(dirty.uvs[30] + glm::vec2(0.1f * float(i), 0.05f * float(i * i)));
    }
    dirty.indices.insert(dirty.indices.end(), {p0, p0 + 1, p0 + 2});

    const TangentMesh a = clean.run(), b = dirty.run();
    check_invariants(clean, a);
    check_invariants(dirty, b);
    for (std::size_t k = 0; k < clean.indices.size(); ++k) {
        const glm::vec4 ta = a.tangents[a.indices[k]], tb = b.tangents[b.indices[k]];
        expect_vec_near(glm::vec3(ta), glm::vec3(tb), 1e-6f);
        EXPECT_EQ(ta.w, tb.w);
    }
    // The degenerate triangles' corners reuse the grid's tangents at those vertices.
    auto tangent_of = [&](const TangentMesh& r, const Mesh& m, std::uint32_t input) {
        for (std::size_t k = 0; k < m.indices.size(); ++k)
            if (m.indices[k] == input) return r.tangents[r.indices[k]];
        return glm::vec4(0.0f);
    };
    const std::size_t base = clean.indices.size();
    for (std::size_t k = base; k < base + 6; ++k) {
        const std::uint32_t in = dirty.indices[k] == dup ? 20u : dirty.indices[k];
        const glm::vec4 expected = tangent_of(a, clean, in), got = b.tangents[b.indices[k]];
        expect_vec_near(glm::vec3(got), glm::vec3(expected), 1e-6f);
        EXPECT_EQ(got.w, expected.w);
    }
    // Only the extra input vertices were added; the grid's vertices were not split.
    EXPECT_EQ(b.remap.size(), dirty.positions.size());
}

// MikkTSpace groups corners through shared edges: two triangles touching only at one vertex
// (same value, same handedness) but with different UV directions keep their own tangents there.
TEST(Tangents, EdgeDisconnectedFansAreNotMerged) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    m.normals.assign(5, {0, 0, 1});
    // Triangle A: u = x, v = -y (tangent +X). Triangle B (opposite quadrant) is the same
    // mapping rotated by 90 degrees: u = -y, v = -x (tangent -Y, not mirrored).
    m.uvs = {{0, 0}, {1, 0}, {0, -1}, {0, 1}, {1, 0}};
    m.indices = {0, 1, 2, 0, 3, 4};
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), 6u);  // the shared vertex 0 is split
    expect_vec_near(glm::vec3(r.tangents[r.indices[0]]), {1, 0, 0});
    expect_vec_near(glm::vec3(r.tangents[r.indices[3]]), {0, -1, 0});
    EXPECT_EQ(r.tangents[r.indices[0]].w, 1.0f);
    EXPECT_EQ(r.tangents[r.indices[3]].w, 1.0f);
}

// The tangent at a vertex is the corner-angle weighted sum of its triangles' (unit) tangents,
// independent of triangle size.
TEST(Tangents, AngleWeightedAverage) {
    // Fan around O: triangle 0 (O, A, B) has a 90 degree corner at O and u = x, v = -y, so its
    // tangent is +X. Triangle 1 (O, B, C) has a 45 degree corner at O; its UVs (same at O and B)
    // give it the tangent (1, 1)/sqrt(2) with the same handedness.
    const float s = std::sqrt(0.5f);
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-s, s, 0}};
    m.normals.assign(4, {0, 0, 1});
    m.uvs = {{0, 0}, {1, 0}, {0, -1}, {-s, -2 * s}};
    m.indices = {0, 1, 2, 0, 2, 3};
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), 4u);
    const glm::vec3 t0(1, 0, 0), t1 = glm::normalize(glm::vec3(1, 1, 0));
    auto angle = [&](std::uint32_t at, std::uint32_t a, std::uint32_t b) {
        return std::acos(glm::dot(glm::normalize(m.positions[a] - m.positions[at]),
                                  glm::normalize(m.positions[b] - m.positions[at])));
    };
    // Shared vertices O (0) and B (2): both triangles contribute.
    const glm::vec3 expect_o = glm::normalize(angle(0, 1, 2) * t0 + angle(0, 2, 3) * t1);
    const glm::vec3 expect_b = glm::normalize(angle(2, 0, 1) * t0 + angle(2, 3, 0) * t1);
    expect_vec_near(glm::vec3(r.tangents[r.indices[0]]), expect_o);
    expect_vec_near(glm::vec3(r.tangents[r.indices[2]]), expect_b);
    // Weighting by angle, not uniformly: O's tangent is (pi/2 * X + pi/4 * t1) normalised.
    EXPECT_NEAR(expect_o.x, 0.96754f, 1e-4f);
    // Unshared vertices keep their own triangle's tangent.
    expect_vec_near(glm::vec3(r.tangents[r.indices[1]]), t0);
    expect_vec_near(glm::vec3(r.tangents[r.indices[5]]), t1);
    for (const auto& t : r.tangents) EXPECT_EQ(t.w, 1.0f);
}

// A triangle with zero UV area ("group with any") contributes nothing but joins its
// neighbours' groups, so it causes no split.
TEST(Tangents, ZeroUvAreaTriangleJoinsGroup) {
    const float s = std::sqrt(0.5f);
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-s, s, 0}};
    m.normals.assign(4, {0, 0, 1});
    m.uvs = {{0, 0}, {1, 0}, {0, -1}, {0, 0}};  // triangle 1's UVs are collinear (u = 0)
    m.indices = {0, 1, 2, 0, 2, 3};
    const TangentMesh r = m.run();
    check_invariants(m, r);
    EXPECT_EQ(r.remap.size(), 4u);
    for (std::size_t k = 0; k < 6; ++k) {
        if (m.indices[k] == 3) continue;  // only in the zero-area triangle: fallback
        expect_vec_near(glm::vec3(r.tangents[r.indices[k]]), {1, 0, 0});
        EXPECT_EQ(r.tangents[r.indices[k]].w, 1.0f);
    }
}

// Hostile input: random topology with repeated indices, non-finite and extreme values.
// Whatever comes in, the output is consistent, finite and unit length.
TEST(Tangents, GarbageInputNeverProducesNaN) {
    std::mt19937 rng(1234);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float specials[] = {0.0f, -0.0f, 1e-30f, -1e-38f, 1e30f, -3e38f, inf, -inf, nan, 1.0f, 0.5f};
    std::uniform_real_distribution<float> real(-2.0f, 2.0f);
    std::uniform_int_distribution<int> pick(0, 9), special(0, int(std::size(specials)) - 1);
    auto value = [&] { return pick(rng) == 0 ? specials[special(rng)] : real(rng); };
    for (int round = 0; round < 20; ++round) {
        Mesh m;
        const int nv = 30;
        for (int i = 0; i < nv; ++i) {
            m.positions.push_back({value(), value(), value()});
            m.normals.push_back(pick(rng) < 3 ? glm::vec3(value(), value(), value())
                                              : glm::normalize(glm::vec3(real(rng), real(rng), 1.0f)));
            m.uvs.push_back(pick(rng) < 2 ? glm::vec2(0.25f) : glm::vec2(value(), value()));
        }
        std::uniform_int_distribution<std::uint32_t> vert(0, nv - 1);
        for (int k = 0; k < 300; ++k) m.indices.push_back(vert(rng));
        const TangentMesh r = m.run();
        check_invariants(m, r);
    }
}

TEST(Tangents, EmptyInput) {
    const TangentMesh r = generate_tangents({}, {}, {}, {});
    EXPECT_TRUE(r.remap.empty());
    EXPECT_TRUE(r.tangents.empty());
    EXPECT_TRUE(r.indices.empty());
}

TEST(Tangents, LargeGridCompletes) {
    const Mesh m = grid(200, true);  // 80,000 triangles
    const auto start = std::chrono::steady_clock::now();
    const TangentMesh r = m.run();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("generate_tangents: %zu triangles in %.1f ms\n", m.indices.size() / 3, ms);
    ASSERT_EQ(r.indices.size(), m.indices.size());
    EXPECT_EQ(r.remap.size(), m.positions.size());
}
