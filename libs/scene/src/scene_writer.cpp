// glTF and OBJ/MTL writers (scene_writer.h). JSON through nlohmann::json, as the loader.
// Long (~850 lines) because the glTF writer, its patcher of an original file and the OBJ/MTL
// writer share the mesh, texture and whole-or-absent file-set helpers here.
#include "fresnel/scene/scene_writer.h"

#include "fresnel/scene/mesh_ops.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <set>

#include <glm/gtc/type_ptr.hpp>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/float_text.h"
#include "fresnel/material/properties.h"
#include "fresnel/scene/paths.h"
#include "gltf_codes.h"

namespace fresnel {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Every writer here stages its files into one fresnel::FileSet (fresnel/core/atomic_file.h),
// committed after the last is written: a .gltf with its .bin and images, an OBJ with its MTL
// and textures, appear together or not at all, the file naming the others moved last.
void stage_bytes(FileSet& files, const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    files.stage(path, std::span<const std::uint8_t>(bytes));
}
void stage_png(FileSet& files, const fs::path& path, const Image8& image) {
    std::vector<std::uint8_t> bytes;
    try {
        bytes = encode_png(image);
    } catch (const Error& e) {
        throw Error(path.string(), "", e.reason());
    }
    stage_bytes(files, path, bytes);
}

json vec_json(const float* v, int n) {
    json a = json::array();
    for (int i = 0; i < n; ++i) a.push_back(v[i]);
    return a;
}

struct GltfBuilder {
    json doc;
    std::vector<std::uint8_t> bin;
    std::set<std::string> used;

