#include "fresnel/material/brdf_model.h"

#include <algorithm>
#include <cstdio>

namespace fresnel::brdf {

namespace {

const std::vector<std::string> kD = {"ggx", "beckmann", "blinn-phong"};
const std::vector<std::string> kG = {"smith-height-correlated", "smith-separable", "schlick-ggx", "cook-torrance",
                                     "kelemen"};
const std::vector<std::string> kF = {"schlick", "exact-dielectric", "spherical-gaussian", "exact"};
const std::vector<std::string> kConductor = {"base-color", "iron",   "gold",     "aluminium",
                                             "chromium",   "copper", "lead",     "platinum", "silver"};
const std::vector<std::string> kDiffuse = {"lambert", "burley", "oren-nayar"};
const std::vector<std::string> kNone;

std::string list(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : "|") + n;
    return s;
}

// A float that GLSL and C++ read back as the same float: 9 significant digits.
std::string float_literal(float x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(x));
    std::string s(buf);
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

std::string vec3_literal(glm::vec3 v) {
    return "vec3(" + float_literal(v.x) + ", " + float_literal(v.y) + ", " + float_literal(v.z) + ")";
}

}  // namespace

const std::vector<std::string>& brdf_conductor_names() { return kConductor; }

const std::vector<std::string>& brdf_model_names(std::string_view key) {
    if (key == "D") return kD;
    if (key == "G") return kG;
    if (key == "F") return kF;
    if (key == "diffuse") return kDiffuse;
    return kNone;
}

std::optional<BrdfModel> parse_brdf_model(std::string_view text, std::string* error) {
    BrdfModel m;
    auto fail = [&](std::string why) -> std::optional<BrdfModel> {
        if (error) *error = std::move(why);
        return std::nullopt;
    };
    if (text.empty() || text == "default") return m;
    std::size_t at = 0;
    while (at <= text.size()) {
        std::size_t comma = text.find(',', at);
        std::string_view item = text.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at);
        std::size_t eq = item.find('=');
        if (eq == std::string_view::npos) return fail("'" + std::string(item) + "' is not KEY=VALUE (keys D, G, F, diffuse)");
        std::string key(item.substr(0, eq)), value(item.substr(eq + 1)), metal;
        if (std::size_t colon = value.find(':'); colon != std::string::npos) {  // F=exact:gold
            metal = value.substr(colon + 1);
            value.resize(colon);
            if (key != "F" || value != "exact")
                return fail("'" + std::string(item) + "': only F=exact takes a metal (F=exact:" + list(kConductor) + ")");
            auto c = std::find(kConductor.begin(), kConductor.end(), metal);
            if (c == kConductor.end())
                return fail("unknown metal '" + metal + "' (F=exact:" + list(kConductor) + ")");
            m.conductor = Conductor(c - kConductor.begin());
        }
        const auto& names = brdf_model_names(key);
        if (names.empty()) return fail("unknown key '" + key + "' (D, G, F or diffuse)");
        auto it = std::find(names.begin(), names.end(), value);
        if (it == names.end()) return fail("unknown " + key + " '" + value + "' (" + list(names) + ")");
        int index = int(it - names.begin());
        if (key == "D") m.d = Distribution(index);
        else if (key == "G") m.g = Geometry(index);
        else if (key == "F") {
            m.f = Fresnel(index);
            if (metal.empty()) m.conductor = Conductor::BaseColor;  // a later F= replaces an earlier F=exact:gold
        }
        else m.diffuse = Diffuse(index);
        if (comma == std::string_view::npos) break;
        at = comma + 1;
    }
    return m;
}

std::string to_string(const BrdfModel& m) {
    std::string f = kF[std::size_t(m.f)];
    if (m.f == Fresnel::Exact && m.conductor != Conductor::BaseColor) f += ":" + kConductor[std::size_t(m.conductor)];
    return "D=" + kD[std::size_t(m.d)] + ",G=" + kG[std::size_t(m.g)] + ",F=" + f + ",diffuse=" +
           kDiffuse[std::size_t(m.diffuse)];
}

std::vector<std::string> brdf_model_defines(const BrdfModel& m) {
    std::vector<std::string> out;
    if (m.d != Distribution::Ggx) out.push_back("BRDF_D " + std::to_string(int(m.d)));
    if (m.g != Geometry::SmithHeightCorrelated) out.push_back("BRDF_G " + std::to_string(int(m.g)));
    if (m.f != Fresnel::Schlick) out.push_back("BRDF_F " + std::to_string(int(m.f)));
    if (m.f == Fresnel::Exact && m.conductor != Conductor::BaseColor) {
        ComplexIor ior = measured_conductor(m.conductor);
        out.push_back("BRDF_CONDUCTOR_N " + vec3_literal(ior.n));
        out.push_back("BRDF_CONDUCTOR_K " + vec3_literal(ior.k));
    }
    if (m.diffuse != Diffuse::Lambert) out.push_back("BRDF_DIFFUSE " + std::to_string(int(m.diffuse)));
    return out;
}

}  // namespace fresnel::brdf
