// Tests of the IBL precomputation against brute-force integration, the cube
// layout and orientation, and the KTX2 files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <random>

#include "fresnel/core/error.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/ibl/cubemap.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/ibl/ktx2.h"
#include "fresnel/ibl/precompute.h"
#include "fresnel/material/brdf.h"

using namespace fresnel;
using namespace fresnel::ibl;
namespace fs = std::filesystem;

namespace {
constexpr float kPi = 3.14159265358979f;

// A smooth test panorama: a bright warm blob above +X+Z, a cool gradient, a dim floor.
ImageF smooth_panorama(int width) {
    ImageF img(width, width / 2);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            glm::vec3 d = equirect_to_direction({(x + 0.5f) / img.width, (y + 0.5f) / img.height});
            glm::vec3 sun = glm::normalize(glm::vec3(0.6f, 0.5f, 0.6f));
            float blob = std::pow(std::max(0.0f, glm::dot(d, sun)), 8.0f);
            glm::vec3 c = glm::vec3(0.2f, 0.3f, 0.5f) * (0.5f + 0.5f * d.y) + glm::vec3(4.0f, 3.0f, 2.0f) * blob +
                          glm::vec3(0.1f) * std::max(0.0f, -d.y);
            float* p = img.at(x, y);
            p[0] = c.x, p[1] = c.y, p[2] = c.z, p[3] = 1;
        }
    return img;
}

// Brute-force integral over the sphere of f(direction), on a fine cube-texel grid.
template <class F>
glm::dvec3 integrate_sphere(F f, int n = 128) {
    glm::dvec3 sum(0.0);
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                sum += glm::dvec3(f(cube_texel_direction(face, x, y, n))) * double(cube_texel_solid_angle(x, y, n));
    return sum;
}
}  // namespace

TEST(Cubemap, SolidAnglesSumToSphere) {
    double total = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) total += cube_texel_solid_angle(x, y, 32);
    EXPECT_NEAR(total * 6, 4 * kPi, 1e-3);
}

TEST(Cubemap, FaceUvRoundTrip) {
    std::mt19937 rng(1);
    std::uniform_int_distribution<int> pick(0, 63);
    for (int i = 0; i < 1000; ++i) {
        int face = i % 6, x = pick(rng), y = pick(rng);
        glm::vec3 d = cube_texel_direction(face, x, y, 64);
        int f2;
        float s, t;
        cube_face_uv(d, f2, s, t);
        EXPECT_EQ(f2, face);
        EXPECT_NEAR(s * 64 - 0.5f, float(x), 1e-3);
        EXPECT_NEAR(t * 64 - 0.5f, float(y), 1e-3);
    }
}

TEST(Orientation, KhronosConvention) {
    // +Y top row, +Z centre column, +X u = 0.25, -X u = 0.75, -Z the seam.
    EXPECT_NEAR(direction_to_equirect({0, 1, 0}).y, 0.0f, 1e-6);
    EXPECT_NEAR(direction_to_equirect({0, 0, 1}).x, 0.5f, 1e-6);
    EXPECT_NEAR(direction_to_equirect({1, 0, 0}).x, 0.25f, 1e-6);
    EXPECT_NEAR(direction_to_equirect({-1, 0, 0}).x, 0.75f, 1e-6);
    float seam = direction_to_equirect({0, 0, -1}).x;
    EXPECT_TRUE(std::fabs(seam) < 1e-6 || std::fabs(seam - 1) < 1e-6);
    for (glm::vec3 d : {glm::vec3(0.3f, 0.4f, -0.866f), glm::vec3(-0.8f, 0.1f, 0.59f)}) {
        d = glm::normalize(d);
        glm::vec3 back = equirect_to_direction(direction_to_equirect(d));
        EXPECT_NEAR(glm::length(back - d), 0.0f, 1e-5);
    }
}

