// Unit tests of the public mesh operations (fresnel/scene/mesh_ops.h), on small hand-made
// meshes whose answers are known without running the code under test.
#include "fresnel/scene/mesh_ops.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace fresnel;

namespace {

using Indices = std::vector<std::uint32_t>;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

void expect_near(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}
void expect_near(const glm::vec4& a, const glm::vec4& b, float eps = 1e-5f) {
    expect_near(glm::vec3(a), glm::vec3(b), eps);
    EXPECT_NEAR(a.w, b.w, eps);
}
void expect_near(const glm::mat4& a, const glm::mat4& b, float eps = 1e-5f) {
    for (int c = 0; c < 4; ++c) expect_near(a[c], b[c], eps);
}

glm::vec3 face(const std::vector<glm::vec3>& p, const Indices& list, std::size_t t) {
    return glm::cross(p[list[t * 3 + 1]] - p[list[t * 3]], p[list[t * 3 + 2]] - p[list[t * 3]]);
}

// Two triangles in the z = 0 plane, counter-clockwise seen from +Z, plus one vertex (4) no
// triangle uses. uv: u along +x, v down the image (v = 1 - y).
Primitive quad() {
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {5, 5, 5}};
    p.uv0 = {{0, 1}, {1, 1}, {1, 0}, {0, 0}, {0.5f, 0.5f}};
    p.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}, {0, 0, 0, 1}};
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

}  // namespace

// ---- index conversion -------------------------------------------------------------------

TEST(MeshOpsTest, TriangleStripBecomesListWithOneWinding) {
    // A zig-zag strip along +x in the z = 0 plane whose first triangle (0, 1, 2) faces -Z:
    // after conversion every triangle must face -Z too.
    std::vector<glm::vec3> p = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 0}, {2, 1, 0}};
    Indices strip = {0, 1, 2, 3, 4, 5};
    Indices list = strip_to_triangles(strip);
    EXPECT_EQ(list, (Indices{0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5}));
    for (std::size_t t = 0; t < list.size() / 3; ++t) EXPECT_LT(face(p, list, t).z, 0.0f) << "triangle " << t;
    EXPECT_TRUE(strip_to_triangles(Indices{0, 1}).empty());
    EXPECT_TRUE(strip_to_triangles(Indices{}).empty());
}

TEST(MeshOpsTest, TriangleFanBecomesListWithOneWinding) {
    // A fan around the origin, counter-clockwise seen from +Z.
    std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}};
    Indices list = fan_to_triangles(Indices{0, 1, 2, 3, 4});
    EXPECT_EQ(list, (Indices{0, 1, 2, 0, 2, 3, 0, 3, 4}));
    for (std::size_t t = 0; t < list.size() / 3; ++t) EXPECT_GT(face(p, list, t).z, 0.0f) << "triangle " << t;
    EXPECT_TRUE(fan_to_triangles(Indices{7, 8}).empty());
}

TEST(MeshOpsTest, LineStripsAndLoopsBecomeLines) {
    EXPECT_EQ(line_strip_to_lines(Indices{5, 6, 7}), (Indices{5, 6, 6, 7}));
    EXPECT_EQ(line_loop_to_lines(Indices{5, 6, 7}), (Indices{5, 6, 6, 7, 7, 5}));
    EXPECT_EQ(line_loop_to_lines(Indices{5, 6}), (Indices{5, 6}));
    EXPECT_TRUE(line_strip_to_lines(Indices{5}).empty());
    EXPECT_TRUE(line_loop_to_lines(Indices{5}).empty());
}

TEST(MeshOpsTest, IndexListOfNonIndexedPrimitiveIsTheIdentity) {
    Primitive p;
    p.positions.resize(4);
    EXPECT_EQ(index_list(p), (Indices{0, 1, 2, 3}));
    p.indices = {3, 2, 1};
    EXPECT_EQ(index_list(p), (Indices{3, 2, 1}));
}

// ---- normals and tangents ---------------------------------------------------------------

