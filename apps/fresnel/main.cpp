// fresnel: a physically based renderer and toolkit. See README.md for the CLI reference.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "fresnel/core/version.h"

#include "cli_common.h"
#include "commands.h"
#include "help_format.h"
#include "huge_pages.h"
#include "usage_errors.h"

int main(int argc, char** argv) {
    fresnel::cli::restart_with_huge_pages_if_useful(argc, argv);
    CLI::App app{"fresnel: physically based rendering of glTF 2.0 models", "fresnel"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "fresnel " + std::string(fresnel::version()));
    app.formatter(fresnel::cli::wrapping_formatter());  // inherited by the commands added below
    auto render = fresnel::cli::add_render_command(app);
    auto info = fresnel::cli::add_info_command(app);
    auto bake = fresnel::cli::add_bake_command(app);
    auto compare = fresnel::cli::add_compare_command(app);
    auto trace = fresnel::cli::add_trace_command(app);
    auto batch = fresnel::cli::add_batch_command(app);
    auto fit = fresnel::cli::add_fit_command(app);
    auto convert = fresnel::cli::add_convert_command(app);
    auto view = fresnel::cli::add_view_command(app);
    auto settings = fresnel::cli::add_settings_command(app);
    auto help = fresnel::cli::add_help_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // Errors of the program's own checks (a bad --size) already read "--flag: expected ...".
        fresnel::cli::print_error(fresnel::cli::usage_message(app, std::vector<std::string>(argv + 1, argv + argc), e));
        return fresnel::cli::kExitUsage;
    }
    try {
        if (app.got_subcommand("render")) return render();
        if (app.got_subcommand("info")) return info();
        if (app.got_subcommand("bake")) return bake();
        if (app.got_subcommand("compare")) return compare();
        if (app.got_subcommand("trace")) return trace();
        if (app.got_subcommand("batch")) return batch();
        if (app.got_subcommand("fit")) return fit();
        if (app.got_subcommand("convert")) return convert();
        if (app.got_subcommand("view")) return view();
        if (app.got_subcommand("settings")) return settings();
        if (app.got_subcommand("help")) return help();
    } catch (const fresnel::Error& e) {
        fresnel::cli::print_error(e);
        return fresnel::cli::kExitBadInput;
    } catch (const std::bad_alloc&) {
        fresnel::cli::print_error("out of memory");
        return fresnel::cli::kExitBadInput;
    } catch (const std::exception& e) {
        fresnel::cli::print_error(e.what());
        return fresnel::cli::kExitBadInput;
    }
    return fresnel::cli::kExitUsage;
}
