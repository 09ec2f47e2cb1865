#pragma once
// The CPU path tracer behind `fresnel trace`: unidirectional path tracing with next-event
// estimation (punctual lights and the environment, the environment importance-sampled and
// combined with BSDF sampling by multiple importance sampling, power heuristic), GGX
// visible-normal sampling, Russian roulette. Rays are Embree 3's.
//
// Conventions, as the rasteriser's where it has one:
//   - the scene is the flattened scene at rest (world-space triangles), cameras and lights as
//     fresnel::resolve() makes them (CameraSetup, LightInstance; light_incident() for the
//     punctual lights' range window and spot cones);
//   - materials through fresnel::evaluate (textures read at level 0, bilinear as the
//     sampler says: the samples of a pixel integrate over its footprint); the occlusion
//     texture is not used (the tracer computes occlusion); unlit materials emit their base
//     colour; roughness below kMinSampledRoughness is raised to it;
//   - single-sided materials: back faces are invisible to every ray (as the rasteriser culls
//     them); double-sided ones shade their back faces with the normal flipped;
//   - alpha: MASK below the cutoff is invisible, BLEND is stochastic opacity (a ray passes
//     with probability 1 - alpha);
//   - a bounce is one scattering event: max_bounces 1 is direct light (punctual lights and the
//     environment) at the first surface, the rasteriser's light transport;
//   - every sample of every pixel draws its own random numbers from (seed, pixel, sample):
//     the same seed gives the same image on any number of threads.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "fresnel/core/image.h"
#include "fresnel/ibl/cubemap.h"
#include "fresnel/material/brdf_model.h"
#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/job/render_settings.h"
#include "fresnel/scene/scene.h"
#include "fresnel/trace/environment_light.h"

namespace fresnel::trace {

struct TraceSettings {
    int width = 1024, height = 768;
    int samples = 64;         // per pixel
    int max_bounces = 16;     // scattering events per path (1 = direct light only)
    double time_limit_s = 0;  // > 0: stop after the pass during which this much time has passed
    // Set (by another thread or a signal handler): stop after the pass in progress (passes are
    // 1, 2, 4, then 8 samples per pixel), keeping every sample done (Ctrl+C in `fresnel trace`).
    const std::atomic<bool>* stop = nullptr;
    std::uint64_t seed = 0;
    unsigned threads = 0;          // 0 = all cores
    bool env_visibility = true;    // false: environment light is never shadowed (real-time IBL)
    bool env_background = true;    // camera rays that miss see the environment (else coverage 0)
    // Set (with env_background): camera rays that miss see this prefiltered cube (the environment's
    // bake, in the environment's frame) at level of detail `background_lod`, times the environment's
    // intensity: the rasteriser's blurred background (RenderSettings::Background::Blurred), so the
    // two front ends draw one background. Null: the panorama itself (sharp).
    const ibl::Cubemap* background_cube = nullptr;
    float background_lod = 0.0f;
    int russian_roulette_start = 3;  // bounces before Russian roulette may end a path
    brdf::BrdfModel brdf;            // the BRDF's terms (`--brdf`), for every light and bounce
    // The BRDF table (ibl::compute_brdf_lut, the rasteriser's): set, every bounce applies the
    // multiple-scattering energy compensation the rasteriser applies (fresnel::EnergyCompensation,
    // E from the table at n.v and roughness), so the two agree in the white furnace; null: the
    // single-scattering GGX, which loses energy on rough metals (0.36 of it at roughness 1).
    const ImageF* brdf_lut = nullptr;
};

struct TraceStats {
    int samples = 0;                  // per pixel, completed
    std::uint64_t camera_paths = 0;   // width * height * samples
    std::uint64_t rays = 0;           // every ray query (camera, continuation, shadow)
    double trace_ms = 0;
    bool time_limited = false;        // stopped by time_limit_s before `samples`
    bool stopped = false;             // stopped by TraceSettings::stop before `samples`
};

// Called after every tile with the fraction of the work done (from worker threads).
using TraceProgress = std::function<void(double fraction)>;

struct TraceSceneOptions {
    // A mesh that several nodes place is held once, in its own space, and placed by Embree
    // instances (EXT_mesh_gpu_instancing's instances, repeated parts, a scene file's copies):
    // memory and build time per mesh, not per placement. false builds every placement in
    // world space (tests compare the two).
    bool instancing = true;
};

// The scene as the tracer holds it: triangles in an Embree BVH (in world space, or once per
// mesh placed several times with an instance per placement), their vertex attributes,
// materials and the textures they read (decoded once). Build once, trace often.
class TraceScene {
public:
    TraceScene(const Scene& scene, const std::vector<NodeInstance>& instances, const TraceSceneOptions& options = {});
    ~TraceScene();
    TraceScene(const TraceScene&) = delete;
    TraceScene& operator=(const TraceScene&) = delete;
    std::size_t triangle_count() const;         // every placement's
    std::size_t stored_triangle_count() const;  // held: a mesh placed several times once
    std::size_t placement_count() const;        // Embree instances (TraceSceneOptions::instancing)
    double build_ms() const;
    // Whether a ray from the surface point `p` (normal `n`, which moves the origin off the
    // surface by a few ulps, as every bounce's) in the unit direction `d` meets a surface before
    // `tfar`. Surfaces are those every ray sees: single-sided back faces, MASK texels below the
    // cutoff and (with probability 1 - alpha, drawn from `seed`) BLEND surfaces let it pass.
    // Thread-safe (bake_vertex_occlusion calls it from every core).
    bool occluded(glm::vec3 p, glm::vec3 n, glm::vec3 d, float tfar, std::uint64_t seed) const;

