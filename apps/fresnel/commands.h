#pragma once
// Each subcommand registers its options on the CLI11 app and returns the
// function that runs it (returning the exit code).
#include <CLI/CLI.hpp>
#include <functional>

namespace fresnel::cli {

using Runner = std::function<int()>;

Runner add_render_command(CLI::App& app);
Runner add_info_command(CLI::App& app);
Runner add_bake_command(CLI::App& app);
Runner add_compare_command(CLI::App& app);
Runner add_trace_command(CLI::App& app);
Runner add_batch_command(CLI::App& app);
Runner add_fit_command(CLI::App& app);
Runner add_convert_command(CLI::App& app);
Runner add_view_command(CLI::App& app);
Runner add_settings_command(CLI::App& app);

}  // namespace fresnel::cli
