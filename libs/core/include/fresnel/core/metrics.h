#pragma once
// Image comparison metrics, computed the way ../shared/tools/fidelity/compare.py does:
// over the pixels where either image differs from the background colour.
#include "fresnel/core/image.h"

namespace fresnel {

struct ImageMetrics {
    double psnr_db = 0;      // PSNR of 8-bit RGB over the compared pixels (inf when identical)
    double mad = 0;          // mean absolute difference, 8-bit steps
    double max_abs = 0;      // largest channel difference, 8-bit steps
    double p99 = 0;          // 99th percentile of per-pixel max channel difference
    std::size_t pixels = 0;  // pixels compared
};

// Compares RGB of two same-sized 8-bit images. When `mask_background` is set,
// only pixels where either image is not exactly `background` count.
ImageMetrics compare_images(const Image8& a, const Image8& b, bool mask_background = true,
                            const std::uint8_t background[3] = nullptr);

}  // namespace fresnel
