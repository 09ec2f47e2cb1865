#pragma once
// The environment as a light for the path tracer: the equirectangular panorama with the
// renderer's orientation (fresnel/ibl/cubemap.h: +Y the top row, +Z the centre column),
// rotation about +Y (RenderSettings::env_rotation_deg: world -> environment turns by
// -angle, as the renderer's u_env_rotation) and intensity, as a piecewise-constant function
// (each direction sees its pixel; at 1k a pixel is 0.35 degrees), importance-sampled by a
// 2-D piecewise-constant distribution over its pixels (luminance times sin(theta), the
// equirectangular map's solid angle per pixel; cells of 2x2 pixels above 512 wide), drawn in
// constant time from an alias table.
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "fresnel/core/image.h"
#include "fresnel/trace/distribution.h"

namespace fresnel::trace {

class EnvironmentLight {
public:
    EnvironmentLight(ImageF panorama, float rotation_deg = 0.0f, float intensity = 1.0f);

    // Radiance arriving from world direction `dir` (unit), travelling along -dir.
    glm::vec3 radiance(glm::vec3 dir) const;

    struct Sample {
        glm::vec3 direction{0.0f, 1.0f, 0.0f};  // world, unit, towards the environment
        glm::vec3 radiance{0.0f};
        float pdf = 0.0f;  // over solid angle; 0: no sample
    };
    Sample sample(glm::vec2 u) const;
    // The density of sample() at world direction `dir`, over solid angle.
    float pdf(glm::vec3 dir) const;

    // World <-> panorama directions (the panorama's frame is that of direction_to_equirect).
    glm::vec3 to_environment(glm::vec3 world) const { return to_env_ * world; }
    glm::vec3 to_world(glm::vec3 env) const { return to_world_ * env; }
    const ImageF& panorama() const { return panorama_; }
    float intensity() const { return intensity_; }

private:
    ImageF panorama_;
    std::vector<glm::vec3> radiance_;  // per pixel, times the intensity
    int cell_ = 1, cells_w_ = 1, cells_h_ = 1;  // the distribution's cells: cell_ x cell_ pixels
    std::vector<float> cell_pdf_;      // density over [0,1)^2 of each cell
    AliasTable alias_;
    glm::mat3 to_env_{1.0f}, to_world_{1.0f};
    float intensity_ = 1.0f;
};

}  // namespace fresnel::trace