TEST(MeshOpsTest, RepairNormalsRenormalisesAndReplacesBadOnes) {
    // Triangle A faces +Y (area 0.5), triangle B faces +X (area 2); vertex 0 is in both, so
    // its area-weighted normal is normalize(4, 1, 0) (cross products (0,1,0) and (4,0,0)).
    std::vector<glm::vec3> pos = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 2, 0}, {0, 0, 2}, {9, 9, 9}};
    Indices tris = {0, 1, 2, 0, 3, 4};
    std::vector<glm::vec3> n = {{0, 0, 0}, {0, 3, 0}, {kNaN, 0, 0}, {kInf, 0, 0}, {0, 0, -2}, {0, 0, 0}};
    EXPECT_EQ(repair_normals(pos, tris, n), 4u);
    expect_near(n[0], glm::normalize(glm::vec3(4, 1, 0)));  // zero: smooth normal
    expect_near(n[1], {0, 1, 0});                            // only renormalised
    expect_near(n[2], {0, 1, 0});                            // NaN: triangle A's normal
    expect_near(n[3], {1, 0, 0});                            // infinite: triangle B's normal
    expect_near(n[4], {0, 0, -1});                           // renormalised, direction kept
    expect_near(n[5], {0, 0, 1});                            // no triangle: +Z
}

