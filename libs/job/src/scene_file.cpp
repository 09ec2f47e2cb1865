// Scene files: JSON onto a Job. Every read goes through Reader, which checks the type and
// range and names the JSON pointer of the value; every object's keys are checked against
// the keys it may hold, and the others reported as warnings (a misspelt key should not
// silently do nothing). Paths go through the models' URI policy (fresnel/scene/paths.h).
// Long (~850 lines): the reader and the writer of one format, kept side by side so that
// what is read and what is written stay the same fields.
#include "fresnel/job/scene_document.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/float_text.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/job/settings.h"
#include "fresnel/scene/paths.h"

namespace fresnel {

namespace fs = std::filesystem;
using json = nlohmann::json;

bool is_scene_file(const fs::path& path) {
    std::string e = path.extension().string();
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e == ".json";
}

namespace {

constexpr std::size_t kMaxModels = 1024, kMaxLights = 1024, kMaxOverrides = 4096;

std::string at(const std::string& ptr, const std::string& key) {
    std::string k;  // JSON pointer escaping (RFC 6901)
    for (char c : key) k += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
    return ptr + "/" + k;
}
std::string at(const std::string& ptr, std::size_t i) { return ptr + "/" + std::to_string(i); }

class Reader {
public:
    Reader(std::string name, fs::path base, Diagnostics& diag, const SceneFileOptions& o)
        : name_(std::move(name)), base_(std::move(base)), diag_(diag), options_(o) {}

    [[noreturn]] void fail(const std::string& ptr, const std::string& what) const { throw Error(name_, ptr, what); }
    void warn(const std::string& ptr, const std::string& what) const { diag_.warn(name_, ptr, what); }

