// The OBJ/MTL loader (fresnel/scene/obj_loader.h) on small hand-written files whose answers
// are known without the code under test: counts, triangulation of concave polygons,
// smoothing groups, relative indices, MTL keys and options, the path policy, hostile
// input; and every shared OBJ case (../shared/assets/obj), which must load or fail clearly.
#include "fresnel/scene/obj_loader.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <set>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "fresnel/material/phong.h"
#include "fresnel/scene/mesh_ops.h"
#include "temp_dir.h"

using namespace fresnel;
namespace fs = std::filesystem;

namespace {

Scene load_text(const std::string& text, Diagnostics& diag, const ObjLoadOptions& o = {},
                const fs::path& dir = "/nonexistent-fresnel-obj-test") {
    std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
    return load_obj_from_memory(bytes, "test.obj", dir, diag, o);
}
Scene load_text(const std::string& text) {
    Diagnostics diag;
    return load_text(text, diag);
}

// The error a text gives (fails the test when it loads).
Error error_of(const std::string& text, const ObjLoadOptions& o = {}) {
    Diagnostics diag;
    try {
        load_text(text, diag, o);
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "loaded without error:\n" << text.substr(0, 200);
    return Error("", "", "");
}

std::size_t triangles(const Scene& s) {
    std::size_t n = 0;
    for (const auto& m : s.meshes)
        for (const auto& p : m.primitives) n += p.triangle_count();
    return n;
}

bool has_warning(const Diagnostics& d, const std::string& part) {
    for (const auto& l : d.lines())
        if (l.find(part) != std::string::npos) return true;
    return false;
}

using fresnel::test::TempDir;  // tests/support/temp_dir.h

void write_png_rgba(const fs::path& p, int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
    fs::create_directories(p.parent_path());
    Image8 img(w, h, 4);
    for (int i = 0; i < w * h; ++i) {
        img.pixels[std::size_t(i) * 4 + 0] = r;
        img.pixels[std::size_t(i) * 4 + 1] = g;
        img.pixels[std::size_t(i) * 4 + 2] = b;
        img.pixels[std::size_t(i) * 4 + 3] = a;
    }
    write_png(p, img);
}

// Signed area of triangle (a, b, c) seen along n.
double signed_area(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& n) {
    return 0.5 * double(glm::dot(glm::cross(b - a, c - a), n));
}

}  // namespace

TEST(ObjLoader, TriangleAndQuad) {
    Scene s = load_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 2 3 4\n");
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].primitives.size(), 1u);
    EXPECT_EQ(triangles(s), 3u);
    const Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.topology, Topology::Triangles);
    ASSERT_FALSE(p.normals.empty());
    for (const auto& n : p.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);  // flat, counter-clockwise seen from +z
    EXPECT_TRUE(p.generated_normals);
    EXPECT_TRUE(p.uv0.empty());
    EXPECT_EQ(s.nodes.size(), 1u);
    ASSERT_EQ(s.scenes.size(), 1u);
    EXPECT_EQ(s.scenes[0].size(), 1u);
    EXPECT_EQ(s.meshes[0].name, "test");  // faces before any o/g: named after the file
    EXPECT_EQ(p.bounds_min, glm::vec3(0, 0, 0));
    EXPECT_EQ(p.bounds_max, glm::vec3(1, 1, 0));
    // The default material (no usemtl): MTL's defaults through the documented conversion.
    ASSERT_GE(p.material, 0);
    const Material& m = s.materials[std::size_t(p.material)];
    EXPECT_NEAR(m.base_color_factor.x, 0.8f, 1e-6f);
    EXPECT_EQ(m.metallic_factor, 0.0f);
    EXPECT_TRUE(m.double_sided);
    ASSERT_TRUE(m.phong);
}

