// Image-based-light precomputation (fresnel/ibl/precompute.h). Long (~600 lines) because the
// specular prefilter, the irradiance (SH and cube), the BRDF table and their parallel, vectorised
// loops share one set of cube-face and sampling helpers that no other file needs.
#include "fresnel/ibl/precompute.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "fresnel/core/parallel.h"
#include "fresnel/material/brdf.h"
#include "fresnel/material/sampling.h"

namespace fresnel::ibl {

namespace {
constexpr float kPi = 3.14159265358979323846f;

void sh_basis(glm::vec3 n, float y[9]) {
    y[0] = 0.282095f;
    y[1] = 0.488603f * n.y;
    y[2] = 0.488603f * n.z;
    y[3] = 0.488603f * n.x;
    y[4] = 1.092548f * n.x * n.y;
    y[5] = 1.092548f * n.y * n.z;
    y[6] = 0.315392f * (3.0f * n.z * n.z - 1.0f);
    y[7] = 1.092548f * n.x * n.z;
    y[8] = 0.546274f * (n.x * n.x - n.y * n.y);
}
}  // namespace

glm::vec3 SH9::evaluate(glm::vec3 n) const {
    float y[9];
    sh_basis(n, y);
    glm::vec3 r(0.0f);
    for (int i = 0; i < 9; ++i) r += c[std::size_t(i)] * y[i];
    return r;
}

SH9 project_radiance(const Cubemap& cube, int max_size) {
    std::size_t level = 0;
    while (level + 1 < cube.levels.size() && cube.levels[level].size > max_size) ++level;
    const CubeLevel& lv = cube.levels[level];
    std::array<glm::dvec3, 9> acc{};
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < lv.size; ++y)
            for (int x = 0; x < lv.size; ++x) {
                glm::vec3 d = cube_texel_direction(f, x, y, lv.size);
                double w = cube_texel_solid_angle(x, y, lv.size);
                const float* t = lv.texel(f, x, y);
                float b[9];
                sh_basis(d, b);
                for (int i = 0; i < 9; ++i) acc[std::size_t(i)] += glm::dvec3(t[0], t[1], t[2]) * (w * b[i]);
            }
    SH9 sh;
    for (int i = 0; i < 9; ++i) sh.c[std::size_t(i)] = glm::vec3(acc[std::size_t(i)]);
    return sh;
}

SH9 irradiance_from_radiance(const SH9& radiance) {
    // Cosine-lobe convolution weights per band (pi, 2pi/3, pi/4), then / pi.
    const float band[9] = {1.0f, 2.0f / 3.0f, 2.0f / 3.0f, 2.0f / 3.0f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f};
    SH9 out;
    for (int i = 0; i < 9; ++i) out.c[std::size_t(i)] = radiance.c[std::size_t(i)] * band[i];
    return out;
}

Cubemap irradiance_convolution(const Cubemap& source, int size, int source_size, unsigned threads) {
    std::size_t level = 0;
    while (level + 1 < source.levels.size() && source.levels[level].size > source_size) ++level;
    const CubeLevel& src = source.levels[level];
    // Flatten the source: direction * solid angle and radiance, one entry per texel.
    std::vector<glm::vec4> dirs;  // xyz = direction, w = solid angle
    std::vector<glm::vec3> radiance;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < src.size; ++y)
            for (int x = 0; x < src.size; ++x) {
                dirs.emplace_back(cube_texel_direction(f, x, y, src.size), cube_texel_solid_angle(x, y, src.size));
                const float* t = src.texel(f, x, y);
                radiance.emplace_back(t[0], t[1], t[2]);
            }
    Cubemap out = make_cubemap(size, 1);
    parallel_for(
        std::size_t(6 * size),
        [&](std::size_t row) {
            int f = int(row / std::size_t(size)), y = int(row % std::size_t(size));
            for (int x = 0; x < size; ++x) {
                glm::vec3 n = cube_texel_direction(f, x, y, size);
                float r = 0, g = 0, b = 0;
                for (std::size_t i = 0; i < dirs.size(); ++i) {
                    float c = n.x * dirs[i].x + n.y * dirs[i].y + n.z * dirs[i].z;
                    float w = c > 0.0f ? c * dirs[i].w : 0.0f;
                    r += radiance[i].x * w;
                    g += radiance[i].y * w;
                    b += radiance[i].z * w;
                }
                float* t = out.levels[0].texel(f, x, y);
                t[0] = r / kPi, t[1] = g / kPi, t[2] = b / kPi, t[3] = 1.0f;
            }
        },
        threads);
    return out;
}

