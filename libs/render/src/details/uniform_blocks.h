#pragma once
// The C++ mirrors of the shaders' std140 uniform blocks, and where they bind. A block is
// filled once (a material's when it changes, the lights once per frame), uploaded into a
// gpu::UniformBuffer and bound for each draw, instead of tens of glUniform calls per draw.
// tests/gpu/material_gpu_test.cpp compares every member's offset with the driver's.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/material/evaluate.h"
#include "details/shader_features.h"
#include "details/shadow_maps.h"

namespace fresnel {

// Uniform buffer binding points; ShaderLibrary connects every program's blocks to them
// (GLSL ES 3.00 has no layout(binding = N) for blocks).
inline constexpr unsigned kFrameBlockBinding = 0;
inline constexpr unsigned kMaterialBlockBinding = 1;

// `uniform MaterialBlock` (shaders/material_block.glsl): a material's raw factors and, per
// map in MaterialMap order, its transform, UV set and anisotropic probes.
struct MaterialBlock {
    glm::vec4 base_color_factor{1.0f};
    glm::vec3 emissive_factor{0.0f};
    float emissive_strength = 1.0f;
    glm::vec3 specular_color_factor{1.0f};
    float specular_factor = 1.0f;
    glm::vec3 sg_specular_factor{1.0f};
    float glossiness_factor = 1.0f;
    glm::vec3 sheen_color_factor{0.0f};
    float sheen_roughness_factor = 0.0f;
    glm::vec3 attenuation_color{1.0f};
    float attenuation_distance = 0.0f;
    glm::vec3 diffuse_transmission_color_factor{1.0f};
    float diffuse_transmission_factor = 0.0f;
    float metallic_factor = 1.0f;
    float roughness_factor = 1.0f;
    float normal_scale = 1.0f;
    float occlusion_strength = 1.0f;
    float alpha_cutoff = 0.5f;
    float ior = 1.5f;
    float clearcoat_factor = 0.0f;
    float clearcoat_roughness_factor = 0.0f;
    float clearcoat_normal_scale = 1.0f;
    float transmission_factor = 0.0f;
    float thickness_factor = 0.0f;
    float dispersion = 0.0f;
    float anisotropy_strength = 0.0f;
    float anisotropy_rotation = 0.0f;
    float iridescence_factor = 0.0f;
    float iridescence_ior = 1.3f;
    float iridescence_thickness_minimum = 100.0f;
    float iridescence_thickness_maximum = 400.0f;
    float diffuse_roughness_factor = 0.0f;  // KHR_materials_diffuse_roughness
    float pad1 = 0.0f;                      // the mat3 below starts on 16 bytes
    struct Map {
        std::array<glm::vec4, 3> transform{glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0)};  // mat3 columns
        std::int32_t uv = 0;
        float anisotropy = 1.0f;
        float pad[2] = {0.0f, 0.0f};
    };
    std::array<Map, kMaterialMapCount> maps{};
};
static_assert(sizeof(MaterialBlock::Map) == 64);
static_assert(offsetof(MaterialBlock, maps) == 192);
static_assert(sizeof(MaterialBlock) == 192 + 64 * kMaterialMapCount);

// `uniform FrameBlock` (shaders/frame_block.glsl): what every draw of a frame shares.
struct FrameBlock {
    glm::mat4 view_projection{1.0f};
    glm::mat4 view{1.0f};
    std::array<glm::vec4, 3> env_rotation{glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0)};  // mat3 columns
    glm::vec3 camera_position{0.0f};
    float env_levels = 1.0f;
    glm::vec3 ambient{0.0f};
    float env_intensity = 1.0f;
    std::int32_t debug = 0;
    std::int32_t energy_compensation = 0;
    std::int32_t light_count = 0;
    std::int32_t pad = 0;
    // Per light: position.xyz + type (0 directional, 1 point, 2 spot, 3 rect, 4 disk, 5 sphere, 6 tube);
    // direction the light travels (an area light's facing) + range (0 = infinite); colour *
    // intensity; spot cone scale and offset, or an area light's first half-extent axis + sphere
    // radius; an area light's second half-extent axis (LightInstance::axis_u, axis_v, radius).
    std::array<glm::vec4, kMaxShaderLights> light_position_type{}, light_direction_range{}, light_color{}, light_cone{},
        light_axis{};
    // Shadows (details/shadow_maps.h, shaders/shadows.glsl): the atlas (1/width, 1/height, the
    // soft filter's radius in texels, 0); per light its first tile (-1: none) and tile count;
    // per tile world -> tile (u, v, depth) in [0, 1], where the tile lies in the atlas (offset,
    // size in atlas uv), and (world texel size, filter margin in tile uv, 0, 0).
    glm::vec4 shadow_atlas{0.0f};
    std::array<glm::vec4, kMaxShaderLights> light_shadow{};
    std::array<glm::mat4, kMaxShadowTiles> shadow_matrix{};
    std::array<glm::vec4, kMaxShadowTiles> shadow_rect{}, shadow_params{};
};
static_assert(offsetof(FrameBlock, light_position_type) == 224);
static_assert(offsetof(FrameBlock, shadow_atlas) == 224 + 80 * kMaxShaderLights);
static_assert(sizeof(FrameBlock) == 224 + 96 * kMaxShaderLights + 16 + 96 * kMaxShadowTiles);

// Each member's GLSL name and byte offset in the C++ mirror (the layout test's table).
std::vector<std::pair<std::string, std::size_t>> material_block_members();
std::vector<std::pair<std::string, std::size_t>> frame_block_members();

}  // namespace fresnel
