#include "fresnel/viewer/thumbnails.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/common.hpp>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/viewer/files.h"

namespace fresnel::viewer {
namespace fs = std::filesystem;

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

Image8 environment_thumbnail(const std::string& preset, int width) {
    if (preset == "studio") return panorama_thumbnail(ibl::make_studio_panorama(256), width);
    if (is_folder(preset)) {  // a bake folder: its preview, when the bake wrote one
        const fs::path preview = fs::path(preset) / "preview" / "specular_level0.exr";
        std::error_code ec;
        if (!fs::exists(preview, ec)) throw Error(preset, "", "a baked folder without previews (fresnel bake wrote none)");
        return panorama_thumbnail(read_image_float(preview), width);
    }
    ibl::EnvironmentSource source;
    source.kind = ibl::EnvironmentSource::Kind::File;
    source.path = preset;
    return panorama_thumbnail(ibl::load_panorama(source), width);
}

}  // namespace fresnel::viewer
