// The metrics of `fresnel compare` (fresnel/core/metrics.h) and its heat map (heatmap.h).
//
// FLIP's authors publish a reference/test pair (their repository's images/reference.png and
// test.png: mean LDR-FLIP 0.159691 from their C++ code, 0.159693 from their NumPy code; HDR-FLIP
// of the EXR pair 0.283478). Those images cannot be fetched on this machine (no network but the
// Debian and npm registries, and no package ships them), so this file checks FLIP three other ways:
//   * closed forms: identical images give 0; uniform images have no features, so FLIP is the
//     redistributed HyAB distance of their Hunt-adjusted L*a*b* colours, computed here
//     independently with the CIE formulas;
//   * properties: symmetry, range, more error -> more FLIP, mask means;
//   * the authors' own reference implementation: their Python code (flip_api.py of
//     NVlabs/flip, non-separable 2-D filters; cv2.filter2D replaced by scipy's correlate with
//     mode 'nearest', which is the same replicate-border correlation) run outside this
//     repository on the procedural pairs below, which the test writes to $FRESNEL_METRICS_DUMP
//     when that is set (PNGs, and raw little-endian float32 RGB for the HDR pair). Their means
//     are the expected values, to 1e-5 (their own C++ and NumPy codes differ by 2e-6).
// SSIM's expected values come the same way from scikit-image 0.19 (structural_similarity with
// gaussian_weights, sigma 1.5, use_sample_covariance False, data_range 1, channel_axis 2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "fresnel/core/error.h"
#include "fresnel/core/heatmap.h"
#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"

using namespace fresnel;

namespace {

// Deterministic integer noise in [0, 255].
int noise(int x, int y, int seed) {
    std::uint32_t h = std::uint32_t(x) * 73856093u ^ std::uint32_t(y) * 19349663u ^ std::uint32_t(seed) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return int(h & 255u);
}

int clamp8(int v) { return v < 0 ? 0 : v > 255 ? 255 : v; }

// 8-bit pairs as display-encoded ImageF (value / 255), opaque.
struct Pair {
    ImageF ref, test;
};

ImageF from8(int w, int h, const std::vector<int>& rgb) {
    ImageF img(w, h);
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
        for (int c = 0; c < 3; ++c) img.pixels[i * 4 + c] = float(rgb[i * 3 + c]) / 255.0f;
        img.pixels[i * 4 + 3] = 1.0f;
    }
    return img;
}

// Pair 0: gradients, a disc and a box; the test moves and recolours the disc, adds noise, and
// inverts a block. Pair 1: an 8-pixel checkerboard against a colour-shifted copy moved by one
// pixel with a soft (box-blurred) edge.
Pair make_pair(int which) {
    const int w = which == 0 ? 96 : 64, h = which == 0 ? 80 : 64;
    std::vector<int> r(std::size_t(w) * h * 3), t(r.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int* pr = &r[(std::size_t(y) * w + x) * 3];
            int* pt = &t[(std::size_t(y) * w + x) * 3];
            if (which == 0) {
                pr[0] = x * 255 / (w - 1), pr[1] = y * 255 / (h - 1), pr[2] = ((x / 6 + y / 5) % 2) * 120 + 60;
                for (int c = 0; c < 3; ++c) pt[c] = pr[c];
                if ((x - 30) * (x - 30) + (y - 40) * (y - 40) < 200) pr[0] = 230, pr[1] = 50, pr[2] = 25;
                if ((x - 33) * (x - 33) + (y - 40) * (y - 40) < 200) pt[0] = 205, pt[1] = 75, pt[2] = 25;
                if (x >= 60 && x < 90 && y >= 10 && y < 30) pr[0] = pt[0] = 25, pr[1] = pt[1] = 25, pr[2] = pt[2] = 200;
                for (int c = 0; c < 3; ++c) pt[c] = clamp8(pt[c] + (noise(x, y, c) - 128) / 10);
                if (x >= 50 && x < 80 && y >= 45 && y < 70)
                    for (int c = 0; c < 3; ++c) pt[c] = 255 - pt[c];
            } else {
                const int checker = ((x / 8 + y / 8) % 2) * 200 + 30;
                pr[0] = pr[1] = pr[2] = checker;
                int sum = 0;
                for (int k = -1; k <= 1; ++k) sum += (((std::max(0, x - 1 + k)) / 8 + y / 8) % 2) * 200 + 30;
                pt[0] = clamp8(sum / 3 + 12), pt[1] = clamp8(sum / 3), pt[2] = clamp8(sum / 3 - 20);
            }
        }
    return {from8(w, h, r), from8(w, h, t)};
}