namespace {
// The inner loop of the prefilter: one face selection per sample, then bilinear
// reads at the two mip levels around the sample's lod, weights pre-multiplied.
// The source levels as the prefilter reads them: each face with one more column and one more
// row, copies of its last (reads clamp to the face's edge), so that a bilinear footprint's
// texels are always (x0, y0) to (x0 + 1, y0 + 1), and a row's two are adjacent (one 8-float
// load in the eight-lane loop).
struct PaddedLevel {
    std::vector<float> texels;  // 6 faces of (size + 1)^2 RGBA texels
    int size = 0;
    float fsize = 0.0f;
};

// Levels below `first` (which no sample reads) are left empty.
std::vector<PaddedLevel> padded_levels(const Cubemap& cube, int first) {
    std::vector<PaddedLevel> out(cube.levels.size());
    for (std::size_t l = std::size_t(std::max(first, 0)); l < cube.levels.size(); ++l) {
        const CubeLevel& lv = cube.levels[l];
        PaddedLevel& p = out[l];
        p.size = lv.size;
        p.fsize = float(lv.size);
        const std::size_t n = std::size_t(lv.size), stride = n + 1;
        p.texels.resize(6 * stride * stride * 4);
        for (int f = 0; f < 6; ++f) {
            float* dst = p.texels.data() + std::size_t(f) * stride * stride * 4;
            for (std::size_t y = 0; y <= n; ++y) {
                const float* row = lv.faces[std::size_t(f)].data() + std::min(y, n - 1) * n * 4;
                std::memcpy(dst + y * stride * 4, row, n * 4 * sizeof(float));
                std::memcpy(dst + (y * stride + n) * 4, row + (n - 1) * 4, 4 * sizeof(float));
            }
        }
    }
    return out;
}


inline void accumulate_bilinear(const PaddedLevel& L, int face, float s, float t, float w, float acc[4]) {
    float fx = s * L.fsize - 0.5f, fy = t * L.fsize - 0.5f;
    float maxc = L.fsize - 1.0f;
    fx = fx < 0.0f ? 0.0f : (fx > maxc ? maxc : fx);
    fy = fy < 0.0f ? 0.0f : (fy > maxc ? maxc : fy);
    int x0 = int(fx), y0 = int(fy);
    float ax = fx - float(x0), ay = fy - float(y0);
    const std::size_t stride = std::size_t(L.size) + 1;
    const float* p00 = L.texels.data() + ((std::size_t(face) * stride + std::size_t(y0)) * stride + std::size_t(x0)) * 4;
    const float* p10 = p00 + 4;
    const float* p01 = p00 + stride * 4;
    const float* p11 = p01 + 4;
    float w00 = (1 - ax) * (1 - ay) * w, w10 = ax * (1 - ay) * w, w01 = (1 - ax) * ay * w, w11 = ax * ay * w;
    for (int c = 0; c < 4; ++c) acc[c] += p00[c] * w00 + p10[c] * w10 + p01[c] * w01 + p11[c] * w11;
}

inline void face_coords(float x, float y, float z, int& face, float& s, float& t) {
    float ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
    float sc, tc, ma;
    if (ax >= ay && ax >= az) {
        ma = ax;
        face = x > 0 ? 0 : 1;
        sc = x > 0 ? -z : z;
        tc = -y;
    } else if (ay >= az) {
        ma = ay;
        face = y > 0 ? 2 : 3;
        sc = x;
        tc = y > 0 ? z : -z;
    } else {
        ma = az;
        face = z > 0 ? 4 : 5;
        sc = z > 0 ? x : -x;
        tc = -y;
    }
    float inv = 0.5f / ma;
    s = sc * inv + 0.5f;
    t = tc * inv + 0.5f;
}

struct LobeSample {
    glm::vec3 dir;  // in the frame where n = v = r = +Z
    float weight;   // n.l
    float lod;      // source mip level
    int level0;     // floor(lod)
    float w0, w1;   // weight * (1 - frac), weight * frac
};

// A lobe sample reading the source mip chain at `lod` (of `levels`), trilinearly: blending
// the two levels around it. (Rounding to one level halves the reads but changes the
// kernel enough to cost ~10 dB against the Khronos Sample Viewer at roughness 1.)
LobeSample make_sample(glm::vec3 dir, float weight, float lod, int levels) {
    int level0 = std::min(int(lod), levels - 1);
    float frac = level0 + 1 < levels ? lod - float(level0) : 0.0f;
    return {dir, weight, lod, level0, weight * (1.0f - frac), weight * frac};
}

// The finest level any of `lobe`'s samples reads.
int first_level_read(const std::vector<LobeSample>& lobe) {
    int first = std::numeric_limits<int>::max();
    for (const LobeSample& s : lobe) first = std::min(first, s.level0);
    return first;
}

// Visit samples mip by mip and around the lobe in order, so consecutive reads touch
// nearby texels of the same level (the sum does not depend on the order).
void sort_for_locality(std::vector<LobeSample>& lobe) {
    std::sort(lobe.begin(), lobe.end(), [](const LobeSample& a, const LobeSample& b) {
        if (a.level0 != b.level0) return a.level0 < b.level0;
        return std::atan2(a.dir.y, a.dir.x) < std::atan2(b.dir.y, b.dir.x);
    });
}

// The weighted mean of the source over `lobe` (defined around +Z) turned to normal n.
glm::vec3 filter_direction(const std::vector<PaddedLevel>& views, const std::vector<LobeSample>& lobe, glm::vec3 n) {
    glm::vec3 t, b;
    sampling::basis(n, t, b);
    float acc[4] = {0, 0, 0, 0};
    float wsum = 0.0f;
    for (const LobeSample& s : lobe) {
        float dx = t.x * s.dir.x + b.x * s.dir.y + n.x * s.dir.z;
        float dy = t.y * s.dir.x + b.y * s.dir.y + n.y * s.dir.z;
        float dz = t.z * s.dir.x + b.z * s.dir.y + n.z * s.dir.z;
        int face;
        float fs, ft;
        face_coords(dx, dy, dz, face, fs, ft);
        accumulate_bilinear(views[std::size_t(s.level0)], face, fs, ft, s.w0, acc);
        if (s.w1 > 0.0f) accumulate_bilinear(views[std::size_t(s.level0 + 1)], face, fs, ft, s.w1, acc);
        wsum += s.weight;
    }
    return glm::vec3(acc[0], acc[1], acc[2]) / std::max(wsum, 1e-8f);
}

// The same sum as filter_direction, eight samples at a time: the lobe is stored as
// batches of 8 that share a mip level (padded with zero weights), and the rotation,
// the cube-face selection and the bilinear weights and addresses are computed with
// vector extensions (SSE/AVX, whatever the target has); only the texel reads are per
// lane, a row's two texels in one load (PaddedLevel). About three times as fast as the
// scalar loop (the two-load rows: 375 -> 225 ms for the default bake's specular filter on
// one thread of this machine); results agree to float rounding.
// Declared 4-byte aligned: loads and stores are then unaligned ones, so no container
// has to honour a 32-byte alignment (std::vector does not, in every configuration).
typedef float V8 __attribute__((vector_size(32), aligned(4)));
typedef std::int32_t I8 __attribute__((vector_size(32), aligned(4)));
constexpr int kLanes = 8;

struct LobeBatch {
    V8 x, y, z;   // directions around +Z
    V8 w0, w1;    // weights at level0 and level0 + 1
    float weight_sum;
    int level0;
    bool has_w1;
};

std::vector<LobeBatch> make_batches(const std::vector<LobeSample>& lobe) {
    std::vector<LobeBatch> out;
    std::size_t i = 0;
    while (i < lobe.size()) {
        LobeBatch b{};
        b.level0 = lobe[i].level0;
        for (int k = 0; k < kLanes; ++k) b.z[k] = 1.0f;  // padding: +Z with zero weight
        int lane = 0;
        for (; lane < kLanes && i < lobe.size() && lobe[i].level0 == b.level0; ++lane, ++i) {
            const LobeSample& s = lobe[i];
            b.x[lane] = s.dir.x, b.y[lane] = s.dir.y, b.z[lane] = s.dir.z;
            b.w0[lane] = s.w0, b.w1[lane] = s.w1;
            b.weight_sum += s.weight;
            b.has_w1 = b.has_w1 || s.w1 > 0.0f;
        }
        out.push_back(b);
    }
    return out;
}

__attribute__((always_inline)) inline void accumulate_bilinear8(const PaddedLevel& L, const I8& face, const V8& s, const V8& t,
                                                                const V8& w, V8& acc) {
    const V8 zero = V8{} + 0.0f, maxc = zero + (L.fsize - 1.0f);
    V8 fx = s * L.fsize - 0.5f, fy = t * L.fsize - 0.5f;
    fx = fx < zero ? zero : (fx > maxc ? maxc : fx);
    fy = fy < zero ? zero : (fy > maxc ? maxc : fy);
    const I8 x0 = __builtin_convertvector(fx, I8), y0 = __builtin_convertvector(fy, I8);
    const V8 ax = fx - __builtin_convertvector(x0, V8), ay = fy - __builtin_convertvector(y0, V8);
    const V8 w00 = (1.0f - ax) * (1.0f - ay) * w, w10 = ax * (1.0f - ay) * w;
    const V8 w01 = (1.0f - ax) * ay * w, w11 = ax * ay * w;
    const int stride = L.size + 1;
    const I8 i00 = ((face * stride + y0) * stride + x0) * 4;
    const float* base = L.texels.data();
    const std::size_t row = std::size_t(stride) * 4;
    // Per lane: texels (x0, y0), (x0 + 1, y0) in one load and the row below in another,
    // weighted [w00 x4, w10 x4] and [w01 x4, w11 x4].
    for (int k = 0; k < kLanes; ++k) {
        const float* p = base + i00[k];
        V8 top, bottom;
        std::memcpy(&top, p, sizeof(V8));
        std::memcpy(&bottom, p + row, sizeof(V8));
        const V8 wt = {w00[k], w00[k], w00[k], w00[k], w10[k], w10[k], w10[k], w10[k]};
        const V8 wb = {w01[k], w01[k], w01[k], w01[k], w11[k], w11[k], w11[k], w11[k]};
        acc += top * wt + bottom * wb;
    }
}

// On x86-64 this is compiled twice, for Haswell-class CPUs (AVX2, FMA: the eight lanes
// in one register) and for the baseline, and the loader picks one at run time; the
// helper is always inlined, so it is compiled into each version.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(FRESNEL_NO_TARGET_CLONES)
#define FRESNEL_KERNEL __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define FRESNEL_KERNEL
#endif

FRESNEL_KERNEL
glm::vec3 filter_direction8(const std::vector<PaddedLevel>& views, const std::vector<LobeBatch>& batches, glm::vec3 n) {
    glm::vec3 t, b;
    sampling::basis(n, t, b);
    V8 acc = V8{} + 0.0f;  // two RGBA sums (the left and right texels' shares)
    float wsum = 0.0f;
    const V8 zero = V8{} + 0.0f;
    for (const LobeBatch& B : batches) {
        const V8 dx = t.x * B.x + b.x * B.y + n.x * B.z;
        const V8 dy = t.y * B.x + b.y * B.y + n.y * B.z;
        const V8 dz = t.z * B.x + b.z * B.y + n.z * B.z;
        const V8 ax = dx < zero ? -dx : dx, ay = dy < zero ? -dy : dy, az = dz < zero ? -dz : dz;
        // The same face rules as face_coords (ties go to x, then y).
        const I8 xm = (ax >= ay) & (ax >= az);
        const I8 ym = ~xm & (ay >= az);
        const V8 ma = xm ? ax : (ym ? ay : az);
        const V8 sc = xm ? (dx > zero ? -dz : dz) : (ym ? dx : (dz > zero ? dx : -dx));
        const V8 tc = ym ? (dy > zero ? dz : -dz) : -dy;
        const I8 face = xm ? (dx > zero ? I8{} + 0 : I8{} + 1)
                           : (ym ? (dy > zero ? I8{} + 2 : I8{} + 3) : (dz > zero ? I8{} + 4 : I8{} + 5));
        const V8 inv = 0.5f / ma;
        const V8 s = sc * inv + 0.5f, tt = tc * inv + 0.5f;
        accumulate_bilinear8(views[std::size_t(B.level0)], face, s, tt, B.w0, acc);
        if (B.has_w1) accumulate_bilinear8(views[std::size_t(B.level0 + 1)], face, s, tt, B.w1, acc);
        wsum += B.weight_sum;
    }
    return glm::vec3(acc[0] + acc[4], acc[1] + acc[5], acc[2] + acc[6]) / std::max(wsum, 1e-8f);
}

void store(float* px, glm::vec3 c) { px[0] = c.x, px[1] = c.y, px[2] = c.z, px[3] = 1.0f; }

std::vector<LobeSample> lobe_samples(float roughness, int count, int lod_count, int source_size, int source_levels,
                                     float lod_bias) {
    std::vector<LobeSample> out;
    float alpha = roughness * roughness;
    // Solid angle of one source texel at level 0 (average over the sphere).
    float texel_solid_angle = 4.0f * kPi / (6.0f * float(source_size) * float(source_size));
    for (int i = 0; i < count; ++i) {
        glm::vec3 h = sampling::sample_ggx_half(sampling::hammersley(std::uint32_t(i), std::uint32_t(count)), alpha);
        glm::vec3 l = 2.0f * h.z * h - glm::vec3(0, 0, 1);  // reflect v = +Z about h
        if (l.z <= 0.0f) continue;
        // pdf of l: D(h) h.z / (4 v.h), with v.h = h.z here: D / 4.
        float pdf = brdf::d_ggx(h.z, alpha) * 0.25f;
        float sample_solid_angle = 1.0f / (float(lod_count) * std::max(pdf, 1e-8f));
        float lod = std::clamp(0.5f * std::log2(sample_solid_angle / texel_solid_angle) + lod_bias, 0.0f,
                               float(source_levels - 1));
        out.push_back(make_sample(l, l.z, lod, source_levels));
    }
    sort_for_locality(out);
    return out;
}
}  // namespace

