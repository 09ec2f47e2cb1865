// glTF 2.0 loader. Parses the JSON with nlohmann::json directly rather than
// through tinygltf 2.7 (Debian's): we need JSON-pointer locations in every
// error, exact control of file access (URI policy), buffers larger than their
// byteLength (valid glTF, rejected by tinygltf 2.7) and parallel image decoding.
// Long (~1190 lines): the core format's reader with every extension's block; the parts with
// a concern of their own are apart (accessors, compression, animation, variants, paths).
#include "fresnel/scene/gltf_loader.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <limits>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <set>

#include "accessor.h"
#include "fresnel/core/parallel.h"
#include "fresnel/scene/mesh_ops.h"
#include "fresnel/scene/pose.h"
#include "geometry.h"
#include "json_reader.h"
#include "meshopt_decoder.h"
#include "uri_policy.h"
#include "webp_decoder.h"
#include "gltf_codes.h"

namespace fresnel {
namespace fs = std::filesystem;
using gltf::json;
using gltf::JsonReader;

const std::vector<std::string>& supported_gltf_extensions() {
    static const std::vector<std::string> list = {
        "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_texture_transform",
        "KHR_materials_unlit", "KHR_mesh_quantization", "KHR_materials_ior", "KHR_materials_specular",
        "KHR_materials_pbrSpecularGlossiness", "KHR_materials_clearcoat", "KHR_materials_sheen",
        "EXT_meshopt_compression", "KHR_draco_mesh_compression", "EXT_texture_webp", "KHR_materials_variants",
        "KHR_animation_pointer", "KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_dispersion",
        "KHR_node_visibility", "KHR_materials_anisotropy", "KHR_materials_iridescence", "EXT_mesh_gpu_instancing",
        "KHR_materials_diffuse_transmission", "KHR_materials_diffuse_roughness", "KHR_texture_basisu",
        "EXT_lights_area",
    };
    return list;
}

const std::vector<std::string>& parsed_unshaded_gltf_extensions() {
    static const std::vector<std::string> list = {};  // none now
    return list;
}

GltfExtensionSupport gltf_extension_support(const std::string& name) {
    const auto& ok = supported_gltf_extensions();
    if (std::find(ok.begin(), ok.end(), name) != ok.end()) return GltfExtensionSupport::Supported;
    const auto& parsed = parsed_unshaded_gltf_extensions();
    if (std::find(parsed.begin(), parsed.end(), name) != parsed.end()) return GltfExtensionSupport::ReadNotShaded;
    return GltfExtensionSupport::Unsupported;
}

namespace {

using gltf_code::kChunkBin;
using gltf_code::kChunkJson;
using gltf_code::kGlbMagic;

std::uint32_t read_u32(const std::uint8_t* p) {
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

struct GlbParts {
    std::string_view json;
    std::span<const std::uint8_t> bin;
    bool has_bin = false;
};

GlbParts split_glb(std::span<const std::uint8_t> bytes, const std::string& file) {
    auto fail = [&](std::size_t at, const std::string& what) -> void {
        throw Error(file, "byte " + std::to_string(at), what);
    };
    if (bytes.size() < 20) fail(0, "GLB file is too short for a header and a chunk (" + std::to_string(bytes.size()) + " bytes)");
    if (read_u32(bytes.data()) != kGlbMagic) fail(0, "not a GLB file (bad magic)");
    std::uint32_t version = read_u32(bytes.data() + 4);
    if (version != 2) fail(4, "unsupported GLB version " + std::to_string(version));
    std::uint32_t length = read_u32(bytes.data() + 8);
    if (length > bytes.size())
        fail(8, "header says the file is " + std::to_string(length) + " bytes but it has " + std::to_string(bytes.size()) +
                    " (truncated?)");
    if (length < 20) fail(8, "header length " + std::to_string(length) + " is too small");
    GlbParts parts;
    std::size_t pos = 12;
    bool first = true;
    while (pos + 8 <= length) {
        std::uint32_t clen = read_u32(bytes.data() + pos), ctype = read_u32(bytes.data() + pos + 4);
        if (std::size_t(clen) > length - pos - 8)
            fail(pos, "chunk length " + std::to_string(clen) + " runs past the end of the file");
        if (clen % 4 != 0) fail(pos, "chunk length " + std::to_string(clen) + " is not a multiple of 4");
        const std::uint8_t* data = bytes.data() + pos + 8;
        if (first) {
            if (ctype != kChunkJson) fail(pos + 4, "the first chunk must be JSON");
            parts.json = std::string_view(reinterpret_cast<const char*>(data), clen);
            first = false;
        } else if (ctype == kChunkBin) {
            if (parts.has_bin) fail(pos + 4, "more than one BIN chunk");
            parts.bin = {data, clen};
            parts.has_bin = true;
        }  // unknown chunks are skipped, as the spec says
        pos += 8 + std::size_t(clen);
    }
    if (first) fail(12, "GLB has no JSON chunk");
    if (pos != length) fail(pos, "trailing bytes after the last chunk");
    return parts;
}

class Loader {
public:
    Loader(std::string file, fs::path base_dir, Diagnostics& diag, const GltfLoadOptions& opt)
        : r_(std::move(file)), base_dir_(std::move(base_dir)), diag_(diag), opt_(opt) {}

    Scene load(std::span<const std::uint8_t> bytes) {
        bool glb = bytes.size() >= 4 && read_u32(bytes.data()) == kGlbMagic;
        GlbParts parts;
        std::string_view text;
        if (glb) {
            parts = split_glb(bytes, r_.file());
            text = parts.json;
        } else {
            text = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        }
        if (!glb) refuse_what_is_not_gltf(bytes);
        try {
            doc_ = json::parse(text.begin(), text.end());
        } catch (const json::parse_error& e) {
            // nlohmann's text without its "[json.exception.parse_error.101] " prefix.
            std::string what = e.what();
            if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos)
                what = what.substr(what.find("] ") + 2);
            throw Error(r_.file(), "byte " + std::to_string(e.byte), "invalid JSON: " + what);
        }
        if (!doc_.is_object()) r_.fail("", "the glTF document must be a JSON object");
        scene_.source = r_.file();
        check_asset();
        check_extensions();
        load_buffers(glb ? &parts : nullptr);
        gltf::decode_meshopt_views(r_, doc_, buffers_, opt_.max_file_bytes,
                                   [this](std::size_t n, const std::string& ptr) { account(n, ptr); });
        load_variants();
        std::size_t input_bytes = bytes.size();
        for (const auto& b : buffers_) input_bytes += b.size();
        geometry_budget_ = opt_.max_geometry_bytes
                               ? opt_.max_geometry_bytes
                               : std::size_t(std::min<std::uint64_t>(
                                     (std::uint64_t(256) << 20) + 64 * std::uint64_t(input_bytes), SIZE_MAX));
        gltf::AccessorDecoder accessors(r_, doc_, buffers_, opt_.max_vertices * 16,
                                        [this](std::size_t n, const std::string& ptr) { check_geometry(n, ptr); });
        load_images(accessors);
        load_samplers_and_textures();
        load_materials();
        load_meshes(accessors);
        load_cameras();
        load_lights();
        load_nodes();
        load_scenes();
        expand_gpu_instancing(accessors);
        load_skins(accessors);
        load_animations(accessors);
        pose_skins();
        return std::move(scene_);
    }

private:
    JsonReader r_;
    fs::path base_dir_;
    Diagnostics& diag_;
    const GltfLoadOptions& opt_;
    json doc_;
    Scene scene_;
    std::size_t area_light_base_ = 0;  // Scene::lights: the punctual ones, then EXT_lights_area's
    std::vector<std::vector<std::uint8_t>> buffers_;
    std::size_t total_bytes_ = 0;
    std::vector<Sampler> samplers_;

    void warn(const std::string& where, const std::string& what) { diag_.warn(r_.file(), where, what); }
    bool uses(const std::string& ext) const {
        return std::find(scene_.extensions_used.begin(), scene_.extensions_used.end(), ext) != scene_.extensions_used.end();
    }

    void account(std::size_t bytes, const std::string& ptr) {
        total_bytes_ += bytes;
        if (total_bytes_ > opt_.max_total_bytes)
            r_.fail(ptr, "buffers and images exceed the limit of " + std::to_string(opt_.max_total_bytes) + " bytes");
    }

    // The geometry budget (GltfLoadOptions::max_geometry_bytes): what the scene keeps, plus what
    // is about to be decoded.
    std::size_t geometry_budget_ = 0, geometry_bytes_ = 0;
    [[noreturn]] void geometry_over(std::size_t more, const std::string& ptr) {
        const auto mib = [](std::size_t b) { return std::to_string((b + (1 << 20) - 1) >> 20) + " MiB"; };
        r_.fail(ptr, "decoding it would take the file's geometry to " + mib(geometry_bytes_ + more) +
                         ", over its memory budget of " + mib(geometry_budget_) +
                         (opt_.max_geometry_bytes ? std::string(" (--max-memory)")
                                                  : std::string(" (256 MiB + 64 bytes per byte of the file and its "
                                                                "buffers; --max-memory raises it)")));
    }
    void check_geometry(std::size_t more, const std::string& ptr) {
        if (more > geometry_budget_ || geometry_bytes_ > geometry_budget_ - more) geometry_over(more, ptr);
    }
    void keep_geometry(const Primitive& p, const std::string& ptr) {
        std::size_t n = p.positions.size() * sizeof(glm::vec3) + p.normals.size() * sizeof(glm::vec3) +
                        p.tangents.size() * sizeof(glm::vec4) + (p.uv0.size() + p.uv1.size()) * sizeof(glm::vec2) +
                        p.colors.size() * sizeof(glm::vec4) + p.indices.size() * sizeof(std::uint32_t) +
                        p.joints.size() * sizeof(glm::uvec4) + p.weights.size() * sizeof(glm::vec4);
        for (const MorphTarget& t : p.targets)
            n += (t.positions.size() + t.normals.size() + t.tangents.size()) * sizeof(glm::vec3);
        check_geometry(n, ptr);
        geometry_bytes_ += n;
    }

    // A file that is no glTF at all (an image, an OBJ, binary junk) is named for what it is,
    // instead of a JSON parser's complaint about its first byte.
    void refuse_what_is_not_gltf(std::span<const std::uint8_t> b) {
        auto starts = [&](std::initializer_list<std::uint8_t> magic) {
            return b.size() >= magic.size() && std::equal(magic.begin(), magic.end(), b.begin());
        };
        const char* kind = nullptr;
        if (starts({0x89, 'P', 'N', 'G'})) kind = "a PNG image";
        else if (starts({0xFF, 0xD8, 0xFF})) kind = "a JPEG image";
        else if (starts({0xAB, 'K', 'T', 'X'})) kind = "a KTX texture";
        else if (starts({'R', 'I', 'F', 'F'})) kind = "a RIFF file (a WebP image?)";
        else if (starts({0x76, 0x2F, 0x31, 0x01})) kind = "an OpenEXR image";
        else if (starts({'#', '?'})) kind = "a Radiance HDR image";
        else if (starts({'P', 'K', 0x03, 0x04})) kind = "a ZIP archive";
        else if (starts({'g', 'l', 'T', 'F'})) kind = nullptr;  // a GLB: split_glb's checks
        if (kind) r_.fail("", std::string("not a glTF file: it is ") + kind + " (a model is a .gltf, .glb or .obj file)");
        std::size_t i = 0;
        if (starts({0xEF, 0xBB, 0xBF})) i = 3;  // a UTF-8 byte order mark
        while (i < b.size() && (b[i] == ' ' || b[i] == '\t' || b[i] == '\r' || b[i] == '\n')) ++i;
        if (i < b.size() && b[i] != '{') {
            char first[8];
            std::snprintf(first, sizeof first, "0x%02X", unsigned(b[i]));
            const bool printable = b[i] >= 0x20 && b[i] < 0x7F;
            r_.fail("byte " + std::to_string(i),
                    std::string("not a glTF file: a .gltf is a JSON object (starts with '{') and a .glb starts with "
                                "'glTF'; this starts with ") +
                        (printable ? "'" + std::string(1, char(b[i])) + "'" : std::string(first)) +
                        (starts({'v', ' '}) || starts({'#', ' '}) || starts({'o', ' '}) || starts({'m', 't', 'l'})
                             ? " (an OBJ file? name it .obj)"
                             : ""));
        }
    }

    void check_asset() {
        const json* asset = r_.find(doc_, "asset");
        if (!asset || !asset->is_object()) r_.fail("/asset", "is required");
        std::string version = r_.string(*asset, "version", "/asset");
        if (version.empty()) r_.fail("/asset/version", "is required");
        if (version.rfind("2.", 0) != 0) r_.fail("/asset/version", "unsupported glTF version '" + version + "'");
        std::string min_version = r_.string(*asset, "minVersion", "/asset");
        if (!min_version.empty() && min_version != "2.0")
            warn("/asset/minVersion", "asset asks for glTF " + min_version + "; reading it as 2.0");
    }

    std::vector<std::string> string_list(const char* key) {
        std::vector<std::string> out;
        const json& arr = r_.array(doc_, key, "");
        for (std::size_t i = 0; i < arr.size(); ++i) {
            if (!arr[i].is_string()) r_.fail(JsonReader::at(std::string("/") + key, i), "must be a string");
            out.push_back(arr[i].get<std::string>());
        }
        return out;
    }

    void check_extensions() {
        scene_.extensions_used = string_list("extensionsUsed");
        scene_.extensions_required = string_list("extensionsRequired");
        const auto& ok = supported_gltf_extensions();
        for (std::size_t i = 0; i < scene_.extensions_required.size(); ++i) {
            const auto& e = scene_.extensions_required[i];
            if (std::find(ok.begin(), ok.end(), e) == ok.end()) {
                std::string ptr = "/extensionsRequired/" + std::to_string(i);
                if (opt_.require_supported_extensions) r_.fail(ptr, "required extension '" + e + "' is not supported");
                warn(ptr, "required extension '" + e + "' is not supported; the file will not render as meant");
            }
        }
        for (const auto& e : scene_.extensions_used)
            if (std::find(ok.begin(), ok.end(), e) == ok.end())
                warn("/extensionsUsed", "extension '" + e + "' is not supported; rendering without it");
    }

    std::vector<std::uint8_t> read_uri(const std::string& uri, const std::string& ptr, std::size_t max_bytes) {
        if (gltf::is_data_uri(uri)) {
            std::string mime, error;
            auto data = gltf::decode_data_uri(uri, std::min(max_bytes, opt_.max_data_uri_bytes), mime, error);
            if (!data) r_.fail(ptr, error);
            return std::move(*data);
        }
        std::string error;
        auto path = gltf::resolve_uri(uri, base_dir_, opt_.allow_external_files, error);
        if (!path) r_.fail(ptr, error);
        try {
            return read_file_bytes(*path, max_bytes);
        } catch (const Error& e) {
            r_.fail(ptr, "URI '" + uri + "': " + e.reason());
        }
    }

    void load_buffers(const GlbParts* glb) {
        const json& arr = r_.array(doc_, "buffers", "");
        // Buffers no bufferView uses are never read: a missing or refused URI there is a warning only.
        std::vector<bool> used(arr.size(), false);
        const json& views = r_.array(doc_, "bufferViews", "");
        auto mark = [&](const json& v) {
            if (v.is_object() && v.contains("buffer") && v["buffer"].is_number()) {
                double b = v["buffer"].get<double>();
                if (b >= 0 && b < double(arr.size())) used[std::size_t(b)] = true;
            }
        };
        for (const auto& v : views) {
            mark(v);
            // EXT_meshopt_compression reads its own buffer.
            if (v.is_object() && v.contains("extensions") && v["extensions"].is_object() &&
                v["extensions"].contains("EXT_meshopt_compression"))
                mark(v["extensions"]["EXT_meshopt_compression"]);
        }
        buffers_.resize(arr.size());
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = "/buffers/" + std::to_string(i);
            const json& b = arr[i];
            if (!b.is_object()) r_.fail(ptr, "must be an object");
            std::size_t length = std::size_t(r_.integer(b, "byteLength", ptr, 0, 1, LLONG_MAX, true));
            if (length > opt_.max_file_bytes)
                r_.fail(ptr + "/byteLength", "buffer of " + std::to_string(length) + " bytes is over the limit");
            if (!r_.has(b, "uri")) {
                if (!glb || i != 0) {
                    if (gltf::is_meshopt_fallback_buffer(r_, b)) continue;  // its views decode from another buffer
                    // A placeholder (data supplied by an extension we lack): an error only if an accessor reads it.
                    warn(ptr, "buffer has no uri; its data is not available");
                    continue;
                }
                if (!glb->has_bin) r_.fail(ptr, "refers to the GLB BIN chunk, but the file has none");
                if (glb->bin.size() < length)
                    r_.fail(ptr + "/byteLength", "is " + std::to_string(length) + " but the BIN chunk holds " +
                                                      std::to_string(glb->bin.size()) + " bytes");
                if (glb->bin.size() > length + 3)
                    warn(ptr + "/byteLength", "BIN chunk is larger than the buffer's byteLength");
                buffers_[i].assign(glb->bin.begin(), glb->bin.begin() + std::ptrdiff_t(length));
            } else {
                std::string uri = r_.string(b, "uri", ptr);
                if (!used[i]) {
                    warn(ptr, "buffer is not used by any bufferView; not read");
                    continue;
                }
                auto data = read_uri(uri, ptr + "/uri", opt_.max_file_bytes);
                if (data.size() < length)
                    r_.fail(ptr + "/byteLength", "is " + std::to_string(length) + " but '" +
                                                      (gltf::is_data_uri(uri) ? std::string("data URI") : uri) +
                                                      "' holds only " + std::to_string(data.size()) + " bytes");
                data.resize(length);
                buffers_[i] = std::move(data);
            }
            account(length, ptr);
        }
    }

