#pragma once
// The rasteriser's fixed limits.

namespace fresnel {

// What the rasteriser's shaders hold: lights shaded per frame (the first ones of a frame; the
// rest are not drawn), joints per skin and morph targets per primitive posed on the GPU (more
// are posed on the CPU).
inline constexpr int kMaxFrameLights = 16;
inline constexpr int kMaxGpuSkinJoints = 32;
inline constexpr int kMaxGpuMorphTargets = 2;

}  // namespace fresnel
