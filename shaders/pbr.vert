// Mesh vertex shader. Attribute locations are fixed by gpu::Program.
in vec3 a_position;
in vec3 a_normal;
in vec4 a_tangent;
in vec2 a_uv0;
in vec2 a_uv1;
in vec4 a_color;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;   // inverse transpose of the model's upper 3x3
uniform mat4 u_view_projection;
uniform float u_handedness;     // sign of det(model): mirrors flip the bitangent
uniform float u_point_size;

out vec3 v_position;
out vec3 v_normal;
out vec4 v_tangent;
out vec3 v_bitangent;
out vec2 v_uv0;
out vec2 v_uv1;
out vec4 v_color;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_position = world.xyz;
#ifdef HAS_NORMAL
    v_normal = normalize(u_normal_matrix * a_normal);
#else
    v_normal = vec3(0.0, 0.0, 1.0);
#endif
#ifdef HAS_TANGENT
    v_tangent = vec4(normalize(mat3(u_model) * a_tangent.xyz), a_tangent.w * u_handedness);
    v_bitangent = cross(v_normal, v_tangent.xyz) * v_tangent.w;
#else
    v_tangent = vec4(1.0, 0.0, 0.0, 1.0);
    v_bitangent = vec3(0.0, 1.0, 0.0);
#endif
#ifdef HAS_UV0
    v_uv0 = a_uv0;
#else
    v_uv0 = vec2(0.0);
#endif
#ifdef HAS_UV1
    v_uv1 = a_uv1;
#else
    v_uv1 = v_uv0;
#endif
#ifdef HAS_COLOR
    v_color = a_color;
#else
    v_color = vec4(1.0);
#endif
    gl_PointSize = u_point_size;
    gl_Position = u_view_projection * world;
}
