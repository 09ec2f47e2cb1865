#pragma once
// How every command's --help reads: options grouped by topic (the settings registry's key
// prefixes: Camera, Model, Animation, Lights, Environment and background, Output; the command's
// own options first), each description wrapped to 100 columns under its name, and `fresnel help
// [COMMAND]` as another way to ask.
#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace fresnel::cli {

// The width --help lines are wrapped to.
constexpr std::size_t kHelpWidth = 100;

// The --help group of the setting `key` ("camera.yaw" -> "Camera").
std::string help_group(const std::string& key);

// A CLI11 formatter that wraps option descriptions at kHelpWidth (words kept whole).
std::shared_ptr<CLI::Formatter> wrapping_formatter();

// Wraps `text` to `width` columns, every line after the first indented by `indent` spaces.
std::string wrap_text(const std::string& text, std::size_t width, std::size_t indent);

// `fresnel help [COMMAND]`: COMMAND's --help, or the program's; returns its runner.
std::function<int()> add_help_command(CLI::App& app);

}  // namespace fresnel::cli