glm::vec3 sample_seamless_cubic(const Cubemap& cube, int level, glm::vec3 dir);  // below

Cubemap prefilter_ggx(const Cubemap& source, const PrefilterOptions& o, const Progress& progress) {
    Cubemap out = make_cubemap(o.size, o.levels);
    // Level 0: the mirror image, the source resampled to the output size.
    int skip = 0;
    while ((source.levels[std::size_t(skip)].size > o.size) && skip + 1 < int(source.levels.size())) ++skip;
    for (int f = 0; f < 6; ++f) {
        const CubeLevel& src = source.levels[std::size_t(skip)];
        if (src.size == o.size) {
            out.levels[0].faces[std::size_t(f)] = src.faces[std::size_t(f)];
        } else {
            for (int y = 0; y < o.size; ++y)
                for (int x = 0; x < o.size; ++x) {
                    glm::vec3 c = source.sample(cube_texel_direction(f, x, y, o.size), float(skip));
                    float* t = out.levels[0].texel(f, x, y);
                    t[0] = c.x, t[1] = c.y, t[2] = c.z, t[3] = 1.0f;
                }
        }
    }
    // Each level >= 1 is filtered at `filtered_size` (half its size by default) into `work`,
    // then magnified into `out`.
    auto filtered_size = [&](int size) { return o.half_resolution ? std::clamp(size / 2, std::min(size, 8), size) : size; };
    Cubemap work;
    work.levels.resize(std::size_t(o.levels));
    for (int l = 1; l < o.levels; ++l) {
        CubeLevel& lv = work.levels[std::size_t(l)];
        lv.size = filtered_size(out.levels[std::size_t(l)].size);
        for (auto& f : lv.faces) f.assign(std::size_t(lv.size) * std::size_t(lv.size) * 4, 0.0f);
    }
    // Work units: rows of every face of every level >= 1, weighted by their cost.
    struct Row {
        int level, face, y;
    };
    std::vector<Row> rows;
    const int lod_count = o.lod_samples > 0 ? o.lod_samples : std::min(kFilterKernelSamples, 4 * o.samples);
    std::vector<std::vector<LobeSample>> lobes(std::size_t(o.levels));
    double total_cost = 0;
    for (int l = 1; l < o.levels; ++l) {
        float roughness = float(l) / float(o.levels - 1);
        lobes[std::size_t(l)] = lobe_samples(roughness, o.samples, lod_count, source.size(),
                                             int(source.levels.size()), o.lod_bias);
        int size = work.levels[std::size_t(l)].size;
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < size; ++y) rows.push_back({l, f, y});
        total_cost += double(size) * size * 6 * double(lobes[std::size_t(l)].size());
    }
    int first_read = std::numeric_limits<int>::max();
    for (const auto& lobe : lobes) first_read = std::min(first_read, lobe.empty() ? first_read : first_level_read(lobe));
    const std::vector<PaddedLevel> padded = padded_levels(source, first_read);
    std::vector<std::vector<LobeBatch>> batches;
    for (const auto& lobe : lobes) batches.push_back(make_batches(lobe));
    const bool kScalar = !o.vectorized;
    std::atomic<double> done_cost{0};
    parallel_for(
        rows.size(),
        [&](std::size_t i) {
            const Row& row = rows[i];
            CubeLevel& lv = work.levels[std::size_t(row.level)];
            const auto& lobe = lobes[std::size_t(row.level)];
            const auto& batch = batches[std::size_t(row.level)];
            for (int x = 0; x < lv.size; ++x) {
                glm::vec3 n = cube_texel_direction(row.face, x, row.y, lv.size);
                store(lv.texel(row.face, x, row.y), kScalar ? filter_direction(padded, lobe, n) : filter_direction8(padded, batch, n));
            }
            if (progress) {
                double c = double(lv.size) * double(lobe.size());
                double prev = done_cost.load();  // (atomic<double>::fetch_add is C++20; libc++ of the web build lacks it)
                while (!done_cost.compare_exchange_weak(prev, prev + c)) {
                }
                double now = prev + c;
                progress(now / total_cost);
            }
        },
        o.threads);
    for (int l = 1; l < o.levels; ++l) {
        CubeLevel& dst = out.levels[std::size_t(l)];
        if (work.levels[std::size_t(l)].size == dst.size) {
            dst = std::move(work.levels[std::size_t(l)]);
            continue;
        }
        parallel_for(
            std::size_t(6 * dst.size),
            [&](std::size_t row) {
                int f = int(row / std::size_t(dst.size)), y = int(row % std::size_t(dst.size));
                for (int x = 0; x < dst.size; ++x)
                    store(dst.texel(f, x, y), sample_seamless_cubic(work, l, cube_texel_direction(f, x, y, dst.size)));
            },
            o.threads);
    }
    return out;
}

