// The environment behind the model: the prefiltered cube map at u_lod (0 = sharp),
// through the same exposure, tone map and encoding as the model.
in vec2 v_texcoord;
out vec4 frag_color;
uniform samplerCube u_specular_env;
uniform mat4 u_inverse_view_projection;
uniform mat3 u_env_rotation;
uniform float u_env_intensity;
uniform float u_lod;
uniform float u_exposure;
uniform int u_tonemap;
uniform int u_encoding;

#include "common.glsl"
#include "color.glsl"
#include "tonemap.glsl"

void main() {
    vec4 p = u_inverse_view_projection * vec4(v_texcoord * 2.0 - 1.0, 1.0, 1.0);
    vec4 q = u_inverse_view_projection * vec4(v_texcoord * 2.0 - 1.0, -1.0, 1.0);
    vec3 dir = normalize(p.xyz / p.w - q.xyz / q.w);
    vec3 c = textureLod(u_specular_env, u_env_rotation * dir, u_lod).rgb * u_env_intensity;
    c = display_transform(c, u_exposure, u_tonemap, u_encoding);
    frag_color = vec4(c, 1.0);
}
