#pragma once
// Sampling routines used by the IBL precomputation and the BRDF quadratures.
// Every sampler here has its pdf next to it; tests/sampling_test.cpp checks one
// against the other (chi-squared) and each pdf's normalisation.
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "fresnel/material/brdf.h"

namespace fresnel::sampling {

// The i-th of n points of the Hammersley set in [0,1)^2.
inline glm::vec2 hammersley(std::uint32_t i, std::uint32_t n) {
    std::uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return {float(i) / float(n), float(bits) * 2.3283064365386963e-10f};
}

// A GGX-distributed half vector around +Z (pdf over half vectors: D(h) * h.z).
inline glm::vec3 sample_ggx_half(glm::vec2 u, float alpha) {
    float a2 = alpha * alpha;
    float cos_t = std::sqrt((1.0f - u.y) / (1.0f + (a2 - 1.0f) * u.y));
    float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
    float phi = 2.0f * brdf::kPi * u.x;
    return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}
inline float pdf_ggx_half(glm::vec3 h, float alpha) { return brdf::d_ggx(h.z, alpha) * h.z; }

// Smith Lambda for GGX (isotropic) at direction w (w.z = cos theta).
inline float smith_lambda(glm::vec3 w, float alpha) {
    float c2 = w.z * w.z;
    if (c2 >= 1.0f) return 0.0f;
    float t2 = std::max(0.0f, 1.0f - c2) / std::max(c2, 1e-12f);
    return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * t2));
}
inline float smith_g1(glm::vec3 w, float alpha) { return 1.0f / (1.0f + smith_lambda(w, alpha)); }

// A half vector from the distribution of GGX normals visible from v (Heitz 2018),
// v in the frame where the normal is +Z. pdf over h: G1(v) max(0, v.h) D(h) / v.z.
// Much lower variance than sampling D at grazing angles.
inline glm::vec3 sample_ggx_vndf(glm::vec3 v, glm::vec2 u, float alpha) {
    glm::vec3 vh = glm::normalize(glm::vec3(alpha * v.x, alpha * v.y, v.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    glm::vec3 t1 = lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1.0f, 0.0f, 0.0f);
    glm::vec3 t2 = glm::cross(vh, t1);
    float r = std::sqrt(u.x), phi = 2.0f * brdf::kPi * u.y;
    float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
    glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-7f, nh.z)));
}
inline float pdf_ggx_vndf(glm::vec3 v, glm::vec3 h, float alpha) {
    return smith_g1(v, alpha) * std::max(0.0f, glm::dot(v, h)) * brdf::d_ggx(h.z, alpha) / std::max(v.z, 1e-8f);
}

// A reflected direction l = reflect(-v, h) with h from the visible normals (sample_ggx_vndf),
// and its pdf over solid angle: pdf_ggx_vndf(v, h) / (4 v.h) (the Jacobian of reflection).
// Directions below the surface (l.z <= 0) carry no energy; the caller drops them.
inline glm::vec3 sample_ggx_reflection(glm::vec3 v, glm::vec2 u, float alpha) {
    glm::vec3 h = sample_ggx_vndf(v, u, alpha);
    return 2.0f * glm::dot(v, h) * h - v;
}
inline float pdf_ggx_reflection(glm::vec3 v, glm::vec3 l, float alpha) {
    glm::vec3 h = v + l;
    float len = glm::length(h);
    if (len <= 0.0f || v.z <= 0.0f) return 0.0f;
    h /= len;
    if (h.z <= 0.0f) return 0.0f;
    float v_dot_h = glm::dot(v, h);
    if (v_dot_h <= 0.0f) return 0.0f;
    return pdf_ggx_vndf(v, h, alpha) / (4.0f * v_dot_h);
}

// Cosine-weighted direction around +Z (pdf cos(theta)/pi).
inline glm::vec3 sample_cosine(glm::vec2 u) {
    float r = std::sqrt(u.x), phi = 2.0f * brdf::kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}
inline float pdf_cosine(glm::vec3 l) { return std::max(l.z, 0.0f) / brdf::kPi; }

// An orthonormal basis with `n` as its third axis (Duff et al. 2017).
inline void basis(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
    float s = std::copysign(1.0f, n.z);
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    t = {1.0f + s * n.x * n.x * a, s * c, -s * n.x};
    b = {c, s + n.y * n.y * a, -n.y};
}

}  // namespace fresnel::sampling
