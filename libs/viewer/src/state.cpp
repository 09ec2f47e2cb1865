#include "fresnel/viewer/state.h"

#include <algorithm>
#include <cmath>

#include <glm/trigonometric.hpp>

#include "fresnel/job/scene_file.h"
#include "fresnel/viewer/geometry.h"

namespace fresnel::viewer {
namespace fs = std::filesystem;

void State::start_with(const std::string& model) {
    opened = model;
    if (!model.empty() && is_folder(model)) {
        folder_models = list_models(model);
        job.source.model = folder_models.empty() ? std::string() : folder_models.front();
        opened = job.source.model;
        if (folder_models.empty()) error = model + ": no models (.gltf, .glb, .obj, .fresnel.json) in this folder";
        if (!opened.empty() && is_scene_file(opened)) {  // a folder that starts with a scene file
            job.source.model.clear();
            first_scene_file = opened;
        }
    } else if (!model.empty()) {
        folder_models = sibling_models(model);
    }
    browser_dir = job.source.model.empty() ? fs::current_path() : fs::absolute(job.source.model).parent_path();
}

Job State::shown_job() const {
    Job j = job;
    const glm::ivec2 v = view_pixels();
    j.output.width = v.x;
    j.output.height = v.y;
    return j;
}

int State::view_left_pixels() const {
    if (view_left <= 0.0f || window.x <= 0) return 0;
    return std::clamp(int(std::lround(view_left * float(framebuffer.x) / float(window.x))), 0, std::max(framebuffer.x - 1, 0));
}
glm::ivec2 State::view_pixels() const {
    return {std::max(framebuffer.x - view_left_pixels(), 1), std::max(framebuffer.y, 1)};
}
glm::ivec2 State::view_points() const {
    return {std::max(int(std::lround(float(window.x) - view_left)), 1), std::max(window.y, 1)};
}

OrbitViewport State::viewport() const {
    const glm::ivec2 v = view_pixels();
    return OrbitViewport{bounds, v.x, v.y};
}

void State::orbit_camera_now() {
    if (job.camera.scene_camera && last_camera) job.camera = orbit_from_setup(*last_camera, bounds, last_camera->yfov_deg);
}

bool State::spinning() const { return spin_camera || spin_environment || (orbit_lights && !job.lights.extra.empty()); }

void State::spin(double seconds) {
    const float step = spin_degrees(seconds);
    if (spin_camera) {
        orbit_camera_now();
        job.camera.yaw_deg = std::remainder(job.camera.yaw_deg + step, 360.0f);
    }
    if (spin_environment) job.environment.rotation_deg = std::remainder(job.environment.rotation_deg + step, 360.0f);
    if (orbit_lights) viewer::orbit_lights(job.lights.extra, bounds, step);
}

void State::pick_at(glm::vec2 point) {
    picked.reset();
    if (!scene || !last_camera) return;
    picked = viewer::pick_at(*scene, resolved.instances, *last_camera, view_points(), in_view(point));
    if (picked) {
        const Primitive& p = scene->meshes[std::size_t(picked->mesh)].primitives[std::size_t(picked->primitive)];
        if (p.material >= 0) edit_material = p.material;
    }
}

bool State::select_primitive(int node, int primitive) {
    for (std::size_t i = 0; i < resolved.instances.size(); ++i)
        if (resolved.instances[i].node == node) {
            PickHit h;
            h.instance = int(i);
            h.node = node;
            h.mesh = scene->nodes[std::size_t(node)].mesh;
            h.primitive = primitive;
            picked = h;
            const int mat = scene->meshes[std::size_t(h.mesh)].primitives[std::size_t(primitive)].material;
            if (mat >= 0) edit_material = mat;
            return true;
        }
    return false;
}

void State::set_node_visible(int node, bool visible) {
    scene->nodes[std::size_t(node)].visible = visible;
    if (picked && !visible) picked.reset();
}

int State::add_light(Light::Type type) {
    const glm::vec3 c = handle_centre(bounds);
    const float r = handle_radius(bounds);
    LightInstance l;
    l.type = type;
    l.direction = direction_from_angles(30.0f, 45.0f);
    l.position = c - l.direction * r;
    l.radiance = glm::vec3(type == Light::Type::Directional ? 3.0f : 3.0f * r * r);
    l.outer_cone = glm::radians(30.0f);
    l.inner_cone = glm::radians(15.0f);
    if (l.is_area()) shape_area_light(l);
    job.lights.extra.push_back(l);
    selected_light = int(job.lights.extra.size()) - 1;
    return selected_light;
}

void State::shape_area_light(LightInstance& l) const {
    const float r = handle_radius(bounds);
    const float size = 0.25f * r;
    area_light_axes(l.direction, size, size, l.axis_u, l.axis_v);  // a disk: its radii
    l.radius = 0.5f * size;
    if (l.type == Light::Type::Tube) {  // twice as long as the others are wide, a tenth as thick, across the view
        l.direction = glm::vec3(1.0f, 0.0f, 0.0f);
        l.axis_u = l.direction * size;
        l.axis_v = glm::vec3(0.0f);
        l.radius = 0.05f * size;
    }
    // The luminous intensity 3 r^2 cd of an added point light, spread over the area seen face on.
    const float seen = l.type == Light::Type::Sphere ? 3.14159265f * l.radius * l.radius
                       : l.type == Light::Type::Tube ? 4.0f * l.radius * glm::length(l.axis_u)  // seen side on
                                                     : l.area();
    const float lum = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
    const glm::vec3 color = lum > 0.0f ? l.radiance / lum : glm::vec3(1.0f);
    l.radiance = color * (3.0f * r * r / std::max(seen, 1e-12f));
}

void State::remove_light(int index) {
    if (index < 0 || index >= int(job.lights.extra.size())) return;
    job.lights.extra.erase(job.lights.extra.begin() + index);
    selected_light = -1;
    dragging_light = -1;
}

bool State::drag_lights(glm::vec2 mouse, bool clicked, bool down) {
    if (!gui_visible || !show_gizmos) return false;
    if (clicked) {
        dragging_light = last_camera ? nearest_handle(job.lights.extra, bounds, *last_camera, view_points(), in_view(mouse)) : -1;
        if (dragging_light >= 0) selected_light = dragging_light;
    }
    if (!down) dragging_light = -1;
    if (dragging_light < 0 || dragging_light >= int(job.lights.extra.size())) return false;
    std::optional<Ray> ray = last_camera ? window_ray(*last_camera, view_points(), in_view(mouse)) : std::nullopt;
    if (ray) drag_light(job.lights.extra[std::size_t(dragging_light)], *ray, bounds, *last_camera);
    return true;
}

void State::open_environment(const std::string& path) {
    job.environment.kind = Job::Environment::Kind::File;
    job.environment.path = path;
    if (!path.empty()) remember(path);
}

void State::load_recent() {
    if (job.environment.use_cache && !recent_file.empty()) recent.load(recent_file);
}

void State::remember(const std::string& path) {
    recent.add(path);
    if (job.environment.use_cache && !recent_file.empty()) recent.save(recent_file);
}

std::optional<std::string> State::step_folder(int delta) const { return viewer::step_folder(folder_models, opened, delta); }

int State::divider_pixels() const {
    const int left = view_left_pixels();
    return std::clamp(left + int(split_pos * float(view_pixels().x) + 0.5f), left, framebuffer.x);
}

std::string State::node_label(int n) const {
    const Node& node = scene->nodes[std::size_t(n)];
    std::string s = node.name.empty() ? "node " + std::to_string(n) : node.name;
    if (node.mesh >= 0) s += "  [mesh " + std::to_string(node.mesh) + "]";
    if (node.light >= 0) s += "  [light " + std::to_string(node.light) + "]";
    if (node.camera >= 0) s += "  [camera " + std::to_string(node.camera) + "]";
    return s;
}

std::string State::camera_label(int i) const {
    const std::string& name = scene->cameras[std::size_t(i)].name;
    return "camera " + std::to_string(i) + (name.empty() ? "" : ": " + name);
}

std::vector<std::string> State::environment_presets() const {
    std::vector<std::string> out = {"studio"};
    auto add = [&](const std::string& p) {
        if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
    };
    if (!job.source.model.empty()) {
        std::vector<std::string> beside;
        std::error_code ec;
        const fs::path folder = fs::path(job.source.model).parent_path();
        for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec), end; !ec && it != end; it.increment(ec))
            if (is_environment(it->path())) beside.push_back((folder / it->path().filename()).string());
        std::sort(beside.begin(), beside.end());
        for (const std::string& p : beside) add(p);
    }
    for (const std::string& p : recent.paths())
        if (is_environment(p)) add(p);
    return out;
}