TEST(MeshOpsTest, RepairNormalsOnPrimitiveOnlyTouchesTriangles) {
    Primitive p = quad();
    p.normals = {{0, 0, 0}, {0, 0, 4}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    EXPECT_EQ(repair_normals(p), 1u);
    expect_near(p.normals[0], {0, 0, 1});
    expect_near(p.normals[1], {0, 0, 1});
    Primitive lines = quad();
    lines.topology = Topology::Lines;
    lines.normals.assign(5, glm::vec3(0, 0, 3));
    EXPECT_EQ(repair_normals(lines), 0u);
    EXPECT_EQ(lines.normals[0], glm::vec3(0, 0, 3));
}

TEST(MeshOpsTest, FlatNormalsSplitEveryTriangle) {
    Primitive p = quad();
    p.positions[3] = {0, 1, 1};  // fold the second triangle out of the plane
    generate_flat_normals(p);
    EXPECT_TRUE(p.generated_normals);
    EXPECT_TRUE(p.indices.empty());
    ASSERT_EQ(p.positions.size(), 6u);  // the unused vertex 4 is gone
    ASSERT_EQ(p.normals.size(), 6u);
    ASSERT_EQ(p.uv0.size(), 6u);
    ASSERT_EQ(p.colors.size(), 6u);
    // Attributes follow the corners 0 1 2 0 2 3.
    EXPECT_EQ(p.positions[3], glm::vec3(0, 0, 0));
    EXPECT_EQ(p.positions[5], glm::vec3(0, 1, 1));
    EXPECT_EQ(p.uv0[5], glm::vec2(0, 0));
    EXPECT_EQ(p.colors[1], glm::vec4(0, 1, 0, 1));
    for (int k = 0; k < 3; ++k) expect_near(p.normals[std::size_t(k)], {0, 0, 1});
    // (0,0,0) (1,1,0) (0,1,1): cross((1,1,0), (0,1,1)) = (1,-1,1).
    for (int k = 3; k < 6; ++k) expect_near(p.normals[std::size_t(k)], glm::normalize(glm::vec3(1, -1, 1)));

    Primitive degenerate;
    degenerate.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
    generate_flat_normals(degenerate);
    for (const auto& n : degenerate.normals) expect_near(n, {0, 0, 1});

    Primitive points = quad();
    points.topology = Topology::Points;
    generate_flat_normals(points);
    EXPECT_TRUE(points.normals.empty());
    EXPECT_EQ(points.positions.size(), 5u);
}

TEST(MeshOpsTest, TangentsOnPrimitiveAreTheMikkTSpaceOnes) {
    Primitive p = quad();
    p.normals.assign(5, glm::vec3(0, 0, 1));
    Primitive before = p;
    ASSERT_TRUE(generate_tangents(p, 0));
    EXPECT_TRUE(p.generated_tangents);
    // The same as tangents.h on the plain arrays, with every attribute following the remap.
    TangentMesh tm = generate_tangents(before.positions, before.normals, before.uv0, before.indices);
    EXPECT_EQ(p.indices, tm.indices);
    ASSERT_EQ(p.tangents.size(), tm.tangents.size());
    ASSERT_EQ(p.positions.size(), tm.remap.size());
    for (std::size_t v = 0; v < tm.remap.size(); ++v) {
        EXPECT_EQ(p.tangents[v], tm.tangents[v]);
        EXPECT_EQ(p.positions[v], before.positions[tm.remap[v]]);
        EXPECT_EQ(p.uv0[v], before.uv0[tm.remap[v]]);
        EXPECT_EQ(p.colors[v], before.colors[tm.remap[v]]);
        // u grows along +x; v grows down the image (towards -y), so the bitangent
        // w * cross(n, t) = +y and w = +1 (see tangents.h).
        expect_near(p.tangents[v], {1, 0, 0, 1});
    }
    // TEXCOORD_1 missing, or not triangles: nothing happens.
    Primitive q = before;
    EXPECT_FALSE(generate_tangents(q, 1));
    EXPECT_TRUE(q.tangents.empty());
    EXPECT_FALSE(q.generated_tangents);
    q.topology = Topology::Lines;
    EXPECT_FALSE(generate_tangents(q, 0));
    // Non-indexed primitives use their vertices in order.
    Primitive flat = before;
    generate_flat_normals(flat);
    ASSERT_TRUE(generate_tangents(flat, 0));
    EXPECT_EQ(flat.indices.size(), 6u);
    for (const auto& t : flat.tangents) expect_near(t, {1, 0, 0, 1});
}

TEST(MeshOpsTest, RepairTangents) {
    std::vector<glm::vec4> t = {{2, 0, 0, 5}, {0, 3, 0, -0.5f}, {kNaN, 0, 0, 1}, {0, 0, 0, -1}, {0, 0, kInf, 1}};
    repair_tangents(t);
    expect_near(t[0], {1, 0, 0, 1});
    expect_near(t[1], {0, 1, 0, -1});
    expect_near(t[2], {1, 0, 0, 1});
    expect_near(t[3], {1, 0, 0, 1});
    expect_near(t[4], {1, 0, 0, 1});
}

// ---- vertices and indices ---------------------------------------------------------------

TEST(MeshOpsTest, RemapVerticesMovesEveryAttribute) {
    Primitive p = quad();
    p.joints = {{0, 0, 0, 0}, {1, 0, 0, 0}, {2, 0, 0, 0}, {3, 0, 0, 0}, {4, 0, 0, 0}};
    p.weights.assign(5, glm::vec4(1, 0, 0, 0));
    remap_vertices(p, Indices{2, 2, 0});
    ASSERT_EQ(p.positions.size(), 3u);
    EXPECT_EQ(p.positions[0], glm::vec3(1, 1, 0));
    EXPECT_EQ(p.positions[2], glm::vec3(0, 0, 0));
    EXPECT_EQ(p.uv0[1], glm::vec2(1, 0));
    EXPECT_EQ(p.colors[2], glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(p.joints[0].x, 2u);
    EXPECT_EQ(p.weights.size(), 3u);
    EXPECT_TRUE(p.normals.empty());  // absent attributes stay absent
    EXPECT_EQ(p.indices, (Indices{0, 1, 2, 0, 2, 3}));
}

TEST(MeshOpsTest, DropIdentityIndices) {
    Primitive p;
    p.positions.resize(3);
    p.indices = {0, 1, 2};
    EXPECT_TRUE(drop_identity_indices(p));
    EXPECT_TRUE(p.indices.empty());
    p.indices = {0, 2, 1};
    EXPECT_FALSE(drop_identity_indices(p));
    p.indices = {0, 1, 2, 0, 1, 2};
    EXPECT_FALSE(drop_identity_indices(p));
    EXPECT_EQ(p.indices.size(), 6u);
}

TEST(MeshOpsTest, CompactVerticesDropsUnreferencedOnes) {
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}};
    p.uv0 = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}};
    p.indices = {3, 1, 4, 4, 1, 3};
    Indices remap = compact_vertices(p);
    EXPECT_EQ(remap, (Indices{1, 3, 4}));
    EXPECT_EQ(p.indices, (Indices{1, 0, 2, 2, 0, 1}));
    ASSERT_EQ(p.positions.size(), 3u);
    EXPECT_EQ(p.positions[0], glm::vec3(1, 0, 0));
    EXPECT_EQ(p.uv0[2], glm::vec2(4, 0));
    // Every corner still reads the same position as before.
    const Indices before = {3, 1, 4, 4, 1, 3};
    for (std::size_t k = 0; k < before.size(); ++k) EXPECT_EQ(p.positions[p.indices[k]].x, float(before[k]));

    // When the used vertices come in order, the index buffer ends up the identity and goes.
    Primitive q = quad();
    q.indices = {0, 1, 2};
    compact_vertices(q);
    EXPECT_TRUE(q.indices.empty());
    EXPECT_EQ(q.positions.size(), 3u);
    EXPECT_EQ(q.colors.size(), 3u);
}