    std::size_t append(const void* data, std::size_t size) {
        while (bin.size() % 4) bin.push_back(0);
        std::size_t offset = bin.size();
        bin.insert(bin.end(), static_cast<const std::uint8_t*>(data), static_cast<const std::uint8_t*>(data) + size);
        return offset;
    }
    int buffer_view(const void* data, std::size_t size, int target) {
        std::size_t offset = append(data, size);
        json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
        if (target) v["target"] = target;
        doc["bufferViews"].push_back(v);
        return int(doc["bufferViews"].size()) - 1;
    }
    template <class V>
    int accessor(const std::vector<V>& values, int components, const char* type, bool min_max, int target) {
        int view = buffer_view(values.data(), values.size() * sizeof(V), target);
        json a = {{"bufferView", view}, {"componentType", gltf_code::kFloat}, {"count", values.size()}, {"type", type}};
        if (min_max) {
            std::vector<float> lo(components, INFINITY), hi(components, -INFINITY);
            for (const V& v : values)
                for (int c = 0; c < components; ++c) {
                    lo[c] = std::min(lo[c], glm::value_ptr(v)[c]);
                    hi[c] = std::max(hi[c], glm::value_ptr(v)[c]);
                }
            a["min"] = lo;
            a["max"] = hi;
        }
        doc["accessors"].push_back(a);
        return int(doc["accessors"].size()) - 1;
    }
    int index_accessor(const std::vector<std::uint32_t>& indices) {
        int view = buffer_view(indices.data(), indices.size() * 4, gltf_code::kElementArrayBuffer);
        doc["accessors"].push_back({{"bufferView", view}, {"componentType", gltf_code::kUnsignedInt}, {"count", indices.size()}, {"type", "SCALAR"}});
        return int(doc["accessors"].size()) - 1;
    }
    json texture_info(const TextureSlot& s, int texture_count) {
        json t = {{"index", s.texture}};
        if (s.tex_coord != 0) t["texCoord"] = s.tex_coord;
        if (s.has_transform) {
            const TextureTransform& x = s.transform_params;
            json e = json::object();
            if (x.offset != glm::vec2(0.0f)) e["offset"] = {x.offset.x, x.offset.y};
            if (x.rotation != 0.0f) e["rotation"] = x.rotation;
            if (x.scale != glm::vec2(1.0f)) e["scale"] = {x.scale.x, x.scale.y};
            t["extensions"]["KHR_texture_transform"] = e;
            used.insert("KHR_texture_transform");
        }
        (void)texture_count;
        return t;
    }
};

bool slot_ok(const TextureSlot& s, const Scene& scene) {
    return s.valid() && std::size_t(s.texture) < scene.textures.size() && scene.textures[std::size_t(s.texture)].image >= 0 &&
           scene.images[std::size_t(scene.textures[std::size_t(s.texture)].image)].valid();
}

json material_json(const Material& m, const Scene& scene, GltfBuilder& b, bool has_tangents) {
    json j = json::object();
    if (!m.name.empty()) j["name"] = m.name;
    int nt = int(scene.textures.size());
    json pbr = json::object();
    if (m.base_color_factor != glm::vec4(1.0f)) pbr["baseColorFactor"] = vec_json(glm::value_ptr(m.base_color_factor), 4);
    if (slot_ok(m.base_color, scene)) pbr["baseColorTexture"] = b.texture_info(m.base_color, nt);
    if (m.metallic_factor != 1.0f) pbr["metallicFactor"] = m.metallic_factor;
    if (m.roughness_factor != 1.0f) pbr["roughnessFactor"] = m.roughness_factor;
    if (slot_ok(m.metallic_roughness, scene)) pbr["metallicRoughnessTexture"] = b.texture_info(m.metallic_roughness, nt);
    j["pbrMetallicRoughness"] = pbr;
    if (slot_ok(m.normal, scene)) {
        j["normalTexture"] = b.texture_info(m.normal, nt);
        if (m.normal_scale != 1.0f) j["normalTexture"]["scale"] = m.normal_scale;
    }
    if (slot_ok(m.occlusion, scene)) {
        j["occlusionTexture"] = b.texture_info(m.occlusion, nt);
        if (m.occlusion_strength != 1.0f) j["occlusionTexture"]["strength"] = m.occlusion_strength;
    }
    if (slot_ok(m.emissive, scene)) j["emissiveTexture"] = b.texture_info(m.emissive, nt);
    glm::vec3 emissive = m.emissive_factor;
    float strength = m.emissive_strength_value();
    float peak = std::max({emissive.x, emissive.y, emissive.z});
    if (peak > 1.0f) {  // emissiveFactor is limited to [0, 1]: the rest goes to the strength
        emissive /= peak;
        strength *= peak;
    }
    if (emissive != glm::vec3(0.0f)) j["emissiveFactor"] = vec_json(glm::value_ptr(emissive), 3);
    if (strength != 1.0f) {
        j["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", strength}};
        b.used.insert("KHR_materials_emissive_strength");
    }
    if (m.alpha_mode == AlphaMode::Mask) {
        j["alphaMode"] = "MASK";
        if (m.alpha_cutoff != 0.5f) j["alphaCutoff"] = m.alpha_cutoff;
    } else if (m.alpha_mode == AlphaMode::Blend) {
        j["alphaMode"] = "BLEND";
    }
    if (m.double_sided) j["doubleSided"] = true;
    if (m.ior && m.ior->ior != 1.5f) {
        j["extensions"]["KHR_materials_ior"] = {{"ior", m.ior->ior}};
        b.used.insert("KHR_materials_ior");
    }
    if (m.specular) {
        const SpecularExt& s = *m.specular;
        json e = json::object();
        if (s.specular_factor != 1.0f) e["specularFactor"] = s.specular_factor;
        if (slot_ok(s.specular_texture, scene)) e["specularTexture"] = b.texture_info(s.specular_texture, nt);
        if (s.specular_color_factor != glm::vec3(1.0f))
            e["specularColorFactor"] = vec_json(glm::value_ptr(s.specular_color_factor), 3);
        if (slot_ok(s.specular_color_texture, scene))
            e["specularColorTexture"] = b.texture_info(s.specular_color_texture, nt);
        j["extensions"]["KHR_materials_specular"] = e;
        b.used.insert("KHR_materials_specular");
    }
    if (m.has_clearcoat()) {
        const ClearcoatExt& c = *m.clearcoat;
        json e = {{"clearcoatFactor", c.clearcoat_factor}};
        if (c.clearcoat_roughness_factor != 0.0f) e["clearcoatRoughnessFactor"] = c.clearcoat_roughness_factor;
        if (slot_ok(c.clearcoat_texture, scene)) e["clearcoatTexture"] = b.texture_info(c.clearcoat_texture, nt);
        if (slot_ok(c.clearcoat_roughness_texture, scene))
            e["clearcoatRoughnessTexture"] = b.texture_info(c.clearcoat_roughness_texture, nt);
        // Without tangents (a coat normal map but no base normal map, so the loader made none),
        // the map would be invalid glTF: it is dropped (write_gltf warns).
        if (slot_ok(c.clearcoat_normal_texture, scene) && has_tangents) {
            e["clearcoatNormalTexture"] = b.texture_info(c.clearcoat_normal_texture, nt);
            if (c.clearcoat_normal_scale != 1.0f) e["clearcoatNormalTexture"]["scale"] = c.clearcoat_normal_scale;
        }
        j["extensions"]["KHR_materials_clearcoat"] = e;
        b.used.insert("KHR_materials_clearcoat");
    }
    if (m.unlit) {
        j["extensions"]["KHR_materials_unlit"] = json::object();
        b.used.insert("KHR_materials_unlit");
    }
    // The other material extensions the loader keeps, written back with every value that
    // differs from the specification's default (so glTF -> glTF loses none of them).
    auto ext = [&](const char* name, json e) {
        j["extensions"][name] = std::move(e);
        b.used.insert(name);
    };
    auto tex = [&](json& e, const char* key, const TextureSlot& t) {
        if (slot_ok(t, scene)) e[key] = b.texture_info(t, nt);
    };
    auto vec3 = [](const glm::vec3& v) { return json::array({v.x, v.y, v.z}); };
    if (m.sheen) {
        const SheenExt& x = *m.sheen;
        json e = json::object();
        if (x.sheen_color_factor != glm::vec3(0.0f)) e["sheenColorFactor"] = vec3(x.sheen_color_factor);
        tex(e, "sheenColorTexture", x.sheen_color_texture);
        if (x.sheen_roughness_factor != 0.0f) e["sheenRoughnessFactor"] = x.sheen_roughness_factor;
        tex(e, "sheenRoughnessTexture", x.sheen_roughness_texture);
        ext("KHR_materials_sheen", e);
    }
    if (m.transmission) {
        json e = json::object();
        if (m.transmission->transmission_factor != 0.0f) e["transmissionFactor"] = m.transmission->transmission_factor;
        tex(e, "transmissionTexture", m.transmission->transmission_texture);
        ext("KHR_materials_transmission", e);
    }
    if (m.volume) {
        const VolumeExt& x = *m.volume;
        json e = json::object();
        if (x.thickness_factor != 0.0f) e["thicknessFactor"] = x.thickness_factor;
        tex(e, "thicknessTexture", x.thickness_texture);
        if (std::isfinite(x.attenuation_distance)) e["attenuationDistance"] = x.attenuation_distance;
        if (x.attenuation_color != glm::vec3(1.0f)) e["attenuationColor"] = vec3(x.attenuation_color);
        ext("KHR_materials_volume", e);
    }
    if (m.dispersion) {
        json e = json::object();
        if (m.dispersion->dispersion != 0.0f) e["dispersion"] = m.dispersion->dispersion;
        ext("KHR_materials_dispersion", e);
    }
    if (m.iridescence) {
        const IridescenceExt& x = *m.iridescence;
        json e = json::object();
        if (x.iridescence_factor != 0.0f) e["iridescenceFactor"] = x.iridescence_factor;
        tex(e, "iridescenceTexture", x.iridescence_texture);
        if (x.iridescence_ior != 1.3f) e["iridescenceIor"] = x.iridescence_ior;
        if (x.iridescence_thickness_minimum != 100.0f) e["iridescenceThicknessMinimum"] = x.iridescence_thickness_minimum;
        if (x.iridescence_thickness_maximum != 400.0f) e["iridescenceThicknessMaximum"] = x.iridescence_thickness_maximum;
        tex(e, "iridescenceThicknessTexture", x.iridescence_thickness_texture);
        ext("KHR_materials_iridescence", e);
    }
    if (m.anisotropy) {
        const AnisotropyExt& x = *m.anisotropy;
        json e = json::object();
        if (x.anisotropy_strength != 0.0f) e["anisotropyStrength"] = x.anisotropy_strength;
        if (x.anisotropy_rotation != 0.0f) e["anisotropyRotation"] = x.anisotropy_rotation;
        tex(e, "anisotropyTexture", x.anisotropy_texture);
        ext("KHR_materials_anisotropy", e);
    }
    if (m.diffuse_transmission) {
        const DiffuseTransmissionExt& x = *m.diffuse_transmission;
        json e = json::object();
        if (x.diffuse_transmission_factor != 0.0f) e["diffuseTransmissionFactor"] = x.diffuse_transmission_factor;
        tex(e, "diffuseTransmissionTexture", x.diffuse_transmission_texture);
        if (x.diffuse_transmission_color_factor != glm::vec3(1.0f))
            e["diffuseTransmissionColorFactor"] = vec3(x.diffuse_transmission_color_factor);
        tex(e, "diffuseTransmissionColorTexture", x.diffuse_transmission_color_texture);
        ext("KHR_materials_diffuse_transmission", e);
    }
    if (m.diffuse_roughness) {
        const DiffuseRoughnessExt& x = *m.diffuse_roughness;
        json e = json::object();
        if (x.diffuse_roughness_factor != 0.0f) e["diffuseRoughnessFactor"] = x.diffuse_roughness_factor;
        tex(e, "diffuseRoughnessTexture", x.diffuse_roughness_texture);
        ext("KHR_materials_diffuse_roughness", e);
    }
    return j;
}

