// Writes the linearly-transformed-cosine table behind fresnel::ltc (libs/material/src/ltc_table.inc,
// fresnel/material/ltc.h): for each perceptual roughness r = i/63 and view parameter t = j/63
// (n.v = 1 - t^2, so that the lookup reads y = sqrt(1 - n.v), as Heitz's table), the inverse matrix M^-1 = [[a, 0, b], [0, c, 0], [d, 0, 1]] of the LTC
// closest to fresnel's GGX lobe D(h) V(l, v) (n.l) (brdf.h, alpha = r^2, no Fresnel), divided by
// its directional albedo, in the frame n = +Z, v in the XZ plane with v.x >= 0.
//
// The fit (after Heitz et al. 2016): M = R(phi) [[m00, 0, m00 s], [0, m11, 0], [0, 0, 1]], where
// R rotates +Z by phi about Y; the four parameters (log m00, log m11, s, phi) minimise the L1
// distance between the normalised lobe (0 below the horizon) and the LTC density over the
// sphere (so the LTC's mass below the horizon, lost to the clipped polygon, counts), estimated with a fixed stratified set of directions
// importance-sampled from both (GGX's D, the transformed cosine) and combined by the balance
// heuristic. Nelder-Mead, started from the neighbouring entry (roughness descending, so the
// rough, cosine-like lobes come first), its scale moved to the new alpha and phi at the lobe's
// mean direction. The L1 distance bounds twice any polygon's error relative to the albedo.
// Roughness is floored at 0.02 (alpha 4e-4) and n.v at 1e-3 so that the matrices stay finite.
// Deterministic (one thread, no random numbers); run it after changing the GGX lobe:
//   build/bin/ltc_fit libs/material/src/ltc_table.inc
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "fresnel/material/brdf.h"
#include "fresnel/material/ltc.h"

namespace {

using glm::dvec3;

constexpr int kSize = fresnel::ltc::kTableSize;
constexpr double kPi = 3.14159265358979323846;
constexpr double kMinRoughness = 0.02;
constexpr double kMinCosView = 1e-3;
constexpr int kFitAxis = 24;      // the objective: kFitAxis^2 directions from each strategy
constexpr int kCheckAxis = 64;    // the reported error: a finer, independent set
constexpr int kAlbedoAxis = 128;  // the albedo and mean direction: kAlbedoAxis^2 GGX samples

// brdf.h's d_ggx and v_smith_ggx_correlated in double (the same formulas, the same floor):
// near-mirror lobes are narrower than float's resolution of n.h near 1.
double d_ggx(double n_dot_h, double alpha) {
    double a2 = alpha * alpha;
    double f = std::max((1.0 - n_dot_h) * (1.0 + n_dot_h) + n_dot_h * n_dot_h * a2, 1e-7);
    return a2 / (kPi * f * f);
}
double v_smith(double n_dot_l, double n_dot_v, double alpha) {
    double a2 = alpha * alpha;
    double ggxv = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    double ggxl = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    double g = ggxv + ggxl;
    return g > 0.0 ? 0.5 / g : 0.0;
}

// Stratified points of the unit square, (k + 0.5) / n per axis.
double grid(int k, int n) { return (double(k) + 0.5) / double(n); }

// The GGX lobe at one (alpha, v).
struct Lobe {
    double alpha = 1.0;
    dvec3 v{0.0, 0.0, 1.0};
    double albedo = 1.0;  // the integral of D V n.l over the hemisphere

    double unnormalised(dvec3 l) const {
        if (l.z <= 0.0) return 0.0;
        dvec3 h = glm::normalize(l + v);
        return d_ggx(h.z, alpha) * v_smith(l.z, v.z, alpha) * l.z;
    }
    double value(dvec3 l) const { return unnormalised(l) / albedo; }
    // The density of l = reflect(-v, h) with h drawn from D(h) (n.h).
    double pdf(dvec3 l) const {
        dvec3 h = l + v;
        double len = glm::length(h);
        if (len <= 0.0) return 0.0;
        h /= len;
        double v_dot_h = glm::dot(v, h);
        if (h.z <= 0.0 || v_dot_h <= 0.0) return 0.0;
        return d_ggx(h.z, alpha) * h.z / (4.0 * v_dot_h);
    }
    dvec3 sample(double u1, double u2) const {
        double a2 = alpha * alpha;
        double cos2 = (1.0 - u1) / (1.0 + (a2 - 1.0) * u1);
        double cos_t = std::sqrt(cos2), sin_t = std::sqrt(std::max(1.0 - cos2, 0.0));
        double phi = 2.0 * kPi * u2;
        dvec3 h(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
        return 2.0 * glm::dot(v, h) * h - v;
    }
};

// A cosine-distributed direction (the LTC's w_o).
dvec3 cosine_sample(double u1, double u2) {
    double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0 - u1, 0.0))};
}

