#pragma once
// The viewer's input geometry, without a window: a window point as a world ray of the last
// frame's camera and back, click picking, the handles of added lights and their drags, and
// the auto-rotation's steps. Window points are ImGui's: points from the top left of a window
// `window_size` points large (not framebuffer pixels, which differ on high-DPI screens).
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/scene/pick.h"
#include "fresnel/scene/scene.h"

namespace fresnel::viewer {

struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
};

// The ray from the near plane through `point`; nothing for an empty window or a degenerate camera.
std::optional<Ray> window_ray(const CameraSetup& camera, glm::ivec2 window_size, glm::vec2 point);
// Where the world point `p` shows in the window; nothing when it lies behind the camera.
std::optional<glm::vec2> to_window(const CameraSetup& camera, glm::ivec2 window_size, glm::vec3 p);

// The click selection at a window point: the nearest visible primitive the ray meets (fresnel::pick).
std::optional<PickHit> pick_at(const Scene& scene, const std::vector<NodeInstance>& instances, const CameraSetup& camera,
                               glm::ivec2 window_size, glm::vec2 point);

// Directional lights' handles sit on a sphere around the model (1.25 times its radius, about
// its centre), towards the light; point and spot lights' at their position.
glm::vec3 handle_centre(const Bounds& bounds);
float handle_radius(const Bounds& bounds);
glm::vec3 light_handle(const LightInstance& light, const Bounds& bounds);
// The light whose handle is nearest `mouse` and within `max_points` of it; -1 for none.
int nearest_handle(const std::vector<LightInstance>& lights, const Bounds& bounds, const CameraSetup& camera,
                   glm::ivec2 window_size, glm::vec2 mouse, float max_points = 10.0f);
// A drag of the light's handle along `ray`: a directional light turns to shine from where the
// ray meets the handle sphere (its near side; the point of the ray nearest the centre when it
// misses); a point or spot light moves in the plane through it that faces `camera`.
void drag_light(LightInstance& light, const Ray& ray, const Bounds& bounds, const CameraSetup& camera);

// "Orbit lights around the model": each light turned by `degrees` about +Y through the bounds' centre.
void orbit_lights(std::vector<LightInstance>& lights, const Bounds& bounds, float degrees);
// Auto-rotation turns 30 degrees a second; a frame that took longer than 0.25 s turns as if it took 0.25 s.
float spin_degrees(double seconds);

}  // namespace fresnel::viewer