Cubemap irradiance_filtered(const Cubemap& source, int size, int samples, float lod_bias, unsigned threads) {
    std::vector<LobeSample> lobe;
    float texel_solid_angle = 4.0f * kPi / (6.0f * float(source.size()) * float(source.size()));
    int levels = int(source.levels.size());
    for (int i = 0; i < samples; ++i) {
        glm::vec3 l = sampling::sample_cosine(sampling::hammersley(std::uint32_t(i), std::uint32_t(samples)));
        if (l.z <= 0.0f) continue;
        float pdf = l.z / kPi;
        float lod = std::clamp(0.5f * std::log2(1.0f / (float(samples) * pdf) / texel_solid_angle) + lod_bias, 0.0f,
                               float(levels - 1));
        // Cosine-distributed samples: each counts once (the cosine is in the pdf).
        lobe.push_back(make_sample(l, 1.0f, lod, levels));
    }
    sort_for_locality(lobe);
    const std::vector<PaddedLevel> padded = padded_levels(source, first_level_read(lobe));
    std::vector<LobeBatch> batches = make_batches(lobe);
    Cubemap out = make_cubemap(size, 1);
    parallel_for(
        std::size_t(6 * size),
        [&](std::size_t row) {
            int f = int(row / std::size_t(size)), y = int(row % std::size_t(size));
            for (int x = 0; x < size; ++x)
                store(out.levels[0].texel(f, x, y), filter_direction8(padded, batches, cube_texel_direction(f, x, y, size)));
        },
        threads);
    return out;
}

