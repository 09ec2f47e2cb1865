#include "fresnel/trace/bsdf.h"

#include <algorithm>
#include <cmath>

#include "fresnel/material/sampling.h"

namespace fresnel::trace {

namespace {
float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

struct Frame {
    glm::vec3 t, b, n;
    explicit Frame(glm::vec3 normal) : n(normal) { sampling::basis(n, t, b); }
    glm::vec3 to_local(glm::vec3 w) const { return {glm::dot(w, t), glm::dot(w, b), glm::dot(w, n)}; }
    glm::vec3 to_world(glm::vec3 w) const { return w.x * t + w.y * b + w.z * n; }
};
}  // namespace

BsdfLobes lobe_probabilities(const EvaluatedMaterial& m, glm::vec3 v) {
    const brdf::Surface& s = m.surface;
    float n_dot_v = std::clamp(glm::dot(m.normal, v), 0.0f, 1.0f);
    glm::vec3 f_dielectric = brdf::f_schlick(s.dielectric_f0() * s.specular_weight, glm::vec3(s.specular_weight), n_dot_v);
    glm::vec3 f_metal = brdf::f_schlick(s.base_color, glm::vec3(1.0f), n_dot_v);
    float spec = (1.0f - s.metallic) * luminance(f_dielectric) + s.metallic * luminance(f_metal);
    float diff = (1.0f - s.metallic) * luminance((1.0f - f_dielectric) * s.base_color);
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

glm::vec3 eval_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l) { return shade_light(m, v, l, glm::vec3(1.0f)); }

namespace {
float pdf_with(const EvaluatedMaterial& m, const BsdfLobes& p, glm::vec3 v, glm::vec3 l) {
    float pdf = 0.0f;
    if (p.diffuse > 0.0f || p.specular > 0.0f) {
        Frame f(m.normal);
        glm::vec3 vl = f.to_local(v), ll = f.to_local(l);
        if (p.diffuse > 0.0f) pdf += p.diffuse * sampling::pdf_cosine(ll);
        if (p.specular > 0.0f && ll.z > 0.0f)
            pdf += p.specular * sampling::pdf_ggx_reflection(vl, ll, brdf::alpha_from_roughness(m.surface.perceptual_roughness));
    }
    if (p.clearcoat > 0.0f) {
        Frame f(m.clearcoat_normal);
        glm::vec3 ll = f.to_local(l);
        if (ll.z > 0.0f)
            pdf += p.clearcoat * sampling::pdf_ggx_reflection(f.to_local(v), ll, brdf::alpha_from_roughness(m.clearcoat_roughness));
    }
    return pdf;
}
}  // namespace

float pdf_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 l) { return pdf_with(m, lobe_probabilities(m, v), v, l); }

BsdfSample sample_bsdf(const EvaluatedMaterial& m, glm::vec3 v, glm::vec3 u) {
    BsdfSample s;
    BsdfLobes p = lobe_probabilities(m, v);
    if (p.diffuse + p.specular + p.clearcoat <= 0.0f) return s;
    glm::vec2 u2(u.y, u.z);
    // Each lobe's samples below its own horizon are lost (the pdf of a lobe is 0 there, so
    // keeping them would make the mixture's pdf wrong where another lobe reaches).
    glm::vec3 local;
    if (u.x < p.diffuse) {
        Frame f(m.normal);
        local = sampling::sample_cosine(u2);
        s.l = f.to_world(local);
    } else if (u.x < p.diffuse + p.specular) {
        Frame f(m.normal);
        glm::vec3 vl = f.to_local(v);
        if (vl.z <= 0.0f) return s;
        local = sampling::sample_ggx_reflection(vl, u2, brdf::alpha_from_roughness(m.surface.perceptual_roughness));
        s.l = f.to_world(local);
    } else {
        Frame f(m.clearcoat_normal);
        glm::vec3 vl = f.to_local(v);
        if (vl.z <= 0.0f) return s;
        local = sampling::sample_ggx_reflection(vl, u2, brdf::alpha_from_roughness(m.clearcoat_roughness));
        s.l = f.to_world(local);
    }
    if (!(local.z > 0.0f)) return s;
    float len = glm::length(s.l);
    if (!(len > 0.0f)) return s;
    s.l /= len;
    s.pdf = pdf_with(m, p, v, s.l);
    if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) {
        s.pdf = 0.0f;
        return s;
    }
    s.f_cos = eval_bsdf(m, v, s.l);
    return s;
}

}  // namespace fresnel::trace
