// KHR_materials_iridescence: the Fresnel of a thin dielectric film (Belcour & Barla 2017) as
// the extension and the Khronos Sample Viewer evaluate it; the same functions as the
// iridescence part of libs/material/include/fresnel/material/brdf.h (brdf.cpp). Included by
// material_inputs.glsl with MATERIAL_IRIDESCENCE only; IridescenceFresnel is in brdf.glsl.

// brdf::iridescence_sensitivity: the XYZ matching functions' Fourier transform (Gaussian
// fits) at optical path difference opd (nm) and phase shift `shift`, in linear Rec.709.
vec3 iridescence_sensitivity(float opd, vec3 shift) {
    float phase = 2.0 * PI * opd * 1.0e-9;
    const vec3 val = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
    const vec3 pos = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
    const vec3 var = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
    vec3 xyz = val * sqrt(2.0 * PI * var) * cos(pos * phase + shift) * exp(-(phase * phase) * var);
    xyz.x += 9.7470e-14 * sqrt(2.0 * PI * 4.5282e+09) * cos(2.2399e+06 * phase + shift.x) *
             exp(-4.5282e+09 * (phase * phase));
    xyz /= 1.0685e-7;
    // CIE XYZ -> linear Rec.709, row by row as in brdf.cpp.
    return vec3(3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
                -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
                0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z);
}

// ((a - b) / (a + b))^2
vec3 ior_pair_f0(vec3 a, float b) {
    vec3 r = (a - b) / (a + b);
    return r * r;
}
float ior_pair_f0(float a, float b) {
    float r = (a - b) / (a + b);
    return r * r;
}

// brdf::iridescence_fresnel: F_iridescence from a medium of outside_ior at cos_theta1 = n.v.
vec3 iridescence_fresnel(float outside_ior, float film_ior, float cos_theta1, float thickness, vec3 base_f0) {
    float t = clamp(thickness / 0.03, 0.0, 1.0);
    float eta2 = outside_ior + (film_ior - outside_ior) * (t * t * (3.0 - 2.0 * t));
    float ratio = outside_ior / eta2;
    float cos2_theta2 = 1.0 - ratio * ratio * (1.0 - cos_theta1 * cos_theta1);
    if (cos2_theta2 < 0.0) return vec3(1.0);  // total internal reflection
    float cos_theta2 = sqrt(cos2_theta2);

    float r12 = f_schlick(ior_pair_f0(eta2, outside_ior), 1.0, cos_theta1);
    float t121 = 1.0 - r12;
    float phi12 = eta2 < outside_ior ? PI : 0.0;
    float phi21 = PI - phi12;
    vec3 sqrt_f0 = sqrt(clamp(base_f0, 0.0, 0.9999));
    vec3 eta3 = (1.0 + sqrt_f0) / (1.0 - sqrt_f0);
    vec3 r23 = f_schlick(ior_pair_f0(eta3, eta2), vec3(1.0), cos_theta2);
    vec3 phi23 = vec3(eta3.x < eta2 ? PI : 0.0, eta3.y < eta2 ? PI : 0.0, eta3.z < eta2 ? PI : 0.0);

    float opd = 2.0 * eta2 * thickness * cos_theta2;
    vec3 phi = vec3(phi21) + phi23;
    vec3 r123 = clamp(r12 * r23, 1e-5, 0.9999);
    vec3 sqrt_r123 = sqrt(r123);
    vec3 rs = t121 * t121 * r23 / (1.0 - r123);
    vec3 result = r12 + rs;
    vec3 cm = rs - t121;
    for (int m = 1; m <= 2; ++m) {
        cm *= sqrt_r123;
        result += cm * 2.0 * iridescence_sensitivity(float(m) * opd, float(m) * phi);
    }
    return max(result, vec3(0.0));
}

// brdf::iridescence_at: the film over both bases at n.v (no film at factor or thickness 0).
IridescenceFresnel iridescence_at(float factor, float film_ior, float thickness, float n_dot_v, vec3 f0_dielectric,
                                  vec3 base_color) {
    IridescenceFresnel film = no_film();
    if (!(factor > 0.0) || !(thickness > 0.0)) return film;
    film.factor = factor;
    film.dielectric = iridescence_fresnel(1.0, film_ior, n_dot_v, thickness, f0_dielectric);
    film.metal = iridescence_fresnel(1.0, film_ior, n_dot_v, thickness, base_color);
    return film;
}