TEST(ObjLoader, AttributesAndIndexForms) {
    Scene s = load_text(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
        "f 1/1/1 2/2/1 3/3/1\n");
    const Primitive& p = s.meshes[0].primitives[0];
    ASSERT_EQ(p.uv0.size(), 3u);
    // vt v is flipped into glTF's UV space.
    std::set<std::pair<float, float>> uvs;
    for (auto uv : p.uv0) uvs.insert({uv.x, uv.y});
    EXPECT_TRUE(uvs.count({0.0f, 1.0f}) && uvs.count({1.0f, 1.0f}) && uvs.count({0.0f, 0.0f}));
    EXPECT_FALSE(p.generated_normals);
    for (auto n : p.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
    // v//vn and v/vt.
    Scene s2 = load_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1/1 2/1 3/1\n");
    EXPECT_EQ(triangles(s2), 2u);
}

TEST(ObjLoader, NegativeIndicesCountBack) {
    Scene a = load_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf -3 -2 -1\n");
    Scene b = load_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf 4 5 6\n");
    const Primitive &pa = a.meshes[0].primitives[0], &pb = b.meshes[0].primitives[0];
    ASSERT_EQ(pa.positions.size(), pb.positions.size());
    for (std::size_t i = 0; i < pa.positions.size(); ++i) EXPECT_EQ(pa.positions[i], pb.positions[i]);
    EXPECT_EQ(index_list(pa), index_list(pb));
    EXPECT_EQ(pa.bounds_max, glm::vec3(6, 6, 5));
    // Relative texture coordinates and normals too.
    Scene c = load_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvn 0 0 -1\nvn 0 0 1\nf -3/-2/-1 -2/-1/-1 -1/-1/-1\n");
    for (auto n : c.meshes[0].primitives[0].normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

// A dart whose fan from the first vertex covers area outside the polygon. Ear clipping must give n - 2 triangles, all facing the polygon's normal,
// whose areas add up to the polygon's. The polygon lies in a tilted plane, so projecting
// onto an axis plane would not be enough.
TEST(ObjLoader, ConcavePolygonIsEarClippedInItsPlane) {
    // 2D outline (counter-clockwise), then placed in the plane spanned by u and w.
    // A dart, counter-clockwise from its right wing: the fan from vertex 0 would cover the notch.
    const std::vector<glm::vec2> outline = {{1, -1}, {0, 2}, {-1, -1}, {0, 0.5f}};
    // Area by the shoelace formula.
    double area = 0;
    for (std::size_t i = 0; i < outline.size(); ++i) {
        const auto& a = outline[i];
        const auto& b = outline[(i + 1) % outline.size()];
        area += 0.5 * (double(a.x) * b.y - double(b.x) * a.y);
    }
    ASSERT_GT(area, 0);
    const glm::vec3 u = glm::normalize(glm::vec3(1, 1, 0)), w = glm::normalize(glm::vec3(-1, 1, 2));
    const glm::vec3 n = glm::normalize(glm::cross(u, w));
    std::string text;
    for (const auto& q : outline) {
        glm::vec3 p = q.x * u + q.y * w + glm::vec3(3, -2, 1);
        text += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    }
    text += "f 1 2 3 4\n";
    Scene s = load_text(text);
    const Primitive& p = s.meshes[0].primitives[0];
    auto idx = index_list(p);
    ASSERT_EQ(idx.size(), 6u);
    double sum = 0;
    for (std::size_t t = 0; t < idx.size(); t += 3) {
        double a = signed_area(p.positions[idx[t]], p.positions[idx[t + 1]], p.positions[idx[t + 2]], n);
        EXPECT_GT(a, 0) << "triangle " << t / 3 << " is flipped or degenerate";
        sum += a;
    }
    EXPECT_NEAR(sum, area, 1e-4);
    for (auto nn : p.normals) EXPECT_GT(glm::dot(nn, n), 0.999f);
}

// The shared concave case's shape, generalised: a comb with many teeth.
TEST(ObjLoader, CombPolygonAreaIsPreserved) {
    std::vector<glm::vec2> outline;
    const int teeth = 12;
    outline.push_back({float(teeth), 0});
    outline.push_back({float(teeth), 3});
    for (int t = teeth - 1; t >= 0; --t) {
        outline.push_back({t + 0.75f, 3});
        outline.push_back({t + 0.75f, 1});
        outline.push_back({t + 0.25f, 1});
        outline.push_back({t + 0.25f, 3});
    }
    outline.push_back({0, 3});
    outline.push_back({0, 0});
    double area = 0;
    for (std::size_t i = 0; i < outline.size(); ++i) {
        const auto& a = outline[i];
        const auto& b = outline[(i + 1) % outline.size()];
        area += 0.5 * (double(a.x) * b.y - double(b.x) * a.y);
    }
    std::string text, face = "f";
    for (std::size_t i = 0; i < outline.size(); ++i) {
        text += "v " + std::to_string(outline[i].x) + " 0 " + std::to_string(-outline[i].y) + "\n";  // in the xz plane
        face += " " + std::to_string(i + 1);
    }
    Scene s = load_text(text + face + "\n");
    const Primitive& p = s.meshes[0].primitives[0];
    auto idx = index_list(p);
    ASSERT_EQ(idx.size(), (outline.size() - 2) * 3);
    double sum = 0;
    for (std::size_t t = 0; t < idx.size(); t += 3) {
        double a = signed_area(p.positions[idx[t]], p.positions[idx[t + 1]], p.positions[idx[t + 2]], glm::vec3(0, 1, 0));
        EXPECT_GE(a, -1e-9);
        sum += a;
    }
    EXPECT_NEAR(sum, area, 1e-3);
}

TEST(ObjLoader, SmoothingGroupsDecideNormals) {
    // Two unit quads meeting at a right angle along the edge x = 1 (vertices 2 and 3).
    const std::string geometry = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 -1\nv 1 1 -1\n";
    auto normals_at_edge = [](const Scene& s) {
        std::vector<glm::vec3> out;
        const Primitive& p = s.meshes[0].primitives[0];
        for (std::size_t i = 0; i < p.positions.size(); ++i)
            if (p.positions[i].x == 1.0f && p.positions[i].z == 0.0f) out.push_back(p.normals[i]);
        return out;
    };
    // Same group: one shared vertex per edge position, with the average of the two faces.
    Scene smooth = load_text(geometry + "s 1\nf 1 2 3 4\nf 2 5 6 3\n");
    auto sn = normals_at_edge(smooth);
    ASSERT_EQ(sn.size(), 2u);
    glm::vec3 expected = glm::normalize(glm::vec3(1, 0, 1));
    for (auto n : sn) EXPECT_GT(glm::dot(n, expected), 0.9999f);
    EXPECT_EQ(smooth.meshes[0].primitives[0].positions.size(), 6u);
    // Smoothing off (the default): each face keeps its own normal, edge vertices split.
    Scene flat = load_text(geometry + "f 1 2 3 4\nf 2 5 6 3\n");
    auto fn = normals_at_edge(flat);
    ASSERT_EQ(fn.size(), 4u);
    int plus_z = 0, plus_x = 0;
    for (auto n : fn) plus_z += n.z > 0.999f, plus_x += n.x > 0.999f;
    EXPECT_EQ(plus_z, 2);
    EXPECT_EQ(plus_x, 2);
    // Different groups: split as well; "s off" after "s 1" turns it off.
    EXPECT_EQ(normals_at_edge(load_text(geometry + "s 1\nf 1 2 3 4\ns 2\nf 2 5 6 3\n")).size(), 4u);
    EXPECT_EQ(normals_at_edge(load_text(geometry + "s 1\nf 1 2 3 4\ns off\nf 2 5 6 3\n")).size(), 4u);
    // The option that smooths files without s statements.
    Diagnostics d;
    ObjLoadOptions o;
    o.smooth_without_groups = true;
    EXPECT_EQ(normals_at_edge(load_text(geometry + "f 1 2 3 4\nf 2 5 6 3\n", d, o)).size(), 2u);
    // Given normals are never replaced by the group's.
    Scene given = load_text(geometry + "vn 0 1 0\ns 1\nf 1//1 2//1 3//1 4//1\nf 2 5 6 3\n");
    const Primitive& p = given.meshes[0].primitives[0];
    int up = 0;
    for (auto n : p.normals) up += n.y > 0.999f;
    EXPECT_EQ(up, 4);
}

TEST(ObjLoader, ObjectsGroupsAndMaterials) {
    TempDir dir;
    dir.write("m.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
    fs::path obj = dir.write("m.obj",
                             "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "o first\nusemtl red\nf 1 2 3\nusemtl blue\nf 1 3 2\nusemtl red\nf 3 2 1\n"
                             "o second\ng part\nusemtl nosuch\nf 1 2 3\nl 1 2 3\np 1 2\n");
    Diagnostics diag;
    Scene s = load_obj(obj, diag);
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].name, "first");
    EXPECT_EQ(s.meshes[1].name, "second/part");
    ASSERT_EQ(s.meshes[0].primitives.size(), 2u);  // one per material
    EXPECT_EQ(s.meshes[0].primitives[0].triangle_count() + s.meshes[0].primitives[1].triangle_count(), 3u);
    ASSERT_EQ(s.materials.size(), 3u);  // red, blue and the default for 'nosuch'
    EXPECT_EQ(s.materials[0].name, "red");
    EXPECT_EQ(s.materials[0].base_color_factor, glm::vec4(1, 0, 0, 1));
    EXPECT_TRUE(has_warning(diag, "nosuch"));
    // Lines and points of the second object: their own primitives.
    std::set<Topology> kinds;
    for (const auto& p : s.meshes[1].primitives) kinds.insert(p.topology);
    EXPECT_EQ(kinds, (std::set<Topology>{Topology::Triangles, Topology::Lines, Topology::Points}));
    for (const auto& p : s.meshes[1].primitives) {
        if (p.topology == Topology::Lines) {
            EXPECT_EQ(index_list(p).size(), 4u);  // two segments
        }
    }
    EXPECT_EQ(s.nodes.size(), 2u);
}

TEST(ObjLoader, ContinuationsCommentsColoursAndNumberForms) {
    Scene s = load_text(
        "# comment\nv 0 0 0 1 0 0\nv +1 0. 0e0 0 1 0  # trailing comment\nv \\\n 0 1 0 0 0 1\n"
        "f 1 2 \\\n 3\n");
    const Primitive& p = s.meshes[0].primitives[0];
    ASSERT_EQ(p.colors.size(), 3u);
    std::set<std::tuple<float, float, float>> cols;
    for (auto c : p.colors) cols.insert({c.x, c.y, c.z});
    EXPECT_TRUE(cols.count({1, 0, 0}) && cols.count({0, 1, 0}) && cols.count({0, 0, 1}));
    EXPECT_EQ(p.bounds_max, glm::vec3(1, 1, 0));
}

TEST(ObjLoader, ByteOrderMarkAndLineEndings) {
    Diagnostics diag;
    Scene s = load_text("\xEF\xBB\xBFv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3", diag);  // CRLF, no final newline
    EXPECT_EQ(triangles(s), 1u);
    EXPECT_EQ(diag.total(), 0u) << diag.lines()[0];
}

TEST(ObjLoader, ErrorsNameTheLine) {
    Error e = error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    EXPECT_EQ(e.file(), "test.obj");
    EXPECT_EQ(e.where(), "line 4");
    EXPECT_NE(e.reason().find("out of range"), std::string::npos) << e.reason();
    EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").where(), "line 4");
    EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nf -3 1 2\n").where(), "line 3");
    EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv nan 1 0\n").where(), "line 3");
    EXPECT_EQ(error_of("v 0 0 0\nv 1e39 0 0\n").where(), "line 2");
    EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/7 2 3\n").where(), "line 4");
    EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2 3\n").where(), "line 4");
    EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n").where(), "line 4");
    EXPECT_EQ(error_of("v 0 0 0\nv x 0 0\n").where(), "line 2");
    EXPECT_EQ(error_of("v 0 0\n").where(), "line 1");
    EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n").where(), "line 4");
    // A line continued over several physical lines is reported at its first.
    EXPECT_EQ(error_of("v 0 0 0\nf 1 \\\n 2 \\\n 3\n").where(), "line 2");
}

TEST(ObjLoader, RepairsWhatCanBeRepaired) {
    Diagnostics diag;
    Scene s = load_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn nan 0 1\nvn 0 0 0\nvt inf 0\nf 1/1/1 2/1/2 3/1/1\nf 1 2\nfoo bar\nvp 1 2\n",
                        diag);
    const Primitive& p = s.meshes[0].primitives[0];
    for (auto n : p.normals) EXPECT_NEAR(n.z, 1.0f, 1e-5f);  // replaced by the face's
    for (auto uv : p.uv0) EXPECT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y));
    EXPECT_TRUE(has_warning(diag, "invalid normals"));
    EXPECT_TRUE(has_warning(diag, "fewer than 3"));
    EXPECT_TRUE(has_warning(diag, "unknown statement 'foo'"));
    EXPECT_TRUE(has_warning(diag, "'vp'"));
    for (const auto& w : diag.warnings()) EXPECT_EQ(w.where.rfind("line ", 0), 0u) << w.text();
}