TEST(Orientation, OneColourPerAxisLandsOnTheRightFaces) {
    // Panorama coloured by the dominant axis of each pixel's direction.
    ImageF pano(256, 128);
    const glm::vec3 colours[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 256; ++x) {
            glm::vec3 d = equirect_to_direction({(x + 0.5f) / 256, (y + 0.5f) / 128});
            int face;
            float s, t;
            cube_face_uv(d, face, s, t);
            float* p = pano.at(x, y);
            p[0] = colours[face].x, p[1] = colours[face].y, p[2] = colours[face].z, p[3] = 1;
        }
    Cubemap cube = cubemap_from_equirect(pano, 32);
    for (int face = 0; face < 6; ++face) {
        const float* centre = cube.levels[0].texel(face, 16, 16);
        EXPECT_NEAR(centre[0], colours[face].x, 1e-3) << "face " << face;
        EXPECT_NEAR(centre[1], colours[face].y, 1e-3) << "face " << face;
        EXPECT_NEAR(centre[2], colours[face].z, 1e-3) << "face " << face;
    }
    // And the GL face order: face 0 is +X, 2 is +Y, 4 is +Z.
    EXPECT_GT(cube_texel_direction(0, 16, 16, 32).x, 0.99f);
    EXPECT_GT(cube_texel_direction(2, 16, 16, 32).y, 0.99f);
    EXPECT_GT(cube_texel_direction(4, 16, 16, 32).z, 0.99f);
    // Row 0 of the +Z face is its top (+Y side).
    EXPECT_GT(cube_texel_direction(4, 16, 0, 32).y, 0.6f);
}

namespace {
// A low-frequency panorama (sky gradient, broad warm lobe, dim floor): the kind of
// lighting 9 SH coefficients represent well.
ImageF broad_panorama(int width) {
    ImageF img(width, width / 2);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            glm::vec3 d = equirect_to_direction({(x + 0.5f) / img.width, (y + 0.5f) / img.height});
            glm::vec3 sun = glm::normalize(glm::vec3(0.6f, 0.5f, 0.6f));
            float lobe = std::max(0.0f, glm::dot(d, sun));
            glm::vec3 c = glm::vec3(0.3f, 0.4f, 0.6f) * (0.6f + 0.4f * d.y) + glm::vec3(2.0f, 1.5f, 1.0f) * lobe * lobe +
                          glm::vec3(0.1f) * std::max(0.0f, -d.y);
            float* p = img.at(x, y);
            p[0] = c.x, p[1] = c.y, p[2] = c.z, p[3] = 1;
        }
    return img;
}

const glm::vec3 kNormals[] = {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0.6f, 0.5f, 0.6f),
                              glm::vec3(-0.3f, 0.2f, -0.9f), glm::vec3(0.7f, -0.6f, 0.2f)};

glm::dvec3 brute_force_irradiance(const Cubemap& cube, glm::vec3 n) {
    return integrate_sphere([&](glm::vec3 d) { return cube.sample_level(d, 0) * std::max(0.0f, glm::dot(d, n)) / kPi; }, 96);
}
}  // namespace

TEST(SphericalHarmonics, IrradianceMatchesBruteForceOnLowFrequencyLight) {
    Cubemap cube = cubemap_from_equirect(broad_panorama(512), 64);
    SH9 irr = irradiance_from_radiance(project_radiance(cube));
    for (glm::vec3 n : kNormals) {
        n = glm::normalize(n);
        glm::dvec3 e = brute_force_irradiance(cube, n);
        glm::vec3 sh = irr.evaluate(n);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sh[c], e[c], 0.01 * e[c]) << "n " << n.x << "," << n.y << "," << n.z;
    }
}

