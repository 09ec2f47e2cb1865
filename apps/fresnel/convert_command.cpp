// `fresnel convert IN OUT [--allow-external-files] [--quiet]`: OBJ/MTL -> glTF (.gltf + .bin, or
// .glb), glTF -> OBJ/MTL, glTF -> glTF (specular-glossiness becomes metallic-roughness).
// Materials go through the fitted conversion of fresnel/material/fit.h (Phong -> PBR and PBR ->
// Phong by least squares over light and view directions); the writers are
// fresnel/scene/scene_writer.h. Each material's residual is printed (stderr).
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/material/evaluate.h"
#include "fresnel/material/fit.h"
#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/obj_loader.h"
#include "fresnel/scene/scene_writer.h"

namespace fresnel::cli {

namespace {

namespace fs = std::filesystem;

struct ConvertOptions {
    std::string input, output;
    bool allow_external_files = false;
    bool quiet = false;
};

std::string lower_ext(const fs::path& p) {
    std::string e = p.extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

// Phong (MTL) materials -> fitted metallic-roughness, in place.
void fit_phong_materials(Scene& scene, bool quiet) {
    std::map<std::tuple<float, float, float, float, float, float, float>, fit::PhongToPbr> cache;
    for (Material& m : scene.materials) {
        if (!m.phong || m.phong->has_pbr() || m.unlit) continue;
        const PhongExt& p = *m.phong;
        bool highlight = p.illum != 0 && p.illum != 1;
        fit::Phong ph{p.diffuse, highlight ? p.specular : glm::vec3(0.0f), p.shininess};
        auto key = std::make_tuple(ph.kd.x, ph.kd.y, ph.kd.z, ph.ks.x, ph.ks.y, ph.ks.z, ph.ns);
        auto it = cache.find(key);
        if (it == cache.end()) it = cache.emplace(key, fit::fit_phong_to_pbr(ph)).first;
        const fit::PhongToPbr& f = it->second;
        // The formula conversion's textures stay (map_Kd, map_Ks as specular colour, ...); the
        // factors become the fitted ones.
        fit::apply_pbr(f.pbr, m);
        if (!quiet)
            std::fprintf(stderr, "fresnel: material %s: Phong -> PBR fit %.1f dB (formula %.1f dB)\n", m.name.c_str(),
                         double(f.residual.psnr_db), double(f.formula_residual.psnr_db));
    }
}

void to_metallic_roughness_all(Scene& scene, Diagnostics& d, const std::string& file) {
    for (Material& m : scene.materials) {
        if (!m.specular_glossiness) continue;
        bool lost = false;
        m = to_metallic_roughness(m, &lost);
        m.specular_glossiness.reset();
        if (lost)
            d.warn(file, m.name, "the glossiness channel of specularGlossinessTexture has no metallic-roughness form; dropped");
    }
}

// The mean of one channel of a texture (1 without a readable one).
float texture_mean(const Scene& scene, const TextureSlot& slot, int channel) {
    if (!slot.valid() || std::size_t(slot.texture) >= scene.textures.size()) return 1.0f;
    int image = scene.textures[std::size_t(slot.texture)].image;
    if (image < 0 || std::size_t(image) >= scene.images.size() || !scene.images[std::size_t(image)].valid()) return 1.0f;
    const Image8& img = scene.images[std::size_t(image)].pixels;
    double sum = 0.0;
    std::size_t n = std::size_t(img.width) * std::size_t(img.height);
    for (std::size_t i = 0; i < n; ++i) sum += img.pixels[i * 4 + std::size_t(channel)];
    return n ? float(sum / double(n) / 255.0) : 1.0f;
}

// PBR materials -> fitted Phong values in Material::phong (for the OBJ writer). A
// metallic-roughness texture enters through its mean (OBJ/MTL has no per-texel Ns); the base
// colour texture stays map_Kd, which modulates the fitted Kd as the base colour factor did.
void fit_pbr_materials(Scene& scene, bool quiet) {
    for (Material& m : scene.materials) {
        if (m.phong) continue;  // from an OBJ: keep its own values
        fit::Pbr pbr = fit::from_material(m);
        pbr.metallic *= texture_mean(scene, m.metallic_roughness, 2);
        pbr.roughness *= texture_mean(scene, m.metallic_roughness, 1);
        m.metallic_factor = pbr.metallic;  // what the MTL's Pm / Pr say (no map_Pm / map_Pr is written)
        m.roughness_factor = pbr.roughness;
        fit::PbrToPhong f = fit::fit_pbr_to_phong(pbr);
        PhongExt p;
        p.diffuse = f.phong.kd;
        p.specular = f.phong.ks;
        p.shininess = f.phong.ns;
        p.ambient = glm::vec3(0.0f);
        p.dissolve = m.base_color_factor.w;
        m.phong = p;
        if (!quiet)
            std::fprintf(stderr, "fresnel: material %s: PBR -> Phong fit %.1f dB (naive %.1f dB)\n", m.name.c_str(),
                         double(f.residual.psnr_db), double(f.naive_residual.psnr_db));
    }
}

int run_convert(const ConvertOptions& o) {
    const std::string in_ext = lower_ext(o.input), out_ext = lower_ext(o.output);
    const bool in_obj = in_ext == ".obj", out_obj = out_ext == ".obj";
    if (!in_obj && in_ext != ".gltf" && in_ext != ".glb") {
        print_error(o.input + ": convert reads .obj, .gltf or .glb");
        return kExitUsage;
    }
    if (!out_obj && out_ext != ".gltf" && out_ext != ".glb") {
        print_error(o.output + ": convert writes .obj, .gltf or .glb");
        return kExitUsage;
    }
    Diagnostics diagnostics;
    Scene scene;
    if (in_obj) {
        ObjLoadOptions opts;
        opts.allow_external_files = o.allow_external_files;
        scene = load_obj(o.input, diagnostics, opts);
    } else {
        GltfLoadOptions opts;
        opts.allow_external_files = o.allow_external_files;
        scene = load_gltf(o.input, diagnostics, opts);
    }
    to_metallic_roughness_all(scene, diagnostics, o.input);
    if (out_obj) {
        fit_pbr_materials(scene, o.quiet);
        write_obj(scene, o.output, diagnostics);
    } else {
        if (in_obj) fit_phong_materials(scene, o.quiet);
        write_gltf(scene, o.output, diagnostics);
    }
    print_warnings(diagnostics);
    return kExitOk;
}

}  // namespace

Runner add_convert_command(CLI::App& app) {
    auto opts = std::make_shared<ConvertOptions>();
    CLI::App* cmd = app.add_subcommand("convert", "Convert OBJ/MTL <-> glTF with fitted materials (.obj, .gltf, .glb)");
    cmd->add_option("input", opts->input, "Input .obj, .gltf or .glb")->required();
    cmd->add_option("output", opts->output, "Output .obj (+ .mtl), .gltf (+ .bin, images) or .glb")->required();
    cmd->add_flag("--allow-external-files", opts->allow_external_files,
                  "Allow URIs and MTL/texture paths outside the model's folder");
    cmd->add_flag("--quiet", opts->quiet, "Do not print each material's fit residual");
    cmd->footer("Phong materials are fitted to metallic-roughness (and back) by fresnel/material/fit.h;\n"
                "specular-glossiness becomes metallic-roughness + KHR_materials_specular.");
    return [opts]() { return run_convert(*opts); };
}

}  // namespace fresnel::cli
