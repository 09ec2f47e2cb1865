// `fresnel view`: the main panel (file, camera, environment, output, split view, statistics)
// and the file browser, in Dear ImGui over the viewer's state.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <future>

#include "fresnel/core/process_memory.h"
#include "fresnel/gpu/device.h"
#include "fresnel/job/features.h"
#include "fresnel/job/orbit_controller.h"
#include "fresnel/job/settings.h"
#include "fresnel/viewer/files.h"
#include "fresnel/viewer/thumbnails.h"
#include "setting_widgets.h"
#include "viewer_app.h"

namespace fresnel::cli::view {
namespace fs = std::filesystem;
namespace {

template <class E>
bool combo(const char* label, E& value, const std::vector<std::pair<E, std::string>>& items) {
    std::string current;
    for (const auto& [v, n] : items)
        if (v == value) current = n;
    bool changed = false;
    if (ImGui::BeginCombo(label, current.c_str())) {
        for (const auto& [v, n] : items) {
            if (ImGui::Selectable(n.c_str(), v == value)) {
                changed = v != value;
                value = v;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

}  // namespace

void Viewer::draw_gui() {
    draw_gizmos();
    const gui::Size win = window_->window_size();
    if (state_.split) {  // the divider, over the frame and under the panels
        float x = state_.view_left + state_.split_pos * float(state_.view_points().x);
        ImDrawList* d = ImGui::GetBackgroundDrawList();
        d->AddLine(ImVec2(x, 0.0f), ImVec2(x, float(win.height)), IM_COL32(255, 255, 255, 200), 2.0f);
    }
    if (!state_.gui_visible) {
        state_.view_left = 0.0f;
        return;
    }
    // Interactive, in a window wide enough: the panel is a side bar docked at the left, its width
    // the user's (dragged at its right edge, kept in the ImGui settings file), and the 3D view is
    // the rest of the window (State::view_left). Scripts, --screenshot and narrow windows keep the
    // view the whole window (the size --size and a script's screenshots mean) with the panel over it.
    const bool docked = dock_panel_ && win.width >= kMinDockedWindow;
    if (docked) {
        ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
        ImGui::SetNextWindowSize(ImVec2(kPanelWidth, float(win.height)), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSizeConstraints(ImVec2(kMinPanelWidth, float(win.height)),
                                            ImVec2(std::max(kMinPanelWidth, 0.45f * float(win.width)), float(win.height)));
        ImGui::SetNextWindowBgAlpha(1.0f);
    } else {
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(kPanelWidth, 0), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowBgAlpha(0.8f);
    }
    const bool open = ImGui::Begin(docked ? "fresnel view (Tab hides)##docked" : "fresnel view (Tab hides)", nullptr,
                                   docked ? ImGuiWindowFlags_NoMove : 0);
    state_.view_left = docked && open ? ImGui::GetWindowPos().x + ImGui::GetWindowWidth() : 0.0f;
    if (!open) {  // collapsed to its title bar
        ImGui::End();
        return;
    }
    // Labels keep about 11 characters' room, so none is cut at 800x600 or on high-DPI screens.
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 11.0f);
    if (!state_.error.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.35f, 1.0f));
        ImGui::TextWrapped("%s", state_.error.c_str());
        ImGui::PopStyleColor();
        if (ImGui::SmallButton("dismiss")) state_.error.clear();
    }
    if (bake_) {
        ImGui::Text("baking %s", bake_->resolved.environment ? bake_->resolved.environment->describe().c_str() : "");
        ImGui::ProgressBar(bake_->progress->load());
    }
    if (ImGui::CollapsingHeader("File", ImGuiTreeNodeFlags_DefaultOpen)) draw_file_panel();
    if (state_.animated() && ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) draw_animation_panel();
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) draw_camera_panel();
    if (state_.scene && ImGui::CollapsingHeader("Features")) draw_features_panel();
    if (ImGui::CollapsingHeader("Environment")) draw_environment_panel();
    draw_output_panels();
    if (state_.scene && ImGui::CollapsingHeader("Scene")) draw_scene_tree();
    if (ImGui::CollapsingHeader("Lights")) draw_lights_panel();
    if (state_.scene && !state_.scene->materials.empty() && ImGui::CollapsingHeader("Materials")) draw_material_editor();
    if (ImGui::CollapsingHeader("Statistics")) {
        const glm::ivec2 fb = state_.framebuffer;
        ImGui::Text("%dx%d pixels, frame %.1f ms (CPU, draw + finish)", fb.x, fb.y, frame_ms_);
        if (gpu_ms_ >= 0.0) ImGui::Text("GPU %.2f ms (timer query)", gpu_ms_);
        else FRESNEL_HINT("GPU time: this context has no timer queries (OpenGL ES 3.0)");
        ImGui::Text("resident memory %.1f MiB, texture memory %.1f MiB", resident_mib(),
                    double(renderer_->texture_bytes()) / (1024.0 * 1024.0));
        ImGui::Text("%d draw calls, %zu triangles, %zu programs", stats_.draw_calls, stats_.triangles,
                    renderer_->program_count());
        ImGui::Text("%d instanced (%zu placements), %d culled", stats_.instanced_draws, stats_.instances_drawn,
                    stats_.culled_draws);
        ImGui::TextWrapped("%s", window_->context().renderer().c_str());
    }
    if (ImGui::CollapsingHeader("Help")) draw_help_panel();
    if (!state_.status.empty()) FRESNEL_HINT("%s", state_.status.c_str());
    ImGui::PopItemWidth();
    ImGui::End();
    if (state_.browser_open) draw_browser();
}

void Viewer::draw_file_panel() {
    const Job& job = state_.job;
    ImGui::TextWrapped("%s", job.source.model.empty() ? "(built-in demo)" : job.source.model.c_str());
    if (ImGui::Button("Open... (O)")) state_.browser_open = true;
    ImGui::SameLine();
    if (ImGui::Button("< PgUp")) step_folder(-1);
    ImGui::SameLine();
    if (ImGui::Button("PgDn >")) step_folder(+1);
    ImGui::SameLine();
    if (ImGui::Button("Demo")) open_model("", false);
    if (!state_.folder_models.empty()) ImGui::Text("%zu models in this folder", state_.folder_models.size());
    if (!state_.recent.paths().empty() && ImGui::TreeNode("Recent")) {
        std::string chosen;
        for (const auto& r : state_.recent.paths())
            if (ImGui::Selectable(r.c_str())) chosen = r;
        ImGui::TreePop();
        if (!chosen.empty()) open_path(chosen);
    }
    if (!state_.warnings.empty() && ImGui::TreeNode("warnings", "%zu warnings", state_.warnings.size())) {
        for (const auto& w : state_.warnings) ImGui::TextWrapped("%s", w.c_str());
        ImGui::TreePop();
    }
    if (state_.scene && !state_.scene->material_variants.empty()) {  // KHR_materials_variants
        const std::vector<std::string>& names = state_.scene->material_variants;
        const std::string& current = job.source.variant;
        std::string chosen = current;
        if (ImGui::BeginCombo("variant", current.empty() ? "(default materials)" : current.c_str())) {
            if (ImGui::Selectable("(default materials)", current.empty())) chosen.clear();
            for (const std::string& n : names)
                if (ImGui::Selectable(n.c_str(), n == current)) chosen = n;
            ImGui::EndCombo();
        }
        if (chosen != current) state_.job.source.variant = chosen;  // reloaded with the variant's materials (reload_if_needed)
    }
    FRESNEL_HINT("drop a model, a scene file or an environment onto the window");
    ImGui::InputText("##scene-file", &state_.scene_save_path);
    ImGui::SameLine();
    if (ImGui::Button("Save scene (Ctrl+S)")) save_scene(state_.scene_save_path);
}

// Playback of the scene's animations: which one, play/pause, the time, speed and looping
// (the state's Playback; the pose is the job's, as `render --time --animation` takes it).
void Viewer::draw_animation_panel() {
    const std::vector<Animation>& animations = state_.scene->animations;
    Job::Source::Animation& a = state_.job.source.animation;
    auto label = [&](int i) {
        const std::string& n = animations[std::size_t(i)].name;
        return std::to_string(i) + ": " + (n.empty() ? "(unnamed)" : n);
    };
    const std::string all = "all (" + std::to_string(animations.size()) + ")";
    if (ImGui::BeginCombo("animation", a.index < 0 ? all.c_str() : label(a.index).c_str())) {
        if (ImGui::Selectable(all.c_str(), a.index < 0)) state_.set_animation(-1);
        for (int i = 0; i < int(animations.size()); ++i)
            if (ImGui::Selectable(label(i).c_str(), a.index == i)) state_.set_animation(i);
        ImGui::EndCombo();
    }
    if (ImGui::Button(state_.playback.playing ? "Pause (Space)" : "Play (Space)")) state_.play(!state_.playback.playing);
    ImGui::SameLine();
    if (ImGui::Button("Rest pose")) {
        state_.play(false);
        a.time.reset();
        a.index = -1;
    }
    const auto [lo, hi] = state_.animation_range();
    float t = a.at();
    if (ImGui::SliderFloat("time", &t, lo, hi, "%.3f s")) state_.set_time(t);  // scrubbing; playing goes on from there
    ImGui::SliderFloat("speed", &state_.playback.speed, -4.0f, 4.0f, "%.2fx");
    ImGui::SameLine();
    ImGui::Checkbox("loop", &state_.playback.loop);
    if (a.posed()) ImGui::Text("%.3f s of %.3f s%s", double(a.at()), double(hi), posing_.on_gpu() ? "" : ", posed on the CPU");
    else FRESNEL_HINT("rest pose (the file's nodes, no animation applied)");
}

// The mouse and the keys (as `view --help` lists them).
void Viewer::draw_help_panel() {
    static const char* const kKeys[][2] = {
        {"left drag", "orbit (on a light's handle: move it)"},
        {"left click", "select what is under the mouse"},
        {"right/middle drag, shift+left", "pan"},
        {"wheel", "dolly"},
        {"F / R", "frame all / reset the camera"},
        {"A", "auto-rotate the camera"},
        {"Space", "play / pause the animations"},
        {"O", "file browser"},
        {"PageUp / PageDown", "previous / next model of the folder"},
        {"Ctrl+C", "copy the view as a render command"},
        {"Ctrl+S", "save the view as a scene file"},
        {"F12", "screenshot of the 3D view"},
        {"F5", "reload the shaders (--shaders)"},
        {"Tab", "hide / show this panel"},
        {"Escape, Q", "quit"},
    };
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingStretchProp)) {
        for (const auto& k : kKeys) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(k[0]);
            ImGui::TableNextColumn();
            ImGui::TextWrapped("%s", k[1]);
        }
        ImGui::EndTable();
    }
    FRESNEL_HINT("drop a model, a scene file or an environment on the window (docs/view.md)");
}