TEST(Irradiance, ConvolutionMatchesBruteForceWhereShCannot) {
    // A sharper light (cos^8 lobe): SH9 is off by several percent here (why shading uses a
    // cube map); the brute-force convolution cube stays within 1 %.
    ImageF pano = smooth_panorama(512);
    Cubemap cube = cubemap_from_equirect(pano, 64);
    build_mip_chain(cube);
    Cubemap irr = irradiance_convolution(cube, 32, 64);
    SH9 sh = irradiance_from_radiance(project_radiance(cube));
    float worst_sh = 0;
    for (glm::vec3 n : kNormals) {
        n = glm::normalize(n);
        glm::dvec3 e = brute_force_irradiance(cube, n);
        // Compare at a texel centre to keep bilinear interpolation out of it.
        int face;
        float s, t;
        cube_face_uv(n, face, s, t);
        int x = std::min(31, int(s * 32)), y = std::min(31, int(t * 32));
        glm::vec3 centre = cube_texel_direction(face, x, y, 32);
        glm::dvec3 ec = brute_force_irradiance(cube, centre);
        const float* got = irr.levels[0].texel(face, x, y);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], ec[c], 0.01 * ec[c] + 1e-4);
        for (int c = 0; c < 3; ++c) worst_sh = std::max(worst_sh, float(std::fabs(sh.evaluate(n)[c] - e[c]) / e[c]));
    }
    std::printf("SH9 worst relative error on this panorama: %.1f %%\n", worst_sh * 100);
    EXPECT_GT(worst_sh, 0.01f);  // the reason the renderer does not shade with SH
}

TEST(Irradiance, FilteredSamplingIsCloseToBruteForce) {
    // The default (Khronos-compatible) filtered importance sampling blurs slightly.
    Cubemap cube = cubemap_from_equirect(broad_panorama(512), 256);
    build_mip_chain(cube);
    Cubemap irr = irradiance_filtered(cube, 16, 2048);
    for (glm::vec3 n : kNormals) {
        n = glm::normalize(n);
        glm::dvec3 e = brute_force_irradiance(cube, n);
        glm::vec3 got = irr.sample_level(n, 0);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], e[c], 0.05 * e[c] + 1e-3);
    }
}

namespace {
}  // namespace

TEST(BrdfLut, MatchesBruteForceIntegration) {
    ImageF lut = compute_brdf_lut(32, 1024);
    // Brute force: integrate f cos over the hemisphere with a fine quadrature, F0 = 0 and F0 = 1.
    // Roughness below ~0.05 is checked analytically below (float quadrature cannot resolve it).
    for (int j : {2, 8, 16, 31})
        for (int i : {0, 4, 16, 31}) {
            float n_dot_v = brdf_lut_n_dot_v(i, 32), roughness = (j + 0.5f) / 32;
            brdf::Surface s1{glm::vec3(1.0f), 1.0f, roughness, 0.04f};  // metal, base 1: F = 1 -> A + B
            brdf::Surface s0{glm::vec3(0.0f), 1.0f, roughness, 0.04f};  // metal, base 0: F = Fc -> B
            float e = brdf::directional_albedo(s1, n_dot_v, 400).x;
            float b = brdf::directional_albedo(s0, n_dot_v, 400).x;
            const float* p = lut.at(i, j);
            EXPECT_NEAR(p[0] + p[1], e, 2e-3) << "n.v " << n_dot_v << " roughness " << roughness;
            EXPECT_NEAR(p[1], b, 2e-3) << "n.v " << n_dot_v << " roughness " << roughness;
            EXPECT_NEAR(p[2], p[0] + p[1], 1e-6);
        }
    // A near-mirror reflects everything: A + B = 1 for any n.v off grazing...
    for (int i : {1, 10, 31}) EXPECT_NEAR(lut.at(i, 0)[0] + lut.at(i, 0)[1], 1.0f, 2e-3);
    // ...and column 0 holds the grazing limit, where masking takes a visible share even of
    // a near-mirror (the clamped n.v of back-facing shading normals reads it).
    EXPECT_FLOAT_EQ(brdf_lut_n_dot_v(0, 32), kBrdfLutGrazingNdotV);
    EXPECT_FLOAT_EQ(brdf_lut_n_dot_v(3, 32), 3.5f / 32);
    float grazing = lut.at(0, 0)[0] + lut.at(0, 0)[1];
    EXPECT_LT(grazing, 0.98f);
    EXPECT_GT(grazing, 0.5f);
}

