#pragma once
// Command-line mistakes said in the program's own voice: "fresnel: error: ..." with the nearest
// command or option (fresnel/core/spelling.h: "did you mean --size?") where CLI11 only says what it did not expect.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace fresnel::cli {

// The message for a parse error of `app` on `args` (argv without the program): an unknown
// command or option with the nearest one, else CLI11's own message; and how to get help.
std::string usage_message(const CLI::App& app, const std::vector<std::string>& args, const CLI::ParseError& error);

}  // namespace fresnel::cli
