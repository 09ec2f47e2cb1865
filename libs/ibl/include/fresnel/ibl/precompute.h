#pragma once
// Image-based lighting precomputation on the CPU (multithreaded):
//  - specular: GGX-prefiltered cube map, level k at perceptual roughness k/(levels-1),
//    level 0 = the mirror image, by importance sampling with filtered importance
//    sampling (Krivanek & Colbert 2008: each sample reads the source mip whose texel
//    solid angle matches the sample's share of the lobe);
//  - diffuse: irradiance as a small cube map (what we shade with), by filtered importance
//    sampling as the Khronos Sample Viewer does (the bake's default) or by brute-force
//    cosine convolution, and as 9 spherical-harmonic coefficients (Ramamoorthi & Hanrahan
//    2001) for clients that want them;
//  - the split-sum BRDF table (Karis 2013) for the same GGX / height-correlated Smith
//    model as direct lighting; R = scale A, G = bias B of F0; A + B is the directional
//    albedo E used for multiple-scattering compensation (Fdez-Aguera 2019); A is the
//    directional albedo of the KHR_materials_sheen lobe.
#include <array>
#include <functional>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/core/image.h"
#include "fresnel/ibl/cubemap.h"

namespace fresnel::ibl {

using Progress = std::function<void(double fraction)>;

struct SH9 {
    std::array<glm::vec3, 9> c{};
    glm::vec3 evaluate(glm::vec3 n) const;  // sum c_i Y_i(n)
};

// SH projection of the radiance of a cube map, weighted by texel solid angle. Reads the
// first mip level no larger than `max_size` per face (level 0 without a chain): bands
// 0-2 are so smooth that a 64^2 box-filtered level gives the same coefficients to ~1e-4,
// at 1/16 of the cost of a 256^2 level.
SH9 project_radiance(const Cubemap& cube, int max_size = 64);
// Cosine-convolved and divided by pi: evaluate(n) = irradiance(n) / pi, i.e. the
// outgoing radiance of a white Lambertian surface with normal n.
SH9 irradiance_from_radiance(const SH9& radiance);

// Irradiance / pi as a cube map of `size`, by brute-force cosine convolution of the
// source mip whose faces are `source_size` (every source texel, weighted by its solid
// angle). Exact up to the source resolution, unlike 9 SH coefficients, whose
// truncation error reaches several percent on environments with a small bright source.
Cubemap irradiance_convolution(const Cubemap& source_with_mips, int size = 32, int source_size = 32,
                               unsigned threads = 0);

// Irradiance / pi as a cube map of `size` by cosine-weighted importance sampling of the
// source's mip chain with filtered importance sampling (the Khronos Sample Viewer's
// method: `samples` Hammersley directions, mip from the sample's solid angle + lod_bias).
// Blurrier than the exact convolution near small bright sources; matches that viewer.
Cubemap irradiance_filtered(const Cubemap& source_with_mips, int size = 32, int samples = 2048,
                            float lod_bias = 1.8257f, unsigned threads = 0);

// The sample count whose filtered-importance-sampling mip levels define the specular filter's
// blur: the Khronos Sample Viewer's 1024, whatever number of samples computes it (see
// PrefilterOptions::lod_samples).
inline constexpr int kFilterKernelSamples = 1024;

struct PrefilterOptions {
    int size = 256;        // level 0 face size
    int levels = 5;        // down to size >> (levels-1)
    int samples = 1024;    // GGX samples per texel (levels >= 1)
    unsigned threads = 0;  // 0 = all cores
    // Added to the filtered-importance-sampling mip level log2(sqrt(sample solid angle /
    // texel solid angle)). Krivanek & Colbert suggest 1; the default, 0.5 log2(4 pi) = 1.83,
    // is what the Khronos Sample Viewer's filter effectively uses (its ratio omits 4 pi),
    // so that the same panorama gives the same blur.
    float lod_bias = 1.8257f;
    // The sample count the mip level of each sample is computed for. The filter's kernel is
    // the lobe blurred by the mip each sample reads, and that mip depends on this count, not
    // on `samples`: 768 or 4096 samples compute the same kernel, coarser or finer. 0 =
    // min(kFilterKernelSamples, 4 * samples): below 256 samples each would read a texel
    // smaller than its share of the lobe (aliasing), so such cheap bakes blur more.
    int lod_samples = 0;
    // Levels >= 1 are filtered at half their face size (not below 8, nor above their own size)
    // and magnified to it bicubically (Catmull-Rom), seamless across faces: a quarter of the
    // work. Each of those levels is a blur several of its texels wide, so the magnification
    // keeps it as close to the filter's converged kernel as filtering every texel (studio_small_03,
    // levels 1-4: 0.73, 2.91, 3.84, 3.25 % RMS against 0.72, 3.12, 3.82, 3.58 %; docs/bake.md).
    bool half_resolution = true;
    // true: the loop that filters eight samples at a time (SIMD); false: the scalar
    // reference loop. Same sum up to float rounding; the switch exists for tests and
    // benchmarks.
    bool vectorized = true;
};

// `source` must hold a full mip chain (build_mip_chain) at the output's level-0 size or larger.
Cubemap prefilter_ggx(const Cubemap& source, const PrefilterOptions& options, const Progress& progress = {});

// Split-sum table, `size` x `size`: x = n.v, y = perceptual roughness, at texel centres,
// except that column 0 holds the grazing limit n.v = kBrdfLutGrazingNdotV. Why: a normal
// map can turn the shading normal away from the viewer; n.v is then clamped to 0 and the
// lookup reads column 0. At the first texel centre of a 128-wide table (n.v = 0.004) a
// smooth lobe is still a perfect mirror (A + B = 1, so F = 1 and no diffuse), which paints
// such texels black, while at n.v -> 0 masking takes over and E falls towards 0. The value
// 1/2048 is the first texel centre of the Khronos Sample Viewer's 1024-wide table, so the
// same normal-mapped model shades the same (NormalTangentTest's bowls, 29.9 -> 31.6 dB).
// The shader reads the table with plain bilinear filtering at u = n.v.
inline constexpr float kBrdfLutGrazingNdotV = 0.5f / 1024.0f;
// A holds the directional albedo E of the white KHR_materials_sheen lobe at (n.v, sheen
// roughness), brdf::sheen_albedo_integral with this many cosine samples per axis (the
// sheen's albedo scaling; brdf::SheenAlbedoTable is the same on the CPU).
inline constexpr int kSheenAlbedoSamplesPerAxis = 32;
ImageF compute_brdf_lut(int size = 128, int samples = 1024, unsigned threads = 0);
// The table read as the shader reads it (ibl.glsl's brdf_lut: bilinear, clamped to its edges,
// at u = n.v, v = roughness): A, B, E = A + B, sheen albedo.
glm::vec4 sample_brdf_lut(const ImageF& lut, float n_dot_v, float roughness);

// KHR_materials_sheen's image-based light, as the Khronos Sample Viewer bakes it (its
// ibl_filtering.frag, cCharlie): level k of `levels` filtered at sheen roughness k/(levels-1)
// with `samples` Charlie half vectors h (sin theta = u^(a/(2a+1)), a = r^2) reflecting the
// normal, weighted by n.l and read from the source mip whose level the viewer computes
// from its sample density D/4 (the coarsest where that is 0). Its level 0 is black and the
// others are wide blurs, so a small cube holds it. The shader reads it at lod = r (levels - 1).
Cubemap prefilter_charlie(const Cubemap& source_with_mips, int size = 32, int levels = 5, int samples = 64,
                          unsigned threads = 0);
// The viewer's Charlie table for that light (its LUT(), cCharlie, in R): at (n.v, roughness)
// texel centres, 8 pi / N * sum over Charlie half vectors of V_Ashikhmin D n.l v.h (its
// estimator as written, with D's exponent 1/r). The sheen's image-based light is the cube's
// radiance * sheen colour * this.
inline constexpr int kCharlieLutSize = 64;
ImageF compute_charlie_lut(int size = kCharlieLutSize, int samples = 256, unsigned threads = 0);

// Writes the A channel (the sheen albedo) of a table made before it held one.
void fill_sheen_albedo(ImageF& lut, unsigned threads = 0);

// The n.v that column `column` of a `size`-wide table holds (see above).
float brdf_lut_n_dot_v(int column, int size);

// The same integrals for one (n.v, roughness), by importance sampling with `samples` samples.
glm::vec2 integrate_split_sum(float n_dot_v, float roughness, int samples);

}  // namespace fresnel::ibl
