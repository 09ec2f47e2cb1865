// The path tracer against scenes whose answer is known in closed form:
//  - white furnace: albedo-1 (Lambertian, no specular lobe) objects under a uniform
//    environment of radiance 1 are 1 everywhere, convex or not, with all bounces;
//  - a convex diffuse object of albedo a under a uniform environment of radiance L is L a;
//  - the inside of a closed diffuse sphere of albedo a whose wall emits Le: with at most N
//    bounces the radiance is Le (1 + a + ... + a^N), converging to Le / (1 - a);
//  - the glTF BRDF (specular lobe on) in the furnace: its directional albedo (brdf.h's quadrature);
//  - the same seed gives the same image on any number of threads, another seed another one;
//  - punctual lights: a diffuse plane under a directional light is E a / pi, its shadow is black.
// Tolerances are a few standard errors of the means measured (the pixels are averaged).
#include "fresnel/trace/tracer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fresnel/ibl/environment.h"
#include "fresnel/material/brdf.h"
#include "fresnel/job/camera.h"
#include "fresnel/scene/procedural.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

using namespace fresnel;
using namespace fresnel::trace;

namespace {

constexpr float kPi = 3.14159265358979323846f;

// A Lambertian material: KHR_materials_specular with factor 0 removes the dielectric lobe,
// leaving f = albedo / pi.
Material lambert(float albedo, bool double_sided = false) {
    Material m;
    m.base_color_factor = glm::vec4(albedo, albedo, albedo, 1.0f);
    m.metallic_factor = 0.0f;
    m.roughness_factor = 1.0f;
    m.specular = SpecularExt{};
    m.specular->specular_factor = 0.0f;
    m.double_sided = double_sided;
    return m;
}

// A scene of spheres (radius r at centres), all of material 0.
Scene spheres(const Material& material, const std::vector<glm::vec4>& centre_radius, bool inward = false) {
    Scene s;
    s.materials.push_back(material);
    Mesh mesh;
    Primitive p = make_uv_sphere(96, 48);
    p.material = 0;
    if (inward) {  // facing the centre: reversed winding and normals
        for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3) std::swap(p.indices[i + 1], p.indices[i + 2]);
        for (auto& n : p.normals) n = -n;
    }
    mesh.primitives.push_back(p);
    s.meshes.push_back(mesh);
    std::vector<int> roots;
    for (const glm::vec4& cr : centre_radius) {
        Node n;
        n.mesh = 0;
        n.local = glm::mat4(cr.w);
        n.local[3] = glm::vec4(glm::vec3(cr), 1.0f);
        roots.push_back(int(s.nodes.size()));
        s.nodes.push_back(n);
    }
    s.scenes.push_back(roots);
    return s;
}

struct Traced {
    ImageF image;
    TraceStats stats;
};

Traced run(const Scene& scene, const EnvironmentLight* env, const TraceSettings& ts, const OrbitParams& orbit = {},
             const std::vector<LightInstance>& lights = {}, const CameraSetup* camera = nullptr) {
    auto instances = flatten(scene);
    TraceScene tscene(scene, instances);
    CameraSetup cam = camera ? *camera : orbit_camera(scene_bounds(scene, instances), orbit, ts.width, ts.height);
    Traced t;
    t.image = trace_image(tscene, cam, lights, env, ts, &t.stats);
    return t;
}

// The mean radiance of channel `c` over what the camera sees of the scene: the sum of the
// (coverage-premultiplied) pixels over the sum of their coverage, so that silhouette pixels
// count by the part of them the object covers; and a standard error from the pixel spread
// of the fully covered pixels.
struct MeanErr {
    double mean = 0, err = 0;
    std::size_t n = 0;  // fully covered pixels
};
MeanErr covered_mean(const ImageF& img, int c = 0) {
    double s = 0, cov = 0, s1 = 0, s2 = 0;
    std::size_t n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* p = img.at(x, y);
            s += p[c];
            cov += p[3];
            if (p[3] < 1.0f) continue;
            s1 += p[c];
            s2 += double(p[c]) * p[c];
            ++n;
        }
    MeanErr m;
    m.n = n;
    if (n < 2 || cov <= 0) return m;
    m.mean = s / cov;
    double mean1 = s1 / double(n);
    m.err = std::sqrt(std::max(0.0, s2 / double(n) - mean1 * mean1) / double(n));
    return m;
}