void Viewer::draw_camera_panel() {
    Job::Camera& c = state_.job.camera;
    const std::optional<CameraSetup>& last = state_.last_camera;
    if (state_.scene && !state_.scene->cameras.empty()) {
        std::string current = c.scene_camera ? state_.camera_label(*c.scene_camera) : "orbit";
        if (ImGui::BeginCombo("view", current.c_str())) {
            if (ImGui::Selectable("orbit", !c.scene_camera)) {
                if (c.scene_camera && last) c = orbit_from_setup(*last, state_.bounds, last->yfov_deg);
            }
            for (int i = 0; i < int(state_.scene->cameras.size()); ++i)
                if (ImGui::Selectable(state_.camera_label(i).c_str(), c.scene_camera == i)) c.scene_camera = i;
            ImGui::EndCombo();
        }
    }
    if (!c.scene_camera) {
        setting_widget(state_.job, "camera.yaw");
        setting_widget(state_.job, "camera.pitch");
        float k = distance_k(c, state_.view_pixels().x, state_.view_pixels().y);
        if (ImGui::DragFloat("distance K", &k, 0.01f, 0.01f, 1e4f, "%.3f")) c.distance_k = std::max(k, 0.01f);
        setting_widget(state_.job, "camera.fov");
        if (c.target) ImGui::Text("target %.3f %.3f %.3f (panned)", c.target->x, c.target->y, c.target->z);
    }
    if (ImGui::Button("Frame all (F)")) c = frame_all(c);
    ImGui::SameLine();
    if (ImGui::Button("Reset (R)")) c = state_.initial_camera;
    if (ImGui::Checkbox("auto-rotate (A)", &state_.spin_camera) && state_.spin_camera) spin_last_.reset();
    if (ImGui::Button("Copy as command line (Ctrl+C)")) copy_command_line();
    if (!state_.command_line.empty()) ImGui::TextWrapped("%s", state_.command_line.c_str());
    FRESNEL_HINT("left drag: orbit; right/middle or shift+left: pan; wheel: dolly");
}

