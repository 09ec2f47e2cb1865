#include "fresnel/ibl/dominant_light.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "fresnel/ibl/cubemap.h"

namespace fresnel::ibl {

namespace {

constexpr double kPi = 3.14159265358979323846;

float luminance(const float* p) { return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]; }

// The texels of `in` and their 4-neighbours (wrapping across the panorama's seam).
std::vector<std::uint8_t> grow(const std::vector<std::uint8_t>& in, int w, int h) {
    std::vector<std::uint8_t> out = in;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!in[std::size_t(y) * w + x]) continue;
            out[std::size_t(y) * w + (x + 1) % w] = 1;
            out[std::size_t(y) * w + (x + w - 1) % w] = 1;
            if (y > 0) out[std::size_t(y - 1) * w + x] = 1;
            if (y + 1 < h) out[std::size_t(y + 1) * w + x] = 1;
        }
    return out;
}

}  // namespace

std::optional<DominantLight> split_dominant_light(ImageF& panorama, const DominantLightOptions& options) {
    const int w = panorama.width, h = panorama.height;
    if (w < 4 || h < 2 || panorama.pixels.size() < std::size_t(w) * h * 4) return std::nullopt;
    // Solid angle of a texel of row y, and the panorama's light (sum of luminance x solid angle).
    std::vector<double> omega(static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y)
        omega[std::size_t(y)] = (2.0 * kPi / w) * (kPi / h) * std::sin((y + 0.5) * kPi / h);
    double total = 0.0;
    std::size_t brightest = 0;
    float peak = -1.0f;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float l = luminance(panorama.at(x, y));
            if (!std::isfinite(l) || l <= 0.0f) continue;
            total += double(l) * omega[std::size_t(y)];
            if (l > peak) {
                peak = l;
                brightest = std::size_t(y) * w + x;
            }
        }
    if (!(total > 0.0) || peak <= 0.0f) return std::nullopt;
    const double mean = total / (4.0 * kPi);
    const float limit = float(options.threshold * mean);
    if (peak <= limit) return std::nullopt;
    // The connected texels above the limit that hold the brightest one (flood fill).
    std::vector<std::uint8_t> region(std::size_t(w) * h, 0);
    std::vector<std::size_t> stack{brightest};
    region[brightest] = 1;
    auto above = [&](int x, int y) {
        const float l = luminance(panorama.at(x, y));
        return std::isfinite(l) && l > limit;
    };
    while (!stack.empty()) {
        const std::size_t i = stack.back();
        stack.pop_back();
        const int x = int(i % std::size_t(w)), y = int(i / std::size_t(w));
        const int nx[4] = {(x + 1) % w, (x + w - 1) % w, x, x};
        const int ny[4] = {y, y, y - 1, y + 1};
        for (int k = 0; k < 4; ++k) {
            if (ny[k] < 0 || ny[k] >= h) continue;
            const std::size_t j = std::size_t(ny[k]) * w + nx[k];
            if (!region[j] && above(nx[k], ny[k])) {
                region[j] = 1;
                stack.push_back(j);
            }
        }
    }
    // Grown by two texels (the light's filtered edge), and the ring of three around it.
    region = grow(grow(region, w, h), w, h);
    std::vector<std::uint8_t> outer = grow(grow(grow(region, w, h), w, h), w, h);
    std::vector<float> ring[3];
    double region_omega = 0.0;
    for (std::size_t i = 0; i < region.size(); ++i) {
        const int y = int(i / std::size_t(w));
        if (region[i]) {
            region_omega += omega[std::size_t(y)];
        } else if (outer[i]) {
            const float* p = &panorama.pixels[i * 4];
            for (int c = 0; c < 3; ++c)
                if (std::isfinite(p[c])) ring[c].push_back(p[c]);
        }
    }
    if (region_omega > options.max_solid_angle) return std::nullopt;
    glm::vec3 background(0.0f);
    for (int c = 0; c < 3; ++c)
        if (!ring[c].empty()) {
            auto mid = ring[c].begin() + std::ptrdiff_t(ring[c].size() / 2);
            std::nth_element(ring[c].begin(), mid, ring[c].end());
            background[c] = *mid;
        }
    // The light: the region's radiance above the background, times solid angle; its direction
    // the luminance-weighted mean of the texels' directions.
    glm::dvec3 e(0.0), d(0.0);
    double light = 0.0;
    std::vector<std::pair<glm::dvec3, double>> weighed;  // each texel's direction and luminance x solid angle
    for (std::size_t i = 0; i < region.size(); ++i) {
        if (!region[i]) continue;
        const int x = int(i % std::size_t(w)), y = int(i / std::size_t(w));
        const float* p = &panorama.pixels[i * 4];
        glm::dvec3 excess(0.0);
        for (int c = 0; c < 3; ++c) excess[c] = std::isfinite(p[c]) ? std::max(0.0, double(p[c]) - background[c]) : 0.0;
        const double o = omega[std::size_t(y)];
        e += excess * o;
        const double l = (0.2126 * excess.x + 0.7152 * excess.y + 0.0722 * excess.z) * o;
        light += l;
        const glm::dvec3 dir(equirect_to_direction({(x + 0.5f) / float(w), (y + 0.5f) / float(h)}));
        d += dir * l;
        weighed.emplace_back(dir, l);
    }
    if (light / total < options.min_share || !(glm::length(d) > 0.0)) return std::nullopt;
    double spread = 0.0;  // the luminance-weighted sum of the squared angle from the mean direction
    const glm::dvec3 centre = glm::normalize(d);
    for (const auto& [dir, l] : weighed) {
        const double theta = std::acos(std::clamp(glm::dot(dir, centre), -1.0, 1.0));
        spread += l * theta * theta;
    }
    for (std::size_t i = 0; i < region.size(); ++i)
        if (region[i]) {
            float* p = &panorama.pixels[i * 4];
            p[0] = background.x;
            p[1] = background.y;
            p[2] = background.z;
        }
    DominantLight out;
    out.direction = glm::vec3(glm::normalize(d));
    out.irradiance = glm::vec3(e);
    out.solid_angle = float(region_omega);
    out.share = float(light / total);
    // Its spread about that direction (the panorama's texels already hold the background now:
    // `spread` was weighed above, before they were replaced).
    out.angular_radius = float(std::sqrt(2.0 * spread / light));
    return out;
}

}  // namespace fresnel::ibl