TraceSettings small(int spp, int bounces = 16) {
    TraceSettings ts;
    ts.width = ts.height = 48;
    ts.samples = spp;
    ts.max_bounces = bounces;
    ts.env_background = false;
    ts.threads = 2;
    return ts;
}

}  // namespace

TEST(Tracer, WhiteFurnaceConvex) {
    EnvironmentLight env(ibl::make_uniform_panorama(glm::vec3(1.0f)));
    Traced t = run(spheres(lambert(1.0f), {{0, 0, 0, 1}}), &env, small(64));
    MeanErr m = covered_mean(t.image);
    ASSERT_GT(m.n, 300u);
    EXPECT_NEAR(m.mean, 1.0, 0.005) << "standard error " << m.err;
    // Every pixel away from the silhouette, not just the mean (64 samples each; the estimator
    // varies only through the MIS weights of the environment and BSDF samples, a standard
    // deviation of about 0.04 per pixel). At the
    // silhouette the interpolated normals and the facets disagree, and directions between
    // the two are lost (as in every tracer that keeps rays on the facet's side).
    auto covered = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < t.image.width && y < t.image.height && t.image.at(x, y)[3] == 1.0f;
    };
    int checked = 0;
    for (int y = 0; y < t.image.height; ++y)
        for (int x = 0; x < t.image.width; ++x) {
            if (!covered(x - 2, y) || !covered(x + 2, y) || !covered(x, y - 2) || !covered(x, y + 2)) continue;
            ASSERT_NEAR(t.image.at(x, y)[0], 1.0f, 0.2f) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 200);
}

TEST(Tracer, WhiteFurnaceInterreflection) {
    // Three overlapping spheres: light bounces between them; with every bounce the furnace is 1,
    // with one bounce the crevices are darker.
    Scene s = spheres(lambert(1.0f), {{-0.8f, 0, 0, 1}, {0.8f, 0, 0, 1}, {0, 0.9f, -0.3f, 0.8f}});
    EnvironmentLight env(ibl::make_uniform_panorama(glm::vec3(1.0f)));
    TraceSettings ts = small(64, 64);
    ts.russian_roulette_start = 1000;  // no roulette: the estimator stays 1 on every path
    Traced all = run(s, &env, ts);
    MeanErr m = covered_mean(all.image);
    ASSERT_GT(m.n, 500u);
    EXPECT_NEAR(m.mean, 1.0, 0.01) << "standard error " << m.err;
    Traced roulette = run(s, &env, small(64, 64));
    MeanErr mr = covered_mean(roulette.image);
    EXPECT_NEAR(mr.mean, 1.0, std::max(0.01, 4 * mr.err)) << "with Russian roulette";
    Traced one = run(s, &env, small(64, 1));
    EXPECT_LT(covered_mean(one.image).mean, 0.97);
}

TEST(Tracer, ConvexDiffuseIsAlbedoTimesRadiance) {
    const float a = 0.4f, L = 2.5f;
    EnvironmentLight env(ibl::make_uniform_panorama(glm::vec3(L)));
    for (int bounces : {1, 16}) {
        Traced t = run(spheres(lambert(a), {{0, 0, 0, 1}}), &env, small(16, bounces));
        MeanErr m = covered_mean(t.image);
        EXPECT_NEAR(m.mean, double(L * a), 0.01 * L * a) << bounces << " bounces, standard error " << m.err;
    }
}

