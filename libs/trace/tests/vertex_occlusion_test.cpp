// Baked per-vertex occlusion (bake_vertex_occlusion) against visibility known in closed form:
//  - an open floor sees the whole sky: visibility 1, bent normal straight up;
//  - a floor vertex at the foot of a tall, long wall sees half of its cosine-weighted
//    hemisphere (0.5) and its bent normal leans away from the wall: the mean cosine-weighted
//    direction over the open half is (2/3 * 2/pi, 2/3), 32.5 degrees from the normal;
//  - instanced and world-space trace scenes, and one or two threads, give the same values;
//  - skinned primitives (drawn posed by their joints) and hidden nodes get none.
#include "fresnel/trace/vertex_occlusion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

using namespace fresnel;
using namespace fresnel::trace;

namespace {

// A square of side 2 * half in the plane through `centre` facing `normal` (single-sided, one
// material), as a 3 x 3 grid of vertices (the middle one at the centre).
Primitive square(glm::vec3 centre, glm::vec3 u, glm::vec3 v, float half) {
    Primitive p;
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            p.positions.push_back(centre + half * (float(i) * u + float(j) * v));
            p.normals.push_back(n);
        }
    for (std::uint32_t j = 0; j < 2; ++j)
        for (std::uint32_t i = 0; i < 2; ++i) {
            const std::uint32_t a = j * 3 + i, b = a + 1, c = a + 3, d = a + 4;
            p.indices.insert(p.indices.end(), {a, b, d, a, d, c});
        }
    p.material = 0;
    return p;
}

Scene scene_of(std::vector<Primitive> prims) {
    Scene s;
    s.materials.emplace_back();
    for (Primitive& p : prims) {
        Mesh m;
        m.primitives.push_back(std::move(p));
        s.meshes.push_back(std::move(m));
        Node n;
        n.mesh = int(s.meshes.size()) - 1;
        s.nodes.push_back(n);
    }
    std::vector<int> roots;
    for (int i = 0; i < int(s.nodes.size()); ++i) roots.push_back(i);
    s.scenes.push_back(roots);
    return s;
}

VertexOcclusion bake(const Scene& s, const VertexOcclusionOptions& options = {}, bool instancing = true) {
    const std::vector<NodeInstance> instances = flatten(s);
    TraceSceneOptions to;
    to.instancing = instancing;
    const TraceScene ts(s, instances, to);
    return bake_vertex_occlusion(ts, s, instances, options);
}

// The floor: y = 0, facing +Y (u = +Z, v = +X: cross(Z, X) = +Y).
Primitive floor_square() { return square(glm::vec3(0.0f), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), 10.0f); }

}  // namespace

TEST(VertexOcclusion, AnOpenFloorSeesTheWholeSky) {
    const Scene s = scene_of({floor_square()});
    const VertexOcclusion occ = bake(s);
    ASSERT_NE(occ.find(0, 0), nullptr);
    EXPECT_EQ(occ.vertices, 9u);
    EXPECT_EQ(occ.rays_per_vertex, 128);
    for (const glm::vec4& v : *occ.find(0, 0)) {
        EXPECT_EQ(v.w, 1.0f);
        EXPECT_NEAR(v.y, 1.0f, 0.01f);  // the mean of cosine-distributed directions: the normal
    }
}

TEST(VertexOcclusion, AWallHidesHalfTheHemisphereAndBendsTheNormalAway) {
    // A wall 100 high and 200 long just beside x = 0, facing +X: the floor's middle column of
    // vertices (x = 0) lies at its foot.
    Primitive wall = square(glm::vec3(-1e-3f, 50.0f, 0.0f), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), 100.0f);
    const Scene s = scene_of({floor_square(), wall});
    VertexOcclusionOptions o;
    o.rays = 1024;
    const VertexOcclusion occ = bake(s, o);
    const std::vector<glm::vec4>& floor = *occ.find(0, 0);
    // Grid vertex (i, j) at index (j + 1) * 3 + (i + 1), at z = 10 i, x = 10 j: x = 0 is j = 0.
    for (int i = -1; i <= 1; ++i) {
        const glm::vec4 v = floor[std::size_t(3 + (i + 1))];
        EXPECT_NEAR(v.w, 0.5f, 0.01f) << "vertex at z = " << 10 * i;
        const float lean = std::atan2(v.x, v.y);  // towards +X, away from the wall
        EXPECT_NEAR(lean, std::atan2(4.0f / (3.0f * 3.14159265f), 2.0f / 3.0f), 0.03f);
        EXPECT_NEAR(glm::length(glm::vec3(v)), 1.0f, 1e-4f);
    }
    // The column beyond the wall (x = -10) is behind it: its floor faces up, the wall's back
    // (single-sided) lets rays through, so it is open.
    EXPECT_EQ(floor[0].w, 1.0f);
    // The column at x = +10 sees the wall's top 150 above at 10 away: nearly the same half hidden.
    EXPECT_GT(floor[6].w, 0.49f);
    EXPECT_LT(floor[6].w, 0.56f);
}

