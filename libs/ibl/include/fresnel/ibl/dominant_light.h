#pragma once
// The environment's dominant light (`--env-light dominant`): a small, bright region of the
// panorama that carries a large share of its light (a sun, a studio's key light) taken out of
// the image-based light and given back as a directional light, which the rasteriser shadows
// (split-sum image-based light is never shadowed). The region is replaced by the radiance of its
// surroundings, so light is neither lost nor counted twice: the light's irradiance is the
// region's radiance above that background, times its solid angle.
#include <optional>

#include <glm/vec3.hpp>

#include "fresnel/core/image.h"

namespace fresnel::ibl {

struct DominantLight {
    glm::vec3 direction{0.0f, 1.0f, 0.0f};  // unit, towards the light, in the panorama's frame (equirect_to_direction)
    glm::vec3 irradiance{0.0f};             // linear RGB on a surface facing it (a directional light's lux)
    float solid_angle = 0.0f;               // of the region taken out, steradians
    float share = 0.0f;                     // of the panorama's light (sum of luminance x solid angle)
    // The angular radius (radians) of a uniform disk as spread as the light about `direction`:
    // sqrt(2 E[theta^2]), the light's texels weighted by their luminance above the background
    // (the two texels the region is grown by carry almost none, unlike its solid angle). The
    // size its shadows come from (contact-hardening shadows).
    float angular_radius = 0.0f;
};

struct DominantLightOptions {
    // A texel belongs to a light when its luminance exceeds this many times the panorama's mean.
    float threshold = 30.0f;
    // The region (the texels above threshold connected to the brightest one) becomes a light only
    // when it carries at least this share of the panorama's light and spans at most this solid
    // angle (a larger region is sky, not a light).
    float min_share = 0.25f;
    float max_solid_angle = 0.2f;
};

// Finds the dominant light of an equirectangular `panorama` (linear RGB; 2:1) and, when there is
// one, takes it out of the panorama in place (its texels, grown by two, set to the median of the
// ring of three around them) and returns it; otherwise leaves the panorama as it is.
std::optional<DominantLight> split_dominant_light(ImageF& panorama, const DominantLightOptions& options = {});

}  // namespace fresnel::ibl