// The HDR pair: linear values from arithmetic only (bit-identical on every IEEE machine).
Pair make_hdr_pair() {
    const int w = 48, h = 40;
    Pair p{ImageF(w, h), ImageF(w, h)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* a = p.ref.at(x, y);
            float* b = p.test.at(x, y);
            const float d2 = float((x - 20) * (x - 20) + (y - 18) * (y - 18));
            a[0] = 0.05f + 6.0f / (1.0f + d2 / 20.0f);
            a[1] = 0.05f + 2.0f * float(x) / float(w);
            a[2] = 0.05f + ((y / 3) % 2 ? 0.4f : 0.0f);
            if (x >= 36 && x < 40 && y >= 6 && y < 10) a[0] = a[1] = a[2] = 50.0f;
            for (int c = 0; c < 3; ++c) b[c] = a[c] * (1.0f + float(noise(x, y, 7 + c) - 128) / 1280.0f);
            if (x >= 8 && x < 24 && y >= 26 && y < 34)
                for (int c = 0; c < 3; ++c) b[c] *= 3.0f;
            a[3] = b[3] = 1.0f;
        }
    return p;
}

// Writes the pairs for the out-of-repository reference runs (see the top of this file).
void dump_if_asked() {
    const char* dir = std::getenv("FRESNEL_METRICS_DUMP");
    if (!dir) return;
    auto png = [](const ImageF& img, const std::filesystem::path& path) {
        Image8 out(img.width, img.height, 3);
        for (std::size_t i = 0; i < std::size_t(img.width) * img.height; ++i)
            for (int c = 0; c < 3; ++c) out.pixels[i * 3 + c] = std::uint8_t(std::lround(img.pixels[i * 4 + c] * 255.0f));
        write_png(path, out);
    };
    auto raw = [](const ImageF& img, const std::filesystem::path& path) {
        std::ofstream f(path, std::ios::binary);
        for (std::size_t i = 0; i < std::size_t(img.width) * img.height; ++i)
            f.write(reinterpret_cast<const char*>(&img.pixels[i * 4]), 3 * sizeof(float));
    };
    for (int k = 0; k < 2; ++k) {
        Pair p = make_pair(k);
        png(p.ref, std::filesystem::path(dir) / ("pair" + std::to_string(k) + "_ref.png"));
        png(p.test, std::filesystem::path(dir) / ("pair" + std::to_string(k) + "_test.png"));
    }
    Pair h = make_hdr_pair();
    raw(h.ref, std::filesystem::path(dir) / "hdr_ref_48x40.f32");
    raw(h.test, std::filesystem::path(dir) / "hdr_test_48x40.f32");
}

ImageF uniform(int w, int h, float r, float g, float b) {
    ImageF img(w, h);
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
        img.pixels[i * 4] = r, img.pixels[i * 4 + 1] = g, img.pixels[i * 4 + 2] = b, img.pixels[i * 4 + 3] = 1;
    }
    return img;
}