    // Warns about each key of `obj` not in `known`.
    void keys(const json& obj, const std::string& ptr, std::initializer_list<const char*> known,
              const std::vector<std::string>& also = {}) const {
        for (auto it = obj.begin(); it != obj.end(); ++it) {
            bool ok = false;
            for (const char* k : known) ok |= it.key() == k;
            for (const auto& k : also) ok |= it.key() == k;
            if (!ok) warn(at(ptr, it.key()), "unknown key '" + it.key() + "' (ignored)");
        }
    }
    const json& object(const json& v, const std::string& ptr) const {
        if (!v.is_object()) fail(ptr, "must be an object");
        return v;
    }
    const json& array(const json& v, const std::string& ptr, std::size_t max) const {
        if (!v.is_array()) fail(ptr, "must be an array");
        if (v.size() > max) fail(ptr, "has " + std::to_string(v.size()) + " entries; at most " + std::to_string(max));
        return v;
    }
    double number(const json& v, const std::string& ptr, double lo = -1e30, double hi = 1e30) const {
        if (!v.is_number()) fail(ptr, "must be a number");
        double d = v.get<double>();
        if (!std::isfinite(d)) fail(ptr, "must be finite");
        if (d < lo || d > hi) {
            std::ostringstream ss;
            ss << "value " << d << " out of range [" << lo << ", " << hi << "]";
            fail(ptr, ss.str());
        }
        return d;
    }
    int integer(const json& v, const std::string& ptr, long long lo, long long hi) const {
        if (!v.is_number()) fail(ptr, "must be an integer");
        double d = v.get<double>();
        if (!std::isfinite(d) || d != std::floor(d)) fail(ptr, "must be an integer");
        if (d < double(lo) || d > double(hi))
            fail(ptr, "value " + v.dump() + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return int(d);
    }
    bool boolean(const json& v, const std::string& ptr) const {
        if (!v.is_boolean()) fail(ptr, "must be true or false");
        return v.get<bool>();
    }
    std::string string(const json& v, const std::string& ptr) const {
        if (!v.is_string()) fail(ptr, "must be a string");
        return v.get<std::string>();
    }
    template <int N>
    glm::vec<N, float> vec(const json& v, const std::string& ptr, double lo = -1e30, double hi = 1e30) const {
        if (!v.is_array() || v.size() != std::size_t(N)) fail(ptr, "must be an array of " + std::to_string(N) + " numbers");
        glm::vec<N, float> out;
        for (int i = 0; i < N; ++i) out[i] = float(number(v[std::size_t(i)], at(ptr, std::size_t(i)), lo, hi));
        return out;
    }
    // A file the document names: resolved by the URI policy, and it must exist.
    fs::path path(const json& v, const std::string& ptr) const {
        std::string s = string(v, ptr);
        std::string error;
        auto p = resolve_relative_path(s, base_, options_.allow_external_files, error);
        if (!p) fail(ptr, error);
        std::error_code ec;
        if (!fs::exists(*p, ec)) fail(ptr, "'" + s + "' does not exist (" + p->string() + ")");
        return *p;
    }
    // An output path: the same policy, but it need not exist.
    fs::path output_path(const json& v, const std::string& ptr) const {
        std::string s = string(v, ptr);
        std::string error;
        auto p = resolve_relative_path(s, base_, options_.allow_external_files, error);
        if (!p) fail(ptr, error);
        return *p;
    }
    const json* find(const json& obj, const char* key) const {
        auto it = obj.find(key);
        return it == obj.end() ? nullptr : &*it;
    }

private:
    std::string name_;
    fs::path base_;
    Diagnostics& diag_;
    SceneFileOptions options_;
};

// The JSON value of a setting (fresnel/job/settings.h) as the registry's text, its JSON type
// checked: booleans, numbers, [X, Y, Z], [W, H] or "WxH", strings; an optional setting's
// word for unset ("fit", "auto") as a string.
std::string setting_text(const Reader& r, const settings::Setting& s, const json& v, const std::string& ptr) {
    using settings::Type;
    if (!s.none.empty() && v.is_string() && v.get<std::string>() == s.none) return s.none;
    switch (s.type) {
        case Type::Bool:
            return r.boolean(v, ptr) ? "true" : "false";
        case Type::Int:
        case Type::Number:
            if (!v.is_number()) r.fail(ptr, "expected " + s.expected() + ", got " + v.dump());
            return v.dump();
        case Type::Vec3: {
            if (!v.is_array() || v.size() != 3) r.fail(ptr, "expected " + s.expected() + " as [X, Y, Z], got " + v.dump());
            std::string t;
            for (std::size_t i = 0; i < 3; ++i) {
                if (!v[i].is_number()) r.fail(at(ptr, i), "must be a number");
                t += (i ? "," : "") + v[i].dump();
            }
            return t;
        }
        case Type::Size:
            if (v.is_string()) return v.get<std::string>();
            if (!v.is_array() || v.size() != 2) r.fail(ptr, "must be [W, H] or \"WxH\"");
            return std::to_string(r.integer(v[0], at(ptr, std::size_t(0)), (long long)s.min, (long long)s.max)) + "x" +
                   std::to_string(r.integer(v[1], at(ptr, std::size_t(1)), (long long)s.min, (long long)s.max));
        case Type::Choice:
        case Type::Text:
            if (!v.is_string()) r.fail(ptr, "expected " + s.expected() + ", got " + v.dump());
            return v.get<std::string>();
    }
    return {};
}

// Sets `s` from the JSON value at `ptr`; a bad value fails naming the file and the pointer.
void apply_setting(const Reader& r, const settings::Setting& s, const json& v, const std::string& ptr, Job& job) {
    std::string text = setting_text(r, s, v, ptr);
    try {
        settings::set(job, s, text, ptr);
    } catch (const Error& e) {
        r.fail(ptr, e.reason());
    }
}

// The keys of object `obj` (at `ptr`, the settings' key prefix `prefix`) that are settings
// scene files hold, set in the registry's order; the others, unless in `structural`, warned about.
void read_settings(const Reader& r, const json& obj, const std::string& prefix, const std::string& ptr, Job& job,
                   std::initializer_list<const char*> structural = {}, const std::vector<std::string>& also = {}) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
        const settings::Setting* s = settings::find(prefix.empty() ? it.key() : prefix + "." + it.key());
        bool known = s && s->offered(settings::kSceneFile) && s->key == (prefix.empty() ? it.key() : prefix + "." + it.key());
        for (const char* k : structural) known |= it.key() == k;
        for (const auto& k : also) known |= it.key() == k;
        if (!known) r.warn(at(ptr, it.key()), "unknown key '" + it.key() + "' (ignored)");
    }
    for (const settings::Setting& s : settings::all()) {
        if (!s.offered(settings::kSceneFile)) continue;
        std::string name = s.key;
        if (!prefix.empty()) {
            if (name.rfind(prefix + ".", 0) != 0) continue;
            name = name.substr(prefix.size() + 1);
        }
        if (name.find('.') != std::string::npos) continue;  // deeper: another object's
        bool skip = false;
        for (const char* k : structural) skip |= name == k;
        if (skip) continue;
        if (auto* v = r.find(obj, name.c_str())) apply_setting(r, s, *v, at(ptr, name), job);
    }
}

glm::mat4 read_transform(const Reader& r, const json& m, const std::string& ptr) {
    const json* matrix = r.find(m, "matrix");
    const json* t = r.find(m, "translation");
    const json* q = r.find(m, "rotation");
    const json* s = r.find(m, "scale");
    if (matrix) {
        if (t || q || s) r.fail(ptr, "has both 'matrix' and translation/rotation/scale");
        if (!matrix->is_array() || matrix->size() != 16) r.fail(at(ptr, "matrix"), "must be an array of 16 numbers");
        glm::mat4 out;
        float* f = glm::value_ptr(out);  // column-major, as glTF's node.matrix
        for (std::size_t i = 0; i < 16; ++i) f[i] = float(r.number((*matrix)[i], at(at(ptr, "matrix"), i)));
        return out;
    }
    glm::mat4 out(1.0f);
    if (t) out = glm::translate(out, r.vec<3>(*t, at(ptr, "translation")));
    if (q) {
        glm::vec4 v = r.vec<4>(*q, at(ptr, "rotation"), -1e6, 1e6);  // x, y, z, w as glTF
        float len = glm::length(v);
        if (!(len > 1e-6f)) r.fail(at(ptr, "rotation"), "must be a unit quaternion [x, y, z, w]");
        v /= len;
        out = out * glm::mat4_cast(glm::quat(v.w, v.x, v.y, v.z));
    }
    if (s) out = glm::scale(out, r.vec<3>(*s, at(ptr, "scale")));
    return out;
}

// A model's material override: "name" or "index", and properties of the material property
// registry (fresnel/material/properties.h) by name, each checked against it.
void read_material_override(const Reader& r, const json& o, const std::string& ptr, Job::Source::MaterialOverride& mo) {
    namespace mp = material_properties;
    r.object(o, ptr);
    for (const auto& [key, v] : o.items()) {
        const std::string where = at(ptr, key);
        if (key == "name") mo.name = r.string(v, where);
        else if (key == "index") mo.index = r.integer(v, where, 0, 1 << 30);
        else if (const mp::Property* p = mp::find(key)) {
            std::string got = "'" + (v.is_string() ? v.get<std::string>() : v.dump()) + "'";
            auto fail = [&] { r.fail(where, "expected " + mp::expected(*p) + ", got " + got); };
            mp::Value value{};
            if (p->type == mp::Type::Bool) {
                if (!v.is_boolean()) fail();
                value[0] = v.get<bool>() ? 1.0f : 0.0f;
            } else if (p->type == mp::Type::Choice) {
                if (!v.is_string()) fail();
                try {
                    value = mp::parse(*p, v.get<std::string>(), where);
                } catch (const Error&) {
                    fail();
                }
            } else {
                std::vector<float> numbers;
                if (v.is_number()) numbers.push_back(v.get<float>());
                else if (v.is_array())
                    for (const json& x : v) {
                        if (!x.is_number()) fail();
                        numbers.push_back(x.get<float>());
                    }
                else fail();
                if (int(numbers.size()) != p->width || (p->width > 1 && !v.is_array())) fail();
                for (std::size_t i = 0; i < numbers.size(); ++i) value[i] = numbers[i];
                if (!mp::check(*p, value).empty()) fail();
            }
            mo.values[key] = value;
        } else
            r.fail(where, "is not a material property (name, index, or one `fresnel settings` lists under materials)");
    }
    if (mo.name && mo.index) r.fail(ptr, "has both 'name' and 'index'");
}

void read_models(const Reader& r, const json& doc, Job& job) {
    const json* single = r.find(doc, "model");
    const json* list = r.find(doc, "models");
    if (single && list) r.fail("", "has both 'model' and 'models'");
    std::vector<Job::Source::Model> models;
    if (single) {
        Job::Source::Model m;
        if (!(single->is_string() && single->get<std::string>() == "demo")) m.path = r.path(*single, "/model").string();
        m.scene = job.source.scene;  // the job's (a batch's --scene) still applies
        models.push_back(m);
    }
    if (list) {
        r.array(*list, "/models", kMaxModels);
        if (list->empty()) r.fail("/models", "must hold at least one model");
        for (std::size_t i = 0; i < list->size(); ++i) {
            std::string ptr = at("/models", i);
            const json& o = r.object((*list)[i], ptr);
            r.keys(o, ptr, {"path", "scene", "translation", "rotation", "scale", "matrix", "materials", "visible", "name"});
            Job::Source::Model m;
            const json* p = r.find(o, "path");
            if (!p) r.fail(ptr, "needs a 'path' (a model file; \"demo\" for the built-in demo)");
            if (p->is_string() && p->get<std::string>() == "demo") m.path.clear();
            else m.path = r.path(*p, at(ptr, "path")).string();
            if (auto* v = r.find(o, "scene")) m.scene = r.integer(*v, at(ptr, "scene"), 0, 1 << 20);
            if (auto* v = r.find(o, "visible")) m.visible = r.boolean(*v, at(ptr, "visible"));
            if (auto* v = r.find(o, "name")) r.string(*v, at(ptr, "name"));
            m.transform = read_transform(r, o, ptr);
            if (auto* v = r.find(o, "materials")) {
                r.array(*v, at(ptr, "materials"), kMaxOverrides);
                for (std::size_t k = 0; k < v->size(); ++k) {
                    Job::Source::MaterialOverride mo;
                    read_material_override(r, (*v)[k], at(at(ptr, "materials"), k), mo);
                    m.materials.push_back(mo);
                }
            }
            models.push_back(std::move(m));
        }
    }
    if (models.empty()) return;
    // One model at the origin, as written, is what a plain `render MODEL` does: keep the
    // one-model form so both load the same way.
    const auto& m0 = models.front();
    if (models.size() == 1 && m0.transform == glm::mat4(1.0f) && m0.visible && m0.materials.empty()) {
        job.source.model = m0.path;
        job.source.scene = m0.scene;
        job.source.models.clear();
    } else {
        job.source.model.clear();
        job.source.scene = -1;
        job.source.models = std::move(models);
    }
}

void read_camera(const Reader& r, const json& c, Job& job) {
    const std::string ptr = "/camera";
    r.object(c, ptr);
    r.keys(c, ptr, {"type", "yaw", "pitch", "distance", "fov", "eye", "target", "up", "model", "index"});
    std::string type;
    if (auto* v = r.find(c, "type")) type = r.string(*v, at(ptr, "type"));
    else type = r.find(c, "eye") ? "lookAt" : r.find(c, "index") ? "model" : "orbit";
    Job::Camera& cam = job.camera;
    auto unused = [&](std::initializer_list<const char*> keys) {
        for (const char* k : keys)
            if (r.find(c, k)) r.warn(at(ptr, k), std::string("not used by a camera of type ") + type + " (ignored)");
    };
    if (type == "orbit") unused({"eye", "up", "model", "index"});
    if (type == "lookAt") unused({"yaw", "pitch", "distance", "model", "index"});
    if (type == "model") unused({"yaw", "pitch", "distance", "fov", "eye", "target", "up"});
    // The camera's settings (fresnel/job/settings.h): camera.yaw is /camera/yaw.
    auto setting = [&](const char* key) {
        if (auto* v = r.find(c, key)) apply_setting(r, settings::at(std::string("camera.") + key), *v, at(ptr, key), job);
    };
    auto fov = [&] { setting("fov"); };
    if (type == "orbit") {
        cam.scene_camera.reset();
        cam.look_at.reset();
        for (const char* key : {"yaw", "pitch", "distance", "target", "fov"}) setting(key);  // target: a panned orbit
    } else if (type == "lookAt") {
        cam.scene_camera.reset();
        Job::Camera::LookAt la;
        const json* eye = r.find(c, "eye");
        const json* target = r.find(c, "target");
        if (!eye || !target) r.fail(ptr, "a lookAt camera needs 'eye' and 'target'");
        la.eye = r.vec<3>(*eye, at(ptr, "eye"));
        la.target = r.vec<3>(*target, at(ptr, "target"));
        if (auto* v = r.find(c, "up")) la.up = r.vec<3>(*v, at(ptr, "up"));
        if (glm::length(la.eye - la.target) <= 0.0f) r.fail(ptr, "'eye' and 'target' must differ");
        cam.look_at = la;
        fov();
    } else if (type == "model") {
        cam.look_at.reset();
        cam.scene_camera = 0;
        cam.scene_camera_model = 0;
        setting("index");
        if (auto* v = r.find(c, "model")) cam.scene_camera_model = r.integer(*v, at(ptr, "model"), 0, 1 << 20);
    } else {
        r.fail(at(ptr, "type"), "must be orbit, lookAt or model, not '" + type + "'");
    }
}

LightInstance read_light(const Reader& r, const json& l, const std::string& ptr) {
    r.object(l, ptr);
    r.keys(l, ptr, {"type", "color", "intensity", "range", "direction", "azimuth", "elevation", "position", "target",
                    "innerConeAngle", "outerConeAngle", "width", "height", "radius", "angularRadius", "length", "name"});
    const json* t = r.find(l, "type");
    if (!t) r.fail(ptr, "needs a 'type': directional, point, spot, rect, disk, sphere or tube");
    std::string type = r.string(*t, at(ptr, "type"));
    LightInstance li;
    glm::vec3 color(1.0f);
    if (auto* v = r.find(l, "color")) color = r.vec<3>(*v, at(ptr, "color"), 0, 1e6);
    float intensity = 1.0f;
    if (auto* v = r.find(l, "intensity")) intensity = float(r.number(*v, at(ptr, "intensity"), 0, 1e12));
    li.radiance = color * intensity;
    if (auto* v = r.find(l, "range")) li.range = float(r.number(*v, at(ptr, "range"), 0, 1e12));
    auto direction = [&](bool required) {
        const json* d = r.find(l, "direction");
        const json* az = r.find(l, "azimuth");
        const json* el = r.find(l, "elevation");
        const json* target = r.find(l, "target");
        if (int(d != nullptr) + int(az || el) + int(target != nullptr) > 1)
            r.fail(ptr, "give one of 'direction', 'azimuth'/'elevation' or 'target'");
        if (d) {
            glm::vec3 v = r.vec<3>(*d, at(ptr, "direction"));
            if (!(glm::length(v) > 0.0f)) r.fail(at(ptr, "direction"), "must not be zero");
            li.direction = glm::normalize(v);
        } else if (az || el) {
            float a = az ? float(r.number(*az, at(ptr, "azimuth"), -1e6, 1e6)) : 0.0f;
            float e = el ? float(r.number(*el, at(ptr, "elevation"), -90, 90)) : 0.0f;
            li.direction = direction_from_angles(a, e);  // as --light dir:AZ,EL: arriving from there
        } else if (target) {
            glm::vec3 v = r.vec<3>(*target, at(ptr, "target")) - li.position;
            if (!(glm::length(v) > 0.0f)) r.fail(at(ptr, "target"), "must differ from 'position'");
            li.direction = glm::normalize(v);
        } else if (required) {
            r.fail(ptr, "needs 'direction', 'azimuth'/'elevation' or 'target'");
        }
    };
    auto position = [&] {
        const json* p = r.find(l, "position");
        if (!p) r.fail(ptr, "needs a 'position'");
        li.position = r.vec<3>(*p, at(ptr, "position"));
    };
    if (type == "directional") {
        li.type = Light::Type::Directional;
        direction(true);
        // The angular radius its soft shadows come from (degrees; the sun's is about 0.27).
        if (const json* v = r.find(l, "angularRadius"))
            li.radius = float(r.number(*v, at(ptr, "angularRadius"), 0, 20)) * 3.14159265358979f / 180.0f;
    } else if (type == "point") {
        li.type = Light::Type::Point;
        position();
    } else if (type == "spot") {
        li.type = Light::Type::Spot;
        position();
        direction(true);
        li.inner_cone = 0.0f;
        li.outer_cone = 0.7853982f;
        if (auto* v = r.find(l, "innerConeAngle")) li.inner_cone = float(r.number(*v, at(ptr, "innerConeAngle"), 0, 1.5707964));
        if (auto* v = r.find(l, "outerConeAngle")) li.outer_cone = float(r.number(*v, at(ptr, "outerConeAngle"), 0, 1.5707964));
        if (!(li.inner_cone < li.outer_cone)) r.fail(ptr, "innerConeAngle must be less than outerConeAngle (radians)");
    } else if (type == "rect" || type == "disk") {
        // Facing along 'direction' (or azimuth/elevation, or towards 'target'), as a spot light aims.
        li.type = type == "rect" ? Light::Type::Rect : Light::Type::Disk;
        position();
        direction(true);
        auto length = [&](const char* key, double fallback) {
            const json* v = r.find(l, key);
            return v ? float(r.number(*v, at(ptr, key), 1e-6, 1e6)) : float(fallback);
        };
        if (li.type == Light::Type::Rect) {
            area_light_axes(li.direction, length("width", 1.0), length("height", 1.0), li.axis_u, li.axis_v);
        } else {
            float radius = length("radius", 0.5);
            area_light_axes(li.direction, 2.0f * radius, 2.0f * radius, li.axis_u, li.axis_v);
        }
    } else if (type == "sphere") {
        li.type = Light::Type::Sphere;
        position();
        const json* v = r.find(l, "radius");
        li.radius = v ? float(r.number(*v, at(ptr, "radius"), 1e-6, 1e6)) : 0.5f;
    } else if (type == "tube") {
        // Its axis along 'direction' (or azimuth/elevation, or towards 'target').
        li.type = Light::Type::Tube;
        position();
        direction(true);
        const json* len = r.find(l, "length");
        const json* rad = r.find(l, "radius");
        li.axis_u = li.direction * (0.5f * (len ? float(r.number(*len, at(ptr, "length"), 1e-6, 1e6)) : 1.0f));
        li.axis_v = glm::vec3(0.0f);
        li.radius = rad ? float(r.number(*rad, at(ptr, "radius"), 1e-6, 1e6)) : 0.05f;
    } else {
        r.fail(at(ptr, "type"), "must be directional, point, spot, rect, disk, sphere or tube, not '" + type + "'");
    }
    if (li.type != Light::Type::Tube && r.find(l, "length")) r.fail(at(ptr, "length"), "is for tube lights");
    if (li.type != Light::Type::Directional && r.find(l, "angularRadius"))
        r.fail(at(ptr, "angularRadius"), "is for directional lights");
    if (li.type != Light::Type::Rect)
        for (const char* key : {"width", "height"})
            if (r.find(l, key)) r.fail(at(ptr, key), "is for rect lights");
    if (li.type == Light::Type::Point || li.type == Light::Type::Spot) {
        // A bulb radius: the light shades as a point and casts contact-hardening shadows.
        if (const json* v = r.find(l, "radius")) li.radius = float(r.number(*v, at(ptr, "radius"), 0, 1e6));
    } else if (li.type != Light::Type::Disk && li.type != Light::Type::Sphere && li.type != Light::Type::Tube &&
               r.find(l, "radius")) {
        r.fail(at(ptr, "radius"), "is for point, spot, disk, sphere and tube lights");
    }
    if (auto* v = r.find(l, "name")) r.string(*v, at(ptr, "name"));
    return li;
}

void read_environment(const Reader& r, const json& e, Job& job) {
    const std::string ptr = "/environment";
    using Kind = Job::Environment::Kind;
    Job::Environment& env = job.environment;
    const settings::Setting& source = settings::at("environment");
    // The registry's text (studio, none, automatic, color:R,G,B or a file); a file through
    // the scene file's path policy, relative to its folder.
    auto set_source = [&](const std::string& text, const std::string& p, const json* file) {
        try {
            settings::set(job, source, text, p);
        } catch (const Error& err) {
            r.fail(p, err.reason());
        }
        if (env.kind == Kind::File) env.path = r.path(file ? *file : json(text), p).string();
    };
    if (e.is_string()) return set_source(e.get<std::string>(), ptr, &e);
    if (!e.is_object()) r.fail(ptr, "must be a string (studio, none, automatic, color:R,G,B or a file) or an object");
    const json* type = r.find(e, "type");
    const json* file = r.find(e, "file");
    const json* color = r.find(e, "color");
    std::string t = type ? r.string(*type, at(ptr, "type")) : file ? "file" : color ? "color" : "";
    if (t == "file") {
        if (!file) r.fail(ptr, "a file environment needs 'file'");
        set_source(r.string(*file, at(ptr, "file")), at(ptr, "file"), file);
    } else if (t == "color") {
        if (!color) r.fail(ptr, "a color environment needs 'color'");
        glm::vec3 c = r.vec<3>(*color, at(ptr, "color"), 0, 1e9);
        set_source("color:" + shortest_text(c.x) + "," + shortest_text(c.y) + "," + shortest_text(c.z), at(ptr, "color"),
                   nullptr);
    } else if (t == "studio" || t == "none" || t == "automatic") {
        set_source(t, at(ptr, "type"), nullptr);
    } else if (!t.empty()) {
        r.fail(at(ptr, "type"), "must be file, color, studio, none or automatic, not '" + t + "'");
    }
    read_settings(r, e, "environment", ptr, job, {"type", "file", "color"});
}

void read_background(const Reader& r, const json& b, Job& job) {
    const std::string ptr = "/background";
    const settings::Setting& background = settings::at("background");
    auto set = [&](const std::string& text, const std::string& p) {
        try {
            settings::set(job, background, text, p);
        } catch (const Error& e) {
            r.fail(p, e.reason());
        }
    };
    auto rgb = [](const glm::vec3& c) {
        return shortest_text(c.x) + "," + shortest_text(c.y) + "," + shortest_text(c.z);
    };
    // "color" alone: the colour the job has (the registry's R,G,B form).
    auto mode = [&](const std::string& s, const std::string& p) { set(s == "color" ? rgb(job.background.color) : s, p); };
    if (b.is_string()) return mode(b.get<std::string>(), ptr);
    if (b.is_array()) return set(rgb(r.vec<3>(b, ptr, 0, 1)), ptr);
    if (!b.is_object()) r.fail(ptr, "must be a string, an [R, G, B] colour or an object");
    r.keys(b, ptr, {"type", "color"});
    const json* color = r.find(b, "color");
    if (color) job.background.color = r.vec<3>(*color, at(ptr, "color"), 0, 1);
    if (auto* t = r.find(b, "type")) mode(r.string(*t, at(ptr, "type")), at(ptr, "type"));
    else if (color) mode("color", ptr);
}

void read_render(const Reader& r, const json& o, Job& job) {
    r.object(o, "/render");
    read_settings(r, o, "render", "/render", job);
}

// The deepest nesting of arrays and objects in `text` (strings skipped), stopping past `limit`.
int nesting_depth(std::string_view text, int limit) {
    int depth = 0, max = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            max = std::max(max, ++depth);
            if (max > limit) return max;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return max;
}

}  // namespace

