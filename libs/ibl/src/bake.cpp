#include "fresnel/ibl/bake.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/error.h"
#include "fresnel/core/version.h"
#include "fresnel/ibl/ktx2.h"

namespace fresnel::ibl {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
constexpr int kFormatVersion = 7;  // bump when the bake's output changes, to invalidate caches
// Version 3 folders lack the table's A channel (5: the sheen albedo) and sheen.ktx2; they load,
// and the channel is computed on load.
constexpr int kSheenlessFormatVersion = 3;
constexpr int kSheenCubeSize = 32;  // the Charlie cube (prefilter_charlie): a wide blur
constexpr int kSheenSamples = 64;   // the Khronos Sample Viewer's count

double ms_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

// The six faces of one level side by side (+X -X +Y -Y +Z -Z), for previews.
ImageF face_strip(const CubeLevel& lv) {
    ImageF img(lv.size * 6, lv.size);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < lv.size; ++y)
            for (int x = 0; x < lv.size; ++x) std::copy_n(lv.texel(f, x, y), 4, img.at(f * lv.size + x, y));
    return img;
}
}  // namespace

std::string BakeOptions::key() const {
    std::ostringstream s;
    s << "v" << kFormatVersion << "-size" << size << "-levels" << levels << "-samples" << samples << "-lut" << lut_size
      << "x" << lut_samples << "-irr" << irradiance_size << "s" << irradiance_samples << "-bias" << lod_bias;
    return s.str();
}

ImageF bake_lut(const BakeOptions& o) { return compute_brdf_lut(o.lut_size, o.lut_samples, o.threads); }

BakedIbl bake(const ImageF& panorama, const BakeOptions& o, const Progress& progress) {
    if (o.size < 4 || o.size > 4096 || (o.size & (o.size - 1)) != 0)
        throw Error("bake", "--size", "face size must be a power of two in [4, 4096]");
    if (o.levels < 1 || (o.size >> (o.levels - 1)) < 1) throw Error("bake", "--levels", "too many levels for the size");
    if (o.samples < 1 || o.lut_size < 2 || o.lut_samples < 1) throw Error("bake", "", "sample counts must be positive");
    auto start = std::chrono::steady_clock::now();
    BakedIbl out;
    out.key = o.key();
    // A uniform panorama (color:R,G,B, furnace tests) filters to itself: skip the sampling.
    bool uniform = !panorama.pixels.empty();
    for (std::size_t i = 4; uniform && i < panorama.pixels.size(); i += 4)
        uniform = panorama.pixels[i] == panorama.pixels[0] && panorama.pixels[i + 1] == panorama.pixels[1] &&
                  panorama.pixels[i + 2] == panorama.pixels[2];
    if (uniform) {
        glm::vec3 c(panorama.pixels[0], panorama.pixels[1], panorama.pixels[2]);
        auto fill = [&](Cubemap& cube) {
            for (auto& lv : cube.levels)
                for (auto& f : lv.faces)
                    for (std::size_t i = 0; i < f.size(); i += 4) f[i] = c.x, f[i + 1] = c.y, f[i + 2] = c.z, f[i + 3] = 1.0f;
        };
        out.specular = make_cubemap(o.size, o.levels);
        fill(out.specular);
        out.irradiance_map = make_cubemap(o.irradiance_size, 1);
        fill(out.irradiance_map);
        out.sheen = make_cubemap(kSheenCubeSize, o.levels);
        fill(out.sheen);
        for (auto& f : out.sheen.levels[0].faces) std::fill(f.begin(), f.end(), 0.0f);  // the viewer's level 0 (see prefilter_charlie)
        out.charlie_lut = compute_charlie_lut();
        out.irradiance.c[0] = c / 0.282095f;  // irradiance / pi of a uniform sky is the sky itself
        out.lut = o.use_lut_cache ? load_or_bake_lut(o) : bake_lut(o);
        out.content_hash = baked_content_hash(out);
        out.bake_ms = ms_since(start);
        return out;
    }
    // Source cube at the output size with a full mip chain for filtered importance sampling.
    Cubemap source = cubemap_from_equirect(panorama, o.size, o.threads);
    build_mip_chain(source);
    out.cube_ms = ms_since(start);
    if (progress) progress(0.05);
    auto t = std::chrono::steady_clock::now();
    out.irradiance = irradiance_from_radiance(project_radiance(source));
    out.irradiance_map = o.irradiance_samples > 0
                             ? irradiance_filtered(source, o.irradiance_size, o.irradiance_samples, o.lod_bias, o.threads)
                             : irradiance_convolution(source, o.irradiance_size, 32, o.threads);
    out.irradiance_ms = ms_since(t);
    t = std::chrono::steady_clock::now();
    PrefilterOptions po{o.size, o.levels, o.samples, o.threads, o.lod_bias};
    out.specular = prefilter_ggx(source, po, [&](double f) {
        if (progress) progress(0.05 + 0.85 * f);
    });
    out.sheen = prefilter_charlie(source, kSheenCubeSize, o.levels, kSheenSamples, o.threads);
    out.charlie_lut = compute_charlie_lut();
    out.specular_ms = ms_since(t);
    t = std::chrono::steady_clock::now();
    // The table does not depend on the environment: it comes from the cache when present.
    out.lut = o.use_lut_cache ? load_or_bake_lut(o) : bake_lut(o);
    out.lut_ms = ms_since(t);
    out.content_hash = baked_content_hash(out);
    if (progress) progress(1.0);
    out.bake_ms = ms_since(start);
    return out;
}

