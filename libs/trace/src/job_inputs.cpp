#include "fresnel/trace/job_inputs.h"

#include "fresnel/ibl/bake.h"
#include "fresnel/ibl/environment.h"

namespace fresnel::trace {

TraceSettings JobInputs::settings(const ResolvedJob& job, TraceSettings base) const {
    const RenderSettings& rs = job.settings;
    base.width = rs.width;
    base.height = rs.height;
    base.brdf = rs.brdf;
    base.brdf_lut = brdf_lut.pixels.empty() ? nullptr : &brdf_lut;
    base.env_background = rs.background_mode != RenderSettings::Background::Color;
    if (blurred_background && !blurred_background->specular.levels.empty()) {
        base.background_cube = &blurred_background->specular;
        base.background_lod = rs.blur_roughness * float(blurred_background->specular.levels.size() - 1);  // the sky pass's u_lod
    }
    return base;
}

JobInputs load_job_inputs(const ResolvedJob& job) {
    JobInputs in;
    const RenderSettings& rs = job.settings;
    if (job.environment) {
        // The whole environment: --env-light's split is the rasteriser's (the tracer shadows every light).
        ibl::EnvironmentSource src = *job.environment;
        src.split_dominant_light = false;
        if (src.kind == ibl::EnvironmentSource::Kind::File && ibl::is_baked_dir(src.path))
            throw Error(src.path.string(), "--env",
                        "a baked folder holds no panorama; trace needs the .hdr/.exr it was baked from");
        in.environment.emplace(ibl::load_panorama(src), rs.env_rotation_deg, rs.env_intensity);
        if (rs.background_mode == RenderSettings::Background::Blurred)
            in.blurred_background = ibl::load_or_bake(src, job.bake_options, {}, job.use_cache);
    }
    if (rs.energy_compensation) in.brdf_lut = ibl::load_or_bake_lut(job.bake_options, job.use_cache);
    return in;
}

std::optional<VertexOcclusion> job_vertex_occlusion(const Job& job, const Scene& scene, int scene_index,
                                                    const OcclusionProgress& progress) {
    if (job.output.ao != AmbientOcclusion::Baked) return std::nullopt;
    VertexOcclusionOptions bake;
    bake.rays = job.output.ao_rays;
    // Cached like baked environments (--no-cache: neither read nor written).
    return load_or_bake_vertex_occlusion(scene, flatten(scene, scene_index), bake, job.environment.use_cache,
                                         job.output.instancing, progress);
}

}  // namespace fresnel::trace
