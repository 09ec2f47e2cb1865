// The path tracer's area lights (fresnel/trace/area_lights.h): a sampled point and the ray that
// meets it agree on direction, distance and density; the samples' irradiance estimates converge
// to the closed forms (a disk seen on its axis, a sphere above the horizon) and to the exact
// polygon form factor of a rectangle (fresnel/material/ltc.h with the identity); the back of a
// one-sided light and the inside of a sphere give nothing.
#include "fresnel/trace/area_lights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "fresnel/material/ltc.h"
#include "fresnel/material/sampling.h"

using namespace fresnel;
using namespace fresnel::trace;

namespace {

constexpr float kPi = 3.14159265358979f;

// A low-discrepancy point set: the estimates below converge fast enough to test tightly.
using sampling::hammersley;

// Irradiance at p with normal n: the mean of L cos / pdf over n samples.
double irradiance(const LightInstance& light, glm::vec3 p, glm::vec3 n, std::uint32_t count = 1 << 16) {
    double sum = 0.0;
    for (std::uint32_t i = 0; i < count; ++i) {
        AreaLightSample s = sample_area_light(light, p, hammersley(i, count));
        if (s.pdf > 0.0f) sum += double(s.radiance.x) * std::max(0.0, double(glm::dot(s.l, n))) / double(s.pdf);
    }
    return sum / double(count);
}

std::vector<LightInstance> lights() {
    return {parse_light("rect:0.3,2,-0.2,20,70,1.5,0.75,1"), parse_light("disk:0,1.5,0,0,90,0.6,1"),
            parse_light("sphere:0.5,1.2,0.4,0.3,1"), parse_light("tube:0.2,1.0,-0.3,60,20,1.4,0.12,1")};
}

// Irradiance at p with normal n the other way: cosine-distributed directions and the light they
// meet (pi L times the fraction that do), the BSDF-sampled half of the tracer's MIS.
double irradiance_by_rays(const LightInstance& light, glm::vec3 p, glm::vec3 n, std::uint32_t count = 1 << 18) {
    const glm::vec3 t1 = glm::normalize(glm::cross(std::abs(n.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), n));
    const glm::vec3 t2 = glm::cross(n, t1);
    double sum = 0.0;
    for (std::uint32_t i = 0; i < count; ++i) {
        const glm::vec2 u = hammersley(i, count);
        const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
        const glm::vec3 d = glm::normalize(r * std::cos(phi) * t1 + r * std::sin(phi) * t2 + std::sqrt(std::max(0.0f, 1.0f - u.x)) * n);
        float pdf = 0.0f, t = 0.0f;
        const glm::vec3 le = area_light_hit(light, p, d, 1e9f, pdf, t);
        if (pdf > 0.0f) sum += double(le.x) * kPi;
    }
    return sum / double(count);
}

}  // namespace

TEST(AreaLights, SampledPointsAndTheirRaysAgree) {
    const glm::vec3 points[] = {{0, 0, 0}, {1.5f, 0.2f, -0.7f}, {-2, 0.5f, 1}};
    for (const LightInstance& light : lights())
        for (glm::vec3 p : points) {
            int valid = 0;
            for (std::uint32_t i = 0; i < 256; ++i) {
                AreaLightSample s = sample_area_light(light, p, hammersley(i, 256));
                if (!(s.pdf > 0.0f)) continue;
                ++valid;
                // A tube's points seen edge on (the cosine at the light, d^2 / (area pdf), under
                // 0.05) are left out: there its density moves with the last bits of the hit.
                if (light.type == Light::Type::Tube && s.distance * s.distance / (light.area() * s.pdf) < 0.05f) continue;
                float pdf = 0.0f, t = 0.0f;
                glm::vec3 le = area_light_hit(light, p, s.l, 1e9f, pdf, t);
                ASSERT_GT(pdf, 0.0f) << light_spec(light) << " sample " << i << " misses its own light";
                // (A tube's quadratic loses a few bits: its densities agree to 1 %, the others' to 0.2 %.)
                EXPECT_NEAR(pdf / s.pdf, 1.0f, light.type == Light::Type::Tube ? 1e-2f : 2e-3f) << light_spec(light);
                EXPECT_NEAR(t, s.distance, 1e-3f * s.distance) << light_spec(light);
                EXPECT_EQ(le, s.radiance);
                // Something nearer on the way hides nothing (lights block no ray), but a ray
                // shorter than the light's distance does not reach it.
                area_light_hit(light, p, s.l, 0.5f * s.distance, pdf, t);
                EXPECT_EQ(pdf, 0.0f);
            }
            EXPECT_GT(valid, 0) << light_spec(light);
        }
}

