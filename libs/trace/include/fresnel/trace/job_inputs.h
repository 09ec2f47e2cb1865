#pragma once
// What a resolved job (fresnel/job/job.h: resolve()) is traced with, for every front end of the
// tracer (`fresnel trace`, the Python module): the job's environment as a light, the rasteriser's
// BRDF table when the job keeps energy compensation, and the settings the job decides.
#include <optional>

#include "fresnel/core/image.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/job/job.h"
#include "fresnel/trace/environment_light.h"
#include "fresnel/trace/tracer.h"
#include "fresnel/trace/vertex_occlusion.h"

namespace fresnel::trace {

struct JobInputs {
    std::optional<EnvironmentLight> environment;  // none: the job has no image-based light
    ImageF brdf_lut;                              // empty: the job turns energy compensation off
    // The environment's bake (as the rasteriser loads it, from the same cache) when the job's
    // background is the blurred environment: camera rays that miss see its prefiltered level, as
    // the rasteriser draws it (TraceSettings::background_cube).
    std::optional<ibl::BakedIbl> blurred_background;
    const EnvironmentLight* light() const { return environment ? &*environment : nullptr; }
    // `base` (samples, bounces, seed, threads, ...) with what the job decides: the image size, the
    // BRDF's terms, the energy model (pointing at brdf_lut, so this must outlive the trace) and
    // whether camera rays that miss see the environment (env and blur backgrounds; not a colour),
    // and for blur the prefiltered level the rasteriser shows.
    TraceSettings settings(const ResolvedJob& job, TraceSettings base) const;
};

// Loads the job's environment panorama (a folder made by `fresnel bake` is refused: it holds no
// panorama) and, with energy compensation, the BRDF table (from the cache the rasteriser uses).
// Throws fresnel::Error naming the file.
JobInputs load_job_inputs(const ResolvedJob& job);

// The rasteriser's baked occlusion for `job` (Job::Output::ao baked; nothing when it asks for
// none): `scene` (scene `scene_index`, in its current pose) in a TraceScene, then
// bake_vertex_occlusion with the job's rays per vertex. Every front end that rasterises a job
// (render, batch, view, Python) calls this and hands the result to Renderer::set_vertex_occlusion.
std::optional<VertexOcclusion> job_vertex_occlusion(const Job& job, const Scene& scene, int scene_index,
                                                    const OcclusionProgress& progress = {});

}  // namespace fresnel::trace