int filter_enum(Filter f) { return f == Filter::Nearest ? gltf_code::kNearest : gltf_code::kLinear; }
int min_filter_enum(const Sampler& s) {
    bool near = s.min_filter == Filter::Nearest;
    switch (s.mipmap) {
        case MipmapMode::None: return near ? gltf_code::kNearest : gltf_code::kLinear;
        case MipmapMode::Nearest: return near ? gltf_code::kNearestMipmapNearest : gltf_code::kLinearMipmapNearest;
        case MipmapMode::Linear: return near ? gltf_code::kNearestMipmapLinear : gltf_code::kLinearMipmapLinear;
    }
    return gltf_code::kLinearMipmapLinear;
}
int wrap_enum(Wrap w) { return w == Wrap::ClampToEdge ? gltf_code::kClampToEdge : w == Wrap::MirroredRepeat ? gltf_code::kMirroredRepeat : gltf_code::kRepeat; }

}  // namespace


std::vector<fs::path> write_gltf(const Scene& in, const fs::path& path, Diagnostics& diagnostics, const GltfWriteOptions& options) {
    // Primitives whose material needs a tangent space get MikkTSpace tangents, on a copy.
    std::optional<Scene> with_tangents;
    for (std::size_t mi = 0; mi < in.meshes.size(); ++mi)
        for (std::size_t pi = 0; pi < in.meshes[mi].primitives.size(); ++pi) {
            const Primitive& p = in.meshes[mi].primitives[pi];
            if (p.tangents.size() == p.positions.size() || p.material < 0 || std::size_t(p.material) >= in.materials.size())
                continue;
            // The loader's rule (tangent_source); an anisotropy block of strength 0 still makes
            // the validator ask for a tangent space (MESH_PRIMITIVE_NO_TANGENT_SPACE).
            const Material& m = in.materials[std::size_t(p.material)];
            const TextureSlot* src = tangent_source(m);
            if (!src && m.anisotropy) src = &m.anisotropy->anisotropy_texture;
            if (src) {
                if (!with_tangents) with_tangents = in;
                generate_tangents(with_tangents->meshes[mi].primitives[pi], src->valid() ? src->tex_coord : 0);
            }
        }
    const Scene& scene = with_tangents ? *with_tangents : in;
    const bool glb = path.extension() == ".glb" || path.extension() == ".GLB";
    const std::string stem = path.stem().string();
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    GltfBuilder b;
    json& doc = b.doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "fresnel convert"}};
    doc["buffers"] = json::array();
    doc["bufferViews"] = json::array();
    doc["accessors"] = json::array();

    // Images first (their PNG bytes go into the buffer for .glb, beside the file for .gltf).
    std::vector<int> image_index(scene.images.size(), -1);
    json images = json::array();
    std::vector<std::pair<fs::path, const Image8*>> image_files;
    for (std::size_t i = 0; i < scene.images.size(); ++i) {
        if (!scene.images[i].valid()) continue;
        json img;
        if (glb) {
            auto bytes = encode_png(scene.images[i].pixels);
            img = {{"bufferView", b.buffer_view(bytes.data(), bytes.size(), 0)}, {"mimeType", "image/png"}};
        } else {
            std::string name = stem + "_image" + std::to_string(i) + ".png";
            img = {{"uri", name}};
            image_files.emplace_back(folder / name, &scene.images[i].pixels);
        }
        image_index[i] = int(images.size());
        images.push_back(img);
    }
    json samplers = json::array(), textures = json::array();
    for (const Texture& t : scene.textures) {
        json s = {{"magFilter", filter_enum(t.sampler.mag_filter)}, {"minFilter", min_filter_enum(t.sampler)},
                  {"wrapS", wrap_enum(t.sampler.wrap_s)}, {"wrapT", wrap_enum(t.sampler.wrap_t)}};
        samplers.push_back(s);
        json tex = {{"sampler", int(samplers.size()) - 1}};
        if (t.image >= 0 && std::size_t(t.image) < image_index.size() && image_index[std::size_t(t.image)] >= 0)
            tex["source"] = image_index[std::size_t(t.image)];
        textures.push_back(tex);
    }
    json materials = json::array();
    std::vector<bool> tangents(scene.materials.size(), true);
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& p : mesh.primitives)
            if (p.material >= 0 && std::size_t(p.material) < tangents.size() && p.tangents.size() != p.positions.size())
                tangents[std::size_t(p.material)] = false;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        if (!tangents[i] && m.has_clearcoat() && slot_ok(m.clearcoat->clearcoat_normal_texture, scene) && !slot_ok(m.normal, scene))
            diagnostics.warn(path.string(), "/materials/" + std::to_string(i),
                             "clearcoatNormalTexture dropped: the mesh has no tangents");
        materials.push_back(material_json(m, scene, b, tangents[i]));
    }

    json meshes = json::array();
    for (const Mesh& mesh : scene.meshes) {
        json jm = {{"primitives", json::array()}};
        if (!mesh.name.empty()) jm["name"] = mesh.name;
        for (const Primitive& p : mesh.primitives) {
            if (p.positions.empty()) continue;
            json attrs;
            attrs["POSITION"] = b.accessor(p.positions, 3, "VEC3", true, gltf_code::kArrayBuffer);
            if (p.normals.size() == p.positions.size()) attrs["NORMAL"] = b.accessor(p.normals, 3, "VEC3", false, gltf_code::kArrayBuffer);
            if (p.tangents.size() == p.positions.size())
                attrs["TANGENT"] = b.accessor(p.tangents, 4, "VEC4", false, gltf_code::kArrayBuffer);
            if (p.uv0.size() == p.positions.size()) attrs["TEXCOORD_0"] = b.accessor(p.uv0, 2, "VEC2", false, gltf_code::kArrayBuffer);
            if (p.uv1.size() == p.positions.size()) attrs["TEXCOORD_1"] = b.accessor(p.uv1, 2, "VEC2", false, gltf_code::kArrayBuffer);
            if (p.colors.size() == p.positions.size()) attrs["COLOR_0"] = b.accessor(p.colors, 4, "VEC4", false, gltf_code::kArrayBuffer);
            json jp = {{"attributes", attrs}};
            if (!p.indices.empty()) jp["indices"] = b.index_accessor(p.indices);
            int mode = 4;
            switch (p.topology) {
                case Topology::Points: mode = 0; break;
                case Topology::Lines: mode = 1; break;
                case Topology::LineLoop: mode = 2; break;
                case Topology::LineStrip: mode = 3; break;
                case Topology::Triangles: mode = 4; break;
            }
            if (mode != 4) jp["mode"] = mode;
            if (p.material >= 0 && std::size_t(p.material) < scene.materials.size()) jp["material"] = p.material;
            // KHR_materials_variants: one mapping per material, listing the variants that pick it.
            std::map<int, std::vector<int>> by_material;
            for (std::size_t v = 0; v < p.variant_materials.size() && v < scene.material_variants.size(); ++v) {
                int mat = p.variant_materials[v];
                if (mat >= 0 && std::size_t(mat) < scene.materials.size()) by_material[mat].push_back(int(v));
            }
            if (!by_material.empty()) {
                json mappings = json::array();
                for (const auto& [mat, variants] : by_material) mappings.push_back({{"material", mat}, {"variants", variants}});
                jp["extensions"]["KHR_materials_variants"] = {{"mappings", mappings}};
                b.used.insert("KHR_materials_variants");
            }
            jm["primitives"].push_back(jp);
        }
        if (jm["primitives"].empty()) diagnostics.warn(path.string(), "/meshes", "a mesh without vertices was written empty");
        meshes.push_back(jm);
    }
    // Lights: the punctual ones in KHR_lights_punctual, the area ones in EXT_lights_area (when
    // asked), each numbered within its own list.
    std::vector<int> light_index(scene.lights.size(), -1);
    int punctual_count = 0, area_count = 0;
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        if (!is_area_light(scene.lights[i].type)) light_index[i] = punctual_count++;
        else if (options.area_lights) light_index[i] = area_count++;
    }
    if (area_count == 0 && std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) { return is_area_light(l.type); }))
        diagnostics.warn(path.string(), "/extensions", "area lights are not written (convert --area-lights writes them as EXT_lights_area)");
    json nodes = json::array();
    for (const Node& n : scene.nodes) {
        json jn = json::object();
        if (!n.name.empty()) jn["name"] = n.name;
        if (n.local != glm::mat4(1.0f)) jn["matrix"] = vec_json(glm::value_ptr(n.local), 16);
        if (n.mesh >= 0 && !meshes[std::size_t(n.mesh)]["primitives"].empty()) jn["mesh"] = n.mesh;
        if (n.camera >= 0) jn["camera"] = n.camera;
        if (!n.visible) {
            jn["extensions"]["KHR_node_visibility"] = {{"visible", false}};
            b.used.insert("KHR_node_visibility");
        }
        if (n.light >= 0 && std::size_t(n.light) < scene.lights.size() && light_index[std::size_t(n.light)] >= 0) {
            const char* ext = is_area_light(scene.lights[std::size_t(n.light)].type) ? "EXT_lights_area" : "KHR_lights_punctual";
            jn["extensions"][ext] = {{"light", light_index[std::size_t(n.light)]}};
            b.used.insert(ext);
        }
        if (n.skin >= 0) diagnostics.warn(path.string(), "/nodes", "skins are not written (the mesh keeps its rest pose)");
        if (!n.children.empty()) jn["children"] = n.children;
        nodes.push_back(jn);
    }
    json cameras = json::array();
    for (const Camera& c : scene.cameras) {
        json jc;
        if (c.type == Camera::Type::Perspective) {
            json p = {{"yfov", c.yfov}, {"znear", c.znear}};
            if (c.aspect_ratio) p["aspectRatio"] = *c.aspect_ratio;
            if (c.zfar) p["zfar"] = *c.zfar;
            jc = {{"type", "perspective"}, {"perspective", p}};
        } else {
            jc = {{"type", "orthographic"},
                  {"orthographic", {{"xmag", c.xmag}, {"ymag", c.ymag}, {"znear", c.znear}, {"zfar", c.zfar.value_or(c.znear + 1000.0f)}}}};
        }
        if (!c.name.empty()) jc["name"] = c.name;
        cameras.push_back(jc);
    }
    if (punctual_count + area_count > 0) {
        json lights = json::array(), area_lights = json::array();
        for (std::size_t i = 0; i < scene.lights.size(); ++i) {
            const Light& l = scene.lights[i];
            if (light_index[i] < 0) continue;
            json jl = {{"type", light_type_name(l.type)}};
            if (l.color != glm::vec3(1.0f)) jl["color"] = vec_json(glm::value_ptr(l.color), 3);
            if (l.intensity != 1.0f) jl["intensity"] = l.intensity;
            if (l.range > 0.0f && (l.type == Light::Type::Point || l.type == Light::Type::Spot)) jl["range"] = l.range;
            if (l.type == Light::Type::Spot)
                jl["spot"] = {{"innerConeAngle", l.inner_cone_angle}, {"outerConeAngle", l.outer_cone_angle}};
            if (l.type == Light::Type::Rect) {
                jl["width"] = l.width;
                jl["height"] = l.height;
            }
            if (l.type == Light::Type::Disk || l.type == Light::Type::Sphere || l.type == Light::Type::Tube) jl["radius"] = l.radius;
            if (l.type == Light::Type::Tube) jl["length"] = l.length;
            if (!l.name.empty()) jl["name"] = l.name;
            (is_area_light(l.type) ? area_lights : lights).push_back(jl);
        }
        if (!lights.empty()) {
            doc["extensions"]["KHR_lights_punctual"] = {{"lights", lights}};
            b.used.insert("KHR_lights_punctual");
        }
        if (!area_lights.empty()) {
            doc["extensions"]["EXT_lights_area"] = {{"lights", area_lights}};
            b.used.insert("EXT_lights_area");
        }
    }
    if (b.used.count("KHR_materials_variants")) {
        json variants = json::array();
        for (const std::string& name : scene.material_variants) variants.push_back({{"name", name}});
        doc["extensions"]["KHR_materials_variants"] = {{"variants", variants}};
    }
    json scenes = json::array();
    // A scene without roots is an empty object: "nodes": [] is an empty array, which the Khronos
    // validator rejects (EMPTY_ENTITY).
    for (const auto& roots : scene.scenes) scenes.push_back(roots.empty() ? json::object() : json{{"nodes", roots}});
    if (scenes.empty() && !nodes.empty()) {
        json roots = json::array();
        std::vector<bool> child(nodes.size(), false);
        for (const Node& n : scene.nodes)
            for (int c : n.children) child[std::size_t(c)] = true;
        for (std::size_t i = 0; i < nodes.size(); ++i)
            if (!child[i]) roots.push_back(i);
        scenes.push_back({{"nodes", roots}});
    }

    if (!images.empty()) doc["images"] = images;
    if (!samplers.empty()) doc["samplers"] = samplers;
    if (!textures.empty()) doc["textures"] = textures;
    if (!materials.empty()) doc["materials"] = materials;
    if (!meshes.empty()) doc["meshes"] = meshes;
    if (!nodes.empty()) doc["nodes"] = nodes;
    if (!cameras.empty()) doc["cameras"] = cameras;
    if (!scenes.empty()) {
        doc["scenes"] = scenes;
        doc["scene"] = std::clamp(scene.default_scene, 0, int(scenes.size()) - 1);
    }
    if (!b.used.empty()) doc["extensionsUsed"] = std::vector<std::string>(b.used.begin(), b.used.end());
    while (b.bin.size() % 4) b.bin.push_back(0);
    if (doc["accessors"].empty()) doc.erase("accessors");
    if (doc["bufferViews"].empty()) doc.erase("bufferViews");
    if (b.bin.empty()) {
        doc.erase("buffers");
    } else if (glb) {
        doc["buffers"].push_back({{"byteLength", b.bin.size()}});
    } else {
        doc["buffers"].push_back({{"byteLength", b.bin.size()}, {"uri", stem + ".bin"}});
    }

    FileSet files;
    for (const auto& [file, image] : image_files) stage_png(files, file, *image);
    if (glb) {
        std::string text = doc.dump();
        while (text.size() % 4) text.push_back(' ');
        std::vector<std::uint8_t> out;
        auto u32 = [&](std::uint32_t v) {
            for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
        };
        std::uint32_t total = 12 + 8 + std::uint32_t(text.size()) + (b.bin.empty() ? 0 : 8 + std::uint32_t(b.bin.size()));
        u32(0x46546C67);  // "glTF"
        u32(2);
        u32(total);
        u32(std::uint32_t(text.size()));
        u32(0x4E4F534A);  // JSON
        out.insert(out.end(), text.begin(), text.end());
        if (!b.bin.empty()) {
            u32(std::uint32_t(b.bin.size()));
            u32(0x004E4942);  // BIN
            out.insert(out.end(), b.bin.begin(), b.bin.end());
        }
        stage_bytes(files, path, out);
    } else {
        if (!b.bin.empty()) stage_bytes(files, folder / (stem + ".bin"), b.bin);
        files.stage(path, doc.dump(2) + "\n");
    }
    files.commit();
    return files.paths();
}

