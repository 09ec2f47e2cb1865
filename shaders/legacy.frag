// Fragment shader of the legacy shading models (legacy.vert):
//   LEGACY_OGL1_VERTEX / LEGACY_OGL1_PIXEL: OpenGL 1 fixed function. Colour sum, GL_MODULATE
//     by map_Kd (texels as stored, no sRGB decode), then fog on the unclamped sum (as Mesa
//     does), then the display value as is: no exposure, no tone mapping, no encoding.
//   LEGACY_BLINN_PHONG: the normalized Blinn-Phong microfacet model in the glTF lights'
//     units, with its image-based path (USE_IBL), exposed, tone mapped and encoded.
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv0;
in float v_eye_depth;
#ifdef LEGACY_OGL1_VERTEX
in vec3 v_primary;
in vec3 v_secondary;
#endif

out vec4 frag_color;

#ifdef HAS_DIFFUSE_MAP
uniform sampler2D u_diffuse_map;
uniform mat3 u_diffuse_transform;
#endif
#ifdef LEGACY_FOG
uniform int u_fog_mode;  // legacy::FogMode
uniform vec4 u_fog;      // start, end, density
uniform vec3 u_fog_color;
#endif

#include "common.glsl"
#include "lights.glsl"
#include "legacy_shading.glsl"
#include "legacy_lighting.glsl"
#ifdef LEGACY_BLINN_PHONG
uniform vec3 u_bp_base_color;
uniform float u_bp_shininess;
uniform float u_bp_fresnel;
uniform float u_bp_metalness;
uniform float u_bp_reflectivity;
uniform float u_exposure;
uniform int u_tonemap;
uniform int u_encoding;
#include "color.glsl"
#include "tonemap.glsl"
#include "ibl.glsl"
#endif

void main() {
    vec4 texel = vec4(1.0);
#ifdef HAS_DIFFUSE_MAP
    texel = texture(u_diffuse_map, (u_diffuse_transform * vec3(v_uv0, 1.0)).xy);
#endif
    float alpha = u_kd.a * texel.a;
#ifdef LEGACY_BLINN_PHONG
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    vec3 v = normalize(u_camera_position - v_position);
    vec3 base = u_bp_base_color * texel.rgb;
    vec3 color = vec3(0.0);
    int i = 0;  // a do-while on the count alone, as pbr.frag's light loop (unrolled otherwise)
    if (u_light_count > 0) do {
        vec3 l;
        vec3 radiance = light_incident(i, v_position, l);
        color += blinn_phong_normalized(base, u_bp_shininess, u_bp_fresnel, u_bp_metalness, u_bp_reflectivity, n, v, l,
                                        radiance);
    } while (++i < u_light_count);
#ifdef USE_IBL
    color += blinn_phong_normalized_ibl(base, u_bp_fresnel, u_bp_metalness, u_bp_reflectivity, clamped_dot(n, v),
                                        ibl_irradiance(n),
                                        ibl_radiance(reflect(-v, n), blinn_phong_ibl_roughness(u_bp_shininess)));
#endif
    color += u_ambient * base + u_ke;
    if (any(isnan(color)) || any(isinf(color))) {
        frag_color = vec4(1.0, 0.0, 1.0, 1.0);
        return;
    }
    color = display_transform(color, u_exposure, u_tonemap, u_encoding);
    frag_color = vec4(color, alpha);
#else
#ifdef LEGACY_OGL1_VERTEX
    vec3 color = v_primary * texel.rgb + v_secondary;
#else
    // Per fragment: the same sums at the interpolated point and normal (two-sided lighting
    // off, as OpenGL's default: back faces keep the front normal).
    vec3 p, s;
    ogl1_lighting(v_position, normalize(v_normal), p, s);
    vec3 color = u_separate_specular == 1 ? clamp(p, 0.0, 1.0) * texel.rgb + clamp(s, 0.0, 1.0)
                                          : clamp(p + s, 0.0, 1.0) * texel.rgb;
#endif
#ifdef LEGACY_FOG
    color = ogl1_apply_fog(color, u_fog_color, ogl1_fog_factor(u_fog_mode, v_eye_depth, u_fog.x, u_fog.y, u_fog.z));
#endif
    frag_color = vec4(clamp(color, 0.0, 1.0), alpha);
#endif
}
