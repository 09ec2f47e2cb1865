// The Python module's tools: environment bakes, material evaluation at surface points, image
// metrics, legacy material fits, and image files.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>

#include "common.h"
#include "fresnel/core/atomic_file.h"
#include "fresnel/core/metrics.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/material/evaluate.h"
#include "fresnel/material/fit.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/scene_textures.h"

namespace fresnel::python {

namespace {

// ---- bake ------------------------------------------------------------------------------

py::array_t<float> cube_array(const ibl::CubeLevel& level) {
    const std::size_t face = std::size_t(level.size) * std::size_t(level.size) * 4;
    std::vector<float> v(face * 6);
    for (std::size_t f = 0; f < 6; ++f) std::copy(level.faces[f].begin(), level.faces[f].end(), v.begin() + std::ptrdiff_t(f * face));
    const py::ssize_t s = level.size;
    return vector_array(std::move(v), {6, s, s, 4});
}

py::dict bake(py::handle environment, const py::object& output, int size, int samples, int levels,
              const py::object& progress) {
    ibl::BakeOptions options;
    options.size = size;
    options.samples = samples;
    options.levels = levels;
    if (size < 4 || size > 4096 || (size & (size - 1)) != 0)
        throw py::value_error("size: expected a power of two in [4, 4096], got " + std::to_string(size));
    if (samples < 1 || samples > 65536) throw py::value_error("samples: expected a whole number in [1, 65536]");
    if (levels < 1 || (1 << (levels - 1)) > size) throw py::value_error("levels: expected 1 .. log2(size) + 1");
    ImageF panorama;
    std::string source = "array";
    if (py::isinstance<py::str>(environment) || py::hasattr(environment, "__fspath__")) {
        source = py::str(py::module_::import("os").attr("fspath")(environment)).cast<std::string>();
        ibl::EnvironmentSource src;
        if (source == "studio") src.kind = ibl::EnvironmentSource::Kind::Studio;
        else {
            src.kind = ibl::EnvironmentSource::Kind::File;
            src.path = source;
        }
        py::gil_scoped_release release;
        panorama = ibl::load_panorama(src);
    } else {
        panorama = image_from(environment, "environment");
        if (panorama.width != 2 * panorama.height)
            throw py::value_error("environment: an equirectangular panorama is twice as wide as it is high; got " +
                                  std::to_string(panorama.width) + "x" + std::to_string(panorama.height));
    }
    ProgressBridge bridge;  // a callback that raises is called no more; its exception is raised after the bake
    bridge.callback = progress;
    std::string dir;
    if (!output.is_none()) dir = py::str(py::module_::import("os").attr("fspath")(output)).cast<std::string>();
    ibl::BakedIbl baked;
    {
        py::gil_scoped_release release;
        baked = ibl::bake(panorama, options, [&](double f) { bridge(f); });
        baked.source = source;
        if (!dir.empty() && !bridge.stop) ibl::save_baked(baked, dir, options);
    }
    bridge.rethrow();
    py::dict d;
    py::list specular;
    for (const ibl::CubeLevel& level : baked.specular.levels) specular.append(cube_array(level));
    d["specular"] = specular;
    d["irradiance"] = cube_array(baked.irradiance_map.levels.at(0));
    std::vector<float> sh;
    for (const glm::vec3& c : baked.irradiance.c) sh.insert(sh.end(), {c.x, c.y, c.z});
    d["irradiance_sh"] = vector_array(std::move(sh), {9, 3});
    const py::ssize_t lut = baked.lut.width;
    d["brdf_lut"] = vector_array(std::move(baked.lut.pixels), {lut, lut, 4});
    d["bake_ms"] = baked.bake_ms;
    d["content_hash"] = baked.content_hash;
    return d;
}

// ---- evaluate --------------------------------------------------------------------------

struct Points {
    std::size_t n = 0;
    py::array_t<float, py::array::c_style | py::array::forcecast> a;
    const float* at(std::size_t i) const { return a.data() + i * std::size_t(a.shape(1)); }
};

Points points(py::handle value, const char* name, py::ssize_t width, std::size_t n) {
    Points p;
    p.a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!p.a || p.a.ndim() != 2 || p.a.shape(1) != width)
        throw py::value_error(std::string(name) + ": expected an array of shape (N, " + std::to_string(width) + ")");
    p.n = std::size_t(p.a.shape(0));
    if (n != 0 && p.n != n)
        throw py::value_error(std::string(name) + ": has " + std::to_string(p.n) + " rows where uv0 has " + std::to_string(n));
    return p;
}

}  // namespace