namespace {
// The folder's files, into `dir` (a temporary folder: save_baked makes the set whole or absent).
void write_baked_files(const BakedIbl& ibl, const fs::path& dir, const BakeOptions& o, bool previews) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(dir.string(), "", "cannot create folder: " + ec.message());
    write_ktx2_cube(dir / "specular.ktx2", ibl.specular);
    const Cubemap& irr = ibl.irradiance_map;
    write_ktx2_cube(dir / "irradiance.ktx2", irr);
    write_ktx2_2d(dir / "brdf_lut.ktx2", ibl.lut);
    write_ktx2_cube(dir / "sheen.ktx2", ibl.sheen);
    if (ibl.background.size() > 0) write_ktx2_cube(dir / "background.ktx2", ibl.background);
    if (!ibl.charlie_lut.pixels.empty()) write_ktx2_2d(dir / "charlie_lut.ktx2", ibl.charlie_lut);
    json sh = json::array();
    for (const auto& c : ibl.irradiance.c) sh.push_back({c.x, c.y, c.z});
    write_file_atomically(dir / "irradiance_sh.json",
                          json{{"description", "irradiance / pi as real SH, bands 0-2, order (0,0) (1,-1) (1,0) (1,1) "
                                               "(2,-2) (2,-1) (2,0) (2,1) (2,2)"},
                               {"coefficients", sh}}
                              .dump(2));
    json files = {"specular.ktx2", "irradiance.ktx2", "irradiance_sh.json", "brdf_lut.ktx2", "sheen.ktx2"};
    if (ibl.background.size() > 0) files.push_back("background.ktx2");
    if (!ibl.charlie_lut.pixels.empty()) files.push_back("charlie_lut.ktx2");
    if (previews) {
        fs::create_directories(dir / "preview", ec);
        for (std::size_t l = 0; l < ibl.specular.levels.size(); ++l) {
            std::string name = "preview/specular_level" + std::to_string(l) + ".exr";
            write_exr(dir / name, face_strip(ibl.specular.levels[l]));
            files.push_back(name);
        }
        write_exr(dir / "preview/irradiance.exr", face_strip(irr.levels[0]));
        write_exr(dir / "preview/brdf_lut.exr", ibl.lut);
        files.push_back("preview/irradiance.exr");
        files.push_back("preview/brdf_lut.exr");
    }
    json manifest = {
        {"generator", "fresnel " + std::string(fresnel::version())},
        {"format_version", kFormatVersion},
        {"source", ibl.source},
        {"key", ibl.key},
        {"parameters",
         {{"size", o.size}, {"levels", o.levels}, {"samples", o.samples}, {"lut_size", o.lut_size},
          {"lut_samples", o.lut_samples}, {"irradiance_size", o.irradiance_size}, {"irradiance_samples", o.irradiance_samples}, {"lod_bias", o.lod_bias},
          {"roughness_of_level", "k / (levels - 1)"}, {"lod_of_roughness", "roughness * (levels - 1)"},
          {"orientation", "+Y top row, +Z centre column (u = 0.5), +X u = 0.25, -X u = 0.75 (Khronos Sample Viewer)"},
          {"faces", "+X -X +Y -Y +Z -Z (OpenGL order)"}}},
        {"irradiance_sh", sh},
        {"bake_ms", ibl.bake_ms},
        {"bake_breakdown_ms", {{"cube", ibl.cube_ms}, {"specular", ibl.specular_ms}, {"irradiance", ibl.irradiance_ms}, {"lut", ibl.lut_ms}}},
        {"files", files},
    };
    if (ibl.dominant_light) {
        const DominantLight& l = *ibl.dominant_light;
        manifest["dominant_light"] = {
            {"description", "taken out of the maps: a directional light towards `direction` (the panorama's frame) "
                            "of `irradiance` (linear RGB, on a surface facing it)"},
            {"direction", {l.direction.x, l.direction.y, l.direction.z}},
            {"irradiance", {l.irradiance.x, l.irradiance.y, l.irradiance.z}},
            {"solid_angle", l.solid_angle},
            {"angular_radius", l.angular_radius},
            {"share", l.share}};
    }
    write_file_atomically(dir / "manifest.json", manifest.dump(2));
}
}  // namespace