    void load_images(const gltf::AccessorDecoder& accessors) {
        const json& arr = r_.array(doc_, "images", "");
        const json& views = r_.array(doc_, "bufferViews", "");
        scene_.images.resize(arr.size());
        std::vector<std::vector<std::uint8_t>> encoded(arr.size());
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = "/images/" + std::to_string(i);
            const json& img = arr[i];
            if (!img.is_object()) r_.fail(ptr, "must be an object");
            SceneImage& out = scene_.images[i];
            out.name = r_.string(img, "name", ptr);
            bool has_uri = r_.has(img, "uri"), has_view = r_.has(img, "bufferView");
            if (has_uri && has_view) r_.fail(ptr, "has both uri and bufferView");
            if (has_uri) {
                std::string uri = r_.string(img, "uri", ptr);
                if (out.name.empty()) out.name = gltf::is_data_uri(uri) ? "image " + std::to_string(i) : uri;
                if (!gltf::is_data_uri(uri)) {
                    std::string error;
                    auto path = gltf::resolve_uri(uri, base_dir_, opt_.allow_external_files, error);
                    if (!path) r_.fail(ptr + "/uri", error);  // policy violations are errors, not warnings
                    std::error_code ec;
                    if (!fs::is_regular_file(*path, ec)) {
                        warn(ptr + "/uri", "image file '" + uri + "' not found; using a neutral texture");
                        continue;
                    }
                }
                if (!opt_.decode_images && !opt_.read_image_headers) continue;
                encoded[i] = read_uri(uri, ptr + "/uri", opt_.image_limits.max_decoded_bytes);
            } else if (has_view) {
                if (out.name.empty()) out.name = "image " + std::to_string(i);
                int v = r_.index(img, "bufferView", ptr, views.size(), "bufferView");
                if (!r_.has(img, "mimeType")) r_.fail(ptr + "/mimeType", "is required with bufferView");
                if (!opt_.decode_images && !opt_.read_image_headers) continue;
                try {
                    auto bytes = accessors.view_bytes(v, ptr + "/bufferView");
                    encoded[i].assign(bytes.begin(), bytes.end());
                } catch (const Error& e) {
                    warn(ptr + "/bufferView", e.reason() + "; using a neutral texture");
                    continue;
                }
            } else {
                r_.fail(ptr, "has neither uri nor bufferView");
            }
            out.header = peek_image_header(encoded[i]);
            out.encoded_bytes = encoded[i].size();
            if (!opt_.decode_images) encoded[i] = {};  // the header was all that was asked
            account(out.encoded_bytes, ptr);
        }
        // Decode in parallel; a bad image becomes a warning and a neutral fallback.
        std::vector<std::string> errors(arr.size());
        parallel_for(
            arr.size(),
            [&](std::size_t i) {
                if (encoded[i].empty()) return;
                try {
                    scene_.images[i].pixels =
                        gltf::is_webp(encoded[i])
                            ? gltf::decode_webp(encoded[i], scene_.images[i].name, opt_.image_limits)
                            : decode_image8(encoded[i], scene_.images[i].name, opt_.image_limits);
                } catch (const Error& e) {
                    errors[i] = e.reason();
                }
                if (opt_.keep_encoded_images && errors[i].empty())
                    scene_.images[i].encoded = std::make_shared<const std::vector<std::uint8_t>>(std::move(encoded[i]));
                encoded[i] = {};
            },
            opt_.threads);
        for (std::size_t i = 0; i < errors.size(); ++i)
            if (!errors[i].empty())
                warn("/images/" + std::to_string(i), "'" + scene_.images[i].name + "': " + errors[i] + "; using a neutral texture");
    }

