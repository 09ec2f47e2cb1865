// The glTF loader's translation of sampler numbers into fresnel::Sampler's typed values:
// every value the specification allows, the defaults, and invalid values (a warning each,
// then the default).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fresnel/scene/gltf_loader.h"

using namespace fresnel;

namespace {

Scene load_samplers(const std::string& samplers, std::size_t count, Diagnostics& diag) {
    std::string textures;
    for (std::size_t i = 0; i < count; ++i) textures += std::string(i ? "," : "") + "{\"sampler\":" + std::to_string(i) + "}";
    textures += std::string(count ? "," : "") + "{}";  // one texture without a sampler
    std::string text = "{\"asset\":{\"version\":\"2.0\"},\"samplers\":[" + samplers + "],\"textures\":[" + textures + "]}";
    return load_gltf_from_memory({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, "samplers.gltf", ".", diag);
}

// Warnings about samplers (the textures here have no image, which warns too).
std::vector<std::string> sampler_warnings(const Diagnostics& diag) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < diag.warnings().size(); ++i)
        if (diag.warnings()[i].where.rfind("/samplers/", 0) == 0)
            out.push_back(diag.warnings()[i].where + ": " + diag.warnings()[i].message);
    return out;
}

}  // namespace

TEST(GltfSamplers, EveryMinFilterBecomesFilterAndMipmapMode) {
    Diagnostics diag;
    Scene s = load_samplers(R"({"minFilter":9728},{"minFilter":9729},{"minFilter":9984},)"
                            R"({"minFilter":9985},{"minFilter":9986},{"minFilter":9987})", 6, diag);
    EXPECT_TRUE(sampler_warnings(diag).empty());
    ASSERT_EQ(s.textures.size(), 7u);
    struct Want { Filter filter; MipmapMode mip; };
    const Want want[6] = {{Filter::Nearest, MipmapMode::None},    {Filter::Linear, MipmapMode::None},
                          {Filter::Nearest, MipmapMode::Nearest}, {Filter::Linear, MipmapMode::Nearest},
                          {Filter::Nearest, MipmapMode::Linear},  {Filter::Linear, MipmapMode::Linear}};
    for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(s.textures[i].sampler.min_filter, want[i].filter) << "sampler " << i;
        EXPECT_EQ(s.textures[i].sampler.mipmap, want[i].mip) << "sampler " << i;
        EXPECT_EQ(s.textures[i].sampler.uses_mipmaps(), want[i].mip != MipmapMode::None) << "sampler " << i;
    }
    // No sampler: trilinear, repeating.
    const Sampler& d = s.textures[6].sampler;
    EXPECT_EQ(d.min_filter, Filter::Linear);
    EXPECT_EQ(d.mipmap, MipmapMode::Linear);
    EXPECT_EQ(d.mag_filter, Filter::Linear);
    EXPECT_EQ(d.wrap_s, Wrap::Repeat);
    EXPECT_EQ(d.wrap_t, Wrap::Repeat);
}

TEST(GltfSamplers, MagFilterAndWrapModes) {
    Diagnostics diag;
    Scene s = load_samplers(R"({"magFilter":9728,"wrapS":33071,"wrapT":33648},{"magFilter":9729,"wrapS":33648,"wrapT":10497})",
                            2, diag);
    EXPECT_TRUE(sampler_warnings(diag).empty());
    ASSERT_EQ(s.textures.size(), 3u);
    EXPECT_EQ(s.textures[0].sampler.mag_filter, Filter::Nearest);
    EXPECT_EQ(s.textures[0].sampler.wrap_s, Wrap::ClampToEdge);
    EXPECT_EQ(s.textures[0].sampler.wrap_t, Wrap::MirroredRepeat);
    EXPECT_EQ(s.textures[1].sampler.mag_filter, Filter::Linear);
    EXPECT_EQ(s.textures[1].sampler.wrap_s, Wrap::MirroredRepeat);
    EXPECT_EQ(s.textures[1].sampler.wrap_t, Wrap::Repeat);
}

TEST(GltfSamplers, InvalidValuesWarnAndFallBack) {
    Diagnostics diag;
    // A mipmap filter is not a magnification filter; 1234 is nothing.
    Scene s = load_samplers(R"({"magFilter":9987,"minFilter":1234,"wrapS":9729,"wrapT":0})", 1, diag);
    ASSERT_EQ(s.textures.size(), 2u);
    const Sampler& t = s.textures[0].sampler;
    EXPECT_EQ(t.mag_filter, Filter::Linear);
    EXPECT_EQ(t.min_filter, Filter::Linear);
    EXPECT_EQ(t.mipmap, MipmapMode::Linear);
    EXPECT_EQ(t.wrap_s, Wrap::Repeat);
    EXPECT_EQ(t.wrap_t, Wrap::Repeat);
    auto warnings = sampler_warnings(diag);
    ASSERT_EQ(warnings.size(), 4u);
    std::string all;
    for (const auto& line : warnings) all += line + "\n";
    EXPECT_NE(all.find("/samplers/0/magFilter"), std::string::npos) << all;
    EXPECT_NE(all.find("invalid filter 1234"), std::string::npos) << all;
    EXPECT_NE(all.find("/samplers/0/wrapS"), std::string::npos) << all;
    EXPECT_NE(all.find("invalid wrap mode 0"), std::string::npos) << all;
}
