// copy_gltf (scene_writer.h): glTF -> glTF as the file is, in another container. The JSON is
// kept key by key (nlohmann::ordered_json) and the binary data byte for byte; only what the
// container change needs is rewritten: buffers merged into one, buffer views and images
// pointing into it, and a missing asset.generator added.
#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/image.h"
#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/scene_writer.h"
#include "gltf_codes.h"
#include "uri_policy.h"

namespace fresnel {

namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

using gltf_code::kChunkBin;
using gltf_code::kChunkJson;
using gltf_code::kGlbMagic;
constexpr std::size_t kMaxBytes = std::size_t(2) << 30;  // one file or buffer, as the loader

std::uint32_t u32(const std::vector<std::uint8_t>& b, std::size_t at) {
    return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
           std::uint32_t(b[at + 3]) << 24;
}
void put_u32(std::vector<std::uint8_t>& b, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(std::uint8_t(v >> (8 * i)));
}
std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}
// The MIME type of encoded image bytes, by their magic ("" when unknown).
std::string mime_of(const std::vector<std::uint8_t>& b) {
    auto starts = [&](std::initializer_list<std::uint8_t> m) {
        return b.size() >= m.size() && std::equal(m.begin(), m.end(), b.begin());
    };
    if (starts({0x89, 'P', 'N', 'G'})) return "image/png";
    if (starts({0xFF, 0xD8, 0xFF})) return "image/jpeg";
    if (b.size() >= 12 && starts({'R', 'I', 'F', 'F'}) && std::memcmp(b.data() + 8, "WEBP", 4) == 0) return "image/webp";
    if (starts({0xAB, 'K', 'T', 'X', ' ', '2', '0'})) return "image/ktx2";
    return "";
}

}  // namespace

