#include "command_line.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "fresnel/job/settings.h"
#include "fresnel/render/renderer.h"

namespace fresnel::cli {

gpu::ContextOptions context_options(const RenderOptions& o) {
    gpu::ContextOptions co;
    ContextFlags f = context_flags(o);
    co.debug = f.debug;
    co.api = f.es3 ? gpu::Api::OpenGLES30 : gpu::Api::OpenGL33;
    co.log = [](const std::string& m) { std::fprintf(stderr, "fresnel: %s\n", m.c_str()); };
    return co;
}

std::string shell_quote(const std::string& s) {
    bool plain = !s.empty();
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || std::string_view("-_./:,=+@%").find(c) != std::string_view::npos))
            plain = false;
    if (plain) return s;
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string render_command_line(const Job& job, const std::string& output) {
    std::string line = "fresnel render";
    auto add = [&](const std::string& flag, const std::string& value = {}) {
        line += " " + flag;
        if (!value.empty()) line += " " + shell_quote(value);
    };
    if (!job.source.model.empty()) line += " " + shell_quote(job.source.model);
    add("-o", output);
    // The settings that differ from the default job (and those always named), as their flags.
    for (const settings::Setting& s : settings::all()) {
        if (!s.offered(settings::kCli) || s.flag.empty() || (s.applies && !s.applies(job))) continue;
        if (settings::is_default(job, s) && !s.print_always) continue;
        const std::string value = settings::get(job, s);
        if (s.type == settings::Type::Bool) {
            if ((value == "false") == s.negated_flag) add(s.flag);
            continue;
        }
        bool shortcut = false;
        for (const auto& sc : s.shortcuts)
            if (sc.value == value) {
                add(sc.flag);
                shortcut = true;
                break;
            }
        if (!shortcut) add(s.flag, value);
    }
    // Extra lights, as --light writes them (a range is not part of that syntax).
    for (const LightInstance& l : job.lights.extra) add("--light", light_spec(l));
    return line;
}

}  // namespace fresnel::cli