TEST(Tracer, ClosedSphereGeometricSeries) {
    // Camera at the centre of a sphere that faces inwards, emits Le and reflects albedo a.
    const float a = 0.6f, Le = 0.5f;
    Material m = lambert(a);
    m.emissive_factor = glm::vec3(Le);
    Scene s = spheres(m, {{0, 0, 0, 1}}, true);
    CameraSetup cam;
    cam.eye = glm::vec3(0.0f);
    cam.view = glm::lookAt(glm::vec3(0.0f), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
    cam.projection = glm::perspective(glm::radians(60.0f), 1.0f, 0.01f, 10.0f);
    for (int n : {0, 1, 2, 4, 8, 32}) {
        TraceSettings ts = small(16, n);
        ts.width = ts.height = 24;
        ts.russian_roulette_start = 1000;
        Traced t = run(s, nullptr, ts, {}, {}, &cam);
        MeanErr me = covered_mean(t.image);
        ASSERT_EQ(me.n, std::size_t(ts.width * ts.height));
        if (n == 0) {
            EXPECT_NEAR(me.mean, Le, 1e-5);  // emission alone: exact
        }
        double expected = Le * (1.0 - std::pow(double(a), n + 1)) / (1.0 - a);
        EXPECT_NEAR(me.mean, expected, std::max(0.005 * expected, 4 * me.err)) << n << " bounces, standard error " << me.err;
    }
    // With Russian roulette (on by default) the limit Le / (1 - a).
    TraceSettings rr = small(16, 1000);
    rr.width = rr.height = 24;
    Traced t = run(s, nullptr, rr, {}, {}, &cam);
    MeanErr me = covered_mean(t.image);
    EXPECT_NEAR(me.mean, Le / (1.0 - a), std::max(0.01 * Le / (1.0 - a), 4 * me.err));
}

TEST(Tracer, GltfBrdfInTheFurnaceMatchesItsAlbedo) {
    // A sphere seen from far away (nearly orthographic): its mean is the directional albedo
    // E(mu) of the glTF BRDF averaged with the weight 2 mu over mu = n.v, which brdf.h's
    // quadrature computes independently of the tracer's sampling. (The glTF BRDF is not
    // energy conserving: the dielectric branch exceeds 1 a little, rough metals lose much.)
    EnvironmentLight env(ibl::make_uniform_panorama(glm::vec3(1.0f)));
    OrbitParams far;
    far.distance_k = 30.0f;
    far.yfov_deg = 4.0f;
    for (float metallic : {0.0f, 1.0f})
        for (float roughness : {0.2f, 0.5f, 1.0f}) {
            Material m;
            m.metallic_factor = metallic;
            m.roughness_factor = roughness;
            Traced t = run(spheres(m, {{0, 0, 0, 1}}), &env, small(32), far);
            MeanErr me = covered_mean(t.image);
            brdf::Surface s;
            s.metallic = metallic;
            s.perceptual_roughness = roughness;
            double expected = 0;
            const int n = 64;
            for (int i = 0; i < n; ++i) {
                float mu = (float(i) + 0.5f) / float(n);
                expected += brdf::directional_albedo(s, mu, 64).x * 2.0 * mu / n;
            }
            EXPECT_NEAR(me.mean, expected, std::max(0.015 * expected, 4 * me.err))
                << "metallic " << metallic << " roughness " << roughness;
        }
}

// The same with alternative BRDF terms (`--brdf`): the tracer evaluates the chosen terms (it
// samples GGX's lobe, which stays unbiased) and matches a quadrature of brdf::evaluate(model).
TEST(Tracer, AlternativeBrdfTermsInTheFurnaceMatchTheirAlbedo) {
    EnvironmentLight env(ibl::make_uniform_panorama(glm::vec3(1.0f)));
    OrbitParams far;
    far.distance_k = 30.0f;
    far.yfov_deg = 4.0f;
    const brdf::BrdfModel dielectric{brdf::Distribution::Beckmann, brdf::Geometry::CookTorrance,
                                     brdf::Fresnel::ExactDielectric, brdf::Diffuse::OrenNayar};
    // And F=exact on a metal: a measured gold conductor in place of the base colour.
    const brdf::BrdfModel gold{{}, {}, brdf::Fresnel::Exact, {}, brdf::Conductor::Gold};
    struct Case {
        brdf::BrdfModel model;
        float metallic, roughness;
    };
    for (const Case& k : {Case{dielectric, 0.0f, 0.5f}, Case{dielectric, 0.0f, 1.0f}, Case{gold, 1.0f, 0.5f}}) {
        const brdf::BrdfModel& model = k.model;
        const float roughness = k.roughness;
        SCOPED_TRACE(brdf::to_string(model));
        Material m;
        m.metallic_factor = k.metallic;
        m.roughness_factor = roughness;
        m.base_color_factor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
        TraceSettings ts = small(32);
        ts.brdf = model;
        Traced t = run(spheres(m, {{0, 0, 0, 1}}), &env, ts, far);
        MeanErr me = covered_mean(t.image);
        brdf::Surface s;
        s.base_color = glm::vec3(0.8f);
        s.metallic = k.metallic;
        s.perceptual_roughness = roughness;
        // E(mu) = integral of f cos over l (midpoint rule in cos(theta_l) and phi), weighted 2 mu.
        double expected = 0;
        const int n_mu = 32, n_c = 128, n_phi = 128;
        const glm::vec3 nrm(0, 0, 1);
        for (int i = 0; i < n_mu; ++i) {
            float mu = (float(i) + 0.5f) / float(n_mu);
            glm::vec3 v(std::sqrt(1.0f - mu * mu), 0.0f, mu);
            double e = 0;
            for (int a = 0; a < n_c; ++a) {
                float c = (float(a) + 0.5f) / float(n_c), sn = std::sqrt(1.0f - c * c);
                for (int b = 0; b < n_phi; ++b) {
                    float phi = 2.0f * kPi * (float(b) + 0.5f) / float(n_phi);
                    glm::vec3 l(sn * std::cos(phi), sn * std::sin(phi), c);
                    e += brdf::evaluate(s, nrm, v, l, model).x * c;
                }
            }
            e *= 2.0 * kPi / (double(n_c) * n_phi);
            expected += e * 2.0 * mu / n_mu;
        }
        EXPECT_NEAR(me.mean, expected, std::max(0.015 * expected, 4 * me.err)) << "roughness " << roughness;
        // And the terms matter: the default BRDF's albedo is measurably different.
        ts.brdf = {};
        Traced d = run(spheres(m, {{0, 0, 0, 1}}), &env, ts, far);
        EXPECT_GT(std::abs(covered_mean(d.image).mean - me.mean), 4 * me.err) << "roughness " << roughness;
    }
}

TEST(Tracer, SameSeedSameImage) {
    Scene s = make_demo_scene();
    EnvironmentLight env(ibl::make_studio_panorama(256), 30.0f);
    TraceSettings ts = small(4);
    ts.env_background = true;
    ts.seed = 7;
    ts.threads = 1;
    Traced a = run(s, &env, ts);
    ts.threads = 2;
    Traced b = run(s, &env, ts);
    EXPECT_EQ(a.image.pixels, b.image.pixels);
    ts.seed = 8;
    Traced c = run(s, &env, ts);
    EXPECT_NE(a.image.pixels, c.image.pixels);
    EXPECT_EQ(a.stats.samples, 4);
    EXPECT_EQ(a.stats.camera_paths, std::uint64_t(48 * 48 * 4));
}

TEST(Tracer, DirectionalLightAndShadow) {
    // A diffuse floor (a flattened sphere's top) under a light arriving at 45 degrees, a small
    // sphere floating over it: E cos45 a / pi on the lit floor and the ball's top, 0 in the
    // ball's shadow, which falls 1 unit towards +X.
    Scene s = spheres(lambert(0.5f), {});
    Node floor;
    floor.mesh = 0;
    floor.local = glm::scale(glm::mat4(1.0f), glm::vec3(4.0f, 0.01f, 4.0f));
    Node ball;
    ball.mesh = 0;
    ball.local = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1.0f, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.3f));
    s.nodes = {floor, ball};
    s.scenes = {{0, 1}};
    LightInstance sun;
    sun.type = Light::Type::Directional;
    sun.direction = glm::normalize(glm::vec3(1, -1, 0));
    sun.radiance = glm::vec3(3.0f);
    CameraSetup cam;  // from above, +X to the right of the image
    cam.view = glm::lookAt(glm::vec3(0, 5, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1));
    cam.projection = glm::perspective(glm::radians(40.0f), 1.0f, 0.1f, 20.0f);
    TraceSettings ts = small(4, 1);
    Traced t = run(s, nullptr, ts, {}, {sun}, &cam);
    const float lit = 3.0f * std::sqrt(0.5f) * 0.5f / kPi;
    // The ball's top: the two pixels either side of its pole (normals tilted by up to 10
    // degrees either way, and interpolated across the UV sphere's pole).
    EXPECT_NEAR(0.5f * (t.image.at(23, 24)[0] + t.image.at(24, 24)[0]), lit, 0.04f * lit);
    EXPECT_NEAR(t.image.at(8, 24)[0], lit, 0.02f);   // open floor at x = -1.2
    // The shadow's centre: x = 0.99 (the ball's height above the floor), ~13 pixels right.
    int shadow_x = 24 + int(std::lround(0.99f / (5.0f * std::tan(glm::radians(20.0f))) * 24.0f));
    EXPECT_LT(t.image.at(shadow_x, 24)[0], 0.01f * lit) << "column " << shadow_x;
    EXPECT_GT(t.image.at(shadow_x, 24)[3], 0.99f);
}

