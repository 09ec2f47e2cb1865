#pragma once
// `fresnel view`: the interactive viewer (viewer/, over libs/viewer; built when libs/gui is).
#include <memory>
#include <optional>
#include <string>

#include "command_line.h"
#include "job_options.h"

namespace fresnel::cli {

struct ViewOptions {
    std::shared_ptr<RenderOptions> job = std::make_shared<RenderOptions>();
    std::string screenshot;     // write the presented frame (without the GUI) to this PNG, then exit
    bool with_gui = false;      // --screenshot includes the GUI drawn over the frame
    std::optional<int> frames;  // exit after this many frames with the scene and its lighting ready
    std::string script;         // fresnel/viewer/script.h
    std::string shaders;        // --shaders DIR: shader files from DIR (F5 reloads them)
    bool watch_shaders = false; // --watch-shaders: reload when a file under --shaders changes
    const CLI::App* cmd = nullptr;  // the view subcommand: which flags were given (they override a scene file)
};

int run_viewer(const ViewOptions& options);

}  // namespace fresnel::cli
