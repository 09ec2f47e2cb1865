// Area lights (rect 3, disk 4, sphere 5, tube 6 in frame_block.glsl's packing) on the material: the twin
// of fresnel::area_light_polygon and fresnel::shade_area_light (fresnel/material/area_light.h),
// which say what each term is. Needs ltc.glsl's table (u_ltc_table) and the split-sum table.
#include "ltc.glsl"

#define AREA_POLYGON_VERTICES 12  // fresnel::kAreaPolygonVertices

// Light i's polygon seen from x, relative to x; -1 when x is inside a sphere light.
int area_light_polygon(int i, vec3 x, out vec3 pts[17]) {
    vec4 pt = u_light_position_type[i];
    vec3 c = pt.xyz - x;
    vec3 u = u_light_cone[i].xyz, v = u_light_axis[i].xyz;
    if (pt.w < 3.5) {
        pts[0] = c - u - v;
        pts[1] = c + u - v;
        pts[2] = c + u + v;
        pts[3] = c - u + v;
        return 4;
    }
    if (pt.w > 5.5) {  // a tube: the rectangle through its axis covering its silhouette
        float half_length = length(u), r = u_light_cone[i].w;
        vec3 a = half_length > 0.0 ? u / half_length : vec3(1.0, 0.0, 0.0);
        vec3 w = -c;
        vec3 across = w - a * dot(w, a);
        float d = length(across);
        if (d <= r * 1e-3 + 1e-12) {
            vec3 end = c + a * (dot(w, a) > 0.0 ? half_length : -half_length);
            int n = ltc_sphere_polygon(end, r, vec3(0.0), pts, AREA_POLYGON_VERTICES);
            return n > 0 ? n : -1;
        }
        if (d <= r) return -1;
        vec3 tu = a * (half_length + 0.25 * PI * r);
        vec3 tv = normalize(cross(across, a)) * (r * d / sqrt((d - r) * (d + r)));
        pts[0] = c - tu - tv;
        pts[1] = c + tu - tv;
        pts[2] = c + tu + tv;
        pts[3] = c - tu + tv;
        return 4;
    }
    if (pt.w > 4.5) {
        int n = ltc_sphere_polygon(c, u_light_cone[i].w, vec3(0.0), pts, AREA_POLYGON_VERTICES);
        return n > 0 ? n : -1;  // inside: surrounded
    }
    // The disk's radii as the axes of a unit disk: an ellipse where they differ.
    return ltc_disk_polygon(c, u, v, 1.0, pts, AREA_POLYGON_VERTICES);
}

float area_integral(mat3 minv, vec3 n, vec3 v, vec3 pts[17], int count) {
    return count < 0 ? 1.0 : ltc_polygon_integral(minv, n, v, pts, count);
}

vec3 shade_area_light(MaterialInputs m, vec3 v, vec3 pts[17], int count, vec3 radiance, vec3 toward,
                      vec3 comp_dielectric, vec3 comp_metal) {
    vec3 n = m.normal;
    float n_dot_v = clamped_dot(n, v);
    float form_factor = area_integral(mat3(1.0), n, v, pts, count);
    float specular = area_integral(ltc_inverse_matrix(n_dot_v, m.roughness), n, v, pts, count);
    vec2 ab = brdf_lut(n_dot_v, m.roughness).rg;
    vec3 f_dielectric = (m.f0_dielectric * ab.x + ab.y) * m.specular_weight;
    vec3 f_metal = m.base_color.rgb * ab.x + ab.y;
    vec3 diffuse = m.base_color.rgb * (1.0 - f_dielectric) * form_factor;
    if (m.diffuse_roughness > 0.0) diffuse *= eon_albedo_factor(m.base_color.rgb, m.diffuse_roughness, n_dot_v);
    if (m.diffuse_transmission > 0.0) {
        float behind = area_integral(mat3(1.0), -n, v, pts, count);
        diffuse = mix(diffuse, m.diffuse_transmission_color * (1.0 - f_dielectric) * behind, m.diffuse_transmission);
    }
    vec3 dielectric = diffuse + f_dielectric * specular * comp_dielectric;
    vec3 metal = f_metal * specular * comp_metal;
    vec3 lit = mix(dielectric, metal, m.metallic);
#ifdef MATERIAL_SHEEN
    if (m.sheen_color != vec3(0.0)) {
        float c = max3(m.sheen_color);
        float n_dot_l = clamped_dot(n, toward);
        float n_dot_h = clamped_dot(n, normalize(toward + v));
        vec3 sheen = n_dot_l > 0.0 ? sheen_specular(m.sheen_color, m.sheen_roughness, n_dot_l, n_dot_v, n_dot_h) : vec3(0.0);
        lit = sheen * (3.14159265358979 * form_factor) + lit * (1.0 - c * sheen_albedo(n_dot_v, m.sheen_roughness));
    }
#endif
#ifdef MATERIAL_CLEARCOAT
    vec3 nc = m.clearcoat_normal;
    float cc_n_dot_v = clamped_dot(nc, v);
    vec2 abc = brdf_lut(cc_n_dot_v, m.clearcoat_roughness).rg;
    float coat = area_integral(ltc_inverse_matrix(cc_n_dot_v, m.clearcoat_roughness), nc, v, pts, count) * (abc.x + abc.y);
    lit = mix(lit, vec3(coat), m.clearcoat * f_schlick(m.clearcoat_f0, 1.0, cc_n_dot_v));
#endif
    return radiance * lit;
}