struct Params {
    std::array<double, 4> x{0.0, 0.0, 0.0, 0.0};  // log m00, log m11, s, phi
};

// M and M^-1 (rows) of the parameters.
struct Ltc {
    double m[3][3];
    double minv[3][3];
    double det_minv;
    explicit Ltc(const Params& p) {
        double m00 = std::exp(p.x[0]), m11 = std::exp(p.x[1]), s = p.x[2];
        double c = std::cos(p.x[3]), sn = std::sin(p.x[3]);
        // R (rows) [[c, 0, sn], [0, 1, 0], [-sn, 0, c]] times S [[m00, 0, m00 s], [0, m11, 0], [0, 0, 1]].
        double rows[3][3] = {{c * m00, 0.0, c * m00 * s + sn}, {0.0, m11, 0.0}, {-sn * m00, 0.0, -sn * m00 * s + c}};
        // S^-1 [[1/m00, 0, -s], [0, 1/m11, 0], [0, 0, 1]] times R^T [[c, 0, -sn], [0, 1, 0], [sn, 0, c]].
        double inv[3][3] = {{c / m00 - s * sn, 0.0, -sn / m00 - s * c}, {0.0, 1.0 / m11, 0.0}, {sn, 0.0, c}};
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) m[i][k] = rows[i][k], minv[i][k] = inv[i][k];
        det_minv = 1.0 / (m00 * m11);
    }
    static dvec3 mul(const double a[3][3], dvec3 x) {
        return {a[0][0] * x.x + a[0][1] * x.y + a[0][2] * x.z, a[1][0] * x.x + a[1][1] * x.y + a[1][2] * x.z,
                a[2][0] * x.x + a[2][1] * x.y + a[2][2] * x.z};
    }
    // The normalised LTC density at the unit direction l.
    double density(dvec3 l) const {
        dvec3 w = mul(minv, l);
        double len = glm::length(w);
        if (w.z <= 0.0) return 0.0;
        return (w.z / len) / kPi * det_minv / (len * len * len);
    }
};

// The directions of one entry's objective: the lobe's own samples (fixed) and the cosine
// samples (moved by M at each evaluation).
struct Samples {
    struct Fixed {
        dvec3 l;
        double f, pdf;
    };
    std::vector<Fixed> lobe;
    std::vector<dvec3> cosine;    // w_o
    double n = 0.0;               // samples per strategy
};

Samples make_samples(const Lobe& lobe, int axis) {
    Samples s;
    s.n = double(axis) * double(axis);
    for (int a = 0; a < axis; ++a)
        for (int b = 0; b < axis; ++b) {
            dvec3 l = lobe.sample(grid(a, axis), grid(b, axis));
            s.lobe.push_back({l, lobe.value(l), lobe.pdf(l)});
            s.cosine.push_back(cosine_sample(grid(a, axis), grid(b, axis)));
        }
    return s;
}

// The L1 distance over the sphere (the lobe is 0 below the horizon, where the LTC's mass is lost
// to the clipped polygon), by the balance heuristic of both strategies.
double l1_error(const Lobe& lobe, const Samples& s, const Params& p) {
    Ltc ltc(p);
    double sum = 0.0;
    for (const Samples::Fixed& x : s.lobe) {
        double d = ltc.density(x.l), q = 0.5 * (x.pdf + d);
        if (q > 0.0) sum += std::fabs(x.f - d) / q;
    }
    for (dvec3 wo : s.cosine) {
        dvec3 w = Ltc::mul(ltc.m, wo);
        double len = glm::length(w);
        w /= len;
        double d = wo.z / kPi * (len * len * len) * ltc.det_minv;
        double q = 0.5 * (lobe.pdf(w) + d);
        if (q > 0.0) sum += std::fabs(lobe.value(w) - d) / q;
    }
    return sum / (2.0 * s.n);
}