// ---- OBJ/MTL -------------------------------------------------------------------------------

namespace {
// The shortest text that reads back as the same float.
std::string num(float v) { return shortest_text(std::isfinite(v) ? v : 0.0f); }
// An OBJ v for the glTF-convention texture coordinate `g`: the shortest decimal d with
// float(1 - d) == g, which is what load_obj computes from it. So a v the OBJ loader read comes
// back as the same digits whenever the decimals that round to g hold no shorter one: always
// for v in [0, 1] written with up to 7 decimal places, and up to 6 for |v| < 8 (the decimals
// of g lie within a float step of 1 - g, which is narrower than those grids); OBJ -> glTF ->
// OBJ keeps exporters' texture coordinates exactly. Any g itself survives glTF -> OBJ -> glTF.
std::string obj_v_text(float g) {
    if (!std::isfinite(g)) g = 0.0f;
    const double centre = 1.0 - double(g);
    char buf[40];
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, centre);
        if (float(1.0 - std::strtod(buf, nullptr)) == g) return buf;
    }
    return buf;  // 17 digits print `centre` exactly, which maps back to g
}
std::string vec3_text(const glm::vec3& v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }
std::string mtl_name(const Material& m, std::size_t i) {
    std::string n = m.name.empty() ? "material" + std::to_string(i) : m.name;
    for (char& c : n)
        if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '#') c = '_';
    return n;
}
}  // namespace

