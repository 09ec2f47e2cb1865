#include "fresnel/material/bsdf.h"

#include <algorithm>
#include <cmath>

#include "fresnel/material/transmission.h"

namespace fresnel {

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace

namespace bxdf {

glm::vec3 CosineLobe::sample(glm::vec2 u) const {
    glm::vec3 local = sampling::sample_cosine(u);
    if (!(local.z > 0.0f)) return glm::vec3(0.0f);
    if (below) local.z = -local.z;
    return frame.to_world(local);
}

float CosineLobe::pdf(glm::vec3 l) const {
    glm::vec3 ll = frame.to_local(l);
    if (below) ll.z = -ll.z;
    return ll.z > 0.0f ? sampling::pdf_cosine(ll) : 0.0f;
}

glm::vec3 GgxLobe::sample(glm::vec2 u) const {
    if (v_local.z <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 local = sampling::sample_ggx_reflection(v_local, u, alpha);
    if (!(local.z > 0.0f)) return glm::vec3(0.0f);  // below its own horizon: lost
    if (mirrored) local.z = -local.z;
    return frame.to_world(local);
}

float GgxLobe::pdf(glm::vec3 l) const {
    glm::vec3 ll = frame.to_local(l);
    if (mirrored) ll.z = -ll.z;
    return ll.z > 0.0f ? sampling::pdf_ggx_reflection(v_local, ll, alpha) : 0.0f;
}

}  // namespace bxdf

BsdfLobes lobe_probabilities(const EvaluatedMaterial& m, glm::vec3 v) {
    const brdf::Surface& s = m.surface;
    float n_dot_v = std::clamp(glm::dot(m.normal, v), 0.0f, 1.0f);
    glm::vec3 f_dielectric = brdf::f_schlick(s.dielectric_f0() * s.specular_weight, glm::vec3(s.specular_weight), n_dot_v);
    glm::vec3 f_metal = brdf::f_schlick(s.base_color, glm::vec3(1.0f), n_dot_v);
    if (m.iridescence > 0.0f) {
        // KHR_materials_iridescence: the lobes' weights follow the film's Fresnel too.
        brdf::IridescenceFresnel film = brdf::iridescence_at(m.iridescence, m.iridescence_ior, m.iridescence_thickness,
                                                             n_dot_v, s.dielectric_f0(), s.base_color);
        f_dielectric = glm::mix(f_dielectric, film.dielectric, film.factor);
        f_metal = glm::mix(f_metal, film.metal, film.factor);
    }
    float spec = (1.0f - s.metallic) * luminance(f_dielectric) + s.metallic * luminance(f_metal);
    float diff = (1.0f - s.metallic) * luminance((1.0f - f_dielectric) * s.base_color);
    // KHR_materials_diffuse_transmission: the share dt of the diffuse goes through, in its colour.
    const float dt = std::clamp(m.diffuse_transmission, 0.0f, 1.0f);
    float diff_t = dt * (1.0f - s.metallic) * luminance((1.0f - f_dielectric) * m.diffuse_transmission_color);
    diff *= 1.0f - dt;
    // KHR_materials_sheen has no sampling routine of its own: its broad lobe is sampled by
    // the cosine lobe, which covers the whole hemisphere (its weight joins the diffuse's).
    diff += luminance(m.sheen_color);
    float coat = m.clearcoat > 0.0f ? brdf::clearcoat_mix(m.clearcoat, m.clearcoat_f0, m.clearcoat_normal, v) : 0.0f;
    const float t = std::clamp(m.transmission.factor, 0.0f, 1.0f);
    BsdfLobes p;
    p.diffuse = std::max(diff, 0.0f) * (1.0f - coat) * (1.0f - t);
    p.diffuse_transmission = std::max(diff_t, 0.0f) * (1.0f - coat) * (1.0f - t);
    p.transmission = std::max(diff + diff_t, 0.0f) * (1.0f - coat) * t;
    p.specular = std::max(spec, 0.0f) * (1.0f - coat);
    p.clearcoat = coat;
    float sum = p.diffuse + p.specular + p.clearcoat + p.transmission + p.diffuse_transmission;
    if (!(sum > 0.0f)) return BsdfLobes{};
    p.diffuse /= sum;
    p.diffuse_transmission /= sum;
    p.specular /= sum;
    p.clearcoat /= sum;
    p.transmission /= sum;
    return p;
}

Bsdf::Bsdf(const EvaluatedMaterial& m, glm::vec3 v, const brdf::BrdfModel& model, const EnergyCompensation& comp)
    : m_(m), v_(v), model_(model), comp_(comp), lobes_(lobe_probabilities(m, v)) {
    const bxdf::Frame base(m.normal);
    const glm::vec3 v_base = base.to_local(v);
    const float alpha = brdf::alpha_from_roughness(m.surface.perceptual_roughness);
    diffuse_ = {base, false};
    diffuse_transmission_ = {base, true};
    // KHR_materials_anisotropy has no sampling routine of its own: shade_light evaluates the
    // stretched lobe, and the isotropic GGX lobe samples it at the geometric mean of its two
    // roughnesses (alpha_t along the direction, alpha across it).
    float specular_alpha = alpha;
    if (m.anisotropy_strength > 0.0f)
        specular_alpha = std::sqrt(brdf::anisotropic_alpha_t(alpha, m.anisotropy_strength) * std::clamp(alpha, 1e-3f, 1.0f));
    specular_ = {base, v_base, specular_alpha, false};
    // The lobe's roughness as Khronos narrows it towards ior 1, kept off the delta (shade_bsdf's).
    transmission_ = {base, v_base,
                     std::max(transmission::apply_ior_to_roughness(alpha, m.transmission.ior), kMinSampledAlpha), true};
    if (lobes_.clearcoat > 0.0f) {
        const bxdf::Frame coat(m.clearcoat_normal);
        clearcoat_ = {coat, coat.to_local(v), brdf::alpha_from_roughness(m.clearcoat_roughness), false};
    }
}

float Bsdf::pdf(glm::vec3 l) const {
    float pdf = 0.0f;
    if (lobes_.diffuse > 0.0f) pdf += lobes_.diffuse * diffuse_.pdf(l);
    if (lobes_.specular > 0.0f) pdf += lobes_.specular * specular_.pdf(l);
    if (lobes_.clearcoat > 0.0f) pdf += lobes_.clearcoat * clearcoat_.pdf(l);
    if (lobes_.transmission > 0.0f) pdf += lobes_.transmission * transmission_.pdf(l);
    if (lobes_.diffuse_transmission > 0.0f) pdf += lobes_.diffuse_transmission * diffuse_transmission_.pdf(l);
    return pdf;
}

BsdfSample Bsdf::sample(glm::vec3 u) const {
    BsdfSample s;
    const BsdfLobes& p = lobes_;
    if (p.diffuse + p.specular + p.clearcoat + p.transmission + p.diffuse_transmission <= 0.0f) return s;
    const glm::vec2 u2(u.y, u.z);
    // Each lobe's samples below its own horizon are lost (the pdf of a lobe is 0 there, so
    // keeping them would make the mixture's pdf wrong where another lobe reaches).
    if (u.x < p.diffuse) {
        s.l = diffuse_.sample(u2);
    } else if (u.x < p.diffuse + p.specular) {
        s.l = specular_.sample(u2);
    } else if (u.x < p.diffuse + p.specular + p.clearcoat) {
        s.l = clearcoat_.sample(u2);
    } else if (u.x < p.diffuse + p.specular + p.clearcoat + p.diffuse_transmission) {
        s.l = diffuse_transmission_.sample(u2);
        s.transmitted = s.diffuse_transmitted = true;
    } else {
        s.l = transmission_.sample(u2);
        s.transmitted = true;
    }
    const float len = glm::length(s.l);
    if (!(len > 0.0f)) return BsdfSample{};
    s.l /= len;
    s.pdf = pdf(s.l);
    if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) {
        s.pdf = 0.0f;
        return s;
    }
    s.f_cos = eval(s.l);
    return s;
}

glm::vec3 eval_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l) { return Bsdf(m, v).eval(l); }
float pdf_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l) { return Bsdf(m, v).pdf(l); }
BsdfSample sample_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 u) { return Bsdf(m, v).sample(u); }

}  // namespace fresnel
