#pragma once
// KHR_materials_transmission, KHR_materials_volume and KHR_materials_dispersion, shaded as
// the Khronos glTF Sample Viewer (1.1.0, the engine of ../shared/tools/khronos-ref) does:
//
//  - Image-based light: the opaque scene (and the environment when it is drawn) is rendered
//    first, in linear radiance, into a square texture with a mip chain; a transmissive point
//    reads it where the refracted ray leaves the volume (the point plus the thickness-scaled
//    refracted direction, projected by the camera), at the mip level
//    log2(size) * apply_ior_to_roughness(roughness, ior), attenuates it by Beer-Lambert over
//    that distance, and weights it by (1 - the split-sum specular albedo) and the base colour.
//    The result replaces the diffuse lobe in proportion to the transmission factor:
//        diffuse' = mix(diffuse, refraction, transmission)
//    before the dielectric Fresnel mix, so it is weighted by 1 - F once more (as Khronos does).
//  - Punctual lights: the specification's BTDF, a GGX lobe around the light mirrored through
//    the surface, at roughness apply_ior_to_roughness(alpha, ior), towards the light direction
//    moved by the transmission ray (btdf_punctual); it replaces the Lambert term likewise.
//  - Dispersion: three refracted rays at ior -/+ (ior - 1) * 0.025 * dispersion, one per
//    colour channel (Khronos' getIBLVolumeRefraction with MATERIAL_DISPERSION).
//
// The GLSL twins are in shaders/transmission.glsl; tests/gpu/transmission_gpu_test.cpp keeps
// them equal. The renderer's pass (libs/render/src/renderer.cpp) draws the opaque texture.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "fresnel/material/brdf.h"

namespace fresnel {

// The transmission inputs at a point (fresnel::evaluate fills them; all zero / neutral
// without the extensions).
struct TransmissionInputs {
    float factor = 0.0f;      // transmissionFactor * transmissionTexture R
    float thickness = 0.0f;   // thicknessFactor * thicknessTexture G, in the mesh's own units
    glm::vec3 attenuation_color{1.0f};
    // attenuationDistance; 0 stands for the specification's default, infinity (no
    // attenuation), as in the Khronos viewer (the shader cannot be given an infinity on ES).
    float attenuation_distance = 0.0f;
    float dispersion = 0.0f;  // KHR_materials_dispersion
    float ior = 1.5f;         // KHR_materials_ior (1.5 without)
};

namespace transmission {

// The Khronos viewer's size of the opaque-scene texture (1024 x 1024, whatever the frame size:
// the frame's view and projection are drawn into it, stretched); the mip level of a lookup
// depends on it.
inline constexpr int kFramebufferSize = 1024;

// Khronos' applyIorToRoughness: the refracted lobe is as rough as the reflected one at
// ior >= 1.5 and sharper towards ior 1 (none at 1).
inline float apply_ior_to_roughness(float roughness, float ior) {
    return roughness * std::clamp(ior * 2.0f - 2.0f, 0.0f, 1.0f);
}

// The mip level of the opaque-scene texture a lookup at perceptual roughness uses.
inline float framebuffer_lod(float perceptual_roughness, float ior, int size = kFramebufferSize) {
    return std::log2(float(size)) * apply_ior_to_roughness(perceptual_roughness, ior);
}

// Beer-Lambert: radiance * attenuationColor^(distance / attenuationDistance); an
// attenuation distance of 0 means infinite (no attenuation).
inline glm::vec3 volume_attenuation(glm::vec3 radiance, float distance, glm::vec3 color, float attenuation_distance) {
    if (attenuation_distance == 0.0f) return radiance;
    float e = distance / attenuation_distance;
    return radiance * glm::vec3(std::pow(color.x, e), std::pow(color.y, e), std::pow(color.z, e));
}

// GLSL's refract(i, n, eta) (glm::refract is the same formula).
inline glm::vec3 refract(glm::vec3 i, glm::vec3 n, float eta) {
    float d = glm::dot(n, i);
    float k = 1.0f - eta * eta * (1.0f - d * d);
    if (k < 0.0f) return glm::vec3(0.0f);
    return eta * i - (eta * d + std::sqrt(k)) * n;
}

// Khronos' getVolumeTransmissionRay: the refracted view ray through a volume of `thickness`,
// scaled by the model matrix's axis lengths (thickness is in the mesh's units). Zero thickness
// (KHR_materials_volume absent) gives a zero ray: a thin-walled surface.
inline glm::vec3 volume_ray(glm::vec3 n, glm::vec3 v, float thickness, float ior, glm::vec3 model_scale) {
    glm::vec3 r = refract(-v, glm::normalize(n), 1.0f / ior);
    float len = glm::length(r);
    if (len <= 0.0f) return glm::vec3(0.0f);
    return r / len * thickness * model_scale;
}

// The three iors of KHR_materials_dispersion (Khronos: halfSpread = (ior - 1) * 0.025 * dispersion).
inline glm::vec3 dispersion_iors(float ior, float dispersion) {
    float half = (ior - 1.0f) * 0.025f * dispersion;
    return glm::vec3(ior - half, ior, ior + half);
}

// Khronos' getPunctualRadianceTransmission: the GGX transmission lobe for a punctual light in
// direction l (from the point, already moved by the transmission ray), without n.l:
//   (1 - F_schlick(f0, f90, v.h)) * base_color * D(n.h) * V(n.l', n.v), with l' = l mirrored
//   through the surface plane, h = normalize(l' + v), at alpha' = apply_ior_to_roughness(alpha, ior).
inline glm::vec3 btdf_punctual(glm::vec3 n, glm::vec3 v, glm::vec3 l, float alpha, glm::vec3 f0, glm::vec3 f90,
                               glm::vec3 base_color, float ior) {
    float a = apply_ior_to_roughness(alpha, ior);
    glm::vec3 l_mirror = glm::normalize(l + 2.0f * n * glm::dot(-l, n));
    glm::vec3 h = glm::normalize(l_mirror + v);
    float d = brdf::d_ggx(std::clamp(glm::dot(n, h), 0.0f, 1.0f), a);
    glm::vec3 f = brdf::f_schlick(f0, f90, std::clamp(glm::dot(v, h), 0.0f, 1.0f));
    float vis = brdf::v_smith_ggx_correlated(std::clamp(glm::dot(n, l_mirror), 0.0f, 1.0f),
                                             std::clamp(glm::dot(n, v), 0.0f, 1.0f), a);
    return (1.0f - f) * base_color * d * vis;
}

// The weight of the refracted image-based light (Khronos' getIBLVolumeRefraction, after the
// lookup): (1 - (f0 * A + f90 * B)) * base_color, with (A, B) the split-sum table at (n.v, roughness).
inline glm::vec3 refraction_weight(glm::vec3 f0, glm::vec3 f90, float lut_a, float lut_b, glm::vec3 base_color) {
    return (1.0f - (f0 * lut_a + f90 * lut_b)) * base_color;
}

}  // namespace transmission
}  // namespace fresnel