std::vector<fs::path> write_obj(const Scene& scene, const fs::path& path, Diagnostics& diagnostics,
                                const ObjWriteOptions& options) {
    const std::string stem = path.stem().string();
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::string mtl, obj = "# written by fresnel convert\nmtllib " + stem + ".mtl\n";
    FileSet files;
    std::map<int, std::string> image_file;  // scene image -> file name
    auto map_line = [&](const char* key, const TextureSlot& s) {
        if (!slot_ok(s, scene)) return;
        int image = scene.textures[std::size_t(s.texture)].image;
        auto it = image_file.find(image);
        if (it == image_file.end()) {
            std::string name = stem + "_image" + std::to_string(image) + ".png";
            stage_png(files, folder / name, scene.images[std::size_t(image)].pixels);
            it = image_file.emplace(image, name).first;
        }
        mtl += std::string(key) + " " + it->second + "\n";
    };
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        PhongExt p;
        if (m.phong) {
            p = *m.phong;
        } else {
            p.diffuse = glm::vec3(m.base_color_factor);
            p.specular = glm::vec3(0.04f);
            p.shininess = 30.0f;
            p.dissolve = m.base_color_factor.w;
        }
        mtl += "newmtl " + mtl_name(m, i) + "\n";
        mtl += "Ka " + vec3_text(p.ambient) + "\nKd " + vec3_text(p.diffuse) + "\nKs " + vec3_text(p.specular) + "\n";
        mtl += "Ke " + vec3_text(m.emissive_factor * m.emissive_strength_value()) + "\nNs " + num(p.shininess) + "\n";
        mtl += "d " + num(m.alpha_mode == AlphaMode::Blend ? m.base_color_factor.w : 1.0f) + "\n";
        mtl += "illum " + std::to_string(m.unlit ? 0 : 2) + "\n";
        if (options.pbr_keys) mtl += "Pr " + num(m.roughness_factor) + "\nPm " + num(m.metallic_factor) + "\n";
        map_line("map_Kd", m.base_color);
        map_line("map_Ke", m.emissive);
        if (slot_ok(m.normal, scene)) map_line("norm", m.normal);
        mtl += "\n";
    }
    std::size_t base_v = 1;
    bool hidden_skipped = false;
    for (const NodeInstance& inst : flatten(scene)) {
        const Node& node = scene.nodes[std::size_t(inst.node)];
        if (node.mesh < 0) continue;
        if (!inst.visible) {  // OBJ cannot hide an object: what is written is what is seen
            if (!hidden_skipped)
                diagnostics.warn(path.string(), "/nodes/" + std::to_string(inst.node),
                                 "hidden nodes (KHR_node_visibility) are not written");
            hidden_skipped = true;
            continue;
        }
        const Mesh& mesh = scene.meshes[std::size_t(node.mesh)];
        obj += "o " + (mesh.name.empty() ? (node.name.empty() ? "mesh" + std::to_string(node.mesh) : node.name) : mesh.name) + "\n";
        const bool identity = inst.world == glm::mat4(1.0f);
        glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(inst.world)));
        for (const Primitive& p : mesh.primitives) {
            if (p.topology != Topology::Triangles) {
                diagnostics.warn(path.string(), mesh.name, "only triangles are written to OBJ; lines and points dropped");
                continue;
            }
            const bool has_n = p.normals.size() == p.positions.size(), has_t = p.uv0.size() == p.positions.size();
            for (const glm::vec3& v : p.positions)
                obj += "v " + vec3_text(identity ? v : glm::vec3(inst.world * glm::vec4(v, 1.0f))) + "\n";
            if (has_t)
                for (const glm::vec2& t : p.uv0) obj += "vt " + num(t.x) + " " + obj_v_text(t.y) + "\n";
            if (has_n)
                for (const glm::vec3& n : p.normals) obj += "vn " + vec3_text(identity ? n : glm::normalize(normal_matrix * n)) + "\n";
            if (p.material >= 0 && std::size_t(p.material) < scene.materials.size())
                obj += "usemtl " + mtl_name(scene.materials[std::size_t(p.material)], std::size_t(p.material)) + "\n";
            auto corner = [&](std::uint32_t i) {
                std::string k = std::to_string(base_v + i);
                if (has_t && has_n) return k + "/" + k + "/" + k;
                if (has_t) return k + "/" + k;
                if (has_n) return k + "//" + k;
                return k;
            };
            std::size_t count = p.indices.empty() ? p.positions.size() : p.indices.size();
            for (std::size_t c = 0; c + 2 < count; c += 3) {
                auto idx = [&](std::size_t k) { return p.indices.empty() ? std::uint32_t(k) : p.indices[k]; };
                obj += "f " + corner(idx(c)) + " " + corner(idx(c + 1)) + " " + corner(idx(c + 2)) + "\n";
            }
            base_v += p.positions.size();
        }
    }
    files.stage(folder / (stem + ".mtl"), mtl);
    files.stage(path, obj);
    files.commit();
    return files.paths();
}


