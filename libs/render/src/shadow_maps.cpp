// Shadow map planning (details/shadow_maps.h): no GL, unit-tested in render_test.
#include "details/shadow_maps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace fresnel {

namespace {

std::array<glm::vec3, 8> corners(const Bounds& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[std::size_t(i)] = glm::vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
    return c;
}

// A light's view looking along `dir` from `eye`, with an up that is never parallel to it.
glm::mat4 light_view(glm::vec3 eye, glm::vec3 dir, glm::vec3 up_hint = glm::vec3(0, 1, 0)) {
    glm::vec3 up = std::abs(glm::dot(glm::normalize(up_hint), dir)) > 0.99f ? glm::vec3(1, 0, 0) : up_hint;
    return glm::lookAt(eye, eye + dir, up);
}

// The depth range from `eye` that holds the box: (nearest, farthest), nearest 0 inside it.
std::pair<float, float> box_distances(glm::vec3 eye, const Bounds& b) {
    float far = 0.0f;
    for (const glm::vec3& c : corners(b)) far = std::max(far, glm::length(c - eye));
    const glm::vec3 closest = glm::clamp(eye, b.min, b.max);
    return {glm::length(closest - eye), far};
}

// The camera's frustum corners (world) at view-space depths `d0` (four) and `d1` (four).
std::array<glm::vec3, 8> frustum_slice(const CameraSetup& cam, float d0, float d1) {
    const glm::mat4 inv_projection = glm::inverse(cam.projection);
    const glm::mat4 inv_view = glm::inverse(cam.view);
    std::array<glm::vec3, 8> out;
    for (int i = 0; i < 4; ++i) {
        const float x = i & 1 ? 1.0f : -1.0f, y = i & 2 ? 1.0f : -1.0f;
        glm::vec4 n = inv_projection * glm::vec4(x, y, -1.0f, 1.0f);
        glm::vec4 f = inv_projection * glm::vec4(x, y, 1.0f, 1.0f);
        const glm::vec3 near = glm::vec3(n) / n.w, far = glm::vec3(f) / f.w;
        const float dn = -near.z, df = -far.z;
        for (int k = 0; k < 2; ++k) {
            const float d = k == 0 ? d0 : d1;
            const float t = df != dn ? (d - dn) / (df - dn) : 0.0f;
            out[std::size_t(i + 4 * k)] = glm::vec3(inv_view * glm::vec4(glm::mix(near, far, t), 1.0f));
        }
    }
    return out;
}

// Rounds a positive length up to the next power of 2^(1/4): a cascade's size steps rather
// than follows the camera continuously (no shimmer while it moves within a step).
float quantise_up(float e) { return std::exp2(std::ceil(std::log2(std::max(e, 1e-6f)) * 4.0f) / 4.0f); }

// The tile's useful part: [margin, size - margin] texels, which the lookups keep inside so that
// the filter never reads a neighbour. Returns size / useful size (>= 1).
float margin_scale(int tile) {
    const float useful = float(std::max(tile - 2 * ShadowPlan::kMarginTexels, 1));
    return float(tile) / useful;
}

void plan_directional(const LightInstance& l, const CameraSetup& cam, const Bounds& scene, int cascades, int tile,
                      std::vector<ShadowTile>& out) {
    const glm::vec3 dir = glm::normalize(l.direction);
    const glm::mat4 view = light_view(glm::vec3(0.0f), dir);
    glm::vec3 lmin(std::numeric_limits<float>::max()), lmax(std::numeric_limits<float>::lowest());
    for (const glm::vec3& c : corners(scene)) {
        const glm::vec3 p = glm::vec3(view * glm::vec4(c, 1.0f));
        lmin = glm::min(lmin, p);
        lmax = glm::max(lmax, p);
    }
    // The part of the camera's depth range the scene occupies.
    float smin = std::numeric_limits<float>::max(), smax = 0.0f;
    for (const glm::vec3& c : corners(scene)) {
        const float d = -(cam.view * glm::vec4(c, 1.0f)).z;
        smin = std::min(smin, d);
        smax = std::max(smax, d);
    }
    float d0 = std::max(cam.znear, smin), d1 = std::min(cam.zfar, smax);
    if (!(d1 > d0)) d0 = cam.znear, d1 = cam.zfar;
    const float scale = margin_scale(tile);
    const float depth_pad = 0.01f * (lmax.z - lmin.z) + 1e-4f;
    for (int c = 0; c < cascades; ++c) {
        auto split = [&](int i) {
            const float f = float(i) / float(cascades);
            const float uniform = d0 + (d1 - d0) * f;
            const float logarithmic = d0 > 0.0f ? d0 * std::pow(d1 / d0, f) : uniform;
            return 0.5f * (uniform + logarithmic);
        };
        const std::array<glm::vec3, 8> slice = frustum_slice(cam, split(c), split(c + 1));
        glm::vec3 centre(0.0f);
        for (const glm::vec3& p : slice) centre += p / 8.0f;
        float radius = 0.0f;
        for (const glm::vec3& p : slice) radius = std::max(radius, glm::length(p - centre));
        const glm::vec3 lc = glm::vec3(view * glm::vec4(centre, 1.0f));
        // The slice's sphere, narrowed to the scene's box where that is smaller.
        glm::vec2 lo(lc.x - radius, lc.y - radius), hi(lc.x + radius, lc.y + radius);
        const glm::vec2 blo = glm::max(lo, glm::vec2(lmin)), bhi = glm::min(hi, glm::vec2(lmax));
        if (bhi.x > blo.x && bhi.y > blo.y) lo = blo, hi = bhi;
        const float extent = quantise_up(std::max(hi.x - lo.x, hi.y - lo.y)) * scale;
        const float texel = extent / float(tile);
        const glm::vec2 mid = glm::floor((lo + hi) * 0.5f / texel + 0.5f) * texel;
        const glm::mat4 projection = glm::ortho(mid.x - extent * 0.5f, mid.x + extent * 0.5f, mid.y - extent * 0.5f,
                                                mid.y + extent * 0.5f, -lmax.z - depth_pad, -lmin.z + depth_pad);
        ShadowTile t;
        t.view_projection = projection * view;
        t.texel_world = texel;
        t.far = (-lmin.z + depth_pad) - (-lmax.z - depth_pad);
        out.push_back(t);
    }
}

ShadowTile perspective_tile(glm::vec3 eye, glm::vec3 dir, glm::vec3 up, float half_tan, float near, float far,
                            int tile) {
    half_tan *= margin_scale(tile);
    ShadowTile t;
    t.view_projection =
        glm::perspective(2.0f * std::atan(half_tan), 1.0f, near, far) * light_view(eye, glm::normalize(dir), up);
    t.texel_world = 2.0f * half_tan / float(tile);
    t.near = near;
    t.far = far;
    return t;
}

}  // namespace

