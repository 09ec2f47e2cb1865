#include "fresnel/viewer/thumbnails.h"

#include <filesystem>

#include "fresnel/core/error.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/viewer/files.h"

namespace fresnel::viewer {
namespace fs = std::filesystem;

Image8 environment_thumbnail(const std::string& preset, int width) {
    if (preset == "studio") return ibl::panorama_thumbnail(ibl::make_studio_panorama(256), width);
    if (is_folder(preset)) {  // a bake folder: its preview, when the bake wrote one
        const fs::path preview = fs::path(preset) / "preview" / "specular_level0.exr";
        std::error_code ec;
        if (!fs::exists(preview, ec)) throw Error(preset, "", "a baked folder without previews (fresnel bake wrote none)");
        return ibl::panorama_thumbnail(read_image_float(preview), width);
    }
    ibl::EnvironmentSource source;
    source.kind = ibl::EnvironmentSource::Kind::File;
    source.path = preset;
    return ibl::panorama_thumbnail(ibl::load_panorama(source), width);
}

}  // namespace fresnel::viewer