    void load_samplers_and_textures() {
        const json& sarr = r_.array(doc_, "samplers", "");
        for (std::size_t i = 0; i < sarr.size(); ++i) {
            std::string ptr = "/samplers/" + std::to_string(i);
            const json& s = sarr[i];
            if (!s.is_object()) r_.fail(ptr, "must be an object");
            using namespace gltf_code;  // the sampler numbers
            Sampler out;
            int mag = int(r_.integer(s, "magFilter", ptr, kLinear, 0, 1 << 20));
            if (mag == kNearest) out.mag_filter = Filter::Nearest;
            else if (mag != kLinear) warn(ptr + "/magFilter", "invalid filter " + std::to_string(mag) + "; using LINEAR");
            int min = int(r_.integer(s, "minFilter", ptr, kLinearMipmapLinear, 0, 1 << 20));
            switch (min) {
                case kNearest: out.min_filter = Filter::Nearest; out.mipmap = MipmapMode::None; break;
                case kLinear: out.min_filter = Filter::Linear; out.mipmap = MipmapMode::None; break;
                case kNearestMipmapNearest: out.min_filter = Filter::Nearest; out.mipmap = MipmapMode::Nearest; break;
                case kLinearMipmapNearest: out.min_filter = Filter::Linear; out.mipmap = MipmapMode::Nearest; break;
                case kNearestMipmapLinear: out.min_filter = Filter::Nearest; out.mipmap = MipmapMode::Linear; break;
                case kLinearMipmapLinear: break;  // the default
                default: warn(ptr + "/minFilter", "invalid filter " + std::to_string(min) + "; using LINEAR"); break;
            }
            auto wrap = [&](const char* key) {
                int v = int(r_.integer(s, key, ptr, kRepeat, 0, 1 << 20));
                if (v == kClampToEdge) return Wrap::ClampToEdge;
                if (v == kMirroredRepeat) return Wrap::MirroredRepeat;
                if (v != kRepeat) warn(ptr + "/" + key, "invalid wrap mode " + std::to_string(v) + "; using REPEAT");
                return Wrap::Repeat;
            };
            out.wrap_s = wrap("wrapS");
            out.wrap_t = wrap("wrapT");
            samplers_.push_back(out);
        }
        const json& tarr = r_.array(doc_, "textures", "");
        for (std::size_t i = 0; i < tarr.size(); ++i) {
            std::string ptr = "/textures/" + std::to_string(i);
            const json& t = tarr[i];
            if (!t.is_object()) r_.fail(ptr, "must be an object");
            Texture out;
            out.image = r_.index(t, "source", ptr, scene_.images.size(), "image");
            const json& ext = r_.object(t, "extensions", ptr);
            std::string ep = ptr + "/extensions/";
            // EXT_texture_webp and KHR_texture_basisu (a KTX2 image: Basis Universal ETC1S or UASTC,
            // decoded by fresnel/core/ktx2.h like any image) name an image that takes the place of
            // the core source when it decoded; without one, the core source stays.
            for (const char* name : {"EXT_texture_webp", "KHR_texture_basisu"}) {
                const json* e = r_.find(ext, name);
                if (!e) continue;
                const std::string xp = ep + name, x = name;
                int src = r_.index(*e, "source", xp, scene_.images.size(), "image");
                if (src < 0) warn(xp, x + ": no source; using the core source");
                else if (scene_.images[std::size_t(src)].valid() || !opt_.decode_images || out.image < 0) out.image = src;
                else warn(xp, x + ": image " + std::to_string(src) + " is not usable; using the core source");
            }
            if (out.image < 0) warn(ptr, "texture has no supported image source; using a neutral texture");
            int s = r_.index(t, "sampler", ptr, samplers_.size(), "sampler");
            if (s >= 0) out.sampler = samplers_[std::size_t(s)];
            scene_.textures.push_back(out);
        }
    }

    TextureRef texture_ref(const json& mat, const char* key, const std::string& mptr, float* scale = nullptr,
                           const char* scale_key = nullptr) {
        TextureRef ref;
        const json* info = r_.find(mat, key);
        if (!info) return ref;
        std::string ptr = JsonReader::at(mptr, key);
        if (!info->is_object()) r_.fail(ptr, "must be an object");
        ref.texture = r_.index(*info, "index", ptr, scene_.textures.size(), "texture", true);
        ref.tex_coord = int(r_.integer(*info, "texCoord", ptr, 0, 0, 1 << 20));
        if (scale) *scale = float(r_.number(*info, scale_key, ptr, *scale));
        const json& ext = r_.object(*info, "extensions", ptr);
        if (const json* tt = r_.find(ext, "KHR_texture_transform")) {
            std::string tp = ptr + "/extensions/KHR_texture_transform";
            auto offset = r_.numbers<2>(*tt, "offset", tp, {0.0, 0.0});
            double rotation = r_.number(*tt, "rotation", tp, 0.0);
            auto sc = r_.numbers<2>(*tt, "scale", tp, {1.0, 1.0});
            ref.tex_coord = int(r_.integer(*tt, "texCoord", tp, ref.tex_coord, 0, 1 << 20));
            TextureTransform t;
            t.offset = glm::vec2(float(offset[0]), float(offset[1]));
            t.rotation = float(rotation);
            t.scale = glm::vec2(float(sc[0]), float(sc[1]));
            ref.set_transform(t);
        }
        if (ref.tex_coord > 1) {
            warn(ptr + "/texCoord", "TEXCOORD_" + std::to_string(ref.tex_coord) + " is not supported; texture ignored");
            ref.texture = -1;
        }
        return ref;
    }

