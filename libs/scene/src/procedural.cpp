#include "fresnel/scene/procedural.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace fresnel {

Primitive make_uv_sphere(int segments, int rings) {
    Primitive p;
    const float pi = 3.14159265358979f;
    for (int i = 0; i <= rings; ++i) {
        float theta = pi * float(i) / float(rings);
        for (int j = 0; j <= segments; ++j) {
            float phi = 2.0f * pi * float(j) / float(segments);
            glm::vec3 n(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
            p.positions.push_back(n);
            p.normals.push_back(n);
            p.uv0.push_back({float(j) / float(segments), float(i) / float(rings)});
        }
    }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            std::uint32_t a = std::uint32_t(i * (segments + 1) + j), b = a + std::uint32_t(segments + 1);
            p.indices.insert(p.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    p.source_vertex_count = p.positions.size();
    p.bounds_min = glm::vec3(-1.0f);
    p.bounds_max = glm::vec3(1.0f);
    return p;
}

Scene make_demo_scene() {
    Scene s;
    s.source = "(built-in demo)";
    Mesh sphere_mesh;
    const int n = 7;
    std::vector<int> roots;
    for (int row = 0; row < n; ++row)
        for (int col = 0; col < n; ++col) {
            Material m;
            m.name = "metallic " + std::to_string(row) + "/6, roughness " + std::to_string(col) + "/6";
            m.base_color_factor = glm::vec4(0.95f, 0.64f, 0.54f, 1.0f);  // copper-like tint
            m.metallic_factor = float(row) / float(n - 1);
            m.roughness_factor = float(col) / float(n - 1);
            s.materials.push_back(m);
            Mesh mesh;
            mesh.name = "sphere";
            Primitive p = make_uv_sphere();
            p.material = int(s.materials.size()) - 1;
            mesh.primitives.push_back(std::move(p));
            s.meshes.push_back(std::move(mesh));
            Node node;
            node.name = m.name;
            node.mesh = int(s.meshes.size()) - 1;
            node.local = glm::translate(glm::mat4(1.0f), glm::vec3((col - 3) * 2.5f, (row - 3) * 2.5f, 0.0f));
            s.nodes.push_back(node);
            roots.push_back(int(s.nodes.size()) - 1);
        }
    s.scenes.push_back(roots);
    return s;
}

Scene make_single_primitive_scene(Primitive p, std::vector<Material> materials) {
    Scene s;
    s.materials = std::move(materials);
    Mesh mesh;
    mesh.primitives.push_back(std::move(p));
    s.meshes.push_back(std::move(mesh));
    Node node;
    node.mesh = 0;
    s.nodes.push_back(node);
    s.scenes.push_back({0});
    return s;
}

}  // namespace fresnel