TEST(VertexOcclusion, SameValuesOnAnyThreadsAndWithInstances) {
    // Two copies of one box-like corner (floor and wall) placed by two nodes: instanced (one
    // prototype) or built in world space, the same rays see the same surfaces.
    Scene s = scene_of({floor_square(), square(glm::vec3(-1e-3f, 5.0f, 0.0f), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), 5.0f)});
    Mesh both;
    both.primitives = {s.meshes[0].primitives[0], s.meshes[1].primitives[0]};
    s.meshes = {both};
    s.nodes.clear();
    for (float x : {0.0f, 40.0f}) {
        Node n;
        n.mesh = 0;
        n.local = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0, 0));
        s.nodes.push_back(n);
    }
    s.scenes = {{0, 1}};
    VertexOcclusionOptions one;
    one.threads = 1;
    VertexOcclusionOptions two;
    two.threads = 2;
    const VertexOcclusion a = bake(s, one, true), b = bake(s, two, true), c = bake(s, two, false);
    for (int node : {0, 1})
        for (std::size_t k : {0u, 1u}) {
            ASSERT_NE(a.find(node, k), nullptr);
            const auto& va = *a.find(node, k);
            const auto& vb = *b.find(node, k);
            const auto& vc = *c.find(node, k);
            ASSERT_EQ(va.size(), 9u);
            for (std::size_t i = 0; i < va.size(); ++i) {
                EXPECT_EQ(va[i], vb[i]) << "threads, node " << node << " primitive " << k << " vertex " << i;
                EXPECT_NEAR(va[i].w, vc[i].w, 2.0f / 128.0f) << "instances, node " << node << " vertex " << i;
            }
        }
    // The corner's foot is half open in both placements.
    EXPECT_NEAR((*a.find(1, 0))[4].w, 0.5f, 0.1f);
}

TEST(VertexOcclusion, SkinnedPrimitivesAndHiddenNodesGetNone) {
    Primitive skinned = floor_square();
    skinned.joints.assign(skinned.positions.size(), glm::uvec4(0));
    skinned.weights.assign(skinned.positions.size(), glm::vec4(1, 0, 0, 0));
    Scene s = scene_of({floor_square(), skinned, floor_square()});
    s.nodes[2].visible = false;
    const VertexOcclusion occ = bake(s);
    EXPECT_NE(occ.find(0, 0), nullptr);
    EXPECT_EQ(occ.find(1, 0), nullptr);
    EXPECT_EQ(occ.find(2, 0), nullptr);
    EXPECT_EQ(occ.vertices, 9u);
}

// The cache (load_or_bake_vertex_occlusion): a second bake of the same scene is read back equal;
// the key follows what the values depend on; a file cut short, of another scene, with another key
// or with a value out of range is not used.
TEST(VertexOcclusionCache, RoundTripsAndRefusesWhatDoesNotFit) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "fresnel_occlusion_cache_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const char* old_cache = std::getenv("XDG_CACHE_HOME");
    const std::string restore = old_cache ? old_cache : "";
    setenv("XDG_CACHE_HOME", (dir / "cache").c_str(), 1);

    Primitive wall = square(glm::vec3(-1e-3f, 5.0f, 0.0f), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), 5.0f);
    Scene s = scene_of({floor_square(), wall});
    const std::vector<NodeInstance> instances = flatten(s);
    VertexOcclusionOptions o;
    o.rays = 32;
    const VertexOcclusion first = load_or_bake_vertex_occlusion(s, instances, o, true);
    const VertexOcclusion again = load_or_bake_vertex_occlusion(s, instances, o, true);
    EXPECT_FALSE(first.from_cache);
    EXPECT_TRUE(again.from_cache);
    EXPECT_EQ(again.nodes, first.nodes);
    EXPECT_EQ(again.vertices, first.vertices);
    EXPECT_EQ(again.rays_per_vertex, 32);
    EXPECT_FALSE(load_or_bake_vertex_occlusion(s, instances, o, false).from_cache);  // --no-cache

    // The key: rays, a moved node, a moved vertex, a material's alpha mode.
    const std::uint64_t key = vertex_occlusion_key(s, instances, o);
    VertexOcclusionOptions more = o;
    more.rays = 64;
    EXPECT_NE(vertex_occlusion_key(s, instances, more), key);
    std::vector<NodeInstance> moved = instances;
    moved[1].world[3][0] += 0.5f;
    EXPECT_NE(vertex_occlusion_key(s, moved, o), key);
    Scene edited = s;
    edited.meshes[1].primitives[0].positions[4].y += 0.1f;
    EXPECT_NE(vertex_occlusion_key(edited, instances, o), key);
    edited = s;
    edited.materials[0].alpha_mode = AlphaMode::Mask;
    EXPECT_NE(vertex_occlusion_key(edited, instances, o), key);

    // Files that do not fit.
    const fs::path file = dir / "x.ao";
    write_vertex_occlusion(file, first, key);
    ASSERT_TRUE(read_vertex_occlusion(file, s, key).has_value());
    EXPECT_FALSE(read_vertex_occlusion(file, s, key + 1).has_value());
    Scene other = s;
    other.meshes[0].primitives[0].positions.pop_back();
    EXPECT_FALSE(read_vertex_occlusion(file, other, key).has_value());
    const auto size = fs::file_size(file);
    for (std::uintmax_t cut : {std::uintmax_t(0), std::uintmax_t(7), std::uintmax_t(30), size / 2, size - 1}) {
        fs::copy_file(file, dir / "cut.ao", fs::copy_options::overwrite_existing);
        fs::resize_file(dir / "cut.ao", cut);
        EXPECT_FALSE(read_vertex_occlusion(dir / "cut.ao", s, key).has_value()) << "cut at " << cut;
    }
    VertexOcclusion bad = first;
    bad.nodes[0][0][2].w = std::nanf("");
    write_vertex_occlusion(file, bad, key);
    EXPECT_FALSE(read_vertex_occlusion(file, s, key).has_value());
    bad.nodes[0][0][2].w = 1.5f;
    write_vertex_occlusion(file, bad, key);
    EXPECT_FALSE(read_vertex_occlusion(file, s, key).has_value());

    if (old_cache) setenv("XDG_CACHE_HOME", restore.c_str(), 1);
    else unsetenv("XDG_CACHE_HOME");
    fs::remove_all(dir);
}