TEST(Prefilter, TexelMatchesBruteForceGgxConvolution) {
    ImageF pano = smooth_panorama(512);
    Cubemap source = cubemap_from_equirect(pano, 64);
    build_mip_chain(source);
    // lod_bias 0: the filtered-importance-sampling estimator itself (the default bias adds
    // the Khronos Sample Viewer's extra blur on purpose).
    PrefilterOptions o{64, 5, 1024, 0, 0.0f};
    o.half_resolution = false;  // the estimator itself, each texel filtered
    Cubemap pf = prefilter_ggx(source, o);
    for (int level : {1, 2, 4}) {
        float roughness = level / 4.0f, alpha = roughness * roughness;
        int size = pf.levels[std::size_t(level)].size;
        for (auto [face, x, y] : {std::tuple{0, size / 2, size / 2}, std::tuple{4, 1, size - 2}, std::tuple{2, size / 3, size / 2}}) {
            glm::vec3 n = cube_texel_direction(face, x, y, size);
            // Reference: integral of L(l) D(h) (n.l) over l with n = v = r, normalised (the same estimator's expectation).
            glm::dvec3 num(0.0);
            double den = 0;
            int grid = 128;
            for (int f = 0; f < 6; ++f)
                for (int yy = 0; yy < grid; ++yy)
                    for (int xx = 0; xx < grid; ++xx) {
                        glm::vec3 l = cube_texel_direction(f, xx, yy, grid);
                        float nl = glm::dot(n, l);
                        if (nl <= 0) continue;
                        glm::vec3 h = glm::normalize(n + l);
                        // Samples are drawn with pdf(l) = D(h)/4 and weighted by n.l.
                        double w = brdf::d_ggx(glm::dot(n, h), alpha) * nl * cube_texel_solid_angle(xx, yy, grid);
                        num += glm::dvec3(source.sample_level(l, 0)) * w;
                        den += w;
                    }
            glm::dvec3 ref = num / den;
            const float* got = pf.levels[std::size_t(level)].texel(face, x, y);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], ref[c], 0.03 * ref[c] + 2e-3) << "level " << level << " face " << face;
        }
    }
}

TEST(Prefilter, VectorizedLoopMatchesTheScalarReference) {
    // A sharp environment (one bright patch), so every face, mip level and lane path
    // (including the padding of the last batch of each level) shows up in the sums.
    ImageF pano = smooth_panorama(256);
    for (int y = 40; y < 60; ++y)
        for (int x = 100; x < 130; ++x) pano.at(x, y)[0] = pano.at(x, y)[1] = 50.0f;
    Cubemap source = cubemap_from_equirect(pano, 32);
    build_mip_chain(source);
    PrefilterOptions o{32, 5, 301, 1};  // 301 samples: batches that do not divide evenly
    Cubemap fast = prefilter_ggx(source, o);
    o.vectorized = false;
    Cubemap reference = prefilter_ggx(source, o);
    double worst = 0;
    for (std::size_t l = 0; l < fast.levels.size(); ++l)
        for (int f = 0; f < 6; ++f)
            for (std::size_t i = 0; i < fast.levels[l].faces[std::size_t(f)].size(); ++i) {
                float a = fast.levels[l].faces[std::size_t(f)][i], b = reference.levels[l].faces[std::size_t(f)][i];
                worst = std::max(worst, double(std::fabs(a - b)) / std::max(1e-3, double(std::fabs(b))));
            }
    EXPECT_LT(worst, 1e-4) << "largest relative difference between the two loops";
}

