#pragma once
// glTF 2.0 loader: .gltf (with external, data-URI or no buffers) and .glb.
// The file is treated as hostile: every offset, stride, count and index is
// checked before use; sizes are capped; URIs may not leave the model's folder.
#include <algorithm>
#include <cstdint>
#include <filesystem>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

struct GltfLoadOptions {
    // Allow URIs outside the model's folder (absolute paths, ".." escapes). Never network.
    bool allow_external_files = false;
    std::size_t max_file_bytes = std::size_t(2) << 30;     // the .gltf/.glb and each external file
    // all buffers and images together: 8 GiB, or all of a 32-bit address space (the web build)
    std::size_t max_total_bytes = std::size_t(std::min<std::uint64_t>(std::uint64_t(8) << 30, SIZE_MAX));
    // The geometry a load decodes and keeps (every primitive's vertices, indices and morph
    // targets, each accessor while it is decoded, Draco's output) is bounded by the input:
    // 0 (the default) allows 256 MiB plus 64 bytes per byte of the file's buffers, so a few
    // hundred bytes of JSON naming huge zero-filled accessors cannot take gigabytes; a value
    // sets the budget itself (`--max-memory`). Over it, the load fails naming the accessor.
    std::size_t max_geometry_bytes = 0;
    std::size_t max_data_uri_bytes = std::size_t(512) << 20;
    std::size_t max_vertices = std::size_t(200) << 20;     // per primitive, after expansion
    int max_node_depth = 1024;
    ImageLimits image_limits{};
    bool decode_images = true;  // false: skip texture decoding (fresnel info)
    // With decode_images false: still read each image's bytes for its header (SceneImage::header,
    // encoded_bytes), as fresnel info lists formats and sizes.
    bool read_image_headers = false;
    // Keep each decoded image's encoded bytes (SceneImage::encoded), so that a renderer can
    // release the decoded pixels once they are on the GPU (a one-shot `fresnel render`).
    bool keep_encoded_images = false;
    // false (fresnel info): an unsupported extension in extensionsRequired is a warning, not
    // an error, so the file can still be described.
    bool require_supported_extensions = true;
    // Pose skinned meshes by their joints' rest transforms (joint world x inverse bind).
    // Off by default: skinned meshes are drawn in their bind pose with the node's matrix,
    // which is what the Khronos Sample Renderer's reference images show.
    bool pose_skins = false;
    unsigned threads = 0;       // image decoding threads, 0 = hardware concurrency
};

// Loads a model; throws fresnel::Error (file, JSON pointer, reason) on bad input.
// Recoverable problems (a missing texture, non-finite normals, ...) become warnings.
Scene load_gltf(const std::filesystem::path& path, Diagnostics& diagnostics, const GltfLoadOptions& options = {});

// Same, from memory (`name` is used in messages; external URIs resolve against `base_dir`).
Scene load_gltf_from_memory(std::span<const std::uint8_t> bytes, const std::string& name,
                            const std::filesystem::path& base_dir, Diagnostics& diagnostics,
                            const GltfLoadOptions& options = {});

// Extensions this loader understands (others in extensionsRequired are an error).
const std::vector<std::string>& supported_gltf_extensions();

// How fresnel handles an extension, for `fresnel info`: Supported (loaded and shaded),
// ReadNotShaded (read into the material with its defaults, not shaded yet: warns),
// Unsupported (ignored: warns; an error when required).
enum class GltfExtensionSupport { Supported, ReadNotShaded, Unsupported };
GltfExtensionSupport gltf_extension_support(const std::string& name);

}  // namespace fresnel
