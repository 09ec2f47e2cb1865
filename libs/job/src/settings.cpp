// The settings registry (fresnel/job/settings.h): the table of every Job setting, and the one
// parser and printer of their text syntax.
// Long (~910 lines) by design: the table declares every setting once, in one place.
#include "fresnel/job/settings.h"

#include "fresnel/job/features.h"

#include "fresnel/core/spelling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "fresnel/core/float_text.h"
#include "fresnel/core/json_text.h"
#include "fresnel/material/brdf_model.h"

namespace fresnel::settings {
namespace {

std::string num(double v) { return shortest_text(float(v)); }
std::string vec_text(const glm::vec3& v) { return num(v.x) + "," + num(v.y) + "," + num(v.z); }

// A whole string as a finite number.
bool read_number(const std::string& s, double& out) {
    if (s.empty() || std::isspace(static_cast<unsigned char>(s.front()))) return false;
    char* end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end && *end == '\0' && std::isfinite(out);
}

// "X,Y,Z": three finite numbers.
bool read_vec3(const std::string& s, glm::vec3& out) {
    std::vector<std::string> parts;
    std::stringstream ss(s);
    for (std::string item; std::getline(ss, item, ',');) parts.push_back(item);
    if (parts.size() != 3 || s.back() == ',') return false;
    for (int i = 0; i < 3; ++i) {
        double d = 0;
        if (!read_number(parts[std::size_t(i)], d)) return false;
        out[i] = float(d);
    }
    return true;
}

std::string range_text(double lo, double hi) { return "[" + num(lo) + ", " + num(hi) + "]"; }

// --- the texts of structured settings ----------------------------------------------------

// environment: automatic | studio | none | color:R,G,B | a file (.hdr, .exr, a baked folder)
std::string check_environment(const std::string& t) {
    const std::string what = "-";
    if (t.empty()) return what;
    if (t.rfind("color:", 0) == 0) {
        glm::vec3 c;
        if (!read_vec3(t.substr(6), c) || c.x < 0 || c.y < 0 || c.z < 0 || c.x > 1e9f || c.y > 1e9f || c.z > 1e9f)
            return what;
    }
    return "";
}
Value environment_value(const Job::Environment& e) {
    using Kind = Job::Environment::Kind;
    Value v;
    switch (e.kind) {
        case Kind::Automatic: v.text = "automatic"; break;
        case Kind::Studio: v.text = "studio"; break;
        case Kind::None: v.text = "none"; break;
        case Kind::Color: v.text = "color:" + vec_text(e.color); break;
        case Kind::File: v.text = e.path; break;
    }
    return v;
}
void put_environment(Job::Environment& e, const std::string& t) {
    using Kind = Job::Environment::Kind;
    if (t == "automatic" || t == "auto") e.kind = Kind::Automatic;
    else if (t == "studio") e.kind = Kind::Studio;
    else if (t == "none") e.kind = Kind::None;
    else if (t.rfind("color:", 0) == 0) {
        e.kind = Kind::Color;
        read_vec3(t.substr(6), e.color);
    } else {
        e.kind = Kind::File;
        e.path = t;
    }
}

// background: automatic | environment | blur | transparent | R,G,B (display-encoded 0..1)
std::string check_background(const std::string& t) {
    static const char* words[] = {"automatic", "auto", "environment", "env", "blur", "transparent"};
    for (const char* w : words)
        if (t == w) return "";
    glm::vec3 c;
    if (read_vec3(t, c) && c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x <= 1 && c.y <= 1 && c.z <= 1) return "";
    return "-";
}
std::string canonical_background(const std::string& t) {
    if (t == "auto") return "automatic";
    if (t == "env") return "environment";
    glm::vec3 c;
    if (read_vec3(t, c)) return vec_text(c);
    return t;
}

// fog: none | linear:START,END (numbers, or near / far: the clip distances) | exp:DENSITY | exp2:DENSITY
std::string check_fog(const std::string& t) {
    const std::string what = "-";
    if (t == "none") return "";
    auto colon = t.find(':');
    if (colon == std::string::npos) return what;
    std::string kind = t.substr(0, colon), args = t.substr(colon + 1);
    double d = 0;
    if (kind == "linear") {
        auto comma = args.find(',');
        if (comma == std::string::npos) return what;
        std::string a = args.substr(0, comma), b = args.substr(comma + 1);
        if (!(a == "near" || read_number(a, d)) || !(b == "far" || read_number(b, d))) return what;
        return "";
    }
    if ((kind == "exp" || kind == "exp2") && read_number(args, d) && d >= 0) return "";
    return what;
}
void put_fog(Fog& fog, const std::string& t) {
    const glm::vec3 color = fog.color;
    fog = Fog{};
    fog.color = color;
    if (t == "none") return;
    auto colon = t.find(':');
    std::string kind = t.substr(0, colon), args = t.substr(colon + 1);
    double d = 0;
    if (kind == "linear") {
        auto comma = args.find(',');
        std::string a = args.substr(0, comma), b = args.substr(comma + 1);
        fog.mode = legacy::FogMode::Linear;
        if (read_number(a, d)) fog.start = float(d);
        if (read_number(b, d)) fog.end = float(d);
    } else {
        fog.mode = kind == "exp" ? legacy::FogMode::Exp : legacy::FogMode::Exp2;
        read_number(args, d);
        fog.density = float(d);
    }
}
std::string fog_text(const Fog& f) {
    switch (f.mode) {
        case legacy::FogMode::None: return "none";
        case legacy::FogMode::Linear:
            return "linear:" + (f.start ? num(*f.start) : std::string("near")) + "," + (f.end ? num(*f.end) : std::string("far"));
        case legacy::FogMode::Exp: return "exp:" + num(f.density);
        case legacy::FogMode::Exp2: return "exp2:" + num(f.density);
    }
    return "none";
}

std::string debug_name(DebugChannel c) {
    for (const std::string& n : debug_channel_names())
        if (parse_debug_channel(n) == c) return n;
    return "none";
}

// --- the table -----------------------------------------------------------------------------

// A number setting held in a float (Type::Number) or an int (Type::Int) field of the Job.
template <typename T>
Setting numeric(Type type, std::string key, std::string flag, std::string unit, double lo, double hi, std::string doc,
                unsigned front_ends, std::function<T&(Job&)> field) {
    Setting s;
    s.key = std::move(key);
    s.flag = std::move(flag);
    s.type = type;
    s.unit = std::move(unit);
    s.min = lo;
    s.max = hi;
    s.doc = std::move(doc);
    s.front_ends = front_ends;
    s.get = [field](const Job& j) {
        Value v;
        v.number = field(const_cast<Job&>(j));
        return v;
    };
    s.put = [field](Job& j, const Value& v) { field(j) = T(v.number); };
    return s;
}
Setting number(std::string key, std::string flag, std::string unit, double lo, double hi, std::string doc,
               unsigned front_ends, std::function<float&(Job&)> field) {
    return numeric<float>(Type::Number, std::move(key), std::move(flag), std::move(unit), lo, hi, std::move(doc),
                          front_ends, std::move(field));
}
Setting integer(std::string key, std::string flag, std::string unit, double lo, double hi, std::string doc,
                unsigned front_ends, std::function<int&(Job&)> field) {
    return numeric<int>(Type::Int, std::move(key), std::move(flag), std::move(unit), lo, hi, std::move(doc),
                        front_ends, std::move(field));
}

// An index into the file's lists (a scene, an animation) held as -1 for `none` ("default", "all").
Setting index_or_none(std::string key, std::string flag, std::string none, std::string doc, unsigned front_ends,
                      std::function<int&(Job&)> field) {
    Setting s;
    s.key = std::move(key);
    s.flag = std::move(flag);
    s.type = Type::Int;
    s.min = 0;
    s.max = 1 << 20;
    s.none = std::move(none);
    s.doc = std::move(doc);
    s.front_ends = front_ends;
    s.get = [field](const Job& j) {
        const int index = field(const_cast<Job&>(j));
        Value v;
        v.unset = index < 0;
        v.number = std::max(index, 0);
        return v;
    };
    s.put = [field](Job& j, const Value& v) { field(j) = v.unset ? -1 : int(v.number); };
    return s;
}

Setting boolean(std::string key, std::string flag, bool negated, std::string doc, unsigned front_ends,
                std::function<bool&(Job&)> field) {
    Setting s;
    s.key = std::move(key);
    s.flag = std::move(flag);
    s.type = Type::Bool;
    s.negated_flag = negated;
    s.doc = std::move(doc);
    s.front_ends = front_ends;
    s.get = [field](const Job& j) {
        Value v;
        v.flag = field(const_cast<Job&>(j));
        return v;
    };
    s.put = [field](Job& j, const Value& v) { field(j) = v.flag; };
    return s;
}

Setting choice(std::string key, std::string flag, std::vector<std::string> choices, std::string doc, unsigned front_ends,
               std::function<std::string(const Job&)> get, std::function<void(Job&, const std::string&)> put) {
    Setting s;
    s.key = std::move(key);
    s.flag = std::move(flag);
    s.type = Type::Choice;
    s.choices = std::move(choices);
    s.doc = std::move(doc);
    s.front_ends = front_ends;
    s.get = [get](const Job& j) {
        Value v;
        v.text = get(j);
        return v;
    };
    s.put = [put](Job& j, const Value& v) { put(j, v.text); };
    return s;
}

// The camera keys of the orbit camera: setting one on a job that looks through a file's
// camera or a lookAt camera turns it into the orbit camera (its defaults), as the flags do.
void to_orbit(Job::Camera& c) {
    if (c.scene_camera || c.look_at) c = Job::Camera{};
}
bool orbit_camera(const Job& j) { return !j.camera.scene_camera && !j.camera.look_at; }

std::vector<Setting> make_registry() {
    constexpr unsigned all = kAll, raster = kCli | kSceneFile | kViewScript | kWeb;
    std::vector<Setting> r;

    // --- camera ---
    {
        Setting s = number("camera.yaw", "--yaw", "degrees", -1e6, 1e6, "Orbit yaw (0: from +Z, 90: from +X)",
                           all | kSweep, [](Job& j) -> float& { return j.camera.yaw_deg; });
        s.slider_min = -180, s.slider_max = 180;
        s.periodic = true;
        s.applies = orbit_camera;
        s.print_always = true;
        s.put = [](Job& j, const Value& v) { to_orbit(j.camera); j.camera.yaw_deg = float(v.number); };
        r.push_back(s);
    }
    {
        Setting s = number("camera.pitch", "--pitch", "degrees", -90, 90, "Orbit pitch (positive: from above)",
                           all | kSweep, [](Job& j) -> float& { return j.camera.pitch_deg; });
        s.applies = orbit_camera;
        s.print_always = true;
        s.put = [](Job& j, const Value& v) { to_orbit(j.camera); j.camera.pitch_deg = float(v.number); };
        r.push_back(s);
    }
    {
        Setting s = number("camera.distance", "--distance", "", 1e-6, 1e6,
                           "Orbit distance as a multiple K of the bounds' radius (fit: the whole model in view)",
                           all | kSweep, nullptr);
        s.none = "fit";
        s.applies = orbit_camera;
        s.get = [](const Job& j) {
            Value v;
            v.unset = !j.camera.distance_k;
            v.number = j.camera.distance_k.value_or(0.0f);
            return v;
        };
        s.put = [](Job& j, const Value& v) {
            to_orbit(j.camera);
            if (v.unset) j.camera.distance_k.reset();
            else j.camera.distance_k = float(v.number);
        };
        r.push_back(s);
    }
    {
        Setting s = number("camera.fov", "--fov", "degrees", 0.01, 179, "Vertical field of view", all | kSweep,
                           [](Job& j) -> float& { return j.camera.yfov_deg; });
        s.slider_min = 1, s.slider_max = 170;
        s.applies = [](const Job& j) { return !j.camera.scene_camera; };
        s.put = [](Job& j, const Value& v) {
            if (j.camera.scene_camera) j.camera = Job::Camera{};  // a lookAt camera keeps its place
            j.camera.yfov_deg = float(v.number);
        };
        r.push_back(s);
    }
    {
        Setting s;
        s.key = "camera.target";
        s.flag = "--target";
        s.type = Type::Vec3;
        s.min = -1e30;
        s.max = 1e30;
        s.none = "center";
        s.applies = orbit_camera;
        s.doc = "The point the orbit camera turns about, X,Y,Z (center: the bounds' centre)";
        s.front_ends = all;
        s.get = [](const Job& j) {
            Value v;
            v.unset = !j.camera.target;
            v.vec = j.camera.target.value_or(glm::vec3(0.0f));
            return v;
        };
        s.put = [](Job& j, const Value& v) {
            to_orbit(j.camera);
            if (v.unset) j.camera.target.reset();
            else j.camera.target = v.vec;
        };
        r.push_back(s);
    }
    {
        Setting s;
        s.key = "camera.index";
        s.flag = "--camera";
        s.type = Type::Int;
        s.min = 0;
        s.max = 1 << 20;
        s.none = "orbit";
        s.doc = "Look through the file's N-th camera (orbit: the orbit camera)";
        s.front_ends = all;
        s.get = [](const Job& j) {
            Value v;
            v.unset = !j.camera.scene_camera;
            v.number = j.camera.scene_camera.value_or(0);
            return v;
        };
        s.put = [](Job& j, const Value& v) {
            if (v.unset) {
                if (j.camera.scene_camera) j.camera = Job::Camera{};
                return;
            }
            j.camera.look_at.reset();
            j.camera.scene_camera = int(v.number);
            j.camera.scene_camera_model = 0;
        };
        r.push_back(s);
    }

    // --- the scene ---
    r.push_back(index_or_none("scene", "--scene", "default", "The glTF scene to show (default: the file's `scene`)",
                              kCli | kTrace | kWeb,  // a scene file gives each model's "scene"
                              [](Job& j) -> int& { return j.source.scene; }));
    {
        Setting s;
        s.key = "variant";
        s.flag = "--variant";
        s.type = Type::Text;
        s.doc = "KHR_materials_variants: the material variant NAME (fresnel info lists them; empty: the default materials)";
        s.front_ends = all;
        s.syntax = "a variant's name (empty: the default materials)";
        s.example = "Yellow";
        s.check = [](const std::string&) { return std::string(); };
        s.get = [](const Job& j) {
            Value v;
            v.text = j.source.variant;
            return v;
        };
        s.put = [](Job& j, const Value& v) { j.source.variant = v.text; };
        r.push_back(s);
    }
    {
        Setting s = number("animation.time", "--time", "seconds", -1e6, 1e6,
                           "Pose the scene at T seconds of its animations (each clamped to its keyframes): skins, "
                           "morph targets and KHR_animation_pointer; the camera keeps fitting the rest pose "
                           "(rest: no animation applied)",
                           all | kSweep, nullptr);
        s.none = "rest";
        s.slider_min = 0, s.slider_max = 10;
        s.example = "1.5";
        s.get = [](const Job& j) {
            Value v;
            v.unset = !j.source.animation.time;
            v.number = j.source.animation.time.value_or(0.0f);
            return v;
        };
        s.put = [](Job& j, const Value& v) {
            if (v.unset) j.source.animation.time.reset();
            else j.source.animation.time = float(v.number);
        };
        r.push_back(s);
    }
    r.push_back(index_or_none("animation.index", "--animation", "all",
                              "Play only animation K (0-based; fresnel info lists them; all: every animation). Alone "
                              "it poses the scene at time 0",
                              all, [](Job& j) -> int& { return j.source.animation.index; }));
    {
        Setting s;
        s.key = "disable";
        s.flag = "--disable";
        s.type = Type::Text;
        s.doc = "Turn parts of the file off, comma-separated: skinning (the bind pose), morphing (no morph targets), "
                "occlusion (occlusion textures unread) and material extensions (KHR_materials_clearcoat, or "
                "clearcoat; fresnel info lists a file's); none: everything on";
        s.front_ends = all;
        s.syntax = "none or a comma-separated list of skinning, morphing, occlusion and KHR_materials_* extensions";
        s.example = "skinning,KHR_materials_clearcoat";
        auto parse = [](const std::string& t, std::string* why) {
            std::vector<std::string> out;
            if (t.empty() || t == "none") return out;
            std::size_t start = 0;
            while (start <= t.size()) {
                std::size_t end = t.find(',', start);
                if (end == std::string::npos) end = t.size();
                const std::string term = t.substr(start, end - start);
                const std::string name = feature_name(term);
                if (name.empty()) {
                    if (why) *why = "'" + term + "' is not one of skinning, morphing, occlusion or a material extension";
                    return std::vector<std::string>{};
                }
                if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
                start = end + 1;
            }
            std::vector<std::string> sorted;  // feature_names() order: one spelling of each list
            for (const std::string& n : feature_names())
                if (std::find(out.begin(), out.end(), n) != out.end()) sorted.push_back(n);
            return sorted;
        };
        auto text = [](const std::vector<std::string>& list) {
            std::string t;
            for (const std::string& n : list) t += (t.empty() ? "" : ",") + n;
            return t.empty() ? std::string("none") : t;
        };
        s.check = [parse](const std::string& t) {
            std::string why;
            parse(t, &why);
            return why;
        };
        s.canonical = [parse, text](const std::string& t) { return text(parse(t, nullptr)); };
        s.get = [text](const Job& j) {
            Value v;
            v.text = text(j.source.disabled);
            return v;
        };
        s.put = [parse](Job& j, const Value& v) { j.source.disabled = parse(v.text, nullptr); };
        r.push_back(s);
    }
    r.push_back(boolean("poseSkins", "--pose-skins", false,
                        "Pose skinned meshes by their joints' rest transforms (false: the bind pose, as the Khronos "
                        "Sample Renderer's reference images show)",
                        all, [](Job& j) -> bool& { return j.source.pose_skins; }));
    r.push_back(choice(
        "specularGlossinessTextures", "--sg-textures", {"khronos", "srgb"},
        "KHR_materials_pbrSpecularGlossiness: read the diffuse and specular-glossiness textures' RGB as the Khronos "
        "Sample Renderer does (khronos: as stored, the default, so the pictures agree) or as the extension's text "
        "says (srgb: decoded from sRGB)",
        all,
        [](const Job& j) {
            return std::string(j.source.sg_textures == Job::Source::SpecularGlossinessTextures::Srgb ? "srgb" : "khronos");
        },
        [](Job& j, const std::string& t) {
            j.source.sg_textures = t == "srgb" ? Job::Source::SpecularGlossinessTextures::Srgb
                                               : Job::Source::SpecularGlossinessTextures::Khronos;
        }));
    r.push_back(choice(
        "objNormals", "--obj-normals", {"auto", "groups", "smooth"},
        "OBJ corners without vn: groups (honour s; none means flat), smooth (a normal per position, as OpenGL 1 "
        "viewers do) or auto (smooth with the ogl1 shading models, groups otherwise)",
        all, [](const Job& j) -> std::string {
            using N = Job::Source::ObjNormals;
            return j.source.obj_normals == N::Smooth ? "smooth" : j.source.obj_normals == N::Groups ? "groups" : "auto";
        },
        [](Job& j, const std::string& t) {
            using N = Job::Source::ObjNormals;
            j.source.obj_normals = t == "smooth" ? N::Smooth : t == "groups" ? N::Groups : N::Auto;
        }));
    r.push_back(boolean("allowExternalFiles", "--allow-external-files", false,
                        "Let URIs point outside the model's folder (absolute paths, ..); never the network",
                        kCli | kTrace, [](Job& j) -> bool& { return j.source.allow_external_files; }));
    r.push_back(number("maxMemory", "--max-memory", "MiB", 0, 1 << 24,
                       "Memory budget of a model's load (buffers, images, decoded geometry); 0: automatic (8 GiB, "
                       "and geometry at most 256 MiB + 64 bytes per byte of the file and its buffers); a file over "
                       "it is refused naming what exceeded it",
                       kCli | kTrace, [](Job& j) -> float& { return j.source.max_memory_mib; }));

    // --- light ---
    {
        Setting s = boolean("sceneLights", "--no-scene-lights", true, "The file's KHR_lights_punctual lights", all,
                            [](Job& j) -> bool& { return j.lights.scene_lights; });
        s.old_names = {"scene-lights"};
        r.push_back(s);
    }
    {
        Setting s;
        s.key = "environment";
        s.flag = "--env";
        s.type = Type::Text;
        s.doc = "Image-based light: an equirectangular .hdr/.exr/.ktx2, a folder made by `fresnel bake`, color:R,G,B "
                "(linear), studio (built in), none, or automatic (studio unless the scene or --light brings lights)";
        s.front_ends = all;
        s.syntax = "automatic, studio, none, color:R,G,B (linear, >= 0) or a file (.hdr, .exr, .ktx2, a folder made by "
                   "fresnel bake)";
        s.check = check_environment;
        s.example = "color:0.5,0.25,1";
        s.shortcuts = {{"--no-ibl", "none", "No image-based light (--env none)"}};
        s.canonical = [](const std::string& t) { return t == "auto" ? std::string("automatic") : t; };
        s.get = [](const Job& j) { return environment_value(j.environment); };
        s.put = [](Job& j, const Value& v) { put_environment(j.environment, v.text); };
        r.push_back(s);
    }
    r.push_back(number("environment.rotation", "--env-rotation", "degrees", -1e6, 1e6,
                       "Turn the environment about +Y", all | kSweep,
                       [](Job& j) -> float& { return j.environment.rotation_deg; }));
    r.back().periodic = true;
    r.back().slider_min = -180, r.back().slider_max = 180;
    r.push_back(number("environment.intensity", "--env-intensity", "", 0, 1e9, "Scale the environment's radiance",
                       all | kSweep, [](Job& j) -> float& { return j.environment.intensity; }));
    r.back().slider_min = 0, r.back().slider_max = 4;
    r.push_back(integer("environment.bakeSamples", "--env-samples", "", 1, 65536,
                        "GGX samples per texel when baking the environment", raster,
                        [](Job& j) -> int& { return j.environment.bake_samples; }));
    r.back().example = "64";
    r.push_back(integer("environment.bakeSize", "--env-size", "pixels, a power of two", 4, 4096,
                        "Specular cube face size when baking the environment", raster,
                        [](Job& j) -> int& { return j.environment.bake_size; }));
    r.back().example = "128";
    r.back().check = [](const std::string& t) {
        int n = std::atoi(t.c_str());
        return n > 0 && (n & (n - 1)) == 0 ? std::string() : std::string("-");
    };
    r.push_back(choice("environment.irradiance", "--env-irradiance", {"filtered", "exact"},
                       "Diffuse image-based light: filtered (importance sampled from blurred levels, as the Khronos "
                       "Sample Viewer bakes it) or exact (the cosine convolution of the panorama: agrees with "
                       "`fresnel trace` within 1 %, where filtered is off by up to 15 % on one side of an environment "
                       "with small bright lights)",
                       raster, [](const Job& j) { return std::string(j.environment.exact_irradiance ? "exact" : "filtered"); },
                       [](Job& j, const std::string& t) { j.environment.exact_irradiance = t == "exact"; }));
    r.push_back(boolean("environment.cache", "--no-cache", true,
                        "Read and write baked environments and the BRDF table under $XDG_CACHE_HOME/fresnel "
                        "(false: bake them again)",
                        kCli | kWeb, [](Job& j) -> bool& { return j.environment.use_cache; }));
    {
        Setting s;
        s.key = "background";
        s.flag = "--background";
        s.type = Type::Text;
        s.doc = "Background: automatic (blur with an environment, else black), environment (sharp), blur (a "
                "prefiltered level), transparent, or R,G,B (0..1, display-encoded)";
        s.front_ends = all;
        s.syntax = "automatic, environment (sharp), blur, transparent or R,G,B (0..1, display-encoded)";
        s.check = check_background;
        s.example = "0.1,0.2,0.3";
        s.canonical = canonical_background;
        s.get = [](const Job& j) {
            using Mode = Job::Background::Mode;
            Value v;
            switch (j.background.mode) {
                case Mode::Automatic: v.text = "automatic"; break;
                case Mode::Environment: v.text = "environment"; break;
                case Mode::Blurred: v.text = "blur"; break;
                case Mode::Transparent: v.text = "transparent"; break;
                case Mode::Color: v.text = vec_text(j.background.color); break;
            }
            return v;
        };
        s.put = [](Job& j, const Value& v) {
            using Mode = Job::Background::Mode;
            const std::string& t = v.text;
            if (t == "automatic") j.background.mode = Mode::Automatic;
            else if (t == "environment") j.background.mode = Mode::Environment;
            else if (t == "blur") j.background.mode = Mode::Blurred;
            else if (t == "transparent") j.background.mode = Mode::Transparent;
            else {
                j.background.mode = Mode::Color;
                read_vec3(t, j.background.color);
            }
        };
        r.push_back(s);
    }

    // --- the image ---
    {
        Setting s;
        s.key = "render.size";
        s.flag = "--size";
        s.type = Type::Size;
        s.min = 1;
        s.max = 16384;
        s.unit = "pixels";
        s.doc = "Image size WxH, or N for N x N";
        s.example = "320x200";
        s.front_ends = all;
        s.get = [](const Job& j) {
            Value v;
            v.width = j.output.width;
            v.height = j.output.height;
            return v;
        };
        s.put = [](Job& j, const Value& v) {
            j.output.width = v.width;
            j.output.height = v.height;
        };
        r.push_back(s);
    }
    {
        Setting s;
        s.key = "render.msaa";
        s.flag = "--msaa";
        s.type = Type::Int;
        s.min = 1;
        s.max = 16;
        s.none = "auto";
        s.doc = "MSAA samples, 1 = off (auto: 4, or 1 with the ogl1 shading models, as OpenGL 1)";
        s.front_ends = raster;
        s.get = [](const Job& j) {
            Value v;
            v.unset = j.output.msaa <= 0;
            v.number = std::max(j.output.msaa, 1);
            return v;
        };
        s.put = [](Job& j, const Value& v) { j.output.msaa = v.unset ? 0 : int(v.number); };
        r.push_back(s);
    }
    r.push_back(number("render.anisotropy", "--anisotropy", "probes", 1, 16,
                       "Most anisotropic filtering probes of the detail maps along the footprint's major axis "
                       "(1: one trilinear probe)",
                       raster, [](Job& j) -> float& { return j.output.anisotropy; }));
    {
        std::vector<std::string> names;
        for (ToneMapper t : {ToneMapper::Neutral, ToneMapper::Aces, ToneMapper::AcesHill, ToneMapper::Reinhard,
                             ToneMapper::Agx, ToneMapper::None})
            names.emplace_back(tone_mapper_name(t));
        Setting s = choice(
            "render.toneMapping", "--tonemap", names, "Tone mapper", all,
            [](const Job& j) { return std::string(tone_mapper_name(j.output.tone_mapper)); },
            [](Job& j, const std::string& t) { j.output.tone_mapper = *parse_tone_mapper(t); });
        s.old_names = {"tonemap"};
        r.push_back(s);
    }
    r.push_back(number("render.exposure", "--exposure", "EV", -64, 64, "Exposure (radiance x 2^EV)", all | kSweep,
                       [](Job& j) -> float& { return j.output.exposure_ev; }));
    r.back().slider_min = -8, r.back().slider_max = 8;
    r.push_back(choice(
        "render.encoding", "--encoding", {"srgb", "gamma2.2"},
        "Display encoding: srgb (the exact curve) or gamma2.2 (pow 1/2.2)", all,
        [](const Job& j) { return std::string(j.output.encoding == Encoding::Gamma22 ? "gamma2.2" : "srgb"); },
        [](Job& j, const std::string& t) { j.output.encoding = *parse_encoding(t); }));
    {
        std::vector<std::string> names = {"none"};
        for (const std::string& n : debug_channel_names())
            if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
        r.push_back(choice(
            "render.debug", "--debug", names, "Show a channel or BRDF term instead of shading (NaN/Inf in magenta)",
            raster, [](const Job& j) { return debug_name(j.output.debug); },
            [](Job& j, const std::string& t) { j.output.debug = *parse_debug_channel(t); }));
    }
    {
        Setting s = boolean("render.energyCompensation", "--no-energy-compensation", true,
                            "Multiple-scattering compensation of the specular lobes, for every light (render) and "
                            "every bounce (trace), so the two agree in the white furnace (false: single scattering)",
                            raster | kTrace,
                            [](Job& j) -> bool& { return j.output.energy_compensation; });
        s.old_names = {"energy-compensation"};
        r.push_back(s);
    }
    r.push_back(boolean("render.instancing", "--no-instancing", true,
                        "Repeated meshes (a mesh several nodes place, EXT_mesh_gpu_instancing, a scene file's copies) "
                        "drawn with one instanced draw per primitive (render) and held once as Embree instances "
                        "(trace): the same picture (false: every placement on its own, to compare)",
                        raster | kTrace, [](Job& j) -> bool& { return j.output.instancing; }));
    r.push_back(choice(
        "render.shadows", "--shadows", {"off", "hard", "soft"},
        "Shadows of punctual lights: soft (a filtered edge, the default), hard (one filtered comparison) or off "
        "(as the Khronos Sample Viewer, which has none). trace always shadows",
        raster, [](const Job& j) { return std::string(shadows_name(j.output.shadows)); },
        [](Job& j, const std::string& t) { j.output.shadows = *parse_shadows(t); }));
    r.push_back(integer("render.shadowMapSize", "--shadow-map-size", "texels", 64, 8192,
                        "Texels a side of each shadow map (a cascade, a spot light's map, a cube face); smaller where "
                        "the atlas of every light's maps would exceed the GPU's texture size",
                        raster, [](Job& j) -> int& { return j.output.shadow_map_size; }));
    r.back().example = "1024";
    r.push_back(integer("render.shadowCascades", "--shadow-cascades", "", 1, 4,
                        "Shadow maps of a directional light, each fitted to a slice of the view's depth", raster,
                        [](Job& j) -> int& { return j.output.shadow_cascades; }));
    r.back().example = "3";
    r.push_back(choice(
        "render.ao", "--ao", {"off", "ssao", "baked"},
        "Occlusion of image-based and ambient light: off (as the Khronos Sample Viewer), ssao (ground-truth "
        "ambient occlusion from each frame's depth, within --ao-radius: everything that moves, "
        "the web page too) or baked (the tracer's rays at every vertex of the static scene, once per load; skinned "
        "and morphed meshes are not occluded); the material's occlusion texture and it, the smaller of the two. "
        "trace always occludes; the web page has no baked",
        raster, [](const Job& j) { return std::string(ambient_occlusion_name(j.output.ao)); },
        [](Job& j, const std::string& t) { j.output.ao = *parse_ambient_occlusion(t); }));
    r.back().choices_not_offered = {{"baked", kWeb}};
    r.push_back(choice(
        "render.envLight", "--env-light", {"off", "dominant"},
        "The environment's dominant light (a sun or a studio's key light: a small region carrying at least a "
        "quarter of its light): off (part of the image-based light, never shadowed) or dominant (taken out of the "
        "bake and drawn as a directional light that casts shadows). trace always uses the whole environment",
        kCli | kSceneFile | kViewScript, [](const Job& j) { return std::string(env_light_name(j.output.env_light)); },
        [](Job& j, const std::string& t) { j.output.env_light = *parse_env_light(t); }));
    r.push_back(integer("render.aoRays", "--ao-rays", "rays", 4, 4096,
                        "Rays per vertex of --ao baked (the visibility's noise falls as 1/sqrt of it)",
                        kCli | kSceneFile | kViewScript, [](Job& j) -> int& { return j.output.ao_rays; }));
    r.back().example = "256";
    r.push_back(number("render.aoRadius", "--ao-radius", "", 0, 1e9,
                       "How far --ao ssao looks for occluders, in the scene's units (0: a quarter of the scene's "
                       "bounding radius)",
                       raster, [](Job& j) -> float& { return j.output.ao_radius; }));
    r.back().example = "0.5";
    r.push_back(choice(
        "render.shading", "--shading", {"auto", "gltf", "ogl1", "ogl1-pixel", "blinn-phong-normalized"},
        "Shading model: auto (OpenGL 1 for OBJ/MTL Phong materials, glTF for the rest), gltf, ogl1 (OpenGL 1 per "
        "vertex), ogl1-pixel (per fragment) or blinn-phong-normalized",
        raster, [](const Job& j) { return std::string(shading_model_name(j.output.shading)); },
        [](Job& j, const std::string& t) { j.output.shading = *parse_shading_model(t); }));
    {
        Setting s;
        s.key = "render.brdf";
        s.flag = "--brdf";
        s.type = Type::Text;
        s.doc = "BRDF terms of the glTF model, comma-separated: D=ggx|beckmann|blinn-phong, "
                "G=smith-height-correlated|smith-separable|schlick-ggx|cook-torrance|kelemen, "
                "F=schlick|exact-dielectric|spherical-gaussian|exact[:iron|gold|aluminium|chromium|copper|lead|"
                "platinum|silver], diffuse=lambert|burley|oren-nayar (default: the first of each, glTF's). render: "
                "punctual lights only; trace: every light and bounce";
        s.front_ends = all;
        s.syntax = "default or TERM=NAME,... (D=, G=, F=, diffuse=)";
        s.example = "D=beckmann,G=kelemen,F=exact:gold,diffuse=oren-nayar";
        s.check = [](const std::string& t) {
            std::string why;
            if (t.empty() || t == "default") return std::string();
            return brdf::parse_brdf_model(t, &why) ? std::string() : why;
        };
        s.canonical = [](const std::string& t) {
            if (t.empty() || t == "default") return std::string("default");
            return brdf::to_string(*brdf::parse_brdf_model(t, nullptr));
        };
        s.get = [](const Job& j) {
            Value v;
            v.text = j.output.brdf.is_default() ? "default" : brdf::to_string(j.output.brdf);
            return v;
        };
        s.put = [](Job& j, const Value& v) {
            j.output.brdf = v.text == "default" ? brdf::BrdfModel{} : *brdf::parse_brdf_model(v.text, nullptr);
        };
        r.push_back(s);
    }
    {
        Setting s;
        s.key = "render.ambient";
        s.flag = "--ambient";
        s.type = Type::Vec3;
        s.min = 0;
        s.max = 1e9;
        s.doc = "Global ambient light R,G,B (OpenGL 1's GL_LIGHT_MODEL_AMBIENT x Ka; glTF: ambient radiance x "
                "diffuse colour)";
        s.front_ends = raster;
        s.get = [](const Job& j) {
            Value v;
            v.vec = j.output.ambient;
            return v;
        };
        s.put = [](Job& j, const Value& v) { j.output.ambient = v.vec; };
        r.push_back(s);
    }
    {
        Setting s;
        s.key = "render.fog";
        s.flag = "--fog";
        s.type = Type::Text;
        s.doc = "OpenGL 1 fog on the eye-plane distance (ogl1 models): none, linear:START,END (near, far: the clip "
                "distances), exp:DENSITY or exp2:DENSITY";
        s.front_ends = raster;
        s.syntax = "none, linear:START,END (numbers, or near and far: the clip distances), exp:DENSITY or "
                   "exp2:DENSITY (DENSITY >= 0)";
        s.check = check_fog;
        s.example = "linear:1,10";
        s.canonical = [](const std::string& t) {
            Fog f;
            put_fog(f, t);
            return fog_text(f);
        };
        s.get = [](const Job& j) {
            Value v;
            v.text = fog_text(j.output.fog);
            return v;
        };
        s.put = [](Job& j, const Value& v) { put_fog(j.output.fog, v.text); };
        r.push_back(s);
    }
    {
        Setting s;
        s.key = "render.fogColor";
        s.flag = "--fog-color";
        s.type = Type::Vec3;
        s.min = 0;
        s.max = 1;
        s.none = "background";
        s.doc = "Fog colour R,G,B (display values; background: the background colour)";
        s.front_ends = raster;
        s.get = [](const Job& j) {
            Value v;
            v.unset = !j.output.fog_color;
            v.vec = j.output.fog_color.value_or(glm::vec3(0.0f));
            return v;
        };
        s.put = [](Job& j, const Value& v) {
            if (v.unset) j.output.fog_color.reset();
            else j.output.fog_color = v.vec;
        };
        r.push_back(s);
    }
    return r;
}

bool same_name(std::string_view a, std::string_view b) { return a == b; }

}  // namespace

std::string Setting::expected() const {
    std::string e;
    const std::string u = unit.empty() ? "" : " (" + unit + ")";
    switch (type) {
        case Type::Bool: e = "true or false"; break;
        case Type::Int: e = "a whole number in " + range_text(min, max) + u; break;
        case Type::Number: e = "a number in " + range_text(min, max) + u; break;
        case Type::Vec3: e = "X,Y,Z, each in " + range_text(min, max); break;
        case Type::Size: e = "WxH (or N for N x N) with " + num(min) + ".." + num(max) + " pixels per side"; break;
        case Type::Choice: {
            for (std::size_t i = 0; i < choices.size(); ++i)
                e += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
            break;
        }
        case Type::Text: e = syntax; break;
    }
    if (!none.empty()) e += " or " + none;
    return e;
}

const std::vector<Setting>& all() {
    static const std::vector<Setting> registry = make_registry();
    return registry;
}

const Setting* find(std::string_view name, std::string* renamed) {
    std::string_view bare = name;
    while (bare.size() > 2 && bare.substr(0, 2) == "--") bare.remove_prefix(2);
    for (const Setting& s : all()) {
        if (same_name(s.key, name)) return &s;
        if (!s.flag.empty() && (same_name(s.flag, name) || same_name(std::string_view(s.flag).substr(2), bare)))
            return &s;
    }
    for (const Setting& s : all())
        for (const std::string& old : s.old_names)
            if (old == name) {
                if (renamed) *renamed = "'" + old + "' is now '" + s.key + "'";
                return &s;
            }
    return nullptr;
}

const Setting& at(std::string_view key) {
    for (const Setting& s : all())
        if (s.key == key) return s;
    throw std::logic_error("no setting '" + std::string(key) + "' in the registry");
}

Value parse(const Setting& s, const std::string& text, const std::string& where) {
    auto fail = [&]() -> Value { throw Error(where, "", "expected " + s.expected() + ", got '" + text + "'"); };
    Value v;
    if (!s.none.empty() && text == s.none) {
        v.unset = true;
        return v;
    }
    double d = 0;
    switch (s.type) {
        case Type::Bool:
            if (text == "true" || text == "1" || text == "on") v.flag = true;
            else if (text == "false" || text == "0" || text == "off") v.flag = false;
            else return fail();
            return v;
        case Type::Int:
            if (!read_number(text, d) || d != std::floor(d) || d < s.min || d > s.max) return fail();
            if (s.check && !s.check(text).empty()) return fail();
            v.number = d;
            return v;
        case Type::Number:
            if (!read_number(text, d) || d < s.min || d > s.max) return fail();
            v.number = float(d);  // what the job holds
            return v;
        case Type::Vec3:
            if (!read_vec3(text, v.vec)) return fail();
            for (int i = 0; i < 3; ++i)
                if (v.vec[i] < s.min || v.vec[i] > s.max) return fail();
            return v;
        case Type::Size: {
            // WxH, or one number N for a square N x N (--size 512).
            auto x = text.find('x');
            double w = 0, h = 0;
            const bool read = x == std::string::npos
                                  ? read_number(text, w) && (h = w, true)
                                  : read_number(text.substr(0, x), w) && read_number(text.substr(x + 1), h);
            if (!read || w != std::floor(w) || h != std::floor(h) || w < s.min || h < s.min || w > s.max || h > s.max)
                return fail();
            v.width = int(w);
            v.height = int(h);
            return v;
        }
        case Type::Choice:
            if (std::find(s.choices.begin(), s.choices.end(), text) == s.choices.end())
                throw Error(where, "", "expected " + s.expected() + ", got '" + text + "'" + did_you_mean(text, s.choices));
            v.text = text;
            return v;
        case Type::Text:
            if (s.check) {
                std::string why = s.check(text);
                if (!why.empty())
                    throw Error(where, "", "expected " + s.expected() + ", got '" + text + "'" +
                                               (why == "-" ? std::string() : " (" + why + ")"));
            }
            v.text = s.canonical ? s.canonical(text) : text;
            return v;
    }
    return fail();
}

std::string format(const Setting& s, const Value& v) {
    if (v.unset && !s.none.empty()) return s.none;
    switch (s.type) {
        case Type::Bool: return v.flag ? "true" : "false";
        case Type::Int: return std::to_string(static_cast<long long>(v.number));
        case Type::Number: return num(v.number);
        case Type::Vec3: return vec_text(v.vec);
        case Type::Size: return std::to_string(v.width) + "x" + std::to_string(v.height);
        case Type::Choice:
        case Type::Text: return v.text;
    }
    return {};
}

std::string get(const Job& job, const Setting& s) { return format(s, s.get(job)); }

void set(Job& job, const Setting& s, const std::string& text, const std::string& where) {
    s.put(job, parse(s, text, where));
}

void set(Job& job, std::string_view name, const std::string& text, const std::string& where, Diagnostics* diag) {
    std::string renamed;
    const Setting* s = find(name, &renamed);
    if (!s) {
        std::vector<std::string> keys;
        for (const Setting& k : all()) keys.push_back(k.key);
        throw Error(where, "", "unknown setting '" + std::string(name) + "'" + did_you_mean(std::string(name), keys));
    }
    if (!renamed.empty() && diag) diag->warn(where, "", renamed + " (the old spelling still works)");
    set(job, *s, text, where);
}

bool is_default(const Job& job, const Setting& s) { return get(job, s) == get(Job{}, s); }

std::vector<const Setting*> offered_by(unsigned front_end) {
    std::vector<const Setting*> out;
    for (const Setting& s : all())
        if (s.offered(front_end)) out.push_back(&s);
    return out;
}

std::string default_text(const Setting& s) { return get(Job{}, s); }

std::string example(const Setting& s) {
    if (!s.example.empty()) return s.example;
    const Value d = s.get(Job{});
    Value v = d;
    v.unset = false;
    switch (s.type) {
        case Type::Bool: v.flag = !d.flag; break;
        case Type::Int: v.number = d.unset ? std::min(s.min + 1, s.max) : d.number + 1 <= s.max ? d.number + 1 : d.number - 1; break;
        case Type::Number: v.number = d.unset ? std::clamp(1.5, s.min, s.max) : d.number + 1.5 <= s.max ? d.number + 1.5 : d.number - 1.5; break;
        case Type::Vec3: v.vec = glm::vec3(0.25f, 0.5f, 0.75f) * float(std::min(s.max, 1.0)); break;
        case Type::Size: v.width = 320; v.height = 200; break;
        case Type::Choice:
            for (const std::string& c : s.choices)
                if (c != d.text) {
                    v.text = c;
                    break;
                }
            break;
        case Type::Text: break;
    }
    return format(s, v);
}

namespace {
std::string json_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}
const char* type_name(Type t) {
    switch (t) {
        case Type::Bool: return "bool";
        case Type::Int: return "int";
        case Type::Number: return "number";
        case Type::Vec3: return "vec3";
        case Type::Size: return "size";
        case Type::Choice: return "choice";
        case Type::Text: return "text";
    }
    return "?";
}
}  // namespace

