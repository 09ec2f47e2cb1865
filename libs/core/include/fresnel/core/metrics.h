#pragma once
// Image comparison metrics.
//
// compare_images(): 8-bit PSNR/MAD/p99 computed the way ../shared/tools/fidelity/compare.py does,
// over the pixels where either image differs from the background colour (the image tests use it).
//
// The rest serves `fresnel compare`: metrics on display-encoded float images (RGB in [0,1]; an
// 8-bit PNG divided by 255, a linear EXR/HDR clamped and sRGB-encoded by to_display()), each over
// every pixel or over a PixelMask:
//   psnr_db      PSNR of RGB with peak 1 (compare.py's psnr_db for 8-bit inputs)
//   ssim         mean SSIM (Wang, Bovik, Sheikh, Simoncelli 2004): Gaussian 11x11 window, sigma 1.5,
//                K1 0.01, K2 0.03, dynamic range 1, per RGB channel and averaged; the map is
//                defined where the whole window lies inside the image (as the authors' MATLAB
//                code's 'valid' filtering and scikit-image do)
//   mv_rms_db    model-viewer's render-fidelity score: colorDelta (pixelmatch's squared, weighted
//                YIQ distance of 0..255 values, colours blended over white by alpha), RMS over the
//                pixels divided by its maximum 35215, in dB (model-viewer fails a scenario above -22)
//   flip_ldr     LDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating
//                Images", HPG 2020), per-pixel error in [0,1]
//   flip_hdr     HDR-FLIP (Andersson et al., "Visualizing Errors in Rendered High Dynamic Range
//                Images", EG 2021): the maximum LDR-FLIP over exposures of linear images
#include <cstddef>
#include <cstdint>
#include <vector>

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

// ---------------------------------------------------------------------------------------------
// Metrics of `fresnel compare`. Images are ImageF holding display-encoded RGBA in [0,1]; every
// function requires equal sizes (throws fresnel::Error otherwise).

// One byte per pixel, rows top to bottom; nonzero = compared. An empty mask means every pixel.
using PixelMask = std::vector<std::uint8_t>;

// A linear float image (EXR/HDR) as display values: RGB clamped to [0,1] and sRGB-encoded,
// alpha clamped. NaN becomes 0.
ImageF to_display(const ImageF& linear);

// compare.py's object mask: pixels where either image is neither exactly `background` (RGB,
// display-encoded) nor fully transparent (alpha 0).
PixelMask background_mask(const ImageF& a, const ImageF& b, const float background[3] = nullptr);
// A mask image: a pixel is compared where max(R,G,B) * alpha >= 0.5.
PixelMask mask_from_image(const ImageF& mask);
// Pixels the mask selects, for an image of `pixel_count` pixels.
std::size_t mask_count(const PixelMask& mask, std::size_t pixel_count);

// PSNR of RGB, peak 1, over the mask: +inf when the pixels are identical, NaN when there are none.
double psnr_db(const ImageF& a, const ImageF& b, const PixelMask& mask = {});

struct SsimResult {
    double ssim = 0;          // mean SSIM over `pixels` (NaN when none)
    std::size_t pixels = 0;   // masked pixels whose whole window lies inside the image
};
SsimResult ssim(const ImageF& a, const ImageF& b, const PixelMask& mask = {});

// model-viewer's RMS in dB: -inf when identical, NaN when the mask is empty.
double mv_rms_db(const ImageF& a, const ImageF& b, const PixelMask& mask = {});

// FLIP's default observer: 0.7 m from a 0.7 m wide display 3840 pixels across (about 67 ppd).
double flip_default_pixels_per_degree();

// Per-pixel LDR-FLIP between display-encoded (sRGB) images, rows top to bottom.
std::vector<float> flip_ldr(const ImageF& reference, const ImageF& test,
                            double pixels_per_degree = flip_default_pixels_per_degree());

// HDR-FLIP between linear images (negative values and NaN count as 0). Exposures from `start`
// to `stop` stops in `count` steps; flip_exposures() picks them from the reference as the
// paper does (ACES tone curve, t = 0.85 at the brightest pixel and at the median luminance; the
// median of the non-zero luminances when more than half the pixels are black), at most 32.
struct FlipExposures {
    double start = 0, stop = 0;
    int count = 1;
};
FlipExposures flip_exposures(const ImageF& linear_reference);
std::vector<float> flip_hdr(const ImageF& linear_reference, const ImageF& linear_test, const FlipExposures& exposures,
                            double pixels_per_degree = flip_default_pixels_per_degree());

// Mean of a per-pixel map over the mask (NaN when empty).
double masked_mean(const std::vector<float>& map, const PixelMask& mask = {});

}  // namespace fresnel