json parse_json_limited(std::string_view text, const std::string& name, const SceneFileOptions& options) {
    if (text.size() > options.max_bytes)
        throw Error(name, "", "is " + std::to_string(text.size()) + " bytes; the limit is " +
                                  std::to_string(options.max_bytes));
    if (nesting_depth(text, options.max_depth) > options.max_depth)
        throw Error(name, "", "nests arrays and objects deeper than " + std::to_string(options.max_depth));
    try {
        return json::parse(text.begin(), text.end());
    } catch (const json::parse_error& e) {
        // e.what() reads "[json.exception.parse_error.101] parse error at line 1, column 2: ..."
        std::string what = e.what();
        auto p = what.find("] ");
        throw Error(name, "byte " + std::to_string(e.byte), p == std::string::npos ? what : what.substr(p + 2));
    } catch (const json::exception& e) {  // e.g. out_of_range.406: a number too large for a double
        std::string what = e.what();
        auto p = what.find("] ");
        throw Error(name, "", p == std::string::npos ? what : what.substr(p + 2));
    }
}

SceneFile parse_scene_document(const json& doc, const std::string& name, const fs::path& base_dir, const Job& defaults,
                               Diagnostics& diag, const SceneFileOptions& options, const std::vector<std::string>& ignore) {
    Reader r(name, base_dir, diag, options);
    if (!doc.is_object()) r.fail("", "a scene file is a JSON object");
    // The top-level settings (poseSkins, variant, objNormals, sceneLights) through the
    // registry; the other keys are the file's structure.
    std::vector<std::string> known = ignore;
    for (const char* k : {"fresnel", "$schema", "description", "model", "models", "camera", "lights", "environment",
                          "background", "render", "animation", "output"})
        known.push_back(k);
    if (auto* v = r.find(doc, "fresnel")) {
        int version = r.integer(*v, "/fresnel", 1, 1 << 30);
        if (version > kSceneFileVersion)
            r.fail("/fresnel", "format version " + std::to_string(version) + " is newer than this fresnel reads (" +
                                   std::to_string(kSceneFileVersion) + ")");
    } else if (options.require_version) {
        r.fail("/fresnel", "a scene file needs \"fresnel\": " + std::to_string(kSceneFileVersion) + " (the format version)");
    }
    if (auto* v = r.find(doc, "$schema")) r.string(*v, "/$schema");
    if (auto* v = r.find(doc, "description")) r.string(*v, "/description");

    SceneFile sf;
    sf.job = defaults;
    Job& job = sf.job;
    read_models(r, doc, job);
    read_settings(r, doc, "", "", job, {"environment", "background"}, known);
    if (auto* v = r.find(doc, "camera")) read_camera(r, *v, job);
    if (auto* v = r.find(doc, "lights")) {
        r.array(*v, "/lights", kMaxLights);
        job.lights.extra.clear();
        for (std::size_t i = 0; i < v->size(); ++i) job.lights.extra.push_back(read_light(r, (*v)[i], at("/lights", i)));
    }
    if (auto* v = r.find(doc, "environment")) read_environment(r, *v, job);
    if (auto* v = r.find(doc, "background")) read_background(r, *v, job);
    if (auto* v = r.find(doc, "render")) read_render(r, *v, job);
    if (auto* v = r.find(doc, "animation")) {
        r.object(*v, "/animation");
        read_settings(r, *v, "animation", "/animation", job);
    }
    if (auto* v = r.find(doc, "output")) {
        sf.output = r.output_path(*v, "/output");
        std::string e = sf.output->extension().string();
        for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (e != ".png" && e != ".exr" && e != ".hdr") r.fail("/output", "must end in .png, .exr or .hdr");
        job.output.float_output = e != ".png";
    }
    return sf;
}

