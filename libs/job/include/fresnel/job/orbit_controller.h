#pragma once
// Mouse and keyboard camera control on Job::Camera's terms, so that every view a viewer
// shows is a `fresnel render` camera (--yaw --pitch --distance --fov --target): orbit turns
// yaw and pitch, pan moves the target in the image plane, dolly scales K (D = K R). Plain
// functions of the camera, the bounds and the viewport size: no window, no state.
#include "fresnel/job/camera.h"
#include "fresnel/job/job.h"

namespace fresnel {

struct OrbitViewport {
    Bounds bounds;
    int width = 1, height = 1;  // the framebuffer, pixels
};

// The K that fits the bounds (camera.h): 1/sin(a), a = min(vfov/2, atan(tan(vfov/2) W/H)).
float fit_distance_k(float yfov_deg, int width, int height);
// The camera's K: distance_k, or the fit when unset.
float distance_k(const Job::Camera& camera, int width, int height);

// Left drag by (dx, dy) pixels (x right, y down): the model turns with the cursor
// (yaw -= dx * deg_per_pixel, pitch += dy * deg_per_pixel, pitch kept within +-89.9).
Job::Camera orbit(Job::Camera camera, float dx, float dy, float deg_per_pixel = 0.3f);
// Right/middle drag: the target moves in the image plane so that the point at the
// target's depth follows the cursor.
Job::Camera pan(Job::Camera camera, const OrbitViewport& view, float dx, float dy);
// Wheel: K *= factor (factor < 1 moves closer), K kept within [0.01, 1e4].
Job::Camera dolly(Job::Camera camera, const OrbitViewport& view, float factor);
// The wheel's factor for `clicks` (positive: towards the model): 0.9^clicks.
float dolly_factor(float clicks);
// Frame all: the bounds' centre and the fitting distance again (yaw, pitch and fov kept).
Job::Camera frame_all(Job::Camera camera);
// The orbit camera that looks from `setup`'s eye the same way (roll dropped): for
// orbiting away from a file's camera. The target lies on the view axis, as far as the
// bounds' centre is along it (at least R/100).
Job::Camera orbit_from_setup(const CameraSetup& setup, const Bounds& bounds, float yfov_deg);

}  // namespace fresnel
