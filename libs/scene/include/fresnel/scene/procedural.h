#pragma once
// Scenes built in code: the demo sphere grid and simple test geometry.
#include "fresnel/scene/scene.h"

namespace fresnel {

// A UV sphere of radius 1 at the origin (positions, normals, uv0, indices).
Primitive make_uv_sphere(int segments = 64, int rings = 32);

// The built-in demo: a 7x7 grid of spheres, metallic rising by row (bottom 0 to top 1),
// roughness rising by column (left 0 to right 1), base colour a warm copper-like tint.
Scene make_demo_scene();

// A scene of one node holding one mesh with the primitive `p`, and `materials` (which
// p.material indexes, or -1 for the default material): the smallest scene tests draw.
Scene make_single_primitive_scene(Primitive p, std::vector<Material> materials = {});

}  // namespace fresnel