TEST(Tracer, DiffuseTransmissionIsLitFromBehind) {
    // KHR_materials_diffuse_transmission: a Lambertian quad lit only from below at 45 degrees
    // shows, from above, E cos45 dt colour / pi (the transmitted lobe, reached by next-event
    // estimation through the surface); without the extension, black.
    Material m = lambert(0.5f, true);
    DiffuseTransmissionExt dt;
    dt.diffuse_transmission_factor = 0.6f;
    dt.diffuse_transmission_color_factor = glm::vec3(0.9f, 0.5f, 0.2f);
    m.diffuse_transmission = dt;
    Scene s = spheres(m, {});
    Primitive quad;
    quad.positions = {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}};
    quad.normals.assign(4, glm::vec3(0, 1, 0));
    quad.indices = {0, 1, 2, 0, 2, 3};
    quad.material = 0;
    s.meshes[0].primitives = {quad};
    Node floor;
    floor.mesh = 0;
    s.nodes = {floor};
    s.scenes = {{0}};
    LightInstance sun;
    sun.type = Light::Type::Directional;
    sun.direction = glm::normalize(glm::vec3(1, 1, 0));  // travelling upwards: the floor's underside is lit
    sun.radiance = glm::vec3(3.0f);
    CameraSetup cam;
    cam.view = glm::lookAt(glm::vec3(0, 5, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1));
    cam.projection = glm::perspective(glm::radians(40.0f), 1.0f, 0.1f, 20.0f);
    Traced t = run(s, nullptr, small(4, 1), {}, {sun}, &cam);
    const glm::vec3 want = 3.0f * std::sqrt(0.5f) * 0.6f * glm::vec3(0.9f, 0.5f, 0.2f) / kPi;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t.image.at(8, 24)[c], want[c], 0.02f * want[c] + 1e-4f) << c;
    s.materials[0].diffuse_transmission.reset();
    Traced none = run(s, nullptr, small(4, 1), {}, {sun}, &cam);
    EXPECT_LT(none.image.at(8, 24)[0], 1e-4f);
}

