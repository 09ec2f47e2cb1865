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
            float l = luminance({p[0], p[1], p[2]});
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
    alias_ = AliasTable(weights);
    texels_.resize(weights.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float* p = panorama_.at(x, y);
            std::size_t i = std::size_t(y) * w + x;
            texels_[i].radiance = glm::vec3(p[0], p[1], p[2]) * intensity_;
            texels_[i].pdf = float(alias_.probability(int(i)) * double(weights.size()));
        }
}

const EnvironmentLight::Texel& EnvironmentLight::texel_at(glm::vec2 uv) const {
    const int w = panorama_.width, h = panorama_.height;
    int x = std::clamp(int(uv.x * float(w)), 0, w - 1), y = std::clamp(int(uv.y * float(h)), 0, h - 1);
    return texels_[std::size_t(y) * w + x];
}

glm::vec3 EnvironmentLight::radiance(glm::vec3 dir) const {
    return texel_at(ibl::direction_to_equirect(to_env_ * dir)).radiance;
}

EnvironmentLight::Sample EnvironmentLight::sample(glm::vec2 u) const {
    Sample s;
    float jx = 0;
    int i = alias_.sample(u.x, jx);
    const Texel& t = texels_[std::size_t(i)];
    const int w = panorama_.width, h = panorama_.height;
    glm::vec2 uv((float(i % w) + jx) / float(w), (float(i / w) + u.y) / float(h));
    float sin_t = std::sin(uv.y * kPi);
    if (t.pdf <= 0.0f || sin_t <= 0.0f) return s;
    s.direction = to_world_ * ibl::equirect_to_direction(uv);
    s.pdf = t.pdf / (2.0f * kPi * kPi * sin_t);
    s.radiance = t.radiance;
    return s;
}

float EnvironmentLight::pdf(glm::vec3 dir) const {
    glm::vec3 e = to_env_ * dir;
    float sin_t = std::sqrt(std::max(0.0f, 1.0f - e.y * e.y));
    if (sin_t <= 0.0f) return 0.0f;
    return texel_at(ibl::direction_to_equirect(e)).pdf / (2.0f * kPi * kPi * sin_t);
}

}  // namespace fresnel::trace