    // The material extensions, each into its block as written (the specification's
    // defaults where absent). Only validation happens here (ranges, ior < 1); the rules
    // that turn the values into shading inputs are fresnel::evaluate's.
    void load_material_extensions(const json& ext, const std::string& ptr, Material& out) {
        auto at = [&](const char* name) { return ptr + "/extensions/" + name; };
        auto vec3_of = [&](const json& j, const char* key, const std::string& p, std::array<double, 3> def) {
            auto c = r_.numbers<3>(j, key, p, def);
            return glm::vec3(float(c[0]), float(c[1]), float(c[2]));
        };
        auto num = [&](const json& j, const char* key, const std::string& p, double def) {
            return float(r_.number(j, key, p, def));
        };
        if (const json* es = r_.find(ext, "KHR_materials_emissive_strength"))
            out.emissive_strength = EmissiveStrengthExt{
                std::max(0.0f, num(*es, "emissiveStrength", at("KHR_materials_emissive_strength"), 1.0))};
        if (r_.has(ext, "KHR_materials_unlit")) out.unlit = UnlitExt{};
        if (const json* ior = r_.find(ext, "KHR_materials_ior")) {
            std::string ip = at("KHR_materials_ior");
            IorExt b;
            b.ior = num(*ior, "ior", ip, 1.5);
            if (b.ior != 0.0f && b.ior < 1.0f) {
                warn(ip + "/ior", "ior below 1; using 1.5");
                b.ior = 1.5f;
            }
            out.ior = b;
        }
        if (const json* sp = r_.find(ext, "KHR_materials_specular")) {
            std::string sptr = at("KHR_materials_specular");
            SpecularExt b;
            b.specular_factor = std::max(0.0f, num(*sp, "specularFactor", sptr, 1.0));
            b.specular_texture = texture_ref(*sp, "specularTexture", sptr);
            b.specular_color_factor = glm::max(vec3_of(*sp, "specularColorFactor", sptr, {1, 1, 1}), 0.0f);
            b.specular_color_texture = texture_ref(*sp, "specularColorTexture", sptr);
            out.specular = b;
        }
        if (const json* cc = r_.find(ext, "KHR_materials_clearcoat")) {
            std::string cp = at("KHR_materials_clearcoat");
            ClearcoatExt b;
            b.clearcoat_factor = std::clamp(num(*cc, "clearcoatFactor", cp, 0.0), 0.0f, 1.0f);
            b.clearcoat_texture = texture_ref(*cc, "clearcoatTexture", cp);
            b.clearcoat_roughness_factor = std::clamp(num(*cc, "clearcoatRoughnessFactor", cp, 0.0), 0.0f, 1.0f);
            b.clearcoat_roughness_texture = texture_ref(*cc, "clearcoatRoughnessTexture", cp);
            b.clearcoat_normal_texture =
                texture_ref(*cc, "clearcoatNormalTexture", cp, &b.clearcoat_normal_scale, "scale");
            out.clearcoat = b;
        }
        if (const json* sg = r_.find(ext, "KHR_materials_pbrSpecularGlossiness")) {
            std::string gp = at("KHR_materials_pbrSpecularGlossiness");
            SpecularGlossinessExt b;
            auto d = r_.numbers<4>(*sg, "diffuseFactor", gp, {1, 1, 1, 1});
            b.diffuse_factor = glm::clamp(glm::vec4(d[0], d[1], d[2], d[3]), 0.0f, 1.0f);
            b.diffuse_texture = texture_ref(*sg, "diffuseTexture", gp);
            b.specular_factor = glm::clamp(vec3_of(*sg, "specularFactor", gp, {1, 1, 1}), 0.0f, 1.0f);
            b.glossiness_factor = std::clamp(num(*sg, "glossinessFactor", gp, 1.0), 0.0f, 1.0f);
            b.specular_glossiness_texture = texture_ref(*sg, "specularGlossinessTexture", gp);
            out.specular_glossiness = b;
        }
        if (const json* e = r_.find(ext, "KHR_materials_sheen")) {
            std::string p = at("KHR_materials_sheen");
            SheenExt b;
            b.sheen_color_factor = glm::max(vec3_of(*e, "sheenColorFactor", p, {0, 0, 0}), 0.0f);
            b.sheen_color_texture = texture_ref(*e, "sheenColorTexture", p);
            b.sheen_roughness_factor = std::clamp(num(*e, "sheenRoughnessFactor", p, 0.0), 0.0f, 1.0f);
            b.sheen_roughness_texture = texture_ref(*e, "sheenRoughnessTexture", p);
            out.sheen = b;
        }
        if (const json* e = r_.find(ext, "KHR_materials_transmission")) {
            std::string p = at("KHR_materials_transmission");
            TransmissionExt b;
            b.transmission_factor = std::clamp(num(*e, "transmissionFactor", p, 0.0), 0.0f, 1.0f);
            b.transmission_texture = texture_ref(*e, "transmissionTexture", p);
            out.transmission = b;
        }
        if (const json* e = r_.find(ext, "KHR_materials_volume")) {
            std::string p = at("KHR_materials_volume");
            VolumeExt b;
            b.thickness_factor = std::max(0.0f, num(*e, "thicknessFactor", p, 0.0));
            b.thickness_texture = texture_ref(*e, "thicknessTexture", p);
            if (r_.find(*e, "attenuationDistance"))
                b.attenuation_distance = num(*e, "attenuationDistance", p, 0.0);
            if (!(b.attenuation_distance > 0.0f)) {
                warn(p + "/attenuationDistance", "must be positive; using infinity");
                b.attenuation_distance = std::numeric_limits<float>::infinity();
            }
            b.attenuation_color = glm::max(vec3_of(*e, "attenuationColor", p, {1, 1, 1}), 0.0f);
            out.volume = b;
        }
        if (const json* e = r_.find(ext, "KHR_materials_iridescence")) {
            std::string p = at("KHR_materials_iridescence");
            IridescenceExt b;
            b.iridescence_factor = std::clamp(num(*e, "iridescenceFactor", p, 0.0), 0.0f, 1.0f);
            b.iridescence_texture = texture_ref(*e, "iridescenceTexture", p);
            b.iridescence_ior = std::max(1.0f, num(*e, "iridescenceIor", p, 1.3));  // the schema's minimum
            b.iridescence_thickness_minimum = std::max(0.0f, num(*e, "iridescenceThicknessMinimum", p, 100.0));
            b.iridescence_thickness_maximum = std::max(0.0f, num(*e, "iridescenceThicknessMaximum", p, 400.0));
            b.iridescence_thickness_texture = texture_ref(*e, "iridescenceThicknessTexture", p);
            out.iridescence = b;
        }
        if (const json* e = r_.find(ext, "KHR_materials_anisotropy")) {
            std::string p = at("KHR_materials_anisotropy");
            AnisotropyExt b;
            b.anisotropy_strength = std::clamp(num(*e, "anisotropyStrength", p, 0.0), 0.0f, 1.0f);
            b.anisotropy_rotation = num(*e, "anisotropyRotation", p, 0.0);
            b.anisotropy_texture = texture_ref(*e, "anisotropyTexture", p);
            out.anisotropy = b;
        }
        if (const json* e = r_.find(ext, "KHR_materials_dispersion"))
            out.dispersion = DispersionExt{std::max(0.0f, num(*e, "dispersion", at("KHR_materials_dispersion"), 0.0))};
        if (const json* e = r_.find(ext, "KHR_materials_diffuse_transmission")) {
            std::string p = at("KHR_materials_diffuse_transmission");
            DiffuseTransmissionExt b;
            b.diffuse_transmission_factor = std::clamp(num(*e, "diffuseTransmissionFactor", p, 0.0), 0.0f, 1.0f);
            b.diffuse_transmission_texture = texture_ref(*e, "diffuseTransmissionTexture", p);
            b.diffuse_transmission_color_factor =
                glm::max(vec3_of(*e, "diffuseTransmissionColorFactor", p, {1, 1, 1}), 0.0f);
            b.diffuse_transmission_color_texture = texture_ref(*e, "diffuseTransmissionColorTexture", p);
            out.diffuse_transmission = b;
        }
        if (const json* e = r_.find(ext, "KHR_materials_diffuse_roughness")) {
            std::string p = at("KHR_materials_diffuse_roughness");
            DiffuseRoughnessExt b;
            b.diffuse_roughness_factor = std::clamp(num(*e, "diffuseRoughnessFactor", p, 0.0), 0.0f, 1.0f);
            b.diffuse_roughness_texture = texture_ref(*e, "diffuseRoughnessTexture", p);
            out.diffuse_roughness = b;
        }
    }

