#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>

#include "draco_decoder.h"
#include "fresnel/scene/mesh_ops.h"
#include "gltf_codes.h"

namespace fresnel::gltf {
namespace {

template <class V>
std::vector<V> to_vectors(const AccessorData& d) {
    constexpr int n = V::length();
    std::vector<V> out(d.count);
    for (std::size_t i = 0; i < d.count; ++i)
        for (int c = 0; c < n; ++c) out[i][c] = c < d.components ? float(d.values[i * std::size_t(d.components) + std::size_t(c)]) : 1.0f;
    return out;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

std::optional<Primitive> build_primitive(const JsonReader& r, const json& prim, const std::string& ptr,
                                         const AccessorDecoder& accessors, const std::vector<Material>& materials,
                                         std::size_t max_vertices, bool mesh_quantization,
                                         const std::vector<float>& morph_weights, Diagnostics& diag) {
    auto warn = [&](const std::string& where, const std::string& what) { diag.warn(r.file(), where, what); };
    if (!prim.is_object()) r.fail(ptr, "must be an object");
    Primitive p;
    int mode = int(r.integer(prim, "mode", ptr, 4, 0, 6));
    p.material = r.index(prim, "material", ptr, materials.size(), "material");
    const json& attrs = r.object(prim, "attributes", ptr);
    std::string ap = ptr + "/attributes";
    // KHR_draco_mesh_compression: the accessors it names read the decoded mesh instead.
    std::map<int, AccessorData> decoded;
    if (const json* draco = r.find(r.object(prim, "extensions", ptr), "KHR_draco_mesh_compression"))
        decoded = decode_draco_primitive(r, prim, *draco, ptr + "/extensions/KHR_draco_mesh_compression", accessors,
                                         max_vertices);
    auto read = [&](int index) {
        auto it = decoded.find(index);
        return it != decoded.end() ? it->second : accessors.read(index);
    };
    int pos_index = r.index(attrs, "POSITION", ap, accessors.accessor_count(), "accessor");
    if (pos_index < 0) {
        warn(ap, "primitive has no POSITION; skipped");
        return std::nullopt;
    }
    {
        bool available = true;
        if (attrs.is_object())
            for (auto it = attrs.begin(); it != attrs.end(); ++it)
                if (it->is_number_unsigned()) available = available && accessors.has_data(it->get<int>());
        if (prim.contains("indices") && prim["indices"].is_number_unsigned())
            available = available && accessors.has_data(prim["indices"].get<int>());
        if (!available) {
            warn(ptr, "primitive data lives in a buffer without data; skipped");
            return std::nullopt;
        }
    }

    // Reads an attribute, checking its type and that its count matches POSITION.
    std::size_t vertex_count = 0;
    auto attribute = [&](const char* name, std::initializer_list<int> allowed_components,
                         bool float_or_normalized) -> std::optional<AccessorData> {
        int idx = r.index(attrs, name, ap, accessors.accessor_count(), "accessor");
        if (idx < 0) return std::nullopt;
        std::string where = ap + "/" + name;
        AccessorData d = read(idx);
        if (std::find(allowed_components.begin(), allowed_components.end(), d.components) == allowed_components.end())
            r.fail(where, std::string("accessor ") + std::to_string(idx) + " has the wrong type for " + name);
        // KHR_mesh_quantization also allows non-normalized 8/16-bit texture coordinates.
        bool quantized_ok = mesh_quantization && std::string_view(name).rfind("TEXCOORD", 0) == 0 &&
                            d.component_type != gltf_code::kUnsignedInt;
        if (float_or_normalized && d.component_type != gltf_code::kFloat && !d.normalized && !quantized_ok)
            r.fail(where, std::string(name) + " must be float or normalized integers");
        if (vertex_count && d.count != vertex_count)
            r.fail(where, "has " + std::to_string(d.count) + " elements, POSITION has " + std::to_string(vertex_count));
        return d;
    };
    {
        auto pos = attribute("POSITION", {3}, false);
        vertex_count = pos->count;
        p.source_vertex_count = vertex_count;
        if (vertex_count > max_vertices) r.fail(ap + "/POSITION", "too many vertices");
        p.positions = to_vectors<glm::vec3>(*pos);
        // The camera convention uses the POSITION accessor's min/max, which for a valid
        // file is the exact box of all its elements (referenced or not): take it from the
        // data before any re-indexing drops unreferenced vertices.
        p.bounds_min = p.bounds_max = p.positions[0];
        for (const auto& v : p.positions) {
            p.bounds_min = glm::min(p.bounds_min, v);
            p.bounds_max = glm::max(p.bounds_max, v);
        }
    }
    if (auto n = attribute("NORMAL", {3}, true)) p.normals = to_vectors<glm::vec3>(*n);
    if (auto t = attribute("TANGENT", {4}, true)) p.tangents = to_vectors<glm::vec4>(*t);
    if (auto t = attribute("TEXCOORD_0", {2}, true)) p.uv0 = to_vectors<glm::vec2>(*t);
    if (auto t = attribute("TEXCOORD_1", {2}, true)) p.uv1 = to_vectors<glm::vec2>(*t);
    if (auto c = attribute("COLOR_0", {3, 4}, true)) p.colors = to_vectors<glm::vec4>(*c);
    if (auto j = attribute("JOINTS_0", {4}, false)) {
        if (j->component_type != gltf_code::kUnsignedByte && j->component_type != gltf_code::kUnsignedShort)
            r.fail(ap + "/JOINTS_0", "must be UNSIGNED_BYTE or UNSIGNED_SHORT");
        p.joints.resize(j->count);
        for (std::size_t i = 0; i < j->count; ++i)
            for (int c = 0; c < 4; ++c) p.joints[i][c] = std::uint32_t(j->values[i * 4 + std::size_t(c)]);
    }
    if (auto w = attribute("WEIGHTS_0", {4}, true)) p.weights = to_vectors<glm::vec4>(*w);
    if (p.joints.empty() != p.weights.empty()) {
        warn(ap, "JOINTS_0 and WEIGHTS_0 must come together; skinning ignored");
        p.joints.clear();
        p.weights.clear();
    }

    // Morph targets at the mesh's default weights (the rest pose).
    const json& targets = r.array(prim, "targets", ptr);
    for (std::size_t k = 0; k < targets.size() && k < morph_weights.size(); ++k) {
        float wk = morph_weights[k];
        if (wk == 0.0f) continue;
        std::string tp = ptr + "/targets/" + std::to_string(k);
        auto apply = [&](const char* name, auto& data) {
            int idx = r.index(targets[k], name, tp, accessors.accessor_count(), "accessor");
            if (idx < 0 || data.empty()) return;
            AccessorData d = accessors.read(idx);
            if (d.count != vertex_count || d.components < 3) r.fail(tp + "/" + name, "does not match the primitive's vertices");
            for (std::size_t i = 0; i < d.count; ++i)
                for (int c = 0; c < 3; ++c) data[i][c] += wk * float(d.values[i * std::size_t(d.components) + std::size_t(c)]);
        };
        apply("POSITION", p.positions);
        apply("NORMAL", p.normals);
        apply("TANGENT", p.tangents);
    }
    // Every target's displacements, kept for animation. A target the rest pose leaves at
    // weight 0 was never read before: one that cannot be read drops the targets with a
    // warning, so such files still load in their rest pose.
    if (!targets.empty()) {
        try {
            for (std::size_t k = 0; k < targets.size(); ++k) {
                std::string tp = ptr + "/targets/" + std::to_string(k);
                if (!targets[k].is_object()) r.fail(tp, "must be an object");
                MorphTarget mt;
                auto keep = [&](const char* name, std::size_t base_size, std::vector<glm::vec3>& out) {
                    int idx = r.index(targets[k], name, tp, accessors.accessor_count(), "accessor");
                    if (idx < 0 || base_size == 0) return;
                    AccessorData d = accessors.read(idx);
                    if (d.count != vertex_count || d.components < 3)
                        r.fail(tp + "/" + name, "does not match the primitive's vertices");
                    out.resize(d.count);
                    for (std::size_t i = 0; i < d.count; ++i) {
                        for (int c = 0; c < 3; ++c) out[i][c] = float(d.values[i * std::size_t(d.components) + std::size_t(c)]);
                        if (!finite(out[i])) r.fail(tp + "/" + name, "non-finite displacement");
                    }
                };
                keep("POSITION", p.positions.size(), mt.positions);
                keep("NORMAL", p.normals.size(), mt.normals);
                keep("TANGENT", p.tangents.size(), mt.tangents);
                p.targets.push_back(std::move(mt));
            }
            p.applied_weights.assign(targets.size(), 0.0f);
            for (std::size_t k = 0; k < targets.size() && k < morph_weights.size(); ++k) p.applied_weights[k] = morph_weights[k];
        } catch (const Error& e) {
            warn(e.where(), e.reason() + "; morph targets cannot be animated");
            p.targets.clear();
            p.applied_weights.clear();
        }
    }

    if (!std::all_of(p.positions.begin(), p.positions.end(), finite)) {
        warn(ap + "/POSITION", "non-finite vertex positions; primitive skipped");
        return std::nullopt;
    }

    // Indices.
    std::vector<std::uint32_t> indices;
    bool indexed = false;
    int iidx = r.index(prim, "indices", ptr, accessors.accessor_count(), "accessor");
    if (iidx >= 0) {
        AccessorData d = read(iidx);
        if (d.components != 1 || (d.component_type != gltf_code::kUnsignedByte && d.component_type != gltf_code::kUnsignedShort && d.component_type != gltf_code::kUnsignedInt))
            r.fail(ptr + "/indices", "indices must be SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        indices.resize(d.count);
        for (std::size_t i = 0; i < d.count; ++i) {
            double v = d.values[i];
            if (v >= double(vertex_count))
                r.fail(ptr + "/indices", "index " + std::to_string((unsigned long long)v) + " at position " +
                                             std::to_string(i) + " is out of range for " + std::to_string(vertex_count) +
                                             " vertices");
            indices[i] = std::uint32_t(v);
        }
        indexed = true;
    } else {
        indices = index_list(p);
    }

    switch (mode) {
        case 0: p.topology = Topology::Points; break;
        case 1: p.topology = Topology::Lines; break;
        case 2: p.topology = Topology::LineLoop; break;
        case 3: p.topology = Topology::LineStrip; break;
        default: p.topology = Topology::Triangles; break;  // 4 list, 5 strip, 6 fan
    }
    if (mode == 5) indices = strip_to_triangles(indices);
    if (mode == 6) indices = fan_to_triangles(indices);
    if (p.topology == Topology::Triangles) {
        if (indices.size() % 3 != 0) {
            warn(indexed ? ptr + "/indices" : ap, "triangle count is not a whole number; extra indices ignored");
            indices.resize(indices.size() / 3 * 3);
        }
        if (indices.empty()) {
            warn(ptr, "primitive has no complete triangle; skipped");
            return std::nullopt;
        }
    }
    p.indices = std::move(indices);

    if (std::size_t bad = repair_normals(p))
        warn(ap + "/NORMAL", std::to_string(bad) + " invalid normals replaced by computed ones");
    if (p.normals.empty()) generate_flat_normals(p);  // only triangles get them

    // Tangents when a normal map or KHR_materials_anisotropy (its direction lies in the tangent
    // frame; the Khronos viewer derives one from the UVs) needs them and the file has none (MikkTSpace).
    const Material* mat = p.material >= 0 ? &materials[std::size_t(p.material)] : nullptr;
    if (const TextureSlot* map = mat ? tangent_source(*mat) : nullptr;
        map && p.tangents.empty() && p.topology == Topology::Triangles) {
        if (!generate_tangents(p, map->tex_coord))
            warn(ptr, mat->anisotropy && map == &mat->anisotropy->anisotropy_texture
                          ? "anisotropy without texture coordinates (no tangents); shaded isotropically"
                          : "normal map without texture coordinates; normal map ignored");
    }
    repair_tangents(p.tangents);
    drop_identity_indices(p);
    return p;
}

}  // namespace fresnel::gltf