// Independent L*a*b* (CIE 1976, D65 white of the sRGB matrix) with the Hunt adjustment, of a
// display-encoded sRGB colour; for the closed-form FLIP of uniform images.
void hunt_lab(const double srgb[3], double out[3]) {
    double lin[3];
    for (int c = 0; c < 3; ++c)
        lin[c] = srgb[c] <= 0.04045 ? srgb[c] / 12.92 : std::pow((srgb[c] + 0.055) / 1.055, 2.4);
    const double m[3][3] = {{0.41238656, 0.35759149, 0.18045049},
                            {0.21263682, 0.71518298, 0.07218020},
                            {0.01933082, 0.11919717, 0.95037259}};
    double f[3];
    for (int i = 0; i < 3; ++i) {
        const double v = m[i][0] * lin[0] + m[i][1] * lin[1] + m[i][2] * lin[2];
        const double white = m[i][0] + m[i][1] + m[i][2];
        const double t = v / white;
        f[i] = t > std::pow(6.0 / 29, 3) ? std::cbrt(t) : t / (3 * std::pow(6.0 / 29, 2)) + 4.0 / 29;
    }
    const double L = 116 * f[1] - 16;
    out[0] = L, out[1] = L / 100 * 500 * (f[0] - f[1]), out[2] = L / 100 * 200 * (f[1] - f[2]);
}

double hyab(const double a[3], const double b[3]) {
    return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

double uniform_flip(const double a[3], const double b[3]) {
    const double green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    double la[3], lb[3], lg[3], lbl[3];
    hunt_lab(a, la), hunt_lab(b, lb), hunt_lab(green, lg), hunt_lab(blue, lbl);
    const double cmax = std::pow(hyab(lg, lbl), 0.7), e = std::pow(hyab(la, lb), 0.7);
    return e < 0.4 * cmax ? 0.95 / (0.4 * cmax) * e : 0.95 + (e - 0.4 * cmax) / (0.6 * cmax) * 0.05;
}

}  // namespace

TEST(Metrics, IdenticalImages) {
    dump_if_asked();
    Pair p = make_pair(0);
    EXPECT_TRUE(std::isinf(psnr_db(p.ref, p.ref)) && psnr_db(p.ref, p.ref) > 0);
    EXPECT_DOUBLE_EQ(ssim(p.ref, p.ref).ssim, 1.0);
    EXPECT_TRUE(std::isinf(mv_rms_db(p.ref, p.ref)) && mv_rms_db(p.ref, p.ref) < 0);
    for (float v : flip_ldr(p.ref, p.ref)) ASSERT_EQ(v, 0.0f);
    Pair h = make_hdr_pair();
    for (float v : flip_hdr(h.ref, h.ref, flip_exposures(h.ref))) ASSERT_EQ(v, 0.0f);
}

TEST(Metrics, PsnrClosedFormAndMask) {
    ImageF a = uniform(20, 10, 0.5f, 0.5f, 0.5f), b = uniform(20, 10, 0.5f, 0.5f, 0.5f);
    const float d = 0.1f;
    for (int x = 0; x < 10; ++x)
        for (int y = 0; y < 10; ++y) b.at(x, y)[1] += d;  // half the pixels, one channel
    // All pixels: MSE = d^2 / 6; over the left half only: d^2 / 3.
    EXPECT_NEAR(psnr_db(a, b), 10 * std::log10(6.0 / (double(d) * d)), 1e-4);
    PixelMask left(200, 0);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x) left[y * 20 + x] = 1;
    EXPECT_NEAR(psnr_db(a, b, left), 10 * std::log10(3.0 / (double(d) * d)), 1e-4);
    PixelMask none(200, 0);
    EXPECT_TRUE(std::isnan(psnr_db(a, b, none)));
    EXPECT_THROW(psnr_db(a, uniform(10, 20, 0, 0, 0)), Error);
    EXPECT_THROW(psnr_db(a, b, PixelMask(7, 1)), Error);
}

// The object mask compare.py uses: background is black or fully transparent in both images.
TEST(Metrics, BackgroundMaskIsComparePys) {
    ImageF a = uniform(4, 1, 0, 0, 0), b = uniform(4, 1, 0, 0, 0);
    a.at(1, 0)[0] = 0.5f;                       // object in a only
    b.at(2, 0)[2] = 0.2f;                       // object in b only
    a.at(3, 0)[1] = 0.7f, a.at(3, 0)[3] = 0.0f;  // colour under alpha 0: background
    PixelMask m = background_mask(a, b);
    EXPECT_EQ(m, (PixelMask{0, 1, 1, 0}));
    EXPECT_EQ(mask_count(m, 4), 2u);
    EXPECT_EQ(mask_count({}, 4), 4u);
    const float grey[3] = {0.5f, 0, 0};  // another background colour
    ImageF ga = uniform(3, 1, 0.5f, 0, 0), gb = ga;
    gb.at(2, 0)[1] = 0.1f;
    EXPECT_EQ(background_mask(ga, gb, grey), (PixelMask{0, 0, 1}));
    EXPECT_EQ(background_mask(ga, gb), (PixelMask{1, 1, 1}));

    ImageF mask = uniform(3, 1, 1, 1, 1);
    mask.at(1, 0)[0] = mask.at(1, 0)[1] = mask.at(1, 0)[2] = 0.4f;
    mask.at(2, 0)[3] = 0.25f;
    EXPECT_EQ(mask_from_image(mask), (PixelMask{1, 0, 0}));
}

