#include "fresnel/viewer/script.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/core/float_text.h"
#include "fresnel/material/properties.h"
#include "fresnel/job/lights.h"
#include "fresnel/job/settings.h"

namespace fresnel::viewer {
namespace {

bool parse_float(const std::string& s, float& out) {
    try {
        std::size_t used = 0;
        out = std::stof(s, &used);
        return used == s.size();
    } catch (const std::logic_error&) {
        return false;
    }
}

struct Signature {
    int args;           // -1: one or more words (a path with spaces); -4: the same, or nothing
    int numbers;        // how many leading args must be numbers
};

const std::map<std::string, Signature>& commands() {
    static const std::map<std::string, Signature> c = {
        {"orbit", {2, 2}},        {"pan", {2, 2}},           {"dolly", {1, 1}},        {"reset", {0, 0}},
        {"frame", {0, 0}},        {"camera", {1, 0}},        {"open", {-1, 0}},        {"env", {-1, 0}},
        {"wait", {1, 1}},         {"screenshot", {-1, 0}},
        {"print", {0, 0}},        {"stats", {0, 0}},        {"set", {-2, 0}},         {"split", {-3, 0}},        {"quit", {0, 0}},
        {"save", {-1, 0}},        {"save-scene", {-1, 0}},   {"auto-rotate", {2, 0}},  {"reload-shaders", {-4, 0}},
        {"light", {1, 0}},        {"light-remove", {1, 1}},  {"orbit-lights", {1, 0}}, {"hide", {1, 1}},
        {"show", {1, 1}},         {"pick", {2, 2}},          {"select", {1, 1}},
        {"play", {0, 0}},         {"pause", {0, 0}},         {"time", {1, 1}},         {"animation", {1, 0}},
        {"speed", {1, 1}},        {"loop", {1, 0}},
    };
    return c;
}

}  // namespace

const char* shorthand_key(const std::string& command) {
    static const std::map<std::string, const char*> keys = {
        {"env-rotation", "environment.rotation"}, {"env-intensity", "environment.intensity"},
        {"exposure", "render.exposure"},          {"tonemap", "render.toneMapping"},
        {"debug", "render.debug"},                {"background", "background"},
    };
    auto it = keys.find(command);
    return it == keys.end() ? nullptr : it->second;
}

bool set_material_field(Material& m, const std::string& field, const std::vector<float>& v) {
    const material_properties::Property* p = material_properties::find(field);
    if (!p || int(v.size()) != p->width) return false;
    material_properties::Value value{};
    for (std::size_t i = 0; i < v.size(); ++i) value[i] = v[i];
    if (!material_properties::check(*p, value).empty()) return false;
    p->put(m, value);
    return true;
}

float Command::number(std::size_t i) const {
    float v = 0.0f;
    parse_float(args.at(i), v);
    return v;
}

std::vector<Command> read_view_script(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path, "", "cannot open the script");
    std::vector<Command> out;
    std::string text;
    for (int n = 1; std::getline(in, text); ++n) {
        std::istringstream words(text);
        Command c;
        c.line = n;
        if (!(words >> c.name) || c.name[0] == '#') continue;
        auto fail = [&](const std::string& why) { throw Error(path, "line " + std::to_string(n), why); };
        auto it = commands().find(shorthand_key(c.name) ? std::string("set") : c.name);
        if (it == commands().end()) fail("unknown command '" + c.name + "'");
        const Signature sig = it->second;
        // The shorthands of settings (exposure EV, tonemap NAME, ...): `set KEY VALUE`, with a
        // warning naming it.
        if (auto key = shorthand_key(c.name)) {
            std::string rest;
            std::getline(words >> std::ws, rest);
            std::fprintf(stderr, "fresnel: warning: %s: line %d: '%s' is now 'set %s %s'\n", path.c_str(), n,
                         c.name.c_str(), key, rest.c_str());
            words = std::istringstream(std::string(key) + " " + rest);
            c.name = "set";
        }
        if (sig.args == -2 || c.name == "set") {  // set material INDEX FIELD VALUE... | set KEY VALUE
            std::string first;
            words >> first;
            if (first != "material") {  // a setting (fresnel/job/settings.h), its value the rest of the line
                std::string value;
                std::getline(words >> std::ws, value);
                while (!value.empty() && (value.back() == ' ' || value.back() == '\r' || value.back() == '\t')) value.pop_back();
                const settings::Setting* s = settings::find(first);
                if (first.empty() || !s || !s->offered(settings::kViewScript))
                    fail("set: expected set KEY VALUE (a setting: fresnel settings lists them) or set material INDEX "
                         "FIELD VALUE..., got '" + first + "'");
                try {
                    settings::parse(*s, value, "set " + first);
                } catch (const Error& e) {
                    fail(e.what());
                }
                c.args = {s->key, value};
                out.push_back(std::move(c));
                continue;
            }
            c.args.push_back(first);
            for (std::string w; words >> w;) c.args.push_back(w);
            if (c.args.size() < 3 || c.args[0] != "material") fail("set: expected set material INDEX FIELD VALUE...");
            float index = 0.0f;
            if (!parse_float(c.args[1], index) || index < 0 || index != float(int(index)))
                fail("set material: '" + c.args[1] + "' is not a material index");
            const material_properties::Property* prop = material_properties::find(c.args[2]);
            if (!prop) fail("set material: unknown property '" + c.args[2] + "' (fresnel settings lists them)");
            std::string text;
            for (std::size_t i = 3; i < c.args.size(); ++i) text += (i > 3 ? " " : "") + c.args[i];
            try {
                // Kept as the value's numbers (a choice's index, 0/1), what set_material_field takes.
                material_properties::Value v = material_properties::parse(*prop, text, "set material " + c.args[2]);
                c.args.resize(3);
                for (int i = 0; i < prop->width; ++i) c.args.push_back(shortest_text(v[std::size_t(i)]));
            } catch (const Error& e) {
                fail(e.file() + ": " + e.reason());
            }
            out.push_back(std::move(c));
            continue;
        }
        if (sig.args == -3) {  // split off | split CHANNEL POS
            for (std::string w; words >> w;) c.args.push_back(w);
            float pos = 0.0f;
            bool off = c.args.size() == 1 && c.args[0] == "off";
            if (!off && (c.args.size() != 2 || !parse_debug_channel(c.args[0]) || !parse_float(c.args[1], pos) ||
                         !(pos >= 0.0f && pos <= 1.0f)))
                fail("split: expected off, or CHANNEL POS (a debug channel or none, the divider at 0..1)");
            out.push_back(std::move(c));
            continue;
        }
        if (sig.args < 0) {  // the rest of the line, trimmed
            std::string rest;
            std::getline(words >> std::ws, rest);
            while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\r' || rest.back() == '\t')) rest.pop_back();
            if (rest.empty() && sig.args != -4) fail(c.name + ": needs a path");
            if (!rest.empty()) c.args.push_back(rest);
        } else {
            for (std::string w; words >> w;) c.args.push_back(w);
            if (int(c.args.size()) != sig.args)
                fail(c.name + ": needs " + std::to_string(sig.args) + " argument" + (sig.args == 1 ? "" : "s") +
                     ", got " + std::to_string(c.args.size()));
        }
        for (int i = 0; i < sig.numbers; ++i) {
            float v = 0.0f;
            if (!parse_float(c.args[std::size_t(i)], v) || !std::isfinite(v))
                fail(c.name + ": '" + c.args[std::size_t(i)] + "' is not a number");
        }
        if (c.name == "camera" && c.args[0] != "orbit") {
            float v = 0.0f;
            if (!parse_float(c.args[0], v) || v < 0 || v != float(int(v))) fail("camera: expected N (>= 0) or orbit");
        }
        if (c.name == "wait" && (c.number(0) < 0 || c.number(0) > 1e6f || c.number(0) != float(int(c.number(0)))))
            fail("wait: expected a whole number of frames");
        if (c.name == "dolly" && !(c.number(0) > 0)) fail("dolly: the factor must be positive");
        if (c.name == "auto-rotate" && ((c.args[0] != "camera" && c.args[0] != "env") || (c.args[1] != "on" && c.args[1] != "off")))
            fail("auto-rotate: expected camera|env on|off");
        if (c.name == "orbit-lights" && c.args[0] != "on" && c.args[0] != "off") fail("orbit-lights: expected on|off");
        if (c.name == "loop" && c.args[0] != "on" && c.args[0] != "off") fail("loop: expected on|off");
        if (c.name == "speed" && !(std::fabs(c.number(0)) <= 100.0f)) fail("speed: expected a number in [-100, 100]");
        if (c.name == "time" && !(std::fabs(c.number(0)) <= 1e6f)) fail("time: expected seconds in [-1e6, 1e6]");
        if (c.name == "animation" && c.args[0] != "all") {
            float v = 0.0f;
            if (!parse_float(c.args[0], v) || v < 0 || v != float(int(v))) fail("animation: expected N (>= 0) or all");
        }
        if (c.name == "light") {
            try {
                parse_light(c.args[0]);
            } catch (const std::exception& e) {
                fail(std::string("light: ") + e.what());
            }
        }
        for (const char* whole : {"light-remove", "hide", "show", "select"})
            if (c.name == whole && (c.number(0) < 0 || c.number(0) != float(int(c.number(0)))))
                fail(c.name + ": expected an index (>= 0)");
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace fresnel::viewer
