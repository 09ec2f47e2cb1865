#pragma once
// What the viewer shows and what the user has done to it, without a window or GL (after
// Filament's viewer Settings): the job, the loaded scene and its resolution for the last frame,
// the selection, the added lights and their drags, the auto-rotation, the split view, the files
// (folder, recent list, save paths), the material edits' bookkeeping and the messages shown.
// The window (apps/fresnel/viewer/) draws it and feeds it input; scripts change it through
// fresnel/viewer/automation.h; the unit tests drive it directly.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "fresnel/job/job.h"
#include "fresnel/job/orbit_controller.h"
#include "fresnel/scene/pick.h"
#include "fresnel/viewer/files.h"

namespace fresnel::viewer {

struct State {
    // --- what is shown ---
    Job job;
    Job::Camera initial_camera;          // R (and the script's `reset`) return to it
    Job::Environment good_environment;   // the last environment whose lighting loaded
    std::unique_ptr<Scene> scene;        // null until a scene loads
    ResolvedJob resolved;                // the job resolved on the scene for the last frame
    Bounds bounds;                       // resolved.bounds
    std::optional<CameraSetup> last_camera;  // the last drawn frame's camera (picking, handles)
    bool last_transparent = false;
    glm::ivec2 framebuffer{0};  // pixels
    glm::ivec2 window{0};       // points (ImGui's coordinates; differs on high-DPI screens)
    // The 3D view: the window right of `view_left` (points; the side panel's right edge when it
    // is docked at the left, else 0). The frame, the camera's aspect, picking, the light handles
    // and the split view's divider all live in it, so the panel never covers the framed model.
    float view_left = 0.0f;

    // --- files ---
    std::string opened;            // the model or scene file shown ("" for the demo)
    std::string first_scene_file;  // a folder opened on the command line whose first model is a scene file
    std::vector<std::string> folder_models;  // what PageUp/PageDown step through
    RecentFiles recent;
    std::filesystem::path recent_file;       // where `recent` is kept (job.environment.use_cache); empty: nowhere
    std::string scene_save_path = "view.fresnel.json", model_save_path;
    std::filesystem::path browser_dir;       // the file browser's folder
    std::vector<std::string> warnings;       // the loaded files'

    // --- selection and edits ---
    std::optional<PickHit> picked;
    int edit_material = 0;                     // the material editor's material
    std::vector<Material> original_materials;  // as loaded: what the edits are diffed against
    bool materials_edited = false;
    int selected_light = -1, dragging_light = -1;  // indices into job.lights.extra

    // --- the view ---
    bool spin_camera = false, spin_environment = false, orbit_lights = false;
    bool show_gizmos = true, gui_visible = true, browser_open = false, screenshot_requested = false;
    bool split = false;           // the split view: right of the divider, split_output's settings
    float split_pos = 0.5f;       // the divider, 0..1 of the width
    Job::Output split_output;

    // --- animation playback ---
    // The time shown and the animation played are the job's (job.source.animation: a time
    // set poses the scene, unset shows the rest pose), so `print`, save-scene and a screenshot
    // name the pose they show; the window poses the scene for them (fresnel::ScenePoser).
    struct Playback {
        bool playing = false;
        float speed = 1.0f;  // seconds of animation per second
        bool loop = true;    // at the end: back to the start, else stop there
    };
    Playback playback;

    // --- messages ---
    std::string error, status, command_line;

    // The command line's model or folder: a folder shows its first model (a scene file first
    // opens as one: first_scene_file) and PageUp/PageDown step through the folder; a model
    // steps through its siblings. Sets the browser's folder.
    void start_with(const std::string& model_or_folder);
    // The job as the window shows it: at the 3D view's size in pixels.
    Job shown_job() const;
    // The 3D view: its left edge and size in framebuffer pixels, its size in window points, and
    // a window point in the view's points (from its top left).
    int view_left_pixels() const;
    glm::ivec2 view_pixels() const;
    glm::ivec2 view_points() const;
    glm::vec2 in_view(glm::vec2 window_point) const { return window_point - glm::vec2(view_left, 0.0f); }
    OrbitViewport viewport() const;
    // Orbiting, panning or dollying away from a file's camera starts from where it looks.
    void orbit_camera_now();

    bool spinning() const;
    // One step of the auto-rotation after `seconds`: the camera about its target, the
    // environment, the added lights about the model, as switched on.
    void spin(double seconds);

    // The click selection at a window point (needs last_camera): the nearest visible primitive,
    // or none; the material editor follows the selection.
    void pick_at(glm::vec2 point);
    // Selects the primitive of the first instance of `node`; false when no instance is that node.
    bool select_primitive(int node, int primitive);
    // KHR_node_visibility (the renderer must read the instances again); a hidden node's
    // selection is cleared.
    void set_node_visible(int node, bool visible);

    // A light added in front of the model (from azimuth 30, elevation 45), selected; its index.
    int add_light(Light::Type type);
    // Gives an area light a size (a quarter of the model's handle radius across, facing as it
    // is) and the luminance that lights the model as the added point lights do.
    void shape_area_light(LightInstance& light) const;
    void remove_light(int index);
    // Left-button drags of a handle of an added light (the panel's gizmos). `clicked`: the button
    // went down this frame (without Shift), `down`: it is held. True while a handle is dragged
    // (the camera stays).
    bool drag_lights(glm::vec2 mouse, bool clicked, bool down);

    // An environment file: the job's environment and the recent list.
    void open_environment(const std::string& path);
    // Reads recent_file into the list (when the job uses the cache).
    void load_recent();
    // `path` at the front of the recent list, written to recent_file when the job uses the cache.
    void remember(const std::string& path);
    // The environment presets the panel offers: "studio" (built in), the environment files beside
    // the model (.hdr, .exr and baked folders, by name), then the recent environments; each once.
    std::vector<std::string> environment_presets() const;
    // The model PageUp (-1) or PageDown (+1) opens; nothing when no folder is being stepped.
    std::optional<std::string> step_folder(int delta) const;

    // The scene's animations (none: false).
    bool animated() const;
    // The time range of the played animation (job.source.animation.index; all: the union of
    // every animation's keyframes); {0, 0} without animations.
    std::pair<float, float> animation_range() const;
    // Playback: play from the time shown (from the start when at the rest pose or the end), pause.
    void play(bool on);
    // Shows time t (the scene posed at it; playing goes on from there).
    void set_time(float t);
    // Plays animation `index` (-1: all), from the start of its range while playing, else at the time shown.
    void set_animation(int index);
    // One step of playback after `seconds` of wall time: time += seconds * speed, wrapped to the
    // start (loop) or stopped at the end. False when nothing moved (paused, no animation).
    bool advance(double seconds);

    // The split view's divider, in framebuffer pixels (split_pos is 0..1 of the 3D view's width).
    int divider_pixels() const;
    // The scene tree's and the camera menu's names (need a scene).
    std::string node_label(int node) const;
    std::string camera_label(int camera) const;
};

}  // namespace fresnel::viewer