// The blur of the specular filter is set by kFilterKernelSamples, not by the sample count
// (before, each count had its own blur), and filtering levels at half size, then magnifying
// them, keeps that kernel about as well as filtering every texel.
TEST(Prefilter, SampleCountsComputeOneKernel) {
    ImageF pano = smooth_panorama(512);
    for (int y = 70; y < 80; ++y)
        for (int x = 300; x < 316; ++x) pano.at(x, y)[0] = pano.at(x, y)[1] = pano.at(x, y)[2] = 40.0f;  // a small bright light
    Cubemap source = cubemap_from_equirect(pano, 128);
    build_mip_chain(source);
    auto rms_relative = [](const Cubemap& a, const Cubemap& b, int level) {
        double se = 0, ss = 0;
        for (int f = 0; f < 6; ++f)
            for (std::size_t i = 0; i < a.levels[std::size_t(level)].faces[std::size_t(f)].size(); ++i) {
                double x = a.levels[std::size_t(level)].faces[std::size_t(f)][i], y = b.levels[std::size_t(level)].faces[std::size_t(f)][i];
                se += (x - y) * (x - y), ss += y * y;
            }
        return std::sqrt(se / ss);
    };
    PrefilterOptions converged{128, 5, 8192, 0};
    converged.lod_samples = kFilterKernelSamples;
    converged.half_resolution = false;
    const Cubemap reference = prefilter_ggx(source, converged);
    const Cubemap by_default = prefilter_ggx(source, PrefilterOptions{128, 5, 1024, 0});
    PrefilterOptions full_1024{128, 5, 1024, 0};
    full_1024.half_resolution = false;
    const Cubemap before = prefilter_ggx(source, full_1024);  // the bake's filter before levels were filtered at half size
    PrefilterOptions own_blur{128, 5, 256, 0};
    own_blur.lod_samples = 256;
    const Cubemap blurrier = prefilter_ggx(source, own_blur);
    for (int level = 1; level < 5; ++level) {
        double d = rms_relative(by_default, reference, level), b = rms_relative(before, reference, level);
        double other_kernel = rms_relative(blurrier, reference, level);
        // Measured when written: the default (half size) 0.64, 0.41, 0.53, 0.78 % from the converged
        // kernel; at full size 0.21, 0.47, 0.65, 0.78 %; 256 samples with their own blur 2.0-8.7 %.
        EXPECT_LT(d, 0.012) << "level " << level;
        EXPECT_LT(d, 1.5 * b + 0.004) << "level " << level << ": the default against 1024 samples at full size";
        EXPECT_GT(other_kernel, 2.5 * d) << "level " << level << ": 256 samples with their own blur are another kernel";
    }
}

TEST(Prefilter, NoSeamsOnASmoothEnvironment) {
    ImageF pano = smooth_panorama(512);
    Cubemap source = cubemap_from_equirect(pano, 64);
    build_mip_chain(source);
    Cubemap pf = prefilter_ggx(source, PrefilterOptions{64, 5, 256, 0});
    // Adjacent texels across each face edge differ about as much as neighbours inside a face.
    for (int level = 0; level < 5; ++level) {
        const CubeLevel& lv = pf.levels[std::size_t(level)];
        float worst_edge = 0, worst_inside = 0;
        for (int face = 0; face < 6; ++face)
            for (int i = 0; i < lv.size; ++i) {
                glm::vec3 d = cube_texel_direction(face, lv.size - 1, i, lv.size);
                glm::vec3 step = cube_texel_direction(face, lv.size - 1, i, lv.size) - cube_texel_direction(face, std::max(0, lv.size - 2), i, lv.size);
                glm::vec3 across = glm::normalize(d + step);
                glm::vec3 a = pf.sample_level(d, level), b = pf.sample_level(across, level);
                glm::vec3 inside = pf.sample_level(d - step, level);
                worst_edge = std::max(worst_edge, glm::length(a - b));
                worst_inside = std::max(worst_inside, glm::length(a - inside));
            }
        EXPECT_LE(worst_edge, 3.0f * worst_inside + 2e-3f) << "level " << level;
    }
}

