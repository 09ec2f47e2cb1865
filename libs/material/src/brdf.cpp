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

}  // namespace fresnel::brdf
