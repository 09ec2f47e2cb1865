// What every draw of a frame shares, as one std140 uniform block uploaded once per frame:
// the camera, the environment's placement, the debug channel, the ambient term and the
// punctual lights. The layout of fresnel::FrameBlock (libs/render/include/fresnel/render/
// uniform_blocks.h), which tests/gpu/material_gpu_test.cpp checks member by member against
// the driver's offsets. Per-draw values (u_model, ...) and per-pass ones (u_exposure, ...)
// stay plain uniforms.
#ifndef MAX_LIGHTS
#define MAX_LIGHTS 16
#endif
#define MAX_SHADOW_TILES 24  // fresnel::kMaxShadowTiles
layout(std140) uniform FrameBlock {
    mat4 u_view_projection;
    mat4 u_view;
    mat3 u_env_rotation;      // world -> environment
    vec3 u_camera_position;
    float u_env_levels;       // levels of the prefiltered cube
    vec3 u_ambient;           // uniform ambient radiance (0 unless asked; OpenGL 1: GL_LIGHT_MODEL_AMBIENT)
    float u_env_intensity;
    int u_debug;              // 0 = shading; other values select a debug channel (see debug.glsl)
    int u_energy_compensation;  // 1: multiple-scattering compensation of punctual specular
    // The lights, packed per light: position.xyz + type (0 dir, 1 point, 2 spot, 3 rect, 4 disk,
    // 5 sphere, 6 tube); direction the light travels (an area light's facing) .xyz + range (0 =
    // infinite); colour * intensity; spot cone scale and offset, or an area light's first
    // half-extent axis (a tube's half length) .xyz + a sphere's or tube's radius; an area light's
    // second half-extent axis.
    int u_light_count;
    vec4 u_light_position_type[MAX_LIGHTS];
    vec4 u_light_direction_range[MAX_LIGHTS];
    vec4 u_light_color[MAX_LIGHTS];
    vec4 u_light_cone[MAX_LIGHTS];
    vec4 u_light_axis[MAX_LIGHTS];
    // Shadows (shadows.glsl; fresnel::FrameBlock says what each holds).
    vec4 u_shadow_atlas_info;
    vec4 u_light_shadow[MAX_LIGHTS];
    mat4 u_shadow_matrix[MAX_SHADOW_TILES];
    vec4 u_shadow_rect[MAX_SHADOW_TILES];
    vec4 u_shadow_params[MAX_SHADOW_TILES];
};