ShadowPlan plan_shadows(const std::vector<LightInstance>& lights, int light_count, const CameraSetup& camera,
                        const Bounds& scene, int map_size, int cascades, int max_texture_size) {
    ShadowPlan plan;
    plan_shadows(lights, light_count, camera, scene, map_size, cascades, max_texture_size, plan);
    return plan;
}

void plan_shadows(const std::vector<LightInstance>& lights, int light_count, const CameraSetup& camera,
                  const Bounds& scene, int map_size, int cascades, int max_texture_size, ShadowPlan& plan) {
    plan.atlas_width = plan.atlas_height = plan.tile_size = 0;
    plan.tiles.clear();
    const int n = std::clamp(light_count, 0, int(lights.size()));
    plan.lights.assign(std::size_t(n), LightShadow{});
    if (scene.empty || n == 0 || map_size <= 0) return;
    cascades = std::clamp(cascades, 1, 4);
    auto tiles_of = [&](const LightInstance& l) {
        // Point and area lights: a cube around the light's centre.
        return l.type == Light::Type::Directional ? cascades : l.type == Light::Type::Spot ? 1 : 6;
    };
    int count = 0;
    for (int i = 0; i < n; ++i) {
        const int k = tiles_of(lights[std::size_t(i)]);
        if (count + k > kMaxShadowTiles) continue;  // the lights after it may still fit
        plan.lights[std::size_t(i)] = {count, k};
        count += k;
    }
    if (count == 0) return;
    const int cols = int(std::ceil(std::sqrt(double(count))));
    const int rows = (count + cols - 1) / cols;
    int tile = map_size;
    const int max_side = std::max(max_texture_size, 64);
    constexpr double kMaxTexels = 4096.0 * 4096.0;
    while (tile > 16 && (cols * tile > max_side || rows * tile > max_side || double(count) * tile * tile > kMaxTexels))
        tile = std::max(16, int(tile * 0.875));
    plan.tile_size = tile;
    plan.atlas_width = cols * tile;
    plan.atlas_height = rows * tile;

    // Distances from a point light to the scene, for the depth ranges of its perspective maps.
    auto ranges = [&](const LightInstance& l) {
        auto [near, far] = box_distances(l.position, scene);
        if (l.range > 0.0f) far = std::min(far, l.range);
        far = std::max(far * 1.01f, 1e-3f);
        near = std::max(near * 0.9f, far * 2e-3f);
        return std::pair{near, std::max(far, near * 2.0f)};
    };
    for (int i = 0; i < n; ++i) {
        const LightShadow& ls = plan.lights[std::size_t(i)];
        if (ls.first_tile < 0) continue;
        const LightInstance& l = lights[std::size_t(i)];
        if (l.type == Light::Type::Directional) {
            plan_directional(l, camera, scene, cascades, tile, plan.tiles);
        } else if (l.type == Light::Type::Spot) {
            const auto [near, far] = ranges(l);
            const float half = std::tan(std::clamp(l.outer_cone, 0.01f, glm::radians(85.0f)));
            plan.tiles.push_back(perspective_tile(l.position, l.direction, glm::vec3(0, 1, 0), half, near, far, tile));
        } else {
            const auto [near, far] = ranges(l);
            static const glm::vec3 kFaces[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            for (int f = 0; f < 6; ++f) {
                const glm::vec3 up = f == 2 || f == 3 ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
                plan.tiles.push_back(perspective_tile(l.position, kFaces[f], up, 1.0f, near, far, tile));
            }
        }
    }
    for (int t = 0; t < int(plan.tiles.size()); ++t)
        plan.tiles[std::size_t(t)].rect = glm::ivec4((t % cols) * tile, (t / cols) * tile, tile, tile);
}

glm::mat4 tile_lookup_matrix(const ShadowTile& tile) {
    const glm::mat4 bias = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    return bias * tile.view_projection;
}

}  // namespace fresnel