// ---- transforms and skinning ------------------------------------------------------------

TEST(MeshOpsTest, WorldMatricesComposeDownTheHierarchy) {
    // The grandchild is listed first, its parent last: the order of the array must not matter.
    std::vector<Node> nodes(3);
    nodes[2].local = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0));  // root
    nodes[2].children = {1};
    nodes[1].local = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
    nodes[1].children = {0};
    nodes[0].local = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
    auto world = world_matrices(nodes);
    ASSERT_EQ(world.size(), 3u);
    expect_near(glm::vec3(world[0] * glm::vec4(0, 0, 0, 1)), {1, 2, 0});
    expect_near(glm::vec3(world[1] * glm::vec4(1, 0, 0, 1)), {3, 0, 0});
    expect_near(world[2], nodes[2].local);

    // flatten() places instances with the same matrices.
    Scene scene;
    scene.nodes = nodes;
    scene.scenes = {{2}};
    auto inst = flatten(scene);
    ASSERT_EQ(inst.size(), 3u);
    for (const auto& i : inst) expect_near(i.world, world[std::size_t(i.node)]);
    EXPECT_EQ(inst[0].node, 2);
    EXPECT_EQ(inst[2].node, 0);
}

TEST(MeshOpsTest, WorldMatricesSurviveBadHierarchies) {
    // A cycle (0 -> 1 -> 0) has no root; a child index out of range is ignored.
    std::vector<Node> nodes(3);
    nodes[0].children = {1, 7, -1};
    nodes[1].children = {0};
    nodes[0].local = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0));
    nodes[1].local = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0));
    nodes[2].local = glm::scale(glm::mat4(1.0f), glm::vec3(3.0f));
    auto world = world_matrices(nodes);
    ASSERT_EQ(world.size(), 3u);
    expect_near(world[0], nodes[0].local);
    expect_near(world[1], nodes[1].local);
    expect_near(world[2], nodes[2].local);
    EXPECT_TRUE(world_matrices(std::vector<Node>{}).empty());
}

TEST(MeshOpsTest, SkinMatricesOfEverySkinInKeptStorage) {
    // Node 0 holds node 1 (translated by 2 in y); skins: a good one, one with a joint out of
    // range, one without joints, one past a joint limit of 2.
    std::vector<Node> nodes(3);
    nodes[0].children = {1};
    nodes[0].local = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0));
    nodes[1].local = glm::translate(glm::mat4(1.0f), glm::vec3(0, 2, 0));
    std::vector<Skin> skins(4);
    skins[0].joints = {0, 1};
    skins[0].inverse_bind = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-1, -2, 0))};
    skins[1].joints = {0, 7};
    skins[3].joints = {0, 1, 2};
    SkinMatrices out;
    skin_matrices(nodes, skins, out, 2);
    ASSERT_EQ(out.world.size(), 3u);
    expect_near(out.world[1], glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 0)));
    ASSERT_EQ(out.skins.size(), 4u);
    ASSERT_EQ(out.skins[0].size(), 2u);
    expect_near(out.skins[0][0], nodes[0].local);  // no inverse bind: the world matrix
    expect_near(out.skins[0][1], glm::mat4(1.0f));  // bind pose = current pose
    EXPECT_TRUE(out.skins[1].empty());
    EXPECT_TRUE(out.skins[2].empty());
    EXPECT_TRUE(out.skins[3].empty());
    // As world_matrices and joint_matrices give them.
    auto world = world_matrices(nodes);
    for (std::size_t i = 0; i < world.size(); ++i) expect_near(out.world[i], world[i]);
    // A second call with the nodes moved reuses the storage (the renderer calls it every frame).
    const glm::mat4* kept = out.skins[0].data();
    nodes[1].local = glm::mat4(1.0f);
    skin_matrices(nodes, skins, out, 2);
    EXPECT_EQ(out.skins[0].data(), kept);
    expect_near(out.skins[0][1], glm::translate(glm::mat4(1.0f), glm::vec3(0, -2, 0)));
}