// Scenes keep their textures decoded for evaluate() (built on first use); declared in session.cpp.
const TextureSource& scene_textures_for(py::handle scene);
const Scene& scene_of(py::handle scene);

namespace {

py::dict evaluate_material(py::handle scene, py::handle material, py::handle uv0, const py::object& uv1,
                           const py::object& color, const py::object& normal, const py::object& tangent, float lod) {
    const Scene& s = scene_of(scene);
    int index = -1;
    if (py::isinstance<py::str>(material)) {
        std::string name = material.cast<std::string>();
        for (std::size_t i = 0; i < s.materials.size(); ++i)
            if (s.materials[i].name == name) index = int(i);
        if (index < 0) throw Error(s.source, "material", "no material named '" + name + "'");
    } else {
        index = material.cast<int>();
        if (index < 0 || std::size_t(index) >= s.materials.size())
            throw Error(s.source, "material", "no material " + std::to_string(index) + " (the scene has " +
                                                  std::to_string(s.materials.size()) + ")");
    }
    const Material& m = s.materials[std::size_t(index)];
    const TextureSource& textures = scene_textures_for(scene);
    Points p0 = points(uv0, "uv0", 2, 0);
    const std::size_t n = p0.n;
    std::optional<Points> p1, pc, pn, pt;
    if (!uv1.is_none()) p1 = points(uv1, "uv1", 2, n);
    if (!color.is_none()) pc = points(color, "color", 4, n);
    if (!normal.is_none()) pn = points(normal, "normal", 3, n);
    if (!tangent.is_none()) pt = points(tangent, "tangent", 4, n);
    std::vector<float> base(n * 4), metallic(n), roughness(n), f0(n * 3), emissive(n * 3), occlusion(n), alpha(n),
        shading_normal(n * 3), clearcoat(n), clearcoat_roughness(n), sheen(n * 3), sheen_roughness(n), anisotropy(n),
        iridescence(n), iridescence_thickness(n), transmission(n), diffuse_transmission(n), diffuse_roughness(n);
    std::vector<std::uint8_t> discard(n);
    {
        py::gil_scoped_release release;
        for (std::size_t i = 0; i < n; ++i) {
            SurfacePoint sp;
            sp.lod = lod;
            sp.inputs.has_uv0 = true;
            sp.uv0 = glm::vec2(p0.at(i)[0], p0.at(i)[1]);
            sp.inputs.has_uv1 = p1.has_value();
            if (p1) {
                sp.uv1 = glm::vec2(p1->at(i)[0], p1->at(i)[1]);
            }
            if (pc) {
                sp.color = glm::vec4(pc->at(i)[0], pc->at(i)[1], pc->at(i)[2], pc->at(i)[3]);
            }
            if (pn) {
                glm::vec3 nn(pn->at(i)[0], pn->at(i)[1], pn->at(i)[2]);
                float len = glm::length(nn);
                sp.normal = len > 0 ? nn / len : glm::vec3(0, 0, 1);
            }
            sp.inputs.has_tangent = pt.has_value();
            if (pt) {
                glm::vec3 t(pt->at(i)[0], pt->at(i)[1], pt->at(i)[2]);
                t = glm::normalize(t - sp.normal * glm::dot(sp.normal, t));
                sp.tangent = t;
                sp.bitangent = glm::cross(sp.normal, t) * (pt->at(i)[3] < 0 ? -1.0f : 1.0f);
            } else {
                // A frame about the normal (the identity frame for the default normal, +Z).
                glm::vec3 up = std::abs(sp.normal.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
                sp.tangent = glm::normalize(glm::cross(up, sp.normal));
                sp.bitangent = glm::cross(sp.normal, sp.tangent);
                if (sp.normal == glm::vec3(0, 0, 1)) {
                    sp.tangent = glm::vec3(1, 0, 0);
                    sp.bitangent = glm::vec3(0, 1, 0);
                }
            }
            EvaluatedMaterial e = evaluate(m, textures, sp);
            const glm::vec3 fd = e.surface.dielectric_f0();
            for (int c = 0; c < 3; ++c) {
                base[i * 4 + std::size_t(c)] = e.surface.base_color[c];
                f0[i * 3 + std::size_t(c)] = fd[c] * (1.0f - e.surface.metallic) + e.surface.base_color[c] * e.surface.metallic;
                emissive[i * 3 + std::size_t(c)] = e.emissive[c];
                shading_normal[i * 3 + std::size_t(c)] = e.normal[c];
                sheen[i * 3 + std::size_t(c)] = e.sheen_color[c];
            }
            base[i * 4 + 3] = e.alpha;
            metallic[i] = e.surface.metallic;
            roughness[i] = e.surface.perceptual_roughness;
            occlusion[i] = e.occlusion;
            alpha[i] = e.alpha;
            discard[i] = e.discard ? 1 : 0;
            clearcoat[i] = e.clearcoat;
            clearcoat_roughness[i] = e.clearcoat_roughness;
            sheen_roughness[i] = e.sheen_roughness;
            anisotropy[i] = e.anisotropy_strength;
            iridescence[i] = e.iridescence;
            iridescence_thickness[i] = e.iridescence_thickness;
            transmission[i] = e.transmission.factor;
            diffuse_transmission[i] = e.diffuse_transmission;
            diffuse_roughness[i] = e.diffuse_roughness;
        }
    }
    const py::ssize_t N = py::ssize_t(n);
    py::dict d;
    d["base_color"] = vector_array(std::move(base), {N, 4});
    d["metallic"] = vector_array(std::move(metallic), {N});
    d["roughness"] = vector_array(std::move(roughness), {N});
    d["f0"] = vector_array(std::move(f0), {N, 3});
    d["emissive"] = vector_array(std::move(emissive), {N, 3});
    d["occlusion"] = vector_array(std::move(occlusion), {N});
    d["alpha"] = vector_array(std::move(alpha), {N});
    d["discard"] = vector_array(std::move(discard), {N}).attr("astype")("bool");
    d["normal"] = vector_array(std::move(shading_normal), {N, 3});
    d["clearcoat"] = vector_array(std::move(clearcoat), {N});
    d["clearcoat_roughness"] = vector_array(std::move(clearcoat_roughness), {N});
    d["sheen_color"] = vector_array(std::move(sheen), {N, 3});
    d["sheen_roughness"] = vector_array(std::move(sheen_roughness), {N});
    d["anisotropy"] = vector_array(std::move(anisotropy), {N});
    d["iridescence"] = vector_array(std::move(iridescence), {N});
    d["iridescence_thickness"] = vector_array(std::move(iridescence_thickness), {N});
    d["transmission"] = vector_array(std::move(transmission), {N});
    d["diffuse_transmission"] = vector_array(std::move(diffuse_transmission), {N});
    d["diffuse_roughness"] = vector_array(std::move(diffuse_roughness), {N});
    return d;
}

// ---- compare ---------------------------------------------------------------------------

double finite_or(double v, double inf_value) { return std::isinf(v) ? (v > 0 ? inf_value : -inf_value) : v; }

py::dict compare(py::handle test, py::handle reference, const py::object& mask, bool linear, double ppd) {
    bool test_float = false, ref_float = false;
    ImageF t = image_from(test, "test", &test_float), r = image_from(reference, "reference", &ref_float);
    if (t.width != r.width || t.height != r.height)
        throw Error("compare", "", "test is " + std::to_string(t.width) + "x" + std::to_string(t.height) + ", reference " +
                                       std::to_string(r.width) + "x" + std::to_string(r.height) + ": compare needs one size");
    const bool t_lin = linear || test_float, r_lin = linear || ref_float;
    ImageF t_disp = t_lin ? to_display(t) : t, r_disp = r_lin ? to_display(r) : r;
    PixelMask m;
    if (!mask.is_none()) {
        if (py::isinstance<py::str>(mask) && mask.cast<std::string>() == "auto") m = background_mask(t_disp, r_disp);
        else {
            ImageF mi = image_from(mask, "mask");
            if (mi.width != t.width || mi.height != t.height) throw Error("compare", "mask", "the mask's size differs from the images'");
            m = mask_from_image(mi);
        }
    }
    py::dict d;
    const std::size_t pixels = mask_count(m, std::size_t(t.width) * std::size_t(t.height));
    d["pixels"] = pixels;
    if (pixels == 0) {
        d["psnr_db"] = 99.0;
        d["ssim"] = 1.0;
        d["flip"] = 0.0;
        d["mv_rms_db"] = -99.0;
        return d;
    }
    py::gil_scoped_release release;
    double psnr = psnr_db(t_disp, r_disp, m);
    double s = ssim(t_disp, r_disp, m).ssim;
    double flip = masked_mean(flip_ldr(r_disp, t_disp, ppd), m);
    double mv = mv_rms_db(t_disp, r_disp, m);
    double hdr = NAN;
    if (t_lin && r_lin) hdr = masked_mean(flip_hdr(r, t, flip_exposures(r), ppd), m);
    py::gil_scoped_acquire gil;
    d["psnr_db"] = finite_or(psnr, 99.0);
    d["ssim"] = s;
    d["flip"] = flip;
    d["mv_rms_db"] = finite_or(mv, 99.0);
    if (!std::isnan(hdr)) d["hdr_flip"] = hdr;
    return d;
}

// ---- fit -------------------------------------------------------------------------------

glm::vec3 vec3_of(py::handle v, const char* name) {
    if (PyNumber_Check(v.ptr()) && !PySequence_Check(v.ptr())) return glm::vec3(v.cast<float>());
    auto a = py::array_t<float, py::array::forcecast>::ensure(v);
    if (!a || a.size() != 3) throw py::value_error(std::string(name) + ": expected a number or 3 numbers");
    return glm::vec3(a.at(0), a.at(1), a.at(2));
}

py::dict residual_dict(const fit::Residual& r) {
    py::dict d;
    d["rms"] = r.rms;
    d["max"] = r.max;
    d["psnr_db"] = r.psnr_db;
    return d;
}

py::dict pbr_dict(const fit::Pbr& p) {
    py::dict d;
    d["base_color"] = py::make_tuple(p.base_color.x, p.base_color.y, p.base_color.z);
    d["metallic"] = p.metallic;
    d["roughness"] = p.roughness;
    d["specular_color"] = py::make_tuple(p.specular_f0.x / 0.04f, p.specular_f0.y / 0.04f, p.specular_f0.z / 0.04f);
    d["specular"] = p.specular_weight;
    return d;
}

py::dict fit_material(const py::object& kd, const py::object& ks, const py::object& ns, const py::object& base_color,
                      const py::object& metallic, const py::object& roughness, const std::string& match) {
    const bool phong = !kd.is_none() || !ks.is_none() || !ns.is_none();
    const bool pbr = !base_color.is_none() || !metallic.is_none() || !roughness.is_none();
    if (phong == pbr)
        throw py::type_error("fit: give a Phong material (kd, ks, ns) or a metallic-roughness one (base_color, metallic, roughness)");
    py::dict d;
    if (phong) {
        std::optional<fit::Match> mt = fit::parse_match(match);
        if (!mt) throw Error("fit", "match", "expected opengl1 or albedo, got '" + match + "'");
        fit::Phong p;
        if (!kd.is_none()) p.kd = vec3_of(kd, "kd");
        if (!ks.is_none()) p.ks = vec3_of(ks, "ks");
        if (!ns.is_none()) p.ns = ns.cast<float>();
        for (float v : {p.kd.x, p.kd.y, p.kd.z, p.ks.x, p.ks.y, p.ks.z})
            if (!(v >= 0.0f && v <= 1.0f)) throw Error("fit", "kd/ks", "colours are in [0, 1] (OpenGL 1 clamps them)");
        if (!(p.ns >= 0.0f && p.ns <= 128.0f)) throw Error("fit", "ns", "the shininess is in [0, 128] (OpenGL 1's range)");
        fit::PhongToPbr f = fit::fit_phong_to_pbr(p, *mt);
        d["pbr"] = pbr_dict(f.pbr);
        d["residual"] = residual_dict(f.residual);
        d["image_based_residual"] = residual_dict(f.image_based);
        d["match"] = fit::match_name(*mt);
    } else {
        fit::Pbr p;
        if (!base_color.is_none()) p.base_color = vec3_of(base_color, "base_color");
        if (!metallic.is_none()) p.metallic = metallic.cast<float>();
        if (!roughness.is_none()) p.roughness = roughness.cast<float>();
        for (float v : {p.base_color.x, p.base_color.y, p.base_color.z, p.metallic, p.roughness})
            if (!(v >= 0.0f && v <= 1.0f)) throw Error("fit", "base_color/metallic/roughness", "values are in [0, 1]");
        fit::PbrToPhong f = fit::fit_pbr_to_phong(p);
        py::dict ph;
        ph["kd"] = py::make_tuple(f.phong.kd.x, f.phong.kd.y, f.phong.kd.z);
        ph["ks"] = py::make_tuple(f.phong.ks.x, f.phong.ks.y, f.phong.ks.z);
        ph["ns"] = f.phong.ns;
        d["phong"] = ph;
        d["residual"] = residual_dict(f.residual);
    }
    return d;
}

// ---- files -----------------------------------------------------------------------------

// A uint8 array (H, W, 1..4) as an 8-bit image (copied).
Image8 image8_from(py::handle image) {
    auto b = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(image);
    if (!b || b.ndim() != 3 || b.shape(2) < 1 || b.shape(2) > 4) throw py::type_error("image: expected a uint8 array (H, W, C)");
    Image8 img{int(b.shape(1)), int(b.shape(0)), int(b.shape(2))};
    std::copy(b.data(), b.data() + b.size(), img.pixels.begin());
    return img;
}

void save_image(const py::object& path, py::handle image) {
    std::string file = py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
    std::string ext = file.size() >= 4 ? file.substr(file.size() - 4) : "";
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    py::array a = py::array::ensure(image);
    if (!a || a.ndim() != 3 || a.shape(2) < 3 || a.shape(2) > 4)
        throw py::type_error("image: expected an array of shape (H, W, 3) or (H, W, 4)");
    const bool bytes = a.dtype().is(py::dtype::of<std::uint8_t>());
    if (ext == ".png") {
        // Floats are quantised as the renderer's PNGs are (to_image8: clamped, rounded).
        Image8 img = bytes ? image8_from(a) : to_image8(image_from(a, "image"), a.shape(2) == 4);
        py::gil_scoped_release release;
        write_png(file, img);
    } else if (ext == ".exr" || ext == ".hdr") {
        if (bytes) throw py::type_error("image: EXR and HDR files hold float images; got uint8");
        ImageF img = image_from(a, "image");
        py::gil_scoped_release release;
        if (ext == ".exr") write_exr(file, img);
        else write_hdr(file, img);
    } else {
        throw Error(file, "", "the name must end in .png, .exr or .hdr");
    }
}

py::bytes png_bytes(py::handle image) {
    std::vector<std::uint8_t> png = encode_png(image8_from(image));
    return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
}

py::object read_image(const py::object& path) {
    bool is_float = false;
    ImageF img = image_from(path, "path", &is_float);
    if (is_float) return to_array(std::move(img));
    return to_array(to_image8(img, true));
}

}  // namespace

void bind_tools(py::module_& m) {
    const fresnel::ibl::BakeOptions defaults;
    // (pybind11 copies a function's docstring.)
    const std::string bake_doc = "bake(environment, output=None, size=" + std::to_string(defaults.size) +
                                 ", samples=" + std::to_string(defaults.samples) + ", levels=" + std::to_string(defaults.levels) +
                                 ", progress=None) -> dict\n"
                                 "Bakes an equirectangular panorama (a .hdr/.exr file, 'studio', or a float array (H, 2H, 3|4), linear) into\n"
                                 "what the rasteriser samples: specular (a list of levels, each (6, S, S, 4)), irradiance (6, s, s, 4),\n"
                                 "irradiance_sh (9, 3), brdf_lut (N, N, 4). With `output`, also writes the folder `fresnel bake` writes.";
    m.def("bake", &bake, py::arg("environment"), py::arg("output") = py::none(), py::arg("size") = defaults.size,
          py::arg("samples") = defaults.samples, py::arg("levels") = defaults.levels, py::arg("progress") = py::none(),
          bake_doc.c_str());
    m.def("evaluate", &evaluate_material, py::arg("scene"), py::arg("material"), py::arg("uv0"), py::arg("uv1") = py::none(),
          py::arg("color") = py::none(), py::arg("normal") = py::none(), py::arg("tangent") = py::none(),
          py::arg("lod") = 0.0f,
          "evaluate(scene, material, uv0, uv1=None, color=None, normal=None, tangent=None, lod=0) -> dict of arrays\n"
          "The material (index or name) at N surface points, as the shaders and the tracer evaluate it (textures\n"
          "filtered at level of detail `lod`): base_color (N, 4), metallic, roughness, f0 (N, 3), emissive, occlusion,\n"
          "alpha, discard, normal (the shading normal, world space when normal/tangent are), clearcoat, sheen_color,\n"
          "anisotropy, iridescence, transmission, diffuse_transmission, diffuse_roughness ... uv0: (N, 2).");
    m.def("compare", &compare, py::arg("test"), py::arg("reference"), py::arg("mask") = py::none(), py::arg("linear") = false,
          py::arg("ppd") = flip_default_pixels_per_degree(),
          "compare(test, reference, mask=None, linear=False, ppd=67.0) -> dict: psnr_db, ssim, flip (LDR-FLIP mean),\n"
          "mv_rms_db, pixels; hdr_flip when both are linear. Images are arrays (uint8 0..255, or floats: display\n"
          "values in [0, 1], linear with linear=True) or file names (EXR/HDR read as linear). mask: 'auto' (pixels\n"
          "either image covers), a mask image, or None (every pixel). `fresnel compare`'s metrics.");
    m.def("fit", &fit_material, py::kw_only(), py::arg("kd") = py::none(), py::arg("ks") = py::none(),
          py::arg("ns") = py::none(), py::arg("base_color") = py::none(), py::arg("metallic") = py::none(),
          py::arg("roughness") = py::none(), py::arg("match") = "albedo",
          "fit(kd=, ks=, ns=, match='albedo') -> {'pbr': {...}, 'residual': {...}, 'image_based_residual': {...}}: a Phong\n"
          "(MTL) material as\n"
          "metallic-roughness; fit(base_color=, metallic=, roughness=) -> {'phong': {...}, 'residual': ...}: the other\n"
          "way. `fresnel fit`'s fits.");
    m.def("save", &save_image, py::arg("path"), py::arg("image"),
          "save(path, image): a .png (uint8 as is, floats clamped to [0, 1]) or .exr/.hdr (floats), written whole or\n"
          "not at all (a temporary file renamed into place).");
    m.def("read", &read_image, py::arg("path"),
          "read(path) -> ndarray: an image file: PNG/JPEG as uint8 (H, W, 4), EXR/HDR as float32 (H, W, 4).");
    m.def("to_png", &png_bytes, py::arg("image"), "The PNG file's bytes of a uint8 image (H, W, C).");
    m.def("debug_channels", &debug_channel_names, "The names Renderer.channel() takes (the settings' debug channels).");
}

}  // namespace fresnel::python
