// FLIP, written from the papers: LDR-FLIP (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom,
// Fairchild, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020) and HDR-FLIP
// (Andersson, Nilsson, Shirley, Akenine-Moller, "Visualizing Errors in Rendered High Dynamic
// Range Images", Eurographics 2021), with the constants of the authors' reference code so that
// mean errors agree with theirs.
//
// Colour pipeline: sRGB -> linear -> XYZ -> YCxCz (opponent space, normalised by the D65 white);
// each channel filtered by its contrast sensitivity function (a sum of Gaussians in visual
// degrees); back to linear RGB, clamped to the unit cube; CIE L*a*b* with the Hunt adjustment
// (a*, b* scaled by L*/100); HyAB distance |dL| + ||(da, db)||, raised to 0.7 and redistributed
// to [0,1] (errors below 0.4 * cmax take 95 % of the range; cmax is the distance from green to
// blue). Feature pipeline: the luminance Y of each image filtered by the first (edges) and second
// (points) derivative of a Gaussian whose spread matches the human edge detector (0.082 degrees
// peak to trough); the larger difference of the gradient magnitudes, /sqrt(2), raised to 0.5.
// FLIP = colour error ^ (1 - feature error).
//
// Every 2-D kernel here is a product (or, for the blue-yellow CSF, a sum of two products) of 1-D
// kernels, so the filters run separably; borders replicate the edge pixel. The 2-D
// normalisations of the reference code (CSF to sum 1; derivative kernels' positive weights to
// sum 1 and negative weights to sum -1) factor exactly into the 1-D ones used here.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "fresnel/core/error.h"
#include "fresnel/core/metrics.h"
#include "fresnel/core/parallel.h"