TEST(MeshOpsTest, JointMatricesAreWorldTimesInverseBind) {
    std::vector<glm::mat4> world = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0, 2, 0)),
                                    glm::scale(glm::mat4(1.0f), glm::vec3(2.0f))};
    std::vector<int> joints = {1, 2};
    std::vector<glm::mat4> ibm = {glm::translate(glm::mat4(1.0f), glm::vec3(0, -2, 0))};
    auto m = joint_matrices(world, joints, ibm);
    ASSERT_EQ(m.size(), 2u);
    expect_near(m[0], glm::mat4(1.0f));  // the bind pose is the current pose: identity
    expect_near(m[1], world[2]);         // no inverse bind matrix: identity
}

TEST(MeshOpsTest, PoseSkinnedBlendsJointsAndFollowsTheNodeWithoutWeights) {
    std::vector<glm::mat4> joints = {glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)),
                                     glm::rotate(glm::mat4(1.0f), 1.5707963f, glm::vec3(0, 0, 1)),
                                     glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, 1))};
    glm::mat4 node = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
    Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}};
    p.normals = {{0, 0, 1}, {1, 0, 0}, glm::normalize(glm::vec3(1, 1, 0)), {0, 1, 0}};
    p.tangents = {{1, 0, 0, 1}, {0, 1, 0, -1}, {1, 0, 0, 1}, {1, 0, 0, -1}};
    p.joints = {{0, 1, 0, 0}, {1, 0, 0, 0}, {2, 0, 0, 0}, {0, 0, 0, 0}};
    p.weights = {{0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 0}};
    EXPECT_FALSE(find_invalid_joint(p, joints.size()).has_value());
    pose_skinned(p, joints, node);
    // Half translated, half rotated (the origin does not move under the rotation).
    expect_near(p.positions[0], {1, 0, 0});
    // Rotated a quarter turn about +Z: position, normal and tangent, w kept.
    expect_near(p.positions[1], {0, 1, 0});
    expect_near(p.normals[1], {0, 1, 0});
    expect_near(p.tangents[1], {-1, 0, 0, -1});
    // Non-uniform scale: the normal goes by the inverse transpose (x halves), then unit.
    expect_near(p.positions[2], {2, 1, 0});
    expect_near(p.normals[2], glm::normalize(glm::vec3(0.5f, 1, 0)));
    expect_near(p.tangents[2], {1, 0, 0, 1});
    // No weight: the node's matrix.
    expect_near(p.positions[3], {0, 0, 5});
    expect_near(p.normals[3], {0, 1, 0});

    // Without JOINTS_0 the whole primitive follows the node.
    Primitive rigid;
    rigid.positions = {{1, 2, 3}};
    rigid.normals = {{0, 0, 2}};
    pose_skinned(rigid, joints, node);
    expect_near(rigid.positions[0], {1, 2, 8});
    expect_near(rigid.normals[0], {0, 0, 1});
}

TEST(MeshOpsTest, FindInvalidJointReportsTheFirstWeightedOne) {
    Primitive p;
    p.positions.resize(3);
    p.joints = {{0, 9, 0, 0}, {1, 7, 0, 0}, {8, 0, 0, 0}};
    p.weights = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}};  // joint 9 has no weight
    auto bad = find_invalid_joint(p, 2);
    ASSERT_TRUE(bad.has_value());
    EXPECT_EQ(bad->vertex, 1u);
    EXPECT_EQ(bad->joint, 7u);
    EXPECT_FALSE(find_invalid_joint(p, 10).has_value());
    // Posing ignores the bad joint instead of reading past the matrices.
    std::vector<glm::mat4> two = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0, 4, 0))};
    pose_skinned(p, two, glm::mat4(1.0f));
    expect_near(p.positions[1], {0, 2, 0});  // only joint 1's half: 0.5 * (0, 4, 0)
    expect_near(p.positions[2], {0, 0, 0});  // no valid weight: the node (identity)
}