void save_baked(const BakedIbl& ibl, const fs::path& dir, const BakeOptions& o, bool previews) {
    // Whole or absent as a set: the files go to a temporary folder beside `dir`, which then takes
    // its place (an existing folder moved aside first and removed once the new one is in place,
    // or put back when that fails). A reader never sees half a bake; a failure leaves `dir` as it was.
    // A folder holding anything but a bake is refused, not replaced: its files are the user's.
    std::error_code ec;
    if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec) && !is_baked_dir(dir))
        throw Error(dir.string(), "", "is a folder holding other files; bake writes a folder of its own (a new or empty "
                                      "one, or an earlier bake, which it replaces)");
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error(dir.string(), "", "is a file, not a folder");
    const fs::path tmp = temporary_path_beside(dir);
    fs::remove_all(tmp, ec);
    try {
        write_baked_files(ibl, tmp, o, previews);
    } catch (const Error& e) {
        fs::remove_all(tmp, ec);
        // Named by the destination (and the file within it), never by the temporary folder.
        std::string file = e.file();
        if (file.rfind(tmp.string(), 0) == 0) file = (dir / fs::path(file).lexically_relative(tmp)).lexically_normal().string();
        throw Error(file, e.where(), e.reason());
    } catch (...) {
        fs::remove_all(tmp, ec);
        throw;
    }
    const fs::path old = temporary_path_beside(dir.string() + "-previous");
    const bool existed = fs::exists(dir, ec);
    if (existed) {
        fs::remove_all(old, ec);
        fs::rename(dir, old, ec);
        if (ec) {
            fs::remove_all(tmp, ec);
            throw Error(dir.string(), "", "cannot replace the folder: " + ec.message());
        }
    }
    fs::rename(tmp, dir, ec);
    if (ec) {
        const std::string why = ec.message();
        fs::remove_all(tmp, ec);
        if (existed) fs::rename(old, dir, ec);
        throw Error(dir.string(), "", "cannot write the folder: " + why);
    }
    if (existed) fs::remove_all(old, ec);
}

bool is_baked_dir(const fs::path& dir) {
    std::error_code ec;
    return fs::is_directory(dir, ec) && fs::is_regular_file(dir / "manifest.json", ec);
}