TEST(Metrics, SsimClosedForms) {
    // Uniform images: no variance, so SSIM = (2 a b + C1) / (a^2 + b^2 + C1) at every pixel.
    const double a = 0.3, b = 0.6, C1 = 1e-4;
    SsimResult s = ssim(uniform(30, 20, float(a), float(a), float(a)), uniform(30, 20, float(b), float(b), float(b)));
    EXPECT_NEAR(s.ssim, (2 * a * b + C1) / (a * a + b * b + C1), 1e-6);
    EXPECT_EQ(s.pixels, std::size_t(20 * 10));  // the 11x11 window fits around (30-10) x (20-10) centres
    EXPECT_TRUE(std::isnan(ssim(uniform(10, 30, 0, 0, 0), uniform(10, 30, 0, 0, 0)).ssim));  // narrower than the window
    // Contrast reversal of a pattern with zero-mean: structure term -1.
    Pair p = make_pair(1);
    ImageF inv = p.ref;
    for (std::size_t i = 0; i < inv.pixels.size(); ++i)
        if (i % 4 != 3) inv.pixels[i] = 1.0f - inv.pixels[i];
    EXPECT_LT(ssim(p.ref, inv).ssim, 0.0);
}

// scikit-image's SSIM of the procedural pairs (see the top of this file).
TEST(Metrics, SsimMatchesScikitImage) {
    const double expected[2] = {0.5633232, 0.7603375};
    for (int k = 0; k < 2; ++k) {
        Pair p = make_pair(k);
        EXPECT_NEAR(ssim(p.test, p.ref).ssim, expected[k], 1e-6) << "pair " << k;
    }
}

TEST(Metrics, ModelViewerRmsClosedForm) {
    // Black against white: only the Y difference (255) is non-zero; colorDelta = 0.5053 * 255^2.
    ImageF black = uniform(4, 4, 0, 0, 0), white = uniform(4, 4, 1, 1, 1);
    EXPECT_NEAR(mv_rms_db(black, white), 10 * std::log10(0.5053 * 255.0 * 255.0 / 35215.0), 1e-6);
    // pixelmatch blends over white by alpha: a transparent black pixel reads white.
    ImageF clear = black;
    for (std::size_t i = 3; i < clear.pixels.size(); i += 4) clear.pixels[i] = 0;
    EXPECT_TRUE(std::isinf(mv_rms_db(clear, white)));
    // RMS of the squared distance: half the pixels black -> ratio / sqrt(2), 1.5 dB less.
    ImageF half = white;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) half.at(x, y)[0] = half.at(x, y)[1] = half.at(x, y)[2] = 0;
    EXPECT_NEAR(mv_rms_db(half, white), mv_rms_db(black, white) - 10 * std::log10(std::sqrt(2.0)), 1e-6);
}

