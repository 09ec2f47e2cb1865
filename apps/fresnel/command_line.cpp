#include "command_line.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "fresnel/render/renderer.h"

namespace fresnel::cli {
namespace {

// The shortest decimal form that reads back as the same float.
std::string num(float v) {
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}
std::string nums(std::initializer_list<float> v) {
    std::string s;
    for (float f : v) s += (s.empty() ? "" : ",") + num(f);
    return s;
}

}  // namespace

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
    const Job defaults;
    std::string line = "fresnel render";
    auto add = [&](const std::string& flag, const std::string& value = {}) {
        line += " " + flag;
        if (!value.empty()) line += " " + shell_quote(value);
    };
    if (!job.source.model.empty()) line += " " + shell_quote(job.source.model);
    add("-o", output);
    const Job::Output& out = job.output;
    if (out.width != defaults.output.width || out.height != defaults.output.height)
        add("--size", std::to_string(out.width) + "x" + std::to_string(out.height));
    const Job::Camera& cam = job.camera;
    if (cam.scene_camera) {
        add("--camera", std::to_string(*cam.scene_camera));
    } else {
        add("--yaw", num(cam.yaw_deg));
        add("--pitch", num(cam.pitch_deg));
        if (cam.distance_k) add("--distance", num(*cam.distance_k));
        if (cam.yfov_deg != defaults.camera.yfov_deg) add("--fov", num(cam.yfov_deg));
        if (cam.target) add("--target", nums({cam.target->x, cam.target->y, cam.target->z}));
    }
    if (job.source.scene >= 0) add("--scene", std::to_string(job.source.scene));
    if (out.tone_mapper != defaults.output.tone_mapper) add("--tonemap", std::string(tone_mapper_name(out.tone_mapper)));
    if (out.exposure_ev != defaults.output.exposure_ev) add("--exposure", num(out.exposure_ev));
    if (out.encoding != defaults.output.encoding) add("--encoding", out.encoding == Encoding::Gamma22 ? "gamma2.2" : "srgb");
    using Mode = Job::Background::Mode;
    const Job::Background& bg = job.background;
    switch (bg.mode) {
        case Mode::Automatic: break;
        case Mode::Environment: add("--background", "env"); break;
        case Mode::Blurred: add("--background", "blur"); break;
        case Mode::Transparent: add("--background", "transparent"); break;
        case Mode::Color: add("--background", nums({bg.color.x, bg.color.y, bg.color.z})); break;
    }
    const Job::Environment& env = job.environment;
    using Kind = Job::Environment::Kind;
    switch (env.kind) {
        case Kind::Automatic: break;
        case Kind::File: add("--env", env.path); break;
        case Kind::Color: add("--env", "color:" + nums({env.color.x, env.color.y, env.color.z})); break;
        case Kind::Studio: add("--env", "studio"); break;
        case Kind::None: add("--no-ibl"); break;
    }
    if (env.rotation_deg != defaults.environment.rotation_deg) add("--env-rotation", num(env.rotation_deg));
    if (env.intensity != defaults.environment.intensity) add("--env-intensity", num(env.intensity));
    if (env.bake_samples != defaults.environment.bake_samples) add("--env-samples", std::to_string(env.bake_samples));
    if (env.bake_size != defaults.environment.bake_size) add("--env-size", std::to_string(env.bake_size));
    if (!env.use_cache) add("--no-cache");
    if (!out.energy_compensation) add("--no-energy-compensation");
    if (!out.brdf.is_default()) add("--brdf", brdf::to_string(out.brdf));
    // Extra lights, as --light writes them (a range is not part of that syntax).
    for (const LightInstance& l : job.lights.extra) {
        float lum = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
        glm::vec3 color = lum > 0 ? l.radiance / lum : glm::vec3(1.0f);
        std::string rgb = color == glm::vec3(1.0f) ? "" : "," + nums({color.x, color.y, color.z});
        const float deg = 180.0f / 3.14159265358979f;
        glm::vec3 from = -l.direction;
        float el = std::asin(std::clamp(from.y, -1.0f, 1.0f)) * deg, az = std::atan2(from.x, from.z) * deg;
        if (l.type == Light::Type::Point) {
            add("--light", "point:" + nums({l.position.x, l.position.y, l.position.z, lum}) + rgb);
        } else if (l.type == Light::Type::Spot) {
            add("--light", "spot:" + nums({l.position.x, l.position.y, l.position.z, az, el, lum, l.inner_cone * deg,
                                           l.outer_cone * deg}) + rgb);
        } else {
            add("--light", "dir:" + nums({az, el, lum}) + rgb);
        }
    }
    if (!job.lights.scene_lights) add("--no-scene-lights");
    if (out.msaa != defaults.output.msaa) add("--msaa", std::to_string(out.msaa));
    if (out.anisotropy != defaults.output.anisotropy) add("--anisotropy", num(out.anisotropy));
    if (out.debug != DebugChannel::None) {
        for (const std::string& name : debug_channel_names())
            if (parse_debug_channel(name) == out.debug) add("--debug", name);
    }
    if (job.source.allow_external_files) add("--allow-external-files");
    if (job.source.pose_skins) add("--pose-skins");
    if (job.source.obj_normals != Job::Source::ObjNormals::Auto)
        add("--obj-normals", job.source.obj_normals == Job::Source::ObjNormals::Smooth ? "smooth" : "groups");
    return line;
}

}  // namespace fresnel::cli