// Nelder-Mead on 4 parameters (reflection 1, expansion 2, contraction 1/2, shrink 1/2).
template <class F>
Params nelder_mead(F&& f, const Params& start, const std::array<double, 4>& step, int max_evals, double tolerance,
                   double& best_value) {
    constexpr int n = 4;
    std::array<Params, n + 1> x;
    std::array<double, n + 1> fx;
    x[0] = start;
    for (int i = 0; i < n; ++i) {
        x[i + 1] = start;
        x[i + 1].x[i] += step[i];
    }
    int evals = 0;
    for (int i = 0; i <= n; ++i) fx[i] = f(x[i]), ++evals;
    auto combine = [](const Params& a, const Params& b, double t) {  // a + t (b - a)
        Params r;
        for (int i = 0; i < n; ++i) r.x[i] = a.x[i] + t * (b.x[i] - a.x[i]);
        return r;
    };
    while (evals < max_evals) {
        std::array<int, n + 1> order{};
        for (int i = 0; i <= n; ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](int a, int b) { return fx[a] < fx[b]; });
        std::array<Params, n + 1> xs;
        std::array<double, n + 1> fs;
        for (int i = 0; i <= n; ++i) xs[i] = x[order[i]], fs[i] = fx[order[i]];
        x = xs;
        fx = fs;
        if (fx[n] - fx[0] <= tolerance * (std::fabs(fx[0]) + 1e-12)) break;
        Params centroid;
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < n; ++k) centroid.x[k] += x[i].x[k] / double(n);
        Params reflected = combine(centroid, x[n], -1.0);
        double fr = f(reflected);
        ++evals;
        if (fr < fx[0]) {
            Params expanded = combine(centroid, x[n], -2.0);
            double fe = f(expanded);
            ++evals;
            if (fe < fr) x[n] = expanded, fx[n] = fe;
            else x[n] = reflected, fx[n] = fr;
        } else if (fr < fx[n - 1]) {
            x[n] = reflected, fx[n] = fr;
        } else {
            bool outside = fr < fx[n];
            Params contracted = combine(centroid, outside ? reflected : x[n], 0.5);
            double fc = f(contracted);
            ++evals;
            if (fc < (outside ? fr : fx[n])) {
                x[n] = contracted, fx[n] = fc;
            } else {
                for (int i = 1; i <= n; ++i) {
                    x[i] = combine(x[0], x[i], 0.5);
                    fx[i] = f(x[i]);
                    ++evals;
                }
            }
        }
    }
    int best = int(std::min_element(fx.begin(), fx.end()) - fx.begin());
    best_value = fx[best];
    return x[best];
}