// Uniform images have no edges or points: FLIP is the colour term alone, everywhere.
TEST(Metrics, FlipOfUniformImagesIsTheColourTerm) {
    const double cases[][6] = {
        {0, 0, 0, 1, 1, 1}, {0.5, 0.5, 0.5, 0.6, 0.5, 0.5}, {0.2, 0.4, 0.8, 0.2, 0.45, 0.7}, {0.9, 0.1, 0.1, 0.1, 0.9, 0.1},
    };
    for (const auto& c : cases) {
        ImageF a = uniform(40, 32, float(c[0]), float(c[1]), float(c[2]));
        ImageF b = uniform(40, 32, float(c[3]), float(c[4]), float(c[5]));
        // The test's colours are the float values the images hold.
        const double ca[3] = {a.pixels[0], a.pixels[1], a.pixels[2]}, cb[3] = {b.pixels[0], b.pixels[1], b.pixels[2]};
        const double expected = uniform_flip(ca, cb);
        std::vector<float> map = flip_ldr(a, b);
        float lo = 1, hi = 0;
        for (float v : map) lo = std::min(lo, v), hi = std::max(hi, v);
        EXPECT_NEAR(lo, expected, 2e-4) << c[0] << "," << c[1] << "," << c[2] << " vs " << c[3] << "," << c[4] << "," << c[5];
        EXPECT_NEAR(hi, expected, 2e-4);
    }
    // Black against white lies in the top 5 % of the range (above 0.4 cmax).
    const double k[3] = {0, 0, 0}, w[3] = {1, 1, 1};
    EXPECT_GT(uniform_flip(k, w), 0.95);
}

TEST(Metrics, FlipProperties) {
    Pair p = make_pair(0);
    std::vector<float> ab = flip_ldr(p.ref, p.test), ba = flip_ldr(p.test, p.ref);
    ASSERT_EQ(ab.size(), std::size_t(96 * 80));
    for (std::size_t i = 0; i < ab.size(); ++i) {
        ASSERT_GE(ab[i], 0.0f);
        ASSERT_LE(ab[i], 1.0f);
        ASSERT_NEAR(ab[i], ba[i], 1e-6f) << "LDR-FLIP is symmetric";
    }
    // More noise, more error.
    auto noisy = [&](int amount) {
        ImageF t = p.ref;
        for (int y = 0; y < t.height; ++y)
            for (int x = 0; x < t.width; ++x)
                for (int c = 0; c < 3; ++c)
                    t.at(x, y)[c] = std::clamp(t.at(x, y)[c] + float((noise(x, y, c) - 128) * amount) / (255.0f * 128.0f), 0.0f, 1.0f);
        return masked_mean(flip_ldr(p.ref, t));
    };
    const double n4 = noisy(4), n16 = noisy(16), n64 = noisy(64);
    EXPECT_GT(n4, 0.0);
    EXPECT_LT(n4, n16);
    EXPECT_LT(n16, n64);
    // A mask selects the mean of its pixels.
    PixelMask box(ab.size(), 0);
    double sum = 0;
    for (int y = 45; y < 70; ++y)
        for (int x = 50; x < 80; ++x) box[std::size_t(y) * 96 + x] = 1, sum += ab[std::size_t(y) * 96 + x];
    EXPECT_NEAR(masked_mean(ab, box), sum / (25 * 30), 1e-9);
    EXPECT_GT(masked_mean(ab, box), masked_mean(ab));  // the inverted block is the worst region
    EXPECT_THROW(flip_ldr(p.ref, uniform(5, 5, 0, 0, 0)), Error);
}

// The authors' reference implementation on the procedural pairs (see the top of this file).
TEST(Metrics, FlipMatchesTheAuthorsReference) {
    const double expected[2] = {0.2186964, 0.4556145};
    for (int k = 0; k < 2; ++k) {
        Pair p = make_pair(k);
        EXPECT_NEAR(masked_mean(flip_ldr(p.ref, p.test)), expected[k], 1e-5) << "pair " << k;
    }
    // At another viewing distance (the filters change size).
    Pair p = make_pair(0);
    EXPECT_NEAR(masked_mean(flip_ldr(p.ref, p.test, 30.0)), 0.2513026, 1e-5);

    Pair h = make_hdr_pair();
    FlipExposures e = flip_exposures(h.ref);
    EXPECT_NEAR(e.start, -4.560560, 1e-5);
    EXPECT_NEAR(e.stop, 1.067997, 1e-5);
    EXPECT_EQ(e.count, 6);
    EXPECT_NEAR(masked_mean(flip_hdr(h.ref, h.test, e)), 0.1419062, 1e-5);
}