TEST(Ktx2, CubeRoundTripAndHeader) {
    Cubemap c = make_cubemap(8, 4);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 8.0f);
    for (auto& lv : c.levels)
        for (auto& f : lv.faces)
            for (auto& v : f) v = u(rng);
    fs::path dir = fs::temp_directory_path() / "fresnel_ktx2_test";
    fs::create_directories(dir);
    write_ktx2_cube(dir / "c.ktx2", c);
    Cubemap back = read_ktx2_cube(dir / "c.ktx2");
    ASSERT_EQ(back.levels.size(), 4u);
    for (std::size_t l = 0; l < 4; ++l)
        for (int f = 0; f < 6; ++f)
            for (std::size_t i = 0; i < c.levels[l].faces[std::size_t(f)].size(); ++i)
                ASSERT_NEAR(back.levels[l].faces[std::size_t(f)][i], c.levels[l].faces[std::size_t(f)][i],
                            c.levels[l].faces[std::size_t(f)][i] * 1e-3f);
    // A truncated file is an error naming the file, not a crash.
    {
        std::ifstream in(dir / "c.ktx2", std::ios::binary);
        std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        for (std::size_t n : {std::size_t(0), std::size_t(11), std::size_t(79), bytes.size() / 2, bytes.size() - 1}) {
            std::ofstream out(dir / "t.ktx2", std::ios::binary);
            out.write(bytes.data(), std::streamsize(n));
            out.close();
            EXPECT_THROW(read_ktx2_cube(dir / "t.ktx2"), Error) << n;
        }
    }
    fs::remove_all(dir);
}

TEST(Ktx2, ReadByIndependentReader) {
    // The npm package ktx-parse (Khronos-compatible reader) must accept our files. Skips
    // when node or the package is unavailable (it is installed by scripts/install-test-tools.sh).
    const char* tools = std::getenv("FRESNEL_NODE_TOOLS");
    fs::path tool_dir = tools ? fs::path(tools) : fs::path(FRESNEL_NODE_TOOLS_DIR);
    if (!fs::exists(tool_dir / "node_modules" / "ktx-parse")) GTEST_SKIP() << "ktx-parse not installed in " << tool_dir;
    fs::path dir = fs::temp_directory_path() / "fresnel_ktx2_parse";
    fs::create_directories(dir);
    Cubemap c = make_cubemap(16, 5);
    write_ktx2_cube(dir / "cube.ktx2", c);
    ImageF img(8, 4);
    write_ktx2_2d(dir / "lut.ktx2", img);
    std::string cmd = "node " + (fs::path(FRESNEL_SOURCE_DIR) / "tests" / "ktx" / "check_ktx2.mjs").string() + " " +
                      tool_dir.string() + " " + (dir / "cube.ktx2").string() + " 16 6 5 " + (dir / "lut.ktx2").string() +
                      " 8 1 1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    fs::remove_all(dir);
}

TEST(Environment, ParseArguments) {
    EXPECT_EQ(parse_environment("studio").kind, EnvironmentSource::Kind::Studio);
    auto c = parse_environment("color:1,0.5,0.25");
    EXPECT_EQ(c.kind, EnvironmentSource::Kind::Uniform);
    EXPECT_FLOAT_EQ(c.color.y, 0.5f);
    EXPECT_THROW(parse_environment("color:1,2"), Error);
    EXPECT_THROW(parse_environment("color:a,b,c"), Error);
    EXPECT_EQ(parse_environment("x.hdr").kind, EnvironmentSource::Kind::File);
}