TEST(AreaLights, IrradianceConvergesToTheClosedForms) {
    // A disk of radius R at height h, facing the point on its axis: E = pi L R^2 / (h^2 + R^2).
    LightInstance disk = parse_light("disk:0,1.5,0,0,90,0.6,1");
    const double e_disk = kPi * 0.36 / (2.25 + 0.36);
    EXPECT_NEAR(irradiance(disk, {0, 0, 0}, {0, 1, 0}), e_disk, 2e-3 * e_disk);
    // A sphere wholly above the horizon: E = pi L (r / d)^2 cos(theta).
    LightInstance sphere = parse_light("sphere:0.5,1.2,0.4,0.3,1");
    const glm::vec3 to = glm::vec3(0.5f, 1.2f, 0.4f);
    const double d = glm::length(to), e_sphere = kPi * 0.09 / (d * d) * (1.2 / d);
    EXPECT_NEAR(irradiance(sphere, {0, 0, 0}, {0, 1, 0}), e_sphere, 2e-3 * e_sphere);
    // A tilted rectangle: pi L times its exact form factor (the identity LTC's polygon sum).
    LightInstance rect = parse_light("rect:0.3,2,-0.2,20,70,1.5,0.75,1");
    const glm::vec3 c = rect.position;
    const glm::vec3 corners[4] = {c - rect.axis_u - rect.axis_v, c + rect.axis_u - rect.axis_v,
                                  c + rect.axis_u + rect.axis_v, c - rect.axis_u + rect.axis_v};
    const double e_rect = kPi * ltc::polygon_integral(glm::mat3(1.0f), {0, 1, 0}, {0, 0, 1}, corners, 4);
    ASSERT_GT(e_rect, 0.01);
    EXPECT_NEAR(irradiance(rect, {0, 0, 0}, {0, 1, 0}), e_rect, 3e-3 * e_rect);
}

// The two halves of the tracer's multiple importance sampling estimate the same irradiance: points
// sampled on each light (their densities) and cosine-distributed rays meeting it (its shape). For
// the tube, whose closed form is not simple, this is the check of its sampling and its
// intersection; the LTC polygon's estimate of it (a rectangle over its silhouette, lengthened for
// the round ends) is printed beside them.
TEST(AreaLights, SampledPointsAndSampledRaysAgree) {
    const glm::vec3 p(0.1f, 0.0f, 0.2f), n(0.0f, 1.0f, 0.0f);
    for (const LightInstance& light : lights()) {
        const double by_points = irradiance(light, p, n), by_rays = irradiance_by_rays(light, p, n);
        std::printf("%s: irradiance %.5f by points on the light, %.5f by rays\n", light_spec(light).c_str(), by_points, by_rays);
        ASSERT_GT(by_points, 1e-3);
        EXPECT_NEAR(by_rays / by_points, 1.0, 0.01) << light_spec(light);
    }
}

TEST(AreaLights, BacksAndInsidesGiveNothing) {
    LightInstance disk = parse_light("disk:0,1.5,0,0,90,0.6,1");  // faces down
    EXPECT_EQ(irradiance(disk, {0, 3, 0}, {0, -1, 0}, 256), 0.0) << "above a light facing down";
    float pdf = 1.0f, t = 0.0f;
    EXPECT_EQ(area_light_hit(disk, {0, 3, 0}, {0, -1, 0}, 1e9f, pdf, t), glm::vec3(0.0f));
    EXPECT_EQ(pdf, 0.0f) << "a ray meeting the back";
    LightInstance sphere = parse_light("sphere:0,0,0,1,1");
    EXPECT_EQ(sample_area_light(sphere, {0.2f, 0, 0}, {0.5f, 0.5f}).pdf, 0.0f) << "inside";
    LightInstance tube = parse_light("tube:0,0,0,0,0,2,0.5,1");
    EXPECT_EQ(sample_area_light(tube, {0.1f, 0.1f, 0.5f}, {0.5f, 0.5f}).pdf, 0.0f) << "inside the tube";
}
