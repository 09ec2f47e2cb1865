#include "fresnel/trace/environment_light.h"

#include <algorithm>
#include <cmath>

#include "fresnel/core/error.h"
#include "fresnel/ibl/cubemap.h"

namespace fresnel::trace {

namespace {
constexpr float kPi = 3.14159265358979323846f;
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
}  // namespace

EnvironmentLight::EnvironmentLight(ImageF panorama, float rotation_deg, float intensity)
    : panorama_(std::move(panorama)), intensity_(intensity) {
    if (panorama_.width < 1 || panorama_.height < 1) throw Error("environment", "", "empty panorama");
    // The renderer's rotation (renderer.cpp, env_rotation): world -> environment by -angle about +Y.
    float a = -rotation_deg * kPi / 180.0f;
    float c = std::cos(a), s = std::sin(a);
    to_env_ = glm::mat3(c, 0, -s, 0, 1, 0, s, 0, c);
    to_world_ = glm::transpose(to_env_);
    const int w = panorama_.width, h = panorama_.height;
    std::vector<float> weights(std::size_t(w) * h);
    double sum = 0;
    for (int y = 0; y < h; ++y) {
        float sin_t = std::sin((float(y) + 0.5f) / float(h) * kPi);
        for (int x = 0; x < w; ++x) {
            const float* p = panorama_.at(x, y);
            // Bilinear lookups reach into the neighbours: weigh each pixel by the brightest of
            // its 3x3 neighbourhood so that no lit direction has a zero density.
            float m = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int yy = std::clamp(y + dy, 0, h - 1), xx = ((x + dx) % w + w) % w;
                    const float* q = panorama_.at(xx, yy);
                    m = std::max(m, luminance({q[0], q[1], q[2]}));
                }
            float l = 0.5f * (luminance({p[0], p[1], p[2]}) + m);
            weights[std::size_t(y) * w + x] = l * sin_t;
            sum += l * sin_t;
        }
    }
    // A floor of 1e-3 of the mean keeps dark regions reachable at negligible cost.
    float floor_w = float(sum / double(weights.size())) * 1e-3f;
    for (int y = 0; y < h; ++y) {
        float sin_t = std::sin((float(y) + 0.5f) / float(h) * kPi);
        for (int x = 0; x < w; ++x) weights[std::size_t(y) * w + x] += floor_w * sin_t;
    }
    distribution_ = Distribution2D(weights, w, h);
}

glm::vec3 EnvironmentLight::lookup(glm::vec2 uv) const {
    // Bilinear, wrapping in u and clamped in v (the panorama as a linear-filtered texture).
    const int w = panorama_.width, h = panorama_.height;
    float fu = uv.x * float(w) - 0.5f, fv = uv.y * float(h) - 0.5f;
    float x0f = std::floor(fu), y0f = std::floor(fv);
    float a = fu - x0f, b = fv - y0f;
    int x0 = int(x0f), y0 = int(y0f);
    int xa = ((x0 % w) + w) % w, xb = (((x0 + 1) % w) + w) % w;
    int ya = std::clamp(y0, 0, h - 1), yb = std::clamp(y0 + 1, 0, h - 1);
    const float *p00 = panorama_.at(xa, ya), *p10 = panorama_.at(xb, ya);
    const float *p01 = panorama_.at(xa, yb), *p11 = panorama_.at(xb, yb);
    glm::vec3 r;
    for (int i = 0; i < 3; ++i)
        r[i] = (1 - a) * (1 - b) * p00[i] + a * (1 - b) * p10[i] + (1 - a) * b * p01[i] + a * b * p11[i];
    return r * intensity_;
}

glm::vec3 EnvironmentLight::radiance(glm::vec3 dir) const {
    return lookup(ibl::direction_to_equirect(to_env_ * dir));
}

EnvironmentLight::Sample EnvironmentLight::sample(glm::vec2 u) const {
    Sample s;
    float pdf_uv = 0;
    glm::vec2 uv = distribution_.sample(u, pdf_uv);
    float sin_t = std::sin(uv.y * kPi);
    if (pdf_uv <= 0.0f || sin_t <= 0.0f) return s;
    s.direction = to_world_ * ibl::equirect_to_direction(uv);
    s.pdf = pdf_uv / (2.0f * kPi * kPi * sin_t);
    s.radiance = lookup(uv);
    return s;
}

float EnvironmentLight::pdf(glm::vec3 dir) const {
    glm::vec3 e = to_env_ * dir;
    glm::vec2 uv = ibl::direction_to_equirect(e);
    float sin_t = std::sqrt(std::max(0.0f, 1.0f - e.y * e.y));
    if (sin_t <= 0.0f) return 0.0f;
    return distribution_.pdf(uv) / (2.0f * kPi * kPi * sin_t);
}

}  // namespace fresnel::trace