SceneFile load_scene_file(const fs::path& path, const Job& defaults, Diagnostics& diag, const SceneFileOptions& options) {
    const std::string name = path.string();
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw Error(name, "", "is a folder, not a scene file");
    auto size = fs::file_size(path, ec);
    if (ec) throw Error(name, "", "cannot read the scene file: " + ec.message());
    if (size > options.max_bytes)
        throw Error(name, "", "is " + std::to_string(size) + " bytes; the limit is " + std::to_string(options.max_bytes));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(name, "", "cannot open the scene file");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    fs::path base = path.parent_path();
    return parse_scene_text(text, name, base.empty() ? fs::path(".") : base, defaults, diag, options);
}

SceneFile parse_scene_text(std::string_view text, const std::string& name, const fs::path& base_dir, const Job& defaults,
                           Diagnostics& diag, const SceneFileOptions& options, const std::vector<std::string>& ignore) {
    return parse_scene_document(parse_json_limited(text, name, options), name, base_dir, defaults, diag, options, ignore);
}


// --- writing -------------------------------------------------------------------------

namespace {

// A float as the JSON number that reads back to the same float: its shortest decimal form
// (0.2f is written 0.2, not 0.20000000298023224).
json num(float v) { return json(std::strtod(shortest_text(v).c_str(), nullptr)); }
template <int N>
json nums(const glm::vec<N, float>& v) {
    json a = json::array();
    for (int i = 0; i < N; ++i) a.push_back(num(v[i]));
    return a;
}

class Writer {
public:
    Writer(const fs::path& base, SceneDocumentReport& report) : report_(report) {
        std::error_code ec;
        base_ = fs::weakly_canonical(fs::absolute(base.empty() ? fs::path(".") : base), ec);
        if (ec) base_ = fs::absolute(base).lexically_normal();
    }
    // `p` relative to the base folder, as the reader's URI policy reads it back ('%' and ':'
    // percent-encoded, '/' separators).
    std::string path(const std::string& p) const {
        std::error_code ec;
        fs::path full = fs::weakly_canonical(fs::absolute(p), ec);
        if (ec) full = fs::absolute(p).lexically_normal();
        fs::path rel = full.lexically_relative(base_);
        std::string out;
        if (rel.empty()) {
            out = full.generic_string();
            report_.outside.push_back(p);
        } else {
            if (*rel.begin() == "..") report_.outside.push_back(p);
            out = rel.generic_string();
        }
        std::string encoded;
        for (char c : out) encoded += c == '%' ? std::string("%25") : c == ':' ? std::string("%3A") : std::string(1, c);
        return encoded;
    }

private:
    fs::path base_;
    SceneDocumentReport& report_;
};

// A setting's value as scene files hold it (the reader's setting_text the other way).
json setting_json(const settings::Setting& s, const settings::Value& v) {
    using settings::Type;
    switch (s.type) {
        case Type::Bool: return v.flag;
        case Type::Int: return static_cast<long long>(v.number);
        case Type::Number: return num(float(v.number));
        case Type::Vec3: return nums<3>(v.vec);
        case Type::Size: return json::array({v.width, v.height});
        case Type::Choice:
        case Type::Text: return v.text;
    }
    return nullptr;
}

// Every setting scene files hold whose value in `job` is set and differs from the default
// job's (or is always named), at its key's place; `structural` keys are the caller's.
void write_settings(json& doc, const Job& job, std::initializer_list<const char*> structural) {
    for (const settings::Setting& s : settings::all()) {
        if (!s.offered(settings::kSceneFile) || (s.applies && !s.applies(job))) continue;
        bool skip = false;
        for (const char* k : structural) skip |= s.key == k;
        if (skip || (settings::is_default(job, s) && !s.print_always)) continue;
        settings::Value v = s.get(job);
        if (v.unset) continue;  // absent: the reader's default
        json* at = &doc;
        std::string key = s.key;
        for (auto dot = key.find('.'); dot != std::string::npos; dot = key.find('.')) {
            at = &(*at)[key.substr(0, dot)];
            key = key.substr(dot + 1);
        }
        (*at)[key] = setting_json(s, v);
    }
}

json material_override_json(const Job::Source::MaterialOverride& mo) {
    namespace mp = material_properties;
    json o = json::object();
    if (mo.name) o["name"] = *mo.name;
    if (mo.index) o["index"] = *mo.index;
    for (const auto& [key, value] : mo.values) {
        const mp::Property* p = mp::find(key);
        if (!p) continue;
        if (p->type == mp::Type::Bool) o[key] = value[0] != 0.0f;
        else if (p->type == mp::Type::Choice) o[key] = mp::format(*p, value);
        else if (!std::isfinite(value[0])) continue;  // the default infinity (attenuationDistance) is no key
        else if (p->width == 1) o[key] = num(value[0]);
        else {
            json a = json::array();
            for (int i = 0; i < p->width; ++i) a.push_back(num(value[std::size_t(i)]));
            o[key] = a;
        }
    }
    return o;
}

json light_json(const LightInstance& l) {
    json o = json::object();
    float intensity = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
    glm::vec3 color = intensity > 0.0f ? l.radiance / intensity : glm::vec3(1.0f);
    o["type"] = light_type_name(l.type);
    if (color != glm::vec3(1.0f)) o["color"] = nums<3>(color);
    o["intensity"] = num(intensity);
    if (l.type != Light::Type::Directional) o["position"] = nums<3>(l.position);
    if (l.type != Light::Type::Point && l.type != Light::Type::Sphere) o["direction"] = nums<3>(l.direction);
    if ((l.type == Light::Type::Point || l.type == Light::Type::Spot) && l.range > 0.0f) o["range"] = num(l.range);
    if (l.type == Light::Type::Rect) {
        o["width"] = num(2.0f * glm::length(l.axis_u));
        o["height"] = num(2.0f * glm::length(l.axis_v));
    }
    if (l.type == Light::Type::Disk) o["radius"] = num(glm::length(l.axis_u));
    if (l.type == Light::Type::Sphere || l.type == Light::Type::Tube) o["radius"] = num(l.radius);
    if (l.type == Light::Type::Directional && l.radius > 0.0f) o["angularRadius"] = num(l.radius * 180.0f / 3.14159265358979f);
    if ((l.type == Light::Type::Point || l.type == Light::Type::Spot) && l.radius > 0.0f) o["radius"] = num(l.radius);
    if (l.type == Light::Type::Tube) o["length"] = num(2.0f * glm::length(l.axis_u));
    if (l.type == Light::Type::Spot) {
        o["innerConeAngle"] = num(l.inner_cone);
        o["outerConeAngle"] = num(l.outer_cone);
    }
    return o;
}

}  // namespace

