// Wavefront MTL parsing: the classic keys (Paul Bourke's "MTL material format"), the PBR
// extension (Exocortex / Blender: Pr Pm Ps Pc Pcr aniso anisor, map_Pr map_Pm map_Ps, norm)
// and texture options (-o -s -t -bm -clamp -imfchan -blendu -blendv -boost -cc -mm -texres
// -type). Values are checked as read: a non-finite or unreadable number is a warning and
// the key keeps its default; unknown keys are warnings. Errors (fresnel::Error) are kept
// for files that cannot be materials at all (a key before any newmtl is only a warning).
#include <algorithm>
#include <cmath>
#include <map>

#include "fresnel/scene/obj_loader.h"
#include "obj_text.h"

namespace fresnel {
using namespace obj;

namespace {

class MtlParser {
public:
    MtlParser(std::string name, Diagnostics& diag, std::size_t max_materials)
        : name_(std::move(name)), warnings_(name_, diag, "lines"), max_materials_(max_materials) {}

    std::vector<MtlMaterialSource> parse(std::string_view text) {
        LineReader lines(text);
        std::string_view line;
        std::vector<std::string_view> tok;
        while (lines.next(line, line_)) {
            tokenize(line, tok);
            if (tok.empty()) continue;
            std::string key = lower(tok[0]);
            if (key == "newmtl") {
                if (out_.size() >= max_materials_)
                    throw Error(name_, where(), "more than " + std::to_string(max_materials_) + " materials");
                MtlMaterialSource m;
                m.name = std::string(rest_after(line, tok[0]));
                m.line = line_;
                out_.push_back(std::move(m));
                continue;
            }
            if (out_.empty()) {
                warn_once("key before newmtl", "'" + printable(tok[0]) + "' before any newmtl; ignored");
                continue;
            }
            statement(key, line, tok);
        }
        warnings_.flush();
        return std::move(out_);
    }

private:
    std::string name_;
    LineWarnings warnings_;
    std::size_t max_materials_;
    int line_ = 0;
    std::vector<MtlMaterialSource> out_;
    std::string where() const { return "line " + std::to_string(line_); }
    // At most 64 warnings of their own per file; those of a kind that may repeat on every line
    // collapse into one, at the first line (LineWarnings).
    void warn(const std::string& message) { warnings_.warn(line_, message); }
    void warn_once(const std::string& kind, const std::string& message) { warnings_.once(line_, kind, message); }

    std::optional<float> number(std::string_view s, const std::string& what) {
        bool partial = false;
        auto v = parse_number(s, partial);
        if (!v) {
            warn("'" + printable(s) + "' is not a number (" + what + "); ignored");
            return std::nullopt;
        }
        if (!std::isfinite(*v) || std::fabs(*v) > 3.0e38) {
            warn(what + " is not finite; ignored");
            return std::nullopt;
        }
        if (partial) warn_once("partial number", "'" + printable(s) + "' is not a number; read as its numeric prefix");
        return float(*v);
    }

    // Ka/Kd/Ks/Ke/Tf: r [g b]; "spectral" and "xyz" forms are not supported.
    void color(const std::vector<std::string_view>& tok, glm::vec3& out) {
        std::string what = std::string(tok[0]);
        if (tok.size() < 2) return warn(what + " without values; ignored");
        std::string form = lower(tok[1]);
        if (form == "spectral" || form == "xyz")
            return warn(what + " " + form + " is not supported; ignored");
        glm::vec3 c;
        auto r = number(tok[1], what);
        if (!r) return;
        c = glm::vec3(*r);
        if (tok.size() >= 4) {
            auto g = number(tok[2], what), b = number(tok[3], what);
            if (!g || !b) return;
            c.y = *g;
            c.z = *b;
        } else if (tok.size() == 3) {
            return warn(what + " needs 1 or 3 values, not 2; ignored");
        }
        out = c;
    }

