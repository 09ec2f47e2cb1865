// `fresnel view`: what is drawn over the frame (light handles, the picked primitive's box) and
// the panels that edit the scene: lights, the scene tree, materials. The geometry is
// fresnel/viewer/geometry.h's; the edits land in the viewer's state.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "fresnel/scene/pick.h"
#include "fresnel/material/properties.h"
#include "fresnel/viewer/files.h"
#include "fresnel/viewer/geometry.h"
#include "setting_widgets.h"
#include "viewer_app.h"

namespace fresnel::cli::view {
// Light handles and the picked primitive's box, under the panels.
void Viewer::draw_gizmos() {
    if (!state_.last_camera || !state_.scene) return;
    const CameraSetup& camera = *state_.last_camera;
    auto to_window = [&](glm::vec3 p) -> std::optional<glm::vec2> {  // the 3D view's points to the window's
        auto v = viewer::to_window(camera, state_.view_points(), p);
        if (v) v->x += state_.view_left;
        return v;
    };
    const Bounds& bounds = state_.bounds;
    const std::vector<NodeInstance>& instances = state_.resolved.instances;
    const std::optional<PickHit>& picked = state_.picked;
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    if (picked && std::size_t(picked->instance) < instances.size()) {
        Bounds b = primitive_world_bounds(*state_.scene, instances[std::size_t(picked->instance)], picked->primitive);
        if (!b.empty) {
            std::optional<glm::vec2> s[8];
            for (int c = 0; c < 8; ++c)
                s[c] = to_window(glm::vec3((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y, (c & 4) ? b.max.z : b.min.z));
            for (int a = 0; a < 8; ++a)
                for (int bit : {1, 2, 4})
                    if (!(a & bit) && s[a] && s[a | bit])
                        dl->AddLine(ImVec2(s[a]->x, s[a]->y), ImVec2(s[a | bit]->x, s[a | bit]->y), IM_COL32(255, 220, 40, 230), 1.5f);
        }
    }
    if (!state_.show_gizmos) return;
    const glm::vec3 c = viewer::handle_centre(bounds);
    const float radius = viewer::handle_radius(bounds);
    auto draw_light = [&](const LightInstance& l, bool added, bool selected) {
        ImU32 col = !added ? IM_COL32(160, 160, 160, 200) : selected ? IM_COL32(255, 220, 40, 255) : IM_COL32(255, 255, 255, 230);
        glm::vec3 h = added ? viewer::light_handle(l, bounds) : (l.type == Light::Type::Directional ? c - l.direction * radius : l.position);
        auto s = to_window(h);
        if (!s) return;
        ImVec2 at(s->x, s->y);
        if (l.type == Light::Type::Directional) {
            if (auto sc = to_window(c)) dl->AddLine(at, ImVec2(sc->x, sc->y), col, 1.0f);
        } else if (l.type == Light::Type::Spot) {
            if (auto e = to_window(l.position + l.direction * radius * 0.3f)) dl->AddLine(at, ImVec2(e->x, e->y), col, 2.0f);
        } else if (l.type == Light::Type::Tube) {
            if (auto a = to_window(h - l.axis_u), b = to_window(h + l.axis_u); a && b)
                dl->AddLine(ImVec2(a->x, a->y), ImVec2(b->x, b->y), col, 3.0f);
        } else if (l.type == Light::Type::Rect || l.type == Light::Type::Disk) {
            // Its outline (a disk as 16 sides) and a stroke where it faces.
            const glm::vec3 o = h - l.position;  // the handle may sit off the light (an added one's orbit)
            const int sides = l.type == Light::Type::Rect ? 4 : 16;
            std::optional<glm::vec2> prev;
            for (int k = 0; k <= sides; ++k) {
                float a = 6.2831853f * (float(k) + (sides == 4 ? 0.5f : 0.0f)) / float(sides);
                glm::vec3 q = o + l.position + (sides == 4 ? 1.41421356f : 1.0f) * (std::cos(a) * l.axis_u + std::sin(a) * l.axis_v);
                auto w = to_window(q);
                if (w && prev) dl->AddLine(ImVec2(prev->x, prev->y), ImVec2(w->x, w->y), col, 1.5f);
                prev = w;
            }
            if (auto e = to_window(h + l.direction * radius * 0.3f)) dl->AddLine(at, ImVec2(e->x, e->y), col, 2.0f);
        }
        dl->AddCircleFilled(at, 6.0f, col);
        dl->AddCircle(at, 8.0f, IM_COL32(0, 0, 0, 200), 0, 1.5f);
    };
    // The scene's lights (resolved.lights: the scene's, then the added ones), grey, not draggable.
    const std::vector<LightInstance>& extra = state_.job.lights.extra;
    const std::vector<LightInstance>& lights = state_.resolved.lights;
    if (!state_.resolved.default_lights && lights.size() >= extra.size())
        for (std::size_t i = 0; i < lights.size() - extra.size(); ++i) draw_light(lights[i], false, false);
    for (std::size_t i = 0; i < extra.size(); ++i) draw_light(extra[i], true, int(i) == state_.selected_light);
}

void Viewer::draw_lights_panel() {
    Job& job = state_.job;
    ImGui::Checkbox("scene lights##lights", &job.lights.scene_lights);
    ImGui::SameLine();
    ImGui::Checkbox("gizmos", &state_.show_gizmos);
    if (state_.resolved.default_lights)
        FRESNEL_HINT("default key + fill lights (the scene has none; adding one replaces them)");
    const float r = viewer::handle_radius(state_.bounds);
    if (ImGui::Button("+ directional")) state_.add_light(Light::Type::Directional);
    ImGui::SameLine();
    if (ImGui::Button("+ point")) state_.add_light(Light::Type::Point);
    ImGui::SameLine();
    if (ImGui::Button("+ spot")) state_.add_light(Light::Type::Spot);
    if (ImGui::Button("+ rect")) state_.add_light(Light::Type::Rect);
    ImGui::SameLine();
    if (ImGui::Button("+ disk")) state_.add_light(Light::Type::Disk);
    ImGui::SameLine();
    if (ImGui::Button("+ sphere")) state_.add_light(Light::Type::Sphere);
    ImGui::SameLine();
    if (ImGui::Button("+ tube")) state_.add_light(Light::Type::Tube);
    if (ImGui::Checkbox("orbit lights around the model", &state_.orbit_lights) && state_.orbit_lights) spin_last_.reset();
    int remove = -1;
    for (int i = 0; i < int(job.lights.extra.size()); ++i) {
        LightInstance& l = job.lights.extra[std::size_t(i)];
        ImGui::PushID(i);
        bool open = ImGui::TreeNodeEx("light", ImGuiTreeNodeFlags_DefaultOpen | (i == state_.selected_light ? ImGuiTreeNodeFlags_Selected : 0),
                                      "%d: %s", i, light_type_name(l.type));
        if (ImGui::IsItemClicked()) state_.selected_light = i;
        ImGui::SameLine();
        if (ImGui::SmallButton("delete")) remove = i;
        if (open) {
            int type = int(l.type);
            if (ImGui::Combo("type", &type, "directional\0point\0spot\0rect\0disk\0sphere\0tube\0")) {
                const Light::Type was = l.type;
                l.type = Light::Type(type);
                if (l.is_area() && !is_area_light(was)) state_.shape_area_light(l);  // a size and nits for it
            }
            if (l.type != Light::Type::Point && l.type != Light::Type::Sphere) {  // where it shines from, as --light dir:AZ,EL
                glm::vec3 from = -l.direction;
                float el = glm::degrees(std::asin(std::clamp(from.y, -1.0f, 1.0f)));
                float az = glm::degrees(std::atan2(from.x, from.z));
                bool ch = ImGui::DragFloat("azimuth", &az, 0.5f, -180.0f, 180.0f, "%.1f deg");
                ch |= ImGui::DragFloat("elevation", &el, 0.5f, -90.0f, 90.0f, "%.1f deg");
                if (ch) {
                    const float w = 2.0f * glm::length(l.axis_u), h = 2.0f * glm::length(l.axis_v);
                    l.direction = direction_from_angles(az, std::clamp(el, -90.0f, 90.0f));
                    if (l.type == Light::Type::Rect || l.type == Light::Type::Disk) area_light_axes(l.direction, w, h, l.axis_u, l.axis_v);
                    if (l.type == Light::Type::Tube) l.axis_u = l.direction * (0.5f * w);  // (the axis: either way)
                }
            }
            if (l.type == Light::Type::Rect || l.type == Light::Type::Disk) {
                float w = 2.0f * glm::length(l.axis_u), h = 2.0f * glm::length(l.axis_v);
                bool ch = l.type == Light::Type::Rect ? ImGui::DragFloat2("width, height", &w, 0.005f * r, 1e-4f, 1e6f)
                                                      : ImGui::DragFloat("diameter", &w, 0.005f * r, 1e-4f, 1e6f);
                if (l.type == Light::Type::Disk) h = w;
                if (ch) area_light_axes(l.direction, std::max(w, 1e-4f), std::max(h, 1e-4f), l.axis_u, l.axis_v);
            }
            if (l.type == Light::Type::Sphere || l.type == Light::Type::Tube)
                ImGui::DragFloat("radius", &l.radius, 0.002f * r, 1e-4f, 1e6f);
            if (l.type == Light::Type::Tube) {
                float length = 2.0f * glm::length(l.axis_u);
                if (ImGui::DragFloat("length", &length, 0.005f * r, 1e-4f, 1e6f)) l.axis_u = l.direction * (0.5f * std::max(length, 1e-4f));
            }
            if (l.type != Light::Type::Directional) ImGui::DragFloat3("position", &l.position.x, 0.01f * r);
            if (l.type == Light::Type::Directional) {  // the angular radius its soft shadows come from
                float angle = glm::degrees(l.radius);
                if (ImGui::DragFloat("angular radius (0: one direction)", &angle, 0.02f, 0.0f, 20.0f, "%.2f deg"))
                    l.radius = glm::radians(std::clamp(angle, 0.0f, 20.0f));
            }
            float lum = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
            glm::vec3 color = lum > 0.0f ? l.radiance / lum : glm::vec3(1.0f);
            bool ch = ImGui::ColorEdit3("colour", &color.x);
            ch |= ImGui::DragFloat(l.type == Light::Type::Directional ? "lux" : l.is_area() ? "nits" : "candela", &lum,
                                   0.01f * std::max(lum, 1.0f), 0.0f, 1e9f);
            if (ch) l.radiance = color * std::max(lum, 0.0f);
            if (l.type == Light::Type::Point || l.type == Light::Type::Spot) {
                ImGui::DragFloat("range (0: infinite)", &l.range, 0.01f * r, 0.0f, 1e6f);
                // The bulb its soft shadows come from (contact hardening; 0: a point).
                ImGui::DragFloat("bulb radius (0: point)", &l.radius, 0.002f * r, 0.0f, 1e6f);
            }
            if (l.type == Light::Type::Spot) {
                float inner = glm::degrees(l.inner_cone), outer = glm::degrees(l.outer_cone);
                if (ImGui::DragFloatRange2("cone", &inner, &outer, 0.2f, 0.0f, 90.0f, "inner %.1f", "outer %.1f")) {
                    l.outer_cone = glm::radians(std::clamp(outer, 0.1f, 90.0f));
                    l.inner_cone = glm::radians(std::clamp(inner, 0.0f, glm::degrees(l.outer_cone) - 0.05f));
                }
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    if (remove >= 0) state_.remove_light(remove);
    FRESNEL_HINT("drag a handle in the view to move a light");
}

// One node of the scene tree: a visibility box, its children, its mesh's primitives.
void Viewer::draw_tree_node(int n, int depth) {
    const Scene& scene = *state_.scene;
    const std::optional<PickHit>& picked = state_.picked;
    if (n < 0 || std::size_t(n) >= scene.nodes.size() || depth > 64) return;
    const Node& node = scene.nodes[std::size_t(n)];
    ImGui::PushID(n);
    bool visible = node.visible;
    if (ImGui::Checkbox("##visible", &visible)) set_node_visible(n, visible);
    ImGui::SameLine();
    const bool leaf = node.children.empty() && node.mesh < 0;
    const bool selected = picked && picked->node == n;
    bool open = ImGui::TreeNodeEx("node", (leaf ? ImGuiTreeNodeFlags_Leaf : 0) | (selected ? ImGuiTreeNodeFlags_Selected : 0),
                                  "%s", state_.node_label(n).c_str());
    if (open) {
        if (node.mesh >= 0 && std::size_t(node.mesh) < scene.meshes.size()) {
            const auto& prims = scene.meshes[std::size_t(node.mesh)].primitives;
            for (int p = 0; p < int(prims.size()); ++p) {
                const int mat = prims[std::size_t(p)].material;
                std::string label = "primitive " + std::to_string(p) + ": " + std::to_string(prims[std::size_t(p)].triangle_count()) +
                                    " triangles, material " +
                                    (mat >= 0 ? std::to_string(mat) + " " + scene.materials[std::size_t(mat)].name : "default");
                bool sel = picked && picked->node == n && picked->primitive == p;
                if (ImGui::Selectable((label + "##p" + std::to_string(p)).c_str(), sel)) state_.select_primitive(n, p);
            }
        }
        for (int child : node.children) draw_tree_node(child, depth + 1);
        ImGui::TreePop();
    }
    ImGui::PopID();
}

// KHR_node_visibility, live: the renderer's instances are read again.
void Viewer::set_node_visible(int n, bool visible) {
    state_.set_node_visible(n, visible);
    renderer_->update_transforms();
}

void Viewer::draw_scene_tree() {
    const Scene& s = *state_.scene;
    ImGui::Text("%zu nodes, %zu meshes, %zu materials, %zu textures, %zu lights, %zu cameras", s.nodes.size(), s.meshes.size(),
                s.materials.size(), s.textures.size(), s.lights.size(), s.cameras.size());
    if (state_.picked) {
        ImGui::Text("selected: node %d, primitive %d", state_.picked->node, state_.picked->primitive);
        ImGui::SameLine();
        if (ImGui::SmallButton("clear")) state_.picked.reset();
    } else {
        FRESNEL_HINT("click the model to select a primitive");
    }
    const int index = state_.resolved.scene_index >= 0 ? state_.resolved.scene_index : s.default_scene;
    if (index >= 0 && std::size_t(index) < s.scenes.size())
        for (int root : s.scenes[std::size_t(index)]) draw_tree_node(root, 0);
}

// The factors of one material, edited in place: the renderer reads the scene's
// materials at every draw, so the next frame shows them. Not saved to the file.
void Viewer::draw_material_editor() {
    // The body reads the state through the names it had in viewer.cpp (kept as they were).
    std::unique_ptr<Scene>& scene_ = state_.scene;
    int& edit_material_ = state_.edit_material;
    bool& materials_edited_ = state_.materials_edited;
    std::vector<Material>& original_materials_ = state_.original_materials;
    Job& job_ = state_.job;
    std::string& model_save_path_ = state_.model_save_path;
    using viewer::is_gltf;
    auto& mats = scene_->materials;
    edit_material_ = std::clamp(edit_material_, 0, int(mats.size()) - 1);
    auto label = [&](int i) {
        return std::to_string(i) + ": " + (mats[std::size_t(i)].name.empty() ? "(unnamed)" : mats[std::size_t(i)].name);
    };
    if (ImGui::BeginCombo("material", label(edit_material_).c_str())) {
        for (int i = 0; i < int(mats.size()); ++i)
            if (ImGui::Selectable(label(i).c_str(), i == edit_material_)) edit_material_ = i;
        ImGui::EndCombo();
    }
    Material& m = mats[std::size_t(edit_material_)];
    bool e = false;
    // One widget per property of the material property registry (fresnel/material/properties.h):
    // the core's, then those of each block the material has; a block can be added.
    namespace mp = material_properties;
    auto widget = [&](const mp::Property& p) {
        if (!mp::editable(p, m)) return;
        const std::string name(p.name);
        if (p.type == mp::Type::Bool || p.type == mp::Type::Choice) {
            mp::Value v = p.get(m);
            int i = int(v[0]);
            bool changed = false;
            if (p.type == mp::Type::Bool) {
                bool on = i != 0;
                changed = ImGui::Checkbox(name.c_str(), &on);
                i = on ? 1 : 0;
            } else if (ImGui::BeginCombo(name.c_str(), std::string(p.choices[std::size_t(i)]).c_str())) {
                for (int c = 0; c < int(p.choices.size()); ++c)
                    if (ImGui::Selectable(std::string(p.choices[std::size_t(c)]).c_str(), c == i)) i = c, changed = true;
                ImGui::EndCombo();
            }
            if (changed) v[0] = float(i), p.put(m, v), e = true;
            return;
        }
        float* f = p.data(m);
        if (p.type == mp::Type::Color)
            e |= p.width == 4 ? ImGui::ColorEdit4(name.c_str(), f, ImGuiColorEditFlags_Float)
                              : ImGui::ColorEdit3(name.c_str(), f, ImGuiColorEditFlags_Float);
        else if (std::isinf(*f))  // attenuationDistance's default: no absorption until dragged
            e |= ImGui::DragFloat(name.c_str(), f, 0.01f, p.slider_min, p.slider_max, "inf");
        else
            e |= ImGui::SliderFloat(name.c_str(), f, p.slider_min, p.slider_max, "%.3f", ImGuiSliderFlags_AlwaysClamp);
        for (int k = 0; k < p.width; ++k) f[k] = std::clamp(f[k], p.min, p.max);
    };
    for (const mp::Property& p : mp::all())
        if (p.block.empty()) widget(p);
    for (const mp::Block& b : mp::blocks()) {
        if (!b.present(m)) continue;
        const std::string title(b.name);
        if (!ImGui::TreeNode(title.c_str())) continue;
        for (const mp::Property& p : mp::all())
            if (p.block == b.name) widget(p);
        ImGui::TreePop();
    }
    if (ImGui::BeginCombo("add extension", "")) {
        for (const mp::Block& b : mp::blocks())
            if (!b.present(m) && ImGui::Selectable(std::string(b.name).c_str())) b.add(m), e = true;
        ImGui::EndCombo();
    }
    const std::pair<const char*, const TextureSlot*> slots[] = {
        {"baseColor", &m.base_color}, {"metallicRoughness", &m.metallic_roughness}, {"normal", &m.normal},
        {"occlusion", &m.occlusion}, {"emissive", &m.emissive}};
    for (const auto& [name, slot] : slots) {
        if (!slot->valid()) continue;
        FRESNEL_HINT("%s texture %d (uv%d)", name, slot->texture, slot->tex_coord);
        if (auto t = renderer_->texture_preview(slot->texture); t && t->width > 0 && t->height > 0) {
            const float h = 64.0f, w = std::min(h * float(t->width) / float(t->height), 256.0f);
            ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(t->id)), ImVec2(w, h));
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("%dx%d%s", t->width, t->height,
                                  t->srgb     ? " (sRGB: shown decoded, darker)"
                                  : t->packed ? " (stored together: occlusion in R, roughness in G, metallic in B)"
                                              : "");
        }
    }
    if (e) materials_edited_ = true;
    if (materials_edited_ && ImGui::Button("Revert all materials")) {
        mats = original_materials_;
        materials_edited_ = false;
        e = true;
    }
    if (e) posing_.keep_materials();  // the playback keeps the edits
    if (materials_edited_)
        FRESNEL_HINT("edits: in a saved scene (as overrides) and saved to glTF below; not in the command line");
    if (scene_ && job_.source.models.empty() && is_gltf(job_.source.model)) {
        ImGui::InputText("##model-file", &model_save_path_);
        ImGui::SameLine();
        if (ImGui::Button("Save to glTF")) save_model(model_save_path_);
    }
}

}  // namespace fresnel::cli::view
