// Forward shading of one glTF primitive into the linear HDR target.
in vec3 v_position;
in vec3 v_normal;
in vec4 v_tangent;
in vec3 v_bitangent;
in vec2 v_uv0;
in vec2 v_uv1;
in vec4 v_color;
in vec4 v_occlusion;  // baked visibility: bent normal (xyz), visibility (w); (0, 0, 0, 1) without (pbr.vert)

out vec4 frag_color;

#include "frame_block.glsl"  // camera, environment placement, debug channel, ambient, lights
uniform float u_exposure;  // linear multiplier, 2^EV
uniform int u_tonemap;     // see tonemap.glsl
uniform int u_encoding;    // -1 = none (linear output), 0 = sRGB, 1 = gamma 2.2
#ifdef FRAME_SSAO
uniform sampler2D u_ssao;  // screen-space visibility at each pixel (ssao.frag, ssao_blur.frag)
#endif

#include "common.glsl"
#include "color.glsl"
#include "tonemap.glsl"
#include "brdf.glsl"
#include "lights.glsl"
#include "shadows.glsl"
#include "ibl.glsl"
#include "material_inputs.glsl"
#include "transmission.glsl"
#ifdef FRAME_AREA_LIGHTS
#include "area_lights.glsl"
#endif
#include "debug.glsl"

struct Frame {
    vec3 n;    // shading normal (read_material's, from the normal map)
    vec3 ng;   // geometric normal (interpolated vertex normal, flipped for back faces)
    vec3 t;
    vec3 b;
    vec3 nc;   // clearcoat normal: its own normal map, else the geometric normal
};

// The geometric frame; read_material applies the normal maps to it.
Frame shading_frame() {
    Frame f;
    f.ng = normalize(v_normal);
    // The interpolated frame, normalised but not re-orthogonalised (as the Khronos
    // Sample Viewer does, so normal-mapped detail matches it).
    f.t = normalize(v_tangent.xyz);
    f.b = normalize(v_bitangent);
#ifdef HAS_NORMAL
    // Back faces of double-sided materials shade with the flipped frame.
    if (!gl_FrontFacing) {
        f.ng = -f.ng;
        f.t = -f.t;
        f.b = -f.b;
    }
#else
    // No normals at all (points and lines): face the viewer.
    f.ng = normalize(u_camera_position - v_position);
#endif
    f.n = f.ng;
    f.nc = f.ng;
    return f;
}

