#include "fresnel/core/color.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/mat3x3.hpp>

namespace fresnel {

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
float linear_to_srgb(float c) {
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}
glm::vec3 srgb_to_linear(glm::vec3 c) { return {srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z)}; }
glm::vec3 linear_to_srgb(glm::vec3 c) { return {linear_to_srgb(c.x), linear_to_srgb(c.y), linear_to_srgb(c.z)}; }

namespace {
struct NamedToneMapper {
    std::string_view name;
    ToneMapper value;
};
constexpr NamedToneMapper kToneMappers[] = {
    {"neutral", ToneMapper::Neutral}, {"aces", ToneMapper::Aces},   {"aces-hill", ToneMapper::AcesHill},
    {"reinhard", ToneMapper::Reinhard}, {"agx", ToneMapper::Agx}, {"none", ToneMapper::None},
};
}  // namespace

std::optional<ToneMapper> parse_tone_mapper(std::string_view name) {
    for (auto& t : kToneMappers)
        if (t.name == name) return t.value;
    return std::nullopt;
}
std::string_view tone_mapper_name(ToneMapper v) {
    for (auto& t : kToneMappers)
        if (t.value == v) return t.name;
    return "?";
}
std::optional<Encoding> parse_encoding(std::string_view name) {
    if (name == "srgb") return Encoding::Srgb;
    if (name == "gamma2.2") return Encoding::Gamma22;
    return std::nullopt;
}

glm::vec3 tone_map_neutral(glm::vec3 color) {
    const float start_compression = 0.8f - 0.04f;
    const float desaturation = 0.15f;
    float x = std::min(color.x, std::min(color.y, color.z));
    float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    color -= offset;
    float peak = std::max(color.x, std::max(color.y, color.z));
    if (peak < start_compression) return color;
    const float d = 1.0f - start_compression;
    float new_peak = 1.0f - d * d / (peak + d - start_compression);
    color *= new_peak / peak;
    float g = 1.0f - 1.0f / (desaturation * (peak - new_peak) + 1.0f);
    return glm::mix(color, glm::vec3(new_peak), g);
}

glm::vec3 tone_map_aces_narkowicz(glm::vec3 c) {
    const float a = 2.51f, b = 0.03f, cc = 2.43f, d = 0.59f, e = 0.14f;
    return glm::clamp((c * (a * c + b)) / (c * (cc * c + d) + e), 0.0f, 1.0f);
}

glm::vec3 tone_map_aces_hill(glm::vec3 c) {
    // Column-major, as in GLSL: sRGB -> RRT_SAT(AP1), and ODT_SAT -> sRGB.
    const glm::mat3 input(0.59719f, 0.07600f, 0.02840f, 0.35458f, 0.90834f, 0.13383f, 0.04823f, 0.01566f, 0.83777f);
    const glm::mat3 output(1.60475f, -0.10208f, -0.00327f, -0.53108f, 1.10813f, -0.07276f, -0.07367f, -0.00605f,
                           1.07602f);
    c = input * c;
    glm::vec3 a = c * (c + 0.0245786f) - 0.000090537f;
    glm::vec3 b = c * (0.983729f * c + 0.4329510f) + 0.238081f;
    c = output * (a / b);
    return glm::clamp(c, 0.0f, 1.0f);
}

glm::vec3 tone_map_reinhard(glm::vec3 c) { return c / (1.0f + glm::max(c, 0.0f)); }

glm::vec3 tone_map_agx(glm::vec3 c) {
    const glm::mat3 agx(0.842479062253094f, 0.0423282422610123f, 0.0423756549057051f, 0.0784335999999992f,
                        0.878468636469772f, 0.0784336f, 0.0792237451477643f, 0.0791661274605434f,
                        0.879142973793104f);
    const glm::mat3 agx_inv(1.19687900512017f, -0.0528968517574562f, -0.0529716355144438f, -0.0980208811401368f,
                            1.15190312990417f, -0.0980434501171241f, -0.0990297440797205f, -0.0989611768448433f,
                            1.15107367264116f);
    const float min_ev = -12.47393f, max_ev = 4.026069f;
    c = agx * glm::max(c, glm::vec3(1e-10f));
    c = glm::clamp(glm::log2(c), min_ev, max_ev);
    c = (c - min_ev) / (max_ev - min_ev);
    glm::vec3 x2 = c * c, x4 = x2 * x2;
    c = 15.5f * x4 * x2 - 40.14f * x4 * c + 31.96f * x4 - 6.868f * x2 * c + 0.4298f * x2 + 0.1191f * c - 0.00232f;
    c = agx_inv * c;
    // The curve's output is display-encoded with a 2.2 power; return it linear.
    return glm::pow(glm::clamp(c, 0.0f, 1.0f), glm::vec3(2.2f));
}

glm::vec3 tone_map(ToneMapper t, glm::vec3 c) {
    switch (t) {
        case ToneMapper::Neutral: return tone_map_neutral(c);
        case ToneMapper::Aces: return tone_map_aces_narkowicz(c);
        case ToneMapper::AcesHill: return tone_map_aces_hill(c);
        case ToneMapper::Reinhard: return tone_map_reinhard(c);
        case ToneMapper::Agx: return tone_map_agx(c);
        case ToneMapper::None: return c;
    }
    return c;
}

glm::vec3 encode_display(Encoding e, glm::vec3 c) {
    c = glm::clamp(c, 0.0f, 1.0f);
    if (e == Encoding::Gamma22) return glm::pow(c, glm::vec3(1.0f / 2.2f));
    return linear_to_srgb(c);
}
glm::vec3 decode_display(Encoding e, glm::vec3 c) {
    c = glm::clamp(c, 0.0f, 1.0f);
    if (e == Encoding::Gamma22) return glm::pow(c, glm::vec3(2.2f));
    return srgb_to_linear(c);
}

float exposure_scale(float ev) { return std::exp2(ev); }

}  // namespace fresnel