// --- material edits written back (the viewer's "save") --------------------------------------
//
// Not write_gltf: that writes what the Scene holds, and a Scene does not hold what fresnel
// does not understand. Here the file itself is the model: its JSON is parsed with its keys in
// order (nlohmann::ordered_json), only the edited values are replaced, and it is written back;
// binary data is copied byte for byte.

namespace {

using ojson = nlohmann::ordered_json;
using gltf_code::kChunkJson;
using gltf_code::kGlbMagic;

std::uint32_t u32_at(const std::vector<std::uint8_t>& b, std::size_t at) {
    return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
           std::uint32_t(b[at + 3]) << 24;
}
void put_u32(std::vector<std::uint8_t>& b, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(std::uint8_t(v >> (8 * i)));
}

// A float as the JSON number of its shortest decimal form (0.2f is 0.2, not 0.20000000298...).
ojson number_of(float v) { return ojson(std::strtod(shortest_text(v).c_str(), nullptr)); }
template <int N>
ojson numbers_of(const glm::vec<N, float>& v) {
    ojson a = ojson::array();
    for (int i = 0; i < N; ++i) a.push_back(number_of(v[i]));
    return a;
}

class MaterialPatcher {
public:
    MaterialPatcher(ojson& doc, const std::string& file, Diagnostics& diag) : doc_(doc), file_(file), diag_(diag) {}

