#pragma once
// Fitted conversion between Phong-era materials (MTL Kd/Ks/Ns as OpenGL 1 shades them) and
// glTF metallic-roughness, by least squares over what the two render, not by a formula.
//
// The two sides, each the library's one truth:
//   Phong: OpenGL 1 fixed-function lighting (legacy::ogl1_light), one directional light of
//          colour 1, no ambient, GL_SINGLE_COLOR, shininess clamped to 128; the display
//          value is clamp(Kd n.l + [n.l > 0] (n.h)^Ns Ks, 0, 1), written with no encoding.
//   PBR:   the glTF BRDF (brdf::evaluate, KHR_materials_specular included) lit by a
//          KHR_lights_punctual directional light of pi lux (what an OpenGL light of colour 1
//          becomes in issue 10's protocol), no image-based light, tone mapping none, sRGB
//          encoding; the display value is linear_to_srgb(clamp(pi f n.l, 0, 1)).
//          Multiple-scattering energy compensation is not modelled (it brightens rough
//          metals by up to ~1.3x in the renderer).
// The error is the difference of the display values, per channel, over a fixed set of
// light and view directions around a normal: views at six elevations (5..80 degrees; weight
// n.v, the share of a rendered surface's pixels that face the camera at that angle), lights
// on a cosine-weighted stratified grid over the hemisphere (fit_samples()). The residual is
// the weighted RMS of that difference (0..1 display units) and its PSNR, 20 log10(1 / rms).
//
// Image-based light. A converted model is mostly seen under an environment, so Phong -> PBR
// fits three lightings at a third of the weight each: the one light above; a uniform
// environment alone at two levels (radiance 0.5 and 1, per view); and the light at 0.6 with a
// uniform environment at 0.4 (per sample). OpenGL 1 under an environment is read as its
// lighting summed over lights from every direction (colour dw / pi each), clamped once and
// written raw: Kd plus Ks times the integral of its highlight / pi; the PBR side is the BRDF's
// directional albedo, sRGB-encoded. Without that, a highlight fitted to one light's peak
// (OpenGL 1's (n.h)^Ns is not energy-normalised) reflects several times the light OpenGL 1
// would under an environment. bench/peer_report_ibl.py measures the result under a real one.
//
// Phong -> PBR (fit_phong_to_pbr) solves for base colour, metallic, roughness, the
// KHR_materials_specular F0 colour (specularColorFactor = F0 / 0.04) and specularFactor; the
// extension is kept only where it lowers the residual by more than 1 % (`uses_specular`).
// PBR -> Phong (fit_pbr_to_phong) solves for Kd, Ks and Ns (0..128). Both scan roughness
// (or log(1 + Ns)) coarsely over the whole range, with the precomputed table's value as one
// more candidate (table_roughness / table_shininess below: libs/material/src/fit_table.inc,
// written by tools/fit_table_gen, the same fit over a grid without the table), refine the
// best by golden-section search, and solve the colours per channel (Nelder-Mead) at each
// step; metallic and specularFactor are searched the same way. The error curves have
// several minima (sRGB encoding against OpenGL 1's unencoded output makes the best fit trade
// diffuse against a broad highlight), so the result is the best found, not a proven optimum. Everything is deterministic: the same input gives the same
// numbers on every machine that rounds floats the same way.
//
// Specular-glossiness -> metallic-roughness (fit_specular_glossiness) is exact (evaluate.h:
// the specular-glossiness BRDF is the dielectric branch with F0 = specular); its residual
// is measured by the same machinery and is 0 up to float rounding.
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "fresnel/material/material.h"

