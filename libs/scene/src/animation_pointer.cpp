// KHR_animation_pointer: the material, light and camera properties an animation channel can
// name by a JSON pointer (the list is in fresnel/scene/pose.h), resolved against the scene.
//
// One resolver serves both questions: "how many floats is this property?" (the loader's
// check, asked on a copy so that the scene is untouched) and "write these floats there"
// (animate). A material block the file does not have is added with the extension's
// defaults, which the specifications choose so that they change nothing until animated.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <vector>

#include "fresnel/material/properties.h"
#include "fresnel/scene/pose.h"

namespace fresnel {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kHalfPi = 1.57079633f;

// The floats a pointer names, and the range its values are kept in.
struct Prop {
    float* data = nullptr;
    int width = 0;
    float lo = -kInf, hi = kInf;
    TextureSlot* transform_of = nullptr;  // a KHR_texture_transform value: refresh the slot's matrix
    std::string why;                      // width 0: why nothing is animated
};

Prop none(std::string why) {
    Prop p;
    p.why = std::move(why);
    return p;
}
Prop prop(float* data, int width, float lo = -kInf, float hi = kInf) {
    Prop p;
    p.data = data;
    p.width = width;
    p.lo = lo;
    p.hi = hi;
    return p;
}

// "/a/b/c" -> {"a", "b", "c"}; false for pointers that are not absolute or that use JSON
// pointer escapes (no property fresnel animates has '~' or '/' in its name).
bool split(std::string_view pointer, std::vector<std::string_view>& out) {
    if (pointer.empty() || pointer.front() != '/' || pointer.find('~') != std::string_view::npos) return false;
    std::size_t at = 1;
    while (true) {
        std::size_t next = pointer.find('/', at);
        std::string_view token = pointer.substr(at, next == std::string_view::npos ? std::string_view::npos : next - at);
        if (token.empty()) return false;
        out.push_back(token);
        if (next == std::string_view::npos) return true;
        at = next + 1;
    }
}

// A decimal array index below `count` (no sign, no leading zeros: JSON pointer's rule).
bool parse_index(std::string_view token, std::size_t count, std::size_t& out) {
    if (token.empty() || token.size() > 9 || (token.size() > 1 && token[0] == '0')) return false;
    unsigned long long v = 0;
    auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec != std::errc() || end != token.data() + token.size() || v >= count) return false;
    out = std::size_t(v);
    return true;
}

std::string join(std::span<const std::string_view> tokens) {
    std::string s;
    for (auto t : tokens) {
        if (!s.empty()) s += '/';
        s += t;
    }
    return s;
}

// A material property by its glTF path: the material property registry
// (fresnel/material/properties.h) holds every path, range and whether it may be animated.
Prop material_prop(Material& m, const std::string& path) {
    namespace mp = material_properties;
    // KHR_texture_transform of any texture.
    const std::string tt = "/extensions/KHR_texture_transform/";
    if (std::size_t at = path.find(tt); at != std::string::npos) {
        const mp::Texture* texture = mp::find_texture_path(path.substr(0, at));
        if (!texture) return none("no texture '" + path.substr(0, at) + "' in a material");
        TextureSlot* slot = texture->slot(m);
        std::string what = path.substr(at + tt.size());
        if (!slot->has_transform) slot->set_transform(TextureTransform{});
        Prop p;
        if (what == "offset") p = prop(&slot->transform_params.offset.x, 2);
        else if (what == "rotation") p = prop(&slot->transform_params.rotation, 1);
        else if (what == "scale") p = prop(&slot->transform_params.scale.x, 2);
        else return none("KHR_texture_transform has no animatable '" + what + "'");
        p.transform_of = slot;
        return p;
    }
    const mp::Property* p = mp::find_path(path);
    if (!p || !p->animatable || !p->data) return none("'" + path + "' is not a material property fresnel animates");
    return prop(p->data(m), p->width, p->min, p->max);
}

Prop light_prop(Light& l, const std::string& path) {
    if (path == "color") return prop(&l.color.x, 3, 0);
    if (path == "intensity") return prop(&l.intensity, 1, 0);
    if (path == "range") {
        if (l.type == Light::Type::Directional) return none("a directional light has no range");
        return prop(&l.range, 1, 0);
    }
    if (path == "spot/innerConeAngle" || path == "spot/outerConeAngle") {
        if (l.type != Light::Type::Spot) return none("only spot lights have cone angles");
        return prop(path == "spot/innerConeAngle" ? &l.inner_cone_angle : &l.outer_cone_angle, 1, 0, kHalfPi);
    }
    return none("'" + path + "' is not a light property fresnel animates");
}

