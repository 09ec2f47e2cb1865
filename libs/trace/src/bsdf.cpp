#include "fresnel/trace/bsdf.h"

#include <algorithm>
#include <cmath>

#include "fresnel/material/sampling.h"
#include "fresnel/material/transmission.h"

namespace fresnel::trace {

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace

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

Bsdf::Bsdf(const EvaluatedMaterial& m, glm::vec3 v, const brdf::BrdfModel& model)
    : m_(m), v_(v), model_(model), lobes_(lobe_probabilities(m, v)) {
    base_.n = m.normal;
    sampling::basis(base_.n, base_.t, base_.b);
    v_base_ = base_.to_local(v);
    alpha_ = brdf::alpha_from_roughness(m.surface.perceptual_roughness);
    // The lobe's roughness as Khronos narrows it towards ior 1, kept off the delta as alpha_ is.
    transmission_alpha_ = std::max(transmission::apply_ior_to_roughness(alpha_, m.transmission.ior),
                                   kMinTraceRoughness * kMinTraceRoughness);
    // KHR_materials_anisotropy has no sampling routine of its own: shade_light evaluates the
    // stretched lobe, and the isotropic GGX lobe samples it at the geometric mean of its two
    // roughnesses (alpha_t along the direction, alpha across it).
    if (m.anisotropy_strength > 0.0f)
        alpha_ = std::sqrt(brdf::anisotropic_alpha_t(alpha_, m.anisotropy_strength) * std::clamp(alpha_, 1e-3f, 1.0f));
    if (lobes_.clearcoat > 0.0f) {
        coat_.n = m.clearcoat_normal;
        sampling::basis(coat_.n, coat_.t, coat_.b);
        v_coat_ = coat_.to_local(v);
        coat_alpha_ = brdf::alpha_from_roughness(m.clearcoat_roughness);
    }
}

glm::vec3 Bsdf::eval_transmission(glm::vec3 l) const {
    const TransmissionInputs& tr = m_.transmission;
    const brdf::Surface& s = m_.surface;
    const glm::vec3 n = base_.n;
    float n_dot_l = glm::dot(n, l);
    if (tr.factor <= 0.0f || n_dot_l >= 0.0f) return glm::vec3(0.0f);
    glm::vec3 lm = l - 2.0f * n_dot_l * n;  // mirrored above the surface
    glm::vec3 h = glm::normalize(lm + v_);
    float n_dot_v = std::clamp(glm::dot(n, v_), 0.0f, 1.0f), n_dot_lm = -n_dot_l;
    float v_dot_h = std::clamp(glm::dot(v_, h), 0.0f, 1.0f);
    float a = transmission_alpha_;
    float dv = brdf::d_ggx(std::clamp(glm::dot(n, h), 0.0f, 1.0f), a) * brdf::v_smith_ggx_correlated(n_dot_lm, n_dot_v, a);
    glm::vec3 f_dielectric = brdf::f_schlick(s.dielectric_f0() * s.specular_weight, glm::vec3(s.specular_weight), v_dot_h);
    glm::vec3 f = (1.0f - s.metallic) * brdf::film_diffuse_weight(f_dielectric, film_at(m_, v_)) * tr.factor *
                  s.base_color * dv * n_dot_lm;
    if (m_.clearcoat > 0.0f) f *= 1.0f - brdf::clearcoat_mix(m_.clearcoat, m_.clearcoat_f0, m_.clearcoat_normal, v_);
    return f;
}

glm::vec3 Bsdf::eval(glm::vec3 l) const {
    // With KHR_materials_diffuse_transmission, shade_light has the transmitted Lambert lobe below.
    glm::vec3 f = shade_light(m_, v_, l, glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(1.0f), model_);
    const TransmissionInputs& tr = m_.transmission;
    if (tr.factor > 0.0f) {
        float n_dot_l = glm::dot(base_.n, l);
        if (n_dot_l < 0.0f && !(m_.diffuse_transmission > 0.0f)) return eval_transmission(l);
        // The transmission takes its share T of the diffuse lobe (with diffuse transmission, of
        // both Lambert lobes' mix).
        const brdf::Surface& s = m_.surface;
        const brdf::Cosines c = brdf::cosines(base_.n, v_, l);
        glm::vec3 f_dielectric = brdf::f_schlick(s.dielectric_f0() * s.specular_weight, glm::vec3(s.specular_weight),
                                                 c.v_dot_h);
        glm::vec3 diffuse = (1.0f - s.metallic) * brdf::film_diffuse_weight(f_dielectric, film_at(m_, v_)) *
                            brdf::diffuse_transmission_mix(brdf::lambert(s.base_color) * c.n_dot_l,
                                                           std::max(-n_dot_l, 0.0f), m_.diffuse_transmission,
                                                           m_.diffuse_transmission_color);
        if (m_.clearcoat > 0.0f)
            diffuse *= 1.0f - brdf::clearcoat_mix(m_.clearcoat, m_.clearcoat_f0, m_.clearcoat_normal, v_);
        f -= tr.factor * diffuse;
        f = glm::max(f, glm::vec3(0.0f));
        if (n_dot_l < 0.0f) f += eval_transmission(l);
    }
    return f;
}

float Bsdf::pdf(glm::vec3 l) const {
    float pdf = 0.0f;
    if (lobes_.diffuse > 0.0f || lobes_.specular > 0.0f) {
        glm::vec3 ll = base_.to_local(l);
        if (ll.z > 0.0f) {
            if (lobes_.diffuse > 0.0f) pdf += lobes_.diffuse * sampling::pdf_cosine(ll);
            if (lobes_.specular > 0.0f) pdf += lobes_.specular * sampling::pdf_ggx_reflection(v_base_, ll, alpha_);
        }
    }
    if (lobes_.clearcoat > 0.0f) {
        glm::vec3 ll = coat_.to_local(l);
        if (ll.z > 0.0f) pdf += lobes_.clearcoat * sampling::pdf_ggx_reflection(v_coat_, ll, coat_alpha_);
    }
    if (lobes_.transmission > 0.0f || lobes_.diffuse_transmission > 0.0f) {
        glm::vec3 ll = base_.to_local(l);
        if (ll.z < 0.0f) {
            const glm::vec3 mirrored(ll.x, ll.y, -ll.z);
            if (lobes_.transmission > 0.0f)
                pdf += lobes_.transmission * sampling::pdf_ggx_reflection(v_base_, mirrored, transmission_alpha_);
            if (lobes_.diffuse_transmission > 0.0f) pdf += lobes_.diffuse_transmission * sampling::pdf_cosine(mirrored);
        }
    }
    return pdf;
}

BsdfSample Bsdf::sample(glm::vec3 u) const {
    BsdfSample s;
    const BsdfLobes& p = lobes_;
    if (p.diffuse + p.specular + p.clearcoat + p.transmission + p.diffuse_transmission <= 0.0f) return s;
    glm::vec2 u2(u.y, u.z);
    // Each lobe's samples below its own horizon are lost (the pdf of a lobe is 0 there, so
    // keeping them would make the mixture's pdf wrong where another lobe reaches).
    glm::vec3 local;
    if (u.x < p.diffuse) {
        local = sampling::sample_cosine(u2);
        s.l = base_.to_world(local);
    } else if (u.x < p.diffuse + p.specular) {
        if (v_base_.z <= 0.0f) return s;
        local = sampling::sample_ggx_reflection(v_base_, u2, alpha_);
        s.l = base_.to_world(local);
    } else if (u.x < p.diffuse + p.specular + p.clearcoat) {
        if (v_coat_.z <= 0.0f) return s;
        local = sampling::sample_ggx_reflection(v_coat_, u2, coat_alpha_);
        s.l = coat_.to_world(local);
    } else if (u.x < p.diffuse + p.specular + p.clearcoat + p.diffuse_transmission) {
        // Diffuse transmission: cosine-weighted about -n.
        local = sampling::sample_cosine(u2);
        local.z = -local.z;
        s.l = base_.to_world(local);
        s.transmitted = true;
        s.diffuse_transmitted = true;
    } else {
        // Transmission: a reflection sample of the lobe mirrored through the surface.
        if (v_base_.z <= 0.0f) return s;
        local = sampling::sample_ggx_reflection(v_base_, u2, transmission_alpha_);
        if (!(local.z > 0.0f)) return s;
        local.z = -local.z;
        s.l = base_.to_world(local);
        s.transmitted = true;
    }
    if (!(s.transmitted ? local.z < 0.0f : local.z > 0.0f)) return s;
    float len = glm::length(s.l);
    if (!(len > 0.0f)) return s;
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

}  // namespace fresnel::trace
