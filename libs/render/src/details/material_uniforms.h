#pragma once
// Material -> shader uniforms, in one place. The values are the material's raw factors;
// the shader (read_material in shaders/material_inputs.glsl) applies the rules, exactly
// as fresnel::evaluate does on the CPU, so nothing here computes F0 or weights.
#include <array>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/material/evaluate.h"
#include "fresnel/material/material.h"
#include "details/shader_features.h"
#include "details/uniform_blocks.h"

namespace fresnel {
namespace gpu {
class Program;
class UniformBuffer;
}

// The values one material uploads: its raw factors and each map's transform, UV set and
// probes, already in the std140 layout of MaterialBlock (uniform_blocks.h,
// material_block.glsl), plus the slot each map reads.
struct MaterialUniforms {
    // The factors (baseColorFactor, or diffuseFactor with specular-glossiness; the extension
    // blocks' factors at their defaults where the material has none) and, per map, transform,
    // UV set and the most probes of the shader's anisotropic filter (maps[i].anisotropy, read
    // by sample_detail_map for the detail maps): 1 here, one trilinear probe; the renderer
    // raises it where the map's sampler and --anisotropy allow.
    MaterialBlock block;
    // The slot each map reads (material_map), nullptr for none; index = MaterialMap.
    std::array<const TextureSlot*, kMaterialMapCount> maps{};
};

MaterialUniforms material_uniforms(const Material& m);

// The shader feature bits (shader_features.h) of the material model: unlit,
// specular-glossiness, clearcoat, sheen, transmission, anisotropy, iridescence, diffuse transmission, alpha mode (feature_defines() spells them as #defines).
FeatureMask material_features(const Material& m);

// The samplers of `program` (in use): units[i] is the texture unit map i is bound to (-1: none).
// The renderer packs the maps a variant reads into consecutive units, so that with the
// image-based light's textures they stay within the 16 units OpenGL ES 3.0 guarantees.
void set_material_samplers(const gpu::Program& program, const std::array<int, kMaterialMapCount>& units);

// Tests: the values into `buffer` (made when empty) bound at kMaterialBlockBinding, and map i
// on unit i where bound[i].
void set_material_uniforms(const gpu::Program& program, const MaterialUniforms& u,
                           const std::array<bool, kMaterialMapCount>& bound, gpu::UniformBuffer& buffer);

}  // namespace fresnel