glm::vec2 integrate_split_sum(float n_dot_v, float roughness, int samples) {
    // Visible-normal sampling (Heitz 2018): with h ~ D_v(h) and l = reflect(-v, h),
    // f cos / pdf = F G2(l, v) / G1(v). G2 is the height-correlated Smith term of
    // the direct-lighting BRDF: G2 = 4 V n.l n.v.
    float alpha = roughness * roughness;
    n_dot_v = std::max(n_dot_v, 1e-4f);
    glm::vec3 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
    float g1 = sampling::smith_g1(v, alpha);
    double a = 0, b = 0;
    for (int i = 0; i < samples; ++i) {
        glm::vec3 h = sampling::sample_ggx_vndf(v, sampling::hammersley(std::uint32_t(i), std::uint32_t(samples)), alpha);
        float v_dot_h = glm::dot(v, h);
        glm::vec3 l = 2.0f * v_dot_h * h - v;
        if (l.z <= 0.0f || v_dot_h <= 0.0f) continue;
        float g2 = brdf::v_smith_ggx_correlated(l.z, n_dot_v, alpha) * 4.0f * l.z * n_dot_v;
        float w = g2 / g1;
        float fc = std::pow(1.0f - v_dot_h, 5.0f);
        a += (1.0f - fc) * w;
        b += fc * w;
    }
    return {float(a / samples), float(b / samples)};
}

