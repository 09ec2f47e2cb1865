#include "fresnel/core/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"

namespace fresnel {

ImageMetrics compare_images(const Image8& a, const Image8& b, bool mask_background, const std::uint8_t background[3]) {
    if (a.width != b.width || a.height != b.height)
        throw Error("", "", "images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(b.width) + "x" + std::to_string(b.height));
    const std::uint8_t black[3] = {0, 0, 0};
    const std::uint8_t* bg = background ? background : black;
    ImageMetrics m;
    double sq = 0, abs_sum = 0;
    std::vector<int> per_pixel;
    per_pixel.reserve(std::size_t(a.width) * a.height);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const std::uint8_t* pa = a.at(x, y);
            const std::uint8_t* pb = b.at(x, y);
            bool a_bg = pa[0] == bg[0] && pa[1] == bg[1] && pa[2] == bg[2];
            bool b_bg = pb[0] == bg[0] && pb[1] == bg[1] && pb[2] == bg[2];
            if (mask_background && a_bg && b_bg) continue;
            int worst = 0;
            for (int c = 0; c < 3; ++c) {
                int d = std::abs(int(pa[c]) - int(pb[c]));
                sq += double(d) * d;
                abs_sum += d;
                worst = std::max(worst, d);
            }
            per_pixel.push_back(worst);
            m.max_abs = std::max<double>(m.max_abs, worst);
        }
    m.pixels = per_pixel.size();
    if (m.pixels == 0) {
        m.psnr_db = std::numeric_limits<double>::infinity();
        return m;
    }
    double mse = sq / (3.0 * double(m.pixels));
    m.psnr_db = mse == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
    m.mad = abs_sum / (3.0 * double(m.pixels));
    std::size_t k = std::min(per_pixel.size() - 1, std::size_t(0.99 * double(per_pixel.size())));
    std::nth_element(per_pixel.begin(), per_pixel.begin() + std::ptrdiff_t(k), per_pixel.end());
    m.p99 = per_pixel[k];
    return m;
}

}  // namespace fresnel

// ---------------------------------------------------------------------------------------------
// Metrics of `fresnel compare` (see metrics.h); SSIM is in ssim.cpp, FLIP in flip.cpp.

namespace fresnel {

namespace {
void require_same_size(const ImageF& a, const ImageF& b) {
    if (a.width != b.width || a.height != b.height)
        throw Error("", "", "images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(b.width) + "x" + std::to_string(b.height));
}
bool selected(const PixelMask& mask, std::size_t i) { return mask.empty() || mask[i] != 0; }
void require_mask(const PixelMask& mask, std::size_t pixels) {
    if (!mask.empty() && mask.size() != pixels)
        throw Error("", "", "mask has " + std::to_string(mask.size()) + " pixels, the images " + std::to_string(pixels));
}
}  // namespace

ImageF to_display(const ImageF& linear) {
    ImageF out(linear.width, linear.height);
    for (std::size_t i = 0; i < linear.pixels.size(); ++i) {
        float v = linear.pixels[i];
        v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
        out.pixels[i] = i % 4 == 3 ? v : linear_to_srgb(v);
    }
    return out;
}

PixelMask background_mask(const ImageF& a, const ImageF& b, const float background[3]) {
    require_same_size(a, b);
    const float black[3] = {0, 0, 0};
    const float* bg = background ? background : black;
    auto is_background = [bg](const float* p) {
        return p[3] == 0.0f || (p[0] == bg[0] && p[1] == bg[1] && p[2] == bg[2]);
    };
    const std::size_t n = std::size_t(a.width) * a.height;
    PixelMask mask(n);
    for (std::size_t i = 0; i < n; ++i)
        mask[i] = !is_background(&a.pixels[i * 4]) || !is_background(&b.pixels[i * 4]);
    return mask;
}

PixelMask mask_from_image(const ImageF& m) {
    const std::size_t n = std::size_t(m.width) * m.height;
    PixelMask mask(n);
    for (std::size_t i = 0; i < n; ++i) {
        const float* p = &m.pixels[i * 4];
        mask[i] = std::max({p[0], p[1], p[2]}) * p[3] >= 0.5f;
    }
    return mask;
}

std::size_t mask_count(const PixelMask& mask, std::size_t pixel_count) {
    if (mask.empty()) return pixel_count;
    return std::size_t(std::count_if(mask.begin(), mask.end(), [](std::uint8_t v) { return v != 0; }));
}

double psnr_db(const ImageF& a, const ImageF& b, const PixelMask& mask) {
    require_same_size(a, b);
    const std::size_t n = std::size_t(a.width) * a.height;
    require_mask(mask, n);
    double sq = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!selected(mask, i)) continue;
        for (int c = 0; c < 3; ++c) {
            double d = double(a.pixels[i * 4 + c]) - double(b.pixels[i * 4 + c]);
            sq += d * d;
        }
        ++count;
    }
    if (count == 0) return std::numeric_limits<double>::quiet_NaN();
    if (sq == 0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(1.0 / (sq / (3.0 * double(count))));
}

double mv_rms_db(const ImageF& a, const ImageF& b, const PixelMask& mask) {
    require_same_size(a, b);
    const std::size_t n = std::size_t(a.width) * a.height;
    require_mask(mask, n);
    // pixelmatch's colour difference: YIQ of 0..255 values blended over white, weighted squared distance.
    auto yiq = [](const float* p, double out[3]) {
        double alpha = p[3], rgb[3];
        for (int c = 0; c < 3; ++c) rgb[c] = 255.0 + (255.0 * p[c] - 255.0) * alpha;
        out[0] = rgb[0] * 0.29889531 + rgb[1] * 0.58662247 + rgb[2] * 0.11448223;
        out[1] = rgb[0] * 0.59597799 - rgb[1] * 0.27417610 - rgb[2] * 0.32180189;
        out[2] = rgb[0] * 0.21147017 - rgb[1] * 0.52261711 + rgb[2] * 0.31114694;
    };
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!selected(mask, i)) continue;
        double p[3], q[3];
        yiq(&a.pixels[i * 4], p);
        yiq(&b.pixels[i * 4], q);
        double delta = 0.5053 * (p[0] - q[0]) * (p[0] - q[0]) + 0.299 * (p[1] - q[1]) * (p[1] - q[1]) +
                       0.1957 * (p[2] - q[2]) * (p[2] - q[2]);
        sum += delta * delta;
        ++count;
    }
    if (count == 0) return std::numeric_limits<double>::quiet_NaN();
    const double ratio = std::sqrt(sum / double(count)) / 35215.0;
    return ratio == 0 ? -std::numeric_limits<double>::infinity() : 10.0 * std::log10(ratio);
}

double masked_mean(const std::vector<float>& map, const PixelMask& mask) {
    require_mask(mask, map.size());
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < map.size(); ++i)
        if (selected(mask, i)) sum += map[i], ++count;
    return count ? sum / double(count) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace fresnel
