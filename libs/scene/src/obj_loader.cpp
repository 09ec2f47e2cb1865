// Wavefront OBJ loader. Our own parser rather than tinyobjloader 2.0.0rc10 (Debian's):
// that library opens files itself (mtllib joined to the base folder with no policy, so
// "../" and absolute paths are read), has no size or count limits, reports problems as
// free text without the file (and several without a line), resolves no texture paths,
// fans or projects polygons onto an axis plane instead of their own plane (wrong for
// concave polygons unless the optional mapbox earcut header, which Debian lacks, is
// present), and gives no way to split smoothing-group normals into a fresnel::Primitive.
//
// Two passes: parse() reads the file into flat arrays (positions, texture coordinates,
// normals, faces as corner lists with their object, material and smoothing group), checking
// every index as it is read; build() then makes one primitive per (object, material, kind),
// triangulating polygons and generating missing normals.
// Long (~950 lines): one format's whole reader (statements, polygons, smoothing groups,
// limits and error places) kept together; MTL is mtl_parser.cpp.
#include "fresnel/scene/obj_loader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "fresnel/core/parallel.h"
#include "fresnel/material/phong.h"
#include "fresnel/scene/mesh_ops.h"
#include "obj_text.h"
#include "uri_policy.h"

namespace fresnel {
namespace fs = std::filesystem;
using namespace obj;

bool is_obj_path(const fs::path& path) { return lower(path.extension().string()) == ".obj"; }

namespace {

enum class Kind : std::uint8_t { Face, Line, Point };

struct Corner {
    std::uint32_t v = 0;
    std::int32_t vt = -1, vn = -1;  // -1: absent
};

struct Face {
    std::uint32_t first = 0, count = 0;  // corners[first .. first + count)
    std::uint32_t smoothing = 0;         // 0: off
    int material = -1;                   // index into the loader's material list; -1: default
    int mesh = 0;
    int line = 0;
    Kind kind = Kind::Face;
};

struct Key {
    std::uint32_t v;
    std::int32_t vt;
    std::int64_t n;  // >= 0: vn index; else a generated-normal id (see build)
    bool operator==(const Key& o) const { return v == o.v && vt == o.vt && n == o.n; }
};
struct KeyHash {
    std::size_t operator()(const Key& k) const {
        std::uint64_t h = k.v * 0x9E3779B97F4A7C15ull;
        h ^= std::uint64_t(std::uint32_t(k.vt)) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= std::uint64_t(k.n) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return std::size_t(h);
    }
};

struct PosGroupHash {
    std::size_t operator()(const std::pair<std::uint32_t, std::uint32_t>& k) const {
        return std::size_t((std::uint64_t(k.first) << 32 | k.second) * 0x9E3779B97F4A7C15ull);
    }
};

// Newell's normal of a polygon: its vector area times two, so longer = larger; exact for
// planar polygons and a good average plane for the others.
glm::dvec3 newell(const std::vector<glm::dvec3>& p) {
    glm::dvec3 n(0.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec3& a = p[i];
        const glm::dvec3& b = p[(i + 1) % p.size()];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    return n;
}

// Whether a polygon given in 2D, counter-clockwise, is convex (every turn left or straight)
// and turns once around (a star pentagon turns left everywhere too, twice around).
bool convex_polygon(const std::vector<glm::dvec2>& pts) {
    const std::size_t n = pts.size();
    if (n < 3) return false;
    glm::dvec2 lo = pts[0], hi = pts[0];
    for (const auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double extent = std::max(hi.x - lo.x, hi.y - lo.y), eps = extent * extent * 1e-12;
    double turning = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 u = pts[i] - pts[(i + n - 1) % n], v = pts[(i + 1) % n] - pts[i];
        const double c = u.x * v.y - u.y * v.x;
        if (c < -eps) return false;
        if (glm::length(u) > 0 && glm::length(v) > 0) turning += std::atan2(c, glm::dot(u, v));
    }
    return turning < 2.0 * 3.14159265358979 * 1.5;  // once around (2 pi), not twice (4 pi)
}

// Ear clipping of a simple polygon given in 2D, counter-clockwise. Writes triangles as
// local index triples. `budget` counts vertex tests; returns false (output unchanged) when
// it runs out. Self-touching polygons (repeated vertices) and collinear runs are handled by
// clipping a convex or flat vertex when no proper ear exists, so it always terminates.
bool ear_clip(const std::vector<glm::dvec2>& pts, std::vector<std::uint32_t>& out, std::size_t& budget) {
    const std::size_t n = pts.size();
    if (n < 3) return true;
    std::vector<std::uint32_t> prev(n), next(n);
    for (std::size_t i = 0; i < n; ++i) {
        prev[i] = std::uint32_t((i + n - 1) % n);
        next[i] = std::uint32_t((i + 1) % n);
    }
    // Scale for the "flat" tolerance: the bounding box.
    glm::dvec2 lo = pts[0], hi = pts[0];
    for (const auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
    double extent = std::max(hi.x - lo.x, hi.y - lo.y);
    double eps = extent * extent * 1e-12;
    auto cross = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        glm::dvec2 u = pts[b] - pts[a], v = pts[c] - pts[b];
        return u.x * v.y - u.y * v.x;
    };
    auto inside = [&](const glm::dvec2& p, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        auto side = [](const glm::dvec2& o, const glm::dvec2& d, const glm::dvec2& q) {
            return (d.x - o.x) * (q.y - o.y) - (d.y - o.y) * (q.x - o.x);
        };
        return side(pts[a], pts[b], p) >= 0 && side(pts[b], pts[c], p) >= 0 && side(pts[c], pts[a], p) >= 0;
    };
    std::vector<std::uint32_t> tris;
    tris.reserve((n - 2) * 3);
    std::size_t remaining = n;
    std::uint32_t i = 0;
    std::size_t stall = 0;
    while (remaining > 3) {
        std::uint32_t a = prev[i], c = next[i];
        bool ear = cross(a, i, c) > eps;
        if (ear) {
            if (budget < remaining) return false;
            budget -= remaining;
            for (std::uint32_t k = next[c]; k != a; k = next[k]) {
                const glm::dvec2& q = pts[k];
                if (q == pts[a] || q == pts[i] || q == pts[c]) continue;
                if (inside(q, a, i, c)) {
                    ear = false;
                    break;
                }
            }
        }
        if (!ear && ++stall <= remaining) {
            i = c;
            continue;
        }
        if (!ear) {
            // No proper ear in a whole round: clip a flat vertex, else a convex one, else this.
            std::uint32_t pick = i, k = i;
            bool found = false;
            for (std::size_t m = 0; m < remaining && !found; ++m, k = next[k])
                if (std::fabs(cross(prev[k], k, next[k])) <= eps) pick = k, found = true;
            for (std::size_t m = 0; m < remaining && !found; ++m, k = next[k])
                if (cross(prev[k], k, next[k]) > 0) pick = k, found = true;
            i = pick;
            a = prev[i];
            c = next[i];
        }
        tris.insert(tris.end(), {a, i, c});
        next[a] = c;
        prev[c] = a;
        --remaining;
        stall = 0;
        i = a;  // the neighbours may have become ears
    }
    tris.insert(tris.end(), {prev[i], i, next[i]});
    out.insert(out.end(), tris.begin(), tris.end());
    return true;
}

class ObjLoader {
public:
    ObjLoader(std::string file, fs::path base_dir, Diagnostics& diag, const ObjLoadOptions& opt)
        : file_(std::move(file)), base_dir_(std::move(base_dir)), diag_(diag), opt_(opt), budget_(opt.triangulation_budget) {}

    Scene load(std::string_view text) {
        scene_.source = file_;
        mesh_index(std::string(), 0);  // the mesh for faces before any o/g (named later)
        parse(text);
        flush_warnings();
        load_textures();
        build();
        flush_warnings();
        return std::move(scene_);
    }

private:
    std::string file_;
    fs::path base_dir_;
    Diagnostics& diag_;
    const ObjLoadOptions& opt_;
    std::size_t budget_;
    Scene scene_;
    int line_ = 0;

    std::vector<glm::vec3> v_;
    std::vector<glm::vec4> color_;  // per v; w < 0: none
    bool any_color_ = false;
    std::vector<glm::vec2> vt_;
    std::vector<glm::vec3> vn_;
    std::vector<Corner> corners_;
    std::vector<Face> faces_;
    std::size_t elements_ = 0;

    struct MeshInfo {
        std::string name;
        int first_line = 0;
    };
    std::vector<MeshInfo> meshes_;
    std::map<std::string, int> mesh_by_name_;
    std::string object_, group_;
    int mesh_ = 0;
    std::uint32_t smoothing_ = 0;
    int material_ = -1;

    // Materials: every MTL material in mtllib order (the first definition of a name wins).
    std::vector<MtlMaterialSource> mtl_;
    std::vector<fs::path> mtl_dir_;  // the folder of each material's MTL file
    std::vector<std::string> mtl_file_;
    std::map<std::string, int> material_by_name_;
    std::vector<fs::path> mtl_loaded_;
    std::map<std::string, int> unknown_materials_;
    bool mtllib_seen_ = false;
    std::size_t unknown_statements_ = 0, missing_textures_ = 0;
    std::size_t texture_bytes_ = 0;

    LineWarnings warnings_{file_, diag_, "times"};

    [[noreturn]] void fail(const std::string& what) const { throw Error(file_, "line " + std::to_string(line_), what); }
    // At most 64 warnings of their own per file; those of a kind that may repeat on every line
    // collapse into one, at the first line (LineWarnings), passed on by flush_warnings().
    void warn(const std::string& what) { warnings_.warn(line_, what); }
    void warn_once(const std::string& kind, const std::string& message) { warnings_.once(line_, kind, message); }
    void flush_warnings() { warnings_.flush(); }

    void count_element(std::size_t n = 1) {
        elements_ += n;
        if (elements_ > opt_.max_elements)
            fail("more than " + std::to_string(opt_.max_elements) + " vertices, texture coordinates, normals and face corners");
    }

    // ---- Parsing ----------------------------------------------------------------------

    float coordinate(std::string_view s, const char* what, bool must_be_finite) {
        return float(coordinate64(s, what, must_be_finite));
    }
    double coordinate64(std::string_view s, const char* what, bool must_be_finite) {
        bool partial = false;
        auto v = parse_number(s, partial);
        if (!v) fail("'" + printable(s) + "' is not a number (" + what + ")");
        if (partial) warn_once("partial number", "'" + printable(s) + "' is not a number; read as its numeric prefix");
        if (!std::isfinite(*v) || std::fabs(*v) > 3.4e38) {
            if (must_be_finite) fail(std::string(what) + " '" + printable(s) + "' is not a finite number");
            warn_once(std::string("nonfinite ") + what, std::string(what) + " is not finite; replaced");
            return std::numeric_limits<double>::quiet_NaN();
        }
        return *v;
    }

    int mesh_index(const std::string& name, int line) {
        auto it = mesh_by_name_.find(name);
        if (it != mesh_by_name_.end()) return it->second;
        int i = int(meshes_.size());
        meshes_.push_back({name, line});
        mesh_by_name_[name] = i;
        return i;
    }
    void select_mesh() {
        std::string name = object_;
        if (!group_.empty()) name = name.empty() ? group_ : name + "/" + group_;
        mesh_ = mesh_index(name, line_);
    }

    // One "v[/vt][/vn]" of a face, line or point, resolved to 0-based indices.
    Corner corner(std::string_view s) {
        Corner c;
        std::string_view parts[3];
        int count = 0;
        std::size_t start = 0;
        for (std::size_t i = 0; i <= s.size(); ++i)
            if (i == s.size() || s[i] == '/') {
                if (count == 3) fail("'" + printable(s) + "' has more than three indices (v/vt/vn)");
                parts[count++] = s.substr(start, i - start);
                start = i + 1;
            }
        auto resolve = [&](std::string_view t, std::size_t size, const char* what) -> long long {
            auto v = parse_integer(t);
            if (!v) fail("'" + printable(t) + "' is not an index (" + what + ")");
            long long i = *v;
            if (i == 0) fail(std::string(what) + " index 0: OBJ indices start at 1 (negative ones count back)");
            long long r = i > 0 ? i - 1 : (long long)size + i;
            if (r < 0 || r >= (long long)size)
                fail(std::string(what) + " index " + std::to_string(i) + " is out of range (" + std::to_string(size) +
                     " defined so far)");
            return r;
        };
        if (parts[0].empty()) fail("'" + printable(s) + "' has no vertex index");
        c.v = std::uint32_t(resolve(parts[0], v_.size(), "vertex"));
        if (count >= 2 && !parts[1].empty()) c.vt = std::int32_t(resolve(parts[1], vt_.size(), "texture coordinate"));
        if (count >= 3 && !parts[2].empty()) c.vn = std::int32_t(resolve(parts[2], vn_.size(), "normal"));
        return c;
    }

    void element(const std::vector<std::string_view>& tok, Kind kind) {
        std::size_t n = tok.size() - 1;
        if (n > opt_.max_polygon_vertices)
            fail(std::to_string(n) + " corners in one element; the limit is " + std::to_string(opt_.max_polygon_vertices));
        std::size_t minimum = kind == Kind::Face ? 3 : kind == Kind::Line ? 2 : 1;
        if (n < minimum) {
            warn_once(std::string("short ") + char('0' + int(kind)),
                      std::string(kind == Kind::Face ? "face with fewer than 3" : kind == Kind::Line ? "line with fewer than 2"
                                                                                                 : "point statement without")
                          + " vertices; skipped");
            return;
        }
        count_element(n);
        Face f;
        f.first = std::uint32_t(corners_.size());
        f.count = std::uint32_t(n);
        f.smoothing = smoothing_;
        f.material = material_;
        f.mesh = mesh_;
        f.line = line_;
        f.kind = kind;
        for (std::size_t i = 1; i < tok.size(); ++i) corners_.push_back(corner(tok[i]));
        faces_.push_back(f);
    }

    void parse(std::string_view text) {
        LineReader lines(text);
        std::string_view line;
        std::vector<std::string_view> tok;
        while (lines.next(line, line_)) {
            tokenize(line, tok);
            if (tok.empty()) continue;
            std::string_view k = tok[0];
            if (k == "v") {
                if (tok.size() < 4) fail("a vertex needs x y z");
                count_element();
                glm::vec3 p(coordinate(tok[1], "x", true), coordinate(tok[2], "y", true), coordinate(tok[3], "z", true));
                v_.push_back(p);
                glm::vec4 col(0.0f, 0.0f, 0.0f, -1.0f);
                if (tok.size() == 7 || tok.size() == 8) {  // x y z r g b [a]
                    for (int c = 0; c < 3; ++c) {
                        float x = coordinate(tok[std::size_t(4 + c)], "colour", false);
                        col[c] = std::isfinite(x) ? x : 0.0f;
                    }
                    float a = tok.size() == 8 ? coordinate(tok[7], "colour", false) : 1.0f;
                    col.w = std::isfinite(a) ? std::clamp(a, 0.0f, 1.0f) : 1.0f;
                    any_color_ = true;
                } else if (tok.size() != 4 && tok.size() != 5) {
                    warn_once("v count", "vertex with " + std::to_string(tok.size() - 1) +
                                             " values (3, 4 or 6 expected); the first three used");
                }
                if (any_color_ || col.w >= 0) {
                    color_.resize(v_.size() - 1, glm::vec4(0, 0, 0, -1));
                    color_.push_back(col);
                }
            } else if (k == "vt") {
                if (tok.size() < 2) fail("a texture coordinate needs u [v [w]]");
                count_element();
                float u = coordinate(tok[1], "u", false);
                double v = tok.size() >= 3 ? coordinate64(tok[2], "v", false) : 0.0;
                // glTF's origin is top-left: 1 - v in double from the file's digits, rounded once
                // (write_obj inverts it exactly; see obj_v_text in scene_writer.cpp).
                vt_.emplace_back(std::isfinite(u) ? u : 0.0f, float(1.0 - (std::isfinite(v) ? v : 0.0)));
            } else if (k == "vn") {
                if (tok.size() < 4) fail("a normal needs x y z");
                count_element();
                // Non-finite normals are repaired after building (repair_normals).
                vn_.emplace_back(coordinate(tok[1], "normal", false), coordinate(tok[2], "normal", false),
                                 coordinate(tok[3], "normal", false));
            } else if (k == "f" || k == "fo") {
                element(tok, Kind::Face);
            } else if (k == "l") {
                element(tok, Kind::Line);
            } else if (k == "p") {
                element(tok, Kind::Point);
            } else if (k == "o") {
                object_ = std::string(rest_after(line, k));
                group_.clear();
                select_mesh();
            } else if (k == "g") {
                // Several names ("g a b") put the faces in several groups; they become one mesh.
                std::string name;
                for (std::size_t i = 1; i < tok.size(); ++i) name += (i > 1 ? " " : "") + std::string(tok[i]);
                group_ = name == "default" ? std::string() : name;
                select_mesh();
            } else if (k == "s") {
                if (tok.size() < 2) {
                    warn_once("s", "s without a value; smoothing off");
                    smoothing_ = 0;
                    continue;
                }
                std::string v = lower(tok[1]);
                if (v == "off") {
                    smoothing_ = 0;
                } else {
                    auto g = parse_integer(tok[1]);
                    if (!g || *g < 0 || *g > 0xFFFFFFFFll) {
                        warn_once("s value", "smoothing group '" + printable(tok[1]) + "' is not a number; smoothing off");
                        smoothing_ = 0;
                    } else {
                        smoothing_ = std::uint32_t(*g);
                    }
                }
            } else if (k == "usemtl") {
                std::string name(rest_after(line, k));
                auto it = material_by_name_.find(name);
                if (it != material_by_name_.end()) {
                    material_ = it->second;
                } else {
                    material_ = -1;
                    // Each unknown name once; past 16 names, one counted warning for the rest.
                    if (unknown_materials_.size() < 16) {
                        if (unknown_materials_.emplace(name, line_).second)
                            warn(std::string(mtllib_seen_ ? "no MTL file read defines" : "no mtllib before") +
                                 " material '" + printable(name) + "'; using the default material");
                    } else if (!unknown_materials_.count(name)) {
                        warn_once("unknown materials", "more materials no MTL file defines; using the default material");
                    }
                }
            } else if (k == "mtllib") {
                mtllib(std::string(rest_after(line, k)));
            } else if (k == "vp" || k == "cstype" || k == "deg" || k == "bmat" || k == "step" || k == "curv" ||
                       k == "curv2" || k == "surf" || k == "parm" || k == "trim" || k == "hole" || k == "scrv" ||
                       k == "sp" || k == "end" || k == "con" || k == "mg" || k == "lod" || k == "bevel" ||
                       k == "c_interp" || k == "d_interp" || k == "shadow_obj" || k == "trace_obj" || k == "usemap" ||
                       k == "maplib" || k == "ctech" || k == "stech" || k == "call" || k == "csh") {
                warn_once("stmt " + std::string(k), "'" + std::string(k) + "' (free-form geometry or display attribute) is not supported; ignored");
            } else {
                // Garbage can hold any number of distinct "statements": name the first few only.
                if (unknown_statements_++ < 16)
                    warn_once("unknown " + printable(k, 32), "unknown statement '" + printable(k, 32) + "'; ignored");
                else
                    warn_once("unknown more", "more unknown statements; ignored");
            }
        }
        if (any_color_) color_.resize(v_.size(), glm::vec4(0, 0, 0, -1));
    }

    // ---- MTL files --------------------------------------------------------------------

    void mtllib(const std::string& rest) {
        mtllib_seen_ = true;
        if (rest.empty()) return warn("mtllib without a file name; ignored");
        // The whole rest is one name when such a file exists (names with blanks); otherwise
        // blank-separated names, as the specification has it.
        std::vector<std::string> names{rest};
        std::string error;
        auto whole = gltf::resolve_model_path(rest, base_dir_, base_dir_, opt_.allow_external_files, error);
        std::error_code ec;
        if (!whole || !fs::is_regular_file(*whole, ec)) {
            std::vector<std::string_view> tok;
            tokenize(rest, tok);
            if (tok.size() > 1) {
                names.clear();
                for (auto t : tok) names.emplace_back(t);
            }
        }
        for (const auto& name : names) {
            auto path = gltf::resolve_model_path(name, base_dir_, base_dir_, opt_.allow_external_files, error);
            if (!path) fail("mtllib '" + printable(name) + "': " + error);
            if (std::find(mtl_loaded_.begin(), mtl_loaded_.end(), *path) != mtl_loaded_.end()) continue;
            if (!fs::is_regular_file(*path, ec)) {
                warn("MTL file '" + printable(name) + "' not found; its materials use the default");
                continue;
            }
            if (mtl_loaded_.size() >= opt_.max_mtl_files)
                fail("more than " + std::to_string(opt_.max_mtl_files) + " MTL files");
            mtl_loaded_.push_back(*path);
            std::string mtl_name = path->string();
            std::vector<std::uint8_t> bytes;
            try {
                bytes = read_file_bytes(*path, opt_.max_file_bytes);
            } catch (const Error& e) {
                fail("mtllib '" + printable(name) + "': " + e.reason());
            }
            std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
            auto mats = parse_mtl(text, mtl_name, diag_, opt_.max_materials);
            std::size_t again = 0;
            int again_line = 0;
            std::string again_name;
            for (auto& m : mats) {
                if (material_by_name_.count(m.name)) {
                    if (again++ == 0) again_line = m.line, again_name = m.name;
                    continue;
                }
                material_by_name_[m.name] = int(mtl_.size());
                mtl_dir_.push_back(path->parent_path());
                mtl_file_.push_back(mtl_name);
                mtl_.push_back(std::move(m));
            }
            if (again)
                diag_.warn(mtl_name, "line " + std::to_string(again_line),
                           "material '" + printable(again_name) + "' is defined again; the first definition is used" +
                               (again > 1 ? " (and " + std::to_string(again - 1) + " more repeated names)" : std::string()));
        }
    }

    // ---- Textures ----------------------------------------------------------------------

    std::map<std::string, int> image_by_path_;
    std::map<std::pair<int, bool>, int> texture_by_image_;

    // A file in `dir` whose name matches `name` ignoring case (MTL files written on Windows).
    static std::optional<fs::path> case_insensitive_match(const fs::path& p) {
        std::error_code ec;
        fs::path dir = p.parent_path();
        std::string want = lower(p.filename().string());
        std::size_t seen = 0;
        for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
            if (++seen > 100000) break;
            if (lower(it->path().filename().string()) == want && it->is_regular_file(ec)) return it->path();
        }
        return std::nullopt;
    }

    // The slot for a map, or an empty one (with a warning) when its file is missing.
    TextureSlot texture_slot(std::size_t m, const MtlTextureRef& ref) {
        TextureSlot slot;
        if (ref.path.empty()) return slot;
        const std::string& mtl = mtl_file_[m];
        std::string error;
        auto path = gltf::resolve_model_path(ref.path, mtl_dir_[m], base_dir_, opt_.allow_external_files, error);
        if (!path) throw Error(mtl, "line " + std::to_string(ref.line), "texture '" + printable(ref.path) + "': " + error);
        std::error_code ec;
        if (!fs::is_regular_file(*path, ec)) {
            auto alt = case_insensitive_match(*path);
            if (!alt) {
                if (missing_textures_++ < 16)
                    diag_.warn(mtl, "line " + std::to_string(ref.line),
                               "texture '" + printable(ref.path) + "' not found; the map is ignored");
                else
                    warn_once("missing textures", "more textures not found; their maps are ignored");
                return slot;
            }
            path = alt;
        }
        std::string key = path->string();
        auto it = image_by_path_.find(key);
        int image;
        if (it != image_by_path_.end()) {
            image = it->second;
        } else {
            image = int(scene_.images.size());
            SceneImage img;
            img.name = printable(ref.path);
            scene_.images.push_back(std::move(img));
            image_paths_.push_back(*path);
            image_where_.push_back({mtl, ref.line});
            image_by_path_[key] = image;
        }
        auto t = texture_by_image_.find({image, ref.clamp});
        if (t != texture_by_image_.end()) {
            slot.texture = t->second;
        } else {
            Texture tex;
            tex.image = image;
            if (ref.clamp) tex.sampler.wrap_s = tex.sampler.wrap_t = Wrap::ClampToEdge;
            slot.texture = int(scene_.textures.size());
            scene_.textures.push_back(tex);
            texture_by_image_[{image, ref.clamp}] = slot.texture;
        }
        if (ref.has_transform) slot.set_transform(ref.transform);
        return slot;
    }
    std::vector<fs::path> image_paths_;
    std::vector<std::pair<std::string, int>> image_where_;

    // Materials: scene.materials[i] is MTL material i; the default material (faces without
    // a known usemtl) is appended when a face needs it.
    void load_textures() {
        for (std::size_t m = 0; m < mtl_.size(); ++m) {
            MtlMaterialSource& s = mtl_[m];
            PhongExt& p = s.phong;
            p.ambient_map.slot = texture_slot(m, s.ambient);
            p.diffuse_map.slot = texture_slot(m, s.diffuse);
            p.specular_map.slot = texture_slot(m, s.specular);
            p.shininess_map.slot = texture_slot(m, s.shininess);
            p.dissolve_map.slot = texture_slot(m, s.dissolve);
            p.emission_map.slot = texture_slot(m, s.emission);
            p.bump_map.slot = texture_slot(m, s.bump);
            p.roughness_map.slot = texture_slot(m, s.roughness);
            p.metallic_map.slot = texture_slot(m, s.metallic);
            p.sheen_map.slot = texture_slot(m, s.sheen);
            p.normal_map.slot = texture_slot(m, s.normal);
        }
        decode_images();
        for (std::size_t m = 0; m < mtl_.size(); ++m) {
            Material mat = phong_to_metallic_roughness(mtl_[m].phong, printable(mtl_[m].name, 1000));
            pack_scalar_maps(mat);
            scene_.materials.push_back(std::move(mat));
        }
    }

    void decode_images() {
        const std::size_t n = scene_.images.size();
        if ((!opt_.decode_images && !opt_.read_image_headers) || n == 0) return;
        std::vector<std::vector<std::uint8_t>> encoded(n);
        for (std::size_t i = 0; i < n; ++i) {
            try {
                encoded[i] = read_file_bytes(image_paths_[i], opt_.image_limits.max_decoded_bytes);
            } catch (const Error& e) {
                diag_.warn(image_where_[i].first, "line " + std::to_string(image_where_[i].second),
                           "texture '" + scene_.images[i].name + "': " + e.reason() + "; the map is ignored");
                continue;
            }
            texture_bytes_ += encoded[i].size();
            if (texture_bytes_ > opt_.max_total_bytes)
                throw Error(image_where_[i].first, "line " + std::to_string(image_where_[i].second),
                            "textures exceed the limit of " + std::to_string(opt_.max_total_bytes) + " bytes");
            scene_.images[i].header = peek_image_header(encoded[i]);
            scene_.images[i].encoded_bytes = encoded[i].size();
            if (!opt_.decode_images) encoded[i] = {};  // the header was all that was asked
        }
        std::vector<std::string> errors(n);
        parallel_for(
            n,
            [&](std::size_t i) {
                if (encoded[i].empty()) return;
                try {
                    scene_.images[i].pixels = decode_image8(encoded[i], scene_.images[i].name, opt_.image_limits);
                } catch (const Error& e) {
                    errors[i] = e.reason();
                }
                encoded[i] = {};
            },
            opt_.threads);
        for (std::size_t i = 0; i < n; ++i)
            if (!errors[i].empty())
                diag_.warn(image_where_[i].first, "line " + std::to_string(image_where_[i].second),
                           "texture '" + scene_.images[i].name + "': " + errors[i] + "; using a neutral texture");
    }

    const Image8* pixels(const MtlMap& map) const {
        if (!map.valid()) return nullptr;
        int image = scene_.textures[std::size_t(map.slot.texture)].image;
        if (image < 0 || !scene_.images[std::size_t(image)].valid()) return nullptr;
        return &scene_.images[std::size_t(image)].pixels;
    }
    static float channel(const Image8& img, int x, int y, MtlChannel c) {
        const std::uint8_t* q = img.at(x, y);
        int n = img.channels;
        auto ch = [&](int i) { return i < n ? q[i] / 255.0f : i == 3 ? 1.0f : q[0] / 255.0f; };  // grey, grey + alpha
        if (n == 2 && c == MtlChannel::Matte) return q[1] / 255.0f;
        switch (c) {
            case MtlChannel::R: return ch(0);
            case MtlChannel::G: return ch(1);
            case MtlChannel::B: return ch(2);
            case MtlChannel::Matte: return ch(3);
            case MtlChannel::Luminance: return 0.2126f * ch(0) + 0.7152f * ch(1) + 0.0722f * ch(2);
        }
        return 0.0f;
    }
    // Nearest texel of `img` for texel (x, y) of a w x h image.
    static float sample(const Image8& img, int x, int y, int w, int h, MtlChannel c) {
        int sx = int((std::int64_t(x) * img.width) / w), sy = int((std::int64_t(y) * img.height) / h);
        return channel(img, std::min(sx, img.width - 1), std::min(sy, img.height - 1), c);
    }

    int add_packed(Image8 img, const std::string& name, const TextureSlot& like) {
        SceneImage si;
        si.name = name;
        si.pixels = std::move(img);
        scene_.images.push_back(std::move(si));
        Texture t;
        t.image = int(scene_.images.size()) - 1;
        if (like.valid()) t.sampler = scene_.textures[std::size_t(like.texture)].sampler;
        scene_.textures.push_back(t);
        return int(scene_.textures.size()) - 1;
    }

    // map_d into the base colour's alpha; map_Pr / map_Pm (or map_Ns through the shininess
    // conversion) into the metallic-roughness texture (G roughness, B metallic). The result
    // takes the largest source size, sampling the others at their nearest texel; the texture
    // transform and coordinate set are the first source's.
    void pack_scalar_maps(Material& mat) {
        const PhongExt& p = *mat.phong;
        if (p.roughness_map.valid() && !p.roughness) mat.roughness_factor = 1.0f;
        if (p.metallic_map.valid() && !p.metallic) mat.metallic_factor = 1.0f;
        if (const Image8* d = pixels(p.dissolve_map)) {
            const Image8* base = pixels(p.diffuse_map);
            int w = std::max(d->width, base ? base->width : 0), h = std::max(d->height, base ? base->height : 0);
            Image8 out;
            out.width = w;
            out.height = h;
            out.pixels.assign(std::size_t(w) * std::size_t(h) * 4, 255);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    std::uint8_t* o = &out.pixels[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
                    if (base)
                        for (int c = 0; c < 3; ++c)
                            o[c] = std::uint8_t(std::lround(sample(*base, x, y, w, h, MtlChannel(c)) * 255.0f));
                    o[3] = std::uint8_t(std::lround(sample(*d, x, y, w, h, p.dissolve_map.channel) * 255.0f));
                }
            const TextureSlot& like = base ? p.diffuse_map.slot : p.dissolve_map.slot;
            TextureSlot slot = like;
            slot.texture = add_packed(std::move(out), mat.name + " (base colour + map_d)", like);
            mat.base_color = slot;
            mat.alpha_mode = AlphaMode::Blend;
        }
        bool pbr = p.has_pbr();
        const Image8* rough = pixels(pbr ? p.roughness_map : MtlMap{});
        const Image8* metal = pixels(pbr ? p.metallic_map : MtlMap{});
        const Image8* shiny = pbr ? nullptr : pixels(p.shininess_map);
        if (rough || metal || shiny) {
            int w = 0, h = 0;
            for (const Image8* i : {rough, metal, shiny})
                if (i) w = std::max(w, i->width), h = std::max(h, i->height);
            Image8 out;
            out.width = w;
            out.height = h;
            out.pixels.assign(std::size_t(w) * std::size_t(h) * 4, 255);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    std::uint8_t* o = &out.pixels[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
                    float r = 1.0f;
                    if (rough) r = sample(*rough, x, y, w, h, p.roughness_map.channel);
                    if (shiny) r = phong_shininess_to_roughness(p.shininess * sample(*shiny, x, y, w, h, p.shininess_map.channel));
                    o[1] = std::uint8_t(std::lround(std::clamp(r, 0.0f, 1.0f) * 255.0f));
                    o[2] = metal ? std::uint8_t(std::lround(sample(*metal, x, y, w, h, p.metallic_map.channel) * 255.0f)) : 255;
                }
            if (shiny) mat.roughness_factor = 1.0f;  // the texture holds the converted roughness
            const MtlMap& src = rough ? p.roughness_map : metal ? p.metallic_map : p.shininess_map;
            TextureSlot slot = src.slot;
            slot.texture = add_packed(std::move(out), mat.name + " (metallic-roughness)", src.slot);
            mat.metallic_roughness = slot;
        }
    }

    int default_material_ = -1;
    int material_for(int m) {
        if (m >= 0) return m;
        if (default_material_ < 0) {
            default_material_ = int(scene_.materials.size());
            scene_.materials.push_back(phong_to_metallic_roughness(PhongExt{}, "default"));
        }
        return default_material_;
    }

    // ---- Building primitives ------------------------------------------------------------

    struct Build {
        Primitive p;
        std::unordered_map<Key, std::uint32_t, KeyHash> vertices;
        bool any_uv = false, any_generated = false;
    };

    void build() {
        // Smooth normals: the Newell vectors of every face of a smoothing group summed per
        // position, for the corners that have no vn.
        std::unordered_map<std::pair<std::uint32_t, std::uint32_t>, glm::dvec3, PosGroupHash> smooth;
        std::vector<glm::dvec3> poly;
        auto polygon = [&](const Face& f) {
            poly.clear();
            for (std::uint32_t i = 0; i < f.count; ++i) poly.push_back(glm::dvec3(v_[corners_[f.first + i].v]));
        };
        for (const Face& f : faces_) {
            std::uint32_t group = f.smoothing ? f.smoothing : opt_.smooth_without_groups ? 1u : 0u;
            if (f.kind != Kind::Face || group == 0) continue;
            bool needs = false;
            for (std::uint32_t i = 0; i < f.count && !needs; ++i) needs = corners_[f.first + i].vn < 0;
            if (!needs) continue;
            polygon(f);
            glm::dvec3 n = newell(poly);
            for (std::uint32_t i = 0; i < f.count; ++i) smooth[{corners_[f.first + i].v, group}] += n;
        }

        std::map<std::tuple<int, int, Kind>, Build> builds;  // (mesh, material, kind), in order
        std::vector<std::uint32_t> local, ids;
        std::vector<glm::dvec2> flat2d;
        std::size_t fanned = 0;
        for (std::size_t fi = 0; fi < faces_.size(); ++fi) {
            const Face& f = faces_[fi];
            line_ = f.line;
            Build& b = builds[{f.mesh, material_for(f.material), f.kind}];
            // The face's corners as primitive vertices.
            glm::vec3 face_normal(0.0f, 0.0f, 1.0f);
            std::uint32_t group = f.smoothing ? f.smoothing : opt_.smooth_without_groups ? 1u : 0u;
            if (f.kind == Kind::Face) {
                polygon(f);
                glm::dvec3 n = newell(poly);
                double len = glm::length(n);
                if (len > 0 && std::isfinite(len)) face_normal = glm::vec3(n / len);
                // Triangulate.
                local.clear();
                if (f.count == 3) {
                    local = {0, 1, 2};
                } else {
                    bool done = false;
                    if (len > 0 && std::isfinite(len)) {
                        glm::dvec3 nn = n / len;
                        glm::dvec3 u = std::fabs(nn.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
                        u = glm::normalize(u - nn * glm::dot(u, nn));
                        glm::dvec3 w = glm::cross(nn, u);
                        flat2d.clear();
                        for (const auto& q : poly) flat2d.emplace_back(glm::dot(q, u), glm::dot(q, w));
                        // Convex: the fan from the first corner, as OpenGL's GL_POLYGON and most
                        // loaders triangulate (so Gouraud shading interpolates as theirs does);
                        // concave: ear clipping.
                        if (convex_polygon(flat2d)) {
                            for (std::uint32_t i = 1; i + 1 < f.count; ++i) local.insert(local.end(), {0u, i, i + 1});
                            done = true;
                        } else {
                            done = ear_clip(flat2d, local, budget_);
                        }
                    }
                    if (!done) {
                        if (len > 0) ++fanned;
                        local.clear();
                        for (std::uint32_t i = 1; i + 1 < f.count; ++i) local.insert(local.end(), {0u, i, i + 1});
                    }
                }
            }
            ids.resize(f.count);
            for (std::uint32_t i = 0; i < f.count; ++i) {
                const Corner& c = corners_[f.first + i];
                Key key{c.v, c.vt, 0};
                if (f.kind != Kind::Face) key.n = -1;
                else if (c.vn >= 0) key.n = c.vn;
                else if (group != 0) key.n = -2 - std::int64_t(group);
                else key.n = std::numeric_limits<std::int64_t>::min() + std::int64_t(fi);  // flat: this face only
                auto [it, added] = b.vertices.emplace(key, std::uint32_t(b.p.positions.size()));
                if (added) {
                    b.p.positions.push_back(v_[c.v]);
                    if (any_color_) {
                        glm::vec4 col = color_[c.v];
                        b.p.colors.push_back(col.w < 0 ? glm::vec4(1.0f) : col);
                    }
                    if (f.kind == Kind::Face) {
                        if (c.vt >= 0) b.any_uv = true;
                        b.p.uv0.push_back(c.vt >= 0 ? vt_[std::size_t(c.vt)] : glm::vec2(0.0f));
                        glm::vec3 nrm = face_normal;
                        if (c.vn >= 0) {
                            nrm = vn_[std::size_t(c.vn)];
                        } else {
                            b.any_generated = true;
                            if (group != 0) {
                                glm::dvec3 s = smooth[{c.v, group}];
                                double l = glm::length(s);
                                nrm = l > 0 && std::isfinite(l) ? glm::vec3(s / l) : face_normal;
                            }
                        }
                        b.p.normals.push_back(nrm);
                    } else if (c.vt >= 0) {
                        b.any_uv = true;
                        b.p.uv0.push_back(vt_[std::size_t(c.vt)]);
                    } else {
                        b.p.uv0.push_back(glm::vec2(0.0f));
                    }
                }
                ids[i] = it->second;
            }
            if (f.kind == Kind::Face) {
                for (std::uint32_t l : local) b.p.indices.push_back(ids[l]);
            } else if (f.kind == Kind::Line) {
                for (std::uint32_t i = 0; i + 1 < f.count; ++i) b.p.indices.insert(b.p.indices.end(), {ids[i], ids[i + 1]});
            } else {
                b.p.indices.insert(b.p.indices.end(), ids.begin(), ids.end());
            }
        }
        if (fanned) warn_once("fanned", std::to_string(fanned) + " polygons triangulated as fans (triangulation work limit reached)");

        // Name the meshes and put one node per non-empty mesh into the scene.
        std::string stem = printable(fs::path(file_).stem().string());
        std::vector<int> mesh_of(meshes_.size(), -1);
        std::vector<int> roots;
        for (auto& [key, b] : builds) {
            auto [mi, material, kind] = key;
            Primitive& p = b.p;
            if (p.indices.empty()) continue;
            if (!b.any_uv) p.uv0.clear();
            p.material = material;
            p.topology = kind == Kind::Face ? Topology::Triangles : kind == Kind::Line ? Topology::Lines : Topology::Points;
            p.generated_normals = b.any_generated;
            line_ = meshes_[std::size_t(mi)].first_line;
            if (kind == Kind::Face) {
                if (std::size_t bad = repair_normals(p))
                    warn_once("bad normals", std::to_string(bad) + " invalid normals (zero or not finite) replaced by computed ones");
                // Tangents where the glTF loader makes them too (mesh_ops' tangent_source): a
                // normal map, a clearcoat normal map, or anisotropy (MTL aniso), from the one UV set.
                const Material& mat = scene_.materials[std::size_t(material)];
                if (const TextureSlot* map = tangent_source(mat)) {
                    if (!generate_tangents(p, 0))
                        warn_once("no uv tangents",
                                  mat.anisotropy && map == &mat.anisotropy->anisotropy_texture
                                      ? "anisotropy on faces without texture coordinates (no tangents); shaded isotropically"
                                      : "normal map on faces without texture coordinates; normal map ignored");
                    repair_tangents(p.tangents);
                }
            }
            p.bounds_min = p.bounds_max = p.positions[0];
            for (const auto& q : p.positions) p.bounds_min = glm::min(p.bounds_min, q), p.bounds_max = glm::max(p.bounds_max, q);
            p.source_vertex_count = p.positions.size();
            drop_identity_indices(p);
            if (mesh_of[std::size_t(mi)] < 0) {
                mesh_of[std::size_t(mi)] = int(scene_.meshes.size());
                Mesh m;
                m.name = meshes_[std::size_t(mi)].name.empty() ? stem : printable(meshes_[std::size_t(mi)].name, 1000);
                scene_.meshes.push_back(std::move(m));
                Node node;
                node.name = scene_.meshes.back().name;
                node.mesh = mesh_of[std::size_t(mi)];
                roots.push_back(int(scene_.nodes.size()));
                scene_.nodes.push_back(std::move(node));
            }
            scene_.meshes[std::size_t(mesh_of[std::size_t(mi)])].primitives.push_back(std::move(p));
        }
        if (scene_.meshes.empty()) {
            line_ = 0;
            warn(faces_.empty() ? (v_.empty() ? "file has no geometry" : "file has vertices but no faces, lines or points")
                                : "file has no drawable element");
        }
        scene_.scenes.push_back(std::move(roots));
        scene_.default_scene = 0;
    }
};

}  // namespace

Scene load_obj_from_memory(std::span<const std::uint8_t> bytes, const std::string& name, const fs::path& base_dir,
                           Diagnostics& diagnostics, const ObjLoadOptions& options) {
    ObjLoader loader(name, base_dir, diagnostics, options);
    if (bytes.size() > options.max_file_bytes)
        throw Error(name, "", "file of " + std::to_string(bytes.size()) + " bytes is over the limit of " +
                                  std::to_string(options.max_file_bytes));
    return as_file_error(name, [&] {
        return loader.load(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    });
}

Scene load_obj(const fs::path& path, Diagnostics& diagnostics, const ObjLoadOptions& options) {
    auto bytes = read_file_bytes(path, options.max_file_bytes);
    fs::path dir = path.parent_path();
    return load_obj_from_memory(bytes, path.string(), dir.empty() ? fs::path(".") : dir, diagnostics, options);
}

}  // namespace fresnel
