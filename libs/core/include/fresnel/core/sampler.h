#pragma once
// How a texture is sampled, in words rather than graphics-API numbers. The scene model
// (fresnel::Sampler) and the GPU layer (gpu::SamplerState) both use these; only libs/gpu
// translates them to OpenGL, and each loader translates its file's values (glTF's numbers
// in the glTF loader).

namespace fresnel {

// Texel filter within one mip level (magnification, or minification's in-level part).
enum class Filter { Nearest, Linear };

// How minification uses the mip chain: not at all, the nearest level, or a blend of the two
// nearest levels. With Filter this spans glTF's six minFilter values.
enum class MipmapMode { None, Nearest, Linear };

// What a texture coordinate outside [0, 1] reads.
enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

}  // namespace fresnel