    struct Impl;
    const Impl& impl() const { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

// Traces an image: RGB the mean radiance of each pixel's samples (linear, before exposure),
// A its coverage (the fraction of camera samples that hit the scene; 1 everywhere when the
// environment is the background). Rows top to bottom.
ImageF trace_image(const TraceScene& scene, const CameraSetup& camera, const std::vector<LightInstance>& lights,
                   const EnvironmentLight* environment, const TraceSettings& settings, TraceStats* stats = nullptr,
                   const TraceProgress& progress = {});

// What the camera sees at each pixel's centre, from one ray per pixel (no shading): the
// geometry a training pipeline or a compositor wants beside the image, exact (float32, no
// multisampling blend at edges). Rows top to bottom, row-major; a pixel with no surface has
// depth +infinity, zero vectors and material/node -1. The surfaces rays see are the tracer's:
// single-sided back faces and MASK texels below the cutoff are not hit; BLEND surfaces are
// hit with probability alpha (seed 0).
struct SurfaceImages {
    int width = 0, height = 0;
    std::vector<float> depth;             // distance from the eye along the view axis (linear depth)
    std::vector<float> position;          // world position, 3 per pixel
    std::vector<float> normal;            // shading normal (interpolated, facing the camera), 3 per pixel
    std::vector<float> geometric_normal;  // the triangle's normal (facing the camera), 3 per pixel
    std::vector<float> uv;                // TEXCOORD_0 (0,0 without), 2 per pixel
    std::vector<int> material;            // the scene's material index (-1: none or the default material)
    std::vector<int> node;                // the scene node whose mesh it is (-1: none)
};
SurfaceImages trace_surfaces(const TraceScene& scene, const CameraSetup& camera, int width, int height,
                             unsigned threads = 0);

// The traced radiance as `fresnel render` would write it with `settings` (exposure, tone
// mapper, encoding, background colour or transparency, premultiplied or straight alpha):
// display-encoded values in [0,1] when settings.encoding is set, else linear.
// Over a colour background, pixels are display(L) + (1 - coverage) * background: the radiance
// over black (what a path tracer's transparent film holds), then the background behind.
ImageF to_output(const ImageF& radiance, const RenderSettings& settings);

}  // namespace fresnel::trace
