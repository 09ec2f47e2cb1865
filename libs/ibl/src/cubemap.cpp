#include "fresnel/ibl/cubemap.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "fresnel/core/parallel.h"

namespace fresnel::ibl {

namespace {
constexpr float kPi = 3.14159265358979323846f;
}

glm::vec2 direction_to_equirect(glm::vec3 d) {
    float u = 0.5f + std::atan2(-d.x, d.z) / (2.0f * kPi);
    float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
    return {u, v};
}

glm::vec3 equirect_to_direction(glm::vec2 uv) {
    float phi = (uv.x - 0.5f) * 2.0f * kPi;  // atan2(-x, z)
    float theta = uv.y * kPi;
    float s = std::sin(theta);
    return {-s * std::sin(phi), std::cos(theta), s * std::cos(phi)};
}

namespace {
// The (unnormalised) direction through face coordinates s, t in [-1, 1] (t down the face).
glm::vec3 face_direction(int face, float s, float t) {
    switch (face) {
        case 0: return {1.0f, -t, -s};
        case 1: return {-1.0f, -t, s};
        case 2: return {s, 1.0f, t};
        case 3: return {s, -1.0f, -t};
        case 4: return {s, -t, 1.0f};
        default: return {-s, -t, -1.0f};
    }
}
}  // namespace

glm::vec3 cube_texel_direction(int face, int x, int y, int size) {
    float s = 2.0f * (float(x) + 0.5f) / float(size) - 1.0f;
    float t = 2.0f * (float(y) + 0.5f) / float(size) - 1.0f;
    return glm::normalize(face_direction(face, s, t));
}

void cube_face_uv(glm::vec3 d, int& face, float& s, float& t) {
    float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    float sc, tc, ma;
    if (ax >= ay && ax >= az) {
        ma = ax;
        if (d.x > 0) { face = 0; sc = -d.z; tc = -d.y; }
        else { face = 1; sc = d.z; tc = -d.y; }
    } else if (ay >= az) {
        ma = ay;
        if (d.y > 0) { face = 2; sc = d.x; tc = d.z; }
        else { face = 3; sc = d.x; tc = -d.z; }
    } else {
        ma = az;
        if (d.z > 0) { face = 4; sc = d.x; tc = -d.y; }
        else { face = 5; sc = -d.x; tc = -d.y; }
    }
    float inv = ma > 0 ? 1.0f / ma : 0.0f;
    s = 0.5f * (sc * inv + 1.0f);
    t = 0.5f * (tc * inv + 1.0f);
}

float cube_texel_solid_angle(int x, int y, int size) {
    // Exact: the area of the texel's projection on the unit sphere (via atan of corner terms).
    auto area = [](float a, float b) { return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0f)); };
    float inv = 1.0f / float(size);
    float x0 = 2.0f * float(x) * inv - 1.0f, x1 = 2.0f * float(x + 1) * inv - 1.0f;
    float y0 = 2.0f * float(y) * inv - 1.0f, y1 = 2.0f * float(y + 1) * inv - 1.0f;
    return area(x0, y0) - area(x0, y1) - area(x1, y0) + area(x1, y1);
}

Cubemap make_cubemap(int size, int levels) {
    Cubemap c;
    for (int l = 0; l < levels; ++l) {
        CubeLevel lv;
        lv.size = std::max(1, size >> l);
        for (auto& f : lv.faces) f.assign(std::size_t(lv.size) * lv.size * 4, 0.0f);
        c.levels.push_back(std::move(lv));
    }
    return c;
}

glm::vec3 Cubemap::sample_level(glm::vec3 dir, int level) const {
    const CubeLevel& lv = levels[std::size_t(std::clamp(level, 0, int(levels.size()) - 1))];
    int face;
    float s, t;
    cube_face_uv(dir, face, s, t);
    float fx = std::clamp(s * float(lv.size) - 0.5f, 0.0f, float(lv.size - 1));
    float fy = std::clamp(t * float(lv.size) - 0.5f, 0.0f, float(lv.size - 1));
    int x0 = int(fx), y0 = int(fy);
    int x1 = std::min(x0 + 1, lv.size - 1), y1 = std::min(y0 + 1, lv.size - 1);
    float ax = fx - float(x0), ay = fy - float(y0);
    const float* f = lv.faces[std::size_t(face)].data();
    const std::size_t n = std::size_t(lv.size);
    const float* p00 = f + (std::size_t(y0) * n + std::size_t(x0)) * 4;
    const float* p10 = f + (std::size_t(y0) * n + std::size_t(x1)) * 4;
    const float* p01 = f + (std::size_t(y1) * n + std::size_t(x0)) * 4;
    const float* p11 = f + (std::size_t(y1) * n + std::size_t(x1)) * 4;
    glm::vec3 r;
    for (int c = 0; c < 3; ++c) {
        float top = p00[c] + (p10[c] - p00[c]) * ax;
        float bottom = p01[c] + (p11[c] - p01[c]) * ax;
        r[c] = top + (bottom - top) * ay;
    }
    return r;
}