TEST(MeshOpsTest, TransformPrimitive) {
    Primitive p;
    p.positions = {{1, 0, 0}};
    p.normals = {{1, 1, 0}};
    p.tangents = {{1, -1, 0, -1}};
    transform_primitive(p, glm::scale(glm::mat4(1.0f), glm::vec3(1, 2, 1)));
    expect_near(p.positions[0], {1, 0, 0});
    expect_near(p.normals[0], glm::normalize(glm::vec3(1, 0.5f, 0)));
    expect_near(p.tangents[0], glm::vec4(glm::normalize(glm::vec3(1, -2, 0)), -1));
}

// ---- picking and node visibility (fresnel/scene/pick.h, KHR_node_visibility) ----------------

namespace {
// Two unit quads in the z = 0 plane of their nodes: node 0 at the origin, node 1 (a child of
// node 0) moved to z = -2 and scaled by 2.
Scene two_quads() {
    Scene s;
    Mesh m;
    Primitive p;
    p.positions = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}};
    p.normals.assign(4, glm::vec3(0, 0, 1));
    p.indices = {0, 1, 2, 0, 2, 3};
    p.bounds_min = {-0.5f, -0.5f, 0};
    p.bounds_max = {0.5f, 0.5f, 0};
    m.primitives = {p};
    s.meshes = {m};
    s.nodes.resize(2);
    s.nodes[0].mesh = 0;
    s.nodes[0].children = {1};
    s.nodes[1].mesh = 0;
    s.nodes[1].local = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -2)), glm::vec3(2.0f));
    s.scenes = {{0}};
    s.default_scene = 0;
    return s;
}
}  // namespace

#include "fresnel/scene/pick.h"

TEST(Pick, NearestTriangleInWorldUnits) {
    Scene s = two_quads();
    auto inst = flatten(s);
    // From z = 5 straight down -z: the front quad at distance 5.
    auto hit = pick(s, inst, {0.1f, 0.2f, 5.0f}, {0, 0, -3});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->node, 0);
    EXPECT_EQ(hit->primitive, 0);
    EXPECT_NEAR(hit->distance, 5.0f, 1e-5f);
    expect_near(hit->point, {0.1f, 0.2f, 0.0f});
    // Outside the front quad (x = 0.8) but inside the scaled back one (half size 1): distance 7.
    hit = pick(s, inst, {0.8f, 0.0f, 5.0f}, {0, 0, -1});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->node, 1);
    EXPECT_NEAR(hit->distance, 7.0f, 1e-5f);
    // Which triangle: (0.4, -0.3) lies in triangle 0 (0, 1, 2), (-0.4, 0.3) in triangle 1.
    EXPECT_EQ(pick(s, inst, {0.4f, -0.3f, 1.0f}, {0, 0, -1})->triangle, 0);
    EXPECT_EQ(pick(s, inst, {-0.4f, 0.3f, 1.0f}, {0, 0, -1})->triangle, 1);
    // From behind: the back face counts; missing everything, or a zero direction: nothing.
    hit = pick(s, inst, {0.0f, 0.0f, -10.0f}, {0, 0, 1});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->node, 1);
    EXPECT_NEAR(hit->distance, 8.0f, 1e-5f);
    EXPECT_FALSE(pick(s, inst, {3.0f, 0.0f, 5.0f}, {0, 0, -1}));
    EXPECT_FALSE(pick(s, inst, {0.0f, 0.0f, 5.0f}, {0, 0, 1}));  // pointing away
    EXPECT_FALSE(pick(s, inst, {0.0f, 0.0f, 5.0f}, {0, 0, 0}));
    // The highlighted box of the back quad: half size 1 at z = -2.
    Bounds b = primitive_world_bounds(s, inst[1], 0);
    expect_near(b.min, {-1, -1, -2});
    expect_near(b.max, {1, 1, -2});
}