// A repeating kind of warning is one line, at its first line, with a count; a file gives at most
// 64 warnings of its own, the rest counted in one (LineWarnings, obj_text.h): OBJ and MTL alike.
TEST(ObjLoader, RepeatedWarningsCollapseAndAreCapped) {
    Diagnostics diag;
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    for (int i = 0; i < 5; ++i) obj += "vp 1 2\n";  // lines 5-9: one kind
    for (int i = 0; i < 70; ++i) obj += "mtllib\n";  // lines 10-79: a warning each
    load_text(obj, diag);
    std::size_t own = 0, vp = 0, more = 0;
    for (const auto& w : diag.warnings()) {
        if (w.message.find("mtllib without a file name") != std::string::npos) ++own;
        if (w.message.find("'vp'") != std::string::npos) {
            ++vp;
            EXPECT_EQ(w.where, "line 5");
            EXPECT_NE(w.message.find("(5 times)"), std::string::npos) << w.message;
        }
        if (w.message.find("more warnings of this file not shown (6 times)") != std::string::npos) {
            ++more;
            EXPECT_EQ(w.where, "line 74");  // the 65th mtllib line
        }
    }
    EXPECT_EQ(own, 64u);
    EXPECT_EQ(vp, 1u);
    EXPECT_EQ(more, 1u);

    Diagnostics mtl_diag;
    parse_mtl("newmtl a\nwhatever 1\nwhatever 2\nwhatever 3\n", "w.mtl", mtl_diag);
    ASSERT_EQ(mtl_diag.warnings().size(), 1u);
    EXPECT_EQ(mtl_diag.warnings()[0].where, "line 2");
    EXPECT_NE(mtl_diag.warnings()[0].message.find("(3 lines)"), std::string::npos) << mtl_diag.warnings()[0].message;
}