unsigned Viewer::thumbnail(const std::string& preset) {
    auto [it, added] = thumbnails_.try_emplace(preset);
    Thumbnail& t = it->second;
    if (added)
        t.pending = std::async(std::launch::async, [preset] {
            struct Wake {  // draw again when it is ready (or failed)
                ~Wake() { gui::Window::wake(); }
            } wake;
            return viewer::environment_thumbnail(preset, 96);
        });
    if (t.pending.valid() && t.pending.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        try {
            const Image8 rgb = t.pending.get();
            std::vector<std::uint8_t> rgba(std::size_t(rgb.width) * std::size_t(rgb.height) * 4, 255);
            for (std::size_t i = 0; i < std::size_t(rgb.width) * std::size_t(rgb.height); ++i)
                for (int c = 0; c < 3; ++c) rgba[i * 4 + std::size_t(c)] = rgb.pixels[i * 3 + std::size_t(c)];
            t.texture = gpu::Texture::create_2d(rgb.width, rgb.height, gpu::TextureFormat::RGBA8, rgba.data(), false);
            t.texture.set_sampler(gpu::SamplerState::clamped(Filter::Linear));
        } catch (const std::exception&) {
            t.failed = true;  // no picture (a folder without previews, a file that does not read)
        }
    }
    return t.texture ? t.texture.id() : 0u;
}

