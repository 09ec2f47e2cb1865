// Mesh vertex shader. Attribute locations are fixed by gpu::Program.
in vec3 a_position;
in vec3 a_normal;
in vec4 a_tangent;
in vec2 a_uv0;
in vec2 a_uv1;
in vec4 a_color;
#ifdef SKINNED
// glTF skinning: joint matrices world[joint] * inverse_bind, read from an RGBA32F texture
// (the renderer's joint texture: joint j's four columns are texels 4 (j % JOINTS_PER_ROW) + c
// of row j / JOINTS_PER_ROW); u_model is the node's world matrix, which vertices without
// weight follow (as fresnel::pose_skinned does).
in vec4 a_joints;  // joint indices as floats (exact below 2^24)
in vec4 a_weights;
uniform highp sampler2D u_joint_matrices;
uniform int u_joint_count;  // the skin's joints: indices at or past it are ignored
mat4 joint_matrix(int j) {
    ivec2 at = ivec2(4 * (j % JOINTS_PER_ROW), j / JOINTS_PER_ROW);
    return mat4(texelFetch(u_joint_matrices, at, 0), texelFetch(u_joint_matrices, at + ivec2(1, 0), 0),
                texelFetch(u_joint_matrices, at + ivec2(2, 0), 0), texelFetch(u_joint_matrices, at + ivec2(3, 0), 0));
}
#endif
#ifdef MORPH_TARGETS
// Up to MAX_MORPH_TARGETS morph targets (fresnel::kMaxShaderMorphTargets) from the
// primitive's RGBA32F texture array: layer u_morph_position_layer + k holds target k's
// POSITION displacements (likewise NORMAL and TANGENT; -1: no target has them), vertex v at
// texel (v % width, v / width). gl_VertexID is the vertex's index (glDrawElements) or its
// number (glDrawArrays from 0). u_morph_weights (four to a vec4) are the weights to add to
// those the vertex data already holds (fresnel::Primitive::applied_weights).
uniform highp sampler2DArray u_morph_targets;
uniform int u_morph_target_count;
uniform int u_morph_position_layer;
uniform int u_morph_normal_layer;
uniform int u_morph_tangent_layer;
uniform vec4 u_morph_weights[MAX_MORPH_TARGETS / 4];
#endif

#include "frame_block.glsl"  // u_view_projection
#ifdef INSTANCED
// One draw of many placements of the primitive (the renderer's instanced batches): each
// instance's model matrix and its normal matrix are per-instance attributes (locations 8..11,
// 12..14, fixed by gpu::Program), in place of u_model and u_normal_matrix. The batch's
// placements share one handedness (u_handedness).
in mat4 a_instance_model;
in mat3 a_instance_normal;
#else
uniform mat4 u_model;
uniform mat3 u_normal_matrix;   // inverse transpose of the model's upper 3x3
#endif
// Baked visibility of the environment (the renderer's vertex occlusion, `--ao baked`): the bent
// normal in world space (xyz) and the cosine-weighted visibility (w). Draws without it leave
// the array off and read the default (0, 0, 0, 1): visibility 1, no bent normal.
in vec4 a_occlusion;
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
out vec4 v_occlusion;

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
    {
        int width = textureSize(u_morph_targets, 0).x;
        ivec2 at = ivec2(gl_VertexID % width, gl_VertexID / width);
        for (int k = 0; k < u_morph_target_count; ++k) {
            float w = u_morph_weights[k / 4][k % 4];
            if (w == 0.0) continue;
            if (u_morph_position_layer >= 0)
                position += w * texelFetch(u_morph_targets, ivec3(at, u_morph_position_layer + k), 0).xyz;
            if (u_morph_normal_layer >= 0)
                normal += w * texelFetch(u_morph_targets, ivec3(at, u_morph_normal_layer + k), 0).xyz;
            if (u_morph_tangent_layer >= 0)
                tangent += w * texelFetch(u_morph_targets, ivec3(at, u_morph_tangent_layer + k), 0).xyz;
        }
    }
#endif
#ifdef INSTANCED
    mat4 model = a_instance_model;
    mat3 normal_matrix = a_instance_normal;
#else
    mat4 model = u_model;
    mat3 normal_matrix = u_normal_matrix;
#endif
    float handedness = u_handedness;
#ifdef SKINNED
    mat4 skin = mat4(0.0);
    float weight_sum = 0.0;
    for (int c = 0; c < 4; ++c) {
        int j = int(a_joints[c] + 0.5);
        float w = a_weights[c];
        if (w != 0.0 && j >= 0 && j < u_joint_count) {
            skin += w * joint_matrix(j);
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
    v_occlusion = a_occlusion;
    gl_PointSize = u_point_size;
#ifdef SHADOW_PASS
    gl_Position = u_light_view_projection * world;
#else
    gl_Position = u_view_projection * world;
#endif
}