float brdf_lut_n_dot_v(int column, int size) {
    return column == 0 ? kBrdfLutGrazingNdotV : (float(column) + 0.5f) / float(size);
}

glm::vec4 sample_brdf_lut(const ImageF& lut, float n_dot_v, float roughness) {
    if (lut.width <= 0 || lut.height <= 0) return glm::vec4(1.0f);
    const float x = std::clamp(n_dot_v, 0.0f, 1.0f) * float(lut.width) - 0.5f;
    const float y = std::clamp(roughness, 0.0f, 1.0f) * float(lut.height) - 0.5f;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const float fx = x - float(x0), fy = y - float(y0);
    auto at = [&](int i, int j) {
        const float* p = lut.at(std::clamp(i, 0, lut.width - 1), std::clamp(j, 0, lut.height - 1));
        return glm::vec4(p[0], p[1], p[2], p[3]);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

ImageF compute_brdf_lut(int size, int samples, unsigned threads) {
    ImageF lut(size, size);
    parallel_for(
        std::size_t(size),
        [&](std::size_t j) {
            float roughness = (float(j) + 0.5f) / float(size);
            for (int i = 0; i < size; ++i) {
                float n_dot_v = brdf_lut_n_dot_v(i, size);
                glm::vec2 ab = integrate_split_sum(n_dot_v, roughness, samples);
                float* p = lut.at(i, int(j));
                p[0] = ab.x, p[1] = ab.y, p[2] = ab.x + ab.y;
                p[3] = brdf::sheen_albedo_integral(n_dot_v, roughness, kSheenAlbedoSamplesPerAxis);
            }
        },
        threads);
    return lut;
}

void fill_sheen_albedo(ImageF& lut, unsigned threads) {
    parallel_for(
        std::size_t(lut.height),
        [&](std::size_t j) {
            float roughness = (float(j) + 0.5f) / float(lut.height);
            for (int i = 0; i < lut.width; ++i)
                lut.at(i, int(j))[3] = brdf::sheen_albedo_integral(brdf_lut_n_dot_v(i, lut.width), roughness,
                                                                   kSheenAlbedoSamplesPerAxis);
        },
        threads);
}

namespace {
// Charlie D with the exponent parameter a as the Khronos filter writes it: (2 + 1/a) sin^(1/a) / (2 pi).
float d_charlie_a(float a, float n_dot_h) {
    a = std::max(a, 1e-6f);
    float sin2h = std::max(1.0f - n_dot_h * n_dot_h, 0.0f);
    return (2.0f + 1.0f / a) * std::pow(sin2h, 0.5f / a) / (2.0f * kPi);
}
// A Charlie half vector for Hammersley point u at perceptual roughness r (alpha = r^2).
glm::vec3 charlie_half(glm::vec2 u, float roughness, float& cos_theta) {
    float alpha = roughness * roughness;
    float sin_theta = std::pow(u.y, alpha / (2.0f * alpha + 1.0f));
    cos_theta = std::sqrt(std::max(1.0f - sin_theta * sin_theta, 0.0f));
    float phi = 2.0f * kPi * u.x;
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}
}  // namespace

// Bilinear at one level with seamless cube filtering (as GL's TEXTURE_CUBE_MAP_SEAMLESS and
// WebGL 2 do): a footprint texel beyond the face's edge is read from the face it lies on. The
// Charlie filter reads the coarsest levels (2x2, 1x1), where clamping at each face's edge would
// paint the faces as blocks.
namespace {
// Texel (x, y) of `face` at one level, where x or y may lie one or two texels beyond the face:
// then the texel whose centre that point of the face's plane lands on, on its neighbour.
const float* seamless_texel(const CubeLevel& lv, int face, int x, int y) {
    if (x >= 0 && y >= 0 && x < lv.size && y < lv.size) return lv.texel(face, x, y);
    int f2;
    float s2, t2;
    cube_face_uv(cube_texel_direction(face, x, y, lv.size), f2, s2, t2);
    int x2 = std::clamp(int(s2 * float(lv.size)), 0, lv.size - 1), y2 = std::clamp(int(t2 * float(lv.size)), 0, lv.size - 1);
    return lv.texel(f2, x2, y2);
}

// Where a direction falls on a level: its face, the texel at or before it in x and y (centres
// at half-integers), and how far past that texel's centre it lies.
struct FacePoint {
    int face, x0, y0;
    float ax, ay;
};
FacePoint face_point(const CubeLevel& lv, glm::vec3 dir) {
    FacePoint p;
    float s, t;
    cube_face_uv(dir, p.face, s, t);
    float fx = s * float(lv.size) - 0.5f, fy = t * float(lv.size) - 0.5f;
    p.x0 = int(std::floor(fx)), p.y0 = int(std::floor(fy));
    p.ax = fx - float(p.x0), p.ay = fy - float(p.y0);
    return p;
}
}  // namespace

glm::vec3 sample_seamless(const Cubemap& cube, int level, glm::vec3 dir) {
    const CubeLevel& lv = cube.levels[std::size_t(level)];
    const auto [face, x0, y0, ax, ay] = face_point(lv, dir);
    glm::vec3 sum(0.0f);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            float w = (i ? ax : 1.0f - ax) * (j ? ay : 1.0f - ay);
            if (w <= 0.0f) continue;
            const float* p = seamless_texel(lv, face, x0 + i, y0 + j);
            sum += w * glm::vec3(p[0], p[1], p[2]);
        }
    return sum;
}

namespace {
// Catmull-Rom weights of the four taps around a point a fraction `a` past the second.
void catmull_rom(float a, float w[4]) {
    float a2 = a * a, a3 = a2 * a;
    w[0] = 0.5f * (-a3 + 2.0f * a2 - a);
    w[1] = 0.5f * (3.0f * a3 - 5.0f * a2 + 2.0f);
    w[2] = 0.5f * (-3.0f * a3 + 4.0f * a2 + a);
    w[3] = 0.5f * (a3 - a2);
}
}  // namespace

// Bicubic (Catmull-Rom) at one level, seamless as sample_seamless; negative results (a
// cubic's overshoot beside a bright source) are clamped to 0.
glm::vec3 sample_seamless_cubic(const Cubemap& cube, int level, glm::vec3 dir) {
    const CubeLevel& lv = cube.levels[std::size_t(level)];
    const auto [face, x0, y0, ax, ay] = face_point(lv, dir);
    float wx[4], wy[4];
    catmull_rom(ax, wx);
    catmull_rom(ay, wy);
    glm::vec3 sum(0.0f);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const float* p = seamless_texel(lv, face, x0 - 1 + i, y0 - 1 + j);
            sum += (wx[i] * wy[j]) * glm::vec3(p[0], p[1], p[2]);
        }
    return glm::max(sum, glm::vec3(0.0f));
}

