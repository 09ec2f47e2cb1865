// `fresnel info MODEL [--json]`: what a model holds, without rendering it.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/job/job.h"
#include "fresnel/material/properties.h"
#include "fresnel/job/scene_file.h"
#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/obj_loader.h"

namespace fresnel::cli {

namespace {
struct InfoOptions {
    std::string model;
    bool json = false;
    bool allow_external = false;
};

// A scene file: what the job holds (validated as `render` reads it), then the composed scene.
int run_scene_file_info(const InfoOptions& o) {
    Diagnostics diag;
    SceneFileOptions so;
    so.allow_external_files = o.allow_external;
    SceneFile sf = load_scene_file(o.model, Job{}, diag, so);
    const Job& job = sf.job;
    Scene scene = load_scene(job, diag);
    ResolvedJob r = resolve(job, scene);
    nlohmann::json j;
    j["file"] = o.model;
    j["format_version"] = kSceneFileVersion;
    nlohmann::json models = nlohmann::json::array();
    if (job.source.models.empty()) models.push_back({{"path", job.source.model.empty() ? "demo" : job.source.model}});
    for (const auto& m : job.source.models)
        models.push_back({{"path", m.path.empty() ? "demo" : m.path}, {"visible", m.visible},
                          {"material_overrides", m.materials.size()}});
    j["models"] = models;
    j["camera"] = job.camera.scene_camera ? "model" : job.camera.look_at ? "lookAt" : "orbit";
    j["lights"] = r.lights.size();
    j["default_lights"] = r.default_lights;
    j["environment"] = r.environment ? r.environment->describe() : "none";
    j["size"] = {job.output.width, job.output.height};
    if (sf.output) j["output"] = sf.output->string();
    std::size_t triangles = 0;
    for (const auto& m : scene.meshes)
        for (const auto& p : m.primitives) triangles += p.triangle_count();
    j["triangles"] = triangles;
    j["materials"] = scene.materials.size();
    if (!r.bounds.empty)
        j["bounds"] = {{"min", {r.bounds.min.x, r.bounds.min.y, r.bounds.min.z}},
                       {"max", {r.bounds.max.x, r.bounds.max.y, r.bounds.max.z}}};
    j["warnings"] = diag.lines();
    if (o.json) {
        std::printf("%s\n", j.dump(2).c_str());
        return kExitOk;
    }
    print_warnings(diag);
    std::printf("%s (scene file, format %d)\n", o.model.c_str(), kSceneFileVersion);
    for (const auto& m : models) std::printf("  %-11s %s\n", "model", m["path"].get<std::string>().c_str());
    for (const char* k : {"camera", "lights", "environment", "size", "output", "triangles", "materials"})
        if (j.contains(k)) std::printf("  %-11s %s\n", k, j[k].is_string() ? j[k].get<std::string>().c_str() : j[k].dump().c_str());
    return kExitOk;
}

int run_info(const InfoOptions& o) {
    if (is_scene_file(o.model)) return run_scene_file_info(o);
    Diagnostics diag;
    Scene scene;
    if (is_obj_path(o.model)) {
        ObjLoadOptions oo;
        oo.allow_external_files = o.allow_external;
        oo.decode_images = false;  // counts and bounds need no pixels
        oo.read_image_headers = true;  // formats and sizes do need the headers
        scene = load_obj(o.model, diag, oo);
    } else {
        GltfLoadOptions lo;
        lo.allow_external_files = o.allow_external;
        lo.decode_images = false;
        lo.read_image_headers = true;
        lo.require_supported_extensions = false;  // describe the file even so (and list them below)
        scene = load_gltf(o.model, diag, lo);
    }
    std::size_t primitives = 0, vertices = 0, triangles = 0;
    for (const auto& m : scene.meshes)
        for (const auto& p : m.primitives) {
            ++primitives;
            vertices += p.source_vertex_count;
            triangles += p.triangle_count();
        }
    auto instances = flatten(scene);
    Bounds b = scene_bounds(scene, instances);
    nlohmann::json j;
    j["file"] = o.model;
    j["scenes"] = scene.scenes.size();
    j["nodes"] = scene.nodes.size();
    j["meshes"] = scene.meshes.size();
    j["primitives"] = primitives;
    j["vertices"] = vertices;
    j["triangles"] = triangles;
    j["materials"] = scene.materials.size();
    j["textures"] = scene.textures.size();
    j["images"] = scene.images.size();
    j["cameras"] = scene.cameras.size();
    j["lights"] = scene.lights.size();
    if (!b.empty) {
        j["bounds"] = {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}},
                       {"center", {b.center().x, b.center().y, b.center().z}}, {"radius", b.radius()}};
    }
    // Meshes placed by several nodes (EXT_mesh_gpu_instancing's instances, repeated parts):
    // held once, drawn instanced and traced as Embree instances (render.instancing).
    std::vector<std::size_t> placements(scene.meshes.size(), 0);
    std::size_t placed_triangles = 0;
    for (const NodeInstance& inst : instances) {
        const int mesh = scene.nodes[std::size_t(inst.node)].mesh;
        if (mesh < 0 || std::size_t(mesh) >= scene.meshes.size() || !inst.visible) continue;
        ++placements[std::size_t(mesh)];
        for (const auto& p : scene.meshes[std::size_t(mesh)].primitives) placed_triangles += p.triangle_count();
    }
    j["placed_triangles"] = placed_triangles;  // every placement's
    j["instanced_meshes"] = nlohmann::json::array();
    for (std::size_t m = 0; m < placements.size(); ++m)
        if (placements[m] >= 2)
            j["instanced_meshes"].push_back({{"mesh", m}, {"name", scene.meshes[m].name}, {"placements", placements[m]}});
    j["skins"] = scene.skins.size();
    j["animations"] = nlohmann::json::array();
    for (const auto& a : scene.animations)
        j["animations"].push_back({{"name", a.name}, {"start", a.start()}, {"end", a.end()}, {"duration", a.duration()},
                                   {"channels", a.channels.size()}});
    j["extensions_used"] = scene.extensions_used;
    j["extensions_required"] = scene.extensions_required;
    // Every extension the file names, with how fresnel handles it.
    std::vector<std::string> all = scene.extensions_used;
    for (const auto& e : scene.extensions_required)
        if (std::find(all.begin(), all.end(), e) == all.end()) all.push_back(e);
    j["extensions"] = nlohmann::json::array();
    for (const auto& e : all) {
        auto s = gltf_extension_support(e);
        bool required = std::find(scene.extensions_required.begin(), scene.extensions_required.end(), e) !=
                        scene.extensions_required.end();
        j["extensions"].push_back({{"name", e},
                                   {"required", required},
                                   {"support", s == GltfExtensionSupport::Supported       ? "supported"
                                               : s == GltfExtensionSupport::ReadNotShaded ? "read, not shaded"
                                                                                          : "not supported"}});
    }
    j["variants"] = scene.material_variants;
    // Each material: its extension blocks and texture slots (by the material property registry,
    // fresnel/material/properties.h), alpha mode, sidedness; the file's size and what its
    // geometry takes decoded (the loader's memory budget counts the same).
    j["material_list"] = nlohmann::json::array();
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        nlohmann::json e = {{"index", i}, {"name", m.name}};
        e["alpha_mode"] = m.alpha_mode == AlphaMode::Blend ? "BLEND" : m.alpha_mode == AlphaMode::Mask ? "MASK" : "OPAQUE";
        e["double_sided"] = m.double_sided;
        e["unlit"] = m.unlit.has_value();
        e["extensions"] = nlohmann::json::array();
        for (const material_properties::Block& bl : material_properties::blocks())
            if (bl.present && bl.present(m)) e["extensions"].push_back(std::string(bl.name));
        if (m.specular_glossiness) e["extensions"].push_back("KHR_materials_pbrSpecularGlossiness");
        e["textures"] = nlohmann::json::array();
        for (const material_properties::Texture& t : material_properties::textures()) {
            const TextureSlot* slot = t.get(m);
            if (slot && slot->texture >= 0) e["textures"].push_back(std::string(t.name));
        }
        j["material_list"].push_back(e);
    }
    // Images: names (image_list), and what each holds with what it takes once loaded: RGBA8 with
    // its mip chain (4/3 of the base level), as the renderer uploads it.
    j["image_list"] = nlohmann::json::array();
    j["image_details"] = nlohmann::json::array();
    std::size_t image_file_bytes = 0, image_memory_bytes = 0;
    for (const SceneImage& im : scene.images) {
        j["image_list"].push_back(im.name);
        const std::size_t memory = std::size_t(im.header.width) * std::size_t(im.header.height) * 4 * 4 / 3;
        j["image_details"].push_back({{"name", im.name}, {"format", im.header.format}, {"width", im.header.width},
                                      {"height", im.header.height}, {"file_bytes", im.encoded_bytes},
                                      {"memory_bytes", memory}});
        image_file_bytes += im.encoded_bytes;
        image_memory_bytes += memory;
    }
    j["image_file_bytes"] = image_file_bytes;
    j["image_memory_bytes"] = image_memory_bytes;
    std::size_t geometry_bytes = 0;
    for (const auto& m : scene.meshes)
        for (const auto& p : m.primitives)
            geometry_bytes += p.positions.size() * 12 + p.normals.size() * 12 + p.tangents.size() * 16 +
                              (p.uv0.size() + p.uv1.size()) * 8 + p.colors.size() * 16 + p.indices.size() * 4 +
                              (p.joints.size() + p.weights.size()) * 16;
    j["geometry_bytes"] = geometry_bytes;
    std::error_code ec;
    const auto file_bytes = std::filesystem::file_size(o.model, ec);
    if (!ec) j["file_bytes"] = file_bytes;
    j["warnings"] = diag.lines();
    if (o.json) {
        std::printf("%s\n", j.dump(2).c_str());
        return kExitOk;
    }
    print_warnings(diag);
    std::printf("%s\n", o.model.c_str());
    for (const char* k : {"scenes", "nodes", "meshes", "primitives", "vertices", "triangles", "materials", "textures",
                          "images", "cameras", "lights"})
        std::printf("  %-11s %s\n", k, j[k].dump().c_str());
    if (!b.empty)
        std::printf("  %-11s min (%g, %g, %g) max (%g, %g, %g)\n", "bounds", b.min.x, b.min.y, b.min.z, b.max.x, b.max.y,
                    b.max.z);
    if (!j["instanced_meshes"].empty()) {
        std::printf("  %-11s %s triangles over every placement\n", "placed", j["placed_triangles"].dump().c_str());
        for (const auto& m : j["instanced_meshes"])
            std::printf("  %-11s mesh %zu %s: %zu placements (drawn instanced)\n", "instanced", m["mesh"].get<std::size_t>(),
                        m["name"].get<std::string>().empty() ? "(unnamed)" : m["name"].get<std::string>().c_str(),
                        m["placements"].get<std::size_t>());
    }
    std::printf("  %-11s %zu\n", "skins", scene.skins.size());
    std::printf("  %-11s %zu\n", "animations", scene.animations.size());
    for (std::size_t k = 0; k < scene.animations.size(); ++k) {
        const Animation& a = scene.animations[k];
        std::printf("    %zu %-20s %.3f s (%g to %g), %zu channels\n", k, a.name.empty() ? "(unnamed)" : a.name.c_str(),
                    a.duration(), a.start(), a.end(), a.channels.size());
    }
    auto list = [](const std::vector<std::string>& v) {
        std::string s;
        for (const auto& e : v) s += (s.empty() ? "" : ", ") + e;
        return s.empty() ? std::string("none") : s;
    };
    std::printf("  %-11s %s\n", "extensions", list(scene.extensions_used).c_str());
    std::printf("  %-11s %s\n", "required", list(scene.extensions_required).c_str());
    for (const auto& e : j["extensions"]) {
        std::string support = e["support"].get<std::string>();
        std::printf("  %-11s %s%s: %s%s\n", "extension", e["name"].get<std::string>().c_str(),
                    e["required"].get<bool>() ? " (required)" : "", support == "supported" ? "" : "warning: ",
                    support.c_str());
    }
    if (!scene.material_variants.empty()) std::printf("  %-11s %s\n", "variants", list(scene.material_variants).c_str());
    auto mib = [](std::size_t b) { return double(b) / (1024.0 * 1024.0); };
    if (j.contains("file_bytes")) std::printf("  %-11s %.2f MiB\n", "file", mib(j["file_bytes"].get<std::size_t>()));
    std::printf("  %-11s %.2f MiB decoded\n", "geometry", mib(geometry_bytes));
    for (const auto& m : j["material_list"]) {
        std::vector<std::string> parts;
        for (const auto& e : m["extensions"]) parts.push_back(e.get<std::string>());
        std::string textures;
        for (const auto& t : m["textures"]) textures += (textures.empty() ? "" : ", ") + t.get<std::string>();
        std::string name = m["name"].get<std::string>();
        std::printf("  %-11s %zu %s: %s%s%s; textures: %s; extensions: %s\n", "material", m["index"].get<std::size_t>(),
                    name.empty() ? "(unnamed)" : name.c_str(), m["alpha_mode"].get<std::string>().c_str(),
                    m["double_sided"].get<bool>() ? ", double-sided" : "", m["unlit"].get<bool>() ? ", unlit" : "",
                    textures.empty() ? "none" : textures.c_str(), list(parts).c_str());
    }
    if (!scene.images.empty())
        std::printf("  %-11s %.2f MiB in files, %.2f MiB loaded (RGBA8 with mipmaps)\n", "textures",
                    mib(j["image_file_bytes"].get<std::size_t>()), mib(j["image_memory_bytes"].get<std::size_t>()));
    for (std::size_t k = 0; k < scene.images.size(); ++k) {
        const SceneImage& im = scene.images[k];
        std::string size = im.header.width > 0 ? std::to_string(im.header.width) + "x" + std::to_string(im.header.height) + ", " : "";
        std::printf("  %-11s %zu %s: %s, %s%.2f MiB\n", "image", k, im.name.c_str(), im.header.format.c_str(), size.c_str(),
                    mib(im.encoded_bytes));
    }
    return kExitOk;
}
}  // namespace

Runner add_info_command(CLI::App& app) {
    auto o = std::make_shared<InfoOptions>();
    CLI::App* cmd = app.add_subcommand("info", "Print counts, bounds and extensions of a glTF or OBJ model, or a scene file");
    cmd->footer("Examples:\n"
                "  fresnel info model.glb                                     # counts, bounds, extensions\n"
                "  fresnel info scene.fresnel.json --json\n");
    cmd->add_option("model", o->model, "glTF 2.0 file (.gltf or .glb), Wavefront OBJ (.obj) or a scene file (.fresnel.json)")->required();
    cmd->add_flag("--json", o->json, "Print a JSON object instead of text");
    cmd->add_flag("--allow-external-files", o->allow_external,
                  "Let URIs point outside the model's folder (absolute paths, ..); never the network");
    return [o] { return run_info(*o); };
}

}  // namespace fresnel::cli
