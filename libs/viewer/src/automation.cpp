#include "fresnel/viewer/automation.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "fresnel/job/lights.h"
#include "fresnel/job/orbit_controller.h"
#include "fresnel/job/render_settings.h"
#include "fresnel/job/settings.h"

namespace fresnel::viewer {


Automation::Automation(std::vector<Command> commands, std::string script)
    : commands_(std::move(commands)), script_(std::move(script)) {}

void Automation::fail(AutomationHost& host, int line, const std::string& what) {
    host.report_error(script_ + ": line " + std::to_string(line) + ": " + what);
    failed_ = true;
}

bool Automation::step(State& s, AutomationHost& host, bool ready) {
    if (wait_ > 0) {
        --wait_;
        return false;
    }
    while (position_ < commands_.size()) {
        Command c = commands_[position_];  // a copy: `set environment` becomes `env`
        auto failed = [&](const std::string& what) { fail(host, c.line, what); };
        const OrbitViewport view = s.viewport();
        if (c.name == "orbit" || c.name == "pan" || c.name == "dolly") s.orbit_camera_now();
        if (c.name == "screenshot") {
            if (!ready || !s.scene) return false;  // after the bake, with the frame drawn
            try {
                host.screenshot(c.args[0]);
            } catch (const std::exception& e) {
                failed(e.what());
            }
            ++position_;
            continue;
        }
        ++position_;
        if (c.name == "quit") return true;
        if (c.name == "wait") {
            wait_ = int(c.number(0));
            return false;
        }
        if (c.name == "set" && c.args[0] == "environment") {  // as `env`: a file is opened, a broken one reported
            c.name = "env";
            c.args = {c.args[1]};
        } else if (c.name == "set" && c.args[0] != "material") {  // a setting, checked when the script was read
            settings::set(s.job, c.args[0], c.args[1], script_);
            return false;
        }
        if (c.name == "set") {
            const std::size_t index = std::size_t(c.number(1));
            std::vector<float> values;
            for (std::size_t i = 3; i < c.args.size(); ++i) values.push_back(c.number(i));
            if (!s.scene || index >= s.scene->materials.size()) {
                failed("set material: no material " + c.args[1] + " (the scene has " +
                       std::to_string(s.scene ? s.scene->materials.size() : 0) + ")");
            } else {
                host.set_material_field(s.scene->materials[index], c.args[2], values);
                s.materials_edited = true;
            }
            return false;  // the next frame shows it
        }
        if (c.name == "split") {
            s.split = c.args[0] != "off";
            if (s.split) {
                s.split_output = s.job.output;
                s.split_output.debug = parse_debug_channel(c.args[0]).value_or(DebugChannel::None);
                s.split_pos = c.number(1);
            }
            return false;
        }
        if (c.name == "save") {  // the material edits into a glTF file
            if (!host.save_model(c.args[0])) failed("save " + c.args[0] + ": " + s.error);
            continue;
        }
        if (c.name == "save-scene") {
            if (!host.save_scene(c.args[0])) failed("save-scene " + c.args[0] + ": " + s.error);
            continue;
        }
        if (c.name == "reload-shaders") {
            if (!host.reload_shaders(c.args.empty() ? std::string() : c.args[0])) failed("reload-shaders: " + s.error);
            return false;  // the next frame draws with them
        }
        if (c.name == "auto-rotate") {
            (c.args[0] == "env" ? s.spin_environment : s.spin_camera) = c.args[1] == "on";
            return false;
        }
        if (c.name == "stats") {
            host.print(host.stats());
            continue;
        }
        if (c.name == "print") {
            host.print(host.render_command_line(s.shown_job()));
            continue;
        }
        if (c.name == "pick") {  // after the frame it clicks on is drawn
            if (!ready || !s.scene || !s.last_camera) {
                --position_;
                return false;
            }
            s.pick_at({c.number(0), c.number(1)});
            if (s.picked) {
                const PickHit& h = *s.picked;
                const int mat = s.scene->meshes[std::size_t(h.mesh)].primitives[std::size_t(h.primitive)].material;
                char line[200];
                std::snprintf(line, sizeof line, "{\"node\":%d,\"mesh\":%d,\"primitive\":%d,\"material\":%d,\"distance\":%.6g}",
                              h.node, h.mesh, h.primitive, mat, double(h.distance));
                host.print(line);
            } else {
                host.print("{\"node\":null}");
            }
            return false;  // the highlight shows in the next frame
        }
        if (c.name == "light") {
            s.job.lights.extra.push_back(parse_light(c.args[0]));  // checked when the script was read
            return false;
        }
        if (c.name == "light-remove") {
            const std::size_t i = std::size_t(c.number(0));
            if (i < s.job.lights.extra.size()) s.job.lights.extra.erase(s.job.lights.extra.begin() + std::ptrdiff_t(i));
            else failed("light-remove: no added light " + c.args[0]);
            return false;
        }
        if (c.name == "play" || c.name == "pause") {
            if (c.name == "play" && !s.animated()) failed("play: the scene has no animations");
            s.play(c.name == "play");
            return false;
        }
        if (c.name == "time") {
            s.set_time(c.number(0));
            return false;
        }
        if (c.name == "animation") {
            const int n = c.args[0] == "all" ? -1 : int(c.number(0));
            const std::size_t count = s.scene ? s.scene->animations.size() : 0;
            if (n >= 0 && std::size_t(n) >= count)
                failed("animation: no animation " + c.args[0] + " (the scene has " + std::to_string(count) + ")");
            else s.set_animation(n);
            return false;
        }
        if (c.name == "speed") {
            s.playback.speed = c.number(0);
            continue;
        }
        if (c.name == "loop") {
            s.playback.loop = c.args[0] == "on";
            continue;
        }
        if (c.name == "orbit-lights") {
            s.orbit_lights = c.args[0] == "on";
            return false;
        }
        if (c.name == "select") {
            const std::size_t n = std::size_t(c.number(0));
            if (!s.scene || n >= s.scene->nodes.size() || s.scene->nodes[n].mesh < 0) failed("select: node " + c.args[0] + " has no mesh");
            else s.select_primitive(int(n), 0);
            return false;
        }
        if (c.name == "hide" || c.name == "show") {
            const std::size_t n = std::size_t(c.number(0));
            if (!s.scene || n >= s.scene->nodes.size()) {
                failed(c.name + ": no node " + c.args[0]);
            } else {
                s.set_node_visible(int(n), c.name == "show");
                host.node_visibility_changed();
            }
            return false;
        }
        if (c.name == "orbit") s.job.camera = orbit(s.job.camera, -c.number(0), c.number(1), 1.0f);
        else if (c.name == "pan") s.job.camera = pan(s.job.camera, view, c.number(0), c.number(1));
        else if (c.name == "dolly") s.job.camera = dolly(s.job.camera, view, c.number(0));
        else if (c.name == "reset") s.job.camera = s.initial_camera;
        else if (c.name == "frame") s.job.camera = frame_all(s.job.camera);
        else if (c.name == "camera" && c.args[0] == "orbit") s.orbit_camera_now();
        else if (c.name == "camera") s.job.camera.scene_camera = int(c.number(0));
        else if (c.name == "open") {
            if (!host.open(c.args[0])) failed("open " + c.args[0] + ": " + s.error);
        } else if (c.name == "env") {
            env_line_ = c.line;
            try {  // the registry's forms: studio, none, automatic, color:R,G,B or a file
                Job next = s.job;
                settings::set(next, "environment", c.args[0], script_);
                if (next.environment.kind == Job::Environment::Kind::File) s.open_environment(next.environment.path);
                else s.job.environment = next.environment;
            } catch (const std::exception& e) {
                failed(e.what());
            }
        }
        return false;  // the next frame shows the change
    }
    return false;
}

}  // namespace fresnel::viewer
