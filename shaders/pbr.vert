// Mesh vertex shader. Attribute locations are fixed by gpu::Program.
in vec3 a_position;
in vec3 a_normal;
in vec4 a_tangent;
in vec2 a_uv0;
in vec2 a_uv1;
in vec4 a_color;
#ifdef SKINNED
// glTF skinning: joint matrices world[joint] * inverse_bind (at most MAX_JOINTS, which is
// fresnel::kMaxShaderJoints); u_model is the node's world matrix, which vertices without
// weight follow (as fresnel::pose_skinned does).
#define MAX_JOINTS 32
in vec4 a_joints;  // joint indices as floats (exact below 2^24)
in vec4 a_weights;
uniform mat4 u_joints[MAX_JOINTS];
#endif
#ifdef MORPH_TARGETS
// Two morph targets (fresnel::kMaxShaderMorphTargets); u_morph_weights are the weights to
// add to those the vertex data already holds (fresnel::Primitive::applied_weights).
in vec3 a_morph_position0;
in vec3 a_morph_normal0;
in vec3 a_morph_tangent0;
in vec3 a_morph_position1;
in vec3 a_morph_normal1;
in vec3 a_morph_tangent1;
uniform float u_morph_weights[2];
#endif

#include "frame_block.glsl"  // u_view_projection
uniform mat4 u_model;
uniform mat3 u_normal_matrix;   // inverse transpose of the model's upper 3x3
uniform float u_handedness;     // sign of det(model): mirrors flip the bitangent
uniform float u_point_size;
#ifdef SHADOW_PASS
uniform mat4 u_light_view_projection;  // a shadow map's tile (shadow.frag)
#endif

out vec3 v_position;
out vec3 v_normal;
out vec4 v_tangent;
out vec3 v_bitangent;
out vec2 v_uv0;
out vec2 v_uv1;
out vec4 v_color;

void main() {
    vec3 position = a_position;
    vec3 normal = vec3(0.0, 0.0, 1.0);
    vec3 tangent = vec3(1.0, 0.0, 0.0);
#ifdef HAS_NORMAL
    normal = a_normal;
#endif
#ifdef HAS_TANGENT
    tangent = a_tangent.xyz;
#endif
#ifdef MORPH_TARGETS
    position += u_morph_weights[0] * a_morph_position0 + u_morph_weights[1] * a_morph_position1;
    normal += u_morph_weights[0] * a_morph_normal0 + u_morph_weights[1] * a_morph_normal1;
    tangent += u_morph_weights[0] * a_morph_tangent0 + u_morph_weights[1] * a_morph_tangent1;
#endif
    mat4 model = u_model;
    mat3 normal_matrix = u_normal_matrix;
    float handedness = u_handedness;
#ifdef SKINNED
    mat4 skin = mat4(0.0);
    float weight_sum = 0.0;
    for (int c = 0; c < 4; ++c) {
        int j = int(a_joints[c] + 0.5);
        float w = a_weights[c];
        if (w != 0.0 && j >= 0 && j < MAX_JOINTS) {
            skin += w * u_joints[j];
            weight_sum += w;
        }
    }
    if (weight_sum > 0.0) {
        model = skin;
        normal_matrix = transpose(inverse(mat3(skin)));
        handedness = determinant(mat3(skin)) < 0.0 ? -1.0 : 1.0;
    }
#endif
    vec4 world = model * vec4(position, 1.0);
#ifdef SKINNED
    world /= world.w;  // w = the sum of the weights: they act normalised (as the Khronos viewer's divide)
#endif
    v_position = world.xyz;
#ifdef HAS_NORMAL
    v_normal = normalize(normal_matrix * normal);
#else
    v_normal = vec3(0.0, 0.0, 1.0);
#endif
#ifdef HAS_TANGENT
    v_tangent = vec4(normalize(mat3(model) * tangent), a_tangent.w * handedness);
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
#ifdef SHADOW_PASS
    gl_Position = u_light_view_projection * world;
#else
    gl_Position = u_view_projection * world;
#endif
}
