// `fresnel view [MODEL|FOLDER] ...`: the interactive viewer. It takes `render`'s camera,
// environment and tone-mapping flags (job_options.h) and opens on the frame `render` would
// write for them; the window and its loop are in viewer/ (over libs/viewer).
#include "cli_common.h"
#include "commands.h"
#include "viewer.h"

namespace fresnel::cli {

Runner add_view_command(CLI::App& app) {
    auto o = std::make_shared<ViewOptions>();
    o->job->settings["render.size"] = "1280x720";  // the window's size, not render's 1024x768
    CLI::App* cmd = app.add_subcommand("view", "Open a model or a scene file in a window: orbit, play, swap models and environments, inspect, save");
    cmd->footer("Examples:\n"
                "  fresnel view model.glb\n"
                "  fresnel view models/                          # PageUp/PageDown step through the folder\n"
                "  fresnel view scene.fresnel.json --env sky.hdr\n"
                "  fresnel view CesiumMan.glb --time 1.2         # paused at 1.2 s (Space plays)\n"
                "\nMouse and keys: left drag orbits (on a light's handle: moves it), left click selects, right or\n"
                "middle drag (or shift + left drag) pans, the wheel dollies; F frames all, R resets the camera, A\n"
                "turns the camera by itself, O opens the file browser, PageUp/PageDown step through the folder,\n"
                "Ctrl+C copies the view as a render command, Ctrl+S saves it as a scene file, F12 saves a\n"
                "screenshot, F5 reloads the shaders (--shaders), Space plays or pauses the animations (an animated\n"
                "file plays as it opens, unless --time, --script or --screenshot is given), Tab hides the GUI,\n"
                "Escape or Q quits. Drop a model, a scene file or an environment on the window to open it\n"
                "(docs/view.md).\n");
    o->cmd = cmd;
    cmd->add_option("model", o->job->models,
                    "A model (.gltf, .glb, .obj), a scene file (.fresnel.json; flags given override it), or a folder "
                    "of them (PageUp/PageDown step through it); omitted: the built-in demo");
    add_job_flags(cmd, *o->job);
    cmd->add_option("--screenshot", o->screenshot,
                    "Write the frame as presented (the 3D view, without the GUI) to this PNG after --exit-after frames, then "
                    "exit 0");
    cmd->add_flag("--with-gui", o->with_gui,
                  "--screenshot: the whole window as a user sees it, the side panel docked at the left and the model "
                  "framed right of it");
    cmd->add_option("--shaders", o->shaders,
                    "Development: read the shader files from this folder (a copy of the source's shaders/) instead "
                    "of the built-in ones; F5 reloads them, a compile error is shown and the running shaders stay");
    cmd->add_flag("--watch-shaders", o->watch_shaders,
                  "Development, with --shaders: reload the shaders by themselves when a file in that folder changes "
                  "(checked twice a second; as F5, a compile error is shown and the running shaders stay)")
        ->needs(cmd->get_option("--shaders"));
    cmd->add_option("--exit-after", o->frames,
                    "Exit after this many frames with the scene and its lighting ready (default with --screenshot: 2; "
                    "render's --frames is an animation's frames)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--script", o->script,
                    "Run the commands of this file, one a line (orbit, dolly, open, env, debug, screenshot, save, "
                    "save-scene, set KEY VALUE, quit, ...: docs/view.md), then stay open unless it says quit")
        ->excludes("--screenshot")->excludes("--exit-after");
    return [o]() -> int {
#ifdef FRESNEL_HAVE_VIEWER
        return run_viewer(*o);
#else
        print_error("this build of fresnel has no viewer (built with FRESNEL_VIEWER=OFF, or without GLFW and Dear ImGui: libglfw3-dev, libimgui-dev)");
        return kExitBadInput;
#endif
    };
}

}  // namespace fresnel::cli