    void load_materials() {
        const json& arr = r_.array(doc_, "materials", "");
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = "/materials/" + std::to_string(i);
            const json& m = arr[i];
            if (!m.is_object()) r_.fail(ptr, "must be an object");
            Material out;
            out.name = r_.string(m, "name", ptr);
            const json& pbr = r_.object(m, "pbrMetallicRoughness", ptr);
            std::string pp = ptr + "/pbrMetallicRoughness";
            auto bc = r_.numbers<4>(pbr, "baseColorFactor", pp, {1, 1, 1, 1});
            out.base_color_factor = glm::clamp(glm::vec4(bc[0], bc[1], bc[2], bc[3]), 0.0f, 1.0f);
            out.base_color = texture_ref(pbr, "baseColorTexture", pp);
            out.metallic_factor = std::clamp(float(r_.number(pbr, "metallicFactor", pp, 1.0)), 0.0f, 1.0f);
            out.roughness_factor = std::clamp(float(r_.number(pbr, "roughnessFactor", pp, 1.0)), 0.0f, 1.0f);
            out.metallic_roughness = texture_ref(pbr, "metallicRoughnessTexture", pp);
            out.normal = texture_ref(m, "normalTexture", ptr, &out.normal_scale, "scale");
            out.occlusion = texture_ref(m, "occlusionTexture", ptr, &out.occlusion_strength, "strength");
            out.occlusion_strength = std::clamp(out.occlusion_strength, 0.0f, 1.0f);
            out.emissive = texture_ref(m, "emissiveTexture", ptr);
            auto em = r_.numbers<3>(m, "emissiveFactor", ptr, {0, 0, 0});
            out.emissive_factor = glm::max(glm::vec3(em[0], em[1], em[2]), 0.0f);
            std::string mode = r_.string(m, "alphaMode", ptr, "OPAQUE");
            if (mode == "OPAQUE") out.alpha_mode = AlphaMode::Opaque;
            else if (mode == "MASK") out.alpha_mode = AlphaMode::Mask;
            else if (mode == "BLEND") out.alpha_mode = AlphaMode::Blend;
            else r_.fail(ptr + "/alphaMode", "invalid alpha mode '" + mode + "'");
            out.alpha_cutoff = std::max(0.0f, float(r_.number(m, "alphaCutoff", ptr, 0.5)));
            out.double_sided = r_.boolean(m, "doubleSided", ptr, false);
            const json& ext = r_.object(m, "extensions", ptr);
            load_material_extensions(ext, ptr, out);
            scene_.materials.push_back(std::move(out));
        }
    }

    void load_meshes(const gltf::AccessorDecoder& accessors) {
        const json& arr = r_.array(doc_, "meshes", "");
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = "/meshes/" + std::to_string(i);
            const json& m = arr[i];
            if (!m.is_object()) r_.fail(ptr, "must be an object");
            Mesh mesh;
            mesh.name = r_.string(m, "name", ptr);
            const json& prims = r_.array(m, "primitives", ptr);
            if (prims.empty()) r_.fail(ptr + "/primitives", "a mesh needs at least one primitive");
            std::vector<float> weights;  // default morph weights: the rest pose
            const json& wj = r_.array(m, "weights", ptr);
            for (std::size_t k = 0; k < wj.size(); ++k) {
                if (!wj[k].is_number()) r_.fail(ptr + "/weights/" + std::to_string(k), "must be a number");
                weights.push_back(wj[k].get<float>());
            }
            for (std::size_t p = 0; p < prims.size(); ++p) {
                std::string pptr = ptr + "/primitives/" + std::to_string(p);
                auto prim = gltf::build_primitive(r_, prims[p], pptr, accessors, scene_.materials, opt_.max_vertices,
                                                  uses("KHR_mesh_quantization"), weights, diag_);
                if (prim) {
                    keep_geometry(*prim, pptr);
                    load_variant_mappings(prims[p], pptr, *prim);
                    mesh.primitives.push_back(std::move(*prim));
                }
            }
            mesh.weights = std::move(weights);
            scene_.meshes.push_back(std::move(mesh));
        }
    }

    // KHR_materials_variants: the variant names (root) and each primitive's mappings.
    void load_variants() {
        const json& ext = r_.object(doc_, "extensions", "");
        const json* v = r_.find(ext, "KHR_materials_variants");
        if (!v) return;
        std::string ptr = "/extensions/KHR_materials_variants";
        if (!v->is_object()) r_.fail(ptr, "must be an object");
        const json& arr = r_.array(*v, "variants", ptr);
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string vp = ptr + "/variants/" + std::to_string(i);
            if (!arr[i].is_object()) r_.fail(vp, "must be an object");
            std::string name = r_.string(arr[i], "name", vp);
            if (name.empty()) r_.fail(vp + "/name", "KHR_materials_variants: a variant needs a name");
            scene_.material_variants.push_back(name);
        }
    }

    void load_variant_mappings(const json& prim, const std::string& pptr, Primitive& out) {
        const json& ext = r_.object(prim, "extensions", pptr);
        const json* v = r_.find(ext, "KHR_materials_variants");
        if (!v) return;
        std::string ptr = pptr + "/extensions/KHR_materials_variants";
        const json& maps = r_.array(*v, "mappings", ptr);
        out.variant_materials.assign(scene_.material_variants.size(), -1);
        for (std::size_t m = 0; m < maps.size(); ++m) {
            std::string mp = ptr + "/mappings/" + std::to_string(m);
            if (!maps[m].is_object()) r_.fail(mp, "must be an object");
            int material = r_.index(maps[m], "material", mp, scene_.materials.size(), "material", true);
            const json& vars = r_.array(maps[m], "variants", mp);
            for (std::size_t k = 0; k < vars.size(); ++k) {
                int var = r_.index_value(vars[k], mp + "/variants/" + std::to_string(k), scene_.material_variants.size(),
                                         "variant");
                out.variant_materials[std::size_t(var)] = material;
            }
        }
    }

    void load_cameras() {
        const json& arr = r_.array(doc_, "cameras", "");
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = "/cameras/" + std::to_string(i);
            const json& c = arr[i];
            if (!c.is_object()) r_.fail(ptr, "must be an object");
            Camera cam;
            cam.name = r_.string(c, "name", ptr);
            std::string type = r_.string(c, "type", ptr);
            if (type == "perspective") {
                const json* p = r_.find(c, "perspective");
                if (!p || !p->is_object()) r_.fail(ptr + "/perspective", "is required for a perspective camera");
                std::string pp = ptr + "/perspective";
                cam.yfov = float(r_.number(*p, "yfov", pp, -1));
                if (!(cam.yfov > 0)) r_.fail(pp + "/yfov", "must be positive");
                if (cam.yfov >= 3.1f) {
                    warn(pp + "/yfov", "field of view of " + std::to_string(cam.yfov) + " rad is too wide; using 3.1");
                    cam.yfov = 3.1f;
                }
                if (r_.has(*p, "aspectRatio")) {
                    float a = float(r_.number(*p, "aspectRatio", pp, 1));
                    if (a > 0) cam.aspect_ratio = a;
                    else warn(pp + "/aspectRatio", "must be positive; using the image's aspect ratio");
                }
                cam.znear = float(r_.number(*p, "znear", pp, -1));
                if (!(cam.znear > 0)) r_.fail(pp + "/znear", "must be positive");
                if (r_.has(*p, "zfar")) {
                    float f = float(r_.number(*p, "zfar", pp, 0));
                    if (!(f > cam.znear)) r_.fail(pp + "/zfar", "must be greater than znear");
                    cam.zfar = f;
                }
            } else if (type == "orthographic") {
                const json* o = r_.find(c, "orthographic");
                if (!o || !o->is_object()) r_.fail(ptr + "/orthographic", "is required for an orthographic camera");
                std::string op = ptr + "/orthographic";
                cam.type = Camera::Type::Orthographic;
                cam.xmag = float(r_.number(*o, "xmag", op, 0));
                cam.ymag = float(r_.number(*o, "ymag", op, 0));
                cam.znear = float(r_.number(*o, "znear", op, -1));
                cam.zfar = float(r_.number(*o, "zfar", op, 0));
                if (cam.xmag == 0 || cam.ymag == 0) r_.fail(op, "xmag and ymag must be non-zero");
                if (!(cam.znear >= 0) || !(*cam.zfar > cam.znear)) r_.fail(op, "needs 0 <= znear < zfar");
            } else {
                r_.fail(ptr + "/type", "must be 'perspective' or 'orthographic'");
            }
            scene_.cameras.push_back(cam);
        }
    }

    void load_lights() {
        const json& ext = r_.object(doc_, "extensions", "");
        const json& lp = r_.object(ext, "KHR_lights_punctual", "/extensions");
        std::string base = "/extensions/KHR_lights_punctual";
        for_each_light(lp, base, [&](const json& l, const std::string& ptr, Light& light, const std::string& type) {
            if (type == "directional") light.type = Light::Type::Directional;
            else if (type == "point") light.type = Light::Type::Point;
            else if (type == "spot") light.type = Light::Type::Spot;
            else {
                warn(ptr + "/type", "unknown light type '" + type + "'; light ignored");
                light.intensity = 0.0f;
            }
            if (light.type != Light::Type::Directional) {
                light.range = float(r_.number(l, "range", ptr, 0.0));
                if (light.range < 0) r_.fail(ptr + "/range", "must be positive");
            }
            if (light.type == Light::Type::Spot) {
                const json* s = r_.find(l, "spot");
                static const json empty = json::object();
                const json& spot = s ? *s : empty;
                light.inner_cone_angle = float(r_.number(spot, "innerConeAngle", ptr + "/spot", 0.0));
                light.outer_cone_angle = float(r_.number(spot, "outerConeAngle", ptr + "/spot", 0.7853981634));
                if (!(light.outer_cone_angle > 0 && light.outer_cone_angle <= 1.5707964f) ||
                    !(light.inner_cone_angle >= 0 && light.inner_cone_angle < light.outer_cone_angle))
                    r_.fail(ptr + "/spot", "needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
            }
        });
        area_light_base_ = scene_.lights.size();
        load_area_lights(ext);
    }

    // Each light of an extension's `lights` list (KHR_lights_punctual, EXT_lights_area): its name,
    // colour and intensity read, then `type_specific(json, pointer, light, type)`, then added.
    template <class F>
    void for_each_light(const json& extension, const std::string& base, F&& type_specific) {
        const json& arr = r_.array(extension, "lights", base);
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = base + "/lights/" + std::to_string(i);
            const json& l = arr[i];
            if (!l.is_object()) r_.fail(ptr, "must be an object");
            Light light;
            light.name = r_.string(l, "name", ptr);
            auto col = r_.numbers<3>(l, "color", ptr, {1, 1, 1});
            light.color = glm::max(glm::vec3(col[0], col[1], col[2]), 0.0f);
            light.intensity = float(r_.number(l, "intensity", ptr, 1.0));
            if (!std::isfinite(light.intensity)) r_.fail(ptr + "/intensity", "is too large");
            light.intensity = std::max(0.0f, light.intensity);
            type_specific(l, ptr, light, r_.string(l, "type", ptr));
            scene_.lights.push_back(light);
        }
    }

    // EXT_lights_area (fresnel's, written by `convert --area-lights`): lights [{type rect|disk|
    // sphere|tube, color, intensity (nits), width, height (rect), radius (disk, sphere, tube),
    // length (tube, along the node's X), name}], a node
    // names one as extensions.EXT_lights_area.light. They follow the punctual lights in
    // Scene::lights.
    void load_area_lights(const json& ext) {
        const json& la = r_.object(ext, "EXT_lights_area", "/extensions");
        std::string base = "/extensions/EXT_lights_area";
        for_each_light(la, base, [&](const json& l, const std::string& ptr, Light& light, const std::string& type) {
            auto size = [&](const char* key, double fallback) {
                float v = float(r_.number(l, key, ptr, fallback));
                if (!(v > 0.0f && v < 1e9f)) r_.fail(ptr + "/" + key, "must be a positive length");
                return v;
            };
            if (type == "rect") {
                light.type = Light::Type::Rect;
                light.width = size("width", 1.0);
                light.height = size("height", 1.0);
            } else if (type == "disk" || type == "sphere") {
                light.type = type == "disk" ? Light::Type::Disk : Light::Type::Sphere;
                light.radius = size("radius", 0.5);
            } else if (type == "tube") {
                light.type = Light::Type::Tube;
                light.length = size("length", 1.0);
                light.radius = size("radius", 0.05);
            } else {
                warn(ptr + "/type", "unknown area light type '" + type + "'; light ignored");
                light.type = Light::Type::Sphere;
                light.intensity = 0.0f;
            }
        });
    }

    void load_nodes() {
        const json& arr = r_.array(doc_, "nodes", "");
        scene_.nodes.resize(arr.size());
        std::vector<int> parents(arr.size(), 0);
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = "/nodes/" + std::to_string(i);
            const json& n = arr[i];
            if (!n.is_object()) r_.fail(ptr, "must be an object");
            Node& node = scene_.nodes[i];
            node.name = r_.string(n, "name", ptr);
            node.mesh = r_.index(n, "mesh", ptr, scene_.meshes.size(), "mesh");
            node.camera = r_.index(n, "camera", ptr, scene_.cameras.size(), "camera");
            node.skin = r_.index(n, "skin", ptr, r_.array(doc_, "skins", "").size(), "skin");
            const json& ext = r_.object(n, "extensions", ptr);
            if (const json* l = r_.find(ext, "KHR_lights_punctual"))
                node.light = r_.index(*l, "light", ptr + "/extensions/KHR_lights_punctual", area_light_base_, "light", true);
            if (const json* l = r_.find(ext, "EXT_lights_area")) {
                if (node.light >= 0) r_.fail(ptr + "/extensions", "a node holds one light, not a punctual and an area light");
                int a = r_.index(*l, "light", ptr + "/extensions/EXT_lights_area", scene_.lights.size() - area_light_base_,
                                 "light", true);
                node.light = int(area_light_base_) + a;
            }
            if (const json* v = r_.find(ext, "KHR_node_visibility"))
                node.visible = r_.boolean(*v, "visible", ptr + "/extensions/KHR_node_visibility", true);
            const json& children = r_.array(n, "children", ptr);
            for (std::size_t c = 0; c < children.size(); ++c) {
                std::string cp = ptr + "/children/" + std::to_string(c);
                long long k = r_.index_value(children[c], cp, arr.size(), "node");
                if (std::size_t(k) == i) r_.fail(cp, "node is its own child");
                if (++parents[std::size_t(k)] > 1) r_.fail(cp, "node " + std::to_string(k) + " has more than one parent");
                node.children.push_back(int(k));
            }
            if (const json* m = r_.find(n, "matrix")) {
                if (!m->is_array() || m->size() != 16) r_.fail(ptr + "/matrix", "must be 16 numbers");
                float v[16];
                for (int k = 0; k < 16; ++k) {
                    if (!(*m)[std::size_t(k)].is_number()) r_.fail(ptr + "/matrix/" + std::to_string(k), "must be a number");
                    v[k] = (*m)[std::size_t(k)].get<float>();
                    if (!std::isfinite(v[k])) r_.fail(ptr + "/matrix/" + std::to_string(k), "must be finite");
                }
                node.local = glm::make_mat4(v);  // column-major, as glTF stores it
                node.has_trs = false;
            } else {
                auto t = r_.numbers<3>(n, "translation", ptr, {0, 0, 0});
                auto q = r_.numbers<4>(n, "rotation", ptr, {0, 0, 0, 1});
                auto s = r_.numbers<3>(n, "scale", ptr, {1, 1, 1});
                glm::quat rot{static_cast<float>(q[3]), static_cast<float>(q[0]), static_cast<float>(q[1]), static_cast<float>(q[2])};
                float len = glm::length(rot);
                rot = len > 0 ? rot / len : glm::quat(1, 0, 0, 0);
                node.local = glm::translate(glm::mat4(1.0f), glm::vec3(t[0], t[1], t[2])) * glm::mat4_cast(rot) *
                             glm::scale(glm::mat4(1.0f), glm::vec3(s[0], s[1], s[2]));
                node.translation = glm::vec3(float(t[0]), float(t[1]), float(t[2]));
                node.rotation = rot;
                node.scale = glm::vec3(float(s[0]), float(s[1]), float(s[2]));
            }
        }
        // With at most one parent per node, a cycle means a set of nodes none of which is a root.
        std::vector<int> depth(arr.size(), -1);
        std::vector<int> stack;
        for (std::size_t i = 0; i < arr.size(); ++i) {
            if (parents[i] != 0) continue;
            stack.push_back(int(i));
            depth[i] = 0;
            while (!stack.empty()) {
                int n = stack.back();
                stack.pop_back();
                if (depth[std::size_t(n)] > opt_.max_node_depth)
                    r_.fail("/nodes/" + std::to_string(n), "node hierarchy deeper than " + std::to_string(opt_.max_node_depth));
                for (int c : scene_.nodes[std::size_t(n)].children) {
                    depth[std::size_t(c)] = depth[std::size_t(n)] + 1;
                    stack.push_back(c);
                }
            }
        }
        for (std::size_t i = 0; i < arr.size(); ++i)
            if (depth[i] < 0) r_.fail("/nodes/" + std::to_string(i), "node is part of a cycle in the node hierarchy");
        roots_parents_ = std::move(parents);
    }
    std::vector<int> roots_parents_;

    // EXT_mesh_gpu_instancing: a node whose mesh is drawn once per instance, each at the node's
    // world transform times the instance's TRANSLATION, ROTATION and SCALE. Each instance becomes a
    // child node of its own holding the mesh (named "NODE #K"), and the node keeps no mesh, so that
    // every consumer of the node graph (rasteriser, tracer, bounds, picking, writers) sees the
    // instances with nothing of its own to learn; the node's lights, camera and children stay
    // single. Accessors: TRANSLATION and SCALE VEC3 float, ROTATION VEC4 float or normalized
    // byte/short, one count; attributes named "_..." are the application's and ignored.
    void expand_gpu_instancing(const gltf::AccessorDecoder& accessors) {
        static const char* kExt = "EXT_mesh_gpu_instancing";
        const json& arr = r_.array(doc_, "nodes", "");
        const std::size_t original = scene_.nodes.size();
        for (std::size_t i = 0; i < original; ++i) {
            const json& ext = r_.object(arr[i], "extensions", "/nodes/" + std::to_string(i));
            const json* inst = r_.find(ext, kExt);
            if (!inst) continue;
            const std::string ptr = "/nodes/" + std::to_string(i) + "/extensions/" + kExt;
            if (!inst->is_object()) r_.fail(ptr, "must be an object");
            if (scene_.nodes[i].mesh < 0) {
                warn(ptr, "the node has no mesh to instance; ignored");
                continue;
            }
            if (scene_.nodes[i].skin >= 0) {
                warn(ptr, "instancing a skinned mesh is not supported; the mesh is drawn once, at the node");
                continue;
            }
            const json& attrs = r_.object(*inst, "attributes", ptr);
            std::vector<double> t, r, sc;
            std::size_t count = 0;
            bool any = false;
            for (auto it = attrs.begin(); it != attrs.end(); ++it) {
                const std::string name = it.key(), ap = ptr + "/attributes/" + name;
                if (!name.empty() && name[0] == '_') continue;  // application-specific
                if (name != "TRANSLATION" && name != "ROTATION" && name != "SCALE") {
                    warn(ap, "unknown instance attribute; ignored");
                    continue;
                }
                int a = r_.index(attrs, name.c_str(), ptr + "/attributes", accessors.accessor_count(), "accessor", true);
                int components = 0, type = 0;
                bool normalized = false;
                std::size_t n = 0;
                accessors.describe(a, components, type, normalized, n);
                const bool rotation = name == "ROTATION";
                const bool float_type = type == gltf_code::kFloat;
                const bool normalized_int = normalized && (type == gltf_code::kByte || type == gltf_code::kShort);
                if (components != (rotation ? 4 : 3) || !(float_type || (rotation && normalized_int)))
                    r_.fail(ap, std::string("must be ") + (rotation ? "VEC4 float or normalized byte/short" : "VEC3 float"));
                if (any && n != count)
                    r_.fail(ap, "accessor " + std::to_string(a) + " has " + std::to_string(n) + " elements, the others " +
                                    std::to_string(count));
                count = n;
                any = true;
                // The nodes the instances become, within the load's geometry budget.
                check_geometry(n * (sizeof(Node) + 3 * sizeof(double) * 4), ap);
                gltf::AccessorData d = accessors.read(a);
                for (double v : d.values)
                    if (!std::isfinite(v)) r_.fail(ap, "holds a value that is not finite");
                (name == "TRANSLATION" ? t : rotation ? r : sc) = std::move(d.values);
            }
            if (!any) r_.fail(ptr + "/attributes", "names no TRANSLATION, ROTATION or SCALE accessor");
            geometry_bytes_ += count * sizeof(Node);
            const int mesh = scene_.nodes[i].mesh;
            const std::vector<float> weights = scene_.nodes[i].weights;
            const std::string base = scene_.nodes[i].name.empty() ? "node " + std::to_string(i) : scene_.nodes[i].name;
            scene_.nodes[i].mesh = -1;
            scene_.nodes.reserve(scene_.nodes.size() + count);
            for (std::size_t k = 0; k < count; ++k) {
                Node n;
                n.name = base + " #" + std::to_string(k);
                n.mesh = mesh;
                n.weights = weights;
                if (!t.empty()) n.translation = glm::vec3(float(t[k * 3]), float(t[k * 3 + 1]), float(t[k * 3 + 2]));
                if (!r.empty()) {
                    glm::quat q{float(r[k * 4 + 3]), float(r[k * 4]), float(r[k * 4 + 1]), float(r[k * 4 + 2])};
                    float len = glm::length(q);
                    n.rotation = len > 0 ? q / len : glm::quat(1, 0, 0, 0);
                }
                if (!sc.empty()) n.scale = glm::vec3(float(sc[k * 3]), float(sc[k * 3 + 1]), float(sc[k * 3 + 2]));
                n.local = glm::translate(glm::mat4(1.0f), n.translation) * glm::mat4_cast(n.rotation) *
                          glm::scale(glm::mat4(1.0f), n.scale);
                scene_.nodes[i].children.push_back(int(scene_.nodes.size()));
                scene_.nodes.push_back(std::move(n));
            }
        }
    }

    // Skins into Scene::skins. Skins were read only to pose them (GltfLoadOptions::pose_skins):
    // without that option, a skin that cannot be read is dropped with a warning (its joints
    // left empty) so that such files still load in their bind pose.
    void load_skins(const gltf::AccessorDecoder& accessors) {
        const json& skins = r_.array(doc_, "skins", "");
        scene_.skins.resize(skins.size());
        for (std::size_t k = 0; k < skins.size(); ++k) {
            try {
                scene_.skins[k] = load_skin(accessors, skins[k], "/skins/" + std::to_string(k));
            } catch (const Error& e) {
                if (opt_.pose_skins) throw;
                warn(e.where(), e.reason() + "; skin ignored");
            }
        }
    }

    Skin load_skin(const gltf::AccessorDecoder& accessors, const json& skin, const std::string& ptr) {
        if (!skin.is_object()) r_.fail(ptr, "must be an object");
        Skin out;
        out.name = r_.string(skin, "name", ptr);
        const json& joints = r_.array(skin, "joints", ptr);
        if (joints.empty()) r_.fail(ptr + "/joints", "a skin needs at least one joint");
        std::vector<glm::mat4> ibm(joints.size(), glm::mat4(1.0f));
        int ibm_index = r_.index(skin, "inverseBindMatrices", ptr, accessors.accessor_count(), "accessor");
        if (ibm_index >= 0) {
            gltf::AccessorData d = accessors.read(ibm_index);
            if (d.components != 16 || d.count < joints.size())
                r_.fail(ptr + "/inverseBindMatrices", "must be MAT4 with one matrix per joint");
            for (std::size_t j = 0; j < joints.size(); ++j)
                for (int c = 0; c < 16; ++c) ibm[j][c / 4][c % 4] = float(d.values[j * 16 + std::size_t(c)]);
        }
        for (std::size_t j = 0; j < joints.size(); ++j)
            out.joints.push_back(int(r_.index_value(joints[j], ptr + "/joints/" + std::to_string(j), scene_.nodes.size(), "node")));
        out.inverse_bind = std::move(ibm);
        return out;
    }

    // Animations into Scene::animations. They do not change the rest pose, so an animation
    // that cannot be used is dropped with a warning, never failing the file: accessors in
    // range and of the right type, keyframe times finite and strictly increasing, output
    // counts matching the times, channels naming nodes with TRS (not matrices).
    // "/nodes/N/translation|rotation|scale|weights" -> node N and that path; false otherwise.
    bool node_pointer(const std::string& pointer, int& node, std::string& path) const {
        const std::string prefix = "/nodes/";
        if (pointer.rfind(prefix, 0) != 0) return false;
        std::size_t slash = pointer.find('/', prefix.size());
        if (slash == std::string::npos) return false;
        std::string index = pointer.substr(prefix.size(), slash - prefix.size());
        std::string prop = pointer.substr(slash + 1);
        if (index.empty() || index.size() > 9 || (index.size() > 1 && index[0] == '0') ||
            !std::all_of(index.begin(), index.end(), [](char ch) { return ch >= '0' && ch <= '9'; }))
            return false;
        std::size_t n = std::stoul(index);
        if (n >= scene_.nodes.size()) return false;
        if (prop != "translation" && prop != "rotation" && prop != "scale" && prop != "weights") return false;
        node = int(n);
        path = prop;
        return true;
    }

    void load_animations(const gltf::AccessorDecoder& accessors) {
        const json& arr = r_.array(doc_, "animations", "");
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = "/animations/" + std::to_string(i);
            try {
                Animation a = load_animation(accessors, arr[i], ptr);
                scene_.animations.push_back(std::move(a));
            } catch (const Error& e) {
                warn(e.where(), e.reason() + "; animation ignored");
            }
        }
    }

    Animation load_animation(const gltf::AccessorDecoder& accessors, const json& a, const std::string& ptr) {
        if (!a.is_object()) r_.fail(ptr, "must be an object");
        Animation out;
        out.name = r_.string(a, "name", ptr);
        const json& samplers = r_.array(a, "samplers", ptr);
        const json& channels = r_.array(a, "channels", ptr);
        for (std::size_t k = 0; k < samplers.size(); ++k) {
            std::string sp = ptr + "/samplers/" + std::to_string(k);
            const json& sj = samplers[k];
            if (!sj.is_object()) r_.fail(sp, "must be an object");
            AnimationSampler s;
            std::string interp = r_.string(sj, "interpolation", sp, "LINEAR");
            if (interp == "LINEAR") s.interpolation = Interpolation::Linear;
            else if (interp == "STEP") s.interpolation = Interpolation::Step;
            else if (interp == "CUBICSPLINE") s.interpolation = Interpolation::CubicSpline;
            else r_.fail(sp + "/interpolation", "unknown interpolation '" + interp + "'");
            int in = r_.index(sj, "input", sp, accessors.accessor_count(), "accessor", true);
            int outi = r_.index(sj, "output", sp, accessors.accessor_count(), "accessor", true);
            gltf::AccessorData din = accessors.read(in);
            if (din.components != 1 || din.component_type != gltf_code::kFloat)
                r_.fail(sp + "/input", "keyframe times must be SCALAR FLOAT");
            if (din.count == 0) r_.fail(sp + "/input", "a sampler needs at least one keyframe");
            s.input.resize(din.count);
            for (std::size_t t = 0; t < din.count; ++t) {
                s.input[t] = float(din.values[t]);
                if (!std::isfinite(s.input[t])) r_.fail(sp + "/input", "keyframe time " + std::to_string(t) + " is not finite");
                if (t > 0 && !(s.input[t] > s.input[t - 1]))
                    r_.fail(sp + "/input", "keyframe times must be strictly increasing (time " + std::to_string(t) + ")");
            }
            gltf::AccessorData dout = accessors.read(outi);
            if (dout.component_type != gltf_code::kFloat && !dout.normalized)
                r_.fail(sp + "/output", "keyframe values must be FLOAT or normalized integers");
            std::size_t per = s.interpolation == Interpolation::CubicSpline ? 3 : 1;
            std::size_t elements = din.count * per;
            if (dout.components == 1) {  // morph weights: one value per target per element
                if (dout.count % elements != 0 || dout.count == 0)
                    r_.fail(sp + "/output", std::to_string(dout.count) + " values are not a whole number per keyframe (" +
                                                std::to_string(elements) + ")");
                s.width = int(std::min<std::size_t>(dout.count / elements, 1u << 16));
                if (std::size_t(s.width) * elements != dout.count) r_.fail(sp + "/output", "too many morph weights");
            } else if (dout.components >= 2 && dout.components <= 4) {  // VEC2: texture transforms (pointer)
                if (dout.count != elements)
                    r_.fail(sp + "/output", "has " + std::to_string(dout.count) + " values for " + std::to_string(elements) +
                                                " keyframe elements");
                s.width = dout.components;
            } else {
                r_.fail(sp + "/output", "keyframe values must be SCALAR, VEC2, VEC3 or VEC4");
            }
            s.output.resize(dout.values.size());
            for (std::size_t v = 0; v < dout.values.size(); ++v) {
                s.output[v] = float(dout.values[v]);
                if (!std::isfinite(s.output[v])) r_.fail(sp + "/output", "keyframe value " + std::to_string(v) + " is not finite");
            }
            out.samplers.push_back(std::move(s));
        }
        for (std::size_t k = 0; k < channels.size(); ++k) {
            std::string cp = ptr + "/channels/" + std::to_string(k);
            const json& cj = channels[k];
            if (!cj.is_object()) r_.fail(cp, "must be an object");
            AnimationChannel c;
            c.sampler = r_.index(cj, "sampler", cp, out.samplers.size(), "sampler", true);
            const json& target = r_.object(cj, "target", cp);
            std::string tp = cp + "/target";
            std::string path = r_.string(target, "path", tp);
            c.node = r_.index(target, "node", tp, scene_.nodes.size(), "node");
            int width = out.samplers[std::size_t(c.sampler)].width;
            if (path == "pointer") {
                // KHR_animation_pointer: a node's TRS and weights become ordinary channels (so a
                // rotation is still interpolated on the sphere); other properties stay pointers.
                std::string pp = tp + "/extensions/KHR_animation_pointer";
                const json* ext = r_.find(target, "extensions");
                const json* ap = ext && ext->is_object() ? r_.find(*ext, "KHR_animation_pointer") : nullptr;
                if (!ap || !ap->is_object()) {
                    warn(tp, "path 'pointer' without a KHR_animation_pointer object; channel ignored");
                    continue;
                }
                std::string pointer = r_.string(*ap, "pointer", pp);
                if (!node_pointer(pointer, c.node, path)) {
                    std::string why;
                    int want = animation_pointer_width(scene_, pointer, &why);
                    if (want == 0) {
                        warn(pp + "/pointer", "'" + pointer.substr(0, 200) + "': " + why + "; channel ignored");
                        continue;
                    }
                    if (width != want) {
                        warn(cp + "/sampler", "the sampler's values (" + std::to_string(width) + " a keyframe) do not fit '" +
                                                  pointer.substr(0, 200) + "' (" + std::to_string(want) + "); channel ignored");
                        continue;
                    }
                    c.path = AnimationPath::Pointer;
                    c.node = -1;
                    c.pointer = pointer;
                    out.channels.push_back(std::move(c));
                    continue;
                }
            }
            if (c.node < 0) continue;  // no target node: ignored, as the specification says
            if (path == "translation") c.path = AnimationPath::Translation;
            else if (path == "rotation") c.path = AnimationPath::Rotation;
            else if (path == "scale") c.path = AnimationPath::Scale;
            else if (path == "weights") c.path = AnimationPath::Weights;
            else r_.fail(tp + "/path", "unknown path '" + path + "'");
            int want = c.path == AnimationPath::Rotation ? 4 : c.path == AnimationPath::Weights ? 0 : 3;
            if (want != 0 && width != want)
                r_.fail(cp + "/sampler", "the sampler's values do not fit path '" + path + "'");
            if (c.path == AnimationPath::Weights && scene_.nodes[std::size_t(c.node)].mesh < 0) {
                warn(tp + "/node", "morph weights animated on a node without a mesh; channel ignored");
                continue;
            }
            if (!scene_.nodes[std::size_t(c.node)].has_trs && c.path != AnimationPath::Weights) {
                warn(tp + "/node", "node " + std::to_string(c.node) + " has a matrix and cannot be animated; channel ignored");
                continue;
            }
            out.channels.push_back(c);
        }
        return out;
    }

    // With GltfLoadOptions::pose_skins, skinned meshes are posed at rest: each vertex moved
    // by its joints' world matrices times their inverse bind matrices (glTF 2.0 skinning, no
    // animation). The posed copy lives in world space; the node keeps its matrix for the
    // camera bounds. Without it (the default) they stay in their bind pose.
    void pose_skins() {
        if (scene_.skins.empty() || !opt_.pose_skins) return;
        // The hierarchy is a forest (checked in load_nodes).
        SkinMatrices posed;
        fresnel::skin_matrices(scene_.nodes, scene_.skins, posed);
        const std::vector<glm::mat4>& world = posed.world;
        const std::vector<std::vector<glm::mat4>>& skin_matrices = posed.skins;
        for (std::size_t i = 0; i < scene_.nodes.size(); ++i) {
            Node& node = scene_.nodes[i];
            if (node.skin < 0 || node.mesh < 0) continue;
            const auto& mats = skin_matrices[std::size_t(node.skin)];
            Mesh posed = scene_.meshes[std::size_t(node.mesh)];
            bool any = false;
            for (auto& p : posed.primitives) {
                if (auto bad = find_invalid_joint(p, mats.size()))
                    r_.fail("/nodes/" + std::to_string(i), "vertex " + std::to_string(bad->vertex) + " uses joint " +
                                                               std::to_string(bad->joint) + " of a skin with " +
                                                               std::to_string(mats.size()));
                any = any || !p.joints.empty();
                pose_skinned(p, mats, world[i]);  // a primitive without joints follows the node
            }
            if (!any) continue;
            scene_.meshes.push_back(std::move(posed));
            node.mesh = int(scene_.meshes.size()) - 1;
            node.world_space_mesh = true;
        }
    }

    void load_scenes() {
        const json& arr = r_.array(doc_, "scenes", "");
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string ptr = "/scenes/" + std::to_string(i);
            const json& s = arr[i];
            if (!s.is_object()) r_.fail(ptr, "must be an object");
            std::vector<int> roots;
            const json& nodes = r_.array(s, "nodes", ptr);
            for (std::size_t k = 0; k < nodes.size(); ++k) {
                std::string np = ptr + "/nodes/" + std::to_string(k);
                long long n = r_.index_value(nodes[k], np, scene_.nodes.size(), "node");
                if (roots_parents_[std::size_t(n)] != 0) r_.fail(np, "scene root node " + std::to_string(n) + " has a parent");
                if (std::find(roots.begin(), roots.end(), int(n)) != roots.end()) r_.fail(np, "node listed twice");
                roots.push_back(int(n));
            }
            scene_.scenes.push_back(std::move(roots));
        }
        if (r_.has(doc_, "scene")) scene_.default_scene = r_.index(doc_, "scene", "", scene_.scenes.size(), "scene");
        if (scene_.scenes.empty()) {
            // No scenes: show every root node, so the model is still viewable.
            std::vector<int> roots;
            for (std::size_t i = 0; i < scene_.nodes.size(); ++i)
                if (roots_parents_[i] == 0) roots.push_back(int(i));
            if (!roots.empty()) warn("/scenes", "file has no scenes; showing all root nodes");
            scene_.scenes.push_back(std::move(roots));
            scene_.default_scene = 0;
        }
    }
};

}  // namespace

Scene load_gltf_from_memory(std::span<const std::uint8_t> bytes, const std::string& name, const fs::path& base_dir,
                            Diagnostics& diagnostics, const GltfLoadOptions& options) {
    Loader loader(name, base_dir, diagnostics, options);
    return as_file_error(name, [&] { return loader.load(bytes); });
}

Scene load_gltf(const fs::path& path, Diagnostics& diagnostics, const GltfLoadOptions& options) {
    auto bytes = read_file_bytes(path, options.max_file_bytes);
    return load_gltf_from_memory(bytes, path.string(), path.parent_path(), diagnostics, options);
}

}  // namespace fresnel
