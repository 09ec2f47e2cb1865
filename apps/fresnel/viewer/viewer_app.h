#pragma once
// `fresnel view`'s window: the GL and Dear ImGui layer over the viewer library
// (libs/viewer: fresnel::viewer::State, the script's Automation, the input geometry and the
// file handling). One class, its parts in one file each:
//   viewer_app.cpp  the loop, the environment bake, the frame, screenshots, run_viewer()
//   content.cpp     opening models, scene files, environments and folders; saving; shaders
//   input.cpp       mouse and keys, the command line copy
//   panels.cpp      the main panel (file, camera, environment, output, split view, statistics), the file browser
//   scene_panels.cpp  the gizmos, the lights panel, the scene tree, the material editor
//   setting_widgets.cpp  a setting's widget from the settings registry (the panels' controls)
//
// The frame is the renderer's, for the Job the state describes at the window's framebuffer
// size (resolve(), the same Renderer, RenderTarget::default_framebuffer); the GUI is drawn
// on top afterwards. Nothing is drawn while nothing changes (the loop waits for events);
// environments bake on a worker thread while the window keeps answering. A file that does
// not load leaves the current scene (or environment) as it was and shows the loader's error.
#include <imgui.h>

#include <atomic>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.h"
#include "fresnel/gpu/resources.h"
#include "fresnel/gui/window.h"
#include "fresnel/render/renderer.h"
#include "fresnel/render/scene_posing.h"
#include "fresnel/viewer/automation.h"
#include "fresnel/viewer/state.h"
#include "viewer.h"

namespace fresnel::cli::view {

// An environment preset's picture (fresnel/viewer/thumbnails.h), made on a worker thread and
// uploaded when ready; `failed` when it could not be made (no picture is shown).
struct Thumbnail {
    std::future<Image8> pending;
    gpu::Texture texture;
    bool failed = false;
};

// An environment bake running on a worker thread.
struct Bake {
    std::string key;
    ResolvedJob resolved;
    std::shared_ptr<std::atomic<float>> progress = std::make_shared<std::atomic<float>>(0.0f);
    std::future<JobLighting> result;
};

// The frame in the window's back buffer as `fresnel render` writes it (rows top to bottom;
// RGB, or RGBA for transparent frames): `width` x `height` pixels from column `x`.
Image8 read_frame(int x, int width, int height, bool alpha);

class Viewer : public viewer::AutomationHost {
public:
    // `defaults`: the job of the flags alone (scene files opened later are read onto it, then
    // the flags given override them, as on the command line).
    Viewer(const ViewOptions& options, Job job, Job defaults, std::vector<viewer::Command> script);
    int run();

    // The script's side that needs the window (viewer::AutomationHost).
    void screenshot(const std::string& path) override;
    bool open(const std::string& path) override { return open_model(path, false); }
    bool save_model(const std::string& path) override;
    bool save_scene(const std::string& path) override;
    bool reload_shaders(const std::string& folder) override;
    void set_material_field(Material& material, const std::string& field, const std::vector<float>& values) override;
    void node_visibility_changed() override { renderer_->update_transforms(); }
    std::string stats() override;
    std::string render_command_line(const Job& job) override;
    void print(const std::string& line) override;
    void report_error(const std::string& message) override;

private:
    // viewer_app.cpp
    void release_gpu();
    void save_gui_layout();
    int loop(gui::Window& window);
    bool update_lighting();
    void reload_if_needed();
    void sync_pose();
    // --ao baked / `set render.ao`: bakes the shown scene's occlusion when the job asks for it and
    // the renderer does not hold it (a new scene, other rays), or drops it.
    bool sync_occlusion();  // true when it changed what the renderer holds
    int occlusion_rays_ = 0;  // rays per vertex of what the renderer holds; 0: none
    void draw_scene();
    // Something moves by the clock: auto-rotation or animation playback.
    bool moving() const { return state_.spinning() || state_.playback.playing; }
    // content.cpp
    bool open_model(const std::string& path, bool keep_camera);
    bool open_scene_file(const std::string& path);
    bool load_job(Job job, const std::string& label);
    void open_path(const std::string& path);
    void step_folder(int delta);
    void add_material_overrides(Job& job) const;  // the material edits as scene-file overrides
    bool shaders_changed();
    // input.cpp
    bool handle_input();
    void spin();
    void copy_command_line();
    std::string screenshot_name() const;
    // panels.cpp
    void draw_gui();
    void draw_file_panel();
    void draw_animation_panel();
    void draw_features_panel();
    void draw_help_panel();
    // The preset's thumbnail texture (GL name), 0 while it is being made or when there is none.
    unsigned thumbnail(const std::string& preset);
    void draw_camera_panel();
    void draw_environment_panel();
    void draw_output_panels();
    void draw_browser();
    // scene_panels.cpp
    void draw_gizmos();
    void draw_lights_panel();
    void draw_tree_node(int n, int depth);
    void draw_scene_tree();
    void set_node_visible(int n, bool visible);
    void draw_material_editor();

    const ViewOptions& options_;
    Job defaults_;
    viewer::State state_;
    viewer::Automation automation_;
    gui::Size window_size_;
    gui::Window* window_ = nullptr;
    std::unique_ptr<Renderer> renderer_;
    JobLighting lighting_;
    ScenePosing posing_;  // state_.scene posed in place at the state's time
    // The side panel docks at the left of interactive windows (not under a script or --screenshot).
    bool dock_panel_ = false;
    static constexpr float kPanelWidth = 320.0f, kMinPanelWidth = 240.0f;
    static constexpr int kMinDockedWindow = 560;  // points: narrower windows keep the panel floating
    std::string imgui_ini_;  // where ImGui keeps the panel's layout (the cache folder), or empty
    Job::Source loaded_source_;               // what state_.scene was loaded with (its animation unset)
    std::map<std::string, Thumbnail> thumbnails_;  // by preset
    Job::Environment environment_before_off_;  // what the Features panel's image-based light switch turns back to
    static constexpr const char* kNoLighting = "(none yet)";
    std::string lighting_key_ = kNoLighting, failed_key_;
    std::unique_ptr<Bake> bake_;
    bool bake_failed_ = false;
    FrameStats stats_;
    double frame_ms_ = 0.0, gpu_ms_ = -1.0;  // gpu_ms_ < 0: no timer queries (or no result yet)
    std::unique_ptr<gpu::TimerQuery> timer_;
    std::string gui_gl_errors_;
    std::optional<Clock::time_point> spin_last_;
    std::map<std::string, std::pair<std::uintmax_t, std::filesystem::file_time_type>> shader_files_;  // --watch-shaders
    glm::vec2 press_at_{0.0f};
    bool press_moved_ = false, dragging_divider_ = false;
};

}  // namespace fresnel::cli::view
