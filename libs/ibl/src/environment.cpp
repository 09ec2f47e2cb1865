#include "fresnel/ibl/environment.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <sstream>

#include "fresnel/core/error.h"
#include "fresnel/ibl/cubemap.h"

namespace fresnel::ibl {

std::string EnvironmentSource::describe() const {
    switch (kind) {
        case Kind::File: return path.string();
        case Kind::Uniform: {
            std::ostringstream s;
            s << "color:" << color.x << "," << color.y << "," << color.z;
            return s.str();
        }
        case Kind::Studio: return "studio-v2";
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

}  // namespace fresnel::ibl