Prop camera_prop(Camera& c, const std::string& path) {
    bool perspective = c.type == Camera::Type::Perspective;
    std::string type = perspective ? "perspective/" : "orthographic/";
    if (path.rfind(type, 0) != 0) return none("camera is not " + path.substr(0, path.find('/')));
    std::string what = path.substr(type.size());
    if (what == "znear") return prop(&c.znear, 1, perspective ? 1e-6f : 0.0f);
    if (what == "zfar") {
        if (!c.zfar) c.zfar = 1e30f;  // infinite: an animated far plane starts there
        return prop(&*c.zfar, 1, 1e-6f);
    }
    if (perspective && what == "yfov") return prop(&c.yfov, 1, 1e-4f, 3.1f);
    if (perspective && what == "aspectRatio") {
        if (!c.aspect_ratio) c.aspect_ratio = 1.0f;
        return prop(&*c.aspect_ratio, 1, 1e-6f);
    }
    if (!perspective && (what == "xmag" || what == "ymag")) return prop(what == "xmag" ? &c.xmag : &c.ymag, 1);
    return none("'" + path + "' is not a camera property fresnel animates");
}

// The property `pointer` names in `scene` (which may gain a default material block).
Prop resolve(Scene& scene, std::string_view pointer) {
    std::vector<std::string_view> t;
    if (!split(pointer, t)) return none("not an absolute JSON pointer without escapes");
    std::size_t i = 0;
    if (t[0] == "materials" && t.size() >= 3) {
        if (!parse_index(t[1], scene.materials.size(), i)) return none("no material " + std::string(t[1]));
        return material_prop(scene.materials[i], join(std::span(t).subspan(2)));
    }
    if (t[0] == "extensions" && t.size() >= 5 && t[1] == "KHR_lights_punctual" && t[2] == "lights") {
        if (!parse_index(t[3], scene.lights.size(), i)) return none("no light " + std::string(t[3]));
        return light_prop(scene.lights[i], join(std::span(t).subspan(4)));
    }
    if (t[0] == "cameras" && t.size() >= 4) {
        if (!parse_index(t[1], scene.cameras.size(), i)) return none("no camera " + std::string(t[1]));
        return camera_prop(scene.cameras[i], join(std::span(t).subspan(2)));
    }
    if (t[0] == "nodes") return none("node properties other than translation, rotation, scale and weights are not animated");
    return none("fresnel animates material, light and camera properties, not '" + std::string(t[0]) + "'");
}

}  // namespace

int animation_pointer_width(const Scene& scene, std::string_view pointer, std::string* why) {
    // Asked on a copy of the one element concerned, so that `scene` stays as it is.
    std::vector<std::string_view> t;
    Scene probe;
    if (split(pointer, t) && t.size() >= 2) {
        std::size_t i = 0;
        if (t[0] == "materials" && parse_index(t[1], scene.materials.size(), i)) {
            probe.materials.assign(i + 1, Material{});
            probe.materials[i] = scene.materials[i];
        } else if (t[0] == "cameras" && parse_index(t[1], scene.cameras.size(), i)) {
            probe.cameras.assign(i + 1, Camera{});
            probe.cameras[i] = scene.cameras[i];
        } else if (t[0] == "extensions" && t.size() >= 4 && parse_index(t[3], scene.lights.size(), i)) {
            probe.lights.assign(i + 1, Light{});
            probe.lights[i] = scene.lights[i];
        }
    }
    Prop p = resolve(probe, pointer);
    if (p.width == 0 && why) *why = p.why;
    return p.width;
}

bool write_animation_pointer(Scene& scene, std::string_view pointer, std::span<const float> values) {
    Prop p = resolve(scene, pointer);
    if (p.width == 0 || values.size() < std::size_t(p.width)) return false;
    for (int k = 0; k < p.width; ++k) {
        float v = values[std::size_t(k)];
        if (std::isfinite(v)) p.data[k] = std::clamp(v, p.lo, p.hi);
    }
    if (p.transform_of) p.transform_of->set_transform(p.transform_of->transform_params);
    // Keep the relations the loader checks: inner < outer cone, znear < zfar.
    for (auto& l : scene.lights)
        if (l.type == Light::Type::Spot && l.inner_cone_angle >= l.outer_cone_angle)
            l.inner_cone_angle = std::max(0.0f, l.outer_cone_angle * 0.999f);
    for (auto& c : scene.cameras)
        if (c.zfar && !(*c.zfar > c.znear)) *c.zfar = c.znear * 1.001f + 1e-6f;
    return true;
}

}  // namespace fresnel
