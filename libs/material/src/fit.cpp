#include "fresnel/material/fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <type_traits>

#include "fresnel/core/color.h"
#include "fresnel/material/brdf.h"
#include "fresnel/material/evaluate.h"
#include "fresnel/material/legacy_shading.h"
#include "fresnel/material/phong.h"
#include "fresnel/material/sampling.h"

namespace fresnel::fit {

namespace {

#include "fit_table.inc"  // kTableRoughnessForNs, kTableNsForRoughness (tools/fit_table_gen)

constexpr float kPi = brdf::kPi;
constexpr int kLightRings = 16, kLightSectors = 32;
constexpr std::array<float, 6> kViewElevationsDeg = {5.0f, 20.0f, 35.0f, 50.0f, 65.0f, 80.0f};
constexpr size_t kViews = kViewElevationsDeg.size();
constexpr size_t kPerView = size_t(kLightRings) * kLightSectors;  // fit_samples() is view-major
// Importance samples per view for a lobe's integral over a uniform environment (8 x 8 stratified).
constexpr int kLobeSamplesSide = 8, kLobeSamples = kLobeSamplesSide * kLobeSamplesSide;

// The image-based part of the objective (fit.h, "Image-based light"): a uniform environment of
// radiance A alone (the display values of an OpenGL 1 white at A), and the key light at
// kMixDirect with a uniform environment at kMixAmbient, so that a white surface facing the
// key shows 1 as under the key alone. Each of the three parts (the key alone, the mix, the
// environment alone) carries a third of the weight.
constexpr std::array<float, 2> kAmbientLevels = {0.5f, 1.0f};
constexpr float kMixDirect = 0.6f, kMixAmbient = 0.4f;
constexpr float kPartWeight = 1.0f / 3.0f;

glm::vec3 view_direction(size_t view) {
    float theta_v = (90.0f - kViewElevationsDeg[view]) * kPi / 180.0f;  // from the normal
    return {std::sin(theta_v), 0.0f, std::cos(theta_v)};
}
// A view's share of the weight (n.v, normalised over the views), as fit_samples() weighs them.
float view_weight(size_t view) {
    float total = 0.0f;
    for (size_t i = 0; i < kViews; ++i) total += view_direction(i).z;
    return view_direction(view).z / total;
}

// linear_to_srgb on [0, 1] through a table with linear interpolation: the fit evaluates it
// millions of times. Within 1e-5 of fresnel::linear_to_srgb (checked in fit_test).
struct SrgbTable {
    static constexpr int kSize = 8192;
    std::array<float, kSize + 1> v{};
    SrgbTable() {
        for (int i = 0; i <= kSize; ++i) v[i] = linear_to_srgb(float(i) / kSize);
    }
    float operator()(float x) const {
        x = std::clamp(x, 0.0f, 1.0f) * kSize;
        int i = std::min(int(x), kSize - 1);
        float t = x - float(i);
        return v[i] + (v[i + 1] - v[i]) * t;
    }
};
const SrgbTable& srgb_table() {
    static const SrgbTable table;
    return table;
}

float clamp01(float x) { return std::clamp(std::isfinite(x) ? x : 0.0f, 0.0f, 1.0f); }

brdf::Surface surface_of(const Pbr& p) {
    brdf::Surface s;
    s.base_color = p.base_color;
    s.metallic = p.metallic;
    s.perceptual_roughness = p.roughness;
    s.specular_f0 = 0.04f;
    s.specular_color = p.specular_f0 / 0.04f;
    s.specular_weight = p.specular_weight;
    return s;
}

// Golden-section search for the minimum of f on [lo, hi]; returns the best point seen
// (the ends included).
float golden(const std::function<float(float)>& f, float lo, float hi, int iterations, float* best_value) {
    const float g = 0.6180339887f;
    float a = lo, b = hi;
    float c = b - g * (b - a), d = a + g * (b - a);
    float fc = f(c), fd = f(d);
    float best_x = fc < fd ? c : d, best = std::min(fc, fd);
    for (int i = 0; i < iterations; ++i) {
        if (fc < fd) {
            b = d; d = c; fd = fc;
            c = b - g * (b - a); fc = f(c);
            if (fc < best) { best = fc; best_x = c; }
        } else {
            a = c; c = d; fc = fd;
            d = a + g * (b - a); fd = f(d);
            if (fd < best) { best = fd; best_x = d; }
        }
    }
    for (float x : {lo, hi}) {
        float fx = f(x);
        if (fx < best) { best = fx; best_x = x; }
    }
    if (best_value) *best_value = best;
    return best_x;
}

// A grid of `cells` + 1 points on [lo, hi] (and `extra`, the table's guess, when it lies
// inside), then golden-section search in the cells either side of the best: the error curves
// here have several local minima.
float scan_golden(const std::function<float(float)>& f, float lo, float hi, int cells, int iterations,
                  float extra = std::numeric_limits<float>::quiet_NaN()) {
    float best = std::numeric_limits<float>::infinity(), best_x = lo;
    float step = (hi - lo) / float(cells);
    for (int i = 0; i <= cells + 1; ++i) {
        float x = i <= cells ? lo + step * float(i) : extra;
        if (!(x >= lo && x <= hi)) continue;
        float v = f(x);
        if (v < best) { best = v; best_x = x; }
    }
    float a = std::max(lo, best_x - step), b = std::min(hi, best_x + step);
    float g_best = 0.0f;
    float x = golden(f, a, b, iterations, &g_best);
    return g_best <= best ? x : best_x;
}

// Nelder-Mead on [0, 1]^2 (points clamped into the box), from x0 with a first step.
std::array<float, 2> nelder_mead2(const std::function<float(float, float)>& f, std::array<float, 2> x0, float step,
                                  int iterations, float* best_value) {
    using P = std::array<float, 2>;
    auto clampp = [](P p) { return P{clamp01(p[0]), clamp01(p[1])}; };
    std::array<P, 3> x = {clampp(x0), clampp({x0[0] + step, x0[1]}), clampp({x0[0], x0[1] + step})};
    if (x[1] == x[0]) x[1] = clampp({x0[0] - step, x0[1]});
    if (x[2] == x[0]) x[2] = clampp({x0[0], x0[1] - step});
    std::array<float, 3> fx;
    for (int i = 0; i < 3; ++i) fx[i] = f(x[i][0], x[i][1]);
    auto eval = [&](P p) { p = clampp(p); return std::pair<P, float>{p, f(p[0], p[1])}; };
    for (int it = 0; it < iterations; ++it) {
        // order
        std::array<int, 3> o = {0, 1, 2};
        std::sort(o.begin(), o.end(), [&](int a, int b) { return fx[a] < fx[b]; });
        P b = x[o[0]], m = x[o[1]], w = x[o[2]];
        float fb = fx[o[0]], fm = fx[o[1]], fw = fx[o[2]];
        x = {b, m, w};
        fx = {fb, fm, fw};
        if (std::abs(fw - fb) <= 1e-12f && std::abs(w[0] - b[0]) + std::abs(w[1] - b[1]) < 1e-6f) break;
        P c = {(b[0] + m[0]) * 0.5f, (b[1] + m[1]) * 0.5f};
        auto [r, fr] = eval({c[0] + (c[0] - w[0]), c[1] + (c[1] - w[1])});
        if (fr < fb) {
            auto [e, fe] = eval({c[0] + 2.0f * (c[0] - w[0]), c[1] + 2.0f * (c[1] - w[1])});
            if (fe < fr) { x[2] = e; fx[2] = fe; } else { x[2] = r; fx[2] = fr; }
        } else if (fr < fm) {
            x[2] = r; fx[2] = fr;
        } else {
            auto [k, fk] = eval({c[0] + 0.5f * (w[0] - c[0]), c[1] + 0.5f * (w[1] - c[1])});
            if (fk < fw) {
                x[2] = k; fx[2] = fk;
            } else {  // shrink towards the best
                for (int i = 1; i < 3; ++i) {
                    x[i] = {b[0] + 0.5f * (x[i][0] - b[0]), b[1] + 0.5f * (x[i][1] - b[1])};
                    fx[i] = f(x[i][0], x[i][1]);
                }
            }
        }
    }
    int best = int(std::min_element(fx.begin(), fx.end()) - fx.begin());
    if (best_value) *best_value = fx[best];
    return x[best];
}

// Per sample, what the PBR side needs at one roughness: pi n.l, Schlick's (1 - v.h)^5 and V D.
//   lobe_schlick, lobe_weight: per view, kLobeSamples GGX (VNDF) reflections of the view: Schlick's
//   term at v.h and V D n.l / pdf, whose mean times the Fresnel factor is the specular lobe's
//   reflectance of a uniform environment (its directional albedo).
struct PbrGeometry {
    std::vector<float> nl, schlick, vd;
    std::vector<float> lobe_schlick, lobe_weight;
};
PbrGeometry pbr_geometry(float roughness) {
    const auto& samples = fit_samples();
    PbrGeometry g;
    g.nl.reserve(samples.size());
    g.schlick.reserve(samples.size());
    g.vd.reserve(samples.size());
    float alpha = brdf::alpha_from_roughness(roughness);
    for (const Sample& s : samples) {
        glm::vec3 n(0, 0, 1);
        glm::vec3 h = glm::normalize(s.l + s.v);
        float nl = std::clamp(glm::dot(n, s.l), 0.0f, 1.0f), nv = std::clamp(glm::dot(n, s.v), 0.0f, 1.0f);
        float nh = std::clamp(glm::dot(n, h), 0.0f, 1.0f), vh = std::clamp(glm::dot(s.v, h), 0.0f, 1.0f);
        g.nl.push_back(kPi * nl);
        g.schlick.push_back(brdf::f_schlick(0.0f, 1.0f, vh));
        g.vd.push_back(brdf::d_ggx(nh, alpha) * brdf::v_smith_ggx_correlated(nl, nv, alpha));
    }
    g.lobe_schlick.reserve(kViews * kLobeSamples);
    g.lobe_weight.reserve(kViews * kLobeSamples);
    for (size_t view = 0; view < kViews; ++view) {
        const glm::vec3 v = view_direction(view);
        for (int k = 0; k < kLobeSamples; ++k) {
            glm::vec2 u((float(k % kLobeSamplesSide) + 0.5f) / kLobeSamplesSide,
                        (float(k / kLobeSamplesSide) + 0.5f) / kLobeSamplesSide);
            glm::vec3 l = sampling::sample_ggx_reflection(v, u, alpha);
            float pdf = sampling::pdf_ggx_reflection(v, l, alpha);
            float weight = 0.0f, schlick = 0.0f;
            if (l.z > 0.0f && pdf > 0.0f) {
                glm::vec3 h = glm::normalize(l + v);
                float nh = std::clamp(h.z, 0.0f, 1.0f), vh = std::clamp(glm::dot(v, h), 0.0f, 1.0f);
                weight = brdf::d_ggx(nh, alpha) * brdf::v_smith_ggx_correlated(l.z, v.z, alpha) * l.z / pdf;
                schlick = brdf::f_schlick(0.0f, 1.0f, vh);
            }
            g.lobe_schlick.push_back(schlick);
            g.lobe_weight.push_back(std::isfinite(weight) ? weight : 0.0f);
        }
    }
    return g;
}
// One channel of pi f n.l: brdf::evaluate_terms written out for one channel (fit_test checks
// it against brdf::evaluate through pbr_display).
inline float pbr_channel(const PbrGeometry& g, size_t i, float base, float metallic, float f0, float w) {
    float s = g.schlick[i];
    float fd = w * (f0 + (1.0f - f0) * s);
    float fm = base + (1.0f - base) * s;
    float f = (1.0f - metallic) * (1.0f - fd) * base / kPi + ((1.0f - metallic) * fd + metallic * fm) * g.vd[i];
    return g.nl[i] * f;
}
// One channel of what a uniform environment of radiance 1 gives back towards view `view`: the
// diffuse part averaged over the view's cosine-distributed light samples (pi f_diffuse), the
// specular part over its GGX samples.
inline float pbr_ambient_channel(const PbrGeometry& g, size_t view, float base, float metallic, float f0, float w) {
    float diffuse = 0.0f;
    if (metallic < 1.0f)
        for (size_t i = view * kPerView; i < (view + 1) * kPerView; ++i)
            diffuse += 1.0f - w * (f0 + (1.0f - f0) * g.schlick[i]);
    diffuse *= (1.0f - metallic) * base / float(kPerView);
    float specular = 0.0f;
    for (size_t k = view * kLobeSamples; k < (view + 1) * kLobeSamples; ++k) {
        float s = g.lobe_schlick[k];
        float fd = w * (f0 + (1.0f - f0) * s);
        float fm = base + (1.0f - base) * s;
        specular += ((1.0f - metallic) * fd + metallic * fm) * g.lobe_weight[k];
    }
    return diffuse + specular / float(kLobeSamples);
}

// Per sample, the Phong side at one shininess: n.l and [n.l > 0] (n.h)^s.
// ambient_spec: per view, what a uniform environment of radiance 1 (OpenGL 1 lights of colour
// dw / pi from every direction) adds through a highlight of Ks 1: the integral of
// [n.l > 0] (n.h)^s over the sphere / pi, by importance samples of the half vector; the diffuse
// part of that environment is Kd exactly.
struct PhongGeometry {
    std::vector<float> nl, spec;
    std::array<float, kViews> ambient_spec{};
};
float phong_ambient_specular(const glm::vec3& v, float s) {
    constexpr int kSide = 32;  // once per shininess, so finer than the PBR side's per-evaluation samples
    double sum = 0.0;
    for (int k = 0; k < kSide * kSide; ++k) {
        float u1 = (float(k % kSide) + 0.5f) / kSide;
        float u2 = (float(k / kSide) + 0.5f) / kSide;
        // pdf(h) = (s + 1) / (2 pi) (n.h)^s over the hemisphere of h.
        float cos_h = std::pow(u1, 1.0f / (s + 1.0f)), sin_h = std::sqrt(std::max(0.0f, 1.0f - cos_h * cos_h));
        float phi = 2.0f * kPi * u2;
        glm::vec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
        float vh = glm::dot(v, h);
        if (vh <= 0.0f) continue;
        glm::vec3 l = 2.0f * vh * h - v;
        legacy::Ogl1Light one = legacy::ogl1_light(glm::vec3(0, 0, 1), v, l, glm::vec3(1.0f), glm::vec3(0.0f),
                                                   glm::vec3(1.0f), s);
        float pdf_l = (s + 1.0f) / (2.0f * kPi) * std::pow(cos_h, s) / (4.0f * vh);
        if (pdf_l > 0.0f) sum += one.specular.x / kPi / pdf_l;
    }
    return float(sum / (kSide * kSide));
}
PhongGeometry phong_geometry(float ns) {
    const auto& samples = fit_samples();
    PhongGeometry g;
    float s = legacy::ogl1_shininess(ns);
    for (const Sample& smp : samples) {
        legacy::Ogl1Light one = legacy::ogl1_light(glm::vec3(0, 0, 1), smp.v, smp.l, glm::vec3(1.0f), glm::vec3(1.0f),
                                                   glm::vec3(1.0f), s);
        g.nl.push_back(one.diffuse.x);
        g.spec.push_back(one.specular.x);
    }
    for (size_t view = 0; view < kViews; ++view) g.ambient_spec[view] = phong_ambient_specular(view_direction(view), s);
    return g;
}

using Targets = std::array<std::vector<float>, 3>;  // display value per channel per sample

Targets phong_targets(const Phong& p) {
    Targets t;
    for (const Sample& s : fit_samples()) {
        glm::vec3 c = phong_display(p, s);
        for (int k = 0; k < 3; ++k) t[k].push_back(c[k]);
    }
    return t;
}
Targets pbr_targets(const Pbr& p) {
    Targets t;
    for (const Sample& s : fit_samples()) {
        glm::vec3 c = pbr_display(p, s);
        for (int k = 0; k < 3; ++k) t[k].push_back(c[k]);
    }
    return t;
}

// The image-based parts of the objective, from the Phong side: per channel, the mix per sample
// (the key light at kMixDirect plus a uniform environment at kMixAmbient) and the uniform
// environment alone per view and level (view-major). OpenGL 1 clamps once and writes raw.
struct ImageTargets {
    std::array<std::vector<float>, 3> mix, ambient;
};
ImageTargets phong_image_targets(const Phong& p) {
    const PhongGeometry g = phong_geometry(p.ns);
    const glm::vec3 kd = glm::clamp(p.kd, 0.0f, 1.0f), ks = glm::clamp(p.ks, 0.0f, 1.0f);
    ImageTargets t;
    for (size_t view = 0; view < kViews; ++view) {
        const glm::vec3 ambient = kd + ks * g.ambient_spec[view];
        for (float level : kAmbientLevels)
            for (int k = 0; k < 3; ++k) t.ambient[k].push_back(clamp01(level * ambient[k]));
        for (size_t i = view * kPerView; i < (view + 1) * kPerView; ++i) {
            const glm::vec3 direct = kd * g.nl[i] + ks * g.spec[i];
            for (int k = 0; k < 3; ++k) t.mix[k].push_back(clamp01(kMixDirect * direct[k] + kMixAmbient * ambient[k]));
        }
    }
    return t;
}

Residual make_residual(double sum_sq, float max_diff) {
    Residual r;
    r.rms = float(std::sqrt(std::max(sum_sq, 0.0)));
    r.max = max_diff;
    r.psnr_db = r.rms > 0.0f ? std::min(99.0f, -20.0f * std::log10(r.rms)) : 99.0f;
    return r;
}

// ---- Phong -> PBR -----------------------------------------------------------------------

struct PbrSolution {
    Pbr pbr;
    float error = 0.0f;  // weighted mean squared display difference over the three channels
};

// Base colour and F0 per channel for a given roughness, metallic and specular weight.
// with_specular false pins F0 to 0.04 (no KHR_materials_specular; weight must be 1).
// `it` null: the one light alone. `encode` false: the PBR side's values compared linear, not
// sRGB-encoded (the highlight fit of --match albedo, which reads the MTL's numbers as linear).
PbrSolution solve_pbr_colours(const Targets& t, const ImageTargets* it, const PbrGeometry& g, float roughness,
                              float metallic, float weight, bool with_specular, const glm::vec3& start_base,
                              const glm::vec3& start_f0, bool encode = true) {
    const auto& samples = fit_samples();
    const auto& table = srgb_table();
    auto srgb = [&](float x) { return encode ? table(x) : clamp01(x); };
    PbrSolution out;
    out.pbr.roughness = roughness;
    out.pbr.metallic = metallic;
    out.pbr.specular_weight = weight;
    double total = 0.0;
    for (int k = 0; k < 3; ++k) {
        auto err = [&](float base, float f0) {
            double e = 0.0;
            if (!it) {
                for (size_t i = 0; i < samples.size(); ++i) {
                    float d = srgb(pbr_channel(g, i, base, metallic, f0, weight)) - t[k][i];
                    e += samples[i].weight * d * d;
                }
                return float(e);
            }
            for (size_t view = 0; view < kViews; ++view) {
                const float ambient = pbr_ambient_channel(g, view, base, metallic, f0, weight);
                const float wv = kPartWeight * view_weight(view) / float(kAmbientLevels.size());
                for (size_t a = 0; a < kAmbientLevels.size(); ++a) {
                    float d = srgb(kAmbientLevels[a] * ambient) - it->ambient[k][view * kAmbientLevels.size() + a];
                    e += wv * d * d;
                }
                for (size_t i = view * kPerView; i < (view + 1) * kPerView; ++i) {
                    float direct = pbr_channel(g, i, base, metallic, f0, weight);
                    float d = srgb(direct) - t[k][i];
                    float dm = srgb(kMixDirect * direct + kMixAmbient * ambient) - it->mix[k][i];
                    e += kPartWeight * samples[i].weight * (d * d + dm * dm);
                }
            }
            return float(e);
        };
        float e = 0.0f;
        if (with_specular && metallic < 1.0f) {
            auto x = nelder_mead2(err, {start_base[k], start_f0[k]}, 0.15f, 60, &e);
            out.pbr.base_color[k] = x[0];
            out.pbr.specular_f0[k] = x[1];
        } else {
            out.pbr.base_color[k] = golden([&](float b) { return err(b, 0.04f); }, 0.0f, 1.0f, 22, &e);
            out.pbr.specular_f0[k] = 0.04f;
        }
        total += e;
    }
    out.error = float(total / 3.0);
    return out;
}

// The residual over the image-based parts alone (their weights normalised to 1); `targets`:
// phong_image_targets(phong) when the caller has them.
Residual image_based_residual(const Phong& phong, const Pbr& pbr, const ImageTargets* targets = nullptr) {
    ImageTargets own;
    if (!targets) own = phong_image_targets(phong), targets = &own;
    const ImageTargets& it = *targets;
    const PbrGeometry g = pbr_geometry(pbr.roughness);
    const auto& samples = fit_samples();
    const auto& srgb = srgb_table();
    double sum = 0.0;
    float max_diff = 0.0f;
    for (int k = 0; k < 3; ++k) {
        const float base = pbr.base_color[k], f0 = pbr.specular_f0[k];
        for (size_t view = 0; view < kViews; ++view) {
            const float ambient = pbr_ambient_channel(g, view, base, pbr.metallic, f0, pbr.specular_weight);
            for (size_t a = 0; a < kAmbientLevels.size(); ++a) {
                float d = srgb(kAmbientLevels[a] * ambient) - it.ambient[k][view * kAmbientLevels.size() + a];
                sum += 0.5 * view_weight(view) / double(kAmbientLevels.size()) * d * d;
                max_diff = std::max(max_diff, std::abs(d));
            }
            for (size_t i = view * kPerView; i < (view + 1) * kPerView; ++i) {
                float direct = pbr_channel(g, i, base, pbr.metallic, f0, pbr.specular_weight);
                float d = srgb(kMixDirect * direct + kMixAmbient * ambient) - it.mix[k][i];
                sum += 0.5 * samples[i].weight * d * d;
                max_diff = std::max(max_diff, std::abs(d));
            }
        }
    }
    return make_residual(sum / 3.0, max_diff);
}

// image_based false: the one light alone.
PhongToPbr fit_phong(const Phong& phong, bool use_table, bool image_based = true, bool encode = true) {
    Targets t = phong_targets(phong);
    const ImageTargets image_targets = phong_image_targets(phong);  // also for the residual reported
    const ImageTargets* it = image_based ? &image_targets : nullptr;
    glm::vec3 kd = glm::clamp(phong.kd, 0.0f, 1.0f), ks = glm::clamp(phong.ks, 0.0f, 1.0f);
    PhongExt ext;
    ext.diffuse = phong.kd;
    ext.specular = phong.ks;
    ext.shininess = phong.ns;
    if (ks == glm::vec3(0.0f)) {
        // No highlight: no specular lobe at all (specularFactor 0), so the material stays matte
        // under any light. A fit over one light would otherwise choose a near-mirror (roughness
        // 0.02), whose reflection the samples almost never see, and which image-based light
        // shows everywhere. Only the base colour is fitted.
        PhongToPbr out;
        out.pbr = solve_pbr_colours(t, it, pbr_geometry(1.0f), 1.0f, 0.0f, 0.0f, false, kd, glm::vec3(0.04f)).pbr;
        out.residual = residual(phong, out.pbr);
        out.image_based = image_based_residual(phong, out.pbr, &image_targets);
        out.formula = from_material(phong_to_metallic_roughness(ext));
        out.formula_residual = residual(phong, out.formula);
        return out;
    }
    // The table's roughness joins a coarse scan of the whole range as one more candidate.
    float r_table = use_table ? table_roughness(phong.ns) : std::numeric_limits<float>::quiet_NaN();
    const float r_lo = 0.02f, r_hi = 1.0f;

    auto fit_one = [&](bool with_specular) {
        PbrSolution best;
        best.error = std::numeric_limits<float>::infinity();
        auto solve = [&](float r, float m, float w) {
            PbrGeometry g = pbr_geometry(r);
            return solve_pbr_colours(t, it, g, r, m, w, with_specular, kd, glm::max(ks, glm::vec3(0.0f)), encode);
        };
        auto keep = [&](const PbrSolution& s) {
            if (s.error < best.error) best = s;
        };
        // 1. roughness for a dielectric and for a metal; keep the better.
        for (float m : {0.0f, 1.0f}) {
            float r = scan_golden([&](float x) { return solve(x, m, 1.0f).error; }, r_lo, r_hi, 8, 10, r_table);
            keep(solve(r, m, 1.0f));
        }
        // 2. metallic, 3. specular weight (dielectric part), 4. roughness again.
        float r = best.pbr.roughness;
        float m = scan_golden([&](float x) { return solve(r, x, 1.0f).error; }, 0.0f, 1.0f, 4, 10);
        keep(solve(r, m, 1.0f));
        m = best.pbr.metallic;
        if (with_specular && m < 1.0f) {
            float w = scan_golden([&](float x) { return solve(r, m, x).error; }, 0.0f, 1.0f, 4, 10);
            keep(solve(r, m, w));
        }
        float w = best.pbr.specular_weight;
        r = golden([&](float x) { return solve(x, m, w).error; }, std::max(r_lo, r - 0.1f), std::min(r_hi, r + 0.1f), 12,
                   nullptr);
        keep(solve(r, m, w));
        return best;
    };
    PbrSolution with = fit_one(true), without = fit_one(false);
    PhongToPbr out;
    out.pbr = with.error < 0.98f * without.error ? with.pbr : without.pbr;
    if (!out.pbr.uses_specular()) out.pbr.specular_f0 = glm::vec3(0.04f);
    out.residual = residual(phong, out.pbr);
    out.image_based = image_based_residual(phong, out.pbr, &image_targets);
    out.formula = from_material(phong_to_metallic_roughness(ext));
    out.formula_residual = residual(phong, out.formula);
    return out;
}

// ---- PBR -> Phong -----------------------------------------------------------------------

struct PhongSolution {
    Phong phong;
    float error = 0.0f;
};
PhongSolution solve_phong_colours(const Targets& t, float ns, const glm::vec3& start_kd, const glm::vec3& start_ks) {
    const auto& samples = fit_samples();
    PhongGeometry g = phong_geometry(ns);
    PhongSolution out;
    out.phong.ns = ns;
    double total = 0.0;
    for (int k = 0; k < 3; ++k) {
        const std::vector<float>& target = t[k];
        auto err = [&](float kd, float ks) {
            double e = 0.0;
            for (size_t i = 0; i < samples.size(); ++i) {
                float d = std::min(kd * g.nl[i] + ks * g.spec[i], 1.0f) - target[i];
                e += samples[i].weight * d * d;
            }
            return float(e);
        };
        float e = 0.0f;
        auto x = nelder_mead2(err, {start_kd[k], start_ks[k]}, 0.15f, 80, &e);
        out.phong.kd[k] = x[0];
        out.phong.ks[k] = x[1];
        total += e;
    }
    out.error = float(total / 3.0);
    return out;
}

PbrToPhong fit_pbr(const Pbr& pbr, bool use_table) {
    Targets t = pbr_targets(pbr);
    glm::vec3 start_kd = glm::clamp(glm::vec3(linear_to_srgb(pbr.base_color)) * (1.0f - pbr.metallic), 0.0f, 1.0f);
    glm::vec3 start_ks = glm::mix(glm::vec3(0.3f), glm::clamp(pbr.base_color, 0.0f, 1.0f), pbr.metallic);
    // Search u = log(1 + Ns) on [0, log 129].
    const float u_max = std::log(129.0f);
    float u_table = use_table ? std::log1p(table_shininess(pbr.roughness)) : std::numeric_limits<float>::quiet_NaN();
    auto ns_of = [](float u) { return std::clamp(std::expm1(u), 0.0f, 128.0f); };
    float u = scan_golden([&](float x) { return solve_phong_colours(t, ns_of(x), start_kd, start_ks).error; }, 0.0f,
                          u_max, 10, 12, u_table);
    PhongSolution s = solve_phong_colours(t, ns_of(u), start_kd, start_ks);
    PbrToPhong out;
    out.phong = s.phong;
    out.residual = residual(out.phong, pbr);
    out.naive.kd = glm::clamp(pbr.base_color, 0.0f, 1.0f);
    out.naive.ks = glm::vec3(0.04f);
    out.naive.ns = roughness_to_phong_shininess(pbr.roughness);
    out.naive_residual = residual(out.naive, pbr);
    return out;
}

float interpolate(const std::array<float, kTableSize>& table, float (*grid)(int), float x) {
    if (!(x > grid(0))) return table[0];
    for (int i = 1; i < kTableSize; ++i) {
        float x1 = grid(i);
        if (x <= x1) {
            float x0 = grid(i - 1);
            float t = (x - x0) / (x1 - x0);
            return table[i - 1] + (table[i] - table[i - 1]) * t;
        }
    }
    return table[kTableSize - 1];
}

}  // namespace

const std::vector<Sample>& fit_samples() {
    static const std::vector<Sample> samples = [] {
        std::vector<Sample> out;
        double total = 0.0;
        for (float elevation : kViewElevationsDeg) {
            float theta_v = (90.0f - elevation) * kPi / 180.0f;  // from the normal
            glm::vec3 v(std::sin(theta_v), 0.0f, std::cos(theta_v));
            for (int i = 0; i < kLightRings; ++i) {
                float u1 = (float(i) + 0.5f) / kLightRings;
                float sin_t = std::sqrt(u1), cos_t = std::sqrt(1.0f - u1);
                for (int j = 0; j < kLightSectors; ++j) {
                    float phi = 2.0f * kPi * (float(j) + 0.5f) / kLightSectors;
                    glm::vec3 l(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
                    out.push_back({l, v, v.z});
                    total += v.z;
                }
            }
        }
        for (Sample& s : out) s.weight = float(s.weight / total);
        return out;
    }();
    return samples;
}

glm::vec3 phong_display(const Phong& p, const Sample& s) {
    legacy::Ogl1Light one = legacy::ogl1_light(glm::vec3(0, 0, 1), s.v, s.l, glm::vec3(1.0f), p.kd, p.ks,
                                               legacy::ogl1_shininess(p.ns));
    return legacy::ogl1_combine(one.diffuse, one.specular, glm::vec3(1.0f), false);
}

glm::vec3 pbr_display(const Pbr& p, const Sample& s) {
    glm::vec3 n(0, 0, 1);
    glm::vec3 radiance = kPi * brdf::evaluate(surface_of(p), n, s.v, s.l) * std::clamp(glm::dot(n, s.l), 0.0f, 1.0f);
    return linear_to_srgb(glm::clamp(radiance, 0.0f, 1.0f));
}

Residual residual(const Phong& phong, const Pbr& pbr) {
    double sum = 0.0;
    float max_diff = 0.0f;
    for (const Sample& s : fit_samples()) {
        glm::vec3 d = pbr_display(pbr, s) - phong_display(phong, s);
        sum += s.weight * double(glm::dot(d, d)) / 3.0;
        max_diff = std::max({max_diff, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
    return make_residual(sum, max_diff);
}

namespace {
template <class A, class B>
Residual residual_of(const A& a, const B& b) {
    double sum = 0.0;
    float max_diff = 0.0f;
    for (const Sample& s : fit_samples()) {
        auto display = [&](const auto& x) {
            if constexpr (std::is_same_v<std::decay_t<decltype(x)>, Phong>) return phong_display(x, s);
            else return pbr_display(x, s);
        };
        glm::vec3 d = display(a) - display(b);
        sum += s.weight * double(glm::dot(d, d)) / 3.0;
        max_diff = std::max({max_diff, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
    return make_residual(sum, max_diff);
}
}  // namespace
Residual residual(const Phong& a, const Phong& b) { return residual_of(a, b); }
Residual residual_image_based(const Phong& phong, const Pbr& pbr) { return image_based_residual(phong, pbr); }

int view_count() { return int(kViews); }
glm::vec3 view_at(int view) { return view_direction(size_t(view)); }
glm::vec3 uniform_environment(const Pbr& p, int view) {
    const PbrGeometry g = pbr_geometry(p.roughness);
    glm::vec3 out;
    for (int k = 0; k < 3; ++k)
        out[k] = pbr_ambient_channel(g, size_t(view), p.base_color[k], p.metallic, p.specular_f0[k], p.specular_weight);
    return out;
}
glm::vec3 uniform_environment(const Phong& p, int view) {
    const float s = phong_ambient_specular(view_direction(size_t(view)), legacy::ogl1_shininess(p.ns));
    return glm::clamp(p.kd, 0.0f, 1.0f) + glm::clamp(p.ks, 0.0f, 1.0f) * s;
}
Residual residual(const Pbr& a, const Pbr& b) { return residual_of(a, b); }

PhongToPbr fit_phong_to_pbr(const Phong& phong) { return fit_phong(phong, true); }

PhongToPbr fit_phong_to_pbr(const Phong& phong, Match match) {
    if (match == Match::OpenGl1) return fit_phong_to_pbr(phong);
    // Kd is the albedo; the highlight alone (Kd 0) is fitted for roughness and F0, whether the
    // fit reads it as a metal's tint or a dielectric's specular colour.
    PhongToPbr out;
    PhongExt ext;
    ext.diffuse = phong.kd;
    ext.specular = phong.ks;
    ext.shininess = phong.ns;
    out.formula = from_material(phong_to_metallic_roughness(ext));
    out.formula_residual = residual(phong, out.formula);
    const glm::vec3 kd = glm::clamp(phong.kd, 0.0f, 1.0f), ks = glm::clamp(phong.ks, 0.0f, 1.0f);
    Pbr p;
    p.base_color = kd;
    p.metallic = 0.0f;
    if (ks == glm::vec3(0.0f)) {
        p.roughness = 1.0f;
        p.specular_weight = 0.0f;
    } else {
        // The highlight read as Kd is, linear: fitted without the sRGB encoding, under the one
        // light and image-based light, so its peak and the light it reflects from an environment
        // (Ks times the integral of (n.h)^Ns / pi) are both OpenGL 1's numbers.
        const Pbr h = fit_phong(Phong{glm::vec3(0.0f), ks, phong.ns}, true, true, false).pbr;
        p.roughness = h.roughness;
        const glm::vec3 dielectric = h.uses_specular() ? h.specular_f0 * h.specular_weight : glm::vec3(0.04f);
        p.specular_f0 = glm::clamp(glm::mix(dielectric, h.base_color, h.metallic), 0.0f, 1.0f);
        p.specular_weight = 1.0f;
    }
    out.pbr = p;
    out.residual = residual(phong, p);
    out.image_based = image_based_residual(phong, p);
    return out;
}

const char* match_name(Match m) { return m == Match::Albedo ? "albedo" : "opengl1"; }
std::optional<Match> parse_match(const std::string& name) {
    if (name == "opengl1") return Match::OpenGl1;
    if (name == "albedo") return Match::Albedo;
    return std::nullopt;
}
PhongToPbr fit_phong_to_pbr_full(const Phong& phong) { return fit_phong(phong, false); }
PbrToPhong fit_pbr_to_phong(const Pbr& pbr) { return fit_pbr(pbr, true); }
PbrToPhong fit_pbr_to_phong_full(const Pbr& pbr) { return fit_pbr(pbr, false); }

SpecularGlossinessToPbr fit_specular_glossiness(glm::vec3 diffuse, glm::vec3 specular, float glossiness) {
    MetallicRoughnessPoint mr = specular_glossiness_to_metallic_roughness(glm::vec4(diffuse, 1.0f), specular, glossiness);
    SpecularGlossinessToPbr out;
    out.pbr.base_color = glm::vec3(mr.base_color);
    out.pbr.metallic = mr.metallic;
    out.pbr.roughness = mr.roughness;
    out.pbr.specular_f0 = glm::min(mr.f0, glm::vec3(1.0f));
    out.pbr.specular_weight = mr.specular_weight;
    // The specular-glossiness side, shaded as evaluate() shades the extension.
    brdf::Surface sg;
    sg.base_color = glm::vec3(mr.base_color);
    sg.metallic = 0.0f;
    sg.perceptual_roughness = 1.0f - std::clamp(glossiness, 0.0f, 1.0f);
    sg.specular_f0 = 1.0f;
    sg.specular_color = glm::clamp(specular, 0.0f, 1.0f);
    double sum = 0.0;
    float max_diff = 0.0f;
    glm::vec3 n(0, 0, 1);
    for (const Sample& s : fit_samples()) {
        float nl = std::clamp(glm::dot(n, s.l), 0.0f, 1.0f);
        glm::vec3 a = linear_to_srgb(glm::clamp(kPi * brdf::evaluate(sg, n, s.v, s.l) * nl, 0.0f, 1.0f));
        glm::vec3 d = pbr_display(out.pbr, s) - a;
        sum += s.weight * double(glm::dot(d, d)) / 3.0;
        max_diff = std::max({max_diff, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
    out.residual = make_residual(sum, max_diff);
    return out;
}

float table_ns_at(int i) {
    float t = float(i) / float(kTableSize - 1);
    return 128.0f * t * t;
}
float table_roughness_at(int i) { return 0.05f + 0.95f * float(i) / float(kTableSize - 1); }

float table_roughness(float ns) {
    return interpolate(kTableRoughnessForNs, table_ns_at, legacy::ogl1_shininess(ns));
}
float table_shininess(float roughness) {
    return interpolate(kTableNsForRoughness, table_roughness_at, clamp01(roughness));
}

Pbr from_material(const Material& m) {
    Pbr p;
    p.base_color = glm::vec3(m.base_color_factor);
    p.metallic = clamp01(m.metallic_factor);
    p.roughness = clamp01(m.roughness_factor);
    float f0 = ior_to_f0(m.ior_value());
    if (m.specular) {
        p.specular_f0 = glm::min(glm::vec3(f0) * m.specular->specular_color_factor, glm::vec3(1.0f));
        p.specular_weight = m.specular->specular_factor;
    } else {
        p.specular_f0 = glm::vec3(f0);
    }
    return p;
}

void apply_pbr(const Pbr& p, Material& m) {
    m.base_color_factor = glm::vec4(p.base_color, m.base_color_factor.w);
    m.metallic_factor = p.metallic;
    m.roughness_factor = p.roughness;
    float f0 = ior_to_f0(m.ior_value());
    bool textures = m.specular && (m.specular->specular_texture.valid() || m.specular->specular_color_texture.valid());
    if (p.uses_specular() || textures || std::abs(f0 - 0.04f) > 1e-6f) {
        SpecularExt s = m.specular.value_or(SpecularExt{});
        s.specular_factor = p.specular_weight;
        s.specular_color_factor = f0 > 0.0f ? p.specular_f0 / f0 : glm::vec3(1.0f);
        m.specular = s;
    } else {
        m.specular.reset();
    }
}

}  // namespace fresnel::fit
