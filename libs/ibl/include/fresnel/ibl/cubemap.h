#pragma once
// Float RGBA cube maps on the CPU, with the OpenGL face order and orientation
// (+X, -X, +Y, -Y, +Z, -Z; row 0 of a face is its top as uploaded), and the
// equirectangular mapping of the Khronos glTF Sample Viewer at its default
// rotation: +Y is the top row, +Z the centre column (u = 0.5), +X u = 0.25,
// -X u = 0.75, -Z the seam.
#include <array>
#include <cstddef>
#include <functional>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "fresnel/core/image.h"

namespace fresnel::ibl {

// Panorama texture coordinates (u right, v down, both in [0,1]) of a world direction, and back.
glm::vec2 direction_to_equirect(glm::vec3 d);
glm::vec3 equirect_to_direction(glm::vec2 uv);

// The unit direction through the centre of texel (x, y) of `face` in a cube of `size`.
glm::vec3 cube_texel_direction(int face, int x, int y, int size);
// The face a direction hits and its face coordinates s, t in [0,1].
void cube_face_uv(glm::vec3 d, int& face, float& s, float& t);
// Solid angle of texel (x, y) on a face of `size` (same on every face).
float cube_texel_solid_angle(int x, int y, int size);

struct CubeLevel {
    int size = 0;
    std::array<std::vector<float>, 6> faces;  // size*size*4 floats each
    float* texel(int face, int x, int y) { return &faces[std::size_t(face)][(std::size_t(y) * size + x) * 4]; }
    const float* texel(int face, int x, int y) const { return &faces[std::size_t(face)][(std::size_t(y) * size + x) * 4]; }
};

struct Cubemap {
    std::vector<CubeLevel> levels;
    int size() const { return levels.empty() ? 0 : levels[0].size; }
    // Bilinear within the face (clamped at its edges) at one level.
    glm::vec3 sample_level(glm::vec3 dir, int level) const;
    // Trilinear: bilinear at the two levels around `lod`, blended.
    glm::vec3 sample(glm::vec3 dir, float lod) const;
};

Cubemap make_cubemap(int size, int levels);

// Resamples an equirectangular panorama into a cube map (one level), averaging a
// few samples per texel so that panoramas finer than the cube do not alias.
Cubemap cubemap_from_equirect(const ImageF& panorama, int size, unsigned threads = 0);

// Fills levels 1.. of `cube` by 2x2 box filtering down to 1x1.
void build_mip_chain(Cubemap& cube);

}  // namespace fresnel::ibl
