#pragma once
// Sampling the glTF BSDF of an evaluated material for the path tracer. The BSDF itself is
// libs/material's: f(v, l) cos = fresnel::shade_light(m, v, l, 1) (the Appendix B BRDF with
// the clearcoat layering), never a second copy. Directions are drawn from a mixture of its
// lobes, each chosen with a probability from its estimated reflectance at the view:
//   diffuse    cosine-weighted about the shading normal (sampling::sample_cosine)
//   specular   GGX visible normals about the shading normal (sampling::sample_ggx_reflection)
//   clearcoat  GGX visible normals about the coat normal, when there is a coat
// and the pdf of a direction is the mixture's (one-sample MIS over the lobes).
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "fresnel/material/evaluate.h"

namespace fresnel::trace {

// Perceptual roughness the tracer shades with at least: the BRDF's D is a delta at 0, which
// neither sampling nor evaluation can represent in floats (0.03: alpha 9e-4).
inline constexpr float kMinTraceRoughness = 0.03f;

struct BsdfLobes {
    float diffuse = 0, specular = 0, clearcoat = 0;  // probabilities, summing to 1 (or all 0)
};
BsdfLobes lobe_probabilities(const EvaluatedMaterial& m, glm::vec3 v);

struct BsdfSample {
    glm::vec3 l{0.0f};
    glm::vec3 f_cos{0.0f};  // f(v, l) cos(theta_l)
    float pdf = 0.0f;       // over solid angle; 0: no sample (absorbed)
};

// v: unit direction towards the viewer; m.normal (and m.clearcoat_normal) must face v.
BsdfSample sample_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 u);
float pdf_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l);
glm::vec3 eval_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l);  // f cos

}  // namespace fresnel::trace
