#pragma once
// Phong-era materials (Wavefront MTL, OpenGL 1's glMaterial) in terms of the glTF
// metallic-roughness model: the FIRST, formula-based conversion the OBJ loader uses. It is
// deliberately simple and documented here; a fitted conversion (least squares over rendered
// light and view directions) is to replace it, which is why Material::phong keeps the
// original values.
//
// phong_to_metallic_roughness(PhongExt p), for a material without the PBR extension:
//   base colour     = Kd (map_Kd as base colour texture), alpha = d; d < 1 gives Blend
//   metallic        = 0
//   roughness       = (2 / (Ns + 2))^(1/4): the Blinn-Phong exponent whose lobe matches a
//                     microfacet distribution of GGX alpha = roughness^2 near its peak
//                     (alpha^2 = 2 / (Ns + 2), the usual Beckmann/Blinn-Phong equivalence);
//                     Ns 0 -> 1, Ns 10 -> 0.65, Ns 100 -> 0.37, Ns 1000 -> 0.21
//   specular        = KHR_materials_specular: F0 colour = Ks (specularColorFactor = Ks / 0.04
//                     at the default ior 1.5; map_Ks as specularColorTexture); Ks = 0 or
//                     illum 0/1 (no highlight) give specularFactor 0
//   emissive        = Ke (map_Ke)
//   normal          = norm, else map_bump/bump (treated as a tangent-space normal map, as most
//                     exporters write it), scale = -bm
//   illum 0         = KHR_materials_unlit (colour only)
// With the PBR extension (Pr or Pm or their maps present), Kd is the base colour, Pm the
// metallic factor (default 0), Pr the roughness (default: from Ns as above), and Ks is not
// used; Pc/Pcr become KHR_materials_clearcoat, Ps KHR_materials_sheen (colour Ps, kept),
// aniso/anisor KHR_materials_anisotropy (rotation = anisor * 2 pi), kept.
// Ni is NOT mapped to KHR_materials_ior: most files write Ni 1 (which would mean F0 = 0).
// Scalar maps whose channels differ from glTF's (map_d, map_Pr, map_Pm, map_Ns) are packed
// into images by the loader, which owns the pixels; this function leaves those slots empty.
// Every material from an OBJ file is double-sided (OBJ has no culling; OpenGL 1 draws both).
#include "fresnel/material/legacy_shading.h"
#include "fresnel/material/material.h"

namespace fresnel {

// (2 / (ns + 2))^(1/4), ns clamped to >= 0; in [0, 1].
float phong_shininess_to_roughness(float ns);
// The inverse: 2 / roughness^4 - 2 (roughness clamped to >= 1e-3, so the result is finite).
float roughness_to_phong_shininess(float roughness);

Material phong_to_metallic_roughness(const PhongExt& phong, const std::string& name = {});

// The Phong values the legacy shading models (legacy_shading.h) draw a material with: an OBJ
// material's own MTL block (Material::phong) as read, else a formula-based view of the
// metallic-roughness material, the reverse of the conversion above:
//   Kd = base colour (1 - metallic), map_Kd = the base colour texture, d = base colour alpha,
//   Ks = mix(F0, base colour, metallic) with F0 = 0.04 x specularFactor x specularColorFactor,
//   Ns = roughness_to_phong_shininess(roughness), Ka = Kd, Ke = emissive (x strength).
PhongExt legacy_phong(const Material& m);

// True when the material is a classic Phong-era one (an MTL block without the PBR extension):
// `--shading auto` draws such materials with OpenGL 1's model, every other with glTF's.
bool is_classic_phong(const Material& m);

// The normalized Blinn-Phong model's inputs for a Phong material:
//   base colour = Kd, shininess = Ns (not clamped), fresnel R0 = max(Ks), reflectivity 1,
//   metalness = Pm (0 without the PBR extension); for a material without an MTL block, the
//   glTF values: base colour, roughness_to_phong_shininess(roughness), metalness = metallic and
//   R0 = mix(F0, 1, metallic) (the model's metal term is F x base colour).
legacy::BlinnPhongMaterial blinn_phong_material(const Material& m);

}  // namespace fresnel
