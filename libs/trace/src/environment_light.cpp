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
    radiance_.resize(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float* p = panorama_.at(x, y);
            radiance_[std::size_t(y) * w + x] = glm::vec3(p[0], p[1], p[2]) * intensity_;
        }
    // The distribution's cells: 2x2 pixels of panoramas wider than 512 (the tables then stay
    // in the caches: a quarter of the lookups' misses), else one pixel.
    cell_ = w > 512 && w % 2 == 0 && h % 2 == 0 ? 2 : 1;
    cells_w_ = w / cell_;
    cells_h_ = h / cell_;
    std::vector<float> weights(std::size_t(cells_w_) * cells_h_, 0.0f);
    double sum = 0;
    for (int y = 0; y < h; ++y) {
        float sin_t = std::sin((float(y) + 0.5f) / float(h) * kPi);
        for (int x = 0; x < w; ++x) {
            float l = luminance(radiance_[std::size_t(y) * w + x]) * sin_t;
            weights[std::size_t(y / cell_) * cells_w_ + std::size_t(x / cell_)] += l;
            sum += l;
        }
    }
    // A floor of 1e-3 of the mean keeps dark regions reachable at negligible cost.
    float floor_w = float(sum / double(weights.size())) * 1e-3f;
    for (int y = 0; y < cells_h_; ++y) {
        float sin_t = std::sin((float(y) + 0.5f) / float(cells_h_) * kPi);
        for (int x = 0; x < cells_w_; ++x) weights[std::size_t(y) * cells_w_ + x] += floor_w * sin_t;
    }
    alias_ = AliasTable(weights);
    cell_pdf_.resize(weights.size());
    for (std::size_t i = 0; i < weights.size(); ++i) cell_pdf_[i] = float(alias_.probability(int(i)) * double(weights.size()));
}

glm::vec3 EnvironmentLight::radiance(glm::vec3 dir) const {
    glm::vec2 uv = ibl::direction_to_equirect(to_env_ * dir);
    const int w = panorama_.width, h = panorama_.height;
    int x = std::clamp(int(uv.x * float(w)), 0, w - 1), y = std::clamp(int(uv.y * float(h)), 0, h - 1);
    return radiance_[std::size_t(y) * w + x];
}

EnvironmentLight::Sample EnvironmentLight::sample(glm::vec2 u) const {
    Sample s;
    float jx = 0;
    int i = alias_.sample(u.x, jx);
    float pdf_uv = cell_pdf_[std::size_t(i)];
    glm::vec2 uv((float(i % cells_w_) + jx) / float(cells_w_), (float(i / cells_w_) + u.y) / float(cells_h_));
    float sin_t = std::sin(uv.y * kPi);
    if (pdf_uv <= 0.0f || sin_t <= 0.0f) return s;
    s.direction = to_world_ * ibl::equirect_to_direction(uv);
    s.pdf = pdf_uv / (2.0f * kPi * kPi * sin_t);
    const int w = panorama_.width, h = panorama_.height;
    int x = std::clamp(int(uv.x * float(w)), 0, w - 1), y = std::clamp(int(uv.y * float(h)), 0, h - 1);
    s.radiance = radiance_[std::size_t(y) * w + x];
    return s;
}

float EnvironmentLight::pdf(glm::vec3 dir) const {
    glm::vec3 e = to_env_ * dir;
    float sin_t = std::sqrt(std::max(0.0f, 1.0f - e.y * e.y));
    if (sin_t <= 0.0f) return 0.0f;
    glm::vec2 uv = ibl::direction_to_equirect(e);
    int x = std::clamp(int(uv.x * float(cells_w_)), 0, cells_w_ - 1), y = std::clamp(int(uv.y * float(cells_h_)), 0, cells_h_ - 1);
    return cell_pdf_[std::size_t(y) * cells_w_ + x] / (2.0f * kPi * kPi * sin_t);
}

}  // namespace fresnel::trace
