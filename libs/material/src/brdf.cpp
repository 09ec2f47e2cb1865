#include "fresnel/material/brdf.h"

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