    void scalar(const std::vector<std::string_view>& tok, float& out) {
        if (tok.size() < 2) return warn(std::string(tok[0]) + " without a value; ignored");
        if (auto v = number(tok.back(), std::string(tok[0]))) out = *v;
    }
    void scalar(const std::vector<std::string_view>& tok, std::optional<float>& out) {
        float v = 0.0f;
        bool set = false;
        if (tok.size() >= 2)
            if (auto n = number(tok.back(), std::string(tok[0]))) v = *n, set = true;
        if (!set) return warn(std::string(tok[0]) + " without a usable value; ignored");
        out = v;
    }

    // map_X [options] FILE: options first, the rest of the line is the file name (which
    // may hold blanks).
    void texture(std::string_view line, const std::vector<std::string_view>& tok, MtlTextureRef& ref, MtlMap& map) {
        MtlTextureRef r;
        r.line = line_;
        glm::vec3 offset{0.0f}, scale{1.0f};
        std::size_t i = 1;
        auto numbers = [&](std::size_t max, glm::vec3& out) {
            std::size_t k = 0;
            while (k < max && i < tok.size()) {
                bool partial = false;
                auto v = parse_number(tok[i], partial);
                if (!v || partial) break;
                if (std::isfinite(*v) && std::fabs(*v) < 1e30) out[int(k)] = float(*v);
                else warn("texture option value is not finite; ignored");
                ++k;
                ++i;
            }
            return k;
        };
        while (i < tok.size() && tok[i].size() > 1 && tok[i][0] == '-') {
            std::string opt = lower(tok[i]);
            ++i;
            glm::vec3 scratch{0.0f};
            if (opt == "-o") {
                if (numbers(3, offset) == 0) warn("-o without values");
                r.has_transform = true;
            } else if (opt == "-s") {
                if (numbers(3, scale) == 0) warn("-s without values");
                r.has_transform = true;
            } else if (opt == "-t") {
                numbers(3, scratch);
                warn_once("-t", "texture option -t (turbulence) is not supported; ignored");
            } else if (opt == "-bm") {
                glm::vec3 bm{1.0f};
                if (numbers(1, bm) == 1) map.bump_multiplier = bm.x;
                else warn("-bm without a value");
            } else if (opt == "-mm") {
                numbers(2, scratch);
                warn_once("-mm", "texture option -mm (range) is not supported; ignored");
            } else if (opt == "-boost" || opt == "-texres") {
                numbers(1, scratch);
            } else if (opt == "-clamp" || opt == "-blendu" || opt == "-blendv" || opt == "-cc") {
                if (i < tok.size()) {
                    std::string v = lower(tok[i]);
                    if (v == "on" || v == "off") {
                        if (opt == "-clamp") r.clamp = v == "on";
                        ++i;
                    }
                }
            } else if (opt == "-imfchan") {
                if (i < tok.size()) {
                    std::string c = lower(tok[i]);
                    ++i;
                    if (c == "r") map.channel = MtlChannel::R;
                    else if (c == "g") map.channel = MtlChannel::G;
                    else if (c == "b") map.channel = MtlChannel::B;
                    else if (c == "m") map.channel = MtlChannel::Matte;
                    else if (c == "l") map.channel = MtlChannel::Luminance;
                    else warn("-imfchan '" + printable(c) + "' is not r, g, b, m or l; using r");
                }
            } else if (opt == "-type") {
                if (i < tok.size()) ++i;
            } else {
                if (unknown_keys_++ < 16) warn_once("option " + opt, "unknown texture option '" + printable(opt) + "'; ignored");
                else warn_once("option more", "more unknown texture options; ignored");
            }
        }
        if (i >= tok.size()) return warn(std::string(tok[0]) + " without a file name; ignored");
        // The file name: from token i to the end of the line, as written.
        std::string_view t = trim(line);
        std::size_t at = std::size_t(tok[i].data() - line.data()) - std::size_t(t.data() - line.data());
        std::string_view file = trim(t.substr(std::min(at, t.size())));
        r.path = std::string(file);
        for (char& c : r.path)
            if (c == '\\') c = '/';
        if (r.has_transform) {
            // MTL maps in OBJ's UV space (v up): u' = s u + o. fresnel's UVs are glTF's
            // (t = 1 - v), so t' = s t + (1 - s - o) for the same texel.
            TextureTransform tt;
            tt.scale = {scale.x, scale.y};
            tt.offset = {offset.x, 1.0f - scale.y - offset.y};
            r.transform = tt;
        }
        ref = std::move(r);
    }

