// placeholder
#include "cli_common.h"
#include "commands.h"
namespace fresnel::cli {
Runner add_convert_command(CLI::App& app) {
    app.add_subcommand("convert", "Convert OBJ/MTL <-> glTF");
    return []() { return kExitUsage; };
}
}  // namespace fresnel::cli
