// `fresnel settings [--json]`: the settings registry (fresnel/job/settings.h), as a table or
// as JSON: every job setting's key (a scene file's place, a view script's and the web page's
// name), its flag, what it takes, its default and the front ends that offer it. With
// --materials, the material property registry (fresnel/material/properties.h): the names
// scene-file material overrides, view scripts' `set material` and the editors use.
#include <cstdio>
#include <string>

#include "commands.h"
#include "fresnel/job/settings.h"
#include "fresnel/material/properties.h"

namespace fresnel::cli {

Runner add_settings_command(CLI::App& app) {
    auto json = std::make_shared<bool>(false);
    auto materials = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand(
        "settings", "List every job setting: its key (scene files, view scripts' set KEY VALUE, the web page), flag, "
                    "values and default");
    cmd->add_flag("--json", *json, "The registry as JSON (key, flag, type, min, max, choices, default, example, doc, ...)");
    cmd->add_flag("--materials", *materials,
                  "The material properties instead: name (scene-file overrides, set material), glTF path, values, default");
    return [json, materials]() -> int {
        namespace mp = material_properties;
        if (*materials && *json) {
            std::fputs(mp::describe_json().c_str(), stdout);
            return 0;
        }
        if (*materials) {
            for (const mp::Property& p : mp::all())
                std::printf("%-30s default %s%s\n    %s\n    takes %s\n    glTF %s\n", std::string(p.name).c_str(),
                            mp::format(p, p.fallback).c_str(), p.animatable ? ", animatable" : "",
                            std::string(p.doc).c_str(), mp::expected(p).c_str(), std::string(p.path).c_str());
            return 0;
        }
        if (*json) {
            std::fputs(settings::describe_json().c_str(), stdout);
            return 0;
        }
        for (const settings::Setting& s : settings::all()) {
            std::string where;
            if (s.offered(settings::kSceneFile)) where += " scene-file";
            if (s.offered(settings::kViewScript)) where += " view-script";
            if (s.offered(settings::kWeb)) where += " web";
            if (s.offered(settings::kSweep)) where += " sweep";
            std::printf("%-26s %-26s default %s\n    %s\n    takes %s\n    in%s%s\n", s.key.c_str(),
                        s.flag.empty() ? "" : s.flag.c_str(), settings::default_text(s).c_str(), s.doc.c_str(),
                        s.type == settings::Type::Bool ? "true or false" : s.expected().c_str(),
                        s.flag.empty() ? "" : " cli", where.c_str());
        }
        return 0;
    };
}

}  // namespace fresnel::cli
