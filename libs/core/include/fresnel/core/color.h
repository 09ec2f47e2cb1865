#pragma once
// Colour functions: transfer curves and tone mappers. Each one exists once here
// and once in shaders/color.glsl / shaders/tonemap.glsl; tests/gpu keeps them equal.
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace fresnel {

// Exact piecewise sRGB curves (IEC 61966-2-1), per channel.
float srgb_to_linear(float c);
float linear_to_srgb(float c);
glm::vec3 srgb_to_linear(glm::vec3 c);
glm::vec3 linear_to_srgb(glm::vec3 c);

enum class ToneMapper {
    Neutral,   // Khronos PBR Neutral (default): keeps base colours up to 0.8, compresses highlights
    Aces,      // ACES filmic fit by Krzysztof Narkowicz
    AcesHill,  // ACES RRT+ODT fit by Stephen Hill (sRGB -> AP1 -> fit -> sRGB)
    Reinhard,  // c / (1 + c) per channel
    Agx,       // AgX base look (Troy Sobotka), polynomial fit by Benjamin Wrensch
    None,      // no curve; clamped only when written to a display format
};

// Display encoding of the tone-mapped linear value.
enum class Encoding {
    Srgb,      // exact piecewise sRGB curve (default)
    Gamma22,   // pow(c, 1/2.2): what the Khronos Sample Viewer writes
};

std::optional<ToneMapper> parse_tone_mapper(std::string_view name);
std::string_view tone_mapper_name(ToneMapper t);
std::optional<Encoding> parse_encoding(std::string_view name);

// Applies the tone mapper to a linear (already exposed) colour. Results of the
// display curves lie in [0,1]; None returns its input unchanged.
glm::vec3 tone_map(ToneMapper t, glm::vec3 c);
glm::vec3 tone_map_neutral(glm::vec3 c);
glm::vec3 tone_map_aces_narkowicz(glm::vec3 c);
glm::vec3 tone_map_aces_hill(glm::vec3 c);
glm::vec3 tone_map_reinhard(glm::vec3 c);
glm::vec3 tone_map_agx(glm::vec3 c);

// Encodes a tone-mapped linear colour for display (input clamped to [0,1]).
glm::vec3 encode_display(Encoding e, glm::vec3 c);
glm::vec3 decode_display(Encoding e, glm::vec3 c);

// Exposure in EV: the linear multiplier 2^EV.
float exposure_scale(float ev);

}  // namespace fresnel
