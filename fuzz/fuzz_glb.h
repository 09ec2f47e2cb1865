#pragma once
// Shared by the decoder fuzz targets: wraps a JSON document and fuzzed bytes (the BIN
// chunk) into a GLB and loads it the way fuzz_gltf does.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fresnel/scene/gltf_loader.h"

namespace fresnel::fuzz {

inline void load_glb(const nlohmann::json& j, const std::uint8_t* bin, std::size_t bin_size) {
    std::string text = j.dump();
    while (text.size() % 4) text += ' ';
    std::size_t padded = (bin_size + 3) / 4 * 4;
    std::vector<std::uint8_t> out;
    auto u32 = [&](std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
    };
    u32(0x46546C67);
    u32(2);
    u32(std::uint32_t(12 + 8 + text.size() + 8 + padded));
    u32(std::uint32_t(text.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    u32(std::uint32_t(padded));
    u32(0x004E4942);
    out.insert(out.end(), bin, bin + bin_size);
    out.resize(out.size() + padded - bin_size, 0);
    Diagnostics diag;
    GltfLoadOptions options;
    options.max_vertices = 1 << 20;
    options.max_total_bytes = 256u << 20;
    options.image_limits.max_decoded_bytes = 64u << 20;
    options.threads = 1;
    // FRESNEL_FUZZ_VERBOSE=1: say what each input became (to check that seeds reach the decoder).
    static const bool verbose = std::getenv("FRESNEL_FUZZ_VERBOSE") != nullptr;
    try {
        Scene s = load_gltf_from_memory(out, "fuzz.glb", "/nonexistent-fresnel-fuzz", diag, options);
        if (verbose) {
            std::size_t triangles = 0, pixels = 0;
            for (const auto& m : s.meshes)
                for (const auto& p : m.primitives) triangles += p.triangle_count();
            for (const auto& i : s.images) pixels += std::size_t(i.pixels.width) * std::size_t(i.pixels.height);
            std::fprintf(stderr, "loaded: %zu triangles, %zu pixels, %zu warnings\n", triangles, pixels, diag.lines().size());
        }
    } catch (const Error& e) {
        if (verbose) std::fprintf(stderr, "error: %s\n", e.what());
    }
}

}  // namespace fresnel::fuzz