namespace fresnel {

namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

// Linear sRGB (D65) to CIE XYZ, in the exact rational form FLIP's reference code uses.
constexpr Mat3 kRgbToXyz = {{{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                             {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                             {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}}};

Mat3 inverse(const Mat3& m) {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    Mat3 r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // cofactor of m[j][i]
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            r[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
        }
    return r;
}

struct Color {
    Mat3 to_xyz = kRgbToXyz, to_rgb = inverse(kRgbToXyz);
    double white[3] = {};  // XYZ of linear RGB (1,1,1): the D65 reference white of this matrix
    Color() {
        for (int i = 0; i < 3; ++i) white[i] = to_xyz[i][0] + to_xyz[i][1] + to_xyz[i][2];
    }
    void rgb_to_xyz(const double in[3], double out[3]) const {
        for (int i = 0; i < 3; ++i) out[i] = to_xyz[i][0] * in[0] + to_xyz[i][1] * in[1] + to_xyz[i][2] * in[2];
    }
    void xyz_to_rgb(const double in[3], double out[3]) const {
        for (int i = 0; i < 3; ++i) out[i] = to_rgb[i][0] * in[0] + to_rgb[i][1] * in[1] + to_rgb[i][2] * in[2];
    }
    // XYZ -> YCxCz (the linear opponent space of Zhang and Wandell's S-CIELAB).
    void xyz_to_ycxcz(const double xyz[3], double out[3]) const {
        const double x = xyz[0] / white[0], y = xyz[1] / white[1], z = xyz[2] / white[2];
        out[0] = 116 * y - 16;
        out[1] = 500 * (x - y);
        out[2] = 200 * (y - z);
    }
    void ycxcz_to_xyz(const double in[3], double out[3]) const {
        const double y = (in[0] + 16) / 116;
        out[0] = (y + in[1] / 500) * white[0];
        out[1] = y * white[1];
        out[2] = (y - in[2] / 200) * white[2];
    }
    // Linear RGB -> CIE L*a*b* with the Hunt adjustment.
    void rgb_to_hunt_lab(const double rgb[3], double out[3]) const {
        double xyz[3];
        rgb_to_xyz(rgb, xyz);
        constexpr double d = 6.0 / 29.0;
        double f[3];
        for (int i = 0; i < 3; ++i) {
            const double t = xyz[i] / white[i];
            f[i] = t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
        }
        const double L = 116 * f[1] - 16;
        out[0] = L;
        out[1] = 0.01 * L * 500 * (f[0] - f[1]);
        out[2] = 0.01 * L * 200 * (f[1] - f[2]);
    }
};

double srgb_decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double srgb_encode(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055; }

double hyab(const double a[3], const double b[3]) {
    return std::abs(a[0] - b[0]) + std::sqrt((a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

using Kernel = std::vector<float>;  // 2r+1 taps, centre at r

// One plane filtered by kx along rows, then ky along columns; edges replicate.
void filter(const std::vector<float>& src, std::vector<float>& dst, int w, int h, const Kernel& kx, const Kernel& ky) {
    std::vector<float> tmp(src.size());
    const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
    parallel_for(std::size_t(h), [&](std::size_t y) {
        const float* row = &src[y * w];
        float* out = &tmp[y * w];
        for (int x = 0; x < w; ++x) {
            float acc = 0;
            for (int k = -rx; k <= rx; ++k) acc += kx[k + rx] * row[std::clamp(x + k, 0, w - 1)];
            out[x] = acc;
        }
    });
    dst.resize(src.size());
    parallel_for(std::size_t(h), [&](std::size_t y) {
        float* out = &dst[y * w];
        for (int x = 0; x < w; ++x) out[x] = 0;
        for (int k = -ry; k <= ry; ++k) {
            const float* row = &tmp[std::size_t(std::clamp(int(y) + k, 0, h - 1)) * w];
            const float wk = ky[k + ry];
            for (int x = 0; x < w; ++x) out[x] += wk * row[x];
        }
    });
}

// exp(-pi^2 (x / ppd)^2 / b) for |x| <= r, normalised to sum 1; `sum` gets the sum before.
Kernel csf_gaussian(double b, double ppd, int r, double& sum) {
    std::vector<double> e(2 * r + 1);
    sum = 0;
    for (int x = -r; x <= r; ++x) {
        const double d = x / ppd;
        sum += e[x + r] = std::exp(-std::numbers::pi * std::numbers::pi * d * d / b);
    }
    Kernel k(2 * r + 1);
    for (int i = 0; i <= 2 * r; ++i) k[i] = float(e[i] / sum);
    return k;
}

// The contrast sensitivity functions of the paper (achromatic, red-green, blue-yellow):
// a1 sqrt(pi/b1) exp(-pi^2 d^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 d^2/b2), d in degrees.
struct Csf {
    double a1, b1, a2, b2;
};
constexpr Csf kCsf[3] = {{1, 0.0047, 0, 1e-5}, {1, 0.0053, 0, 1e-5}, {34.1, 0.04, 13.5, 0.025}};

struct Features {
    Kernel smooth, edge, point;
};

Features feature_kernels(double ppd) {
    const double sd = 0.5 * 0.082 * ppd;
    const int r = int(std::ceil(3 * sd));
    Features f;
    f.smooth.resize(2 * r + 1), f.edge.resize(2 * r + 1), f.point.resize(2 * r + 1);
    std::vector<double> g(2 * r + 1), e(2 * r + 1), p(2 * r + 1);
    double gs = 0, ep = 0, en = 0, pp = 0, pn = 0;
    for (int x = -r; x <= r; ++x) {
        g[x + r] = std::exp(-(x * x) / (2 * sd * sd));
        e[x + r] = -x * g[x + r];
        p[x + r] = (x * x / (sd * sd) - 1) * g[x + r];
        gs += g[x + r];
        (e[x + r] > 0 ? ep : en) += std::abs(e[x + r]);
        (p[x + r] > 0 ? pp : pn) += std::abs(p[x + r]);
    }
    for (int i = 0; i <= 2 * r; ++i) {
        f.smooth[i] = float(g[i] / gs);
        f.edge[i] = float(e[i] / (e[i] > 0 ? ep : en));
        f.point[i] = float(p[i] / (p[i] > 0 ? pp : pn));
    }
    return f;
}

void require_same_size(const ImageF& a, const ImageF& b) {
    if (a.width != b.width || a.height != b.height)
        throw Error("", "", "images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(b.width) + "x" + std::to_string(b.height));
}

// LDR-FLIP of two images given as display-encoded sRGB planes (R, G, B; values clamped to [0,1]).
class LdrFlip {
public:
    LdrFlip(int w, int h, double ppd) : w_(w), h_(h), features_(feature_kernels(ppd)) {
        const double max_b = 0.04;  // the widest of the CSF Gaussians
        const int r = int(std::ceil(3 * std::sqrt(max_b / (2 * std::numbers::pi * std::numbers::pi)) * ppd));
        for (int c = 0; c < 3; ++c) {
            const Csf& s = kCsf[c];
            double sum1 = 0, sum2 = 0;
            csf_[c][0] = csf_gaussian(s.b1, ppd, r, sum1);
            csf_[c][1] = csf_gaussian(s.b2, ppd, r, sum2);
            // Weights of the two normalised separable terms in the kernel normalised to sum 1.
            const double t1 = s.a1 * std::sqrt(std::numbers::pi / s.b1) * sum1 * sum1;
            const double t2 = s.a2 * std::sqrt(std::numbers::pi / s.b2) * sum2 * sum2;
            weight_[c][0] = t1 / (t1 + t2);
            weight_[c][1] = t2 / (t1 + t2);
        }
        double green[3] = {0, 1, 0}, blue[3] = {0, 0, 1}, lg[3], lb[3];
        color_.rgb_to_hunt_lab(green, lg);
        color_.rgb_to_hunt_lab(blue, lb);
        cmax_ = std::pow(hyab(lg, lb), 0.7);
    }

    // rgb: 3 planes of w*h display values each (reference then test).
    std::vector<float> run(const std::array<std::vector<float>, 3>& ref, const std::array<std::vector<float>, 3>& test) const {
        const std::size_t n = std::size_t(w_) * h_;
        Prepared pr = prepare(ref), pt = prepare(test);
        std::vector<float> out(n);
        parallel_for(std::size_t(h_), [&](std::size_t y) {
            for (std::size_t i = y * w_; i < (y + 1) * w_; ++i) {
                const double a[3] = {pr.lab[0][i], pr.lab[1][i], pr.lab[2][i]};
                const double b[3] = {pt.lab[0][i], pt.lab[1][i], pt.lab[2][i]};
                const double color = redistribute(std::pow(hyab(a, b), 0.7));
                const double edge = std::abs(std::hypot(pr.feat[0][i], pr.feat[1][i]) - std::hypot(pt.feat[0][i], pt.feat[1][i]));
                const double point = std::abs(std::hypot(pr.feat[2][i], pr.feat[3][i]) - std::hypot(pt.feat[2][i], pt.feat[3][i]));
                const double feature = std::sqrt(std::max(edge, point) / std::numbers::sqrt2);
                out[i] = float(std::pow(color, 1 - feature));
            }
        });
        return out;
    }

private:
    struct Prepared {
        std::array<std::vector<float>, 3> lab;   // Hunt-adjusted L*a*b* after CSF filtering
        std::array<std::vector<float>, 4> feat;  // edge x, edge y, point x, point y
    };

    double redistribute(double e) const {
        constexpr double pc = 0.4, pt = 0.95;
        const double knee = pc * cmax_;
        return e < knee ? pt / knee * e : pt + (e - knee) / (cmax_ - knee) * (1 - pt);
    }

    Prepared prepare(const std::array<std::vector<float>, 3>& rgb) const {
        const std::size_t n = std::size_t(w_) * h_;
        std::array<std::vector<float>, 3> opp;
        for (auto& p : opp) p.resize(n);
        std::vector<float> lum(n);
        parallel_for(std::size_t(h_), [&](std::size_t y) {
            for (std::size_t i = y * w_; i < (y + 1) * w_; ++i) {
                const double lin[3] = {srgb_decode(rgb[0][i]), srgb_decode(rgb[1][i]), srgb_decode(rgb[2][i])};
                double xyz[3], o[3];
                color_.rgb_to_xyz(lin, xyz);
                color_.xyz_to_ycxcz(xyz, o);
                for (int c = 0; c < 3; ++c) opp[c][i] = float(o[c]);
                lum[i] = float((o[0] + 16) / 116);  // Y / Yn
            }
        });
        Prepared p;
        for (int c = 0; c < 3; ++c) {
            filter(opp[c], p.lab[c], w_, h_, csf_[c][0], csf_[c][0]);
            if (weight_[c][1] > 0) {
                std::vector<float> second;
                filter(opp[c], second, w_, h_, csf_[c][1], csf_[c][1]);
                const float w0 = float(weight_[c][0]), w1 = float(weight_[c][1]);
                for (std::size_t i = 0; i < n; ++i) p.lab[c][i] = w0 * p.lab[c][i] + w1 * second[i];
            }
        }
        parallel_for(std::size_t(h_), [&](std::size_t y) {
            for (std::size_t i = y * w_; i < (y + 1) * w_; ++i) {
                const double o[3] = {p.lab[0][i], p.lab[1][i], p.lab[2][i]};
                double xyz[3], lin[3], lab[3];
                color_.ycxcz_to_xyz(o, xyz);
                color_.xyz_to_rgb(xyz, lin);
                for (double& v : lin) v = std::clamp(v, 0.0, 1.0);
                color_.rgb_to_hunt_lab(lin, lab);
                for (int c = 0; c < 3; ++c) p.lab[c][i] = float(lab[c]);
            }
        });
        filter(lum, p.feat[0], w_, h_, features_.edge, features_.smooth);
        filter(lum, p.feat[1], w_, h_, features_.smooth, features_.edge);
        filter(lum, p.feat[2], w_, h_, features_.point, features_.smooth);
        filter(lum, p.feat[3], w_, h_, features_.smooth, features_.point);
        return p;
    }

    int w_, h_;
    Color color_;
    Features features_;
    Kernel csf_[3][2];
    double weight_[3][2] = {};
    double cmax_ = 1;
};

std::array<std::vector<float>, 3> display_planes(const ImageF& img) {
    const std::size_t n = std::size_t(img.width) * img.height;
    std::array<std::vector<float>, 3> p;
    for (int c = 0; c < 3; ++c) {
        p[c].resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const float v = img.pixels[i * 4 + c];
            p[c][i] = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
        }
    }
    return p;
}

// The ACES fit (Narkowicz) HDR-FLIP assumes, with its 0.6 pre-exposure folded into the
// coefficients: (k0 x^2 + k1 x) / (k3 x^2 + k4 x + k5).
constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

double aces(double x) {
    if (!(x < std::numeric_limits<double>::max())) return 1.0;  // inf
    const double y = (kAces[0] * x * x + kAces[1] * x + kAces[2]) / (kAces[3] * x * x + kAces[4] * x + kAces[5]);
    return std::clamp(y, 0.0, 1.0);
}

// The x at which the ACES curve reaches t.
double aces_inverse(double t) {
    const double c0 = (kAces[1] - kAces[4] * t) / (kAces[0] - kAces[3] * t);
    const double c1 = (kAces[2] - kAces[5] * t) / (kAces[0] - kAces[3] * t);
    return -0.5 * c0 + std::sqrt(0.25 * c0 * c0 - c1);
}

float clean(float v) { return std::isnan(v) || v < 0 ? 0.0f : v; }

}  // namespace

double flip_default_pixels_per_degree() { return 0.7 * (3840.0 / 0.7) * std::numbers::pi / 180.0; }

std::vector<float> flip_ldr(const ImageF& reference, const ImageF& test, double ppd) {
    require_same_size(reference, test);
    if (!(ppd > 0) || ppd > 1000) throw Error("", "", "pixels per degree must lie in (0, 1000]");
    if (reference.width == 0 || reference.height == 0) return {};
    LdrFlip flip(reference.width, reference.height, ppd);
    return flip.run(display_planes(reference), display_planes(test));
}

FlipExposures flip_exposures(const ImageF& ref) {
    const std::size_t n = std::size_t(ref.width) * ref.height;
    std::vector<float> lum(n);
    float y_max = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const float* p = &ref.pixels[i * 4];
        lum[i] = 0.2126f * clean(p[0]) + 0.7152f * clean(p[1]) + 0.0722f * clean(p[2]);
        if (!std::isfinite(lum[i])) lum[i] = std::numeric_limits<float>::max();
        y_max = std::max(y_max, lum[i]);
    }
    FlipExposures e;
    if (y_max <= 0) return e;  // black reference: one exposure, 0
    const double t = 0.85;
    const double x = aces_inverse(t);
    e.start = std::log2(x / y_max);
    std::vector<float> positive;
    // The median as NumPy's percentile(50) takes it: the mean of the two middle values of an even count.
    auto median = [](std::vector<float>& v) {
        auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
        std::nth_element(v.begin(), mid, v.end());
        double m = *mid;
        if (v.size() % 2 == 0) m = 0.5 * (m + double(*std::max_element(v.begin(), mid)));
        return m;
    };
    double y_mid = median(lum);
    if (y_mid <= 0) {
        for (float v : lum)
            if (v > 0) positive.push_back(v);
        y_mid = median(positive);
    }
    e.stop = std::log2(x / y_mid);
    if (e.stop <= e.start) {
        e.stop = e.start;
        e.count = 1;
        return e;
    }
    e.count = int(std::clamp(std::ceil(e.stop - e.start), 2.0, 32.0));
    return e;
}

std::vector<float> flip_hdr(const ImageF& reference, const ImageF& test, const FlipExposures& exposures, double ppd) {
    require_same_size(reference, test);
    if (!(ppd > 0) || ppd > 1000) throw Error("", "", "pixels per degree must lie in (0, 1000]");
    if (exposures.count < 1 || exposures.count > 256 || !std::isfinite(exposures.start) || !std::isfinite(exposures.stop))
        throw Error("", "", "bad HDR-FLIP exposure range");
    const int w = reference.width, h = reference.height;
    if (w == 0 || h == 0) return {};
    const std::size_t n = std::size_t(w) * h;
    LdrFlip flip(w, h, ppd);
    std::vector<float> result(n, 0.0f);
    const double step = exposures.count > 1 ? (exposures.stop - exposures.start) / (exposures.count - 1) : 0.0;
    for (int k = 0; k < exposures.count; ++k) {
        const double scale = std::exp2(exposures.start + k * step);
        auto tone = [&](const ImageF& img) {
            std::array<std::vector<float>, 3> p;
            for (int c = 0; c < 3; ++c) {
                p[c].resize(n);
                for (std::size_t i = 0; i < n; ++i) p[c][i] = float(srgb_encode(aces(scale * clean(img.pixels[i * 4 + c]))));
            }
            return p;
        };
        std::vector<float> e = flip.run(tone(reference), tone(test));
        for (std::size_t i = 0; i < n; ++i) result[i] = std::max(result[i], e[i]);
    }
    return result;
}

}  // namespace fresnel
