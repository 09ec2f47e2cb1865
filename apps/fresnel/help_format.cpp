#include "help_format.h"

#include <cstdio>
#include <sstream>
#include <vector>

#include "fresnel/core/spelling.h"
#include "cli_common.h"

namespace fresnel::cli {

std::string help_group(const std::string& key) {
    const std::string head = key.substr(0, key.find('.'));
    if (head == "camera") return "Camera";
    if (head == "animation") return "Animation";
    if (head == "environment" || head == "background") return "Environment and background";
    if (head == "render") return "Output";
    if (head == "sceneLights" || head == "lights") return "Lights";
    return "Model";
}

std::string wrap_text(const std::string& text, std::size_t width, std::size_t indent) {
    std::string out, line;
    std::istringstream words(text);
    const std::size_t room = width > indent + 20 ? width - indent : 20;
    auto put = [&](const std::string& piece, bool space) {
        if (!line.empty() && line.size() + (space ? 1 : 0) + piece.size() > room) {
            out += line + "\n" + std::string(indent, ' ');
            line.clear();
        } else if (!line.empty() && space) {
            line += ' ';
        }
        line += piece;
    };
    for (std::string w; words >> w;) {
        // A word longer than the line (a list of choices) breaks after its | and , separators.
        std::size_t start = 0;
        bool first = true;
        while (start < w.size()) {
            std::size_t end = w.size();
            if (w.size() - start > room / 2)
                for (std::size_t i = start; i + 1 < w.size(); ++i)
                    if (w[i] == '|' || w[i] == ',') {
                        end = i + 1;
                        break;
                    }
            put(w.substr(start, end - start), first);
            first = false;
            start = end;
        }
    }
    return out + line;
}

namespace {

class WrappingFormatter : public CLI::Formatter {
public:
    WrappingFormatter() { column_width(30); }
    std::string make_option(const CLI::Option* opt, bool is_positional) const override {
        std::string name = "  " + make_option_name(opt, is_positional) + make_option_opts(opt);
        const std::string desc = make_option_desc(opt);
        std::string out = name;
        if (!desc.empty()) {
            if (name.size() >= column_width_) out += "\n" + std::string(column_width_, ' ');
            else out += std::string(column_width_ - name.size(), ' ');
            out += wrap_text(desc, kHelpWidth, column_width_);
        }
        return out + "\n";
    }
    std::string make_subcommand(const CLI::App* sub) const override {
        std::string name = "  " + sub->get_display_name(true);
        std::string out = name;
        if (name.size() >= column_width_) out += "\n" + std::string(column_width_, ' ');
        else out += std::string(column_width_ - name.size(), ' ');
        return out + wrap_text(sub->get_description(), kHelpWidth, column_width_) + "\n";
    }
    std::string make_description(const CLI::App* app) const override {
        const std::string text = CLI::Formatter::make_description(app);
        return text.empty() ? text : wrap_text(text, kHelpWidth, 0) + "\n";
    }
};

}  // namespace

std::shared_ptr<CLI::Formatter> wrapping_formatter() { return std::make_shared<WrappingFormatter>(); }

std::function<int()> add_help_command(CLI::App& app) {
    auto topic = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand("help", "Show the help of a command (fresnel help render is fresnel render --help)");
    cmd->add_option("command", *topic, "The command (render, view, trace, ...); omitted: the list of commands");
    return [&app, topic]() -> int {
        if (topic->empty()) {
            std::fputs(app.help().c_str(), stdout);  // as fresnel --help
            return kExitOk;
        }
        std::vector<std::string> names;
        for (const CLI::App* sub : app.get_subcommands({}))
            if (sub->get_name() != "help") names.push_back(sub->get_name());
        for (const CLI::App* sub : app.get_subcommands({}))
            if (sub->get_name() == *topic && *topic != "help") {
                std::fputs(sub->help(app.get_name()).c_str(), stdout);  // as fresnel COMMAND --help
                return kExitOk;
            }
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
        std::string message = "help: no command '" + *topic + "'";
        if (const std::string near = nearest_name(*topic, names); !near.empty()) message += "; did you mean '" + near + "'?";
        print_error(message + " (the commands: " + list + ")");
        return kExitUsage;
    };
}

}  // namespace fresnel::cli
