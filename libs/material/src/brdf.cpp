#include "fresnel/material/brdf.h"

namespace fresnel::brdf {

glm::vec3 directional_albedo(const Surface& s, float n_dot_v, int samples_per_axis) {
    // Integrate in (cos theta, phi) so the cosine-weighted measure is uniform:
    // dw = d(cos theta) d(phi), and f * cos theta is evaluated at cell centres.
    const glm::vec3 n(0, 0, 1);
    n_dot_v = std::clamp(n_dot_v, 1e-4f, 1.0f);
    const glm::vec3 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
    glm::dvec3 sum(0.0);
    const int n_theta = samples_per_axis, n_phi = samples_per_axis;
    for (int i = 0; i < n_theta; ++i) {
        // Concentrate samples near the pole where the specular lobe lives: cos theta = 1 - u^2.
        double u0 = double(i) / n_theta, u1 = double(i + 1) / n_theta, u = (i + 0.5) / n_theta;
        double cos_t = 1.0 - u * u;
        double dcos = (1.0 - u0 * u0) - (1.0 - u1 * u1);
        double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
        for (int j = 0; j < n_phi; ++j) {
            double phi = 2.0 * 3.141592653589793 * (j + 0.5) / n_phi;
            glm::vec3 l(float(sin_t * std::cos(phi)), float(sin_t * std::sin(phi)), float(cos_t));
            glm::vec3 f = evaluate(s, n, v, l);
            sum += glm::dvec3(f) * cos_t * dcos * (2.0 * 3.141592653589793 / n_phi);
        }
    }
    return glm::vec3(sum);
}

}  // namespace fresnel::brdf