// Switches, as the Khronos Sample Viewer's: image-based light, the file's punctual lights,
// shadows (settings of their own), and the parts of the file a job can turn off (the setting
// `disable`: skinning, morphing, occlusion, each material extension the file uses), which reload
// the scene without them (fresnel/job/features.h), as `render --disable` loads it.
void Viewer::draw_features_panel() {
    using Kind = Job::Environment::Kind;
    Job& job = state_.job;
    bool ibl = job.environment.kind != Kind::None;
    if (ImGui::Checkbox("image-based light", &ibl)) {
        if (!ibl) {
            environment_before_off_ = job.environment;
            job.environment.kind = Kind::None;
        } else {
            job.environment = environment_before_off_;
            if (job.environment.kind == Kind::None) job.environment.kind = Kind::Automatic;
        }
    }
    setting_widget(job, "sceneLights", "punctual lights (the file's)");
    setting_widget(job, "render.shadows", "shadows##features");  // the Environment panel has one too
    std::vector<std::string> features = scene_features(*state_.scene);
    for (const std::string& f : job.source.disabled)
        if (std::find(features.begin(), features.end(), f) == features.end()) features.push_back(f);
    if (features.empty()) FRESNEL_HINT("the file has no skins, morph targets, occlusion or material extensions");
    std::optional<std::vector<std::string>> next;
    for (const std::string& f : features) {
        const auto at = std::find(job.source.disabled.begin(), job.source.disabled.end(), f);
        bool on = at == job.source.disabled.end();
        const std::string label = (f.starts_with("KHR_materials_") ? f.substr(14) : f) + "##feature";
        if (ImGui::Checkbox(label.c_str(), &on)) {
            next = job.source.disabled;
            if (on) next->erase(next->begin() + (at - job.source.disabled.begin()));
            else next->push_back(f);
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", f.c_str());
    }
    if (next) {  // the scene again without them (reload_if_needed); the view and the playback stay
        std::string list;
        for (const std::string& f : *next) list += (list.empty() ? "" : ",") + f;
        settings::set(job, "disable", list.empty() ? std::string("none") : list, "--disable");
    }
}

void Viewer::draw_environment_panel() {
    using Kind = Job::Environment::Kind;
    Job& job = state_.job;
    Job::Environment& e = job.environment;
    combo<Kind>("light", e.kind,
                {{Kind::Automatic, "automatic"}, {Kind::Studio, "studio"}, {Kind::File, "file"},
                 {Kind::Color, "colour"}, {Kind::None, "none (no IBL)"}});
    // Presets: the built-in studio, the environments beside the model, the recent ones.
    const std::string shown = e.kind == Kind::File ? fs::path(e.path).filename().string() : e.kind == Kind::Studio ? "studio" : "";
    if (ImGui::BeginCombo("preset", shown.empty() ? "(choose)" : shown.c_str(), ImGuiComboFlags_HeightLarge)) {
        const float h = ImGui::GetTextLineHeightWithSpacing() * 1.6f;
        for (const std::string& p : state_.environment_presets()) {
            const bool studio = p == "studio";
            const std::string label = studio ? "studio (built in)" : fs::path(p).filename().string() + "##" + p;
            if (unsigned id = thumbnail(p)) {  // the picture, then the name
                ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(id)), ImVec2(2.0f * h, h));
            } else {
                ImGui::Dummy(ImVec2(2.0f * h, h));
            }
            ImGui::SameLine();
            if (ImGui::Selectable(label.c_str(), studio ? e.kind == Kind::Studio : e.kind == Kind::File && e.path == p,
                                  0, ImVec2(0.0f, h))) {
                if (studio) e.kind = Kind::Studio;
                else state_.open_environment(p);
            }
            if (!studio && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.c_str());
        }
        ImGui::EndCombo();
    }
    if (e.kind == Kind::File) ImGui::TextWrapped("%s", e.path.empty() ? "(drop a .hdr/.exr)" : e.path.c_str());
    if (e.kind == Kind::Color) ImGui::ColorEdit3("colour", &e.color.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
    setting_widget(job, "environment.rotation");
    ImGui::SameLine();
    ImGui::Checkbox("spin", &state_.spin_environment);
    setting_widget(job, "environment.intensity");
    using Mode = Job::Background::Mode;
    combo<Mode>("background", job.background.mode,
                {{Mode::Automatic, "automatic"}, {Mode::Environment, "environment (sharp)"},
                 {Mode::Blurred, "blurred"}, {Mode::Color, "colour"}, {Mode::Transparent, "transparent"}});
    if (job.background.mode == Mode::Color) ImGui::ColorEdit3("background colour", &job.background.color.x);
    setting_widget(job, "sceneLights");
    setting_widget(job, "render.shadows");
    setting_widget(job, "render.envLight", "key light shadowed");
    setting_widget(job, "render.ao", "occlusion (baked)");
}