BakedIbl load_baked(const fs::path& dir) {
    fs::path mpath = dir / "manifest.json";
    auto bytes = read_file_bytes(mpath, 16u << 20);
    json m;
    try {
        m = json::parse(bytes.begin(), bytes.end());
    } catch (const json::exception& e) {
        throw Error(mpath.string(), "", std::string("invalid manifest: ") + e.what());
    }
    BakedIbl ibl;
    int format_version = kFormatVersion;
    try {
        format_version = m.at("format_version").get<int>();
        if (format_version != kFormatVersion && format_version != kSheenlessFormatVersion)
            throw Error(mpath.string(), "/format_version", "baked with another format version; bake again");
        ibl.source = m.value("source", "");
        ibl.key = m.value("key", "");
        if (m.contains("dominant_light")) {
            const json& d = m.at("dominant_light");
            DominantLight l;
            for (int c = 0; c < 3; ++c) {
                l.direction[c] = d.at("direction").at(std::size_t(c)).get<float>();
                l.irradiance[c] = d.at("irradiance").at(std::size_t(c)).get<float>();
            }
            l.solid_angle = d.value("solid_angle", 0.0f);
            l.angular_radius = std::clamp(d.value("angular_radius", 0.0f), 0.0f, 0.5f);
            l.share = d.value("share", 0.0f);
            const float len = glm::length(l.direction);
            if (!(len > 0.5f && len < 2.0f) || !std::isfinite(l.irradiance.x + l.irradiance.y + l.irradiance.z) ||
                l.irradiance.x < 0 || l.irradiance.y < 0 || l.irradiance.z < 0)
                throw Error(mpath.string(), "/dominant_light", "needs a unit direction and a non-negative irradiance");
            l.direction /= len;
            ibl.dominant_light = l;
        }
        const json& sh = m.at("irradiance_sh");
        if (!sh.is_array() || sh.size() != 9) throw Error(mpath.string(), "/irradiance_sh", "needs 9 RGB triples");
        for (std::size_t i = 0; i < 9; ++i)
            ibl.irradiance.c[i] = {sh[i].at(0).get<float>(), sh[i].at(1).get<float>(), sh[i].at(2).get<float>()};
    } catch (const json::exception& e) {
        throw Error(mpath.string(), "", std::string("invalid manifest: ") + e.what());
    }
    ibl.specular = read_ktx2_cube(dir / "specular.ktx2");
    ibl.irradiance_map = read_ktx2_cube(dir / "irradiance.ktx2");
    ibl.lut = read_ktx2_2d(dir / "brdf_lut.ktx2");
    if (format_version == kSheenlessFormatVersion) {
        fill_sheen_albedo(ibl.lut);
        // No Charlie cube either: filter the mirror level's mip chain (the bake's source at its size).
        Cubemap source = make_cubemap(ibl.specular.size(), 1);
        source.levels[0] = ibl.specular.levels[0];
        build_mip_chain(source);
        ibl.sheen = prefilter_charlie(source, kSheenCubeSize, int(ibl.specular.levels.size()), kSheenSamples);
    } else {
        ibl.sheen = read_ktx2_cube(dir / "sheen.ktx2");
    }
    // The Charlie table does not depend on the environment; folders written before it was
    // stored (and any with another size) get it computed (~25 ms).
    std::error_code ec;
    if (fs::is_regular_file(dir / "charlie_lut.ktx2", ec)) {
        ImageF lut = read_ktx2_2d(dir / "charlie_lut.ktx2");
        if (lut.width == kCharlieLutSize && lut.height == kCharlieLutSize) ibl.charlie_lut = std::move(lut);
    }
    if (ibl.charlie_lut.pixels.empty()) ibl.charlie_lut = compute_charlie_lut();
    if (ibl.dominant_light && fs::is_regular_file(dir / "background.ktx2", ec)) {
        ibl.background = read_ktx2_cube(dir / "background.ktx2");
        if (ibl.background.size() != ibl.specular.size() || ibl.background.levels.size() != ibl.specular.levels.size())
            throw Error((dir / "background.ktx2").string(), "", "not the size and levels of specular.ktx2");
    }
    ibl.from_cache = true;
    ibl.content_hash = baked_content_hash(ibl);
    return ibl;
}

namespace {
// Word-wise mixing (a multiply-xorshift step per 32-bit float): fast enough to run on every
// bake and load. Not a cryptographic hash; it tells baked environments apart.
std::uint64_t mix_floats(const std::vector<float>& v, std::uint64_t h) {
    const std::uint32_t* w = reinterpret_cast<const std::uint32_t*>(v.data());
    for (std::size_t i = 0; i < v.size(); ++i) {
        h = (h ^ w[i]) * 0x9E3779B97F4A7C15ull;
        h ^= h >> 29;
    }
    return (h ^ v.size()) * 0xBF58476D1CE4E5B9ull;
}
std::uint64_t mix_cube(const Cubemap& c, std::uint64_t h) {
    for (const auto& lv : c.levels)
        for (const auto& f : lv.faces) h = mix_floats(f, h ^ std::uint64_t(lv.size));
    return h;
}
}  // namespace

std::uint64_t image_content_hash(const ImageF& image, std::uint64_t seed) {
    std::uint64_t h = seed ^ (std::uint64_t(image.width) << 32) ^ std::uint64_t(image.height);
    return mix_floats(image.pixels, h);
}

