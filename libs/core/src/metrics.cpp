#include "fresnel/core/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