TEST(Tracer, OneBounceUnshadowedEnvironmentIsTheRasterisersTransport) {
    // --bounces 1 --no-env-visibility: direct light only and the environment never shadowed,
    // so even where three spheres occlude each other a Lambertian surface of albedo a under a
    // uniform radiance L is exactly L a (what a rasteriser's irradiance gives); with
    // visibility the crevices are darker, with all bounces brighter again.
    const float a = 0.7f, L = 1.5f;
    Scene s = spheres(lambert(a), {{-0.8f, 0, 0, 1}, {0.8f, 0, 0, 1}, {0, 0.9f, -0.3f, 0.8f}});
    EnvironmentLight env(ibl::make_uniform_panorama(glm::vec3(L)));
    TraceSettings ts = small(32, 1);
    ts.env_visibility = false;
    Traced unshadowed = run(s, &env, ts);
    MeanErr mu = covered_mean(unshadowed.image);
    EXPECT_NEAR(mu.mean, double(L * a), 0.01 * L * a) << "standard error " << mu.err;
    ts.env_visibility = true;
    MeanErr ms = covered_mean(run(s, &env, ts).image);
    EXPECT_LT(ms.mean, 0.97 * L * a);
    ts.max_bounces = 16;
    MeanErr mall = covered_mean(run(s, &env, ts).image);
    EXPECT_GT(mall.mean, ms.mean + 3 * (mall.err + ms.err));
    EXPECT_LT(mall.mean, L * a);
}

