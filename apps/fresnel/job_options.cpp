// The job flags of `render`, `batch`, `trace` and `view` (job_options.h): declared from the
// settings registry (fresnel/job/settings.h; add_job_flags, whose --help docs/cli-reference.md
// shows), and how they become a fresnel::Job, alone or over a scene file.
#include "job_options.h"

#include "help_format.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>
#include <thread>

#include "cli_common.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/render/renderer.h"
#include "fresnel/job/scene_file.h"
#include "fresnel/job/settings.h"

namespace fresnel::cli {

std::optional<Job> job_from_options(const RenderOptions& o, Job job, const GivenFlags& given) {
    // Every setting through the registry (fresnel/job/settings.h), in its order: a flag the
    // user gave (or, without a command, any value present: the flags alone describe the job).
    try {
        for (const settings::Setting& s : settings::all()) {
            if (!s.offered(settings::kCli) || s.flag.empty()) continue;
            if (s.type == settings::Type::Bool) {
                auto it = o.switches.find(s.key);
                if (it != o.switches.end() && it->second && given(s.flag.c_str()))
                    settings::set(job, s, s.negated_flag ? "false" : "true", s.flag);
            } else {
                auto it = o.settings.find(s.key);
                if (it != o.settings.end() && given(s.flag.c_str()) && (given.cmd || !it->second.empty()))
                    settings::set(job, s, it->second, s.flag);
            }
            for (const auto& shortcut : s.shortcuts) {
                auto it = o.switches.find(shortcut.flag);
                if (it != o.switches.end() && it->second && given(shortcut.flag.c_str()))
                    settings::set(job, s, shortcut.value, shortcut.flag);
            }
        }
        if (given("--light")) {
            job.lights.extra.clear();  // --light replaces a scene file's lights
            for (const auto& spec : o.lights) job.lights.extra.push_back(parse_light(spec));
        }
    } catch (const Error& e) {
        print_error(e);
        return std::nullopt;
    }
    return job;
}

std::optional<Job> job_from_sources(const RenderOptions& o, const CLI::App* cmd, Diagnostics& diag, const Job& defaults,
                                    std::string* scene_output) {
    // A scene file read onto the default job, then the flags the user gave; or the flags
    // alone (every one, defaults included) for models and the demo.
    bool scene_file = o.models.size() == 1 && is_scene_file(o.models[0]);
    if (!scene_file && o.models.size() > 1)
        for (const auto& m : o.models)
            if (is_scene_file(m)) {
                print_error("a scene file is rendered alone, not with other models: '" + m + "'");
                return std::nullopt;
            }
    std::optional<Job> parsed;
    if (scene_file) {
        SceneFileOptions so;
        so.allow_external_files = o.allow_external();
        // Usage checks of the flags first (exit 2), before the file is read.
        if (!job_from_options(o, defaults, GivenFlags{cmd})) return std::nullopt;
        SceneFile sf = load_scene_file(o.models[0], defaults, diag, so);
        parsed = job_from_options(o, sf.job, GivenFlags{cmd});
        if (scene_output && sf.output) *scene_output = sf.output->string();
    } else {
        parsed = job_from_options(o, defaults);  // usage checks first (exit 2), before touching files
        if (parsed && o.models.size() == 1) parsed->source.model = o.models[0];
        if (parsed && o.models.size() > 1)
            for (const auto& m : o.models) {
                Job::Source::Model model;
                model.path = m;
                parsed->source.models.push_back(model);
            }
    }
    return parsed;
}

std::optional<Job> job_from_command(const RenderOptions& o, const CLI::App* cmd, Diagnostics& diag,
                                    std::string& output) {
    std::string scene_output;
    std::optional<Job> parsed = job_from_sources(o, cmd, diag, Job{}, &scene_output);
    output = o.output.empty() ? scene_output : o.output;
    if (!parsed) return std::nullopt;
    if (output.empty()) {
        print_error("-o,--output is required (or an \"output\" in the scene file)");
        return std::nullopt;
    }
    return parsed;
}

ContextFlags context_flags(const RenderOptions& o) {
    ContextFlags f;
#ifndef NDEBUG
    f.debug = true;  // debug builds always report KHR_debug messages
#else
    f.debug = o.gl_debug;
#endif
    f.es3 = o.gl == "es3";
    return f;
}

void write_image(const std::string& path, const ImageF& image, bool transparent) {
    const std::string ext = lower_extension(path);
    if (ext == ".png") write_png(path, to_image8(image, transparent));
    else if (ext == ".exr") write_exr(path, image);
    else write_hdr(path, image);
}

void add_model_and_output(CLI::App* cmd, RenderOptions& o) {
    cmd->add_option("model", o.models,
                    "glTF 2.0 file (.gltf/.glb), several (one scene, each at its own place), or a scene file "
                    "(.fresnel.json, docs/scene-file.md; the flags given override it); omitted: the built-in demo "
                    "(7x7 spheres)");
    cmd->add_option("-o,--output", o.output,
                    "Output image: .png (8-bit, display-encoded), .exr/.hdr (linear float after exposure and tone "
                    "map). Required unless the scene file names an output");
}

nlohmann::json camera_json(const CameraSetup& camera) {
    return {{"eye", {camera.eye.x, camera.eye.y, camera.eye.z}},
            {"target", {camera.target.x, camera.target.y, camera.target.z}},
            {"znear", camera.znear},
            {"zfar", camera.zfar},
            {"yfov_deg", camera.yfov_deg}};
}

void add_job_flags(CLI::App* cmd, RenderOptions& opts, JobFlagSet set) {
    const bool raster = set == JobFlagSet::Raster;
    // The settings' flags, their help from the registry: the doc, what the value takes, the
    // key that scene files, view scripts and the web page use.
    for (const settings::Setting& s : settings::all()) {
        if (!s.offered(settings::kCli) || s.flag.empty() || (!raster && !s.offered(settings::kTrace))) continue;
        using settings::Type;
        const std::string group = help_group(s.key);
        if (s.type == Type::Bool) {
            std::string help = s.doc + (s.negated_flag ? ": off" : ": on") + " [" + s.key + "]";
            cmd->add_flag(s.flag, opts.switches[s.key], help)->group(group);
        } else {
            // Choices and texts list their values in the doc already; numbers say their range.
            const bool listed = s.type == Type::Choice || s.type == Type::Text;
            std::string help = s.doc + (listed ? "" : ": " + s.expected()) + " [" + s.key + "]";
            std::string& value = opts.settings[s.key];
            CLI::Option* opt = cmd->add_option(s.flag, value, help);
            opt->default_str(value.empty() ? settings::default_text(s) : value);
            const char* names[] = {"", "INT", "NUMBER", "X,Y,Z", "WxH", "NAME", "TEXT"};
            opt->type_name(names[int(s.type)]);
            opt->group(group);
        }
        for (const auto& shortcut : s.shortcuts)
            cmd->add_flag(shortcut.flag, opts.switches[shortcut.flag], shortcut.doc)->group(group);
    }
    cmd->get_option("--camera")->excludes("--yaw")->excludes("--pitch")->excludes("--distance")->excludes("--fov")->excludes("--target");
    cmd->add_option("--light", opts.lights,
                    "Add a light: dir:AZIMUTH,ELEVATION,LUX[,R,G,B] (arriving from that direction), "
                    "point:X,Y,Z,CANDELA[,R,G,B], spot:X,Y,Z,AZIMUTH,ELEVATION,CANDELA,INNER,OUTER[,R,G,B] "
                    "(shining as a dir light from AZIMUTH,ELEVATION; cone half-angles in degrees; point and spot "
                    "lights take a last ,radius=R: the bulb their contact-hardening soft shadows come from, metres; "
                    "dir lights ,angle=A: their angular radius, degrees), "
                    "or an area light "
                    "(luminance in nits): rect:X,Y,Z,AZIMUTH,ELEVATION,WIDTH,HEIGHT,NITS[,R,G,B] or "
                    "disk:X,Y,Z,AZIMUTH,ELEVATION,RADIUS,NITS[,R,G,B] (one-sided, facing as a spot light aims) or "
                    "sphere:X,Y,Z,RADIUS,NITS[,R,G,B] or tube:X,Y,Z,AZIMUTH,ELEVATION,LENGTH,RADIUS,NITS[,R,G,B] (its axis "
                    "pointing towards AZIMUTH,ELEVATION); repeatable. Replaces a scene file's \"lights\"")
        ->group("Lights");
    if (raster) {
        cmd->add_flag("--gl-debug", opts.gl_debug, "Request a debug GL context and print KHR_debug messages")->group("Graphics API");
        cmd->add_option("--gl", opts.gl, "Graphics API: gl33 (OpenGL 3.3 core) or es3 (OpenGL ES 3.0; same pictures)")
            ->capture_default_str()
            ->check(CLI::IsMember({"gl33", "es3"}))
            ->group("Graphics API");
    }
}

}  // namespace fresnel::cli
