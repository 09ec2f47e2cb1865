#pragma once
// The numeric codes of the glTF 2.0 file format: accessor component types, sampler filters and
// wrap modes, buffer view targets. The specification takes their values from OpenGL's enums;
// here they are file-format vocabulary, read by the glTF loader and written by the scene
// writer, and nothing else sees them: the scene model uses typed enums (scene.h's topology,
// core/sampler.h's filters and wraps).
#include <cstdint>

namespace fresnel::gltf_code {

// The GLB container: its magic ("glTF") and chunk types, little-endian u32s.
constexpr std::uint32_t kGlbMagic = 0x46546C67;
constexpr std::uint32_t kChunkJson = 0x4E4F534A;
constexpr std::uint32_t kChunkBin = 0x004E4942;

// accessor.componentType
constexpr int kByte = 5120;
constexpr int kUnsignedByte = 5121;
constexpr int kShort = 5122;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;

// sampler.magFilter / minFilter
constexpr int kNearest = 9728;
constexpr int kLinear = 9729;
constexpr int kNearestMipmapNearest = 9984;
constexpr int kLinearMipmapNearest = 9985;
constexpr int kNearestMipmapLinear = 9986;
constexpr int kLinearMipmapLinear = 9987;

// sampler.wrapS / wrapT
constexpr int kRepeat = 10497;
constexpr int kClampToEdge = 33071;
constexpr int kMirroredRepeat = 33648;

// bufferView.target
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

}  // namespace fresnel::gltf_code
