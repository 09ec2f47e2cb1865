#include "usage_errors.h"

#include "fresnel/core/spelling.h"

#include <algorithm>

namespace fresnel::cli {

std::string usage_message(const CLI::App& app, const std::vector<std::string>& args, const CLI::ParseError& error) {
    const std::vector<const CLI::App*> subs = app.get_subcommands([](const CLI::App*) { return true; });
    std::vector<std::string> commands;
    for (const CLI::App* sub : subs) commands.push_back(sub->get_name());
    std::string all;
    for (const auto& c : commands) all += (all.empty() ? "" : ", ") + c;
    // The command: the first word that is not an option.
    const auto first = std::find_if(args.begin(), args.end(), [](const std::string& a) { return a.empty() || a[0] != '-'; });
    if (first == args.end()) return "no command given (one of " + all + ")\nRun 'fresnel --help' for more.";
    const CLI::App* sub = nullptr;
    for (const CLI::App* s : subs)
        if (s->check_name(*first)) sub = s;
    if (!sub) {
        const std::string near = nearest_name(*first, commands);
        return "'" + *first + "' is not a fresnel command" + (near.empty() ? "" : "; did you mean '" + near + "'?") +
               " (the commands: " + all + ")\nRun 'fresnel --help' for more.";
    }
    const std::string help = "\nRun 'fresnel " + sub->get_name() + " --help' for its options.";
    // Options the command does not have, each with the nearest one it has.
    std::vector<std::string> options;
    for (const CLI::Option* o : sub->get_options())
        for (const std::string& n : o->get_lnames()) options.push_back("--" + n);
    for (auto it = std::next(first); it != args.end(); ++it) {
        const std::string& a = *it;
        if (a == "--") break;
        if (a.size() < 3 || a.rfind("--", 0) != 0) continue;
        const std::string name = a.substr(0, a.find('='));
        if (std::find(options.begin(), options.end(), name) != options.end()) continue;
        const std::string near = nearest_name(name, options);
        return "unknown option " + name + (near.empty() ? "" : "; did you mean " + near + "?") + help;
    }
    return std::string(error.what()) + help;
}

}  // namespace fresnel::cli