    // Every property of the material property registry (fresnel/material/properties.h) whose
    // value changed, at its glTF path; an extension block the edit added is written whole.
    void patch(std::size_t i, const Material& was, const Material& now) {
        namespace mp = material_properties;
        ojson& m = doc_["materials"][i];
        const std::string ptr = "/materials/" + std::to_string(i);
        bool pbr_edited = false;
        for (const mp::Property& p : mp::all()) {
            if (!mp::changed(p, was, now)) continue;
            const mp::Value v = p.get(now);
            // Walk the path: objects are added, except a texture reference the material lacks
            // (a normalTexture's scale without a normalTexture means nothing).
            ojson* parent = &m;
            std::string_view rest = p.path;
            bool missing = false;
            for (std::size_t slash = rest.find('/'); slash != std::string_view::npos; slash = rest.find('/')) {
                std::string part(rest.substr(0, slash));
                rest.remove_prefix(slash + 1);
                if (part.size() > 7 && part.ends_with("Texture") && !(parent->contains(part) && (*parent)[part].is_object())) {
                    diag_.warn(file_, ptr, "has no " + part + ": its " + std::string(rest) + " is not written");
                    missing = true;
                    break;
                }
                if (parent == &m && part == "pbrMetallicRoughness") pbr_edited = true;
                if (part.starts_with("KHR_")) used(part.c_str());
                parent = &object(*parent, part.c_str());
            }
            if (missing) continue;
            const std::string key(rest);
            if (p.type == mp::Type::Bool) set(*parent, key.c_str(), v[0] != 0.0f);
            else if (p.type == mp::Type::Choice) set(*parent, key.c_str(), mp::format(p, v));
            else if (!std::isfinite(v[0])) {  // the default infinity (attenuationDistance) is written by leaving the key out
                if (parent->erase(key)) ++changed_;
            } else if (p.width == 1) set(*parent, key.c_str(), number_of(v[0]));
            else {
                ojson a = ojson::array();
                for (int k = 0; k < p.width; ++k) a.push_back(number_of(v[std::size_t(k)]));
                set(*parent, key.c_str(), a);
            }
        }
        if (was.specular_glossiness && pbr_edited)
            diag_.warn(file_, ptr, "uses KHR_materials_pbrSpecularGlossiness: the edit is written to "
                                   "pbrMetallicRoughness, which viewers that read the extension ignore");
    }
    // True when any property patch() writes differs between the two.
    static bool differs(const Material& a, const Material& b) {
        namespace mp = material_properties;
        for (const mp::Property& p : mp::all()) {
            const bool in_a = mp::present(p, a), in_b = mp::present(p, b);
            if (in_a != in_b || (in_a && !mp::same(p, p.get(a), p.get(b)))) return true;
        }
        return false;
    }
    int changed() const { return changed_; }

private:
    ojson& object(ojson& parent, const char* key) {
        if (!parent.contains(key) || !parent[key].is_object()) parent[key] = ojson::object();
        return parent[key];
    }
    void set(ojson& parent, const char* key, const ojson& value) {
        parent[key] = value;
        ++changed_;
    }
    void used(const char* name) {
        ojson& list = doc_["extensionsUsed"];
        if (!list.is_array()) list = ojson::array();
        for (const auto& e : list)
            if (e == name) return;
        list.push_back(name);
    }
    ojson& doc_;
    std::string file_;
    Diagnostics& diag_;
    int changed_ = 0;
};

}  // namespace

