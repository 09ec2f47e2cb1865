#include "fresnel/material/ltc.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

namespace fresnel::ltc {

namespace {

#include "ltc_table.inc"  // kLtcInverse (tools/ltc_fit)

static_assert(kLtcInverse.size() == std::size_t(kTableSize * kTableSize * 4));

constexpr float kPi = 3.14159265358979323846f;

// The texel (i, j) of the table, clamped to its edges.
glm::vec4 texel(int i, int j) {
    i = std::clamp(i, 0, kTableSize - 1);
    j = std::clamp(j, 0, kTableSize - 1);
    const float* p = kLtcInverse.data() + (std::size_t(j) * kTableSize + std::size_t(i)) * 4;
    return {p[0], p[1], p[2], p[3]};
}

// A GL sampler's bilinear, clamp-to-edge filter at uv (texel centres at (k + 0.5) / size).
glm::vec4 sample_table(glm::vec2 uv) {
    float x = uv.x * float(kTableSize) - 0.5f, y = uv.y * float(kTableSize) - 0.5f;
    float x0 = std::floor(x), y0 = std::floor(y);
    float fx = x - x0, fy = y - y0;
    int i = int(x0), j = int(y0);
    glm::vec4 bottom = texel(i, j) * (1.0f - fx) + texel(i + 1, j) * fx;
    glm::vec4 top = texel(i, j + 1) * (1.0f - fx) + texel(i + 1, j + 1) * fx;
    return bottom * (1.0f - fy) + top * fy;
}

// The integral of the clamped cosine over the edge a -> b of a polygon on the unit sphere,
// times 2 pi: the angle between a and b times the z of the unit normal of their plane,
// atan2(|a x b|, a.b) (a.b) / |a x b|, robust for nearly parallel edges (the angle from atan2,
// the ratio -> 1 as |a x b| -> 0).
float edge_integral(glm::vec3 a, glm::vec3 b) {
    glm::vec3 c = glm::cross(a, b);
    float s = glm::length(c);
    float theta = std::atan2(s, glm::dot(a, b));
    return c.z * (theta / std::max(s, 1e-7f));
}

}  // namespace

const float* table_data() { return kLtcInverse.data(); }

glm::mat3 inverse_matrix(float n_dot_v, float perceptual_roughness) {
    float r = std::clamp(perceptual_roughness, 0.0f, 1.0f);
    float t = std::sqrt(1.0f - std::clamp(n_dot_v, 0.0f, 1.0f));
    glm::vec2 uv = glm::vec2(r, t) * (float(kTableSize - 1) / float(kTableSize)) + 0.5f / float(kTableSize);
    glm::vec4 e = sample_table(uv);
    // Rows [[a, 0, b], [0, c, 0], [d, 0, 1]]; glm's constructor takes columns.
    return glm::mat3(glm::vec3(e.x, 0.0f, e.w), glm::vec3(0.0f, e.z, 0.0f), glm::vec3(e.y, 0.0f, 1.0f));
}

float polygon_integral(const glm::mat3& minv, glm::vec3 n, glm::vec3 v, const glm::vec3* points, int count) {
    if (count < 3 || count > kMaxPolygon) return 0.0f;
    // The frame: n = +Z, v in the XZ plane with v.x >= 0.
    glm::vec3 t1 = v - n * glm::dot(v, n);
    float len = glm::length(t1);
    if (len > 1e-6f) {
        t1 = t1 / len;
    } else {  // v parallel to n: any tangent
        t1 = std::fabs(n.z) < 0.999f ? glm::cross(glm::vec3(0.0f, 0.0f, 1.0f), n) : glm::vec3(1.0f, 0.0f, 0.0f);
        t1 = glm::normalize(t1 - n * glm::dot(t1, n));
    }
    glm::vec3 t2 = glm::cross(n, t1);
    // Into the frame, through M^-1, onto the unit sphere.
    glm::vec3 p[kMaxPolygon];
    for (int i = 0; i < count; ++i) {
        glm::vec3 q = minv * glm::vec3(glm::dot(points[i], t1), glm::dot(points[i], t2), glm::dot(points[i], n));
        float l = glm::length(q);
        p[i] = l > 0.0f ? q / l : q;
    }
    // Clip to z >= 0 (Sutherland-Hodgman against one plane): a convex polygon gains at most
    // one vertex.
    glm::vec3 c[kMaxPolygon + 1];
    int m = 0;
    for (int i = 0; i < count; ++i) {
        glm::vec3 a = p[i];
        glm::vec3 b = p[i + 1 < count ? i + 1 : 0];
        if (a.z >= 0.0f && m <= kMaxPolygon) c[m++] = a;
        if ((a.z >= 0.0f) != (b.z >= 0.0f) && m <= kMaxPolygon) {
            glm::vec3 x = a + (b - a) * (a.z / (a.z - b.z));
            x.z = 0.0f;
            float l = glm::length(x);
            c[m++] = l > 0.0f ? x / l : x;
        }
    }
    if (m < 3) return 0.0f;
    float sum = 0.0f;
    for (int i = 0; i < m; ++i) sum += edge_integral(c[i], c[i + 1 < m ? i + 1 : 0]);
    // Counter-clockwise seen from the lit side (below the polygon) is clockwise seen from +Z,
    // where the edge sum is negative.
    return std::max(-sum / (2.0f * kPi), 0.0f);
}

int disk_polygon(glm::vec3 center, glm::vec3 axis_u, glm::vec3 axis_v, float radius, glm::vec3* out, int count) {
    count = std::clamp(count, 3, kMaxPolygon);
    float step = 2.0f * kPi / float(count);
    float circumradius = radius * std::sqrt(kPi / (0.5f * float(count) * std::sin(step)));
    for (int k = 0; k < count; ++k) {
        float phi = step * float(k);
        out[k] = center + circumradius * (std::cos(phi) * axis_u + std::sin(phi) * axis_v);
    }
    return count;
}

int sphere_polygon(glm::vec3 center, float radius, glm::vec3 shading_point, glm::vec3* out, int count) {
    glm::vec3 w = shading_point - center;
    float d = glm::length(w);
    if (!(d > radius)) return 0;
    w = w / d;  // the disk's lit side faces the point: u x v = w
    glm::vec3 u = std::fabs(w.z) < 0.999f ? glm::cross(glm::vec3(0.0f, 0.0f, 1.0f), w) : glm::vec3(1.0f, 0.0f, 0.0f);
    u = glm::normalize(u - w * glm::dot(u, w));
    glm::vec3 v = glm::cross(w, u);
    float disk_radius = radius * d / std::sqrt((d - radius) * (d + radius));
    return disk_polygon(center, u, v, disk_radius, out, count);
}

}  // namespace fresnel::ltc
