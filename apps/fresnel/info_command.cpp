// `fresnel info MODEL [--json]`: what a model holds, without rendering it.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/scene/gltf_loader.h"

namespace fresnel::cli {

namespace {
struct InfoOptions {
    std::string model;
    bool json = false;
    bool allow_external = false;
};

int run_info(const InfoOptions& o) {
    Diagnostics diag;
    GltfLoadOptions lo;
    lo.allow_external_files = o.allow_external;
    lo.decode_images = false;  // counts and bounds need no pixels
    Scene scene = load_gltf(o.model, diag, lo);
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
    j["skins"] = scene.skins.size();
    j["animations"] = nlohmann::json::array();
    for (const auto& a : scene.animations)
        j["animations"].push_back({{"name", a.name}, {"start", a.start()}, {"end", a.end()}, {"duration", a.duration()},
                                   {"channels", a.channels.size()}});
    j["extensions_used"] = scene.extensions_used;
    j["extensions_required"] = scene.extensions_required;
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
    return kExitOk;
}
}  // namespace

Runner add_info_command(CLI::App& app) {
    auto o = std::make_shared<InfoOptions>();
    CLI::App* cmd = app.add_subcommand("info", "Print counts, bounds and extensions of a glTF model");
    cmd->add_option("model", o->model, "glTF 2.0 file (.gltf or .glb)")->required();
    cmd->add_flag("--json", o->json, "Print a JSON object instead of text");
    cmd->add_flag("--allow-external-files", o->allow_external,
                  "Let URIs point outside the model's folder (absolute paths, ..); never the network");
    return [o] { return run_info(*o); };
}

}  // namespace fresnel::cli
