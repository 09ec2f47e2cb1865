#include "fresnel/material/brdf.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include "fresnel/material/sampling.h"

namespace fresnel::brdf {

glm::vec3 directional_albedo(const Surface& s, float n_dot_v, int samples_per_axis) {
    // A deterministic quadrature in the visible-normal sampling domain: a regular
    // grid of midpoints u in [0,1]^2 mapped to half vectors h, reflected to l,
    // weighted by f cos / pdf, with f from evaluate_terms(). Concentrates points
    // where the specular lobe lives for every roughness and view angle (a plain
    // hemisphere grid misses lobes narrower than its spacing). Float precision
    // limits it to perceptual roughness >= ~0.05.
    // The diffuse part is integrated separately on a cosine-weighted grid.
    const glm::vec3 n(0, 0, 1);
    n_dot_v = std::clamp(n_dot_v, 1e-4f, 1.0f);
    const glm::vec3 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
    const float alpha = alpha_from_roughness(s.perceptual_roughness);
    const int n_axis = samples_per_axis;
    glm::dvec3 spec(0.0), diff(0.0);
    for (int i = 0; i < n_axis; ++i)
        for (int j = 0; j < n_axis; ++j) {
            glm::vec2 u((float(i) + 0.5f) / float(n_axis), (float(j) + 0.5f) / float(n_axis));
            // Specular: h from the visible normals of v, l = reflect(-v, h), pdf(l) = pdf_vndf(h) / (4 v.h).
            glm::vec3 h = sampling::sample_ggx_vndf(v, u, alpha);
            float v_dot_h = glm::dot(v, h);
            if (v_dot_h > 0.0f) {
                glm::vec3 l = 2.0f * v_dot_h * h - v;
                if (l.z > 0.0f) {
                    float pdf = sampling::pdf_ggx_vndf(v, h, alpha) / (4.0f * v_dot_h);
                    if (pdf > 0.0f) spec += glm::dvec3(evaluate_terms(s, n, v, l).specular) * double(l.z / pdf);
                }
            }
            // Diffuse: cosine-weighted l, pdf = cos / pi.
            glm::vec3 l = sampling::sample_cosine(u);
            if (l.z > 0.0f) diff += glm::dvec3(evaluate_terms(s, n, v, l).diffuse) * double(kPi);
        }
    double count = double(n_axis) * double(n_axis);
    return glm::vec3((spec + diff) / count);
}

float sheen_albedo_integral(float n_dot_v, float sheen_roughness, int samples_per_axis) {
    // Cosine-weighted l: f cos / pdf = D V pi. The Charlie lobe is broad (its peak is at
    // grazing half vectors), so a regular grid in the cosine domain resolves it at every roughness.
    n_dot_v = std::clamp(n_dot_v, 1e-4f, 1.0f);
    const glm::vec3 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
    const int n_axis = samples_per_axis;
    double sum = 0.0;
    for (int i = 0; i < n_axis; ++i)
        for (int j = 0; j < n_axis; ++j) {
            glm::vec2 u((float(i) + 0.5f) / float(n_axis), (float(j) + 0.5f) / float(n_axis));
            glm::vec3 l = sampling::sample_cosine(u);
            if (l.z <= 0.0f) continue;
            glm::vec3 h = glm::normalize(l + v);
            float n_dot_h = std::clamp(h.z, 0.0f, 1.0f);
            sum += double(d_charlie(sheen_roughness, n_dot_h) * v_sheen(l.z, n_dot_v, sheen_roughness) * kPi);
        }
    return float(sum / (double(n_axis) * double(n_axis)));
}

float SheenAlbedoTable::column_n_dot_v(int column, int size) {
    // The split-sum table's first column holds n.v = 0.5 / 1024 (ibl::kBrdfLutGrazingNdotV).
    return column == 0 ? 0.5f / 1024.0f : (float(column) + 0.5f) / float(size);
}

SheenAlbedoTable::SheenAlbedoTable(int size, int samples_per_axis) : size_(size), values_(std::size_t(size * size)) {
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i)
            values_[std::size_t(j) * std::size_t(size) + std::size_t(i)] =
                sheen_albedo_integral(column_n_dot_v(i, size), (float(j) + 0.5f) / float(size), samples_per_axis);
}

