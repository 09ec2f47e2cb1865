#pragma once
// The glTF BSDF of an evaluated material as a Monte Carlo estimator needs it (the path tracer,
// libs/trace): its value, a direction drawn from it and that direction's pdf. The value is
// fresnel::shade_bsdf (evaluate.h): shade_light's layering of the lobes, with the thin-walled
// transmission below the surface, never a second copy. Directions are drawn from a mixture of
// lobes, each a BxDF in pbrt-v4's shape (its own frame, sample and pdf kept together), chosen
// with a probability from its estimated reflectance at the view (lobe_probabilities):
//   diffuse    CosineLobe about the shading normal (Lambert, the EON lobe of
//              KHR_materials_diffuse_roughness and KHR_materials_sheen's broad lobe)
//   specular   GgxLobe, visible normals about the shading normal (KHR_materials_anisotropy at
//              the geometric mean of its two roughnesses)
//   clearcoat  GgxLobe about the coat normal, when there is a coat
//   transmission  KHR_materials_transmission, thin-walled: a GgxLobe at
//              apply_ior_to_roughness(alpha, ior) mirrored through the surface; it takes the
//              share T of the diffuse lobe's weight
//   diffuse transmission  KHR_materials_diffuse_transmission: a CosineLobe about -n, with the
//              share of the diffuse lobe's weight the factor gives, its colour for the base's
// and the pdf of a direction is the mixture's (one-sample MIS over the lobes). Any pdf that
// covers the value keeps the estimate unbiased; bsdf_test holds the estimator of every lobe
// combination to a quadrature of shade_bsdf.
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "fresnel/material/evaluate.h"
#include "fresnel/material/sampling.h"

namespace fresnel {

// Perceptual roughness a sampled BSDF is shaded with at least: the BRDF's D is a delta at 0,
// which neither sampling nor evaluation can represent in floats (0.03: alpha 9e-4,
// kMinSampledAlpha).
inline constexpr float kMinSampledRoughness = 0.03f;

namespace bxdf {

// An orthonormal shading frame about n.
struct Frame {
    glm::vec3 t{1, 0, 0}, b{0, 1, 0}, n{0, 0, 1};
    Frame() = default;
    explicit Frame(glm::vec3 normal) : n(normal) { sampling::basis(n, t, b); }
    glm::vec3 to_local(glm::vec3 w) const { return {glm::dot(w, t), glm::dot(w, b), glm::dot(w, n)}; }
    glm::vec3 to_world(glm::vec3 w) const { return w.x * t + w.y * b + w.z * n; }
};

// Cosine-weighted directions about the frame's normal (or, `below`, about its opposite).
struct CosineLobe {
    Frame frame;
    bool below = false;
    // A direction (world), or a zero vector where the sample is lost.
    glm::vec3 sample(glm::vec2 u) const;
    float pdf(glm::vec3 l) const;
};

// GGX visible normals about the frame's normal at `alpha`, reflected about them (or, `mirrored`,
// reflected and mirrored through the surface: the thin-walled transmission).
struct GgxLobe {
    Frame frame;
    glm::vec3 v_local{0, 0, 1};  // the view in the frame
    float alpha = 1.0f;
    bool mirrored = false;
    glm::vec3 sample(glm::vec2 u) const;
    float pdf(glm::vec3 l) const;
};

}  // namespace bxdf

struct BsdfLobes {
    float diffuse = 0, specular = 0, clearcoat = 0, transmission = 0;  // probabilities, summing to 1 (or all 0)
    float diffuse_transmission = 0;
};
BsdfLobes lobe_probabilities(const EvaluatedMaterial& m, glm::vec3 v);

struct BsdfSample {
    glm::vec3 l{0.0f};
    glm::vec3 f_cos{0.0f};  // f(v, l) |cos(theta_l)|
    float pdf = 0.0f;       // over solid angle; 0: no sample (absorbed)
    bool transmitted = false;  // through the surface (a transmission lobe): l is below it
    bool diffuse_transmitted = false;  // ... by the diffuse transmission lobe (no volume to cross)
};

// The BSDF at one shading point, seen from v (unit, towards the viewer; m.normal and
// m.clearcoat_normal must face it), with its lobe probabilities and frames set up once for
// the several queries a path vertex makes. `m` must outlive it.
class Bsdf {
public:
    // `model`: the BRDF's terms (brdf_model.h) that eval() uses; sampling stays GGX's. `comp`:
    // the specular lobes' energy compensation (evaluate.h) that eval() applies.
    Bsdf(const EvaluatedMaterial& m, glm::vec3 v, const brdf::BrdfModel& model = {}, const EnergyCompensation& comp = {});
    BsdfSample sample(glm::vec3 u) const;  // u uniform in [0,1)^3: lobe, then direction
    float pdf(glm::vec3 l) const;
    glm::vec3 eval(glm::vec3 l) const { return shade_bsdf(m_, v_, l, model_, comp_); }  // f |cos|
    const BsdfLobes& lobes() const { return lobes_; }

private:
    const EvaluatedMaterial& m_;
    glm::vec3 v_;
    brdf::BrdfModel model_;
    EnergyCompensation comp_;
    BsdfLobes lobes_;
    bxdf::CosineLobe diffuse_, diffuse_transmission_;
    bxdf::GgxLobe specular_, clearcoat_, transmission_;
};

// One-query forms of the same (tests).
BsdfSample sample_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 u);
float pdf_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l);
glm::vec3 eval_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l);  // f |cos|

}  // namespace fresnel
