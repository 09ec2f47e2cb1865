// Mesh vertex shader of the legacy shading models (RenderSettings::shading, renderer.h;
// variants: legacy_feature in shader_features.h). LEGACY_OGL1_VERTEX lights each vertex
// as OpenGL 1 does (Gouraud) and clamps the colour sums per vertex before interpolation.
in vec3 a_position;
in vec3 a_normal;
in vec2 a_uv0;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
#include "frame_block.glsl"  // u_view, u_view_projection
uniform float u_point_size;

out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv0;
out float v_eye_depth;  // |z_eye|, for fog
#ifdef LEGACY_OGL1_VERTEX
out vec3 v_primary;
out vec3 v_secondary;
#include "common.glsl"
#include "lights.glsl"
#include "legacy_shading.glsl"
#include "legacy_lighting.glsl"
#endif

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_position = world.xyz;
#ifdef HAS_NORMAL
    v_normal = normalize(u_normal_matrix * a_normal);  // GL_NORMALIZE
#else
    v_normal = normalize(u_normal_matrix * vec3(0.0, 0.0, 1.0));  // OpenGL's current normal
#endif
#ifdef HAS_UV0
    v_uv0 = a_uv0;
#else
    v_uv0 = vec2(0.0);
#endif
    v_eye_depth = abs((u_view * world).z);
#ifdef LEGACY_OGL1_VERTEX
    vec3 p, s;
    ogl1_lighting(v_position, v_normal, p, s);
    if (u_separate_specular == 1) {
        v_primary = clamp(p, 0.0, 1.0);
        v_secondary = clamp(s, 0.0, 1.0);
    } else {
        v_primary = clamp(p + s, 0.0, 1.0);
        v_secondary = vec3(0.0);
    }
#endif
    gl_PointSize = u_point_size;
    gl_Position = u_view_projection * world;
}