// "Output" and "Split view".
void Viewer::draw_output_panels() {
    if (ImGui::CollapsingHeader("Output")) {
        for (const char* key : {"render.toneMapping", "render.exposure", "render.encoding", "render.debug",
                                "render.energyCompensation"})
            setting_widget(state_.job, key);
        setting_widget(state_.job, "render.msaa", "MSAA");
        if (ImGui::Button("Screenshot (F12)")) state_.screenshot_requested = true;
    }
    if (ImGui::CollapsingHeader("Split view")) {
        if (ImGui::Checkbox("split (drag the divider)", &state_.split) && state_.split) state_.split_output = state_.job.output;
        if (state_.split) {
            // The right half's output settings, through the registry on a job holding them.
            Job right = state_.job;
            right.output = state_.split_output;
            FRESNEL_HINT("right of the divider:");
            ImGui::PushID("right");
            for (const char* key : {"render.debug", "render.toneMapping", "render.exposure", "render.energyCompensation"})
                setting_widget(right, key);
            ImGui::PopID();
            state_.split_output = right.output;
        }
    }
}

// A file browser in ImGui: folders, models and environments of one folder at a time.
void Viewer::draw_browser() {
    using viewer::is_environment;
    using viewer::is_folder;
    using viewer::is_model;
    fs::path& browser_dir = state_.browser_dir;
    ImGui::SetNextWindowSize(ImVec2(480, 420), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Open", &state_.browser_open)) {
        ImGui::End();
        return;
    }
    std::string dir = browser_dir.string();
    if (ImGui::InputText("folder", &dir, ImGuiInputTextFlags_EnterReturnsTrue)) browser_dir = dir;
    ImGui::BeginChild("entries");
    std::error_code ec;
    std::vector<fs::directory_entry> entries;
    for (fs::directory_iterator it(browser_dir, ec), end; !ec && it != end; it.increment(ec)) entries.push_back(*it);
    if (ec) FRESNEL_HINT("%s", ec.message().c_str());
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
        bool da = is_folder(a.path()), db = is_folder(b.path());
        return da != db ? da : a.path().filename() < b.path().filename();
    });
    fs::path next_dir;
    std::string chosen;
    if (ImGui::Selectable("../")) next_dir = browser_dir.parent_path();
    for (const auto& e : entries) {
        const fs::path& p = e.path();
        if (p.filename().string().starts_with(".")) continue;
        bool dir_entry = is_folder(p) && !is_environment(p);
        if (!dir_entry && !is_model(p) && !is_environment(p)) continue;
        std::string label = p.filename().string() + (dir_entry ? "/" : is_model(p) ? "" : "  (environment)");
        if (ImGui::Selectable(label.c_str())) {
            if (dir_entry) next_dir = p;
            else chosen = p.string();
        }
    }
    ImGui::EndChild();
    ImGui::End();
    if (!next_dir.empty()) browser_dir = next_dir;
    if (!chosen.empty()) {
        open_path(chosen);
        state_.browser_open = false;
    }
}

}  // namespace fresnel::cli::view
