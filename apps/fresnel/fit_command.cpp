// `fresnel fit --phong KD,KS,NS | --pbr BASE,METALLIC,ROUGHNESS | --specgloss DIFFUSE,SPECULAR,GLOSSINESS
// [--json]`: the fitted conversion of fresnel/material/fit.h for one material, with the
// residual (display-value RMS over light and view directions, and its PSNR) of the fit, of
// the simple formula it replaces, and of the round trip back. Colours are one grey value or
// R:G:B (KD as 0.8:0.2:0.1).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/material/fit.h"

namespace fresnel::cli {

namespace {

struct FitOptions {
    std::string phong, pbr, specgloss;
    std::string match = "albedo";
    bool json = false;
};

// Values outside what OpenGL 1 shades (Kd, Ks in [0, 1], Ns in [0, 128]) are clamped by the
// fit; said once per value, on stderr.
void warn_out_of_range(const fit::Phong& p) {
    auto colour = [](const char* name, const glm::vec3& c) {
        if (glm::any(glm::lessThan(c, glm::vec3(0.0f))) || glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
            std::fprintf(stderr, "fresnel: warning: --phong: %s outside [0, 1] is clamped (OpenGL 1 clamps it)\n", name);
    };
    colour("KD", p.kd);
    colour("KS", p.ks);
    if (p.ns < 0.0f || p.ns > 128.0f)
        std::fprintf(stderr, "fresnel: warning: --phong: NS outside [0, 128] is clamped (OpenGL 1's range)\n");
}

// "a,b,c" where each item is a number or R:G:B.
std::vector<glm::vec3> parse_items(const std::string& text, size_t count, const char* flag) {
    std::vector<glm::vec3> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        std::vector<float> parts;
        std::stringstream is(item);
        std::string part;
        while (std::getline(is, part, ':')) {
            try {
                size_t used = 0;
                float v = std::stof(part, &used);
                if (used != part.size() || !std::isfinite(v)) throw std::invalid_argument(part);
                parts.push_back(v);
            } catch (const std::exception&) {
                throw Error("", std::string(flag), "not a number: '" + part + "'");
            }
        }
        if (parts.size() == 1) out.emplace_back(parts[0]);
        else if (parts.size() == 3) out.emplace_back(parts[0], parts[1], parts[2]);
        else throw Error("", std::string(flag), "'" + item + "' is neither a number nor R:G:B");
    }
    if (out.size() != count) throw Error("", std::string(flag), "expected " + std::to_string(count) + " comma-separated values");
    return out;
}

nlohmann::json vec(const glm::vec3& v) { return {v.x, v.y, v.z}; }
nlohmann::json json_of(const fit::Residual& r) { return {{"rms", r.rms}, {"max", r.max}, {"psnr_db", r.psnr_db}}; }
nlohmann::json json_of(const fit::Phong& p) { return {{"Kd", vec(p.kd)}, {"Ks", vec(p.ks)}, {"Ns", p.ns}}; }
nlohmann::json json_of(const fit::Pbr& p) {
    nlohmann::json j = {{"baseColor", vec(p.base_color)}, {"metallic", p.metallic}, {"roughness", p.roughness}};
    if (p.uses_specular())
        j["KHR_materials_specular"] = {{"specularFactor", p.specular_weight},
                                       {"specularColorFactor", vec(p.specular_f0 / 0.04f)}};
    return j;
}

std::string text(const glm::vec3& v) {
    char buf[96];
    if (v.x == v.y && v.y == v.z) std::snprintf(buf, sizeof buf, "%.4g", double(v.x));
    else std::snprintf(buf, sizeof buf, "%.4g:%.4g:%.4g", double(v.x), double(v.y), double(v.z));
    return buf;
}
std::string text(const fit::Phong& p) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4g", double(p.ns));
    return "Kd " + text(p.kd) + "  Ks " + text(p.ks) + "  Ns " + buf;
}
std::string text(const fit::Pbr& p) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "  metallic %.4g  roughness %.4g", double(p.metallic), double(p.roughness));
    std::string s = "baseColor " + text(p.base_color) + buf;
    if (p.uses_specular()) {
        std::snprintf(buf, sizeof buf, "%.4g", double(p.specular_weight));
        s += "  KHR_materials_specular: specularFactor " + std::string(buf) + " specularColorFactor " +
             text(p.specular_f0 / 0.04f);
    }
    return s;
}
std::string text(const fit::Residual& r) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "rms %.4f (%.1f dB), max %.3f", double(r.rms), double(r.psnr_db), double(r.max));
    return buf;
}