TEST(ObjLoader, HostileSizesAreCapped) {
    ObjLoadOptions o;
    o.max_elements = 100;
    std::string many;
    for (int i = 0; i < 200; ++i) many += "v 0 0 0\n";
    EXPECT_NE(error_of(many, o).reason().find("more than 100"), std::string::npos);
    o = {};
    o.max_polygon_vertices = 8;
    EXPECT_NE(error_of("v 0 0 0\nf 1 1 1 1 1 1 1 1 1 1\n", o).reason().find("limit"), std::string::npos);
    Diagnostics diag;
    EXPECT_THROW(load_text(std::string(100, 'x'), diag, [] { ObjLoadOptions l; l.max_file_bytes = 10; return l; }()),
                 Error);
    // A big polygon over the triangulation budget is fanned, with a warning, not hung on.
    o = {};
    o.triangulation_budget = 10;
    std::string text, face = "f";
    for (int i = 0; i < 200; ++i) {
        double a = 2 * M_PI * i / 200.0, r = (i % 2) ? 1.0 : 0.5;  // a star: concave everywhere
        text += "v " + std::to_string(r * std::cos(a)) + " " + std::to_string(r * std::sin(a)) + " 0\n";
        face += " " + std::to_string(i + 1);
    }
    Diagnostics d2;
    Scene s = load_text(text + face + "\n", d2, o);
    EXPECT_EQ(triangles(s), 198u);
    EXPECT_TRUE(has_warning(d2, "fans"));
    // With the default budget the star is clipped properly: all triangles face +z.
    Scene star = load_text(text + face + "\n");
    const Primitive& p = star.meshes[0].primitives[0];
    auto idx = index_list(p);
    ASSERT_EQ(idx.size(), 198u * 3);
    double sum = 0;
    for (std::size_t t = 0; t < idx.size(); t += 3) {
        double a = signed_area(p.positions[idx[t]], p.positions[idx[t + 1]], p.positions[idx[t + 2]], glm::vec3(0, 0, 1));
        EXPECT_GT(a, -1e-9);
        sum += a;
    }
    double area = 0;  // 200 triangles (centre, i, i+1) of the star
    for (int i = 0; i < 200; ++i) {
        double a0 = 2 * M_PI * i / 200.0, a1 = 2 * M_PI * (i + 1) / 200.0;
        double r0 = (i % 2) ? 1.0 : 0.5, r1 = ((i + 1) % 2) ? 1.0 : 0.5;
        area += 0.5 * r0 * r1 * std::sin(a1 - a0);
    }
    EXPECT_NEAR(sum, area, 1e-3);
    // Self-touching polygons (a vertex list repeated, as in the shared box_longline.obj) end.
    Scene repeated = load_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4 1 2 3 4 1 2 3 4\n");
    EXPECT_EQ(triangles(repeated), 10u);
}

