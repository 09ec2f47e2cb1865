#pragma once
// Where image-based light comes from: an equirectangular panorama file (.hdr, .exr),
// a uniform colour, or the built-in procedural studio.
#include <filesystem>
#include <glm/vec3.hpp>
#include <string>

#include "fresnel/core/image.h"

namespace fresnel::ibl {

struct EnvironmentSource {
    enum class Kind { File, Uniform, Studio } kind = Kind::Studio;
    std::filesystem::path path;  // Kind::File
    glm::vec3 color{1.0f};       // Kind::Uniform, linear
    // Bake without the panorama's dominant light, which the bake returns as a directional light
    // (fresnel/ibl/dominant_light.h, BakedIbl::dominant_light; `--env-light dominant`).
    bool split_dominant_light = false;
    // A stable description used in cache keys and manifests ("studio-v2", "color:1,1,1", the path;
    // " without its dominant light" appended when split_dominant_light).
    std::string describe() const;
};

// Parses the --env argument: "color:R,G,B", "studio", or a file path. Throws fresnel::Error.
EnvironmentSource parse_environment(const std::string& arg);

// The procedural studio: a dark-grey room with a soft overhead box light, two
// rectangular side soft boxes (warm key at +X+Z, cool fill at -X), a narrow rim
// light behind (-Z), a horizon band and a floor gradient. Values are linear
// radiance; 2:1 equirectangular.
ImageF make_studio_panorama(int width = 1024);

// A panorama of one colour.
ImageF make_uniform_panorama(glm::vec3 color, int width = 64);

// Loads the panorama of a source (files through read_image_float, with limits).
ImageF load_panorama(const EnvironmentSource& source, const ImageLimits& limits = {});

// A small picture of a panorama (linear RGBA floats, any size; alpha unused) for lists of
// environments (the viewer's and the page's presets): box-filtered to `width` x width / 2,
// exposed so that its mean luminance is 0.18, tone mapped (x / (1 + x)) and sRGB-encoded: RGB,
// rows top to bottom; non-finite texels count as black.
Image8 panorama_thumbnail(const ImageF& panorama, int width = 96);

}  // namespace fresnel::ibl
