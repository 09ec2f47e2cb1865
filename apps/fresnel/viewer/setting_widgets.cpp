#include "setting_widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "fresnel/job/settings.h"

namespace fresnel::cli::view {
namespace {

// "render.toneMapping" -> "tone mapping".
std::string words(std::string_view key) {
    std::string_view last = key.substr(key.find_last_of('.') == std::string_view::npos ? 0 : key.find_last_of('.') + 1);
    std::string out;
    for (char c : last) {
        if (std::isupper(static_cast<unsigned char>(c))) {
            out += ' ';
            out += char(std::tolower(static_cast<unsigned char>(c)));
        } else {
            out += c;
        }
    }
    return out;
}

}  // namespace

bool setting_widget(Job& job, std::string_view key, const char* label) {
    using settings::Type;
    const settings::Setting& s = settings::at(key);
    settings::Value v = s.get(job);  // the value itself, not its text: this runs every frame
    const std::string name = label ? std::string(label) : words(s.key);
    const std::string id = "##" + s.key + (label ? std::string(label) : "");
    const double lo = s.slider_lo(), hi = s.slider_hi();
    bool changed = false;
    if (!s.none.empty()) {
        // An optional setting: its "none" word (auto, fit) as a checkbox; the value when unticked.
        bool unset = v.unset;
        if (ImGui::Checkbox((s.none + id + "none").c_str(), &unset)) {
            changed = true;
            v.unset = unset;
            if (!unset) v.number = std::clamp(v.number, lo, hi);
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", s.doc.c_str());
        ImGui::SameLine();
        if (v.unset) {
            ImGui::TextUnformatted(name.c_str());
            if (changed) s.put(job, v);
            return changed;
        }
    }
    const std::string shown = name + id;
    const std::string unit = s.unit.empty() ? "" : " " + s.unit;
    switch (s.type) {
        case Type::Bool:
            changed |= ImGui::Checkbox(shown.c_str(), &v.flag);
            break;
        case Type::Int: {
            int i = int(v.number);
            if (ImGui::SliderInt(shown.c_str(), &i, int(lo), int(hi), ("%d" + unit).c_str())) {
                v.number = std::clamp(double(i), s.min, s.max);
                changed = true;
            }
            break;
        }
        case Type::Number: {
            float f = float(v.number);
            const std::string format = "%.2f" + unit;
            // A slider where the range is a handful of units; a drag field (clamped to the hard
            // range) where it is wide or open-ended.
            const bool slider = std::isfinite(hi - lo) && hi - lo <= 400.0;
            const bool moved = slider ? ImGui::SliderFloat(shown.c_str(), &f, float(lo), float(hi), format.c_str())
                                      : ImGui::DragFloat(shown.c_str(), &f, 0.01f, float(std::max(s.min, -1e9)),
                                                         float(std::min(s.max, 1e9)), format.c_str());
            if (moved) {
                v.number = std::clamp(double(f), s.min, s.max);
                changed = true;
            }
            break;
        }
        case Type::Choice:
            if (ImGui::BeginCombo(shown.c_str(), v.text.c_str())) {
                for (const std::string& c : s.choices)
                    if (ImGui::Selectable(c.c_str(), c == v.text) && c != v.text) v.text = c, changed = true;
                ImGui::EndCombo();
            }
            break;
        case Type::Vec3:
            if (ImGui::DragFloat3(shown.c_str(), &v.vec.x, 0.01f, float(std::max(s.min, -1e9)), float(std::min(s.max, 1e9))))
                changed = true;
            break;
        case Type::Size:
        case Type::Text:
            ImGui::Text("%s: %s", name.c_str(), settings::get(job, s).c_str());  // set by the panel's own controls
            break;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)", s.doc.c_str(), s.expected().c_str());
    // Every value the widgets give is within the setting's range (clamped) or one of its choices.
    if (changed) s.put(job, v);
    return changed;
}

}  // namespace fresnel::cli::view
