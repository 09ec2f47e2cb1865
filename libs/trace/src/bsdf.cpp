#include "fresnel/trace/bsdf.h"

#include <algorithm>
#include <cmath>

#include "fresnel/material/sampling.h"

namespace fresnel::trace {

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace

BsdfLobes lobe_probabilities(const EvaluatedMaterial& m, glm::vec3 v) {
    const brdf::Surface& s = m.surface;
    float n_dot_v = std::clamp(glm::dot(m.normal, v), 0.0f, 1.0f);
    glm::vec3 f_dielectric = brdf::f_schlick(s.dielectric_f0() * s.specular_weight, glm::vec3(s.specular_weight), n_dot_v);
    glm::vec3 f_metal = brdf::f_schlick(s.base_color, glm::vec3(1.0f), n_dot_v);
    float spec = (1.0f - s.metallic) * luminance(f_dielectric) + s.metallic * luminance(f_metal);
    float diff = (1.0f - s.metallic) * luminance((1.0f - f_dielectric) * s.base_color);
    // KHR_materials_sheen has no sampling routine of its own: its broad lobe is sampled by
    // the cosine lobe, which covers the whole hemisphere (its weight joins the diffuse's).
    diff += luminance(m.sheen_color);
    float coat = m.clearcoat > 0.0f ? brdf::clearcoat_mix(m.clearcoat, m.clearcoat_f0, m.clearcoat_normal, v) : 0.0f;
    BsdfLobes p;
    p.diffuse = std::max(diff, 0.0f) * (1.0f - coat);
    p.specular = std::max(spec, 0.0f) * (1.0f - coat);
    p.clearcoat = coat;
    float sum = p.diffuse + p.specular + p.clearcoat;
    if (!(sum > 0.0f)) return BsdfLobes{};
    p.diffuse /= sum;
    p.specular /= sum;
    p.clearcoat /= sum;
    return p;
}

Bsdf::Bsdf(const EvaluatedMaterial& m, glm::vec3 v) : m_(m), v_(v), lobes_(lobe_probabilities(m, v)) {
    base_.n = m.normal;
    sampling::basis(base_.n, base_.t, base_.b);
    v_base_ = base_.to_local(v);
    alpha_ = brdf::alpha_from_roughness(m.surface.perceptual_roughness);
    if (lobes_.clearcoat > 0.0f) {
        coat_.n = m.clearcoat_normal;
        sampling::basis(coat_.n, coat_.t, coat_.b);
        v_coat_ = coat_.to_local(v);
        coat_alpha_ = brdf::alpha_from_roughness(m.clearcoat_roughness);
    }
}

glm::vec3 Bsdf::eval(glm::vec3 l) const { return shade_light(m_, v_, l, glm::vec3(1.0f)); }

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
    return pdf;
}

BsdfSample Bsdf::sample(glm::vec3 u) const {
    BsdfSample s;
    const BsdfLobes& p = lobes_;
    if (p.diffuse + p.specular + p.clearcoat <= 0.0f) return s;
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
    } else {
        if (v_coat_.z <= 0.0f) return s;
        local = sampling::sample_ggx_reflection(v_coat_, u2, coat_alpha_);
        s.l = coat_.to_world(local);
    }
    if (!(local.z > 0.0f)) return s;
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
