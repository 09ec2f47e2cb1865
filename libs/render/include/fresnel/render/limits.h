#pragma once
// The rasteriser's fixed limits.

namespace fresnel {

// What the rasteriser's shaders hold: lights shaded per frame (the first ones of a frame; the
// rest are not drawn), joints per skin and morph targets per primitive posed on the GPU (more
// are posed on the CPU, as are morphed primitives of more than 2048 x 2048 vertices). Joint
// matrices and morph displacements are read from float textures (pbr.vert), as the Khronos
// glTF Sample Viewer reads them.
inline constexpr int kMaxFrameLights = 16;
inline constexpr int kMaxGpuSkinJoints = 4096;
inline constexpr int kMaxGpuMorphTargets = 64;

}  // namespace fresnel