Cubemap prefilter_charlie(const Cubemap& source, int size, int levels, int samples, unsigned threads) {
    Cubemap out = make_cubemap(size, levels);
    const int source_levels = int(source.levels.size());
    const float width = float(source.size());
    for (int level = 0; level < levels; ++level) {
        const float roughness = levels > 1 ? float(level) / float(levels - 1) : 0.0f;
        std::vector<LobeSample> lobe;
        for (int i = 0; i < samples; ++i) {
            float cos_theta;
            glm::vec3 h = charlie_half(sampling::hammersley(std::uint32_t(i), std::uint32_t(samples)), roughness, cos_theta);
            glm::vec3 l = 2.0f * h.z * h - glm::vec3(0, 0, 1);  // reflect v = n = +Z about h
            if (l.z <= 0.0f) continue;
            // The viewer's mip from its sample "pdf" D / 4 (0 gives the coarsest level).
            float pdf = d_charlie_a(roughness * roughness, cos_theta) * 0.25f;
            float lod = roughness == 0.0f ? 0.0f
                        : pdf > 0.0f ? 0.5f * std::log2(6.0f * width * width / (float(samples) * pdf))
                                     : float(source_levels - 1);
            lod = std::clamp(lod, 0.0f, float(source_levels - 1));
            lobe.push_back(make_sample(l, l.z, lod, source_levels));
        }
        CubeLevel& dst = out.levels[std::size_t(level)];
        parallel_for(
            std::size_t(6 * dst.size),
            [&](std::size_t row) {
                int f = int(row / std::size_t(dst.size)), y = int(row % std::size_t(dst.size));
                for (int x = 0; x < dst.size; ++x) {
                    glm::vec3 n = cube_texel_direction(f, x, y, dst.size), tt, bb;
                    sampling::basis(n, tt, bb);
                    glm::vec3 sum(0.0f);
                    float wsum = 0.0f;
                    for (const LobeSample& s : lobe) {
                        glm::vec3 d = tt * s.dir.x + bb * s.dir.y + n * s.dir.z;
                        glm::vec3 c = sample_seamless(source, s.level0, d) * (1.0f - (s.w1 > 0.0f ? s.w1 / s.weight : 0.0f));
                        if (s.w1 > 0.0f) c += sample_seamless(source, s.level0 + 1, d) * (s.w1 / s.weight);
                        sum += c * s.weight;
                        wsum += s.weight;
                    }
                    store(dst.texel(f, x, y), wsum > 0.0f ? sum / wsum : glm::vec3(0.0f));
                }
            },
            threads);
    }
    return out;
}