    void statement(const std::string& key, std::string_view line, const std::vector<std::string_view>& tok) {
        MtlMaterialSource& m = out_.back();
        PhongExt& p = m.phong;
        if (key == "ka") color(tok, p.ambient);
        else if (key == "kd") color(tok, p.diffuse);
        else if (key == "ks") color(tok, p.specular);
        else if (key == "ke") color(tok, p.emission);
        else if (key == "tf") color(tok, p.transmission_filter);
        else if (key == "ns") scalar(tok, p.shininess);
        else if (key == "ni") scalar(tok, p.optical_density);
        else if (key == "d") {
            // "d -halo 0.5": the value is the last token.
            float d = p.dissolve;
            scalar(tok, d);
            p.dissolve = d;
            has_d_.resize(out_.size(), false);
            has_d_.back() = true;
        } else if (key == "tr") {
            has_d_.resize(out_.size(), false);
            float tr = 1.0f - p.dissolve;
            scalar(tok, tr);
            if (!has_d_.back()) p.dissolve = 1.0f - tr;  // d wins where both are written
        } else if (key == "illum") {
            if (tok.size() < 2) return warn("illum without a value; ignored");
            auto v = parse_integer(tok[1]);
            if (!v || *v < 0 || *v > 10) return warn("illum '" + printable(tok[1]) + "' is not 0..10; ignored");
            p.illum = int(*v);
        } else if (key == "pr") scalar(tok, p.roughness);
        else if (key == "pm") scalar(tok, p.metallic);
        else if (key == "ps") scalar(tok, p.sheen);
        else if (key == "pc") scalar(tok, p.clearcoat);
        else if (key == "pcr") scalar(tok, p.clearcoat_roughness);
        else if (key == "aniso") scalar(tok, p.anisotropy);
        else if (key == "anisor") scalar(tok, p.anisotropy_rotation);
        else if (key == "map_ka") texture(line, tok, m.ambient, p.ambient_map);
        else if (key == "map_kd") texture(line, tok, m.diffuse, p.diffuse_map);
        else if (key == "map_ks") texture(line, tok, m.specular, p.specular_map);
        else if (key == "map_ns") texture(line, tok, m.shininess, p.shininess_map);
        else if (key == "map_d") texture(line, tok, m.dissolve, p.dissolve_map);
        else if (key == "map_ke") texture(line, tok, m.emission, p.emission_map);
        else if (key == "map_bump" || key == "bump") texture(line, tok, m.bump, p.bump_map);
        else if (key == "norm" || key == "map_kn") texture(line, tok, m.normal, p.normal_map);
        else if (key == "map_pr") texture(line, tok, m.roughness, p.roughness_map);
        else if (key == "map_pm") texture(line, tok, m.metallic, p.metallic_map);
        else if (key == "map_ps") texture(line, tok, m.sheen, p.sheen_map);
        else if (key == "sharpness" || key == "disp" || key == "decal" || key == "refl" || key == "map_aat" ||
                 key == "map_tr" || key == "map_pc" || key == "map_pcr" || key == "map_ka" || key == "tw")
            warn_once("key " + key, "'" + std::string(tok[0]) + "' is not supported; ignored");
        else if (unknown_keys_++ < 16)
            warn_once("key " + key, "unknown key '" + printable(tok[0]) + "'; ignored");
        else
            warn_once("key more", "more unknown keys; ignored");
    }
    std::vector<bool> has_d_;
    std::size_t unknown_keys_ = 0;
};

}  // namespace

std::vector<MtlMaterialSource> parse_mtl(std::string_view text, const std::string& name, Diagnostics& diagnostics,
                                         std::size_t max_materials) {
    return MtlParser(name, diagnostics, max_materials).parse(text);
}

}  // namespace fresnel
