// `fresnel convert IN OUT [--allow-external-files] [--quiet]`: OBJ/MTL -> glTF (.gltf + .bin, or
// .glb), glTF -> OBJ/MTL, glTF -> glTF (specular-glossiness becomes metallic-roughness).
// Materials go through the fitted conversion of fresnel/material/fit.h (Phong -> PBR and PBR ->
// Phong by least squares over light and view directions); the writers are
// fresnel/scene/scene_writer.h. Each material's residual is printed (stderr).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/core/color.h"
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
    bool no_diffuse_bake = false;
    std::string match = "albedo";  // Phong -> PBR intent (fit::Match)
    bool rewrite = false;          // glTF -> glTF through the scene model instead of copy_gltf
    bool area_lights = false;      // --rewrite: area lights written as EXT_lights_area
};

std::string lower_ext(const fs::path& p) {
    std::string e = p.extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
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

// Phong (MTL) materials -> fitted metallic-roughness, in place, for `match`'s intent. Values
// outside OpenGL 1's ranges (Kd, Ks above 1, Ns above 128) are clamped with a warning.
// With a map_Kd and --match opengl1: OpenGL 1 modulates the lighting by the texels as stored
// (GL_MODULATE) and adds a textured material's highlight after it (GL_SEPARATE_SPECULAR_COLOR),
// so the highlight is weighed against the diffuse the material shows on average: the fit is of
// Kd times the texture's mean, and the base colour factor is the fitted colour over that mean as
// a glTF viewer reads it (sRGB-decoded), clamped to 1, so factor x texture averages to the fit.
void fit_phong_materials(Scene& scene, bool quiet, fit::Match match, Diagnostics& d, const std::string& file) {
    std::map<std::tuple<float, float, float, float, float, float, float>, fit::PhongToPbr> cache;
    for (Material& m : scene.materials) {
        if (!m.phong || m.phong->has_pbr() || m.unlit) continue;
        const PhongExt& p = *m.phong;
        bool highlight = p.illum != 0 && p.illum != 1;
        fit::Phong ph{p.diffuse, highlight ? p.specular : glm::vec3(0.0f), p.shininess};
        const std::string where = "material '" + m.name + "'";
        auto clamp_colour = [&](const char* key, glm::vec3& c) {
            if (glm::any(glm::lessThan(c, glm::vec3(0.0f))) || glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
                d.warn(file, where, std::string(key) + " outside [0, 1] is clamped (OpenGL 1 clamps it)");
            c = glm::clamp(c, 0.0f, 1.0f);
        };
        clamp_colour("Kd", ph.kd);
        clamp_colour("Ks", ph.ks);
        if (ph.ns < 0.0f || ph.ns > 128.0f) d.warn(file, where, "Ns outside [0, 128] is clamped (OpenGL 1's range)");
        ph.ns = std::clamp(ph.ns, 0.0f, 128.0f);
        glm::vec3 texel(1.0f);  // the mean of map_Kd as stored
        if (match == fit::Match::OpenGl1 && p.diffuse_map.slot.valid())
            for (int c = 0; c < 3; ++c) texel[c] = texture_mean(scene, p.diffuse_map.slot, c);
        ph.kd *= texel;
        auto key = std::make_tuple(ph.kd.x, ph.kd.y, ph.kd.z, ph.ks.x, ph.ks.y, ph.ks.z, ph.ns);
        auto it = cache.find(key);
        if (it == cache.end()) it = cache.emplace(key, fit::fit_phong_to_pbr(ph, match)).first;
        fit::PhongToPbr f = it->second;
        for (int c = 0; c < 3; ++c)
            if (texel[c] != 1.0f) {
                const float decoded = srgb_to_linear(texel[c]);
                f.pbr.base_color[c] = decoded > 0.0f ? std::min(f.pbr.base_color[c] / decoded, 1.0f) : 1.0f;
            }
        // The formula conversion's textures stay (map_Kd, map_Ks as specular colour, ...); the
        // factors become the fitted ones.
        fit::apply_pbr(f.pbr, m);
        if (!quiet)
            std::fprintf(stderr, "fresnel: material %s: Phong -> PBR fit %.1f dB (formula %.1f dB)\n", m.name.c_str(),
                         double(f.residual.psnr_db), double(f.formula_residual.psnr_db));
    }
}

// A copy of texture `texture` whose RGB is the stored texels re-encoded as sRGB: a metallic-
// roughness slot (decoded from sRGB) then reads the values a specular-glossiness material reads
// as stored, as the Khronos Sample Renderer does and `render` by default (--sg-textures). One copy
// per texture (`copies`); -1 stays -1, and a texture without an image is kept as it is.
int srgb_encoded_copy(Scene& scene, int texture, std::map<int, int>& copies) {
    if (texture < 0 || std::size_t(texture) >= scene.textures.size()) return texture;
    if (auto it = copies.find(texture); it != copies.end()) return it->second;
    const Texture tex = scene.textures[std::size_t(texture)];
    if (tex.image < 0 || std::size_t(tex.image) >= scene.images.size() || !scene.images[std::size_t(tex.image)].valid())
        return copies[texture] = texture;
    SceneImage copy = scene.images[std::size_t(tex.image)];
    copy.name += " (sRGB-encoded)";
    copy.header = {};
    copy.encoded_bytes = 0;
    std::array<std::uint8_t, 256> encode{};
    for (int v = 0; v < 256; ++v) encode[std::size_t(v)] = std::uint8_t(std::lround(255.0f * linear_to_srgb(float(v) / 255.0f)));
    Image8& px = copy.pixels;
    for (std::size_t i = 0; i < px.pixels.size(); ++i)
        if (i % std::size_t(px.channels) < 3) px.pixels[i] = encode[px.pixels[i]];
    scene.images.push_back(std::move(copy));
    scene.textures.push_back({int(scene.images.size()) - 1, tex.sampler});
    return copies[texture] = int(scene.textures.size()) - 1;
}

void to_metallic_roughness_all(Scene& scene, Diagnostics& d, const std::string& file) {
    std::map<int, int> copies;
    for (Material& m : scene.materials) {
        if (!m.specular_glossiness) continue;
        // The textures as render reads them by default: their RGB as stored (map_srgb).
        SpecularGlossinessExt& sg = *m.specular_glossiness;
        sg.diffuse_texture.texture = srgb_encoded_copy(scene, sg.diffuse_texture.texture, copies);
        sg.specular_glossiness_texture.texture = srgb_encoded_copy(scene, sg.specular_glossiness_texture.texture, copies);
        bool lost = false;
        m = to_metallic_roughness(m, &lost);
        m.specular_glossiness.reset();
        if (lost)
            d.warn(file, m.name, "the glossiness channel of specularGlossinessTexture has no metallic-roughness form; dropped");
    }
}

// The image of a texture slot, or null.
const Image8* slot_image(const Scene& scene, const TextureSlot& slot) {
    if (!slot.valid() || std::size_t(slot.texture) >= scene.textures.size()) return nullptr;
    int image = scene.textures[std::size_t(slot.texture)].image;
    if (image < 0 || std::size_t(image) >= scene.images.size() || !scene.images[std::size_t(image)].valid()) return nullptr;
    return &scene.images[std::size_t(image)].pixels;
}

// OpenGL 1 modulates only by map_Kd, so a metallic-roughness texture's metalness would be lost
// with one Kd per material: metal texels would show their base colour as diffuse. Instead the
// fitted diffuse is baked per texel into a new map_Kd (and Kd becomes 1): the fit of the mean
// material gives Kd for the mean diffuse albedo a = base * (1 - metallic), and each texel gets
// Kd * encode(a_texel) / encode(a_mean), per channel (the fit works on display values; sRGB
// encoding makes the ratio of albedos one of encoded values). Needs both maps on the same UV
// set without transforms; the texels are matched by relative position (nearest).
bool bake_diffuse_map(Scene& scene, Material& m, const glm::vec3& kd, const glm::vec3& mean_base, float mean_metallic) {
    const Image8* mr = slot_image(scene, m.metallic_roughness);
    if (!mr) return false;
    const Image8* base = slot_image(scene, m.base_color);
    if (base && (m.base_color.tex_coord != m.metallic_roughness.tex_coord || m.base_color.has_transform ||
                 m.metallic_roughness.has_transform))
        return false;
    const int w = base ? std::max(base->width, mr->width) : mr->width, h = base ? std::max(base->height, mr->height) : mr->height;
    auto texel = [](const Image8& im, int x, int y, int w, int h) {
        return im.at(std::min(im.width - 1, x * im.width / w), std::min(im.height - 1, y * im.height / h));
    };
    const glm::vec3 factor = glm::vec3(m.base_color_factor);
    const glm::vec3 a_mean = linear_to_srgb(glm::max(mean_base * (1.0f - mean_metallic), glm::vec3(0.0f)));
    Image8 out;
    out.width = w;
    out.height = h;
    out.channels = 4;
    out.pixels.resize(std::size_t(w) * std::size_t(h) * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::vec3 c = factor;
            float alpha = 255.0f;
            if (base) {
                const std::uint8_t* b = texel(*base, x, y, w, h);
                c *= srgb_to_linear(glm::vec3(b[0], b[1], b[2]) / 255.0f);
                alpha = b[3];
            }
            const float metallic = std::clamp(m.metallic_factor * float(texel(*mr, x, y, w, h)[2]) / 255.0f, 0.0f, 1.0f);
            const glm::vec3 a = linear_to_srgb(c * (1.0f - metallic));
            std::uint8_t* o = out.at(x, y);
            for (int k = 0; k < 3; ++k) {
                float d = a_mean[k] > 1e-4f ? kd[k] * a[k] / a_mean[k] : kd[k];
                o[k] = std::uint8_t(std::lround(std::clamp(d, 0.0f, 1.0f) * 255.0f));
            }
            o[3] = std::uint8_t(alpha);
        }
    SceneImage img;
    img.name = "baked diffuse of " + m.name;
    img.pixels = std::move(out);
    scene.images.push_back(std::move(img));
    Texture t = base ? scene.textures[std::size_t(m.base_color.texture)] : scene.textures[std::size_t(m.metallic_roughness.texture)];
    t.image = int(scene.images.size()) - 1;
    scene.textures.push_back(t);
    m.base_color.texture = int(scene.textures.size()) - 1;
    m.base_color.tex_coord = m.metallic_roughness.tex_coord;
    return true;
}

// The mean linear base colour of a material (factor times its texture's mean, decoded).
glm::vec3 mean_base_color(const Scene& scene, const Material& m) {
    glm::vec3 c = glm::vec3(m.base_color_factor);
    const Image8* img = slot_image(scene, m.base_color);
    if (!img) return c;
    glm::dvec3 sum(0.0);
    std::size_t n = std::size_t(img->width) * std::size_t(img->height);
    for (std::size_t i = 0; i < n; ++i)
        sum += glm::dvec3(srgb_to_linear(glm::vec3(img->pixels[i * 4], img->pixels[i * 4 + 1], img->pixels[i * 4 + 2]) / 255.0f));
    return n ? c * glm::vec3(sum / double(n)) : c;
}

// PBR materials -> fitted Phong values in Material::phong (for the OBJ writer). A
// metallic-roughness texture enters through its mean (OBJ/MTL has no per-texel Ns); the base
// colour texture stays map_Kd, which modulates the fitted Kd as the base colour factor did.
void fit_pbr_materials(Scene& scene, bool quiet, bool bake) {
    for (Material& m : scene.materials) {
        if (m.phong) continue;  // from an OBJ: keep its own values
        fit::Pbr pbr = fit::from_material(m);
        pbr.metallic *= texture_mean(scene, m.metallic_roughness, 2);
        pbr.roughness *= texture_mean(scene, m.metallic_roughness, 1);
        m.metallic_factor = pbr.metallic;  // what the MTL's Pm / Pr say (no map_Pm / map_Pr is written)
        m.roughness_factor = pbr.roughness;
        // With a metallic-roughness texture the diffuse is baked per texel (bake_diffuse_map),
        // fitted for the mean material; otherwise map_Kd modulates Kd as the factor did.
        const bool per_texel = bake && slot_image(scene, m.metallic_roughness) != nullptr;
        glm::vec3 mean_base(0.0f);
        if (per_texel) {
            mean_base = mean_base_color(scene, m);
            pbr.base_color = glm::min(mean_base, glm::vec3(1.0f));
        }
        fit::PbrToPhong f = fit::fit_pbr_to_phong(pbr);
        PhongExt p;
        p.diffuse = f.phong.kd;
        if (per_texel && bake_diffuse_map(scene, m, f.phong.kd, mean_base, pbr.metallic)) p.diffuse = glm::vec3(1.0f);
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

// Each file of the set convert committed, with its size, and the total.
void print_written(const std::vector<fs::path>& files) {
    std::uintmax_t total = 0;
    for (const fs::path& f : files) {
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(f, ec);
        if (ec) continue;
        total += size;
        std::fprintf(stderr, "  %s  %s\n", human_bytes(size).c_str(), f.string().c_str());
    }
    if (files.size() > 1) std::fprintf(stderr, "  %s  in %zu files\n", human_bytes(total).c_str(), files.size());
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
    if (!in_obj && !out_obj && !o.rewrite) {
        // glTF -> glTF: the file as it is, in the other container (scene_writer.h's copy_gltf).
        const std::vector<fs::path> written = copy_gltf(o.input, o.output, diagnostics, o.allow_external_files);
        print_warnings(diagnostics);
        if (!o.quiet) {
            std::fprintf(stderr, "fresnel: convert: wrote %s: %s as it is, in a new container\n", o.output.c_str(), o.input.c_str());
            print_written(written);
        }
        return kExitOk;
    }
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
    std::vector<fs::path> written;
    if (out_obj) {
        fit_pbr_materials(scene, o.quiet, !o.no_diffuse_bake);
        written = write_obj(scene, o.output, diagnostics);
    } else {
        if (in_obj) fit_phong_materials(scene, o.quiet, *fit::parse_match(o.match), diagnostics, o.input);
        GltfWriteOptions wo;
        wo.area_lights = o.area_lights;
        written = write_gltf(scene, o.output, diagnostics, wo);
    }
    print_warnings(diagnostics);
    // What was written, whole (the set is committed together: fresnel/core/atomic_file.h).
    std::size_t primitives = 0, triangles = 0, images = 0;
    for (const Mesh& m : scene.meshes)
        for (const Primitive& p : m.primitives) {
            ++primitives;
            triangles += (p.indices.empty() ? p.positions.size() : p.indices.size()) / 3;
        }
    for (const SceneImage& i : scene.images) images += i.valid();
    if (!o.quiet) {
        std::fprintf(stderr, "fresnel: convert: wrote %s: %zu meshes (%zu primitives, %zu triangles), %zu materials, %zu images\n",
                     o.output.c_str(), scene.meshes.size(), primitives, triangles, scene.materials.size(), images);
        print_written(written);
    }
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
    cmd->add_flag("--rewrite", opts->rewrite,
                  "glTF -> glTF: write the file anew from fresnel's scene model (specular-glossiness becomes "
                  "metallic-roughness, tangents generated, images re-encoded as PNG), dropping what the model does "
                  "not hold (animations, skins, morph targets, extras, unknown extensions); without it the file is "
                  "kept as it is, only its container changes");
    cmd->add_flag("--area-lights", opts->area_lights,
                  "glTF output through the scene model (--rewrite): write area lights (rect, disk, sphere) as "
                  "EXT_lights_area, fresnel's extension; without it they are left out with a warning (a plain glTF -> "
                  "glTF convert keeps the file's extension data as it is)");
    cmd->add_option("--match", opts->match,
                    "OBJ -> glTF: what the fitted materials are for: albedo (Kd is the albedo, as Blender and obj2gltf "
                    "read it; roughness and specular fitted from Ks and Ns) or opengl1 (look like the OpenGL 1 render "
                    "under one light in a glTF viewer); Ks 0 gives no specular lobe either way")
        ->capture_default_str()
        ->check(CLI::IsMember({"opengl1", "albedo"}));
    cmd->add_flag("--no-diffuse-bake", opts->no_diffuse_bake,
                  "glTF -> OBJ: keep the base colour texture as map_Kd with one fitted Kd per material, instead of "
                  "baking the fitted diffuse per texel (metallic-roughness textures) into a new map_Kd");
    cmd->footer("Examples:\n"
                "  fresnel convert model.obj model.glb                      # Kd as the albedo (--match albedo)\n"
                "  fresnel convert model.obj model.glb --match opengl1      # look like the OpenGL 1 render\n"
                "  fresnel convert model.gltf model.glb                     # glTF -> glTF as it is, one file\n"
                "  fresnel convert model.glb model.obj                      # fitted Kd/Ks/Ns\n"
                "\nPhong materials are fitted to metallic-roughness (and back) by fresnel/material/fit.h; glTF -> glTF\n"
                "keeps the file as it is (--rewrite: through the scene model, specular-glossiness becoming\n"
                "metallic-roughness + KHR_materials_specular).");
    return [opts]() { return run_convert(*opts); };
}

}  // namespace fresnel::cli