TEST(Environment, UniformBakeIsFlat) {
    BakeOptions o;
    o.size = 16;
    o.levels = 3;
    o.samples = 64;
    o.lut_size = 8;
    o.lut_samples = 64;
    BakedIbl b = bake(make_uniform_panorama(glm::vec3(1.0f, 0.5f, 0.25f)), o);
    for (const auto& lv : b.specular.levels)
        for (const auto& f : lv.faces)
            for (std::size_t i = 0; i < f.size(); i += 4) {
                ASSERT_NEAR(f[i], 1.0f, 1e-4);
                ASSERT_NEAR(f[i + 1], 0.5f, 1e-4);
            }
    glm::vec3 e = b.irradiance.evaluate({0.3f, 0.9f, 0.3f});
    EXPECT_NEAR(e.x, 1.0f, 1e-3);  // a white Lambertian surface in a uniform environment reflects it
    EXPECT_NEAR(e.z, 0.25f, 1e-3);
}

TEST(Bake, ContentHashIdentifiesTheBakedData) {
    BakeOptions o;
    o.size = 16;
    o.levels = 3;
    o.samples = 16;
    o.lut_size = 8;
    o.lut_samples = 16;
    o.use_lut_cache = false;
    BakedIbl a = bake(make_uniform_panorama(glm::vec3(1.0f, 0.5f, 0.25f)), o);
    BakedIbl same = bake(make_uniform_panorama(glm::vec3(1.0f, 0.5f, 0.25f)), o);
    BakedIbl other = bake(make_uniform_panorama(glm::vec3(1.0f, 0.5f, 0.5f)), o);
    EXPECT_NE(a.content_hash, 0u);
    EXPECT_EQ(a.content_hash, same.content_hash);
    EXPECT_NE(a.content_hash, other.content_hash);
    EXPECT_EQ(a.content_hash, baked_content_hash(a));
    // One texel changed anywhere changes it.
    BakedIbl edited = a;
    edited.specular.levels.back().faces[5][0] += 1e-3f;
    EXPECT_NE(baked_content_hash(edited), a.content_hash);
    // Through the bake folder (half floats): loading sets the hash of what was loaded, the
    // same every time.
    auto dir = std::filesystem::temp_directory_path() / "fresnel-ibl-hash-test";
    std::filesystem::remove_all(dir);
    save_baked(a, dir, o, false);
    BakedIbl loaded = load_baked(dir), again = load_baked(dir);
    EXPECT_NE(loaded.content_hash, 0u);
    EXPECT_EQ(loaded.content_hash, baked_content_hash(loaded));
    EXPECT_EQ(loaded.content_hash, again.content_hash);
    // The Charlie table comes back from charlie_lut.ktx2 (half floats); a folder without it
    // (written before it was stored) gets it computed, the same table.
    ASSERT_TRUE(std::filesystem::exists(dir / "charlie_lut.ktx2"));
    ASSERT_EQ(loaded.charlie_lut.pixels.size(), a.charlie_lut.pixels.size());
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.charlie_lut.pixels.size(); ++i)
        worst = std::max(worst, std::abs(loaded.charlie_lut.pixels[i] - a.charlie_lut.pixels[i]) /
                                    std::max(1e-3f, std::abs(a.charlie_lut.pixels[i])));
    EXPECT_LT(worst, 2e-3f);  // half precision
    std::filesystem::remove(dir / "charlie_lut.ktx2");
    BakedIbl computed = load_baked(dir);
    EXPECT_EQ(computed.charlie_lut.pixels, a.charlie_lut.pixels);
    std::filesystem::remove_all(dir);
}

