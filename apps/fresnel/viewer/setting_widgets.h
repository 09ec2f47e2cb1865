#pragma once
// Dear ImGui widgets for the settings registry (fresnel/job/settings.h): a setting's widget,
// label, range (its slider range), unit, choices and tooltip come from its declaration, and its
// value goes through settings::get / settings::set as in every other front end, so the panels
// hold no per-setting ranges or names of their own.
#include <imgui.h>

#include <string_view>

#include "fresnel/job/job.h"

// A greyed hint, wrapped at the panel's edge (never cut): ImGui::TextDisabled's arguments.
#define FRESNEL_HINT(...)              \
    do {                               \
        ImGui::PushTextWrapPos(0.0f);  \
        ImGui::TextDisabled(__VA_ARGS__); \
        ImGui::PopTextWrapPos();       \
    } while (0)

namespace fresnel::cli::view {

// Draws the widget of the setting `key` for `job`: a checkbox (Bool), a slider (Int, Number;
// a drag field where the slider range is wide), a drop-down (Choice), a field (Vec3); an
// optional setting (Setting::none, "auto") gets a checkbox of its own first. `label`: the
// text shown (default: the key's last part in words, "toneMapping" -> "tone mapping"); "##id"
// suffixes keep two widgets of one key apart. True when the job changed.
bool setting_widget(Job& job, std::string_view key, const char* label = nullptr);

}  // namespace fresnel::cli::view
