// SSIM (Wang, Bovik, Sheikh, Simoncelli, "Image Quality Assessment: From Error Visibility to
// Structural Similarity", IEEE TIP 2004) with the paper's parameters: an 11x11 circular-symmetric
// Gaussian window of sigma 1.5 normalised to sum 1, C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 1.
// Local means, variances and the covariance are Gaussian-weighted (population, not sample,
// statistics, as the authors' code). The map is computed only where the window fits inside the
// image ('valid'), per RGB channel, and the three channel means are averaged.
#include <cmath>
#include <limits>

#include "fresnel/core/error.h"
#include "fresnel/core/metrics.h"
#include "fresnel/core/parallel.h"

namespace fresnel {

SsimResult ssim(const ImageF& a, const ImageF& b, const PixelMask& mask) {
    if (a.width != b.width || a.height != b.height)
        throw Error("", "", "images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(b.width) + "x" + std::to_string(b.height));
    const int w = a.width, h = a.height;
    if (!mask.empty() && mask.size() != std::size_t(w) * h) throw Error("", "", "mask size differs from the images");
    constexpr int R = 5;  // 11 taps
    constexpr double sigma = 1.5, C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;
    double g[2 * R + 1], gsum = 0;
    for (int i = -R; i <= R; ++i) gsum += g[i + R] = std::exp(-(i * i) / (2 * sigma * sigma));
    for (double& v : g) v /= gsum;  // the 2-D window g(x) g(y) then sums to 1

    SsimResult result;
    const int vw = w - 2 * R, vh = h - 2 * R;  // valid region: centres R.. w-1-R
    if (vw <= 0 || vh <= 0) {
        result.ssim = std::numeric_limits<double>::quiet_NaN();
        return result;
    }
    // Horizontal pass over all rows, for the valid columns: 5 moments x 3 channels.
    constexpr int M = 15;
    std::vector<double> horiz(std::size_t(vw) * h * M);
    parallel_for(std::size_t(h), [&](std::size_t y) {
        for (int x = 0; x < vw; ++x) {
            double acc[M] = {};
            for (int k = 0; k <= 2 * R; ++k) {
                const float* pa = a.at(x + k, int(y));
                const float* pb = b.at(x + k, int(y));
                for (int c = 0; c < 3; ++c) {
                    double u = pa[c], v = pb[c], wk = g[k];
                    acc[c * 5 + 0] += wk * u;
                    acc[c * 5 + 1] += wk * v;
                    acc[c * 5 + 2] += wk * u * u;
                    acc[c * 5 + 3] += wk * v * v;
                    acc[c * 5 + 4] += wk * u * v;
                }
            }
            std::copy(acc, acc + M, &horiz[(y * vw + x) * M]);
        }
    });
    // Vertical pass and the SSIM of each valid centre, summed per row.
    std::vector<double> row_sum(vh, 0.0);
    std::vector<std::size_t> row_count(vh, 0);
    parallel_for(std::size_t(vh), [&](std::size_t vy) {
        for (int x = 0; x < vw; ++x) {
            const std::size_t centre = (vy + R) * std::size_t(w) + x + R;
            if (!mask.empty() && !mask[centre]) continue;
            double m[M] = {};
            for (int k = 0; k <= 2 * R; ++k) {
                const double* src = &horiz[((vy + k) * vw + x) * M];
                for (int j = 0; j < M; ++j) m[j] += g[k] * src[j];
            }
            double s = 0;
            for (int c = 0; c < 3; ++c) {
                const double mu_a = m[c * 5], mu_b = m[c * 5 + 1];
                const double var_a = m[c * 5 + 2] - mu_a * mu_a, var_b = m[c * 5 + 3] - mu_b * mu_b;
                const double cov = m[c * 5 + 4] - mu_a * mu_b;
                s += ((2 * mu_a * mu_b + C1) * (2 * cov + C2)) / ((mu_a * mu_a + mu_b * mu_b + C1) * (var_a + var_b + C2));
            }
            row_sum[vy] += s / 3.0;
            ++row_count[vy];
        }
    });
    double sum = 0;
    for (int y = 0; y < vh; ++y) sum += row_sum[y], result.pixels += row_count[y];
    result.ssim = result.pixels ? sum / double(result.pixels) : std::numeric_limits<double>::quiet_NaN();
    return result;
}

}  // namespace fresnel
