#include "fresnel/material/brdf_model.h"

#include <algorithm>

namespace fresnel::brdf {

namespace {

const std::vector<std::string> kD = {"ggx", "beckmann", "blinn-phong"};
const std::vector<std::string> kG = {"smith-height-correlated", "smith-separable", "schlick-ggx", "cook-torrance",
                                     "kelemen"};
const std::vector<std::string> kF = {"schlick", "exact-dielectric", "spherical-gaussian"};
const std::vector<std::string> kDiffuse = {"lambert", "burley", "oren-nayar"};
const std::vector<std::string> kNone;

std::string list(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : "|") + n;
    return s;
}

}  // namespace

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
        std::string key(item.substr(0, eq)), value(item.substr(eq + 1));
        const auto& names = brdf_model_names(key);
        if (names.empty()) return fail("unknown key '" + key + "' (D, G, F or diffuse)");
        auto it = std::find(names.begin(), names.end(), value);
        if (it == names.end()) return fail("unknown " + key + " '" + value + "' (" + list(names) + ")");
        int index = int(it - names.begin());
        if (key == "D") m.d = Distribution(index);
        else if (key == "G") m.g = Geometry(index);
        else if (key == "F") m.f = Fresnel(index);
        else m.diffuse = Diffuse(index);
        if (comma == std::string_view::npos) break;
        at = comma + 1;
    }
    return m;
}

std::string to_string(const BrdfModel& m) {
    return "D=" + kD[std::size_t(m.d)] + ",G=" + kG[std::size_t(m.g)] + ",F=" + kF[std::size_t(m.f)] +
           ",diffuse=" + kDiffuse[std::size_t(m.diffuse)];
}

std::vector<std::string> brdf_model_defines(const BrdfModel& m) {
    std::vector<std::string> out;
    if (m.d != Distribution::Ggx) out.push_back("BRDF_D " + std::to_string(int(m.d)));
    if (m.g != Geometry::SmithHeightCorrelated) out.push_back("BRDF_G " + std::to_string(int(m.g)));
    if (m.f != Fresnel::Schlick) out.push_back("BRDF_F " + std::to_string(int(m.f)));
    if (m.diffuse != Diffuse::Lambert) out.push_back("BRDF_DIFFUSE " + std::to_string(int(m.diffuse)));
    return out;
}

}  // namespace fresnel::brdf