int save_gltf_material_edits(const fs::path& source, const fs::path& dest, const std::vector<Material>& original,
                             const std::vector<Material>& edited, Diagnostics& diagnostics) {
    const std::string src_name = source.string(), dst_name = dest.string();
    auto ext_of = [](const fs::path& p) {
        std::string e = p.extension().string();
        for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
        return e;
    };
    const std::string ext = ext_of(source);
    if (ext != ".gltf" && ext != ".glb") throw Error(src_name, "", "only glTF files (.gltf, .glb) save material edits");
    if (ext_of(dest) != ext) throw Error(dst_name, "", "saving keeps the container: " + ext + " to " + ext);
    if (original.size() != edited.size())
        throw Error(src_name, "", "the edited materials are not the file's (" + std::to_string(edited.size()) + " of " +
                                      std::to_string(original.size()) + ")");
    const std::vector<std::uint8_t> bytes = read_file_bytes(source, std::size_t(2) << 30);
    const bool glb = ext == ".glb";
    std::size_t json_at = 0, json_size = bytes.size(), rest_at = bytes.size();
    if (glb) {
        if (bytes.size() < 20 || u32_at(bytes, 0) != kGlbMagic || u32_at(bytes, 12 + 4) != kChunkJson)
            throw Error(src_name, "byte 0", "not a GLB file with a JSON chunk first");
        json_size = u32_at(bytes, 12);
        json_at = 20;
        if (json_size > bytes.size() - json_at) throw Error(src_name, "byte 12", "the JSON chunk runs past the end of the file");
        rest_at = json_at + json_size;
    }
    ojson doc;
    try {
        doc = ojson::parse(bytes.begin() + std::ptrdiff_t(json_at), bytes.begin() + std::ptrdiff_t(json_at + json_size));
    } catch (const ojson::exception& e) {
        throw Error(src_name, "", std::string("cannot parse the JSON: ") + e.what());
    }
    if (!doc.is_object()) throw Error(src_name, "", "the glTF JSON is not an object");
    const std::size_t count = doc.contains("materials") && doc["materials"].is_array() ? doc["materials"].size() : 0;
    MaterialPatcher patcher(doc, src_name, diagnostics);
    for (std::size_t i = 0; i < edited.size(); ++i) {
        if (!MaterialPatcher::differs(edited[i], original[i])) continue;
        if (i >= count || !doc["materials"][i].is_object()) {
            diagnostics.warn(src_name, "/materials/" + std::to_string(i), "is not in the file (a default material): not written");
            continue;
        }
        patcher.patch(i, original[i], edited[i]);
    }
    // The layout of the text as the file had it: indented, or on one line.
    const bool indented = std::find(bytes.begin() + std::ptrdiff_t(json_at),
                                    bytes.begin() + std::ptrdiff_t(json_at + json_size), '\n') !=
                          bytes.begin() + std::ptrdiff_t(json_at + json_size);
    std::string text = doc.dump(indented ? 2 : -1);

    fs::path dest_dir = dest.parent_path().empty() ? fs::path(".") : dest.parent_path();
    fs::path src_dir = source.parent_path().empty() ? fs::path(".") : source.parent_path();
    if (std::error_code ec; !fs::is_directory(dest_dir, ec))
        throw Error(dst_name, "", "cannot write: the folder " + dest_dir.string() + " does not exist");
    if (glb) {
        while (text.size() % 4) text += ' ';  // the JSON chunk is padded with spaces
        std::vector<std::uint8_t> out;
        out.reserve(bytes.size() + text.size());
        put_u32(out, kGlbMagic);
        put_u32(out, 2);
        put_u32(out, 0);  // the total length, below
        put_u32(out, std::uint32_t(text.size()));
        put_u32(out, kChunkJson);
        out.insert(out.end(), text.begin(), text.end());
        out.insert(out.end(), bytes.begin() + std::ptrdiff_t(rest_at), bytes.end());  // BIN and any other chunk, as they were
        std::uint32_t total = std::uint32_t(out.size());
        for (int i = 0; i < 4; ++i) out[8 + std::size_t(i)] = std::uint8_t(total >> (8 * i));
        write_file_atomically(dest, std::span<const std::uint8_t>(out));
    } else {
        FileSet files;
        // The files the JSON names (buffers, images), beside the new file when it is elsewhere.
        std::error_code ec;
        if (!fs::equivalent(fs::absolute(dest_dir), fs::absolute(src_dir), ec)) {
            for (const char* list : {"buffers", "images"}) {
                if (!doc.contains(list) || !doc[list].is_array()) continue;
                for (std::size_t i = 0; i < doc[list].size(); ++i) {
                    const ojson& item = doc[list][i];
                    if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
                    const std::string uri = item["uri"].get<std::string>();
                    if (uri.rfind("data:", 0) == 0) continue;
                    std::string error;
                    auto from = resolve_relative_path(uri, src_dir, false, error);
                    auto to = resolve_relative_path(uri, dest_dir, false, error);
                    const std::string where = "/" + std::string(list) + "/" + std::to_string(i) + "/uri";
                    if (!from || !to) {
                        diagnostics.warn(dst_name, where, "'" + uri + "' is not copied: " + error);
                        continue;
                    }
                    fs::create_directories(to->parent_path(), ec);
                    auto data = read_file_bytes(*from, std::size_t(2) << 30);
                    if (!files.staged(*to)) stage_bytes(files, *to, data);
                }
            }
        }
        files.stage(dest, text + (indented ? "\n" : ""));
        files.commit();
    }
    return patcher.changed();
}

}  // namespace fresnel