void main() {
    Frame f = shading_frame();
    MaterialInputs m = read_material(f.t, f.b, f.ng);
#ifdef ALPHA_MASK
    if (m.discard_fragment) discard;
#endif
    f.n = m.normal;
    f.nc = m.clearcoat_normal;
    vec3 v = normalize(u_camera_position - v_position);
    // Occlusion of indirect light: the material's occlusion texture and the baked visibility
    // (`--ao baked`; front faces: it was measured over the front hemisphere) combined as the
    // smaller of the two, so a crease both darken is not darkened twice. The diffuse share gets
    // back the light its surroundings reflect (ao_multibounce); the diffuse irradiance is looked up
    // along the bent normal, turned as the normal map turns the surface.
    vec3 diffuse_occlusion = vec3(m.occlusion);
    vec3 irradiance_normal = f.n;
    if (v_occlusion.w < 1.0 && gl_FrontFacing) {
        m.occlusion = min(m.occlusion, max(v_occlusion.w, 0.0));
        diffuse_occlusion = ao_multibounce(m.occlusion, m.base_color.rgb);
        vec3 turned = dot(v_occlusion.xyz, v_occlusion.xyz) > 1e-8 ? f.n + normalize(v_occlusion.xyz) - f.ng : f.n;
        if (dot(turned, turned) > 1e-8) irradiance_normal = normalize(turned);
    }
#ifdef FRAME_SSAO
    // Screen-space occlusion (--ao ssao), combined the same way: the smaller of it and the texture's.
    m.occlusion = min(m.occlusion, texelFetch(u_ssao, ivec2(gl_FragCoord.xy) / 2, 0).r);  // at half resolution
    diffuse_occlusion = ao_multibounce(m.occlusion, m.base_color.rgb);
#endif

    vec3 color = vec3(0.0);
#ifdef UNLIT
    color = m.base_color.rgb;
#else
    float n_dot_v = clamped_dot(f.n, v);
    // Directional albedo E of the GGX lobe, for energy compensation of punctual specular.
    float e = brdf_lut(n_dot_v, m.roughness).b;
    vec3 comp_dielectric = u_energy_compensation == 1 ? energy_compensation(m.f0_dielectric * m.specular_weight, e) : vec3(1.0);
    vec3 comp_metal = u_energy_compensation == 1 ? energy_compensation(m.base_color.rgb, e) : vec3(1.0);
#ifdef MATERIAL_CLEARCOAT
    // KHR_materials_clearcoat layering: mix(base, coat, clearcoat * Fc), Fc the Schlick
    // Fresnel of the coat at its normal and the view (the extension's fresnel_coat).
    float cc_n_dot_v = clamped_dot(f.nc, v);
    float cc_mix = m.clearcoat * f_schlick(m.clearcoat_f0, 1.0, cc_n_dot_v);  // brdf::clearcoat_mix
#endif
#ifdef MATERIAL_TRANSMISSION
    // KHR_materials_transmission / _volume (transmission.glsl): the refracted ray through the
    // volume, for punctual lights (the BTDF towards the light seen from its exit) and the
    // refraction of the opaque scene.
    TransmissionInputs tr = read_transmission();
    vec3 tr_ray = volume_ray(f.n, v, tr.thickness, tr.ior, model_scale());
    float tr_ray_length = length(tr_ray);
#endif
#ifndef FRAME_NO_LIGHTS  // a frame without punctual lights (shader_features.h, FrameVariant)
    // A do-while on the count alone (the renderer keeps it <= MAX_LIGHTS): a loop bounded by a
    // constant is unrolled by Mesa's compiler into MAX_LIGHTS masked copies, and a software
    // rasteriser runs every copy (docs/performance.md).
    int i = 0;
    if (u_light_count > 0) do {
#ifdef FRAME_AREA_LIGHTS
        // Rectangles, disks, spheres and tubes (area_lights.glsl): their area integrated, the shadow
        // looked up towards their centre.
        if (u_light_position_type[i].w > 2.5) {
            vec3 pts[17];
            int count = area_light_polygon(i, v_position, pts);
            vec3 to_centre = u_light_position_type[i].xyz - v_position;
            vec3 toward = dot(to_centre, to_centre) > 0.0 ? normalize(to_centre) : f.n;
            color += shade_area_light(m, v, pts, count, u_light_color[i].rgb, toward, comp_dielectric, comp_metal) *
                     shadow_visibility(i, v_position, f.ng, toward);
            continue;
        }
#endif
        vec3 l;
        vec3 radiance = light_incident(i, v_position, l);
        radiance *= shadow_visibility(i, v_position, f.ng, l);
        vec3 lit = shade_light(m, v, l, radiance, comp_dielectric, comp_metal);  // fresnel::shade_light
#ifdef MATERIAL_TRANSMISSION
        vec3 lt = normalize(point_to_light(i, v_position) - tr_ray);
        lit += shade_light_transmission(m, tr, v, l, lt, tr_ray_length, radiance);  // fresnel::shade_light_transmission
#endif
        color += lit;
    } while (++i < u_light_count);
#endif
#ifdef USE_IBL
    {
        // Split-sum image-based light, weighted as the glTF BRDF's dielectric/metal mix.
        vec3 r = reflect(-v, f.n);
        vec3 diffuse = ibl_irradiance(irradiance_normal) * m.base_color.rgb;
        // KHR_materials_diffuse_roughness: the EON lobe's directional albedo at n.v relative to
        // Lambert's (brdf::eon_albedo_factor; 1 for a white surface and for roughness 0).
        diffuse *= eon_albedo_factor(m.base_color.rgb, m.diffuse_roughness, clamped_dot(f.n, v));
#ifdef MATERIAL_DIFFUSE_TRANSMISSION
        // KHR_materials_diffuse_transmission, as the Khronos viewer: the share transmitted sees the
        // irradiance from behind the surface, in its own colour (brdf::diffuse_transmission_mix).
        diffuse = mix(diffuse, ibl_irradiance(-f.n) * m.diffuse_transmission_color, m.diffuse_transmission);
#endif
#ifdef MATERIAL_TRANSMISSION
        diffuse = mix(diffuse, ibl_transmission(m, tr, f.n, v, v_position), tr.factor);
#endif
#ifdef MATERIAL_ANISOTROPY
        vec3 specular = m.anisotropy_strength > 0.0
                            ? ibl_radiance_anisotropic(f.n, v, m.roughness, m.anisotropy_strength, m.anisotropic_b)
                            : ibl_radiance(r, m.roughness);
#else
        vec3 specular = ibl_radiance(r, m.roughness);
#endif
        vec3 fresnel_dielectric = ibl_ggx_fresnel(n_dot_v, m.roughness, m.f0_dielectric, m.specular_weight);
        vec3 fresnel_metal = ibl_ggx_fresnel(n_dot_v, m.roughness, m.base_color.rgb, 1.0);
        vec3 diffuse_weight = 1.0 - fresnel_dielectric;
#ifdef MATERIAL_IRIDESCENCE
        // KHR_materials_iridescence, as the Khronos Sample Viewer: the film's Fresnel at n.v mixed
        // into both lobes' split-sum Fresnel; the diffuse keeps 1 - max(F_film) (brdf::layer).
        IridescenceFresnel film = material_film(m, v);
        if (film.factor > 0.0) {
            diffuse_weight = film_diffuse_weight(fresnel_dielectric, film);
            fresnel_dielectric = mix(fresnel_dielectric, film.dielectric, film.factor);
            fresnel_metal = mix(fresnel_metal, film.metal, film.factor);
        }
#endif
        float so = specular_occlusion(n_dot_v, m.occlusion, m.roughness);  // exactly 1 where occlusion is 1
        vec3 dielectric = diffuse * diffuse_weight * diffuse_occlusion + specular * fresnel_dielectric * so;
        vec3 metal = specular * fresnel_metal * so;
        vec3 ibl = mix(dielectric, metal, m.metallic);
#ifdef MATERIAL_SHEEN
        // KHR_materials_sheen: the Charlie lobe's light over the base, which keeps 1 - max(c) E.
        ibl = ibl_sheen(f.n, v, m.sheen_color, m.sheen_roughness) * m.occlusion +
              ibl * (1.0 - max3(m.sheen_color) * sheen_albedo(n_dot_v, m.sheen_roughness));
#endif
#ifdef MATERIAL_CLEARCOAT
        // The coat reflects the prefiltered environment at its roughness; its Fresnel is cc_mix.
        vec3 coat = ibl_radiance(reflect(-v, f.nc), m.clearcoat_roughness);
        coat *= specular_occlusion(cc_n_dot_v, m.occlusion, m.clearcoat_roughness);
        ibl = mix(ibl, coat, cc_mix);
#endif
        color += ibl;
    }
#elif defined(MATERIAL_TRANSMISSION)
    {
        // No environment: the refracted opaque scene still shows (as in the Khronos viewer,
        // whose image-based light is then only dark), under the same Fresnel weights.
        vec3 fd = ibl_ggx_fresnel(n_dot_v, m.roughness, m.f0_dielectric, m.specular_weight);
        vec3 refraction = tr.factor * ibl_transmission(m, tr, f.n, v, v_position) * (1.0 - fd) * m.occlusion *
                          (1.0 - m.metallic);
#ifdef MATERIAL_CLEARCOAT
        refraction *= 1.0 - cc_mix;
#endif
        color += refraction;
    }
#endif
    // Occlusion applies to indirect light only. A uniform ambient lights both sides: with diffuse
    // transmission the diffuse albedo is mix(base, transmission colour, factor).
    vec3 ambient_albedo = m.base_color.rgb;
    ambient_albedo *= eon_albedo_factor(m.base_color.rgb, m.diffuse_roughness, clamped_dot(f.n, v));
#ifdef MATERIAL_DIFFUSE_TRANSMISSION
    ambient_albedo = mix(ambient_albedo, m.diffuse_transmission_color, m.diffuse_transmission);
#endif
    color += u_ambient * ambient_albedo * (1.0 - m.metallic) * diffuse_occlusion;
#ifdef MATERIAL_CLEARCOAT
    color += m.emissive * (1.0 - cc_mix);  // emission passes through the coat
#else
    color += m.emissive;
#endif
#endif

#ifdef DEBUG_VIEW
    if (u_debug != 0) {
        frag_color = vec4(debug_value(u_debug, m, f.n, f.ng, f.t, f.b, v), 1.0);
        return;
    }
#endif
    // Exposure, tone map and encoding per sample, before the MSAA resolve: edges then
    // average display values, as every display renderer (and the Khronos Sample
    // Viewer) does; with --tonemap none and float output this is linear radiance.
    if (any(isnan(color)) || any(isinf(color))) {
        frag_color = vec4(1.0, 0.0, 1.0, 1.0);  // NaN / Inf shows as magenta
        return;
    }
    color = display_transform(color, u_exposure, u_tonemap, u_encoding);
    frag_color = vec4(color, m.base_color.a);  // straight alpha; blending composites
}
