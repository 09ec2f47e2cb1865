// A shadow map's depth pass (pbr.vert with SHADOW_PASS): depth only, into a tile of the atlas
// (shadows.glsl). Alpha-masked materials (ALPHA_MASK) cast where their base colour's alpha
// (factor x vertex colour x map, the map read through its transform, UV set 0) reaches the
// cutoff, as they are drawn.
#ifdef ALPHA_MASK
in vec2 v_uv0;
in vec4 v_color;
uniform vec4 u_base_color_factor;
uniform float u_alpha_cutoff;
#ifdef HAS_BASE_COLOR_MAP
uniform sampler2D u_base_color_map;
uniform mat3 u_base_color_transform;
#endif
#endif

void main() {
#ifdef ALPHA_MASK
    float alpha = u_base_color_factor.a * v_color.a;
#ifdef HAS_BASE_COLOR_MAP
    alpha *= texture(u_base_color_map, (u_base_color_transform * vec3(v_uv0, 1.0)).xy).a;
#endif
    if (alpha < u_alpha_cutoff) discard;
#endif
}