json scene_document(const Job& job, const fs::path& base_dir, const std::optional<fs::path>& output,
                    SceneDocumentReport* report) {
    SceneDocumentReport local;
    SceneDocumentReport& rep = report ? *report : local;
    Writer w(base_dir, rep);
    json doc = json::object();
    doc["fresnel"] = kSceneFileVersion;
    auto model_path = [&](const std::string& p) { return p.empty() ? std::string("demo") : w.path(p); };

    // Models: one at the origin as "model" (a plain `render MODEL`), else the list.
    if (job.source.models.empty() && job.source.scene < 0) {
        doc["model"] = model_path(job.source.model);
    } else {
        std::vector<Job::Source::Model> models = job.source.models;
        if (models.empty()) {
            Job::Source::Model m;
            m.path = job.source.model;
            m.scene = job.source.scene;
            models.push_back(m);
        }
        json list = json::array();
        for (const auto& m : models) {
            json o = json::object();
            o["path"] = model_path(m.path);
            if (m.scene >= 0) o["scene"] = m.scene;
            if (!m.visible) o["visible"] = false;
            if (m.transform != glm::mat4(1.0f)) {
                json a = json::array();
                const float* f = glm::value_ptr(m.transform);  // column-major, as glTF
                for (int i = 0; i < 16; ++i) a.push_back(num(f[i]));
                o["matrix"] = a;
            }
            if (!m.materials.empty()) {
                json mats = json::array();
                for (const auto& mo : m.materials) mats.push_back(material_override_json(mo));
                o["materials"] = mats;
            }
            list.push_back(o);
        }
        doc["models"] = list;
    }
    // Camera: its type and the lookAt camera's structure; the settings below add the rest.
    const Job::Camera& c = job.camera;
    json cam = json::object();
    if (c.scene_camera) {
        cam["type"] = "model";
        if (c.scene_camera_model != 0) cam["model"] = c.scene_camera_model;
    } else if (c.look_at) {
        cam["type"] = "lookAt";
        cam["eye"] = nums<3>(c.look_at->eye);
        cam["target"] = nums<3>(c.look_at->target);
        cam["up"] = nums<3>(c.look_at->up);
    } else {
        cam["type"] = "orbit";
    }
    doc["camera"] = cam;

    // Lights: the job's extra lights (given, they replace the defaults, as the reader reads them).
    if (!job.lights.extra.empty()) {
        json lights = json::array();
        for (const auto& l : job.lights.extra) lights.push_back(light_json(l));
        doc["lights"] = lights;
    }

    // Environment and background: their object forms (a file relative to the scene file).
    using Kind = Job::Environment::Kind;
    const Job::Environment& e = job.environment;
    json env = json::object();
    switch (e.kind) {
        case Kind::Automatic: env["type"] = "automatic"; break;
        case Kind::File: env["type"] = "file"; env["file"] = w.path(e.path); break;
        case Kind::Color: env["type"] = "color"; env["color"] = nums<3>(e.color); break;
        case Kind::Studio: env["type"] = "studio"; break;
        case Kind::None: env["type"] = "none"; break;
    }
    doc["environment"] = env;
    using Mode = Job::Background::Mode;
    if (job.background.mode == Mode::Color)
        doc["background"] = json{{"type", "color"}, {"color", nums<3>(job.background.color)}};
    else
        doc["background"] = settings::get(job, "background");

    // Every other setting, through the registry.
    write_settings(doc, job, {"environment", "background"});
    if (output) doc["output"] = w.path(output->string());
    return doc;
}

std::string scene_text(const Job& job, const fs::path& base_dir, const std::optional<fs::path>& output,
                       SceneDocumentReport* report) {
    return scene_document(job, base_dir, output, report).dump(2) + "\n";
}

void save_scene_file(const fs::path& path, const Job& job, Diagnostics& diag, const std::optional<fs::path>& output) {
    const std::string name = path.string();
    SceneDocumentReport report;
    fs::path base = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::string text = scene_text(job, base, output, &report);
    for (const auto& p : report.outside)
        diag.warn(name, "", "names '" + p + "', outside the file's folder: read it with --allow-external-files");
    for (const auto& d : report.dropped) diag.warn(name, "", "a scene file holds no " + d + " (not written)");
    write_file_atomically(path, std::string_view(text));  // whole or absent; throws naming `path`
}

}  // namespace fresnel