// save_baked writes the folder whole or not at all: an earlier bake is replaced as a set (no
// file of it stays), a folder holding other files is refused and left as it was, a failure
// names the destination, and no temporary folder is left beside it.
TEST(Bake, SaveBakedIsWholeOrAbsent) {
    namespace fs = std::filesystem;
    BakeOptions o;
    o.size = 8, o.levels = 2, o.samples = 8, o.lut_size = 8, o.lut_samples = 8, o.irradiance_size = 4;
    o.use_lut_cache = false;
    const BakedIbl a = bake(make_uniform_panorama(glm::vec3(1.0f)), o);
    const fs::path root = fs::temp_directory_path() / "fresnel-save-baked-test";
    fs::remove_all(root);
    fs::create_directories(root / "theirs");
    { std::ofstream(root / "theirs" / "notes.txt") << "mine"; }
    save_baked(a, root / "bake", o, false);
    { std::ofstream(root / "bake" / "stale.ktx2") << "old"; }
    save_baked(a, root / "bake", o, false);  // replaces the earlier bake as a whole
    EXPECT_TRUE(is_baked_dir(root / "bake"));
    EXPECT_FALSE(fs::exists(root / "bake" / "stale.ktx2"));
    try {
        save_baked(a, root / "theirs", o, false);
        ADD_FAILURE() << "a folder of other files was replaced";
    } catch (const fresnel::Error& e) {
        EXPECT_EQ(e.file(), (root / "theirs").string());
    }
    EXPECT_TRUE(fs::exists(root / "theirs" / "notes.txt"));
    EXPECT_FALSE(fs::exists(root / "theirs" / "manifest.json"));
    { std::ofstream(root / "file") << "x"; }
    try {
        save_baked(a, root / "file" / "bake", o, false);  // under a file: cannot be created
        ADD_FAILURE() << "wrote under a file";
    } catch (const fresnel::Error& e) {
        EXPECT_EQ(e.file().find(".partial"), std::string::npos) << e.file();
        EXPECT_EQ(e.file().rfind((root / "file" / "bake").string(), 0), 0u) << e.file();
    }
    int left = 0;
    for (const auto& entry : fs::directory_iterator(root)) left += entry.path().filename().string().find(".partial") != std::string::npos;
    EXPECT_EQ(left, 0);
    fs::remove_all(root);
}

// KHR_materials_sheen's image-based light. The Charlie table against figures from an
// independent NumPy transcription of the Khronos viewer's estimator (512 Hammersley samples).
TEST(Sheen, CharlieLutMatchesTheViewersEstimator) {
    ImageF lut = compute_charlie_lut(64, 512);
    auto at = [&](float nv, float r) {
        return lut.at(std::min(int(nv * 64.0f), 63), std::min(int(r * 64.0f), 63))[0];
    };
    EXPECT_NEAR(at(0.5f, 0.5f), 0.320f, 0.015f);
    EXPECT_NEAR(at(0.2f, 0.3f), 0.697f, 0.04f);
    EXPECT_NEAR(at(0.99f, 0.99f), 0.162f, 0.01f);
    EXPECT_NEAR(at(0.8f, 0.8f), 0.211f, 0.01f);
}

// The Charlie cube of a uniform sky: black at level 0 (no sample above the horizon, as in the
// viewer), the sky itself elsewhere; and the bake carries it (uniform or not).
TEST(Sheen, CharlieCubeOfAUniformSky) {
    Cubemap sky = make_cubemap(16, 1);
    for (auto& f : sky.levels[0].faces)
        for (std::size_t i = 0; i < f.size(); i += 4) f[i] = 0.5f, f[i + 1] = 1.0f, f[i + 2] = 2.0f, f[i + 3] = 1.0f;
    build_mip_chain(sky);
    Cubemap c = prefilter_charlie(sky, 8, 5, 64);
    ASSERT_EQ(c.levels.size(), 5u);
    EXPECT_EQ(c.levels[0].texel(2, 3, 3)[1], 0.0f);
    for (int l = 1; l < 5; ++l)
        for (int f = 0; f < 6; ++f) {
            const float* t = c.levels[std::size_t(l)].texel(f, 0, c.levels[std::size_t(l)].size - 1);
            EXPECT_NEAR(t[0], 0.5f, 1e-4f);
            EXPECT_NEAR(t[2], 2.0f, 1e-4f);
        }
}
