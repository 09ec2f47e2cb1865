// Debug channels: display-ready values, written without tone mapping. The
// numbers match render::DebugChannel. Scalars show as grey; vectors map
// [-1,1] to [0,1]; colours are sRGB-encoded; BRDF terms use light 0 (or the
// view direction when there is no light) and are clamped to [0,1].
#ifdef DEBUG_VIEW
vec3 debug_value(int channel, MaterialInputs m, vec3 n, vec3 ng, vec3 t, vec3 b, vec3 v) {
    if (channel == 1) return linear_to_srgb(clamp(m.base_color.rgb, 0.0, 1.0));
    if (channel == 2) return vec3(m.metallic);
    if (channel == 3) return vec3(m.roughness);
    if (channel == 4) return n * 0.5 + 0.5;
    if (channel == 5) return ng * 0.5 + 0.5;
    if (channel == 6) return t * 0.5 + 0.5;
    if (channel == 7) return b * 0.5 + 0.5;
    if (channel == 8) return vec3(m.occlusion);
    if (channel == 9) return linear_to_srgb(clamp(m.emissive, 0.0, 1.0));
    if (channel == 10) return vec3(m.base_color.a);
    if (channel == 11) return vec3(fract(v_uv0), 0.0);
    if (channel == 12) return vec3(fract(v_uv1), 0.0);
    if (channel == 22 || channel == 23) {
#ifdef MATERIAL_TRANSMISSION
        TransmissionInputs tr = read_transmission();
        return vec3(channel == 22 ? tr.factor : clamp(tr.thickness, 0.0, 1.0));
#else
        return vec3(0.0);  // not transmissive
#endif
    }
    if (channel == 24) return linear_to_srgb(clamp(m.sheen_color, 0.0, 1.0));  // KHR_materials_sheen (0 without)
    if (channel == 25) return vec3(m.sheen_roughness);
    if (channel == 26) return vec3(m.anisotropy_strength);  // KHR_materials_anisotropy (0 without)
    if (channel == 27) return m.anisotropy_strength > 0.0 ? vec3(m.anisotropy_direction * 0.5 + 0.5, 0.0) : vec3(0.0);
    if (channel == 28) return vec3(m.iridescence);  // KHR_materials_iridescence (0 without)
    if (channel == 29) return vec3(clamp(m.iridescence_thickness / 1000.0, 0.0, 1.0));  // micrometres
    if (channel == 30) return vec3(m.diffuse_transmission);  // KHR_materials_diffuse_transmission (0 without)
    if (channel == 31) return m.diffuse_transmission > 0.0 ? linear_to_srgb(clamp(m.diffuse_transmission_color, 0.0, 1.0)) : vec3(0.0);
    if (channel == 32) return vec3(m.diffuse_roughness);  // KHR_materials_diffuse_roughness (0 without: Lambert)
    vec3 l = v;
    if (u_light_count > 0) light_incident(0, v_position, l);
    // With the thin film where there is one (F shows the film's colours).
    BrdfTerms bt = brdf_terms_film(m.base_color.rgb, m.metallic, m.roughness, m.f0_dielectric, m.specular_weight, n, v, l,
                                   material_film(m, v));
#ifdef MATERIAL_ANISOTROPY
    if (m.anisotropy_strength > 0.0)
        apply_anisotropy(bt, m.metallic, m.roughness, n, v, l, m.anisotropic_t, m.anisotropic_b, m.anisotropy_strength);
#endif
    float n_dot_l = clamped_dot(n, l), n_dot_v = clamped_dot(n, v);
    if (channel == 13) return vec3(clamp(bt.d, 0.0, 1.0));
    if (channel == 14) return vec3(clamp(bt.v * 4.0 * n_dot_l * n_dot_v, 0.0, 1.0));
    if (channel == 15) return clamp(bt.f, 0.0, 1.0);
    if (channel == 16) return clamp(bt.diffuse * PI, 0.0, 1.0);
    if (channel == 17) return clamp(bt.specular * n_dot_l, 0.0, 1.0);
#ifdef USE_IBL
    // Image-based light terms, tone mapped by the neutral curve so they stay readable.
    if (channel == 18) return linear_to_srgb(tone_map_neutral(ibl_irradiance(n)));
    if (channel == 19) return linear_to_srgb(tone_map_neutral(ibl_radiance(reflect(-v, n), m.roughness)));
    if (channel == 20) {
        vec3 fd = ibl_ggx_fresnel(n_dot_v, m.roughness, m.f0_dielectric, m.specular_weight);
        return linear_to_srgb(tone_map_neutral(ibl_irradiance(n) * m.base_color.rgb * (1.0 - fd) * (1.0 - m.metallic) * m.occlusion));
    }
    if (channel == 21) {
        vec3 spec = ibl_radiance(reflect(-v, n), m.roughness);
        vec3 fd = ibl_ggx_fresnel(n_dot_v, m.roughness, m.f0_dielectric, m.specular_weight);
        vec3 fm = ibl_ggx_fresnel(n_dot_v, m.roughness, m.base_color.rgb, 1.0);
        return linear_to_srgb(tone_map_neutral(spec * mix(fd, fm, m.metallic)));
    }
#else
    if (channel >= 18 && channel <= 21) return vec3(0.0);  // no environment
#endif
    return vec3(1.0, 0.0, 1.0);
}
#endif
