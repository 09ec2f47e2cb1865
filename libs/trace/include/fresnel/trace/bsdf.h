#pragma once
// Sampling the glTF BSDF of an evaluated material for the path tracer. The BSDF itself is
// libs/material's: f(v, l) cos = fresnel::shade_light(m, v, l, 1) (the Appendix B BRDF with
// the clearcoat layering), never a second copy. Directions are drawn from a mixture of its
// lobes, each chosen with a probability from its estimated reflectance at the view:
//   diffuse    cosine-weighted about the shading normal (sampling::sample_cosine)
//   specular   GGX visible normals about the shading normal (sampling::sample_ggx_reflection)
//   clearcoat  GGX visible normals about the coat normal, when there is a coat
//   transmission  KHR_materials_transmission, thin-walled: the Khronos BTDF's lobe, GGX
//              visible normals at apply_ior_to_roughness(alpha, ior) mirrored through the
//              surface (transmission.h); it takes the share T of the diffuse lobe's weight
//   diffuse transmission  KHR_materials_diffuse_transmission: cosine-weighted about -n, with the
//              share of the diffuse lobe's weight the factor gives, its colour for the base's
// and the pdf of a direction is the mixture's (one-sample MIS over the lobes).
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "fresnel/material/evaluate.h"

namespace fresnel::trace {

// Perceptual roughness the tracer shades with at least: the BRDF's D is a delta at 0, which
// neither sampling nor evaluation can represent in floats (0.03: alpha 9e-4).
inline constexpr float kMinTraceRoughness = 0.03f;

struct BsdfLobes {
    float diffuse = 0, specular = 0, clearcoat = 0, transmission = 0;  // probabilities, summing to 1 (or all 0)
    float diffuse_transmission = 0;
};
BsdfLobes lobe_probabilities(const EvaluatedMaterial& m, glm::vec3 v);

struct BsdfSample {
    glm::vec3 l{0.0f};
    glm::vec3 f_cos{0.0f};  // f(v, l) cos(theta_l)
    float pdf = 0.0f;       // over solid angle; 0: no sample (absorbed)
    bool transmitted = false;  // through the surface (the transmission lobe): l is below it
    bool diffuse_transmitted = false;  // ... by the diffuse transmission lobe (no volume to cross)
};

// The BSDF at one shading point, seen from v (unit, towards the viewer; m.normal and
// m.clearcoat_normal must face it), with its lobe probabilities and frames set up once for
// the several queries a path vertex makes. `m` must outlive it.
class Bsdf {
public:
    // `model`: the BRDF's terms (brdf_model.h) that eval() uses; sampling stays GGX's (any
    // pdf that covers the lobe keeps the estimate unbiased).
    Bsdf(const EvaluatedMaterial& m, glm::vec3 v, const brdf::BrdfModel& model = {});
    BsdfSample sample(glm::vec3 u) const;  // u uniform in [0,1)^3: lobe, then direction
    float pdf(glm::vec3 l) const;
    glm::vec3 eval(glm::vec3 l) const;  // f cos
    const BsdfLobes& lobes() const { return lobes_; }

private:
    struct Frame {
        glm::vec3 t{1, 0, 0}, b{0, 1, 0}, n{0, 0, 1};
        glm::vec3 to_local(glm::vec3 w) const { return {glm::dot(w, t), glm::dot(w, b), glm::dot(w, n)}; }
        glm::vec3 to_world(glm::vec3 w) const { return w.x * t + w.y * b + w.z * n; }
    };
    const EvaluatedMaterial& m_;
    glm::vec3 v_;
    brdf::BrdfModel model_;
    BsdfLobes lobes_;
    Frame base_, coat_;
    glm::vec3 v_base_{0.0f}, v_coat_{0.0f};  // v in each frame
    float alpha_ = 0.0f, coat_alpha_ = 0.0f, transmission_alpha_ = 0.0f;
    // The transmission lobe's f cos at l below the surface (0 above).
    glm::vec3 eval_transmission(glm::vec3 l) const;
};

// One-query forms of the same (tests).
BsdfSample sample_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 u);
float pdf_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l);
glm::vec3 eval_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l);  // f cos

}  // namespace fresnel::trace