std::vector<fs::path> copy_gltf(const fs::path& source, const fs::path& dest, Diagnostics& diagnostics,
                                bool allow_external_files) {
    const std::string src_name = source.string(), dst_name = dest.string();
    const bool in_glb = lower(source.extension().string()) == ".glb", out_glb = lower(dest.extension().string()) == ".glb";
    // The whole file through the loader first: what the loader refuses is not copied.
    {
        GltfLoadOptions check;
        check.allow_external_files = allow_external_files;
        check.decode_images = false;
        Diagnostics ignored;
        (void)load_gltf(source, ignored, check);
    }
    const std::vector<std::uint8_t> bytes = read_file_bytes(source, kMaxBytes);
    std::size_t json_at = 0, json_size = bytes.size();
    std::vector<std::uint8_t> glb_bin;
    bool has_glb_bin = false;
    if (in_glb) {
        if (bytes.size() < 20 || u32(bytes, 0) != kGlbMagic || u32(bytes, 16) != kChunkJson)
            throw Error(src_name, "byte 0", "not a GLB file with a JSON chunk first");
        json_size = u32(bytes, 12);
        json_at = 20;
        const std::size_t bin_at = json_at + json_size;
        if (json_size > bytes.size() - json_at) throw Error(src_name, "byte 12", "the JSON chunk runs past the end");
        if (bin_at + 8 <= bytes.size() && u32(bytes, bin_at + 4) == kChunkBin) {
            const std::size_t n = u32(bytes, bin_at);
            if (n > bytes.size() - bin_at - 8) throw Error(src_name, "byte " + std::to_string(bin_at), "the BIN chunk runs past the end");
            glb_bin.assign(bytes.begin() + std::ptrdiff_t(bin_at + 8), bytes.begin() + std::ptrdiff_t(bin_at + 8 + n));
            has_glb_bin = true;
        }
    }
    ojson doc = ojson::parse(bytes.begin() + std::ptrdiff_t(json_at), bytes.begin() + std::ptrdiff_t(json_at + json_size));
    const fs::path src_dir = source.parent_path().empty() ? fs::path(".") : source.parent_path();
    const fs::path dst_dir = dest.parent_path().empty() ? fs::path(".") : dest.parent_path();
    std::error_code ec;
    const bool same_folder = fs::equivalent(fs::absolute(src_dir), fs::absolute(dst_dir), ec);

    // The bytes a URI names (a data URI, or a file beside the model).
    auto uri_bytes = [&](const std::string& uri, const std::string& where, std::string* mime) {
        std::string error, m;
        if (gltf::is_data_uri(uri)) {
            auto data = gltf::decode_data_uri(uri, kMaxBytes, m, error);
            if (!data) throw Error(src_name, where, error);
            if (mime) *mime = m;
            return *data;
        }
        auto path = gltf::resolve_uri(uri, src_dir, allow_external_files, error);
        if (!path) throw Error(src_name, where, error);
        return read_file_bytes(*path, kMaxBytes);
    };

    // Every buffer with data goes into one (8-byte aligned starts); a buffer without data (a
    // meshopt fallback) stays a buffer of its own.
    std::vector<std::uint8_t> bin;
    std::vector<std::size_t> start;  // per old buffer: its offset in `bin`, or npos
    std::vector<int> new_index;      // per old buffer: its index in the new list
    ojson buffers = ojson::array();
    buffers.push_back(ojson::object());  // the merged buffer, filled below
    const bool had_buffers = doc.contains("buffers") && doc["buffers"].is_array();
    if (had_buffers) {
        bool glb_bin_used = false;
        for (std::size_t i = 0; i < doc["buffers"].size(); ++i) {
            ojson& b = doc["buffers"][i];
            const std::string where = "/buffers/" + std::to_string(i);
            std::vector<std::uint8_t> data;
            bool has_data = true;
            if (b.contains("uri") && b["uri"].is_string()) {
                data = uri_bytes(b["uri"].get<std::string>(), where + "/uri", nullptr);
            } else if (in_glb && has_glb_bin && !glb_bin_used) {
                data = glb_bin;
                glb_bin_used = true;
            } else {
                has_data = false;
            }
            if (!has_data) {
                start.push_back(std::string::npos);
                new_index.push_back(int(buffers.size()));
                ojson kept = b;
                kept.erase("uri");
                buffers.push_back(kept);
                continue;
            }
            const std::size_t length = b.value("byteLength", std::size_t(0));
            if (data.size() < length) throw Error(src_name, where, "holds fewer bytes than its byteLength");
            data.resize(length);  // a GLB's BIN chunk may be padded past the buffer
            while (bin.size() % 8) bin.push_back(0);
            start.push_back(bin.size());
            new_index.push_back(0);
            bin.insert(bin.end(), data.begin(), data.end());
            // Names, extras and extensions of the merged buffers: the first buffer's are kept.
            if (i == 0)
                for (auto it = b.begin(); it != b.end(); ++it)
                    if (it.key() != "uri" && it.key() != "byteLength") buffers[0][it.key()] = it.value();
        }
    }
    // Buffer views point into the merged buffer (EXT_meshopt_compression's own reference too).
    auto remap = [&](ojson& ref, const std::string& where) {
        if (!ref.contains("buffer") || !ref["buffer"].is_number_unsigned()) return;
        const std::size_t b = ref["buffer"].get<std::size_t>();
        if (b >= start.size()) throw Error(src_name, where + "/buffer", "no such buffer");
        ref["buffer"] = new_index[b];
        if (start[b] != std::string::npos) ref["byteOffset"] = ref.value("byteOffset", std::size_t(0)) + start[b];
    };
    if (doc.contains("bufferViews") && doc["bufferViews"].is_array())
        for (std::size_t i = 0; i < doc["bufferViews"].size(); ++i) {
            ojson& v = doc["bufferViews"][i];
            const std::string where = "/bufferViews/" + std::to_string(i);
            remap(v, where);
            if (v.contains("extensions") && v["extensions"].contains("EXT_meshopt_compression"))
                remap(v["extensions"]["EXT_meshopt_compression"], where + "/extensions/EXT_meshopt_compression");
        }

    // Images: inside a .glb every image lives in the buffer (its bytes as they are, its MIME
    // type); beside a .gltf a file image stays a file (copied when the folder changes).
    FileSet files;
    std::set<std::string> copied;
    if (doc.contains("images") && doc["images"].is_array())
        for (std::size_t i = 0; i < doc["images"].size(); ++i) {
            ojson& img = doc["images"][i];
            const std::string where = "/images/" + std::to_string(i);
            if (!img.contains("uri") || !img["uri"].is_string()) continue;
            const std::string uri = img["uri"].get<std::string>();
            if (out_glb) {
                std::string mime;
                std::vector<std::uint8_t> data = uri_bytes(uri, where + "/uri", &mime);
                if (mime.empty() || mime == "application/octet-stream") mime = mime_of(data);
                if (mime.empty() && img.contains("mimeType")) mime = img["mimeType"].get<std::string>();
                if (mime.empty()) throw Error(src_name, where, "an image of unknown type cannot go into a .glb");
                while (bin.size() % 4) bin.push_back(0);
                if (!doc.contains("bufferViews")) doc["bufferViews"] = ojson::array();
                doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", data.size()}});
                bin.insert(bin.end(), data.begin(), data.end());
                img.erase("uri");
                img["bufferView"] = doc["bufferViews"].size() - 1;
                img["mimeType"] = mime;
            } else if (!gltf::is_data_uri(uri) && !same_folder) {
                std::string error;
                auto from = gltf::resolve_uri(uri, src_dir, allow_external_files, error);
                auto to = gltf::resolve_uri(uri, dst_dir, false, error);
                if (!from || !to) {
                    diagnostics.warn(dst_name, where + "/uri", "'" + uri + "' is not copied beside the new file: " + error);
                    continue;
                }
                if (copied.insert(to->lexically_normal().string()).second) {
                    fs::create_directories(to->parent_path(), ec);
                    files.stage(*to, std::span<const std::uint8_t>(read_file_bytes(*from, kMaxBytes)));
                }
            }
        }

    while (bin.size() % 4) bin.push_back(0);
    if (bin.empty() && buffers.size() > 1) {
        // No buffer held data (only meshopt fallbacks): no merged buffer; the others move up.
        buffers.erase(buffers.begin());
        for (auto& v : doc["bufferViews"])
            for (ojson* ref : {&v, v.contains("extensions") && v["extensions"].contains("EXT_meshopt_compression")
                                       ? &v["extensions"]["EXT_meshopt_compression"]
                                       : nullptr})
                if (ref && ref->contains("buffer") && (*ref)["buffer"].is_number_unsigned())
                    (*ref)["buffer"] = (*ref)["buffer"].get<int>() - 1;
        doc["buffers"] = buffers;
    } else if (bin.empty()) {
        doc.erase("buffers");
    } else {
        buffers[0]["byteLength"] = bin.size();
        if (!out_glb) {
            buffers[0]["uri"] = dest.stem().string() + ".bin";
            // uri first, as writers put it.
            ojson b0 = ojson::object();
            b0["uri"] = buffers[0]["uri"];
            for (auto it = buffers[0].begin(); it != buffers[0].end(); ++it)
                if (it.key() != "uri") b0[it.key()] = it.value();
            buffers[0] = b0;
        }
        doc["buffers"] = buffers;
    }
    // asset: kept as it is (copyright, version, extras); a generator is added when there is none.
    if (!doc.contains("asset") || !doc["asset"].is_object()) doc["asset"] = {{"version", "2.0"}};
    if (!doc["asset"].contains("generator")) doc["asset"]["generator"] = "fresnel convert";
    // Extensions fresnel does not read are carried as they are, said once each.
    if (doc.contains("extensionsUsed") && doc["extensionsUsed"].is_array())
        for (const auto& e : doc["extensionsUsed"])
            if (e.is_string() && gltf_extension_support(e.get<std::string>()) == GltfExtensionSupport::Unsupported)
                diagnostics.warn(src_name, "/extensionsUsed",
                                 e.get<std::string>() + " is not read by fresnel: carried to the new file as it is");

    if (out_glb) {
        std::string text = doc.dump();
        while (text.size() % 4) text.push_back(' ');
        std::vector<std::uint8_t> out;
        put_u32(out, kGlbMagic);
        put_u32(out, 2);
        put_u32(out, 0);
        put_u32(out, std::uint32_t(text.size()));
        put_u32(out, kChunkJson);
        out.insert(out.end(), text.begin(), text.end());
        if (!bin.empty()) {
            put_u32(out, std::uint32_t(bin.size()));
            put_u32(out, kChunkBin);
            out.insert(out.end(), bin.begin(), bin.end());
        }
        const std::uint32_t total = std::uint32_t(out.size());
        for (int i = 0; i < 4; ++i) out[8 + std::size_t(i)] = std::uint8_t(total >> (8 * i));
        files.stage(dest, std::span<const std::uint8_t>(out));
    } else {
        if (doc.contains("buffers")) files.stage(dst_dir / (dest.stem().string() + ".bin"), std::span<const std::uint8_t>(bin));
        files.stage(dest, doc.dump(2) + "\n");
    }
    files.commit();
    return files.paths();
}

}  // namespace fresnel