TEST(Metrics, FlipExposuresOfMostlyBlackImages) {
    // More than half black: the median of the lit pixels sets the stop exposure.
    ImageF img = uniform(10, 10, 0, 0, 0);
    for (int x = 0; x < 10; ++x)
        for (int y = 0; y < 3; ++y) img.at(x, y)[0] = img.at(x, y)[1] = img.at(x, y)[2] = y == 0 ? 8.0f : 1.0f;
    FlipExposures e = flip_exposures(img);
    EXPECT_TRUE(std::isfinite(e.stop));
    EXPECT_NEAR(e.stop - e.start, 3.0, 1e-6);  // brightest 8, lit median 1: three stops
    EXPECT_EQ(e.count, 3);
    FlipExposures black = flip_exposures(uniform(4, 4, 0, 0, 0));
    EXPECT_EQ(black.count, 1);
}

TEST(Heatmap, MagmaEndsAndOrder) {
    EXPECT_EQ(magma(0.0f), (Rgb8{0, 0, 4}));
    EXPECT_EQ(magma(1.0f), (Rgb8{252, 253, 191}));
    EXPECT_EQ(magma(-1.0f), magma(0.0f));
    EXPECT_EQ(magma(std::numeric_limits<float>::quiet_NaN()), magma(0.0f));
    double last = -1;
    for (int i = 0; i <= 64; ++i) {  // magma is perceptually ordered: luminance rises
        Rgb8 c = magma(float(i) / 64);
        const double y = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        EXPECT_GT(y, last - 0.5) << i;
        last = y;
    }
}

TEST(Heatmap, MapLegendAndLabels) {
    const int w = 64, h = 32;
    std::vector<float> map(std::size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) map[std::size_t(y) * w + x] = float(x) / (w - 1);
    Image8 img = error_heatmap(map, w, h, "LDR-FLIP MEAN 0.5000");
    ASSERT_GE(img.width, 200);  // room for the labels
    ASSERT_GT(img.height, h + 30);
    for (int x = 0; x < w; x += 7) {
        const Rgb8 c = magma(map[std::size_t(5) * w + x]);
        EXPECT_EQ(img.at(x, 5)[0], c[0]);
        EXPECT_EQ(img.at(x, 5)[1], c[1]);
        EXPECT_EQ(img.at(x, 5)[2], c[2]);
    }
    // The bar: dark at its left end, bright at its right end.
    const int bar_y = h + 6 + 6;
    auto lum = [&](int x, int y) { return 0.2126 * img.at(x, y)[0] + 0.7152 * img.at(x, y)[1] + 0.0722 * img.at(x, y)[2]; };
    EXPECT_LT(lum(11, bar_y), 10);
    EXPECT_GT(lum(img.width - 12, bar_y), 200);
    // Label and caption rows carry ink (light pixels on the dark band).
    auto ink_in_rows = [&](int y0, int y1) {
        int n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < img.width; ++x) n += img.at(x, y)[0] > 200 && img.at(x, y)[1] > 200;
        return n;
    };
    const int label_y = h + 6 + 12 + 3 + 2;
    EXPECT_GT(ink_in_rows(label_y, label_y + 7), 30);
    EXPECT_GT(ink_in_rows(label_y + 12, label_y + 19), 60);
    EXPECT_THROW(error_heatmap(map, w + 1, h, ""), Error);
}

TEST(Heatmap, FontDrawsGlyphs) {
    Image8 img(12, 7, 3);
    draw_text(img, 0, 0, "1", 1, {255, 255, 255});
    // '1': the stem in column 2 on every row, the foot across columns 1..3 on the last row.
    for (int y = 0; y < 7; ++y) EXPECT_EQ(img.at(2, y)[0], 255) << y;
    EXPECT_EQ(img.at(1, 6)[0], 255);
    EXPECT_EQ(img.at(3, 6)[0], 255);
    EXPECT_EQ(img.at(0, 3)[0], 0);
    EXPECT_EQ(text_width("10", 1), 11);
    EXPECT_EQ(text_width("10", 2), 22);
    draw_text(img, 100, 100, "clipped", 3, {1, 2, 3});  // outside: no effect, no fault
}
