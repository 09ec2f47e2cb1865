#include "usage_errors.h"

#include <algorithm>
#include <cctype>

namespace fresnel::cli {

std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
    auto lower = [](std::string s) {
        for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    const std::string w = lower(word);
    std::string best;
    std::size_t best_d = std::max<std::size_t>(2, w.size() / 3) + 1;
    for (const std::string& name : names) {
        const std::string n = lower(name);
        // Levenshtein distance, one row.
        std::vector<std::size_t> row(n.size() + 1);
        for (std::size_t j = 0; j <= n.size(); ++j) row[j] = j;
        for (std::size_t i = 1; i <= w.size(); ++i) {
            std::size_t diag = row[0];
            row[0] = i;
            for (std::size_t j = 1; j <= n.size(); ++j) {
                const std::size_t up = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (w[i - 1] == n[j - 1] ? 0 : 1)});
                diag = up;
            }
        }
        if (row[n.size()] < best_d) best_d = row[n.size()], best = name;
    }
    return best;
}

std::string usage_message(const CLI::App& app, const std::vector<std::string>& args, const CLI::ParseError& error) {
    std::vector<std::string> commands;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) commands.push_back(sub->get_name());
    std::string all;
    for (const auto& c : commands) all += (all.empty() ? "" : ", ") + c;
    // The command: the first word that is not an option.
    const auto first = std::find_if(args.begin(), args.end(), [](const std::string& a) { return a.empty() || a[0] != '-'; });
    if (first == args.end()) return "no command given (one of " + all + ")\nRun 'fresnel --help' for more.";
    const CLI::App* sub = nullptr;
    for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; }))
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