TEST(ObjLoader, MtlKeysAndTextureOptions) {
    Diagnostics diag;
    auto mats = parse_mtl(
        "newmtl a\nKa 0.1 0.2 0.3\nKd 0.5\nKs 0.25 0.5 0.75\nKe 1 2 3\nNs 96\nNi 1.45\nTr 0.25\nillum 1\n"
        "map_Kd -o 0.5 0.25 -s 2 4 1 -clamp on tex/diffuse map.png\n"
        "map_bump -bm 0.3 bump.png\nnorm -bm 2 normal.png\nmap_d -imfchan m alpha.png\nmap_Ns -imfchan l shiny.png\n"
        "map_Ks spec.png\nmap_Ke emit.png\n"
        "newmtl b\nd 0.5\nTr 0.9\nPr 0.3\nPm 0.8\nPs 0.2\nPc 0.5\nPcr 0.1\naniso 0.4\nanisor 0.25\n"
        "map_Pr -imfchan g rough.png\nmap_Pm metal.png\nmap_Ps sheen.png\n"
        "newmtl c\nKd spectral file.rfl\nsharpness 60\nwhatever 1\n",
        "t.mtl", diag);
    ASSERT_EQ(mats.size(), 3u);
    const PhongExt& a = mats[0].phong;
    EXPECT_EQ(a.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(a.diffuse, glm::vec3(0.5f));
    EXPECT_EQ(a.specular, glm::vec3(0.25f, 0.5f, 0.75f));
    EXPECT_EQ(a.emission, glm::vec3(1, 2, 3));
    EXPECT_EQ(a.shininess, 96.0f);
    EXPECT_FLOAT_EQ(a.optical_density, 1.45f);
    EXPECT_FLOAT_EQ(a.dissolve, 0.75f);  // 1 - Tr
    EXPECT_EQ(a.illum, 1);
    EXPECT_EQ(mats[0].diffuse.path, "tex/diffuse map.png");  // names with blanks
    EXPECT_TRUE(mats[0].diffuse.clamp);
    ASSERT_TRUE(mats[0].diffuse.has_transform);
    // -o 0.5 0.25 -s 2 4: u' = 2u + 0.5, v' = 4v + 0.25; in glTF's flipped v: t' = 4t + (1 - 4 - 0.25).
    EXPECT_EQ(mats[0].diffuse.transform.scale, glm::vec2(2, 4));
    EXPECT_FLOAT_EQ(mats[0].diffuse.transform.offset.x, 0.5f);
    EXPECT_FLOAT_EQ(mats[0].diffuse.transform.offset.y, -3.25f);
    EXPECT_FLOAT_EQ(a.bump_map.bump_multiplier, 0.3f);
    EXPECT_FLOAT_EQ(a.normal_map.bump_multiplier, 2.0f);
    EXPECT_EQ(mats[0].bump.path, "bump.png");
    EXPECT_EQ(mats[0].normal.path, "normal.png");
    EXPECT_EQ(a.dissolve_map.channel, MtlChannel::Matte);
    EXPECT_EQ(a.shininess_map.channel, MtlChannel::Luminance);
    EXPECT_EQ(mats[0].specular.path, "spec.png");
    EXPECT_EQ(mats[0].emission.path, "emit.png");
    EXPECT_FALSE(a.has_pbr());
    const PhongExt& b = mats[1].phong;
    EXPECT_FLOAT_EQ(b.dissolve, 0.5f);  // d wins over Tr
    ASSERT_TRUE(b.roughness && b.metallic && b.sheen && b.clearcoat && b.clearcoat_roughness && b.anisotropy &&
                b.anisotropy_rotation);
    EXPECT_FLOAT_EQ(*b.roughness, 0.3f);
    EXPECT_FLOAT_EQ(*b.metallic, 0.8f);
    EXPECT_FLOAT_EQ(*b.sheen, 0.2f);
    EXPECT_FLOAT_EQ(*b.clearcoat, 0.5f);
    EXPECT_FLOAT_EQ(*b.clearcoat_roughness, 0.1f);
    EXPECT_FLOAT_EQ(*b.anisotropy, 0.4f);
    EXPECT_FLOAT_EQ(*b.anisotropy_rotation, 0.25f);
    EXPECT_EQ(mats[1].roughness.path, "rough.png");
    EXPECT_EQ(b.roughness_map.channel, MtlChannel::G);
    EXPECT_EQ(mats[1].metallic.path, "metal.png");
    EXPECT_EQ(mats[1].sheen.path, "sheen.png");
    EXPECT_TRUE(b.has_pbr());
    EXPECT_EQ(mats[2].phong.diffuse, glm::vec3(0.8f));  // spectral: unsupported, default kept
    EXPECT_TRUE(has_warning(diag, "spectral"));
    EXPECT_TRUE(has_warning(diag, "whatever"));
    for (const auto& w : diag.warnings()) {
        EXPECT_EQ(w.file, "t.mtl");
        EXPECT_EQ(w.where.rfind("line ", 0), 0u);
    }
}

TEST(ObjLoader, PhongConversionIsTheDocumentedOne) {
    EXPECT_FLOAT_EQ(phong_shininess_to_roughness(0), 1.0f);
    EXPECT_NEAR(phong_shininess_to_roughness(98), std::pow(0.02f, 0.25f), 1e-6f);
    for (float ns : {1.0f, 10.0f, 100.0f, 1000.0f})
        EXPECT_NEAR(roughness_to_phong_shininess(phong_shininess_to_roughness(ns)), ns, ns * 1e-4f);
    EXPECT_TRUE(std::isfinite(roughness_to_phong_shininess(0)));
    PhongExt p;
    p.diffuse = {0.5f, 0.25f, 0.125f};
    p.specular = glm::vec3(0.04f);
    p.shininess = 30;
    p.dissolve = 0.5f;
    Material m = phong_to_metallic_roughness(p, "x");
    EXPECT_EQ(m.base_color_factor, glm::vec4(0.5f, 0.25f, 0.125f, 0.5f));
    EXPECT_EQ(m.alpha_mode, AlphaMode::Blend);
    EXPECT_EQ(m.metallic_factor, 0.0f);
    EXPECT_NEAR(m.roughness_factor, std::pow(2.0f / 32.0f, 0.25f), 1e-6f);
    ASSERT_TRUE(m.specular);
    EXPECT_NEAR(m.specular->specular_color_factor.x * ior_to_f0(m.ior_value()), 0.04f, 1e-6f);  // F0 = Ks
    EXPECT_EQ(m.specular->specular_factor, 1.0f);
    ASSERT_TRUE(m.phong);
    EXPECT_EQ(m.phong->shininess, 30.0f);
    p.specular = glm::vec3(0.0f);
    EXPECT_EQ(phong_to_metallic_roughness(p).specular->specular_factor, 0.0f);
    p.illum = 0;
    EXPECT_TRUE(phong_to_metallic_roughness(p).unlit);
    PhongExt q;
    q.metallic = 1.0f;
    q.roughness = 0.2f;
    q.clearcoat = 0.5f;
    Material pm = phong_to_metallic_roughness(q);
    EXPECT_EQ(pm.metallic_factor, 1.0f);
    EXPECT_FLOAT_EQ(pm.roughness_factor, 0.2f);
    EXPECT_FALSE(pm.specular);
    ASSERT_TRUE(pm.clearcoat);
    EXPECT_FLOAT_EQ(pm.clearcoat->clearcoat_factor, 0.5f);
}

TEST(ObjLoader, TexturesResolveAgainstTheMtlFolderAndArePacked) {
    TempDir dir;
    write_png_rgba(dir.path() / "sub" / "kd.png", 4, 4, 200, 100, 50, 255);
    write_png_rgba(dir.path() / "sub" / "alpha.png", 2, 2, 128, 128, 128, 255);
    write_png_rgba(dir.path() / "sub" / "NORMAL.png", 2, 2, 128, 128, 255, 255);
    write_png_rgba(dir.path() / "top.png", 2, 2, 0, 64, 255, 255);
    dir.write("sub/m.mtl",
              "newmtl m\nKd 1 1 1\nmap_Kd kd.png\nmap_d alpha.png\nnorm normal.png\nmap_Pr -imfchan g ../top.png\n"
              "map_Pm -imfchan b ../top.png\nmap_Ks missing.png\n");
    fs::path obj = dir.write("m.obj",
                             "mtllib sub/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\n"
                             "f 1/1 2/2 3/3\n");
    Diagnostics diag;
    Scene s = load_obj(obj, diag);
    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    // Base colour + map_d packed: RGB from map_Kd, A from map_d's R at map_Kd's size.
    ASSERT_TRUE(m.base_color.valid());
    const SceneImage& base = s.images[std::size_t(s.textures[std::size_t(m.base_color.texture)].image)];
    ASSERT_TRUE(base.valid());
    EXPECT_EQ(base.pixels.width, 4);
    EXPECT_EQ(base.pixels.at(1, 1)[0], 200);
    EXPECT_EQ(base.pixels.at(1, 1)[3], 128);
    EXPECT_EQ(m.alpha_mode, AlphaMode::Blend);
    // map_Pr (G of top.png) and map_Pm (B) packed into metallic-roughness.
    ASSERT_TRUE(m.metallic_roughness.valid());
    const SceneImage& mr = s.images[std::size_t(s.textures[std::size_t(m.metallic_roughness.texture)].image)];
    EXPECT_EQ(mr.pixels.at(0, 0)[1], 64);
    EXPECT_EQ(mr.pixels.at(0, 0)[2], 255);
    EXPECT_EQ(m.roughness_factor, 1.0f);
    EXPECT_EQ(m.metallic_factor, 1.0f);
    // The normal map found despite its name's case (files written on Windows); tangents made.
    EXPECT_TRUE(m.normal.valid());
    EXPECT_FALSE(s.meshes[0].primitives[0].tangents.empty());
    EXPECT_TRUE(has_warning(diag, "missing.png"));
    // The Phong block keeps every map's own texture.
    ASSERT_TRUE(m.phong);
    EXPECT_TRUE(m.phong->diffuse_map.valid() && m.phong->dissolve_map.valid() && m.phong->roughness_map.valid());
    EXPECT_FALSE(m.phong->specular_map.valid());
}

TEST(ObjLoader, AnisotropyGetsTangentsAsInGltf) {
    // MTL aniso is KHR_materials_anisotropy, whose direction lies in the tangent frame: the
    // faces get tangents from their UVs without a normal map (mesh_ops' tangent_source, the
    // glTF loader's rule), and none without aniso.
    TempDir dir;
    dir.write("m.mtl", "newmtl a\nKd 1 1 1\nPr 0.4\naniso 0.6\nnewmtl plain\nKd 1 1 1\n");
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n";
    fs::path obj = dir.write("m.obj", "mtllib m.mtl\n" + tri + "usemtl a\nf 1/1/1 2/2/1 3/3/1\nusemtl plain\nf 1/1/1 3/3/1 2/2/1\n");
    Diagnostics diag;
    Scene s = load_obj(obj, diag);
    ASSERT_EQ(s.materials.size(), 2u);
    ASSERT_TRUE(s.materials[0].has_anisotropy());
    int with = 0, without = 0;
    for (const Mesh& mesh : s.meshes)
        for (const Primitive& p : mesh.primitives) {
            if (p.material == 0) {
                ASSERT_EQ(p.tangents.size(), p.positions.size());
                // u runs along +x: the tangent is +x, right-handed.
                for (const glm::vec4& t : p.tangents) {
                    EXPECT_NEAR(t.x, 1.0f, 1e-5f);
                    EXPECT_NEAR(t.w, 1.0f, 1e-5f);
                }
                ++with;
            } else {
                EXPECT_TRUE(p.tangents.empty());
                ++without;
            }
        }
    EXPECT_EQ(with, 1);
    EXPECT_EQ(without, 1);
    // Without texture coordinates: no tangents, said once.
    Diagnostics diag2;
    fs::path bare = dir.write("bare.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    Scene b = load_obj(bare, diag2);
    EXPECT_TRUE(b.meshes.at(0).primitives.at(0).tangents.empty());
    EXPECT_TRUE(has_warning(diag2, "anisotropy"));
}

TEST(ObjLoader, PathsOutsideTheFolderAreRefused) {
    TempDir dir;
    dir.write("outside.mtl", "newmtl m\nKd 1 0 0\n");
    write_png_rgba(dir.path() / "outside.png", 1, 1, 255, 0, 0, 255);
    dir.write("model/inner.mtl", "newmtl m\nmap_Kd ../outside.png\n");
    dir.write("model/abs.mtl", "newmtl m\nmap_Kd " + (dir.path() / "outside.png").string() + "\n");
    const std::string geo = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";
    auto error = [&](const fs::path& obj, bool allow) -> std::string {
        Diagnostics diag;
        ObjLoadOptions o;
        o.allow_external_files = allow;
        try {
            load_obj(obj, diag, o);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    fs::path a = dir.write("model/a.obj", "mtllib ../outside.mtl\n" + geo);
    EXPECT_NE(error(a, false).find("outside the model's folder"), std::string::npos) << error(a, false);
    EXPECT_NE(error(a, false).find("line 1"), std::string::npos);
    EXPECT_EQ(error(a, true), "");
    fs::path b = dir.write("model/b.obj", "mtllib " + (dir.path() / "outside.mtl").string() + "\n" + geo);
    EXPECT_NE(error(b, false).find("absolute"), std::string::npos) << error(b, false);
    fs::path c = dir.write("model/c.obj", "mtllib inner.mtl\n" + geo);
    std::string ec = error(c, false);
    EXPECT_NE(ec.find("outside the model's folder"), std::string::npos) << ec;
    EXPECT_NE(ec.find("inner.mtl"), std::string::npos) << ec;  // the MTL file and its line
    EXPECT_NE(ec.find("line 2"), std::string::npos) << ec;
    EXPECT_EQ(error(c, true), "");
    fs::path d = dir.write("model/d.obj", "mtllib abs.mtl\n" + geo);
    EXPECT_NE(error(d, false).find("absolute"), std::string::npos);
    fs::path e = dir.write("model/e.obj", "mtllib http://example.com/x.mtl\n" + geo);
    EXPECT_NE(error(e, true).find("scheme"), std::string::npos);  // never the network, even when allowed
}

TEST(ObjLoader, MissingMtlIsAWarning) {
    TempDir dir;
    fs::path obj = dir.write("m.obj", "mtllib none.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl x\nf 1 2 3\n");
    Diagnostics diag;
    Scene s = load_obj(obj, diag);
    EXPECT_EQ(triangles(s), 1u);
    EXPECT_TRUE(has_warning(diag, "none.mtl"));
}

TEST(ObjLoader, ExtensionTest) {
    EXPECT_TRUE(is_obj_path("a/b.obj"));
    EXPECT_TRUE(is_obj_path("B.OBJ"));
    EXPECT_FALSE(is_obj_path("b.gltf"));
    EXPECT_FALSE(is_obj_path("obj"));
}

// Every shared OBJ case loads or fails with a clear message (file, line, reason); the list
// is printed for the record.
TEST(ObjLoader, SharedCasesLoadOrFailClearly) {
    const fs::path root = fs::path(FRESNEL_SHARED_DIR) / "assets" / "obj";
    if (!fs::is_directory(root)) GTEST_SKIP() << "shared OBJ cases not found: " << root.string();
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(root))
        if (e.is_regular_file() && is_obj_path(e.path())) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty());
    std::size_t loaded = 0;
    for (const auto& f : files) {
        Diagnostics diag;
        std::string rel = f.lexically_relative(root).string();
        try {
            Scene s = load_obj(f, diag);
            ++loaded;
            std::size_t tris = triangles(s), prims = 0, verts = 0;
            for (const auto& m : s.meshes)
                for (const auto& p : m.primitives) {
                    ++prims;
                    verts += p.vertex_count();
                    for (const auto& q : p.positions) ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
                    for (const auto& n : p.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f) << rel;
                    for (std::uint32_t i : index_list(p)) ASSERT_LT(i, p.vertex_count()) << rel;
                }
            std::printf("[obj case] %-32s loaded: %zu meshes, %zu primitives, %zu vertices, %zu triangles, %zu materials, %zu images, %zu warnings\n",
                        rel.c_str(), s.meshes.size(), prims, verts, tris, s.materials.size(), s.images.size(), diag.warnings().size());
            for (const auto& l : diag.lines()) std::printf("[obj case]     warning: %s\n", l.c_str());
        } catch (const Error& e) {
            std::printf("[obj case] %-32s error: %s\n", rel.c_str(), e.what());
            EXPECT_FALSE(e.reason().empty()) << rel;
            EXPECT_FALSE(e.file().empty()) << rel;
        }
    }
    // The well-formed ones among them must load (the others are point clouds, lines, odd formats).
    for (const char* must : {"box.obj", "spider.obj", "concave_polygon.obj", "cube_usemtl.obj", "regr01.obj",
                             "box_mat_with_spaces.obj", "mtl_different_folder.obj", "cube_with_vertexcolors.obj"}) {
        Diagnostics diag;
        EXPECT_NO_THROW(load_obj(root / must, diag)) << must;
    }
    EXPECT_GE(loaded, files.size() - 2);
}