namespace fresnel::fit {

struct Phong {
    glm::vec3 kd{0.8f};
    glm::vec3 ks{0.0f};
    float ns = 0.0f;
};

struct Pbr {
    glm::vec3 base_color{1.0f};
    float metallic = 0.0f;
    float roughness = 1.0f;
    // KHR_materials_specular: F0 colour of the dielectric (0.04 * specularColorFactor at
    // ior 1.5, each channel <= 1) and specularFactor.
    glm::vec3 specular_f0{0.04f};
    float specular_weight = 1.0f;
    bool uses_specular() const { return specular_weight != 1.0f || specular_f0 != glm::vec3(0.04f); }
};

struct Residual {
    float rms = 0.0f;       // weighted RMS of the display-value difference, 0..1
    float max = 0.0f;       // largest difference over the samples
    float psnr_db = 99.0f;  // 20 log10(1 / rms), 99 when rms is 0
};

struct PhongToPbr {
    Pbr pbr;
    Residual residual;          // of the fit, under the one light
    Residual image_based;       // of the fit, under the image-based parts of the objective
    Pbr formula;                // phong_to_metallic_roughness's values (phong.h)
    Residual formula_residual;  // of the formula
};
struct PbrToPhong {
    Phong phong;
    Residual residual;
    Phong naive;                // Kd = base colour, Ks = 0.04, Ns = roughness_to_phong_shininess
    Residual naive_residual;
};

// One (light, view) pair around the normal (0, 0, 1) and its weight (weights sum to 1).
struct Sample {
    glm::vec3 l, v;
    float weight;
};
const std::vector<Sample>& fit_samples();

// Display values on both sides for one sample (legacy_shading.h and brdf.h underneath).
glm::vec3 phong_display(const Phong& p, const Sample& s);
glm::vec3 pbr_display(const Pbr& p, const Sample& s);

// The residual of rendering `pbr` where `phong` was meant (the same function both ways), under
// the one light.
Residual residual(const Phong& phong, const Pbr& pbr);
// The same under image-based light: the uniform environment alone and the light with it
// (the objective's image-based parts, their weights normalised to 1).
Residual residual_image_based(const Phong& phong, const Pbr& pbr);
// What the image-based parts are made of, at the fit's view directions (view_at(i), i <
// view_count(), around the normal (0, 0, 1)): the linear radiance a uniform environment of
// radiance 1 gives back. PBR: the BRDF's directional albedo (cosine samples for the diffuse
// part, GGX samples for the lobes). Phong: OpenGL 1 lit from every direction by lights of
// colour dw / pi (Kd + Ks times the highlight's integral / pi), unclamped.
int view_count();
glm::vec3 view_at(int view);
glm::vec3 uniform_environment(const Pbr& p, int view);
glm::vec3 uniform_environment(const Phong& p, int view);
// Same-model residuals, for round trips (Phong -> PBR -> Phong, PBR -> Phong -> PBR).
Residual residual(const Phong& a, const Phong& b);
Residual residual(const Pbr& a, const Pbr& b);

PhongToPbr fit_phong_to_pbr(const Phong& phong);
PbrToPhong fit_pbr_to_phong(const Pbr& pbr);

// What a Phong -> PBR conversion is for (`--match` of fit and convert):
//   OpenGl1: look like the OpenGL 1 render of the MTL in a glTF viewer (fit_phong_to_pbr: the
//            least-squares fit above, the one light and image-based light). A material without specular (Ks 0) gets no
//            specular lobe (specularFactor 0, roughness 1): matte under any light, never a
//            mirror.
//   Albedo:  Kd is the albedo, as Blender and obj2gltf read it: base colour Kd, dielectric;
//            the highlight alone (Ks, Ns with Kd 0) fitted for roughness and the specular F0
//            colour (KHR_materials_specular), linear (no sRGB encoding on the PBR side: the
//            MTL's numbers read as Kd is) under the one light and image-based light; Ks 0: no
//            specular lobe.
// Inputs are clamped to [0, 1] (Kd, Ks) and [0, 128] (Ns) as OpenGL 1 does; callers warn.
enum class Match { OpenGl1, Albedo };
PhongToPbr fit_phong_to_pbr(const Phong& phong, Match match);
const char* match_name(Match m);
std::optional<Match> parse_match(const std::string& name);  // "opengl1", "albedo"

struct SpecularGlossinessToPbr {
    Pbr pbr;
    Residual residual;  // specular-glossiness BRDF against the metallic-roughness one
};
SpecularGlossinessToPbr fit_specular_glossiness(glm::vec3 diffuse, glm::vec3 specular, float glossiness);

// The precomputed table: the fitted roughness for Ns (a grey reference material, Kd 0.5,
// Ks 0.5) and the fitted Ns for a roughness (base 0.5, dielectric), interpolated.
float table_roughness(float ns);
float table_shininess(float roughness);

// For tools/fit_table_gen: the fits with the full search range instead of the table's.
PhongToPbr fit_phong_to_pbr_full(const Phong& phong);
PbrToPhong fit_pbr_to_phong_full(const Pbr& pbr);
// The grids the table is tabulated on.
inline constexpr int kTableSize = 33;
float table_ns_at(int i);         // 0 .. 128, denser at low Ns
float table_roughness_at(int i);  // 0.05 .. 1

// Material-level helpers for converters. from_material reads the factors (base colour,
// metallic, roughness, KHR_materials_specular) of a metallic-roughness material;
// apply_pbr writes a fitted Pbr into one (adding or removing KHR_materials_specular).
Pbr from_material(const Material& m);
void apply_pbr(const Pbr& p, Material& m);

}  // namespace fresnel::fit