float SheenAlbedoTable::operator()(float n_dot_v, float sheen_roughness) const {
    // GL's LINEAR filter with CLAMP_TO_EDGE at (u, v) = (n.v, r).
    float fx = std::clamp(std::clamp(n_dot_v, 0.0f, 1.0f) * float(size_) - 0.5f, 0.0f, float(size_ - 1));
    float fy = std::clamp(std::clamp(sheen_roughness, 0.0f, 1.0f) * float(size_) - 0.5f, 0.0f, float(size_ - 1));
    int x0 = int(fx), y0 = int(fy);
    int x1 = std::min(x0 + 1, size_ - 1), y1 = std::min(y0 + 1, size_ - 1);
    float ax = fx - float(x0), ay = fy - float(y0);
    float top = at(x0, y0) * (1.0f - ax) + at(x1, y0) * ax;
    float bottom = at(x0, y1) * (1.0f - ax) + at(x1, y1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

const SheenAlbedoTable& SheenAlbedoTable::standard() {
    static const SheenAlbedoTable table;  // immutable once built (thread-safe initialisation)
    return table;
}

}  // namespace fresnel::brdf

namespace fresnel::brdf {

namespace {
glm::vec3 sq(glm::vec3 x) { return x * x; }
float sq(float x) { return x * x; }
// ((a - b) / (a + b))^2: the normal-incidence reflectance between iors a and b.
glm::vec3 ior_pair_f0(glm::vec3 a, float b) { return sq((a - b) / (a + b)); }
float ior_pair_f0(float a, float b) { return sq((a - b) / (a + b)); }
}  // namespace

glm::vec3 iridescence_sensitivity(float opd, glm::vec3 shift) {
    // Belcour & Barla's Gaussian fit of the XYZ matching functions, evaluated in Fourier
    // space at phase 2 pi opd (opd in nm, so 1e-9 m), with a second lobe for X's blue bump.
    const float phase = 2.0f * kPi * opd * 1.0e-9f;
    const glm::vec3 val(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
    const glm::vec3 pos(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
    const glm::vec3 var(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
    glm::vec3 xyz;
    for (int i = 0; i < 3; ++i)
        xyz[i] = val[i] * std::sqrt(2.0f * kPi * var[i]) * std::cos(pos[i] * phase + shift[i]) *
                 std::exp(-sq(phase) * var[i]);
    xyz.x += 9.7470e-14f * std::sqrt(2.0f * kPi * 4.5282e+09f) * std::cos(2.2399e+06f * phase + shift.x) *
             std::exp(-4.5282e+09f * sq(phase));
    xyz /= 1.0685e-7f;
    // CIE XYZ -> linear Rec.709 (sRGB primaries, D65).
    return {3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
            -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
            0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z};
}

glm::vec3 iridescence_fresnel(float outside_ior, float film_ior, float cos_theta1, float thickness,
                              glm::vec3 base_f0) {
    // The film's ior, eased to the outside's as the film vanishes.
    const float t = std::clamp(thickness / 0.03f, 0.0f, 1.0f);
    const float eta2 = outside_ior + (film_ior - outside_ior) * (t * t * (3.0f - 2.0f * t));
    // Snell's law into the film; none gets in beyond the critical angle.
    const float cos2_theta2 = 1.0f - sq(outside_ior / eta2) * (1.0f - sq(cos_theta1));
    if (cos2_theta2 < 0.0f) return glm::vec3(1.0f);
    const float cos_theta2 = std::sqrt(cos2_theta2);

    // Outside -> film: Schlick reflectance, transmission both ways, and the phase shifts
    // (pi on reflection off the denser side).
    const float r12 = f_schlick(ior_pair_f0(eta2, outside_ior), 1.0f, cos_theta1);
    const float t121 = 1.0f - r12;
    const float phi12 = eta2 < outside_ior ? kPi : 0.0f;
    const float phi21 = kPi - phi12;
    // Film -> base: the base's ior from its F0 (a dielectric's notion, used for metals too).
    const glm::vec3 sqrt_f0 = glm::sqrt(glm::clamp(base_f0, 0.0f, 0.9999f));
    const glm::vec3 eta3 = (1.0f + sqrt_f0) / (1.0f - sqrt_f0);
    const glm::vec3 r23 = f_schlick(ior_pair_f0(eta3, eta2), glm::vec3(1.0f), cos_theta2);
    glm::vec3 phi23(0.0f);
    for (int i = 0; i < 3; ++i)
        if (eta3[i] < eta2) phi23[i] = kPi;

    // The Airy sum: the m = 0 term (no interference) plus orders 1 and 2, each weighted by
    // the sensitivity at m times the optical path difference and m times the phase.
    const float opd = 2.0f * eta2 * thickness * cos_theta2;
    const glm::vec3 phi = glm::vec3(phi21) + phi23;
    const glm::vec3 r123 = glm::clamp(r12 * r23, 1e-5f, 0.9999f);
    const glm::vec3 sqrt_r123 = glm::sqrt(r123);
    const glm::vec3 rs = sq(t121) * r23 / (1.0f - r123);
    glm::vec3 result = r12 + rs;
    glm::vec3 cm = rs - t121;
    for (int m = 1; m <= 2; ++m) {
        cm *= sqrt_r123;
        result += cm * 2.0f * iridescence_sensitivity(float(m) * opd, float(m) * phi);
    }
    return glm::max(result, glm::vec3(0.0f));
}

IridescenceFresnel iridescence_at(float factor, float film_ior, float thickness, float n_dot_v,
                                  glm::vec3 f0_dielectric, glm::vec3 base_color) {
    IridescenceFresnel film;
    if (!(factor > 0.0f) || !(thickness > 0.0f)) return film;
    film.factor = factor;
    film.dielectric = iridescence_fresnel(1.0f, film_ior, n_dot_v, thickness, f0_dielectric);
    film.metal = iridescence_fresnel(1.0f, film_ior, n_dot_v, thickness, base_color);
    return film;
}

}  // namespace fresnel::brdf