std::uint64_t baked_content_hash(const BakedIbl& ibl) {
    std::uint64_t h = mix_cube(ibl.specular, 0x243F6A8885A308D3ull);
    h = mix_cube(ibl.irradiance_map, h);
    h = mix_cube(ibl.sheen, h);
    if (ibl.background.size() > 0) h = mix_cube(ibl.background, h);
    return image_content_hash(ibl.lut, h) | 1u;  // never 0 (0 = not computed)
}

std::uint64_t content_hash(std::span<const std::uint8_t> bytes, std::uint64_t h) {
    for (std::uint8_t b : bytes) {
        h ^= b;
        h *= 1099511628211ull;
    }
    return h;
}

fs::path cache_root() {
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "fresnel";
    if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "fresnel";
    return fs::temp_directory_path() / "fresnel-cache";
}

ImageF load_or_bake_lut(const BakeOptions& o, bool use_cache) {
    fs::path file = cache_root() / ("brdf_lut-v" + std::to_string(kFormatVersion) + "-" + std::to_string(o.lut_size) + "x" +
                                    std::to_string(o.lut_samples) + ".ktx2");
    std::error_code ec;
    if (use_cache && fs::is_regular_file(file, ec)) {
        try {
            ImageF lut = read_ktx2_2d(file);
            if (lut.width == o.lut_size && lut.height == o.lut_size) return lut;
        } catch (const Error&) {
        }
    }
    ImageF lut = bake_lut(o);
    if (use_cache) {
        fs::create_directories(file.parent_path(), ec);
        try {
            write_file_atomically(file, [&](const fs::path& tmp) { write_ktx2_2d(tmp, lut); });
        } catch (const Error&) {
            // caching is best effort
        }
    }
    return lut;
}

BakedIbl load_or_bake(const EnvironmentSource& source, const BakeOptions& options, const Progress& progress,
                      bool use_cache) {
    if (source.kind == EnvironmentSource::Kind::File && is_baked_dir(source.path)) return load_baked(source.path);
    // Without the cache the BRDF table is baked too: use_cache = false neither reads nor writes cache_root().
    BakeOptions o = options;
    if (!use_cache) o.use_lut_cache = false;
    std::uint64_t h = content_hash({reinterpret_cast<const std::uint8_t*>(options.key().data()), options.key().size()});
    if (source.kind == EnvironmentSource::Kind::File) {
        auto bytes = read_file_bytes(source.path, std::size_t(2) << 30);
        h = content_hash(bytes, h);
        if (source.split_dominant_light) h = content_hash({reinterpret_cast<const std::uint8_t*>("split"), 5}, h);
    } else {
        std::string d = source.describe();
        h = content_hash({reinterpret_cast<const std::uint8_t*>(d.data()), d.size()}, h);
    }
    char name[17];
    std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(h));
    fs::path dir = cache_root() / "env" / name;
    if (use_cache && is_baked_dir(dir)) {
        try {
            BakedIbl cached = load_baked(dir);
            // A split bake holds the background with the light; an entry without it is rebuilt.
            if (!(cached.dominant_light && cached.background.size() == 0)) return cached;
        } catch (const Error&) {
            // A damaged cache entry is rebuilt below.
        }
    }
    ImageF panorama = load_panorama(source);
    std::optional<DominantLight> light;
    ImageF whole;
    if (source.split_dominant_light) {
        whole = panorama;
        light = split_dominant_light(panorama);
    }
    BakedIbl ibl = bake(panorama, o, progress);
    ibl.dominant_light = light;
    if (light) {
        // The background keeps the light: the whole panorama, prefiltered as the shading's cube.
        const auto t = std::chrono::steady_clock::now();
        Cubemap source_cube = cubemap_from_equirect(whole, o.size, o.threads);
        build_mip_chain(source_cube);
        ibl.background = prefilter_ggx(source_cube, PrefilterOptions{o.size, o.levels, o.samples, o.threads, o.lod_bias});
        ibl.content_hash = baked_content_hash(ibl);
        ibl.bake_ms += ms_since(t);
    }
    ibl.source = source.describe();
    if (use_cache) {
        // save_baked writes the set whole or not at all, so a concurrent reader never sees half a bake.
        try {
            save_baked(ibl, dir, options, false);
        } catch (const Error&) {
            // caching is best effort; the render goes on
        }
    }
    return ibl;
}

}  // namespace fresnel::ibl