glm::vec3 Cubemap::sample(glm::vec3 dir, float lod) const {
    float maxl = float(levels.size() - 1);
    lod = std::clamp(lod, 0.0f, maxl);
    int l0 = int(lod);
    float a = lod - float(l0);
    glm::vec3 c0 = sample_level(dir, l0);
    if (a <= 0.0f || l0 + 1 > int(maxl)) return c0;
    return c0 + (sample_level(dir, l0 + 1) - c0) * a;
}

namespace {
glm::vec3 sample_equirect(const ImageF& img, glm::vec2 uv) {
    // Bilinear, wrapping horizontally, clamped vertically.
    float fx = uv.x * float(img.width) - 0.5f, fy = std::clamp(uv.y * float(img.height) - 0.5f, 0.0f, float(img.height - 1));
    int x0 = int(std::floor(fx)), y0 = int(fy);
    float ax = fx - float(x0), ay = fy - float(y0);
    auto wrap = [&](int x) { return ((x % img.width) + img.width) % img.width; };
    int xa = wrap(x0), xb = wrap(x0 + 1), y1 = std::min(y0 + 1, img.height - 1);
    glm::vec3 r;
    for (int c = 0; c < 3; ++c) {
        float top = img.at(xa, y0)[c] + (img.at(xb, y0)[c] - img.at(xa, y0)[c]) * ax;
        float bottom = img.at(xa, y1)[c] + (img.at(xb, y1)[c] - img.at(xa, y1)[c]) * ax;
        r[c] = top + (bottom - top) * ay;
    }
    return r;
}

// atan2 to within 2e-6 radians (an odd minimax polynomial on [0, 1] and the octant's
// symmetries): a hundredth of a texel of a 1k panorama, and no library call, so the
// resampling loop below vectorises.
inline float fast_atan2(float y, float x) {
    const float ax = std::fabs(x), ay = std::fabs(y);
    const float hi = std::max(ax, ay), lo = std::min(ax, ay);
    const float a = hi > 0.0f ? lo / hi : 0.0f, a2 = a * a;
    float r = a * (0.99997726f + a2 * (-0.33262347f + a2 * (0.19354346f + a2 * (-0.11643287f + a2 * (0.05265332f + a2 * -0.01172120f)))));
    r = ay > ax ? 0.5f * kPi - r : r;
    r = x < 0.0f ? kPi - r : r;
    return y < 0.0f ? -r : r;
}
}  // namespace

Cubemap cubemap_from_equirect(const ImageF& pano, int size, unsigned threads) {
    Cubemap cube = make_cubemap(size, 1);
    // Samples per texel side: enough to cover the panorama texels a cube texel spans.
    float pano_texels_per_cube_texel = float(pano.width) / (4.0f * float(size));
    int ss = std::clamp(int(std::ceil(pano_texels_per_cube_texel)), 1, 4);
    parallel_for(
        std::size_t(6 * size),
        [&](std::size_t row) {
            int face = int(row / std::size_t(size)), y = int(row % std::size_t(size));
            for (int x = 0; x < size; ++x) {
                glm::vec3 sum(0.0f);
                for (int j = 0; j < ss; ++j)
                    for (int i = 0; i < ss; ++i) {
                        float s = 2.0f * (float(x) + (float(i) + 0.5f) / float(ss)) / float(size) - 1.0f;
                        float t = 2.0f * (float(y) + (float(j) + 0.5f) / float(ss)) / float(size) - 1.0f;
                        // direction_to_equirect of the (unnormalised) direction: u from its
                        // azimuth, v from its angle to +Y.
                        glm::vec3 d = face_direction(face, s, t);
                        glm::vec2 uv(0.5f + fast_atan2(-d.x, d.z) / (2.0f * kPi),
                                     fast_atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y) / kPi);
                        sum += sample_equirect(pano, uv);
                    }
                sum /= float(ss * ss);
                float* t = cube.levels[0].texel(face, x, y);
                t[0] = sum.x;
                t[1] = sum.y;
                t[2] = sum.z;
                t[3] = 1.0f;
            }
        },
        threads);
    return cube;
}

void build_mip_chain(Cubemap& cube) {
    while (cube.levels.back().size > 1) {
        const CubeLevel& src = cube.levels.back();
        CubeLevel dst;
        dst.size = src.size / 2;
        for (int f = 0; f < 6; ++f) {
            dst.faces[std::size_t(f)].resize(std::size_t(dst.size) * dst.size * 4);
            for (int y = 0; y < dst.size; ++y)
                for (int x = 0; x < dst.size; ++x)
                    for (int c = 0; c < 4; ++c)
                        dst.texel(f, x, y)[c] = 0.25f * (src.texel(f, 2 * x, 2 * y)[c] + src.texel(f, 2 * x + 1, 2 * y)[c] +
                                                         src.texel(f, 2 * x, 2 * y + 1)[c] + src.texel(f, 2 * x + 1, 2 * y + 1)[c]);
        }
        cube.levels.push_back(std::move(dst));
    }
}

}  // namespace fresnel::ibl
