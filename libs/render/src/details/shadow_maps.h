#pragma once
// Where the rasteriser's shadow maps look (no GL): for each punctual light of a frame, the
// light's view and projection of one or more square tiles of a depth atlas.
//   directional: `cascades` orthographic maps, each fitted to a slice of the camera's depth
//     range (the slices split the part of the range the scene occupies, between uniform and
//     logarithmic), narrowed to the scene's own box where that is smaller; sizes step by
//     2^(1/4) and origins snap to whole texels, so the maps hold still while the camera moves;
//   spot: one perspective map over the outer cone (plus the filter's margin);
//   point: six perspective maps, one per cube face (+X, -X, +Y, -Y, +Z, -Z), each a little
//     wider than 90 degrees so that a filter near a face's edge stays inside its tile.
// Every map's depth range holds the whole scene as seen from the light, so casters outside the
// view still cast. shaders/shadows.glsl reads the tiles: a point light's by the major axis of
// the direction from the light, a directional light's first cascade that holds the point.
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/render/limits.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

// Tiles one frame may use: 16 lights can't all have six, the first ones get theirs.
inline constexpr int kMaxShadowTiles = 24;

struct ShadowTile {
    glm::mat4 view_projection{1.0f};  // world -> the depth pass's clip space
    glm::ivec4 rect{0};               // x, y, width, height in atlas texels
    // The world size of one texel: orthographic maps a length, perspective ones a length per
    // unit of distance from the light (shadows.glsl's normal offset).
    float texel_world = 0.0f;
    // A perspective map's depth range (the distances along its axis its depths 0..1 span, as
    // glm::perspective maps them); for an orthographic map, whose depths are linear, near 0 and
    // far the length its depths 0..1 span.
    float near = 0.0f, far = 0.0f;
};

struct LightShadow {
    int first_tile = -1;  // -1: the light casts no shadow this frame
    int tiles = 0;
};

struct ShadowPlan {
    int atlas_width = 0, atlas_height = 0;  // 0: no shadow this frame
    int tile_size = 0;
    std::vector<ShadowTile> tiles;
    std::vector<LightShadow> lights;  // one per light given
    // A tile's filter margin, in texels: the kernel's radius and the bilinear footprint.
    static constexpr int kMarginTexels = 4;
    bool empty() const { return tiles.empty(); }
};

// Plans the maps of the first `light_count` lights of `lights` for a frame seen through
// `camera`, the scene (casters and receivers) inside `scene`. Each tile is `map_size` texels a
// side, smaller when the atlas would exceed `max_texture_size` a side or 4096 x 4096 texels in
// all; a directional light takes `cascades` (1..4) tiles. Nothing when `scene` is empty.
ShadowPlan plan_shadows(const std::vector<LightInstance>& lights, int light_count, const CameraSetup& camera,
                        const Bounds& scene, int map_size, int cascades, int max_texture_size);
// The same into `plan`, whose storage is reused (a warm frame allocates nothing).
void plan_shadows(const std::vector<LightInstance>& lights, int light_count, const CameraSetup& camera,
                  const Bounds& scene, int map_size, int cascades, int max_texture_size, ShadowPlan& plan);

// The tile's matrix for lookups: world -> (u, v, depth) in [0, 1] of the tile itself.
glm::mat4 tile_lookup_matrix(const ShadowTile& tile);

}  // namespace fresnel