TEST(Tracer, PointAndSpotLightsFollowTheExtension) {
    // light_incident (the twin of shaders/lights.glsl): 1/d^2, the range window
    // clamp(1 - (d/range)^4, 0, 1), and the spot's smooth cone between inner and outer angles.
    LightInstance point;
    point.type = Light::Type::Point;
    point.position = glm::vec3(0, 2, 0);
    point.radiance = glm::vec3(8.0f);
    glm::vec3 l;
    float d = 0;
    EXPECT_NEAR(light_incident(point, glm::vec3(0), l, d).x, 8.0f / 4.0f, 1e-5f);
    EXPECT_NEAR(d, 2.0f, 1e-6f);
    EXPECT_NEAR(l.y, 1.0f, 1e-6f);
    point.range = 4.0f;
    EXPECT_NEAR(light_incident(point, glm::vec3(0), l, d).x, 2.0f * (1.0f - 0.0625f), 1e-5f);
    EXPECT_EQ(light_incident(point, glm::vec3(0, -3, 0), l, d).x, 0.0f);  // beyond the range
    LightInstance spot = point;
    spot.type = Light::Type::Spot;
    spot.range = 0.0f;
    spot.direction = glm::vec3(0, -1, 0);
    spot.inner_cone = glm::radians(10.0f);
    spot.outer_cone = glm::radians(20.0f);
    EXPECT_NEAR(light_incident(spot, glm::vec3(0), l, d).x, 2.0f, 1e-5f);  // on the axis
    EXPECT_EQ(light_incident(spot, glm::vec3(2.0f * std::tan(glm::radians(25.0f)), 0, 0), l, d).x, 0.0f);
    float half = light_incident(spot, glm::vec3(2.0f * std::tan(glm::radians(15.0f)), 0, 0), l, d).x;
    EXPECT_GT(half, 0.0f);
    EXPECT_LT(half, 2.0f);

    // Through the tracer: a diffuse floor lit by the point light from 2 units above is
    // I / d^2 * a / pi under the light.
    Scene s = spheres(lambert(0.5f), {});
    Node floor;
    floor.mesh = 0;
    floor.local = glm::scale(glm::mat4(1.0f), glm::vec3(4.0f, 0.01f, 4.0f));
    s.nodes = {floor};
    s.scenes = {{0}};
    CameraSetup cam;
    cam.view = glm::lookAt(glm::vec3(0, 5, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1));
    cam.projection = glm::perspective(glm::radians(4.0f), 1.0f, 0.1f, 20.0f);  // cos^3 falloff < 1.5 % in view
    point.range = 0.0f;
    point.position = glm::vec3(0, 2.01f, 0);
    Traced t = run(s, nullptr, small(4, 1), {}, {point}, &cam);
    EXPECT_NEAR(covered_mean(t.image).mean, 8.0 / 4.0 * 0.5 / kPi, 0.02 * 8.0 / 4.0 * 0.5 / kPi);
}

// KHR_materials_transmission in the tracer: a white glass sphere with no reflection (specular
// factor 0) passes the uniform environment through (1); with KHR_materials_volume its path
// leaves after the thickness-scaled refracted ray, which has the length of the thickness, so an
// attenuation colour 0.5 at attenuationDistance = thickness halves it everywhere (an opaque
// Lambertian sphere of the same base colour would stay at 1).
TEST(Tracer, TransmissionAndVolumeAttenuation) {
    EnvironmentLight env(ibl::make_uniform_panorama(glm::vec3(1.0f)));
    Material glass = lambert(1.0f);
    glass.roughness_factor = 0.0f;
    glass.transmission = TransmissionExt{1.0f, {}};
    Traced thin = run(spheres(glass, {{0, 0, 0, 1}}), &env, small(32));
    MeanErr m = covered_mean(thin.image);
    ASSERT_GT(m.n, 300u);
    EXPECT_NEAR(m.mean, 1.0, 0.03) << "standard error " << m.err;
    VolumeExt vol;
    vol.thickness_factor = 2.0f;
    vol.attenuation_color = glm::vec3(0.5f);
    vol.attenuation_distance = 2.0f;
    glass.volume = vol;
    Traced thick = run(spheres(glass, {{0, 0, 0, 1}}), &env, small(32));
    MeanErr a = covered_mean(thick.image);
    ASSERT_GT(a.n, 300u);
    EXPECT_NEAR(a.mean, 0.5, 0.05) << "standard error " << a.err;
}