std::string describe_json() {
    std::string out = "[";
    for (const Setting& s : all()) {
        if (out.size() > 1) out += ",";
        out += "\n{\"key\":" + json_string(s.key) + ",\"flag\":" + json_string(s.flag) + ",\"type\":\"" +
               type_name(s.type) + "\",\"unit\":" + json_string(s.unit);
        if (s.type == Type::Int || s.type == Type::Number || s.type == Type::Vec3 || s.type == Type::Size)
            out += ",\"min\":" + json_number(s.min) + ",\"max\":" + json_number(s.max) +
                   ",\"sliderMin\":" + json_number(s.slider_lo()) + ",\"sliderMax\":" + json_number(s.slider_hi());
        out += ",\"choices\":[";
        for (std::size_t i = 0; i < s.choices.size(); ++i) out += (i ? "," : "") + json_string(s.choices[i]);
        out += "],\"none\":" + json_string(s.none) + ",\"default\":" + json_string(default_text(s)) +
               ",\"example\":" + json_string(example(s)) + ",\"expected\":" + json_string(s.expected()) +
               ",\"doc\":" + json_string(s.doc) + ",\"frontEnds\":[";
        const std::pair<unsigned, const char*> names[] = {{kCli, "cli"},   {kTrace, "trace"}, {kSceneFile, "sceneFile"},
                                                          {kViewScript, "viewScript"}, {kWeb, "web"}, {kSweep, "sweep"}};
        auto front_end_names = [&](unsigned bits) {
            std::string fe;
            for (const auto& [bit, name] : names)
                if (bits & bit) fe += std::string(fe.empty() ? "" : ",") + "\"" + name + "\"";
            return fe;
        };
        out += front_end_names(s.front_ends) + "],\"choicesNotOffered\":[";
        for (std::size_t i = 0; i < s.choices_not_offered.size(); ++i)
            out += std::string(i ? "," : "") + "{\"choice\":" + json_string(s.choices_not_offered[i].first) +
                   ",\"frontEnds\":[" + front_end_names(s.choices_not_offered[i].second) + "]}";
        out += "],\"oldNames\":[";
        for (std::size_t i = 0; i < s.old_names.size(); ++i) out += (i ? "," : "") + json_string(s.old_names[i]);
        out += "],\"shortcuts\":[";
        for (std::size_t i = 0; i < s.shortcuts.size(); ++i)
            out += std::string(i ? "," : "") + "{\"flag\":" + json_string(s.shortcuts[i].flag) +
                   ",\"value\":" + json_string(s.shortcuts[i].value) + "}";
        out += std::string("],\"periodic\":") + (s.periodic ? "true" : "false") + "}";
    }
    return out + "\n]\n";
}

}  // namespace fresnel::settings