ImageF compute_charlie_lut(int size, int samples, unsigned threads) {
    ImageF lut(size, size);
    parallel_for(
        std::size_t(size),
        [&](std::size_t row) {
            const int j = int(row);
            const float roughness = (float(j) + 0.5f) / float(size);
            // The half vectors and D of this row's roughness, for every n.v of the row.
            std::vector<glm::vec3> half(std::size_t(samples), glm::vec3(0.0f));
            std::vector<float> d(std::size_t(samples), 0.0f);
            for (int k = 0; k < samples; ++k) {
                float cos_theta;
                half[std::size_t(k)] = charlie_half(sampling::hammersley(std::uint32_t(k), std::uint32_t(samples)), roughness, cos_theta);
                d[std::size_t(k)] = d_charlie_a(roughness, std::clamp(half[std::size_t(k)].z, 0.0f, 1.0f));
            }
            for (int i = 0; i < size; ++i) {
                const float n_dot_v = (float(i) + 0.5f) / float(size);
                const glm::vec3 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
                double c = 0.0;
                for (int k = 0; k < samples; ++k) {
                    const glm::vec3 h = half[std::size_t(k)];
                    glm::vec3 l = glm::normalize(2.0f * glm::dot(v, h) * h - v);
                    float n_dot_l = std::clamp(l.z, 0.0f, 1.0f);
                    if (n_dot_l <= 0.0f) continue;
                    float v_dot_h = std::clamp(glm::dot(v, h), 0.0f, 1.0f);
                    float vis = std::clamp(1.0f / (4.0f * (n_dot_l + n_dot_v - n_dot_l * n_dot_v)), 0.0f, 1.0f);  // Ashikhmin
                    c += double(vis * d[std::size_t(k)] * n_dot_l * v_dot_h);
                }
                float* p = lut.at(i, j);
                p[0] = float(8.0 * double(kPi) * c / double(samples));
                p[1] = p[2] = 0.0f;
                p[3] = 1.0f;
            }
        },
        threads);
    return lut;
}

}  // namespace fresnel::ibl