// trace_surfaces against a sphere whose answer is known: at the image centre the ray meets the
// sphere's nearest point, at distance D - r along the view axis, normal towards the camera;
// corners see nothing; ids name the material and the node; the depth grows off-centre as the
// sphere curves away, and every hit lies on the sphere.
TEST(TraceSurfaces, SphereDepthNormalsAndIds) {
    Scene s = spheres(lambert(0.5f), {glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), glm::vec4(0.0f, 0.0f, -40.0f, 1.0f)});
    auto instances = flatten(s);
    TraceScene tscene(s, instances);
    Bounds box;
    box.min = glm::vec3(-1.0f);
    box.max = glm::vec3(1.0f);
    box.empty = false;
    CameraSetup cam = look_at_camera(box, glm::vec3(0.0f, 0.0f, 5.0f),
                                     glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 30.0f, 65, 49);
    SurfaceImages g = trace_surfaces(tscene, cam, 65, 49, 1);
    ASSERT_EQ(g.width, 65);
    ASSERT_EQ(g.depth.size(), std::size_t(65 * 49));
    const std::size_t c = std::size_t(24) * 65 + 32;  // the centre pixel
    EXPECT_NEAR(g.depth[c], 4.0f, 2e-3f);  // a 96x48 sphere is within 1e-3 of the true one there
    EXPECT_NEAR(g.normal[c * 3 + 2], 1.0f, 1e-3f);
    EXPECT_NEAR(g.geometric_normal[c * 3 + 2], 1.0f, 1e-2f);
    EXPECT_NEAR(g.position[c * 3 + 2], 1.0f, 2e-3f);
    EXPECT_EQ(g.material[c], 0);
    EXPECT_EQ(g.node[c], 0);  // the near sphere, not the one behind it
    EXPECT_TRUE(std::isinf(g.depth[0]));
    EXPECT_EQ(g.material[0], -1);
    EXPECT_EQ(g.node[0], -1);
    int hits = 0;
    for (std::size_t i = 0; i < g.depth.size(); ++i) {
        if (!std::isfinite(g.depth[i])) continue;
        ++hits;
        glm::vec3 p(g.position[i * 3], g.position[i * 3 + 1], g.position[i * 3 + 2]);
        EXPECT_NEAR(glm::length(p), 1.0f, 5e-3f);
        EXPECT_GE(g.depth[i], g.depth[c] - 1e-4f);
        EXPECT_NEAR(g.depth[i], 5.0f - p.z, 1e-4f);  // depth is along the view axis
    }
    EXPECT_GT(hits, 100);
    // The same on two threads.
    SurfaceImages g2 = trace_surfaces(tscene, cam, 65, 49, 2);
    EXPECT_EQ(g2.depth, g.depth);
    EXPECT_EQ(g2.node, g.node);
}