int run_fit(const FitOptions& o) {
    int given = int(!o.phong.empty()) + int(!o.pbr.empty()) + int(!o.specgloss.empty());
    if (given != 1) {
        print_error("fit: give exactly one of --phong, --pbr, --specgloss");
        return kExitUsage;
    }
    nlohmann::json j;
    if (!o.phong.empty()) {
        auto v = parse_items(o.phong, 3, "--phong");
        fit::Phong p{v[0], v[1], v[2].x};
        warn_out_of_range(p);
        const fit::Match match = *fit::parse_match(o.match);
        fit::PhongToPbr f = fit::fit_phong_to_pbr(p, match);
        fit::PbrToPhong back = fit::fit_pbr_to_phong(f.pbr);
        fit::Residual trip = fit::residual(p, back.phong);
        if (o.json) {
            j = {{"phong", json_of(p)},
                 {"match", fit::match_name(match)},
                 {"fitted", json_of(f.pbr)},
                 {"residual", json_of(f.residual)},
                 {"image_based_residual", json_of(f.image_based)},
                 {"formula", json_of(f.formula)},
                 {"formula_residual", json_of(f.formula_residual)},
                 {"formula_image_based_residual", json_of(fit::residual_image_based(p, f.formula))},
                 {"round_trip", json_of(back.phong)},
                 {"round_trip_residual", json_of(trip)}};
        } else {
            std::printf("Phong            %s\n", text(p).c_str());
            const char* note = match == fit::Match::Albedo ? " (to the OpenGL 1 look; --match albedo keeps Kd)" : "";
            std::printf("fitted PBR       %s\n  residual       %s%s\n  image-based    %s\n", text(f.pbr).c_str(),
                        text(f.residual).c_str(), note, text(f.image_based).c_str());
            std::printf("formula PBR      %s\n  residual       %s\n  image-based    %s\n", text(f.formula).c_str(),
                        text(f.formula_residual).c_str(), text(fit::residual_image_based(p, f.formula)).c_str());
            std::printf("round trip       %s\n  vs the Phong   %s\n", text(back.phong).c_str(), text(trip).c_str());
        }
    } else if (!o.pbr.empty()) {
        auto v = parse_items(o.pbr, 3, "--pbr");
        fit::Pbr p;
        p.base_color = v[0];
        p.metallic = std::clamp(v[1].x, 0.0f, 1.0f);
        p.roughness = std::clamp(v[2].x, 0.0f, 1.0f);
        fit::PbrToPhong f = fit::fit_pbr_to_phong(p);
        fit::PhongToPbr back = fit::fit_phong_to_pbr(f.phong);
        fit::Residual trip = fit::residual(p, back.pbr);
        if (o.json) {
            j = {{"pbr", json_of(p)},
                 {"fitted", json_of(f.phong)},
                 {"residual", json_of(f.residual)},
                 {"naive", json_of(f.naive)},
                 {"naive_residual", json_of(f.naive_residual)},
                 {"round_trip", json_of(back.pbr)},
                 {"round_trip_residual", json_of(trip)}};
        } else {
            std::printf("PBR              %s\n", text(p).c_str());
            std::printf("fitted Phong     %s\n  residual       %s\n", text(f.phong).c_str(), text(f.residual).c_str());
            std::printf("naive Phong      %s\n  residual       %s\n", text(f.naive).c_str(),
                        text(f.naive_residual).c_str());
            std::printf("round trip       %s\n  vs the PBR     %s\n", text(back.pbr).c_str(), text(trip).c_str());
        }
    } else {
        auto v = parse_items(o.specgloss, 3, "--specgloss");
        fit::SpecularGlossinessToPbr f = fit::fit_specular_glossiness(v[0], v[1], v[2].x);
        if (o.json) {
            j = {{"specular_glossiness", {{"diffuse", vec(v[0])}, {"specular", vec(v[1])}, {"glossiness", v[2].x}}},
                 {"fitted", json_of(f.pbr)},
                 {"residual", json_of(f.residual)}};
        } else {
            std::printf("specular-glossiness  diffuse %s  specular %s  glossiness %.4g\n", text(v[0]).c_str(),
                        text(v[1]).c_str(), double(v[2].x));
            std::printf("metallic-roughness   %s\n  residual           %s\n", text(f.pbr).c_str(),
                        text(f.residual).c_str());
        }
    }
    if (o.json) std::printf("%s\n", j.dump(2).c_str());
    return kExitOk;
}

}  // namespace

Runner add_fit_command(CLI::App& app) {
    auto opts = std::make_shared<FitOptions>();
    CLI::App* cmd = app.add_subcommand(
        "fit", "Fitted Phong <-> metallic-roughness conversion of one material, with residuals (fresnel/material/fit.h)");
    cmd->add_option("--phong", opts->phong, "KD,KS,NS: an MTL/OpenGL 1 material to fit in metallic-roughness");
    cmd->add_option("--pbr", opts->pbr, "BASE,METALLIC,ROUGHNESS: a glTF material to fit in Phong");
    cmd->add_option("--specgloss", opts->specgloss,
                    "DIFFUSE,SPECULAR,GLOSSINESS: a KHR_materials_pbrSpecularGlossiness material to convert");
    cmd->add_option("--match", opts->match,
                    "--phong's intent: albedo (KD is the albedo, as Blender and obj2gltf read it; roughness and "
                    "specular fitted from KS and NS) or opengl1 (look like the OpenGL 1 render under one light in a "
                    "glTF viewer); KS 0 gives no specular lobe either way")
        ->capture_default_str()
        ->check(CLI::IsMember({"opengl1", "albedo"}));
    cmd->add_flag("--json", opts->json, "Print JSON instead of text");
    cmd->footer("Examples:\n"
                "  fresnel fit --phong 0.5:0.1:0.1,0.5,32                   # Kd, Ks, Ns -> metallic-roughness\n"
                "  fresnel fit --pbr 0.8,1,0.3 --json                       # base, metallic, roughness -> Phong\n"
                "\nColours are one grey value or R:G:B. Residual: RMS of the display-value difference over light and\n"
                "view directions (cosine-weighted, six view elevations), with its PSNR.");
    return [opts]() { return run_fit(*opts); };
}

}  // namespace fresnel::cli
