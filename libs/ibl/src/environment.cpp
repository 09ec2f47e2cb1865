#include "fresnel/ibl/environment.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <sstream>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/ibl/cubemap.h"

namespace fresnel::ibl {

std::string EnvironmentSource::describe() const {
    const std::string split = split_dominant_light ? " without its dominant light" : "";
    switch (kind) {
        case Kind::File: return path.string() + split;
        case Kind::Uniform: {
            std::ostringstream s;
            s << "color:" << color.x << "," << color.y << "," << color.z;
            return s.str() + split;
        }
        case Kind::Studio: return "studio-v2" + split;
    }
    return "?";
}

EnvironmentSource parse_environment(const std::string& arg) {
    EnvironmentSource s;
    if (arg == "studio" || arg.empty()) return s;
    if (arg.rfind("color:", 0) == 0) {
        s.kind = EnvironmentSource::Kind::Uniform;
        std::stringstream ss(arg.substr(6));
        std::string item;
        int n = 0;
        while (std::getline(ss, item, ',')) {
            try {
                std::size_t used = 0;
                float v = std::stof(item, &used);
                if (used != item.size() || !std::isfinite(v) || v < 0 || n >= 3) throw std::invalid_argument(item);
                s.color[n++] = v;
            } catch (const std::logic_error&) {
                throw Error("--env", arg, "expected color:R,G,B with three non-negative numbers");
            }
        }
        if (n != 3) throw Error("--env", arg, "expected color:R,G,B with three non-negative numbers");
        return s;
    }
    s.kind = EnvironmentSource::Kind::File;
    s.path = arg;
    return s;
}

namespace {
// Smooth rectangle mask in (azimuth, elevation) with soft edges.
float soft_box(float az, float el, float az0, float el0, float half_w, float half_h, float softness) {
    float da = std::remainder(az - az0, 2.0f * 3.14159265f);
    float x = (std::fabs(da) - half_w) / softness, y = (std::fabs(el - el0) - half_h) / softness;
    auto edge = [](float t) { return 1.0f - glm::smoothstep(0.0f, 1.0f, t); };
    return edge(x) * edge(y);
}
}  // namespace

ImageF make_studio_panorama(int width) {
    int height = width / 2;
    ImageF img(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            glm::vec3 d = equirect_to_direction({(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)});
            float el = std::asin(std::clamp(d.y, -1.0f, 1.0f));
            float az = std::atan2(d.x, d.z);  // 0 = +Z, pi/2 = +X
            // Room: dark walls, a slightly brighter ceiling, a floor gradient to the horizon.
            glm::vec3 c = d.y >= 0 ? glm::mix(glm::vec3(0.035f, 0.037f, 0.04f), glm::vec3(0.08f), d.y)
                                   : glm::mix(glm::vec3(0.05f, 0.047f, 0.045f), glm::vec3(0.02f), std::min(1.0f, -d.y * 2.0f));
            // Horizon glow band.
            c += glm::vec3(0.05f, 0.05f, 0.055f) * std::exp(-(el * el) / 0.01f);
            // Overhead soft box (round, white).
            c += glm::vec3(6.0f) * glm::smoothstep(0.955f, 0.975f, d.y);
            // Warm key soft box at azimuth 45 degrees (+X+Z), elevation 25.
            c += glm::vec3(12.0f, 10.5f, 9.0f) * soft_box(az, el, 0.785f, 0.44f, 0.2f, 0.26f, 0.04f);
            // Cool fill strip at azimuth -100 degrees (-X), elevation 10.
            c += glm::vec3(2.2f, 2.6f, 3.2f) * soft_box(az, el, -1.75f, 0.17f, 0.1f, 0.42f, 0.05f);
            // Rim light behind (-Z), narrow and bright.
            c += glm::vec3(6.0f) * soft_box(az, el, 3.14159f, 0.35f, 0.05f, 0.32f, 0.03f);
            float* p = img.at(x, y);
            p[0] = c.x, p[1] = c.y, p[2] = c.z, p[3] = 1.0f;
        }
    return img;
}

ImageF make_uniform_panorama(glm::vec3 color, int width) {
    ImageF img(width, width / 2);
    for (std::size_t i = 0; i < img.pixels.size(); i += 4) {
        img.pixels[i] = color.x, img.pixels[i + 1] = color.y, img.pixels[i + 2] = color.z, img.pixels[i + 3] = 1.0f;
    }
    return img;
}

ImageF load_panorama(const EnvironmentSource& s, const ImageLimits& limits) {
    switch (s.kind) {
        case EnvironmentSource::Kind::Studio: return make_studio_panorama();
        case EnvironmentSource::Kind::Uniform: return make_uniform_panorama(s.color);
        case EnvironmentSource::Kind::File: break;
    }
    ImageF img = read_image_float(s.path, limits);
    for (float& v : img.pixels)
        if (!std::isfinite(v) || v < 0) v = 0;  // hostile or broken pixels must not poison the bake
    return img;
}

Image8 panorama_thumbnail(const ImageF& pano, int width) {
    width = std::max(width, 2);
    const int height = std::max(width / 2, 1);
    Image8 out(width, height, 3);
    if (pano.width <= 0 || pano.height <= 0) return out;
    std::vector<glm::vec3> box(std::size_t(width) * std::size_t(height), glm::vec3(0.0f));
    double luminance_sum = 0.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // The panorama's pixels under this one (at least one).
            const int x0 = x * pano.width / width, x1 = std::max(x0 + 1, (x + 1) * pano.width / width);
            const int y0 = y * pano.height / height, y1 = std::max(y0 + 1, (y + 1) * pano.height / height);
            glm::dvec3 sum(0.0);
            for (int v = y0; v < y1; ++v)
                for (int u = x0; u < x1; ++u) {
                    const float* p = pano.at(u, v);
                    const glm::dvec3 c(p[0], p[1], p[2]);
                    if (std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) sum += glm::max(c, glm::dvec3(0.0));
                }
            const glm::vec3 c = glm::vec3(sum / double((x1 - x0) * (y1 - y0)));
            box[std::size_t(y) * std::size_t(width) + std::size_t(x)] = c;
            luminance_sum += 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
        }
    const double mean = luminance_sum / double(box.size());
    const float exposure = mean > 0.0 ? float(0.18 / mean) : 1.0f;
    for (std::size_t i = 0; i < box.size(); ++i) {
        const glm::vec3 c = box[i] * exposure;
        for (int k = 0; k < 3; ++k) {
            const float mapped = c[k] / (1.0f + c[k]);
            out.pixels[i * 3 + std::size_t(k)] = std::uint8_t(std::lround(std::clamp(linear_to_srgb(mapped), 0.0f, 1.0f) * 255.0f));
        }
    }
    return out;
}

}  // namespace fresnel::ibl