// A mesh placed several times is held once and placed by Embree instances
// (TraceSceneOptions::instancing): the image and the surfaces are those of the placements built
// in world space. Placements turned, scaled unevenly (the normal matrix matters) and mirrored
// (clockwise triangles face front), single-sided (back faces are not hit), with tangents (the
// bitangent follows the handedness) and one mesh placed once (built in world space either way).
TEST(Tracer, InstancedPlacementsTraceAsWorldSpaceCopies) {
    Material shiny;
    shiny.base_color_factor = glm::vec4(0.8f, 0.6f, 0.4f, 1.0f);
    shiny.roughness_factor = 0.3f;
    shiny.metallic_factor = 0.5f;
    shiny.anisotropy = AnisotropyExt{};  // reads the tangent frame
    shiny.anisotropy->anisotropy_strength = 0.6f;
    Scene s = spheres(shiny, {});
    Primitive& sphere = s.meshes[0].primitives[0];
    sphere.tangents.resize(sphere.positions.size());
    for (std::size_t v = 0; v < sphere.positions.size(); ++v)
        sphere.tangents[v] = glm::vec4(glm::normalize(glm::cross(glm::vec3(0, 1, 0), sphere.normals[v]) + glm::vec3(1e-3f)), 1.0f);
    s.materials.push_back(lambert(0.6f));
    Mesh floor_mesh;
    Primitive floor = make_uv_sphere(32, 16);
    floor.material = 1;
    floor_mesh.primitives.push_back(floor);
    s.meshes.push_back(floor_mesh);
    std::vector<int> roots;
    for (int k = 0; k < 6; ++k) {
        Node n;
        n.mesh = 0;
        n.local = glm::translate(glm::mat4(1.0f), glm::vec3(-2.5f + float(k % 3) * 2.5f, 1.0f, -1.2f + float(k / 3) * 2.4f)) *
                  glm::rotate(glm::mat4(1.0f), 0.7f * float(k), glm::normalize(glm::vec3(1, 2, 0.5f))) *
                  glm::scale(glm::mat4(1.0f), glm::vec3(k % 2 ? -1.0f : 1.0f, 0.6f + 0.15f * float(k), 0.9f));
        roots.push_back(int(s.nodes.size()));
        s.nodes.push_back(n);
    }
    Node ground;
    ground.mesh = 1;
    ground.local = glm::scale(glm::mat4(1.0f), glm::vec3(6.0f, 0.05f, 6.0f));
    roots.push_back(int(s.nodes.size()));
    s.nodes.push_back(ground);
    s.scenes = {roots};
    const auto instances = flatten(s);
    TraceScene flat(s, instances, TraceSceneOptions{false});
    TraceScene placed(s, instances);
    EXPECT_EQ(flat.placement_count(), 0u);
    EXPECT_EQ(placed.placement_count(), 6u);
    EXPECT_EQ(placed.triangle_count(), flat.triangle_count());
    EXPECT_LT(placed.stored_triangle_count() * 3, flat.stored_triangle_count());

    EnvironmentLight env(ibl::make_studio_panorama(128), 30.0f);
    LightInstance sun;
    sun.type = Light::Type::Directional;
    sun.direction = glm::normalize(glm::vec3(0.5f, -1, 0.3f));
    sun.radiance = glm::vec3(2.0f);
    TraceSettings ts = small(16, 4);
    ts.width = 96;
    ts.height = 64;
    ts.seed = 3;
    const CameraSetup cam = look_at_camera(scene_bounds(s, instances), glm::vec3(0.0f, 6.0f, 6.0f), glm::vec3(0.0f, 0.5f, 0.0f),
                                           glm::vec3(0.0f, 1.0f, 0.0f), 45.0f, ts.width, ts.height);
    const ImageF a = trace_image(flat, cam, {sun}, &env, ts);
    const ImageF b = trace_image(placed, cam, {sun}, &env, ts);
    // The same paths but where a ray meets an edge within rounding (an instance intersects in
    // the mesh's space): a few pixels differ by their samples' noise, the mean not at all.
    double diff = 0, sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        diff += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
        sum += std::abs(double(a.pixels[i]));
    }
    std::printf("instanced against world-space copies: mean |difference| %.2e of mean %.3f\n",
                diff / double(a.pixels.size()), sum / double(a.pixels.size()));
    EXPECT_LT(diff, 0.01 * sum);

    const SurfaceImages fa = trace_surfaces(flat, cam, ts.width, ts.height, 1);
    const SurfaceImages fb = trace_surfaces(placed, cam, ts.width, ts.height, 1);
    int same_node = 0, hits = 0;
    float worst_normal = 0.0f, worst_depth = 0.0f;
    for (std::size_t i = 0; i < fa.depth.size(); ++i) {
        if (!std::isfinite(fa.depth[i])) continue;
        ++hits;
        if (fa.node[i] != fb.node[i]) continue;
        ++same_node;
        worst_depth = std::max(worst_depth, std::abs(fa.depth[i] - fb.depth[i]));
        for (int c = 0; c < 3; ++c)
            worst_normal = std::max({worst_normal, std::abs(fa.normal[i * 3 + c] - fb.normal[i * 3 + c]),
                                     std::abs(fa.geometric_normal[i * 3 + c] - fb.geometric_normal[i * 3 + c])});
    }
    std::printf("surfaces: %d of %d hits on the same node; worst depth %.2e, normal %.2e\n", same_node, hits,
                double(worst_depth), double(worst_normal));
    EXPECT_GT(hits, 1000);
    EXPECT_GE(same_node, hits - 4);
    EXPECT_LT(worst_depth, 1e-3f);
    EXPECT_LT(worst_normal, 1e-3f);
}
