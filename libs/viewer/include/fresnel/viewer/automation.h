#pragma once
// `fresnel view --script FILE` run against the viewer's state (after Filament's viewer
// AutomationEngine): the commands that change what is shown (camera, settings, lights,
// selection, split view, auto-rotation) act on fresnel::viewer::State here; what needs the
// window, the renderer or the loaders (screenshots, opening and saving files, shaders,
// statistics) goes through AutomationHost, which the window implements and the unit tests fake.
// The script is read and checked by read_view_script (fresnel/viewer/script.h, whose list of
// commands this follows); a command reaches this engine only once its arguments were checked.
#include <cstddef>
#include <string>
#include <vector>

#include "fresnel/job/job.h"
#include "fresnel/material/material.h"
#include "fresnel/viewer/script.h"
#include "fresnel/viewer/state.h"

namespace fresnel::viewer {

// What a script does beyond the state: the window's side.
class AutomationHost {
public:
    virtual ~AutomationHost() = default;
    // `screenshot PATH`: the last frame drawn, written as a PNG. Throws on failure.
    virtual void screenshot(const std::string& path) = 0;
    // `open PATH`: a model or a scene file, as a drop opens it; false (State::error says why)
    // leaves the current scene.
    virtual bool open(const std::string& path) = 0;
    // `save PATH`, `save-scene PATH`, `reload-shaders [DIR]`: false with State::error set.
    virtual bool save_model(const std::string& path) = 0;
    virtual bool save_scene(const std::string& path) = 0;
    virtual bool reload_shaders(const std::string& folder) = 0;
    // `set material INDEX FIELD VALUE...` on the scene's material `index` (in range).
    virtual void set_material_field(Material& material, const std::string& field, const std::vector<float>& values) = 0;
    // After `hide` or `show` changed a node's visibility in the state's scene.
    virtual void node_visibility_changed() = 0;
    // `stats`: the frame's statistics as one JSON line; `print`: the `fresnel render` command line of `job`.
    virtual std::string stats() = 0;
    virtual std::string render_command_line(const Job& job) = 0;
    // A line of the script's output (stdout), and an error of the script ("FILE: line N: what").
    virtual void print(const std::string& line) = 0;
    virtual void report_error(const std::string& message) = 0;
};

class Automation {
public:
    Automation() = default;
    // `script`: the file's name, for messages and setting errors.
    Automation(std::vector<Command> commands, std::string script);

    // Runs commands until one changes what is drawn (the next frame shows it), a `wait`, or a
    // command that needs a drawn frame while `ready` (the scene and its lighting loaded, the
    // frame drawn) is false. True at `quit`.
    bool step(State& state, AutomationHost& host, bool ready);

    bool pending() const { return position_ < commands_.size(); }
    // Whether a command failed (`quit` then exits 1).
    bool failed() const { return failed_; }
    // A failure of the script's line `line` (reported as "FILE: line N: what").
    void fail(AutomationHost& host, int line, const std::string& what);
    void mark_failed() { failed_ = true; }
    // The line of the last `env` (or `set environment`) run: the environment's bake reports a failure there.
    int env_line() const { return env_line_; }
    const std::string& script() const { return script_; }

private:
    std::vector<Command> commands_;
    std::string script_;
    std::size_t position_ = 0;
    int wait_ = 0, env_line_ = 0;
    bool failed_ = false;
};

}  // namespace fresnel::viewer
