#pragma once
// fresnel as a library: every layer's public headers and fresnel::version().
// Link fresnel::fresnel (CMake: find_package(fresnel REQUIRED)). Layers, bottom up:
// core (errors, colour, images), material (the material model, evaluate, the BRDF), scene
// (the scene model, mesh operations, the glTF and OBJ loaders), ibl (environments, baking),
// job (what to render, GL-free: jobs, settings, scene files, cameras, lights), gpu (OpenGL
// contexts and objects), render (the rasteriser), trace (the CPU path tracer).
#include "fresnel/core/version.h"

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/core/float_text.h"
#include "fresnel/core/heatmap.h"
#include "fresnel/core/json_text.h"
#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"
#include "fresnel/core/mipmap.h"
#include "fresnel/core/parallel.h"
#include "fresnel/core/sampler.h"
#include "fresnel/core/spelling.h"

#include "fresnel/scene/animation.h"
#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/merge.h"
#include "fresnel/scene/mesh_ops.h"
#include "fresnel/scene/obj_loader.h"
#include "fresnel/scene/paths.h"
#include "fresnel/scene/pick.h"
#include "fresnel/scene/pose.h"
#include "fresnel/scene/procedural.h"
#include "fresnel/scene/scene_writer.h"
#include "fresnel/scene/scene.h"
#include "fresnel/scene/scene_textures.h"
#include "fresnel/scene/tangents.h"

#include "fresnel/material/brdf.h"
#include "fresnel/material/brdf_model.h"
#include "fresnel/material/bsdf.h"
#include "fresnel/material/evaluate.h"
#include "fresnel/material/fit.h"
#include "fresnel/material/material.h"
#include "fresnel/material/legacy_shading.h"
#include "fresnel/material/phong.h"
#include "fresnel/material/properties.h"
#include "fresnel/material/sampling.h"
#include "fresnel/material/texture.h"
#include "fresnel/material/transmission.h"

#include "fresnel/ibl/bake.h"
#include "fresnel/ibl/cubemap.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/ibl/ktx2.h"
#include "fresnel/ibl/precompute.h"

#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/gpu/libraries.h"
#include "fresnel/gpu/resources.h"

#include "fresnel/job/camera.h"
#include "fresnel/job/features.h"
#include "fresnel/job/render_settings.h"
#include "fresnel/job/job.h"
#include "fresnel/job/lights.h"
#include "fresnel/job/orbit_controller.h"
#include "fresnel/render/limits.h"
#include "fresnel/render/renderer.h"
#include "fresnel/render/scene_posing.h"
#include "fresnel/job/scene_file.h"
#include "fresnel/job/settings.h"

#include "fresnel/trace/distribution.h"
#include "fresnel/trace/environment_light.h"
#include "fresnel/trace/job_inputs.h"
#include "fresnel/trace/tracer.h"

#include "fresnel/viewer/automation.h"
#include "fresnel/viewer/files.h"
#include "fresnel/viewer/geometry.h"
#include "fresnel/viewer/script.h"
#include "fresnel/viewer/state.h"

#include "fresnel/shaders/shaders.h"
