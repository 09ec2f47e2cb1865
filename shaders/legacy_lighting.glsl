// The legacy models' material uniforms and OpenGL 1's per-point lighting, shared by
// legacy.vert (Gouraud) and legacy.frag (per fragment). The formulas are in
// legacy_shading.glsl (C++ twin: fresnel/material/legacy_shading.h); the values are
// legacy_phong() of the material (fresnel/material/phong.h), set by the renderer.
// Needs common.glsl, lights.glsl and legacy_shading.glsl.
uniform vec3 u_ka;             // GL_AMBIENT (MTL Ka)
uniform vec4 u_kd;             // GL_DIFFUSE (Kd, alpha d)
uniform vec3 u_ks;             // GL_SPECULAR (Ks)
uniform vec3 u_ke;             // GL_EMISSION (Ke)
uniform float u_shininess;     // GL_SHININESS, already clamped to 0..128
uniform int u_separate_specular;  // GL_SEPARATE_SPECULAR_COLOR (textured materials, as rgl)

// An OpenGL light of colour I for a light of intensity I: directional lights as they are;
// point and spot lights with OpenGL's default attenuation (none) and the glTF cone window.
vec3 ogl1_light_incident(int i, vec3 position, out vec3 l) { return light_arriving(i, position, false, l); }

// The primary (emission + ambient + diffuse) and secondary (specular) sums at a point,
// unclamped, with the local viewer.
void ogl1_lighting(vec3 position, vec3 n, out vec3 primary, out vec3 secondary) {
    vec3 v = normalize(u_camera_position - position);
    primary = ogl1_base(u_ke, u_ka, u_ambient);  // GL_LIGHT_MODEL_AMBIENT
    secondary = vec3(0.0);
    int i = 0;  // a do-while on the count alone, as pbr.frag's light loop (unrolled otherwise)
    if (u_light_count > 0) do {
        vec3 l;
        vec3 color = ogl1_light_incident(i, position, l);
        Ogl1Light o = ogl1_light(n, v, l, color, u_kd.rgb, u_ks, u_shininess);
        primary += o.diffuse;
        secondary += o.specular;
    } while (++i < u_light_count);
}