// The library's float GGX and the double twins above agree.
bool twins_agree() {
    for (double alpha : {0.01, 0.1, 0.4, 1.0})
        for (double c : {0.05, 0.3, 0.7, 0.99}) {
            double d = d_ggx(c, alpha), df = fresnel::brdf::d_ggx(float(c), float(alpha));
            double v = v_smith(c, 1.0 - 0.5 * c, alpha);
            double vf = fresnel::brdf::v_smith_ggx_correlated(float(c), float(1.0 - 0.5 * c), float(alpha));
            if (std::fabs(d - df) > 1e-4 * d || std::fabs(v - vf) > 1e-4 * v) return false;
        }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: ltc_fit OUT.inc\n");
        return 2;
    }
    if (!twins_agree()) {
        std::fprintf(stderr, "ltc_fit: the double GGX differs from brdf.h's\n");
        return 1;
    }
    auto t0 = std::chrono::steady_clock::now();
    std::vector<float> table(std::size_t(kSize) * kSize * 4);
    std::vector<Params> fits(std::size_t(kSize) * kSize);
    std::vector<double> errors(std::size_t(kSize) * kSize);
    double worst = 0.0, total = 0.0;
    int worst_i = 0, worst_j = 0;
    for (int j = 0; j < kSize; ++j) {
        double t = double(j) / double(kSize - 1);
        double cos_v = std::max(1.0 - t * t, kMinCosView);  // t = sqrt(1 - n.v), the lookup's y
        double row_worst = 0.0;
        for (int i = kSize - 1; i >= 0; --i) {
            Lobe lobe;
            double r = std::max(double(i) / double(kSize - 1), kMinRoughness);
            lobe.alpha = r * r;
            lobe.v = dvec3(std::sqrt(1.0 - cos_v * cos_v), 0.0, cos_v);
            // Albedo and mean direction: E = mean of f / pdf = 4 V n.l v.h / n.h.
            double albedo = 0.0;
            dvec3 mean(0.0);
            for (int a = 0; a < kAlbedoAxis; ++a)
                for (int b = 0; b < kAlbedoAxis; ++b) {
                    dvec3 l = lobe.sample(grid(a, kAlbedoAxis), grid(b, kAlbedoAxis));
                    double pdf = lobe.pdf(l);
                    if (l.z <= 0.0 || pdf <= 0.0) continue;
                    double w = lobe.unnormalised(l) / pdf;
                    albedo += w;
                    mean += w * l;
                }
            lobe.albedo = albedo / double(kAlbedoAxis * kAlbedoAxis);
            double phi_mean = std::atan2(mean.x, mean.z);
            Samples samples = make_samples(lobe, kFitAxis);
            auto f = [&](const Params& p) {
                if (!(std::fabs(p.x[3]) < 0.5 * kPi) || std::fabs(p.x[0]) > 20.0 || std::fabs(p.x[1]) > 20.0)
                    return 1e30;
                return l1_error(lobe, samples, p);
            };
            // Start: the best of the neighbours (rougher; the previous view), their scale moved to
            // this alpha, each as fitted and turned to the lobe's mean direction, and a cosine
            // scaled to alpha along the mean direction.
            std::vector<Params> starts;
            Params fresh;
            fresh.x[0] = fresh.x[1] = std::log(std::min(lobe.alpha * 2.0, 1.0));
            fresh.x[3] = phi_mean;
            starts.push_back(fresh);
            for (int k = 0; k < 2; ++k) {
                int ni = k == 0 ? i + 1 : i, nj = k == 0 ? j : j - 1;
                if (ni >= kSize || nj < 0) continue;
                Params p = fits[std::size_t(nj) * kSize + std::size_t(ni)];
                double rn = std::max(double(ni) / double(kSize - 1), kMinRoughness);
                double scale = std::log(lobe.alpha / (rn * rn));
                p.x[0] += scale;
                p.x[1] += scale;
                starts.push_back(p);
                p.x[3] = phi_mean;
                starts.push_back(p);
            }
            Params start = starts[0];
            double start_value = f(start);
            for (const Params& p : starts) {
                double value = f(p);
                if (value < start_value) start = p, start_value = value;
            }
            double best = 0.0;
            for (int round = 0; round < 3; ++round) {
                double m00 = std::exp(start.x[0]);
                std::array<double, 4> step = {0.1, 0.1, 0.1, std::min(0.25 * m00, 0.1)};
                start = nelder_mead(f, start, step, 300, 1e-6, best);
            }
            fits[std::size_t(j) * kSize + std::size_t(i)] = start;
            // The reported error, on a finer set of directions than the fit's.
            double check = l1_error(lobe, make_samples(lobe, kCheckAxis), start);
            errors[std::size_t(j) * kSize + std::size_t(i)] = check;
            total += check;
            row_worst = std::max(row_worst, check);
            if (check > worst) worst = check, worst_i = i, worst_j = j;
            // M^-1 normalised so that [2][2] = 1.
            Ltc ltc(start);
            double z = ltc.minv[2][2];
            float* e = &table[(std::size_t(j) * kSize + std::size_t(i)) * 4];
            e[0] = float(ltc.minv[0][0] / z);
            e[1] = float(ltc.minv[0][2] / z);
            e[2] = float(ltc.minv[1][1] / z);
            e[3] = float(ltc.minv[2][0] / z);
        }
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const float* e0 = &table[(std::size_t(j) * kSize + 16) * 4];
        std::fprintf(stderr,
                     "t %2d/63 n.v %.4f: worst L1 %.4f (r 0.25: L1 %.4f, M^-1 a %.3f b %.3f c %.3f d %.3f) %6.1f s\n", j,
                     cos_v, row_worst, errors[std::size_t(j) * kSize + 16], double(e0[0]), double(e0[1]), double(e0[2]),
                     double(e0[3]), seconds);
    }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "worst L1 %.4f at roughness %.3f, n.v %.4f; mean L1 %.4f; %.1f s\n", worst,
                 double(worst_i) / double(kSize - 1), 1.0 - std::pow(double(worst_j) / double(kSize - 1), 2.0),
                 total / double(kSize * kSize), seconds);
    std::string tmp = std::string(argv[1]) + ".tmp";
    {
        std::ofstream out(tmp);
        out << "// Generated by tools/ltc_fit; do not edit.\n"
            << "// M^-1 (a, b, c, d) per texel, index ((j * 64 + i) * 4 + k): roughness i / 63,\n"
            << "// n.v = 1 - (j / 63)^2 (read at y = sqrt(1 - n.v)). See fresnel/material/ltc.h.\n";
        out << "constexpr std::array<float, 64 * 64 * 4> kLtcInverse = {";
        char buf[48];
        for (std::size_t k = 0; k < table.size(); ++k) {
            std::snprintf(buf, sizeof buf, "%#.8gf", double(table[k]));
            out << (k % 8 == 0 ? "\n    " : " ") << buf << (k + 1 < table.size() ? "," : "");
        }
        out << "};\n";
        if (!out) {
            std::fprintf(stderr, "ltc_fit: cannot write %s\n", tmp.c_str());
            return 1;
        }
    }
    std::filesystem::rename(tmp, argv[1]);
    return 0;
}
