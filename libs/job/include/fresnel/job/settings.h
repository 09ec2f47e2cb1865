#pragma once
// The settings registry: every setting of a Job declared once, with its key, type, unit,
// range, default, one-line documentation, command-line spelling and the front ends that
// offer it. The command line (flags, --help, the print-back of a view), scene files (reader,
// writer, docs/scene.schema.json), view scripts (`set KEY VALUE`), the web page
// (fresnel_set) and batch sweeps parse and print settings through it, so a setting added
// here is offered everywhere it is marked for, with one syntax and one error format:
//   <where>: expected <what the setting takes>, got '<text>'
// where <where> is the flag (--pitch), the scene file and JSON pointer (/camera/pitch), the
// script's file and line, or the key.
//
// A setting's key is its place in a scene file: "camera.pitch" is /camera/pitch. Its value
// is exchanged as text in one syntax (the command line's): numbers in their shortest exact
// form, vectors as X,Y,Z, sizes as WxH, booleans as true/false (1/0, on/off accepted).
// Lists and structures are not settings: the models and their material overrides, the
// added lights (--light, "lights") and the lookAt camera stay structured in scene files.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "fresnel/core/error.h"
#include "fresnel/job/job.h"

namespace fresnel::settings {

enum class Type {
    Bool,    // true/false
    Int,     // a whole number in [min, max]
    Number,  // a finite number in [min, max]
    Vec3,    // X,Y,Z, each in [min, max]
    Size,    // WxH, each side in [min, max]
    Choice,  // one of `choices`
    Text,    // free text checked by Setting::check (an environment, a BRDF, fog)
};

// The front ends that offer a setting.
enum FrontEnd : unsigned {
    kCli = 1u << 0,         // a flag of render, batch and view
    kTrace = 1u << 1,       // the flag is trace's too (settings of the rasteriser are not)
    kSceneFile = 1u << 2,   // a key of scene files
    kViewScript = 1u << 3,  // `set KEY VALUE` of view scripts
    kWeb = 1u << 4,         // fresnel_set(KEY, VALUE) of the web page
    kSweep = 1u << 5,       // a batch sweep parameter (numbers)
    kAll = kCli | kTrace | kSceneFile | kViewScript | kWeb,
};

// A parsed value. `unset` is an optional setting's "none" (Setting::none: fit, the bounds'
// centre, automatic).
struct Value {
    bool unset = false;
    bool flag = false;          // Bool
    double number = 0.0;        // Int, Number
    glm::vec3 vec{0.0f};        // Vec3
    int width = 0, height = 0;  // Size
    std::string text;           // Choice, Text
};

struct Setting {
    std::string key;   // "environment.rotation" = the scene file's /environment/rotation
    std::string flag;  // "--env-rotation"; empty: no flag
    Type type = Type::Number;
    std::string unit;  // "degrees", "EV", ""
    double min = 0.0, max = 0.0;
    // The range a slider offers (the viewer's panels, the web page); both 0: [min, max]. Soft:
    // values outside it within [min, max] stay valid (a yaw of 720, an intensity of 50).
    double slider_min = 0.0, slider_max = 0.0;
    std::vector<std::string> choices;  // Choice
    std::string none;                  // optional settings: the word for unset ("fit", "center", "auto")
    std::string doc;                   // one line
    std::string example;               // a value other than the default (example() derives one when empty)
    unsigned front_ends = 0;
    bool negated_flag = false;  // Bool: the flag (--no-cache) sets it false
    bool periodic = false;      // an angle: a sweep over whole turns leaves out its end
    std::vector<std::string> old_names;  // earlier spellings: accepted with a warning
    // Flags that set a fixed value ("--no-ibl" sets environment "none"), with their doc.
    struct Shortcut {
        std::string flag, value, doc;
    };
    std::vector<Shortcut> shortcuts;
    // Whether the setting means anything for `job` (null: always): the orbit camera's keys
    // only for the orbit camera. Writers (scene files, the command line) leave out the others.
    std::function<bool(const Job&)> applies;
    // The command line names it even at its default (the orbit camera's angles: a line
    // applied over a scene file's camera shows the view it was copied from).
    bool print_always = false;
    std::function<Value(const Job&)> get;
    std::function<void(Job&, const Value&)> put;
    // Text: what it takes, in words; and its check: "" when `text` is good, else why not
    // (the message adds it to `syntax`).
    std::string syntax;
    std::function<std::string(const std::string& text)> check;
    // Choice and Text: the canonical spelling of an accepted alias ("env" -> "environment").
    std::function<std::string(const std::string& text)> canonical;

    // Choices some front ends offer the setting without (their bits): --ao baked needs the
    // tracer's rays, which the web page has not.
    std::vector<std::pair<std::string, unsigned>> choices_not_offered;

    bool offered(unsigned front_end) const { return (front_ends & front_end) != 0; }
    bool choice_offered(const std::string& choice, unsigned front_end) const {
        for (const auto& [c, bits] : choices_not_offered)
            if (c == choice && (bits & front_end)) return false;
        return true;
    }
    double slider_lo() const { return slider_min == slider_max ? min : slider_min; }
    double slider_hi() const { return slider_min == slider_max ? max : slider_max; }
    // What the setting takes, for messages and --help: "a number in [-90, 90] (degrees)".
    std::string expected() const;
};

// Every setting, in the order --help and the docs list them.
const std::vector<Setting>& all();

// A setting by its key, its flag (with or without the dashes) or an old name; null when none.
// `renamed` (when given) gets "'OLD' is now 'KEY'" for an old name.
const Setting* find(std::string_view name, std::string* renamed = nullptr);

// The setting of `key`; throws std::logic_error for a key not in the registry (a programming error).
const Setting& at(std::string_view key);

// `text` parsed as `setting` takes it. Throws fresnel::Error(where, "", "expected ..., got '...'").
Value parse(const Setting& setting, const std::string& text, const std::string& where);

// A value in the registry's text syntax (parse() reads it back to the same value).
std::string format(const Setting& setting, const Value& value);

// The setting's value in `job`, as text.
std::string get(const Job& job, const Setting& setting);
inline std::string get(const Job& job, std::string_view key) { return get(job, at(key)); }

// Sets the setting named `name` (key, flag or old name) from `text`. Unknown names and bad
// values throw fresnel::Error(where, "", reason); an old name warns in `diag` (when given).
void set(Job& job, std::string_view name, const std::string& text, const std::string& where,
         Diagnostics* diag = nullptr);
void set(Job& job, const Setting& setting, const std::string& text, const std::string& where);

// True when `job` holds the default job's value of the setting.
bool is_default(const Job& job, const Setting& setting);

// The settings offered by a front end.
std::vector<const Setting*> offered_by(unsigned front_end);

// The default, as text (for --help).
std::string default_text(const Setting& setting);

// A valid value other than the default (docs, tests): Setting::example, or one derived from
// the type (the other boolean, another choice, a number in range).
std::string example(const Setting& setting);

// The registry as JSON text (an array of {key, flag, type, unit, min, max, sliderMin, sliderMax, choices, none,
// default, example, doc, frontEnds, oldNames, periodic}): `fresnel settings --json`, the web
// page's fresnel_settings(), and the scripts that generate docs/scene.schema.json from it.
std::string describe_json();

}  // namespace fresnel::settings