TEST(Pick, HiddenNodesAndTheirChildrenAreNotSeen) {
    Scene s = two_quads();
    s.nodes[0].visible = false;  // hides node 1 too, though its own flag says visible
    auto inst = flatten(s);
    ASSERT_EQ(inst.size(), 2u);
    EXPECT_FALSE(inst[0].visible);
    EXPECT_FALSE(inst[1].visible);
    EXPECT_FALSE(pick(s, inst, {0.0f, 0.0f, 5.0f}, {0, 0, -1}));
    s.nodes[0].visible = true;
    s.nodes[1].visible = false;  // only the child hidden: the ray through both meets node 0 only
    inst = flatten(s);
    EXPECT_TRUE(inst[0].visible);
    EXPECT_FALSE(inst[1].visible);
    auto hit = pick(s, inst, {0.0f, 0.0f, -10.0f}, {0, 0, 1});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->node, 0);
    EXPECT_NEAR(hit->distance, 10.0f, 1e-5f);
}

// Triangles sorted by the Morton order of their UV centroids: the same triangles with the
// same windings, grouped by UV region; a broken list is left alone.
TEST(MeshOps, SortTrianglesByUv) {
    // A 4x4 grid of UV cells, two triangles per cell, listed in a scrambled cell order.
    std::vector<glm::vec2> uv;
    std::vector<std::uint32_t> tris;
    const int order[16] = {5, 12, 0, 15, 3, 9, 6, 1, 14, 10, 2, 8, 13, 7, 11, 4};
    for (int cell : order) {
        const float x = float(cell % 4) / 4.0f, y = float(cell / 4) / 4.0f, d = 0.25f;
        const auto base = std::uint32_t(uv.size());
        uv.insert(uv.end(), {{x, y}, {x + d, y}, {x + d, y + d}, {x, y + d}});
        tris.insert(tris.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    std::vector<std::uint32_t> sorted = tris;
    sort_triangles_by_uv(sorted, uv);
    ASSERT_EQ(sorted.size(), tris.size());
    // The same triangles, each with its own indices in its own order (winding kept).
    auto as_set = [](const std::vector<std::uint32_t>& t) {
        std::multiset<std::array<std::uint32_t, 3>> s;
        for (std::size_t i = 0; i < t.size(); i += 3) s.insert({t[i], t[i + 1], t[i + 2]});
        return s;
    };
    EXPECT_EQ(as_set(sorted), as_set(tris));
    // Cell by cell in Z order: (0,0) (1,0) (0,1) (1,1) (2,0) (3,0) ... i.e. cells 0 1 4 5 2 3 6 7 ...
    const int z_order[16] = {0, 1, 4, 5, 2, 3, 6, 7, 8, 9, 12, 13, 10, 11, 14, 15};
    for (int k = 0; k < 16; ++k) {
        for (int half = 0; half < 2; ++half) {
            const std::size_t t = std::size_t(k * 2 + half) * 3;
            glm::vec2 c = (uv[sorted[t]] + uv[sorted[t + 1]] + uv[sorted[t + 2]]) / 3.0f;
            EXPECT_EQ(int(c.x * 4.0f) + 4 * int(c.y * 4.0f), z_order[k]) << "triangle " << k * 2 + half;
        }
    }
    // Repeating UVs sort by their position within the tile: shifting every UV by whole tiles changes nothing.
    std::vector<glm::vec2> shifted = uv;
    for (auto& c : shifted) c += glm::vec2(3.0f, -2.0f);
    std::vector<std::uint32_t> sorted_shifted = tris;
    sort_triangles_by_uv(sorted_shifted, shifted);
    EXPECT_EQ(sorted_shifted, sorted);
    // Not whole triangles, or an index out of range: unchanged.
    std::vector<std::uint32_t> broken = tris;
    broken.pop_back();
    sort_triangles_by_uv(broken, uv);
    EXPECT_TRUE(std::equal(broken.begin(), broken.end(), tris.begin()));
    broken = tris;
    broken[4] = std::uint32_t(uv.size());
    std::vector<std::uint32_t> before = broken;
    sort_triangles_by_uv(broken, uv);
    EXPECT_EQ(broken, before);
}