bool State::animated() const { return scene && !scene->animations.empty(); }

std::pair<float, float> State::animation_range() const {
    if (!animated()) return {0.0f, 0.0f};
    const auto& all = scene->animations;
    const int index = job.source.animation.index;
    if (index >= 0 && std::size_t(index) < all.size()) return {all[std::size_t(index)].start(), all[std::size_t(index)].end()};
    float lo = all.front().start(), hi = all.front().end();
    for (const Animation& a : all) lo = std::min(lo, a.start()), hi = std::max(hi, a.end());
    return {lo, hi};
}

void State::play(bool on) {
    playback.playing = on && animated();
    if (!playback.playing) return;
    const auto [lo, hi] = animation_range();
    std::optional<float>& t = job.source.animation.time;
    if (!t || *t >= hi || *t < lo) t = lo;
}

void State::set_time(float t) {
    if (std::isfinite(t)) job.source.animation.time = t;
}

void State::set_animation(int index) {
    job.source.animation.index = index;
    const auto [lo, hi] = animation_range();
    std::optional<float>& t = job.source.animation.time;
    if (playback.playing || !t) t = lo;
    else t = std::clamp(*t, lo, hi);
}

bool State::advance(double seconds) {
    if (!playback.playing || !animated()) return false;
    const auto [lo, hi] = animation_range();
    const double length = double(hi) - double(lo);
    double t = double(job.source.animation.at()) + seconds * double(playback.speed);
    if (length <= 0.0) {
        t = lo;
    } else if (t > hi || t < lo) {
        if (playback.loop) {
            t = double(lo) + std::fmod(t - double(lo), length);
            if (t < lo) t += length;  // playing backwards
        } else {
            t = std::clamp(t, double(lo), double(hi));
            playback.playing = false;
        }
    }
    job.source.animation.time = float(t);
    return true;
}

}  // namespace fresnel::viewer
